#pragma once
// The CLI's commands, callable from main and from tests. Each returns the
// process exit code (docs/cli.md).

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace cairn::cli {

/// Exit codes (a public contract).
inline constexpr int kExitStable = 0;
inline constexpr int kExitUnstable = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInfeasible = 3;

/// How the input file is read and what the command line changes in its model
/// (shared by check, simulate and convert; docs/cli.md, "Reading the model").
struct ModelArgs {
  /// "scene" (scene format v1, the default) or "compas" (a COMPAS assembly).
  std::string format = "scene";
  /// --friction: μ of every contact. Required with compas (the files store
  /// none); with scene it replaces the scene's `friction` (friction pairs keep
  /// theirs).
  std::optional<double> friction;
  /// --supports: parts (COMPAS blocks: node keys) fixed in addition to those
  /// the file fixes (`is_support`, `"fixed": true`).
  std::vector<std::string> supports;
  /// --tolerance: the length tolerance (contact distance, allowed overlap,
  /// planarity); replaces the scene's `tolerance` or the COMPAS default.
  std::optional<double> tolerance;
  /// --gravity: replaces the gravity (2 numbers in 2-D, 3 in 3-D); empty: the
  /// file's, or the default.
  std::vector<double> gravity;
  /// --interfaces: "detect" (contacts found from the shapes, the default) or
  /// "stored" (a COMPAS file's stored interfaces: CompasOptions::stored_interfaces).
  std::string interfaces = "detect";
};

struct CheckArgs {
  std::string scene;
  bool json = false;
  std::string normalize;             // part name, or empty
  std::vector<std::string> without;  // part names
  ModelArgs model;
};

/// `cairn check`: writes the report to `out`, errors to `err`.
int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err);

struct SimulateArgs {
  std::string scene;
  std::string plan;
  bool json = false;
  std::string timeline;   // CSV file, or empty
  std::string normalize;  // part name, or empty
  bool continue_after_failure = false;
  /// --suggest-fixtures: when a step fails, look for the fewest fixels that
  /// make the plan stable (planning/fixtures.h) and report them.
  bool suggest_fixtures = false;
  int max_fixels = 3;  ///< --max-fixels
  ModelArgs model;
};

/// `cairn simulate`: exit 0 stable, 1 unstable or unsupported, 3 infeasible,
/// 2 bad input.
int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err);

struct ConvertArgs {
  std::string input;
  std::string output;
  ModelArgs model;
};

/// `cairn convert`: writes the validated model of `input` to `output` as a
/// scene file (format v1), whole or not at all; a one-line summary to `out`.
/// Exit 0, or 2 on bad input (nothing written).
int RunConvert(const ConvertArgs& args, std::ostream& out, std::ostream& err);

struct BlockingArgs {
  std::string scene;
  bool json = false;
  std::vector<std::string> without;  // part names
  ModelArgs model;
};

/// `cairn blocking`: the NDBG of the scene (planning/blocking.h), per cell
/// its directions and the parts that can leave. Exit 0, or 2 on bad input.
int RunBlocking(const BlockingArgs& args, std::ostream& out, std::ostream& err);

struct PlanArgs {
  std::string scene;
  bool json = false;
  int max = 0;                    // --max K; 0: every sequence
  int threads = 0;                // --threads; 0: every core
  std::string paths;              // --paths FILE: candidate paths per part
  std::string emit_plans;         // --emit-plans DIR
  std::string dot;                // --dot FILE
  std::vector<std::string> keep;  // --keep: parts never removed
  std::string support = "full";   // --support full|none|both
  bool no_subassemblies = false;  // --single-parts
  double dt = 0, speed = 0;       // --dt, --speed; 0: automatic
  int allow_fixtures = 0;         // --allow-fixtures N
  ModelArgs model;
};

/// `cairn plan`: stable disassembly sequences (planning/planner.h). Exit 0
/// when a stable sequence was found, 1 when none, 2 on bad input.
int RunPlan(const PlanArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

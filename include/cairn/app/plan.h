#pragma once
/// @file
/// `cairn plan`: stable disassembly sequences (docs/planning.md).

#include <cstdint>
#include <string>
#include <vector>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/io/input_file.h"
#include "cairn/planning/planner.h"

namespace cairn::app {

struct PlanQuery {
  int max = 0;                      ///< --max K; 0: every sequence
  int threads = 0;                  ///< --threads; 0: every core
  std::string paths;                ///< --paths FILE: candidate paths per part; empty: none
  std::vector<std::string> keep;    ///< --keep: parts never removed
  std::string support = "full";     ///< --support full|none|both
  bool single_parts = false;        ///< --single-parts: no subassemblies
  double dt = 0, speed = 0;         ///< --dt, --speed; 0: automatic
  int allow_fixtures = 0;           ///< --allow-fixtures N
  std::string directions = "ndbg";  ///< --directions ndbg|axes: the NDBG's cells, or ±x, ±y (, ±z)
  bool dot = false;                 ///< also the --dot graph
  bool emit_plans = false;          ///< also the --emit-plans files
  bool page = false;                ///< also the result page
  /// --rule: where rigid bodies leave a node check open.
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  bool require_strong = false;  ///< --require strong: states not proved strong are not stable
  std::uint64_t max_input_size = kDefaultMaxInputSize;  ///< the paths file's largest size
  /// Runs the node checks and edges; null: this process's threads (the
  /// CLI passes its MPI executor under mpirun).
  PlanExecutor* executor = nullptr;
};

/// The search on `model`: exit 0 when a stable sequence was found, 1 when
/// none. `monitor` is polled before each node check and at every simulated
/// time step, and told how many nodes are checked. @throws InputError on bad
/// input (the paths file, a part name, an option's value).
CommandResult PlanDocument(const Model& model, const PlanQuery& query, const Monitor& monitor = {});

}  // namespace cairn::app

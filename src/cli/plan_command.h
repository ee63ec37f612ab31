#pragma once
// `cairn plan`: stable disassembly sequences (docs/planning.md).

#include <iosfwd>
#include <string>
#include <vector>

#include "cairn/app/model.h"
#include "cairn/planning/planner.h"
#include "cli/command.h"

namespace cairn::cli {

struct PlanArgs {
  std::string scene;
  bool json = false;
  int max = 0;                            // --max K; 0: every sequence
  int threads = 0;                        // --threads; 0: every core
  std::string paths;                      // --paths FILE: candidate paths per part
  std::string emit_plans;                 // --emit-plans DIR
  std::string html;                       // --html FILE: the result page, or empty
  std::string dot;                        // --dot FILE
  std::vector<std::string> keep;          // --keep: parts never removed
  std::string support = "full";           // --support full|none|both
  std::string rule = "loaded-from-rest";  // --rule: loaded-from-rest or equilibrium
  std::string require;                    // --require: "strong" or empty
  bool no_subassemblies = false;          // --single-parts
  double dt = 0, speed = 0;               // --dt, --speed; 0: automatic
  int allow_fixtures = 0;                 // --allow-fixtures N
  std::string directions = "ndbg";  // --directions ndbg|axes: the NDBG's cells, or ±x, ±y (, ±z)
  ModelArgs model;
};

/// `cairn plan --json`'s document (without --emit-plans and --dot, which
/// write files); exit 0 when a stable sequence was found, 1 when none.
/// `checkpoint` is called before each node check and at every simulated time
/// step; `executor` (null: this process's threads) runs the node checks and
/// edges. @throws InputError on bad input.
CommandDocument PlanDocument(const PlanArgs& args, const Checkpoint& checkpoint = {},
                             PlanExecutor* executor = nullptr);

/// `cairn plan`: stable disassembly sequences (planning/planner.h). Under
/// `mpirun` with more than one rank, the search is spread over the ranks
/// (src/cli/mpi.h) and rank 0 alone writes. Exit 0
/// when a stable sequence was found, 1 when none, 2 on bad input.
int RunPlan(const PlanArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

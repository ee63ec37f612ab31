#pragma once
// `cairn simulate`: a plan along its paths (docs/cli.md, docs/plan-format.md).

#include <iosfwd>
#include <string>
#include <vector>

#include "cairn/app/model.h"
#include "cairn/geometry/plan.h"
#include "cli/command.h"

namespace cairn::cli {

struct SimulateArgs {
  std::string scene;
  std::string plan;
  bool json = false;
  std::string timeline;   // CSV file, or empty
  std::string html;       // --html FILE: the result page, or empty
  std::string normalize;  // part name, or empty
  bool continue_after_failure = false;
  std::string rule = "loaded-from-rest";  // --rule: loaded-from-rest or equilibrium
  std::string require;                    // --require: "strong" or empty
  /// --suggest-fixtures: when a step fails, look for the fewest fixels that
  /// make the plan stable (planning/fixtures.h) and report them.
  bool suggest_fixtures = false;
  int max_fixels = 3;  ///< --max-fixels
  /// --max-ticks: the most time steps one step of the plan may take.
  long long max_ticks = Plan::kDefaultMaxTicks;
  ModelArgs model;
  /// --margin friction: also the least friction factor for which
  /// every tick is stable (motion/plan_margin.h); empty: not asked for.
  std::string margin;
};

/// `cairn simulate --json`'s document (without --timeline, which writes a
/// file); exit 0 stable, 1 unstable or unsupported, 3 infeasible.
/// `checkpoint` is called at every time step. @throws InputError on bad input.
CommandDocument SimulateDocument(const SimulateArgs& args, const Checkpoint& checkpoint = {});

/// `cairn simulate`: exit 0 stable, 1 unstable or unsupported, 3 infeasible,
/// 2 bad input.
int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

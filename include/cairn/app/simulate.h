#pragma once
/// @file
/// `cairn simulate`: a plan along its paths (docs/cli.md, docs/plan-format.md).

#include <cstdint>
#include <optional>
#include <string>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/geometry/plan.h"
#include "cairn/io/input_file.h"
#include "cairn/stability/solve_component.h"

namespace cairn::app {

struct SimulateQuery {
  /// The plan's file: read, unless `plan_data` gives the plan (then the name
  /// its messages give it).
  std::string plan_file;
  std::optional<nlohmann::json> plan_data;  ///< a plan given as data (Python's dict)
  std::string normalize;                    ///< --normalize: a part, or empty
  bool continue_after_failure = false;      ///< --continue
  /// --suggest-fixtures: when a step fails, the fewest fixels that make the
  /// plan stable (planning/fixtures.h); at most `max_fixels`.
  bool suggest_fixtures = false;
  int max_fixels = 3;
  long long max_ticks = Plan::kDefaultMaxTicks;  ///< --max-ticks
  /// --margin: "friction" (the least friction factor for which every tick
  /// is stable, motion/plan_margin.h) or empty.
  std::string margin;
  bool timeline = false;                                ///< also the --timeline CSV
  bool page = false;                                    ///< also the result page
  std::uint64_t max_input_size = kDefaultMaxInputSize;  ///< the plan file's largest size
  /// --rule: where rigid bodies leave a static check open.
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  /// --require strong: exit kExitNotStrong when every step stands but some
  /// configuration checked from rest is not proved strongly stable.
  bool require_strong = false;
};

/// The plan run on `model`: exit 0 stable, 1 unstable or unsupported, 3
/// infeasible, or (--require strong) stable without strong stability proved. `monitor` is polled at
/// every time step and told the step and time step. @throws InputError on bad input (the plan file,
/// a part name).
CommandResult SimulateDocument(const Model& model, const SimulateQuery& query,
                               const Monitor& monitor = {});

}  // namespace cairn::app

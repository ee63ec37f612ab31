#pragma once
/// @file
/// `cairn sequence`: a build order with the fewest temporary supports
/// (docs/sequence.md, planning/sequence.h).

#include <functional>
#include <string>
#include <vector>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/core/types.h"
#include "cairn/stability/solve_component.h"

namespace cairn::app {

struct SequenceQuery {
  std::string temporary = "hold";  ///< --temporary hold|prop|both: the kinds of support
  int max_temporary = -1;          ///< --max-temporary K; -1: no bound
  /// --direction X,Y(,Z): the one removal direction (a part arrives along
  /// its reverse); empty: `directions`.
  std::vector<double> direction;
  /// --directions up|axes|ndbg: against gravity, ±x, ±y (, ±z) after up, or
  /// the NDBG's cells (closest to up first)
  std::string directions = "up";
  int beam_width = 4;     ///< --beam W: states kept per step
  int threads = 0;        ///< --threads; 0: every core
  double time_limit = 0;  ///< --time-limit S (seconds; 0: none)
  /// Polled during the search: true ends it with the best order so far (the
  /// CLI's SIGINT). Empty: never.
  std::function<bool()> stop;
  VerdictRule rule = VerdictRule::kLoadedFromRest;  ///< --rule
  bool require_strong = false;                      ///< --require strong
  /// --emit-plans: also the order as an assembly plan `cairn simulate` runs
  /// (CommandResult::plans: "sequence.assemble.plan.json"), its supports as
  /// held parts.
  bool emit_plans = false;
  /// --html: also the result page (CommandResult::page).
  bool page = false;
};

/// The build order of `model`: exit 0 when a complete order was found within
/// the bound, 1 when none. @throws InputError on a bad option's value.
CommandResult SequenceDocument(const Model& model, const SequenceQuery& query,
                               const Monitor& monitor = {});

}  // namespace cairn::app

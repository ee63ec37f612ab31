#pragma once
/// @file
/// `cairn check`: is one configuration of a model stable? (docs/cli.md)

#include <string>
#include <vector>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/report/report.h"
#include "cairn/stability/solve_component.h"

namespace cairn::app {

struct CheckQuery {
  std::vector<std::string> without;  ///< parts taken away, by name
  std::string normalize;             ///< the part whose weight is the force unit; empty: none
  ContactListing contacts = ContactListing::kSummary;  ///< the text's contact lines
  bool page = false;                                   ///< also the result page
  /// Where rigid bodies leave the answer open (stability/solve_component.h).
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  /// --require strong: exit kExitNotStrong when it stands without a proof of
  /// strong stability.
  bool require_strong = false;
};

/// The check of `model` with the parts `without` taken away: exit 0 stable,
/// 1 not, 3 stable but strong stability required and not proved. A check is one solve: `monitor` is
/// polled before it only.
/// @throws InputError naming the option (`--without`, `--normalize`).
CommandResult CheckDocument(const Model& model, const CheckQuery& query,
                            const Monitor& monitor = {});

}  // namespace cairn::app

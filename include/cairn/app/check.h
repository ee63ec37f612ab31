#pragma once
/// @file
/// `cairn check`: is one configuration of a model stable? (docs/cli.md)

#include <string>
#include <vector>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/report/report.h"

namespace cairn::app {

struct CheckQuery {
  std::vector<std::string> without;  ///< parts taken away, by name
  std::string normalize;             ///< the part whose weight is the force unit; empty: none
  ContactListing contacts = ContactListing::kSummary;  ///< the text's contact lines
  bool page = false;                                   ///< also the result page
};

/// The check of `model` with the parts `without` taken away: exit 0 stable,
/// 1 not. A check is one solve: `monitor` is polled before it only.
/// @throws InputError naming the option (`--without`, `--normalize`).
CommandResult CheckDocument(const Model& model, const CheckQuery& query,
                            const Monitor& monitor = {});

}  // namespace cairn::app

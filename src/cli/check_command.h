#pragma once
// `cairn check`: is one configuration of a scene stable? (docs/cli.md)

#include <iosfwd>
#include <string>
#include <vector>

#include "cairn/app/model.h"
#include "cli/command.h"

namespace cairn::cli {

struct CheckArgs {
  std::string scene;
  bool json = false;
  std::string html;                       // --html FILE: the result page, or empty
  std::string normalize;                  // part name, or empty
  std::vector<std::string> without;       // part names
  std::string contacts = "summary";       // --contacts: summary, all or none (text only)
  std::string rule = "loaded-from-rest";  // --rule: loaded-from-rest or equilibrium
  std::string require;                    // --require: "strong" or empty
  ModelArgs model;
};

/// `cairn check --json`'s document; exit 0 stable, 1 not. @throws InputError
/// on bad input. A check is one solve: `checkpoint` is called before it only.
CommandDocument CheckDocument(const CheckArgs& args, const Checkpoint& checkpoint = {});

/// `cairn check`: writes the report to `out`, errors to `err`.
int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

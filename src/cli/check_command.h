#pragma once
// `cairn check`: is one configuration of a scene stable? (docs/cli.md)

#include <iosfwd>
#include <string>
#include <vector>

#include "cli/model.h"

namespace cairn::cli {

struct CheckArgs {
  std::string scene;
  bool json = false;
  std::string html;                  // --html FILE: the result page, or empty
  std::string normalize;             // part name, or empty
  std::vector<std::string> without;  // part names
  ModelArgs model;
};

/// `cairn check`: writes the report to `out`, errors to `err`.
int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

#pragma once
// `cairn convert`: a model written back as a scene file (docs/cli.md).

#include <iosfwd>
#include <string>

#include "cairn/app/model.h"

namespace cairn::cli {

struct ConvertArgs {
  std::string input;
  std::string output;
  app::ModelArgs model;
};

/// `cairn convert`: writes the validated model of `input` to `output` as a
/// scene file (format v1), whole or not at all; a one-line summary to `out`.
/// Exit 0, or 2 on bad input (nothing written).
int RunConvert(const ConvertArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

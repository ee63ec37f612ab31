#pragma once
// `cairn margin`: how far from failing is a configuration? The critical
// friction, the critical tilt about an axis, or the largest load a part takes
// (docs/margin.md).

#include <iosfwd>
#include <string>
#include <vector>

#include "cairn/app/margin.h"
#include "cairn/app/model.h"
#include "cli/command.h"

namespace cairn::cli {

struct MarginArgs {
  std::string scene;
  bool json = false;
  std::vector<std::string> without;  // part names
  /// --friction [MU]: given at all (`friction_given`), and its value if any.
  /// Alone it asks for the friction margin (and MU, if given, is the
  /// model's μ, as on the other commands); with --tilt or --load it must
  /// carry MU and only sets the model's μ.
  bool friction_given = false;
  std::string friction_value;
  std::string rule;        // --rule
  std::string html;        // --html
  app::MarginQuery query;  // tilt, load, point, direction (friction from above; without: below)
  app::ModelArgs model;    // --friction's value goes to model.friction
};

/// `cairn margin --json`'s document, for `cairn batch`: exit 0 when the
/// configuration stands as given, 1 when not. @throws InputError on bad
/// input; std::runtime_error when the solver failed (exit 4).
CommandDocument MarginDocument(const MarginArgs& args, const Checkpoint& checkpoint = {});

/// `cairn margin`: exit 0 when the configuration stands as given (and the
/// margin is computed), 1 when it does not stand, 2 bad input, 4 a solver
/// failure.
int RunMargin(const MarginArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

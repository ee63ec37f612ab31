#pragma once
// `cairn margin`: how far from failing is a configuration? The critical
// friction, the critical tilt about an axis, or the largest load a part takes
// (docs/margin.md).

#include <iosfwd>
#include <string>
#include <vector>

#include "cairn/stability/margin.h"
#include "cli/model.h"

namespace cairn::cli {

/// Which margin, as the command line (or the Python module) says it.
struct MarginQuery {
  bool friction = false;          ///< --friction (without --tilt and --load)
  std::vector<double> tilt;       ///< --tilt X,Y,Z
  std::string load;               ///< --load PART
  std::vector<double> point;      ///< --point (2 or 3 numbers)
  std::vector<double> direction;  ///< --direction (2 or 3 numbers)
};

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
  MarginQuery query;  // tilt, load, point, direction (friction from above)
  ModelArgs model;    // --friction's value goes to model.friction
};

/// The request of `query` on `assembly`. @throws InputError naming the flag
/// (and `file`): no quantity or two, a wrong count of numbers, an unknown
/// part.
MarginRequest ResolveMarginQuery(const Assembly& assembly, const MarginQuery& query,
                                 const std::string& file);

/// `cairn margin`: exit 0 when the configuration stands as given (and the
/// margin is computed), 1 when it does not stand, 2 bad input, 4 a solver
/// failure.
int RunMargin(const MarginArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

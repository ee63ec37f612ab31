#pragma once
/// @file
/// `cairn margin`: how far from failing is a configuration? The critical
/// friction, the critical tilt about an axis, or the largest load a part
/// takes (docs/margin.md).

#include <string>
#include <vector>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/stability/margin.h"

namespace cairn::app {

/// Which margin, as the command line (or the Python module) says it.
struct MarginQuery {
  bool friction = false;                            ///< --friction (without --tilt and --load)
  std::vector<double> tilt;                         ///< --tilt X,Y,Z
  std::string load;                                 ///< --load PART
  std::vector<double> point;                        ///< --point (2 or 3 numbers)
  std::vector<double> direction;                    ///< --direction (2 or 3 numbers)
  std::vector<std::string> without;                 ///< parts taken away, by name
  VerdictRule rule = VerdictRule::kLoadedFromRest;  ///< --rule (the check's)
  bool page = false;                                ///< also the result page (--html)
};

/// The request of `query` on `assembly`. @throws InputError naming the flag
/// (and `file`): no quantity or two, a wrong count of numbers, an unknown
/// part.
MarginRequest ResolveMarginQuery(const Assembly& assembly, const MarginQuery& query,
                                 const std::string& file);

/// The margin of `model` with the parts `without` taken away: exit 0 when
/// the configuration stands as given (the check's verdict, with the query's
/// rule; the margin is computed either way), 1 when it does not stand, 4 when the solver failed
/// (`failure` says how; the document is complete all the same). @throws InputError on bad input.
CommandResult MarginDocument(const Model& model, const MarginQuery& query,
                             const Monitor& monitor = {});

}  // namespace cairn::app

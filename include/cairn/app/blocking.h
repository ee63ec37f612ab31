#pragma once
/// @file
/// `cairn blocking`: the NDBG of a model, or its graphs along one direction
/// (docs/blocking.md).

#include <string>
#include <vector>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/core/types.h"

namespace cairn::app {

struct BlockingQuery {
  std::vector<std::string> without;  ///< parts taken away, by name
  std::vector<double> direction;     ///< --direction: one direction only; empty: the NDBG
  std::string direction_option = "--direction";  ///< what errors call it (Python: its keyword)
  bool page = false;                             ///< also the result page (--html)
};

/// The direction of `--direction` as the command reads it: X,Y (or X,Y,0)
/// in a 2-D scene, X,Y,Z in a 3-D one; finite, not all zero. Errors name
/// `option`. @throws InputError when it is not a direction.
Vector3 BlockingDirection(const std::vector<double>& xyz, const Assembly& assembly,
                          const std::string& option = "--direction");

/// The NDBG of `model` with the parts `without` taken away (exit 0).
/// `monitor` is polled all through. @throws InputError on bad input.
CommandResult BlockingDocument(const Model& model, const BlockingQuery& query,
                               const Monitor& monitor = {});

}  // namespace cairn::app

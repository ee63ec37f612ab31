#pragma once
// `cairn blocking`: the NDBG of a scene (docs/blocking.md).

#include <iosfwd>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/model.h"

namespace cairn::cli {

struct BlockingArgs {
  std::string scene;
  bool json = false;
  std::vector<std::string> without;  // part names
  std::vector<double> direction;     // --direction X,Y,Z: one direction only; empty: the NDBG
  ModelArgs model;
};

/// `cairn blocking --json`'s document (exit 0). `checkpoint` is polled all
/// through the computation (it may throw to abandon it: `cairn batch
/// --job-timeout`). @throws InputError on bad input.
CommandDocument BlockingDocument(const BlockingArgs& args, const Checkpoint& checkpoint = {});

/// The direction of `--direction` as the command reads it (3 finite numbers,
/// not all zero; Z = 0 in a 2-D scene), for the Python module's
/// `cairn.blocking(direction=...)`. Errors name `option`.
/// @throws InputError when it is not a direction.
Vector3 BlockingDirection(const std::vector<double>& xyz, const Assembly& assembly,
                          const std::string& option = "--direction");

/// `cairn blocking`: the NDBG of the scene (planning/blocking.h), per cell
/// its directions and the parts that can leave. Exit 0, or 2 on bad input.
int RunBlocking(const BlockingArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

#pragma once
// `cairn blocking`: the NDBG of a scene (docs/blocking.md).

#include <iosfwd>
#include <string>
#include <vector>

#include "cairn/app/model.h"
#include "cli/command.h"

namespace cairn::cli {

struct BlockingArgs {
  std::string scene;
  bool json = false;
  std::vector<std::string> without;  // part names
  std::vector<double> direction;     // --direction X,Y,Z: one direction only; empty: the NDBG
  std::string html;                  // --html
  ModelArgs model;
};

/// `cairn blocking --json`'s document (exit 0). `checkpoint` is polled all
/// through the computation (it may throw to abandon it: `cairn batch
/// --job-timeout`). @throws InputError on bad input.
CommandDocument BlockingDocument(const BlockingArgs& args, const Checkpoint& checkpoint = {});

/// `cairn blocking`: the NDBG of the scene (planning/blocking.h), per cell
/// its directions and the parts that can leave. Exit 0, or 2 on bad input.
int RunBlocking(const BlockingArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

#pragma once
// `cairn sequence`: a build order with the fewest temporary supports
// (docs/sequence.md).

#include <iosfwd>
#include <string>
#include <vector>

#include "cairn/app/model.h"
#include "cli/command.h"

namespace cairn::cli {

struct SequenceArgs {
  std::string scene;
  bool json = false;
  std::string temporary = "hold";         // --temporary hold|prop|both
  int max_temporary = -1;                 // --max-temporary K; -1: no bound
  std::vector<double> direction;          // --direction X,Y(,Z): the one removal direction
  std::string directions = "up";          // --directions up|axes
  int beam = 4;                           // --beam W
  int threads = 0;                        // --threads N; 0: every core
  double time_limit = 0;                  // --time-limit S; 0: none
  std::string rule = "loaded-from-rest";  // --rule
  std::string require;                    // --require strong
  std::string emit_plans;                 // --emit-plans DIR
  std::string html;                       // --html PAGE
  ModelArgs model;
};

/// `cairn sequence --json`'s document; exit 0 when a complete order was
/// found, 1 when none. @throws InputError on bad input.
CommandDocument SequenceDocument(const SequenceArgs& args, const Checkpoint& checkpoint = {});

/// `cairn sequence`: exit 0 when a complete order was found, 1 when none, 2
/// on bad input.
int RunSequence(const SequenceArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

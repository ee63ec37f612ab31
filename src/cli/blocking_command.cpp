#include "cli/commands.h"
#include <ostream>
namespace cairn::cli {
int RunBlocking(const BlockingArgs&, std::ostream&, std::ostream& err) {
  err << "cairn: blocking: being written\n";
  return kExitBadInput;
}
}  // namespace cairn::cli

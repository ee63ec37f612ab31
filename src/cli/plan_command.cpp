#include "cli/commands.h"
#include <ostream>
namespace cairn::cli {
int RunPlan(const PlanArgs&, std::ostream&, std::ostream& err) {
  err << "cairn: plan: being written\n";
  return kExitBadInput;
}
}  // namespace cairn::cli

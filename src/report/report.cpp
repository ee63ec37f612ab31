#include "cairn/report/report.h"

namespace cairn {

std::pair<double, std::string> ForceScale(const Assembly& assembly, const ReportOptions& options) {
  if (!options.normalize_part) return {1.0, "force units"};
  const Part& p = assembly.part(*options.normalize_part);
  return {p.mass * assembly.gravity().norm(), "weight of " + p.name};
}

}  // namespace cairn

#include "cairn/core/format.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cairn/core/tolerances.h"

namespace cairn {

std::string FormatNumber(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

std::string FormatPoint(const Vector3& p, int dimension) {
  std::ostringstream os;
  os.precision(4);
  const double dust = numeric::kParameterSlack * std::max(1.0, p.cwiseAbs().maxCoeff());
  const auto clean = [dust](double x) { return std::abs(x) < dust ? 0.0 : x; };
  os << "(" << clean(p.x()) << ", " << clean(p.y());
  if (dimension == 3) os << ", " << clean(p.z());
  os << ")";
  return os.str();
}

}  // namespace cairn

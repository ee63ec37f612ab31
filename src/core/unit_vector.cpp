#include "cairn/core/unit_vector.h"

namespace cairn {

std::optional<Vector3> UnitVector(const Vector3& v) {
  if (!v.allFinite()) return std::nullopt;
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0)) return std::nullopt;
  // Each component divided by the largest is in [−1, 1] and the largest is
  // ±1 exactly: its squares neither overflow nor all underflow.
  const Vector3 scaled = v / largest;
  return Vector3(scaled / scaled.norm());
}

}  // namespace cairn

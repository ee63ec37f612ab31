#include "cairn/core/unit_vector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace cairn {
namespace {

// The same unit vector for a direction at any finite scale: the squared norm
// of (1e155, 1e155) overflows and that of (1e-300, 0, 0) underflows, so
// normalized() gives (0, 0, 0) or counts the vector as zero.
TEST(UnitVector, TheSameAtEveryScale) {
  const Vector3 expected(1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0);
  for (const double s : {1.0, 1e155, 1e300, std::numeric_limits<double>::max(), 1e-160, 1e-300,
                         std::numeric_limits<double>::denorm_min()}) {
    SCOPED_TRACE(s);
    const std::optional<Vector3> u = UnitVector(Vector3(s, s, 0));
    ASSERT_TRUE(u.has_value());
    EXPECT_EQ(*u, *UnitVector(Vector3(1, 1, 0)));
    EXPECT_NEAR((*u - expected).norm(), 0, 1e-15);
  }
  EXPECT_EQ(*UnitVector(Vector3(1e-300, 0, 0)), Vector3(1, 0, 0));
  EXPECT_EQ(*UnitVector(Vector3(0, -1e200, 0)), Vector3(0, -1, 0));
  const Vector3 mixed = *UnitVector(Vector3(3e200, 0, -4e200));
  EXPECT_NEAR(mixed.x(), 0.6, 1e-15);
  EXPECT_NEAR(mixed.z(), -0.8, 1e-15);
  EXPECT_NEAR(mixed.norm(), 1, 1e-15);
}

// Zero and non-finite vectors have no direction.
TEST(UnitVector, RefusesZeroAndNonFinite) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(UnitVector(Vector3::Zero()).has_value());
  EXPECT_FALSE(UnitVector(Vector3(-0.0, 0.0, -0.0)).has_value());
  EXPECT_FALSE(UnitVector(Vector3(inf, 0, 0)).has_value());
  EXPECT_FALSE(UnitVector(Vector3(1, -inf, 0)).has_value());
  EXPECT_FALSE(UnitVector(Vector3(nan, 1, 0)).has_value());
}

}  // namespace
}  // namespace cairn

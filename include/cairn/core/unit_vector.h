#pragma once
/// @file
/// A direction given by a user (an axis, a load's or a removal's direction,
/// gravity) as a unit vector, safe for any finite input.
///
/// Eigen's normalized() divides by sqrt(x² + y² + z²): from about 1e154 on the
/// squares overflow to +∞ and the result is (0, 0, 0); below about 1e-154
/// they underflow to 0 and the vector counts as zero. UnitVector first
/// divides by the largest |component| (exact in the exponent, so the scaled
/// vector has a component ±1 and a norm in [1, √3]) and only then normalises,
/// so (1, 1), (1e155, 1e155) and (1e-300, 1e-300) give the same unit vector.

#include <optional>

#include "cairn/core/types.h"

namespace cairn {

/// v / |v|, computed without overflow or underflow. Empty when v is zero or
/// has a component that is not finite (NaN, ±∞): callers refuse such input
/// (an InputError naming the option or the JSON path).
std::optional<Vector3> UnitVector(const Vector3& v);

}  // namespace cairn

#pragma once
/// @file
/// Numbers and points as messages and reports write them: the one place that
/// decides how many digits a person reads. Words about physics (how a part
/// moves, why a step failed) are the report stage's (cairn/report/words.h);
/// these are the primitives every stage's messages share.

#include <string>

#include "cairn/core/types.h"

namespace cairn {

/// A number in a message, as `operator<<` writes it (6 significant digits).
std::string FormatNumber(double x);

/// "(x, y)" in 2-D, "(x, y, z)" in 3-D, 4 significant digits; round-off dust
/// (below 1e-9 of the largest coordinate, or of 1) prints as 0, so that a
/// unit axis reads (1, 0, 0) and not (1, 1e-17, 0).
std::string FormatPoint(const Vector3& p, int dimension);

}  // namespace cairn

#pragma once
/// @file
/// Basic numeric types. Cairn uses Eigen for all vectors and matrices.

#include <Eigen/Core>
#include <vector>

namespace cairn {

using Vector2 = Eigen::Vector2d;
using Vector3 = Eigen::Vector3d;
using VectorX = Eigen::VectorXd;
using MatrixX = Eigen::MatrixXd;

/// The 2-D scalar cross product a × b = a_x b_y − a_y b_x (the z component of
/// the 3-D cross product of the two vectors embedded in the xy plane).
inline double Cross2(const Vector2& a, const Vector2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The vector ω ẑ × r for a scalar angular rate ω about +z: (−ω r_y, ω r_x).
inline Vector2 CrossZ(double omega, const Vector2& r) { return {-omega * r.y(), omega * r.x()}; }

}  // namespace cairn

#pragma once
/// @file
/// Basic numeric types. Cairn uses Eigen for all vectors and matrices.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, rotations
#include <vector>

namespace cairn {

using Vector2 = Eigen::Vector2d;
using Vector3 = Eigen::Vector3d;
using VectorX = Eigen::VectorXd;
using MatrixX = Eigen::MatrixXd;
using Matrix3 = Eigen::Matrix3d;
/// A generalised velocity or wrench of one rigid body at its centroid, world
/// frame: (v_x, v_y, v_z, ω_x, ω_y, ω_z) or (f_x, f_y, f_z, τ_x, τ_y, τ_z).
/// A 2-D (planar) body uses the components v_x, v_y, ω_z only.
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// A 2-D point or vector embedded in 3-D (z = 0).
inline Vector3 Embed(const Vector2& v) { return {v.x(), v.y(), 0.0}; }

/// The 2-D scalar cross product a × b = a_x b_y − a_y b_x (the z component of
/// the 3-D cross product of the two vectors embedded in the xy plane).
inline double Cross2(const Vector2& a, const Vector2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The vector ω ẑ × r for a scalar angular rate ω about +z: (−ω r_y, ω r_x).
inline Vector2 CrossZ(double omega, const Vector2& r) { return {-omega * r.y(), omega * r.x()}; }

}  // namespace cairn

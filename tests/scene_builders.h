#pragma once
// Small builders of AssemblyDefs for parametric physics tests.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cairn/geometry/assembly.h"

namespace cairn::testing {

/// A 3-D box [lo, hi], placed by X (applied to its corners as given).
inline PartDef Box3(const std::string& name, const Vector3& lo, const Vector3& hi,
                    bool fixed = false,
                    const Eigen::Isometry3d& X = Eigen::Isometry3d::Identity()) {
  PartDef p;
  p.name = name;
  p.fixed = fixed;
  PolyhedronDef poly;
  for (int k = 0; k < 8; ++k)
    poly.vertices.push_back(
        X * Vector3(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z()));
  poly.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  p.polyhedron = poly;
  return p;
}

inline PartDef Box(const std::string& name, double x0, double y0, double x1, double y1,
                   bool fixed = false) {
  PartDef p;
  p.name = name;
  p.fixed = fixed;
  p.polygon = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  return p;
}

/// A w × h block resting on a fixed wedge whose top face slopes down to the
/// right at `theta` (rad). Returns the def; the block is part 1.
inline AssemblyDef BlockOnIncline(double theta, double mu, double w = 1.0, double h = 0.5) {
  const double L = 6.0, H = L * std::tan(theta);
  const Vector2 u(std::cos(theta), -std::sin(theta));  // down the slope
  const Vector2 n(std::sin(theta), std::cos(theta));   // slope normal
  const Vector2 p0 = Vector2(0, H) + 2.0 * u;
  AssemblyDef def;
  def.friction = mu;
  PartDef wedge;
  wedge.name = "incline";
  wedge.fixed = true;
  wedge.polygon = {{0, 0}, {L, 0}, {0, H}};
  PartDef block;
  block.name = "block";
  block.polygon = {p0, p0 + w * u, p0 + w * u + h * n, p0 + h * n};
  def.parts = {wedge, block};
  return def;
}

/// A plank of length l and thickness t leaning at `theta` (rad) against a
/// frictionless wall (x = 0), its foot on a floor (y = 0) of friction mu.
inline AssemblyDef Ladder(double theta, double mu, double l = 4.0, double t = 0.05) {
  AssemblyDef def;
  def.friction = mu;
  def.friction_pairs = {{"ladder", "wall", 0.0}};
  const Vector2 pf(l * std::cos(theta), 0), pw(0, l * std::sin(theta));
  const Vector2 off(t * std::sin(theta), t * std::cos(theta));
  PartDef ladder;
  ladder.name = "ladder";
  ladder.polygon = {pf, pf + off, pw + off, pw};
  def.parts = {Box("floor", -1, -1, 6, 0, true), Box("wall", -1, 0, 0, 6, true), ladder};
  return def;
}

/// The exact critical floor friction of Ladder(): μ ≥ (x_foot − x_c) / y_top.
inline double LadderCriticalMu(double theta, double l = 4.0, double t = 0.05) {
  return (l * std::cos(theta) / 2 - t * std::sin(theta) / 2) / (l * std::sin(theta));
}

/// A wall of `courses` courses of bricks 2 × 1 in running bond on a fixed
/// ground, friction mu, g = (0, −9.81): even courses hold `bricks` full
/// bricks, odd ones bricks − 1 full bricks between a half brick 1 × 1 at each
/// end, so both end faces are flush. Brick k of course r is named "r<r>_<k>";
/// the wall spans x ∈ [0, 2 bricks], y ∈ [0, courses]. Statically
/// indeterminate: every brick face carries two contact points per neighbour.
inline AssemblyDef RunningBondWall(int courses, int bricks, double mu = 0.6) {
  AssemblyDef def;
  def.name = "wall";
  def.friction = mu;
  def.parts.push_back(Box("ground", -2, -1, 2.0 * bricks + 2, 0, true));
  for (int r = 0; r < courses; ++r) {
    std::vector<std::pair<double, double>> spans;
    if (r % 2 == 0) {
      for (int k = 0; k < bricks; ++k) spans.emplace_back(2.0 * k, 2.0 * k + 2);
    } else {
      spans.emplace_back(0, 1);
      for (int k = 0; k + 1 < bricks; ++k) spans.emplace_back(1 + 2.0 * k, 3 + 2.0 * k);
      spans.emplace_back(2.0 * bricks - 1, 2.0 * bricks);
    }
    for (size_t k = 0; k < spans.size(); ++k)
      def.parts.push_back(Box("r" + std::to_string(r) + "_" + std::to_string(k), spans[k].first, r,
                              spans[k].second, r + 1.0));
  }
  return def;
}

// A block that just fits between two fixed walls, with nothing under it.
// Friction on the walls could hold it if they squeezed it (2 μ N ≥ m g for a
// large enough N), so an equilibrium exists; but nothing produces N from rest,
// so the contact LCP lets it fall: weakly stable. Without friction no
// equilibrium exists at all.
inline AssemblyDef JammedBlock(double mu) {
  AssemblyDef def;
  def.friction = mu;
  def.parts = {Box("left", -1, -2, 0, 2, true), Box("right", 1, -2, 2, 2, true),
               Box("block", 0, 0, 1, 1)};
  return def;
}

}  // namespace cairn::testing

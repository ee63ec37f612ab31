#pragma once
// Small builders of AssemblyDefs for parametric physics tests.
#include <cmath>
#include <string>

#include "cairn/geometry/assembly.h"

namespace cairn::testing {

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

}  // namespace cairn::testing

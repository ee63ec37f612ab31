#include "cairn/core/tolerances.h"

namespace cairn {

Tolerances Tolerances::Scaled(double scene_size, double gravity, double dt, double weight,
                              double length_override, const ToleranceFactors& f) {
  // A degenerate scale (empty scene, no gravity) falls back to 1 so that the
  // tolerances stay positive.
  const double L = scene_size > 0 ? scene_size : 1.0;
  const double g = gravity > 0 ? gravity : 1.0;
  const double W = weight > 0 ? weight : 1.0;
  Tolerances t;
  t.length = length_override > 0 ? length_override : f.length * L;
  t.penetration = t.length;
  t.angle = f.angle;
  t.acceleration = f.acceleration * g;
  t.velocity = f.velocity * g * (dt > 0 ? dt : 1.0);
  t.force = f.force * W;
  return t;
}

}  // namespace cairn

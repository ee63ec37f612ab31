#pragma once
// Postcondition checks on a StabilityResult, shared by the stability tests.
#include <gtest/gtest.h>

#include <algorithm>

#include "cairn/stability/analyze.h"

namespace cairn::testing {

// Computed from the reported forces alone: in a stable configuration every
// movable part is in static equilibrium, Σ f + m g = 0 and Σ (p − c) × f = 0
// (2-D and 3-D alike: 2-D forces and points lie in the z = 0 plane).
inline void ExpectStaticEquilibrium(const Assembly& a, const Configuration& config,
                                    const StabilityResult& r) {
  const double W = 1e-7 * std::max(1.0, a.gravity().norm());
  for (const PartMotion& m : r.parts) {
    const Part& part = a.part(m.part);
    const Vector3 c = config.WorldCentroid(a, m.part);
    Vector3 force = part.mass * a.gravity();
    Vector3 torque = Vector3::Zero();
    for (const ContactReport& cr : r.contacts) {
      const Contact& k = cr.contact;
      const Vector3 f = cr.normal_force * k.n_W + cr.friction_force;
      if (k.part_a == m.part) {
        force += f;
        torque += (k.p_WC - c).cross(f);
      } else if (k.part_b == m.part) {
        force -= f;
        torque -= (k.p_WC - c).cross(f);
      }
    }
    EXPECT_NEAR(force.norm(), 0.0, W * part.mass) << part.name;
    EXPECT_NEAR(torque.norm(), 0.0, W * part.mass * a.scene_size()) << part.name;
  }
}

}  // namespace cairn::testing

#pragma once
// The drive of a part pulled along +x by the gripper with support "none"
// (guided: its weight rests on the parts under it), every other part judged.
#include "cairn/stability/analyze.h"

namespace cairn::testing {

inline DriveInputs PullAlongX(const Assembly& a, int part, double speed) {
  DriveInputs d;
  const int n = a.num_parts();
  d.role.assign(n, PartRole::kJudged);
  d.velocity.assign(n, Vector3::Zero());
  d.guide.assign(n, Vector3::UnitX());
  d.nu_prev.assign(n, Vector6::Zero());
  d.role[part] = PartRole::kGuided;
  d.velocity[part] = speed * Vector3::UnitX();
  return d;
}

}  // namespace cairn::testing

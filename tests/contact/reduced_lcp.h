#pragma once
// The solution of an LCP built from a subset of a component's contacts
// (HullContactSubset), extended to the LCP of all of them as
// include/cairn/contact/contact_reduction.h proves: zero p_n and p_f at the
// dropped contacts, λ = max(0, max_k −(J_dk ν)) there. Header-only, shared
// by tests/contact/contact_reduction_test.cpp and bench/degenerate_lcp_bench.cpp.

#include <algorithm>
#include <vector>

#include "cairn/mechanics/contact_model.h"

namespace cairn::testing {

// `full` and `reduced` are LCPs of the same bodies and formulation, `reduced`
// of the contacts `keep` (indices into full.contacts, ascending) in that order.
inline VectorX ExtendReducedSolution(const ContactLcp& full, const ContactLcp& reduced,
                                     const std::vector<int>& keep, const VectorX& z_reduced) {
  const int nc = static_cast<int>(full.contacts.size());
  const int nf = full.num_friction, D = full.num_directions;
  const int rc = static_cast<int>(reduced.contacts.size());
  const int rf = reduced.num_friction;
  VectorX z = VectorX::Zero(full.size());
  for (int r = 0; r < rc; ++r) {
    const int c = keep[r];
    z[c] = z_reduced[r];
    const int f = full.friction_of[c], g = reduced.friction_of[r];
    if (f < 0 || g < 0) continue;
    for (int k = 0; k < D; ++k) z[nc + D * f + k] = z_reduced[rc + D * g + k];
    z[nc + D * nf + f] = z_reduced[rc + D * rf + g];
  }
  if (nf == 0) return z;
  // λ at the dropped frictional contacts: λ enters only its own friction
  // rows (with coefficient 1), so w_dk = (J_dk ν) + λ.
  std::vector<bool> kept(nc, false);
  for (int c : keep) kept[c] = true;
  const VectorX w = full.Multiply(z) + full.q;
  for (int c = 0; c < nc; ++c) {
    const int f = full.friction_of[c];
    if (kept[c] || f < 0) continue;
    double lambda = 0;
    for (int k = 0; k < D; ++k) lambda = std::max(lambda, -w[nc + D * f + k]);
    z[nc + D * nf + f] = lambda;
  }
  return z;
}

}  // namespace cairn::testing

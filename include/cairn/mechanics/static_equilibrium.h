#pragma once
/// @file
/// Does a static equilibrium exist? A linear program over the contact forces
/// of one component, independent of the LCP:
///
///     find f_n ≥ 0, β_k ≥ 0 (per contact, k = 1..D)
///     with  Σ_c J_cᵀ (f_n n + Σ_k β_k d_k) + F_ext = 0  on every free body
///           Σ_k β_k ≤ μ f_n       (Coulomb: exact in 2-D, where d = ±t; the
///                                  LCP's inscribed D-pyramid in 3-D)
///
/// A feasibility problem: no objective. (Minimising Σ f_n, which picks a
/// canonical answer among the many of a statically indeterminate assembly,
/// made GLPK's simplex wander through tens of thousands of degenerate
/// vertices: 95 s against 4 s on the 184-block cross vault; the answer is
/// only asked whether it exists, docs/benchmarks.md.) The forces returned are
/// one equilibrium, not a canonical one.
///
/// The contact LCP decides what the parts *do* from rest; this decides
/// whether they *could* stand. The two differ where parts can only be held by
/// a squeeze that nothing produces: a block jammed between two walls, an arch
/// of wedges, the COMPAS H and A frames. There the LCP finds motion (from
/// rest no force builds the squeeze) while an equilibrium exists: the
/// configuration is *weakly stable* in the sense of Pang and Trinkle (paper
/// ref. [28]): some solution of the contact problem is at rest, not every
/// one. A configuration the LCP finds at rest always has an equilibrium (its
/// forces are one).
///
/// Guided bodies (pushed along a path) are in equilibrium only in their free
/// directions (the gripper supplies the rest); prescribed bodies are not
/// constrained. Solved with Clp's dual simplex (Debian coinor-libclp-dev); the answer is re-checked
/// from the returned forces.

#include <string>

#include "cairn/mechanics/contact_model.h"

namespace cairn {

/// The outcome of FindStaticEquilibrium.
struct StaticEquilibrium {
  bool solved = false;  ///< the LP solver reached a verdict (false: numerical trouble, see message)
  bool exists = false;  ///< an equilibrium exists
  VectorX normal_force;                 ///< (nc) force units, when it exists
  std::vector<Vector3> friction_force;  ///< (nc) on a, world frame, when it exists
  double residual = 0;  ///< max over body equations of |Σ J f + F_ext| (force units)
  /// When it exists: the same forces as unknowns of the component's LCP, with
  /// every body at rest (Baraff: the forces; Stewart–Trinkle: impulses f Δt,
  /// β Δt, and λ = 0). From rest with no gaps and no driven motion this solves
  /// the LCP (IsContactLcpSolution says whether it does): the stability
  /// analysis falls back on it when Lemke's method fails.
  VectorX lcp_z;
  std::string message;  ///< diagnostics when !solved
};

/// Solves the equilibrium LP of one component (see the file comment). Uses the
/// component's bodies, contact rows and contacts' μ; works for either
/// formulation of `lcp`.
StaticEquilibrium FindStaticEquilibrium(const ContactLcp& lcp);

}  // namespace cairn

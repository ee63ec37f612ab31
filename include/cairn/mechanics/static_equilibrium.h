#pragma once
/// @file
/// Could the parts stand? Linear programs over the contact forces of one
/// component, independent of the LCP.
///
/// **The equilibrium LP** (generator form). At a frictional contact the
/// admissible forces form the LCP's friction pyramid, the cone spanned by the
/// D generators  g_k = n + μ d_k  (k = 1..D; 2-D: n ± μ t, the exact Coulomb
/// cone; 3-D: the inscribed D-pyramid); at a frictionless one, by n alone.
///
///     find x ≥ 0 (one per generator)
///     with  Σ_j W_j x_j + F_ext = 0  on every free body   (W_j = J_jᵀ g_j, the
///                                                          generator's wrench)
///
/// A feasibility problem: no objective. Written with generators there are no
/// cone rows: on the Armadillo vault 2196 × 20 124 against 7227 × 25 155 for the
/// (f_n, β, Σβ ≤ μ f_n) form (../shared/notes/stability-lp-first.md). Large
/// problems are solved by Clp's interior-point method without crossover
/// (0.2 s there, against 6–10 s for the dual simplex), whose answer lies
/// strictly inside every cone used; small ones, and any the barrier leaves
/// unproven, by the dual simplex. Every answer is re-checked from the forces
/// (the equilibrium residual), never taken from the solver's status alone.
///
/// **Strong stability.** With `EquilibriumOptions::frictionless` the same LP
/// is solved with normal forces only. If a frictionless equilibrium exists,
/// every solution of the component's contact LCP from rest is at rest:
///   for any solution, with ν the body velocities after the step (S–T) or
///   accelerations (Baraff), the complementarity conditions give
///       νᵀ M ν = Δt F·ν + p_nᵀ J_n ν + p_fᵀ D ν = Δt F·ν − Σ_c μ_c λ_c p_n,c
///               ≤ Δt F·ν
///   (p_n ⊥ J_n ν; p_f ⊥ Dᵀν + Eλ; λ ⊥ μ p_n − Eᵀ p_f), and a frictionless
///   equilibrium F = −J_nᵀ f, f ≥ 0, gives F·ν = −fᵀ J_n ν ≤ 0 since J_n ν ≥ 0.
///   So νᵀ M ν ≤ 0 and ν = 0 (M is positive definite on the free motions).
/// (From rest, without gaps or driven parts: the static check.) An interior
/// frictional equilibrium is not enough: the COMPAS H frame has one and its
/// crossbar also falls (Pang and Trinkle's weak stability).
///
/// **The mechanism LP** (FindMechanism). By Farkas' lemma the equilibrium LP
/// is infeasible exactly when some virtual motion ν of the free bodies has
///     W_jᵀ ν ≥ 0 for every generator j  and  F_ext·ν > 0:
/// a motion no admissible contact force resists (each generator does
/// non-negative work: every contact opens or dilates) along which gravity does
/// positive work. Its bodies with ν ≠ 0 must move in some way: they name the
/// parts. It is the dual of the *elastic* equilibrium LP
///     min Σ_i w_i (s⁺_i + s⁻_i)  with  Σ_j W_j x_j + s⁺ − s⁻ = −F_ext,  x, s ≥ 0
/// (w = 1 on force rows, 1/r on torque rows, r the body's radius of
/// gyration): its row duals y give ν = −y, the motion of largest gravity power
/// F_ext·ν with W_jᵀν ≥ 0 and |v| ≤ 1, |ω| ≤ 1/r; the optimum is the least
/// unbalanced load. Solved like the equilibrium LP (barrier, with crossover so
/// that the dual is a vertex: bodies that need not move are exactly at rest),
/// it also decides infeasibility far faster than the dual simplex does.
///
/// The contact LCP decides what the parts *do* from rest; these decide what
/// they *could* do. Guided bodies (pushed along a path) are in equilibrium only
/// in their free directions (the gripper supplies the rest); prescribed bodies
/// are not constrained and do not move in a mechanism.

#include <optional>
#include <string>
#include <vector>

#include "cairn/mechanics/contact_model.h"

namespace cairn {

/// The outcome of FindMechanism.
struct Mechanism {
  bool found = false;  ///< a verified mechanism (see the file comment)
  /// (nb) the virtual motion (v, ω) of each body at its centroid, world axes;
  /// scaled so that its largest |v| + r|ω| is 1 (length/s of a unit-speed
  /// motion: a direction, not a velocity). Zero for bodies it leaves at rest.
  std::vector<Vector6> nu;
  std::vector<int> moving;  ///< local indices of the bodies with ν ≠ 0
  double power = 0;         ///< F_ext·ν > 0 (force · length/s)
  /// min over generators of W_jᵀ ν (≥ −roundoff: every contact opens or dilates)
  double least_generator_power = 0;
  std::string message;  ///< why none was found, when !found
};

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
  /// the LCP (IsContactLcpSolution says whether it does).
  VectorX lcp_z;
  /// When no equilibrium exists and the elastic LP proved it (large problems
  /// whose barrier solve failed): its mechanism, already checked.
  std::optional<Mechanism> mechanism;
  /// "barrier", "dual simplex", "primal simplex" or "barrier, mechanism"
  const char* method = "";
  int iterations = 0;   ///< of the method that decided
  std::string message;  ///< diagnostics when !solved
};

/// Options of FindStaticEquilibrium.
struct EquilibriumOptions {
  /// Normal forces only (every μ taken as 0): the strong-stability certificate.
  bool frictionless = false;
  /// Give up (solved = false) after this many simplex iterations; ≤ 0: Clp's
  /// default. A deterministic work budget for certificates worth less than
  /// their cost on very large components. With a budget only the dual simplex
  /// runs (the interior-point method is slow to prove infeasibility).
  int max_iterations = 0;
  /// The simplex only, even on large components: a vertex, whose amounts
  /// the basis gives to roundoff, where the interior-point method's answer
  /// balances only to its tolerance.
  bool vertex = false;
};

/// Solves the equilibrium LP of one component (see the file comment). Uses the
/// component's bodies, contact rows and contacts' μ; works for either
/// formulation of `lcp`.
StaticEquilibrium FindStaticEquilibrium(const ContactLcp& lcp,
                                        const EquilibriumOptions& options = {});

/// The mechanism LP (see the file comment): a virtual motion that proves the
/// component cannot stand, and names the parts that must move.
Mechanism FindMechanism(const ContactLcp& lcp);

/// Checks a virtual motion `nu` (one (v, ω) per body) as a mechanism of
/// `lcp`, as FindMechanism checks its own: scaled so that the fastest body
/// moves by 1, gravity's power F·ν > 0 and no generator's power negative,
/// both to the same slack. `found` says whether it passed. For motions that
/// come from elsewhere, such as the duals of a margin LP.
Mechanism VerifyMechanism(const ContactLcp& lcp, std::vector<Vector6> nu);

}  // namespace cairn

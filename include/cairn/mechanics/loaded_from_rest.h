#pragma once
/// @file
/// Loaded from rest: does a component stand when gravity is applied gently to
/// its unstressed parts, with compliant contacts? The answer rigid bodies
/// leave open (an equilibrium exists, and so does a motion: Pang and
/// Trinkle's weak stability) decided the way discrete-element practice
/// decides it.
///
/// **Model.** The parts stay rigid; each contact point is a pair of springs
/// (docs/loaded-from-rest.md): normal stiffness k_n in compression only, and
/// tangential stiffness k_t = κ k_n with Coulomb slip. Small displacements:
/// body k moves by u_k = B_k ξ_k (its free directions B_k, contact_model.h),
/// a contact's relative displacement is J u (the LCP's rows). Gravity is
/// applied from zero, proportionally, to an assembly with no initial stress
/// and no gaps (the parts just touch).
///
/// **One linear complementarity problem.** With zero initial gaps every
/// relation is positively homogeneous: if (ξ, f) is an equilibrium under the
/// full load, λ(ξ, f) is one under λ times the load, and the slips grow in
/// proportion, each along its friction force. So the proportional path
/// from rest is radial, and the quasi-static incremental analysis (the loads
/// applied in steps, each a consistent increment of the elastic–plastic
/// contact laws) is the one state at full load (holonomic, deformation-theory
/// friction):
///
///     Σ J_nᵀ f_n + Σ J_Dᵀ β + F = 0            on every body's free directions
///     0 ≤ f_n ⊥ J_n u + f_n / k_n ≥ 0           (penetration f_n / k_n, or open)
///     0 ≤ β   ⊥ J_D u + Gᵀ G β / k_t + E γ ≥ 0  (the slip s = J_D-part + t / k_t
///                                                 opposes the friction force
///                                                 t = Σ_k d_k β_k)
///     0 ≤ γ   ⊥ μ f_n − Eᵀ β ≥ 0                (sticks inside the pyramid,
///                                                 slips on its edge)
///
/// with G = [d_1 … d_D] the friction directions (the LCP's pyramid).
///
/// **One LCP.** u is free: written as ξ' − s·1 (ξ' ≥ 0, one shift s ≥ 0),
/// with the equilibrium rows as the partners of ξ' and their negated sum as
/// the partner of s (all ≥ 0 forces equality), the problem is one LCP whose
/// matrix is skew-symmetric plus the contact laws' block, with quadratic form
/// f_n²/k_n + |t|²/k_t + γ μ f_n ≥ 0 on z ≥ 0: copositive, as the
/// Stewart–Trinkle matrix is. Lemke's method solves it; the solution is
/// checked against the equilibrium (to 10⁻⁶ of a weight).
///
/// **What it answers.** A solution: the component stands when loaded from
/// rest, with these forces. A secondary ray: no state of the springs holds
/// full gravity, it gives way (with friction Lemke's method is not proved
/// complete here: the ray is taken as the answer). How it gives way: one
/// implicit Stewart–Trinkle step from rest with the compliant contacts and
/// almost no inertia (m / Δt² = 10⁻⁶ k_n): the bodies the springs hold barely
/// move, the others run away (`displacement`, `unbalanced` the share of the
/// fastest body's displacement).
///
/// **No absolute stiffness.** Scaling k_n and k_t together (and with them the
/// step's inertia, ρ being a ratio) scales u by the inverse and leaves every
/// force and verdict as it is (the LCP is homogeneous); only κ = k_t / k_n
/// matters. κ = 2(1 − ν)/(2 − ν) with
/// ν = 0.2 (Mindlin's ratio for stone and concrete): 0.889.
#include <optional>
#include <string>
#include <vector>

#include "cairn/lcp/lemke.h"
#include "cairn/mechanics/contact_model.h"

namespace cairn {

/// Mindlin's ratio of tangential to normal contact stiffness, 2(1 − ν)/(2 − ν)
/// at Poisson's ratio ν = 0.2 (dimensionless).
inline constexpr double kTangentialStiffnessRatio = 2.0 * (1.0 - 0.2) / (2.0 - 0.2);

/// Options of LoadFromRest.
struct LoadFromRestOptions {
  /// κ = k_t / k_n (dimensionless, > 0).
  double stiffness_ratio = kTangentialStiffnessRatio;
  /// Multiplies every stiffness (dimensionless, > 0). No answer depends on it
  /// beyond round-off (the file comment): tests scale it by 10.
  double stiffness_scale = 1.0;
  /// The largest LCP LoadFromRest solves (variables); above it the answer is
  /// "not run" (a work budget).
  int max_variables = 1500;
  /// Lemke's method on the loading LCP; max_pivots ≤ 0 means 10 per variable
  /// (a path that ends takes at most 5 on the cross vault's states).
  LemkeParameters lemke;
  /// Whether a component that gives way is also said to move how (the
  /// collapse step, often more work than the verdict). Off: `displacement`
  /// and `unbalanced` stay empty.
  bool explain = true;
};

/// The outcome of LoadFromRest.
struct LoadedFromRest {
  enum class Outcome {
    kStands,    ///< an equilibrium of the compliant contacts under full gravity (checked)
    kGivesWay,  ///< no such equilibrium: something slides or tips even when loaded gently
    kNotRun,    ///< beyond the work budget (LoadFromRestOptions::max_variables)
    kFailed,    ///< Lemke's method failed (see message)
  };
  Outcome outcome = Outcome::kNotRun;
  VectorX normal_force;                 ///< (nc) force units, on a along n (kStands)
  std::vector<Vector3> friction_force;  ///< (nc) on a, world frame (kStands)
  std::vector<bool> slipping;           ///< (nc) the contact slips (on its pyramid's edge)
  /// (nb) each body's displacement (v, ω) at its centroid, in units of the
  /// model's own stiffness scale: only its shape is meaningful.
  std::vector<Vector6> displacement;
  /// (nb) the force the contacts leave unbalanced on each body, as a fraction of its weight
  std::vector<double> unbalanced;
  double equilibrium_residual = 0;  ///< the largest of `unbalanced`
  double tolerance = 0;             ///< a body gives way when its `unbalanced` is above it
  int variables = 0;                ///< the LCP's size
  int pivots = 0;
  double stiffness = 0;  ///< k_n used, force/length (any positive value gives the same answer)
  std::string message;
};

/// "stands", "gives way", "not run", "failed".
const char* to_string(LoadedFromRest::Outcome o);

/// Loads the component of `lcp` (its bodies, contacts, μ and friction
/// directions; not its formulation's matrix) from rest (file comment).
/// Driven bodies are treated as their free directions allow (prescribed ones
/// do not move).
LoadedFromRest LoadFromRest(const ContactLcp& lcp, const LoadFromRestOptions& options = {});

}  // namespace cairn

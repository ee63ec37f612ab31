#pragma once
/// @file
/// How far from failing is one component? Parametric forms of the
/// equilibrium LP (mechanics/static_equilibrium.h), whose answers are the
/// margins of `cairn margin` (docs/margin.md).
///
/// **A load along a line.** With F(s) = F_ext + s F₁ (F₁ a wrench per body),
/// the set of s at which the component can stand,
///     S = { s : ∃ x ≥ 0,  Σ_j W_j x_j + F_ext + s F₁ = 0 },
/// is the projection of a polyhedron: a closed interval. Its ends are one LP
/// each (OptimizeLoadParameter: max s or min s over (x, s)). S is unbounded
/// above exactly when F₁ alone is carried: if Σ W_j y_j + F₁ = 0 for some
/// y ≥ 0 then F_ext + s F₁ is carried for every s ≥ s₀ ∈ S (add (s − s₀) y);
/// conversely F(s)/s → F₁ and the cone of the W_j is closed. So one
/// equilibrium LP (F₁ alone carried?) decides unboundedness exactly: the
/// margins solve the LP for the end first and ask it only when that LP
/// reports no finite end.
///
///  - the load margin: F₁ = Jᵀ(P) d, the wrench of a unit force along d at
///    point P of one body; s ≥ 0 is the force in force units.
///  - the tilt margin: gravity turned by θ about an axis a ⟂ g (the assembly
///    fixed to the axis), in the assembly's frame g(θ) = cos θ g − sin θ
///    (a × g); divided by cos θ > 0 it is g − t (a × g), t = tan θ, and
///    feasibility does not change under a positive scaling of every load.
///    So F₁ = −m (a × g) on each body (a force at its centroid), one LP per
///    end for |θ| < 90°, and the same with −F_ext for 90° < θ < 270°
///    (stability/margin.h puts the pieces together).
///
/// **Friction.** The generators n + k μ_c d_k are bilinear in the factor k,
/// so the least k is not one LP; but feasibility is monotone in k (the
/// pyramid k μ P grows with k, as P, the convex hull of the unit directions
/// d_k, contains 0). FrictionDeficitLp measures how far a factor k is from
/// standing, φ(k), with the slope that Newton's method needs
/// (stability/margin.cpp).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cairn/mechanics/contact_model.h"
#include "cairn/mechanics/static_equilibrium.h"

namespace cairn {

/// The outcome of OptimizeLoadParameter.
struct LoadParameterResult {
  enum class Status {
    kOptimal,     ///< `value` is the end of S; `equilibrium` the forces there (verified)
    kInfeasible,  ///< S is empty (or its side of s ≥ lower bound is)
    kUnbounded,   ///< the LP reports no finite end (IsCarried should have said so first)
    kFailed,      ///< numerical trouble (`message`)
  };
  Status status = Status::kFailed;
  double value = 0;  ///< the optimal s
  /// The equilibrium at F_ext + value F₁, re-checked from the forces.
  StaticEquilibrium equilibrium;
  /// The LP's row duals as a virtual motion per body, ν = −P y: no generator
  /// resists it and F₁·ν ≠ 0, so past the end (s beyond `value`) gravity and
  /// the load do work along it. A mechanism just past the end, unverified
  /// (VerifyMechanism checks it).
  std::vector<Vector6> motion;
  const char* method = "";
  int iterations = 0;
  std::string message;
};

/// OptimizeLoadParameter solves by the LP policy's method for a parametric
/// LP (cairn/mechanics/lp_policy.h; columns: generators + 1). The simplex
/// proves an empty S as fast as the equilibrium LP; the interior-point method
/// does not (it runs to its iteration limit first), which callers may weigh.
/// max s (maximize) or min s over S ∩ [lower_bound, ∞) (see the file
/// comment); `load` has one wrench per body of `lcp` (force units per unit of
/// s); `frictionless` solves with normal forces only (the strong-stability
/// certificate's margin).
LoadParameterResult OptimizeLoadParameter(const ContactLcp& lcp, const std::vector<Vector6>& load,
                                          bool maximize, double lower_bound, bool frictionless);

/// `lcp` with every body's external wrench replaced by `load` (one per body).
ContactLcp WithLoads(const ContactLcp& lcp, const std::vector<Vector6>& load);

/// `lcp` with every contact's μ multiplied by `factor` (≥ 0; its friction rows
/// are kept, so that factor 0 is the frictionless LP).
ContactLcp WithFrictionFactor(const ContactLcp& lcp, double factor);

/// The least friction factor at which the forces of `e` (an equilibrium of
/// `lcp`) are admissible: max over contacts of γ(f_t / (μ_c f_n)), γ the
/// gauge of the polygon P = conv{d_k} (2-D: |f_t| / (μ f_n); 3-D, the D
/// directions at angles 2πk/D: max_k u·(d_k + d_{k+1}) / (1 + cos 2π/D)).
/// The same forces are an equilibrium at every factor from it on: an upper
/// bound on k* as good as the solution is tight. +∞ when a contact with no
/// friction carries a tangential force.
double FrictionUse(const ContactLcp& lcp, const StaticEquilibrium& e);

/// The friction deficit at factor k: how much friction the component lacks
/// to stand. The equilibrium LP (generator form) with, at every frictional
/// contact, extra friction z_ci ≥ 0 along each direction d_i beyond the
/// pyramid k μ_c f_n:
///
///     φ(k) = min Σ z_ci  over x ≥ 0, z ≥ 0 with
///            Σ_j W_j(k) x_j + Σ_ci T_ci z_ci + F_ext = 0,
///
/// W_j(k) = J_jᵀ (n + k μ_c d_i) the pyramid's edges, T_ci = J_cᵀ d_i, in
/// units of the largest load. φ(k) = 0 exactly when the component stands at
/// k (the x of the LP's answer are then such an equilibrium), φ(k) > 0 when
/// it does not. The LP's φ is good to its solver's tolerance only (the
/// interior-point method's gap, 1e-8 relative): a small positive `deficit`
/// is not a proof of failure. The dual `motion` checked as a mechanism
/// (VerifyMechanism), or the equilibrium LP at k, proves it. Unlike the feasibility LP, whose
/// interior vanishes as k → k* (the interior-point method ran out of its 60 iterations there), this
/// one is strictly feasible on either side of k*, so the interior-point method reaches an answer
/// there too, if slowly (100–750 iterations on the Armadillo vault: docs/benchmarks.md).
///
/// φ is non-increasing in k. By the envelope theorem, raising k by δ turns
/// generator (c, i) by δ μ_c T_ci; a contact's normal force may go to any of
/// its D generators, so φ falls by δ Σ_c μ_c f_n,c max_i yᵀT_ci, y the
/// equilibrium rows' duals: that is `slope` (≤ 0, as the d_i sum to 0).
/// Newton's step k + φ/|slope| from below reaches k* in a few LPs where
/// bisection needs twenty (stability/margin.cpp).
struct FrictionDeficit {
  bool solved = false;  ///< the LP was solved (false: `message`)
  /// φ(k) (dimensionless, in units of the largest load); +∞ when no
  /// friction, however large, holds the component (the LP is infeasible)
  double deficit = 0;
  double slope = 0;  ///< dφ/dk (≤ 0), from this solution's duals
  /// The equilibrium rows' duals as a virtual motion per body, ν = −P y:
  /// where φ(k) > 0 no generator at k resists it and gravity does work φ(k)
  /// along it (in load units), a mechanism at k, unverified (VerifyMechanism)
  std::vector<Vector6> motion;
  bool exists = false;            ///< φ(k) ≈ 0 and its forces passed the re-check: `equilibrium`
  StaticEquilibrium equilibrium;  ///< at factor k, in the caller's force units
  const char* method = "";
  int iterations = 0;
  std::string message;
};

/// φ(k) of one component (see FrictionDeficit) at successive factors k:
/// the interior-point method (no crossover) on large components, the dual
/// simplex on small ones.
class FrictionDeficitLp {
 public:
  explicit FrictionDeficitLp(ContactLcp lcp) : lcp_(std::move(lcp)) {}

  /// φ(k); `k` ≥ 0 multiplies every μ.
  FrictionDeficit Solve(double k);
  int lps() const { return lps_; }                ///< LPs solved so far
  int iterations() const { return iterations_; }  ///< simplex and barrier iterations

 private:
  ContactLcp lcp_;
  int lps_ = 0, iterations_ = 0;
};

}  // namespace cairn

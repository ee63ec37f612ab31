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
/// conversely F(s)/s → F₁ and the cone of the W_j is closed. So
/// IsCarried(F₁) (one equilibrium LP) decides unboundedness exactly, and the
/// LP for the end is only solved when it has a finite optimum.
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
/// d_k, contains 0), so a bisection on k converges to k* with verified ends.
/// FrictionProbe solves the equilibrium LP at successive k on one Clp model,
/// warm-started from the last basis: with no objective every basis is dual
/// feasible, so the dual simplex starts from it whatever the new k.

#include <memory>
#include <optional>
#include <string>
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
  const char* method = "";
  int iterations = 0;
  std::string message;
};

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

/// The largest friction factor at which mechanism `m` of `lcp` stays
/// admissible: every generator power P_n + k μ P_dk ≥ 0 holds for k ≤
/// min over P_dk < 0 of P_n / (μ |P_dk|) (and P_n ≥ 0, the average over the
/// symmetric d_k). So no equilibrium exists at any factor up to it: a lower
/// bound on k*. +∞ when no generator's power falls with k.
double MechanismFrictionBound(const ContactLcp& lcp, const Mechanism& m);

/// The equilibrium LP of one component at successive friction factors k, on
/// one warm-started Clp model (see the file comment).
class FrictionProbe {
 public:
  explicit FrictionProbe(const ContactLcp& lcp);
  ~FrictionProbe();
  FrictionProbe(const FrictionProbe&) = delete;
  FrictionProbe& operator=(const FrictionProbe&) = delete;

  /// Can the component stand with every μ multiplied by k? `solved` false:
  /// the solver failed (the caller decides). A "yes" is re-checked from the
  /// forces (the equilibrium residual); the forces are in `last()`.
  struct Answer {
    bool solved = false;
    bool exists = false;
  };
  Answer Probe(double k);
  /// The equilibrium of the last probe that found one.
  const StaticEquilibrium& last() const { return last_; }
  int lps() const { return lps_; }                ///< probes solved so far
  int iterations() const { return iterations_; }  ///< simplex iterations, all probes
  int warm_starts() const { return warm_; }       ///< probes started from a stored basis

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  StaticEquilibrium last_;
  int lps_ = 0, iterations_ = 0, warm_ = 0;
};

}  // namespace cairn

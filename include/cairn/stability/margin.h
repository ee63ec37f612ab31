#pragma once
/// @file
/// How far from failing is a configuration? The critical friction, the
/// critical tilt about an axis, or the largest load along a line that the
/// assembly carries at rest (`cairn margin`; the mathematics is in
/// mechanics/margin_lp.h and docs/margin.md).
///
/// ComputeMargin reads as its steps: build each contact-graph component's
/// LCP (BuildComponentLcps) → each component's margin (one or a few LPs, or
/// a verified bisection) → the assembly's margin, the worst component's →
/// the certificates: the equilibrium at the critical value, re-checked from
/// its forces, and the mechanism just past it (FindMechanism, checked), and
/// for friction the check (AnalyzeConfiguration) just below μ*: which parts
/// move and how.
///
/// Every margin here is the *weak* one: the LP's, "an equilibrium exists"
/// (rest is possible). The strong margin (every solution of the LCP at rest)
/// is bounded from within by the frictionless-equilibrium certificate
/// (mechanics/static_equilibrium.h): where a frictionless equilibrium exists
/// the assembly is strongly stable, so the same parametric LP with normal
/// forces only gives a range of loads or tilts certified strong. It is a
/// sufficient condition: beyond it strong stability is not decided.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/geometry/assembly.h"
#include "cairn/stability/analyze.h"

namespace cairn {

/// What the margin measures.
enum class MarginQuantity { kFriction, kTilt, kLoad };

/// "friction", "tilt", "load".
const char* to_string(MarginQuantity q);

/// What to compute.
struct MarginRequest {
  MarginQuantity quantity = MarginQuantity::kFriction;
  /// kTilt: the axis (world frame of the assembled pose; normalised here).
  /// 2-D scenes turn in their plane: the axis must be ±z.
  Vector3 axis{0, 0, 1};
  /// kLoad: the part, the point of application (world frame, assembled
  /// pose) and the direction of the force (normalised here).
  int part = -1;
  Vector3 point{0, 0, 0};
  Vector3 direction{0, 0, 0};
  /// The verdict whose threshold `verdict_critical` is, and whose answer at
  /// the nominal value `stands_at_nominal` is (the check's --rule).
  VerdictRule rule = VerdictRule::kLoadedFromRest;
};

/// The equilibrium at a critical value: the contact forces, re-checked.
struct MarginEquilibrium {
  double at = 0;  ///< the value (μ or factor, degrees, force units)
  std::vector<Contact> contacts;
  VectorX normal_force;                 ///< (nc) force units
  std::vector<Vector3> friction_force;  ///< (nc) on a, world frame
  double residual = 0;                  ///< max |Σ J f + F_ext| (force units)
};

/// The mechanism just past a critical value (mechanics/static_equilibrium.h,
/// FindMechanism): a virtual motion no contact resists, along which the
/// loads do positive work.
struct MarginMechanism {
  double at = 0;            ///< the value it was found at
  bool found = false;       ///< verified (false: see message)
  std::vector<int> parts;   ///< part indices that move
  std::vector<Vector6> nu;  ///< their (v, ω), in the order of `parts` (a direction)
  /// How each of `parts` moves (ClassifyRigidMotion, keeping contact: a
  /// mechanism is a direction of motion from the contacts, slides or tips).
  std::vector<MotionKind> kinds;
  double power = 0;  ///< the loads' power along it (force · length/s)
  std::string message;
};

/// One end of the margin (tilt: each sense; friction and load: one).
struct MarginSide {
  /// The critical value (μ* or k*; degrees, signed; F* in force units);
  /// empty: no end (tilt: holds all the way round; load: carries any load;
  /// friction: no friction makes it stand).
  std::optional<double> critical;
  int component = -1;  ///< the component that decides it (index into components)
  std::optional<MarginEquilibrium> equilibrium;
  std::optional<MarginMechanism> mechanism;
  /// The range certified strong (a frictionless equilibrium: the same
  /// parametric LP with normal forces only), when computed; empty critical
  /// inside: holds all the way.
  std::optional<std::optional<double>> strong;
  /// kTilt, kLoad: the threshold of the check's verdict (the request's rule)
  /// in this sense: the largest angle (degrees, signed) or load (force units)
  /// up to which the check was found to stand, within the result's
  /// `verdict_tolerance`; 0 when it does not stand as given; empty: it stands
  /// at every angle (every load up to `verdict_searched_to`) tried.
  std::optional<double> verdict_critical;
};

/// One component's margin.
struct ComponentMargin {
  std::vector<int> parts;
  bool holds_at_nominal = true;
  std::vector<std::optional<double>> critical;  ///< one per side
  int lps = 0;
};

/// Everything ComputeMargin found.
struct MarginResult {
  MarginQuantity quantity = MarginQuantity::kFriction;
  bool solved = true;  ///< false: an LP failed (message); nothing else is meaningful
  std::string message;
  /// The configuration as given stands (weakly): friction at its own μ,
  /// no tilt, no load.
  bool holds_at_nominal = true;
  /// The verdict of `cairn check` (with the request's rule) on the
  /// configuration as given: the command's exit code. It can fall where an
  /// equilibrium holds (`holds_at_nominal`), never the other way round.
  bool stands_at_nominal = true;
  /// kFriction: whether `critical` is μ itself (every contact the same μ) or
  /// a factor k scaling every μ (the scene has friction_pairs).
  bool factor = false;
  double nominal = 0;             ///< kFriction: the configuration's own μ, or 1 (factor)
  Vector3 axis{0, 0, 1};          ///< kTilt: the unit axis
  double part_weight = 0;         ///< kLoad: m |g| of the loaded part (force units)
  std::vector<MarginSide> sides;  ///< tilt: {negative sense, positive sense}; else one
  std::vector<ComponentMargin> components;
  std::string method;
  /// The numerical tolerance of `critical` (its unit): a bisection's final
  /// bracket, or the LP's relative feasibility tolerance times the value.
  double tolerance = 0;
  int lps = 0;  ///< linear programs solved (all components, certificates excluded)
  /// kFriction: the check just below μ* (at μ*(1 − 1e-3), or at the
  /// greatest factor proved to fail where the bracket is wider: μ* below
  /// 1e-6): its μ (or factor), and the moving parts with how they move.
  std::optional<double> failing_at;
  std::vector<PartMotion> failing_below;
  /// kFriction: every component has a frictionless equilibrium (strongly
  /// stable at every μ); false: the certificate holds at no μ.
  std::optional<bool> strong_all;
  /// The threshold of the verdict (`cairn check`, the
  /// loaded-from-rest rule: stability/solve_component.h): the least μ (or
  /// factor) at which the check stands, to `verdict_tolerance` (the final
  /// bracket). It is at least the equilibrium's `critical`; empty when the
  /// check stands at no μ up to `verdict_searched_to` (ten times the larger
  /// of `critical` and the nominal μ).
  std::optional<double> verdict_critical;
  double verdict_searched_to = 0;
  double verdict_tolerance = 0;
  bool verdict_computed = false;
  int verdict_checks = 0;  ///< checks made to find it
};

/// Computes the margin of `config` (see the file comment). `def` is the
/// model's definition (its friction: FrictionScalingOf); the friction margin
/// varies μ on `assembly` itself (Assembly::WithFriction). @throws InputError for a request that
/// makes no sense (a fixed or absent part, a zero or non-finite axis or direction, a point beyond
/// the scene's coordinate range, a 2-D tilt off z). The axis and direction
/// may have any finite length (UnitVector).
MarginResult ComputeMargin(const AssemblyDef& def, const Assembly& assembly,
                           const Configuration& config, const MarginRequest& request);

/// The checks ComputeMargin makes of a request on `assembly` (all but the
/// loaded part's presence in the configuration), for front ends that check
/// before they load more. @throws InputError naming `file` and the flag
/// (--tilt, --load, --point, --direction) and what is wrong.
void CheckMarginRequest(const Assembly& assembly, const MarginRequest& request,
                        const std::string& file = "");

/// The model with every friction coefficient multiplied by `factor` (the
/// default μ and every friction pair's): what the friction margin scales.
AssemblyDef ScaleFriction(const AssemblyDef& def, double factor);

/// What a friction margin varies: the friction factor k on `base`.
/// Without friction pairs, base has μ = 1 everywhere, so k is μ itself and
/// the scene's μ is `nominal`; with them, base is the scene and k scales every
/// μ (`nominal` = 1). `k_max` keeps every μ within limits::kMaxFriction.
struct FrictionScaling {
  bool factor = false;  ///< k scales the scene's friction pairs (else k is μ)
  double base_mu = 1;   ///< base's default μ (1, or the scene's with pairs)
  double nominal = 0;
  double k_max = 0;
  /// The scene's model (built from the definition this scaling was made of)
  /// at factor k: base scaled by k, without building it again.
  Assembly At(const Assembly& scene, double k) const { return scene.WithFriction(base_mu * k, k); }
};
FrictionScaling FrictionScalingOf(const AssemblyDef& def);

}  // namespace cairn

#pragma once
/// @file
/// Every tolerance Cairn uses, named, with its unit, in one struct, scaled to
/// the scene (after Box2D's B2_LINEAR_SLOP and Drake's ComputeZeroTolerance).
///
/// The scale of a scene is its size L (length units: the diagonal of the
/// bounding box of all parts) and its gravity g (length/s², the norm of the
/// gravity vector; 1 if the scene has none). The rules:
///   length       = 1e-6 · L       unless the scene sets "tolerance"
///   angle        = 1e-6 rad       (parallel/anti-parallel edges, normals);
///                  a tessellated model's: its overlap allowance over its
///                  smallest part's size, if larger (at most 1e-2)
///   acceleration = 1e-6 · g       (length/s²; a part whose points accelerate
///                                  less than this is at rest)
///   velocity     = 1e-6 · g · Δt  (length/s; the same for one time step)
///   force        = 1e-9 · W       (force units; W = the scene's largest weight)
/// The relative factors are the defaults of ToleranceFactors; change them
/// there, not at the call sites.

namespace cairn {

/// Numerical thresholds: not physical tolerances (those are Tolerances, below,
/// scaled to the scene) but the roundoff allowed in purely numerical
/// decisions. Dimensionless, relative to the magnitudes compared.
namespace numeric {
/// Roundoff of a comparison of O(1) quantities: two unit vectors this close are
/// the same, a determinant this small relative to its factors' lengths is
/// singular, a gap this small is a tie (≈ 4500 ε).
inline constexpr double kRoundoff = 1e-12;
/// Slack on a parameter in [0, 1] (along a segment, a path, barycentric) or on
/// a direction cosine near ±1 before it counts as outside: far above the
/// roundoff of the products that make it, far below any tolerance a user sets.
inline constexpr double kParameterSlack = 1e-9;
}  // namespace numeric

/// The ranges of a scene's numbers that Cairn accepts (docs/scene-format.md,
/// "Validated ranges"). Beyond them the products the mechanics forms
/// (moments, inertias m·L², impulses m·g·Δt, the LCP's W M⁻¹ Wᵀ) lose their
/// precision or leave the range of a double, and a verdict could not be
/// trusted; so the input is refused, naming the value, instead.
namespace limits {
/// |x| of every vertex and point of a scene (length units).
inline constexpr double kMaxCoordinate = 1e12;
/// A part's size (the diagonal of its bounding box) at least this many
/// length tolerances: a smaller part is within the tolerance of a point, so
/// its edges and faces cannot be told apart (a scene spanning too many orders
/// of magnitude, or a --tolerance too coarse for its parts).
inline constexpr double kMinPartSizeInTolerances = 100;
/// A part's mass (mass units), given or from its density.
inline constexpr double kMinMass = 1e-30, kMaxMass = 1e30;
/// The heaviest movable part at most this many times the lightest: the
/// contact problem's matrix W M⁻¹ Wᵀ has entries in the ratio of the masses.
inline constexpr double kMaxMassRatio = 1e9;
/// Coulomb friction coefficients (dimensionless): at most this. A contact
/// that must never slide is modelled well by μ = 100 already; the friction
/// pyramid's generators n + μ d lose the normal's digits beyond this.
inline constexpr double kMaxFriction = 1e3;
/// |g| (length/s²): zero (no gravity) or within these.
inline constexpr double kMinGravity = 1e-9, kMaxGravity = 1e9;
/// The angle tolerance of a tessellated model (radians) at most: its
/// allowance over its smallest part's size (Assembly::MakeTolerances),
/// kept below the angles that tell one facet of a curved surface from the
/// next (OpenCASCADE's angular deflection is 0.5 rad; Cairn's facets turn
/// by far less).
inline constexpr double kMaxApproximatedAngle = 1e-2;
/// The largest overlap depth (AssemblyDef::overlap_depth), as a fraction of
/// the smallest part's bounding-box diagonal (dimensionless): deeper than
/// that, parts do not touch, they share material (a bolt in its hole, a
/// part placed twice), which `--fastened` or a corrected model answers.
inline constexpr double kMaxOverlapDepthFactor = 0.05;
}  // namespace limits

/// Relative factors from which Tolerances are scaled (dimensionless).
struct ToleranceFactors {
  double length = 1e-6;        ///< × scene size L.
  double angle = 1e-6;         ///< radians, not scaled.
  double acceleration = 1e-6;  ///< × |g|.
  double velocity = 1e-6;      ///< × |g| Δt.
  double force = 1e-9;         ///< × largest weight m|g|.
};

/// Absolute tolerances for one scene.
struct Tolerances {
  double length = 1e-6;        ///< length units: contact distance, overlap allowance.
  double angle = 1e-6;         ///< radians: parallelism of edges and normals.
  double acceleration = 1e-6;  ///< length/s²: largest point acceleration called "at rest".
  double velocity = 1e-6;      ///< length/s: largest point velocity called "at rest".
  double force = 1e-9;         ///< force units: a contact force below this is zero.
  /// length units: how deep two parts may interpenetrate and still be read
  /// as apart or touching: the overlap test's allowance (an assembly's
  /// parts, a part's path, the relation to infinity of blocking graphs).
  /// `length` plus, where the surfaces are approximations, an allowance
  /// (AssemblyDef::overlap_allowance): a STEP model's facets cut into the
  /// void across a hole's wall by up to the chordal tolerance, so a pin and
  /// its hole, touching in CAD, interpenetrate by up to that much; plus the
  /// overlap depth of parts meant to touch (AssemblyDef::overlap_depth).
  double penetration = 1e-6;

  /// Tolerances for a scene of size `scene_size` (length), gravity magnitude
  /// `gravity` (length/s²), time step `dt` (s), largest weight `weight`.
  /// `length_override` > 0 replaces the scaled length tolerance.
  static Tolerances Scaled(double scene_size, double gravity, double dt, double weight,
                           double length_override = 0.0, const ToleranceFactors& f = {});
};

}  // namespace cairn

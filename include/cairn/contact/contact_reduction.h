#pragma once
/// @file
/// Reducing every planar contact patch to the vertices of its convex hull.
///
/// A face–face contact in 3-D, or a stored interface, gives one contact point
/// per vertex of the contact polygon, and an interface triangulated in CAD
/// gives many more: points inside the polygon and on its edges. They all
/// share one normal, so the contact LCP's rows of one patch span at most six
/// dimensions, and the redundant ones make Lemke's method massively
/// degenerate. HullContactSubset keeps of each patch only the vertices of its
/// convex hull.
///
/// Patch. Contacts i and j belong to one patch when they join the same parts
/// (part_a, part_b, in that order), have the same μ, normals n_i·n_j ≥
/// cos(angle tolerance), lie in one plane (|n·(p_j − p_i)| ≤ length
/// tolerance) and have gaps within the gap tolerance of each other. The points
/// of a patch are projected on its plane, and the points that are not vertices
/// of the 2-D convex hull — interior points and points on a hull edge — are
/// dropped. A patch whose points are collinear keeps its two extreme points
/// (this is also how a 2-D edge contact reduces); a patch of one point keeps
/// it. Vertex tests are exact up to roundoff (kHullRoundoff), never up to the
/// length tolerance: a point that is outside the hull by more than roundoff
/// is kept.
///
/// Why this is exact. Let a dropped point be p = Σ_i α_i p_i (α ≥ 0, Σ α = 1)
/// over hull vertices p_i of its patch, all with normal n, gap g, and μ.
///
///  - Static equilibrium (linear program over contact forces). A force f
///    (f_n ≥ 0, |f_t| ≤ μ f_n) at p has the wrench (f, p × f) = Σ α_i (f,
///    p_i × f): the forces α_i f at the hull vertices, each in the same cone.
///    Every equilibrium with the full set of points is one with the hull
///    vertices only (and conversely, trivially). This needs p in the plane of
///    the p_i: a component h n of p − Σ α_i p_i changes the moment by
///    h n × f_t. Hence the coplanarity test.
///
///  - The contact LCPs (Baraff; Stewart–Trinkle). Given a solution z_r of the
///    reduced LCP, extend it by p_n = 0, p_f = 0 at each dropped point, and
///    for Stewart–Trinkle λ = max(0, max_k −(J_dk ν⁺)) there. The body motions
///    ν (ν̇ for Baraff) do not change (the dropped points carry no force), so
///    every kept row keeps its w and its complementarity. At the dropped
///    point:
///      * normal row: w_n(p) = n·(v_a + ω_a × (p − c_a) − v_b − ω_b × (p − c_b))
///        + g/Δt is affine in p, so w_n(p) = Σ α_i w_n(p_i) ≥ 0 (with the
///        same g at every point: hence the gap test; and it is unchanged by
///        a displacement of p along n, since n·(ω × n) = 0). With p_n = 0 it
///        is complementary.
///      * friction rows: w_dk = J_dk ν + λ ≥ 0 by the choice of λ, ⊥ p_f = 0.
///      * λ row: w_λ = μ p_n − Σ_k p_fk = 0, so λ ≥ 0 is complementary.
///    So the extension solves the full LCP: the verdict (which parts move and
///    how) of the reduced LCP is a valid verdict of the full one.
///
/// When it is NOT exact (and such points are kept): points with different
/// gaps (the Stewart–Trinkle normal offset g/Δt differs, so w_n is no longer
/// the convex combination; points are grouped only with gaps within the gap
/// tolerance, 0 by default: identical), different normals or μ (not one
/// patch), points off the plane (the LP's friction moment). Keeping at most
/// four points per face, as game engines do, changes the wrench cone and is
/// never exact; HullContactSubset keeps every hull vertex.
///
/// Use: call it on one component's contacts before BuildContactLcp (the
/// equilibrium LP likewise), and build the LCP from the kept contacts only;
/// report zero force at the dropped ones.

#include <vector>

#include "cairn/contact/contact.h"

namespace cairn {

/// Tolerances of HullContactSubset.
struct ContactReductionTolerances {
  /// Largest angle between two normals of one patch (rad). The argument above
  /// is exact for identical normals (one face–face patch, one stored
  /// interface); with different normals it errs by O(angle · |ν|).
  double angle = 1e-9;
  /// Largest distance of a point from its patch's plane (length). Usually the
  /// model's length tolerance.
  double length = 1e-9;
  /// Largest difference of gaps within a patch (length). 0 (default): only
  /// identical gaps, exact for every formulation. A caller that ignores gaps
  /// (a static check, BuildContactLcp with use_gaps = false, or the LP) may
  /// pass infinity.
  double gap = 0.0;
};

/// Relative roundoff of the convex-hull vertex test: a point is on a hull edge
/// when its distance from the edge's line is ≤ kHullRoundoff × the patch's
/// diameter (dimensionless).
inline constexpr double kHullRoundoff = 1e-12;

/// The indices (ascending) of the contacts to keep: of every planar patch (see
/// the file comment) the vertices of its convex hull in the patch plane; every
/// contact that shares no patch is kept. Works in 2-D (collinear patches) and
/// 3-D. Deterministic: depends only on the contacts and their order.
/// @throws std::invalid_argument on a negative or NaN tolerance.
std::vector<int> HullContactSubset(const std::vector<Contact>& contacts,
                                   const ContactReductionTolerances& tolerances = {});

}  // namespace cairn

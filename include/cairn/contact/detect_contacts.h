#pragma once
/// @file
/// Contact detection between the parts of one configuration (2-D).
///
/// Two polygons touch where a vertex of one lies on an edge of the other. Every
/// touching pair of features is found by testing each vertex of a against each
/// edge of b and each vertex of b against each edge of a:
///  - a vertex v touches edge e when its distance to e is ≤ tol, it projects
///    onto e (within tol of its extent), v is a convex vertex of its polygon,
///    and both edges at v leave v on the outer side of e (within the angle
///    tolerance): the polygon's material at v lies outside e, so the contact
///    can push;
///  - two edges that touch along a segment (anti-parallel within tolerance,
///    overlapping extents) are found as the two ends of their overlap, each of
///    which is a vertex of one edge lying on the other: so an edge–edge contact
///    gives its two end points, with the edge's normal, as Baraff's and the
///    paper's models want;
///  - duplicates (the same point with the same normal, e.g. where two vertices
///    coincide) are merged.
/// A vertex touching a vertex gives one contact per edge it lies on
/// (conservative: both normals are kept).
/// Contacts between two fixed parts, and with absent parts, are not made.
/// Fixtures become contacts with the fixed world (frictionless).

#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/geometry/assembly.h"

namespace cairn {

/// Statistics of one detection pass.
struct ContactStats {
  int pairs_tested = 0;    ///< part pairs whose bounding boxes overlapped
  int pairs_touching = 0;  ///< part pairs with at least one contact
};

/// All contacts of `config`, sorted by (part_a, part_b, feature): deterministic.
/// `tol` is the contact distance tolerance (length), `angle_tol` the angle
/// tolerance (rad).
std::vector<Contact> DetectContacts(const Assembly& assembly, const Configuration& config,
                                    double tol, double angle_tol, ContactStats* stats = nullptr);

/// Contacts between the polygons of parts i and j (both present, not both
/// fixed), appended to `out`. Part i is `a`, part j is `b`.
void DetectPairContacts(const Polygon& poly_i, const Polygon& poly_j, int i, int j, double mu,
                        double tol, double angle_tol, std::vector<Contact>& out);

}  // namespace cairn

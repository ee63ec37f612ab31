#pragma once
/// @file
/// Contacts between two polyhedra in 3-D: the geometric kernel,
/// for two validated Polyhedron placed by rigid poses.
///
/// Convention as in 2-D (docs/notation.md): the normal n_W points from b into
/// a. Touches are found within `length_tol` (length) and `angle_tol` (rad):
///
///  - face–face: a face of a and a face of b coplanar within the tolerances
///    (or a's behind b's by up to `depth_tol`) with opposing normals. Their polygons (convex or
///    not) are intersected in the plane with Boost.Geometry; every piece of the intersection is one
///    contact *patch*, and its vertices are the contact points. n_W = b's face
///    normal.
///  - vertex–face: a vertex of one part on a face of the other (inside its
///    polygon), with its part's material on the far side of the face, and
///    not already inside a face–face patch. n_W = the face's normal (signed
///    from b into a).
///  - edge–face: an edge of one part lying on a face of the other, clipped to
///    the face polygon; its two ends are the points (when not already vertex
///    or face–face points).
///  - edge–edge: two edges crossing at an interior point of both, not
///    parallel; n_W = ± e_a × e_b, signed so that it points into a's material
///    (against the sum of the outward normals of a's two faces at the edge).
///
/// Points closer than `length_tol` with the same normal are merged. These are
/// the candidates of one pair: where a corner or an edge of one touches a
/// corner or an edge of the other, the same point comes with several normals,
/// and DetectContacts applies the corner rule to them (docs/contacts.md). Every point
/// carries the id of its patch, so outputs can group the points of one face
/// contact as the paper's figures do.

#include <Eigen/Geometry>
#include <vector>

#include "cairn/geometry/polyhedron.h"

namespace cairn {

/// How a 3-D contact point arose.
enum class ContactKind3 { kFaceFace, kVertexFace, kFaceVertex, kEdgeFace, kFaceEdge, kEdgeEdge };

/// "face-face", "vertex-face", "face-vertex", "edge-face", "face-edge", "edge-edge".
const char* to_string(ContactKind3 kind);

/// One contact point between polyhedra a and b.
struct PolyhedronContactPoint {
  Vector3 p_W{0, 0, 0};  ///< world frame (length)
  Vector3 n_W{0, 0, 1};  ///< unit normal from b into a
  double gap = 0;        ///< signed distance along n_W (length; < 0: overlap within tolerance)
  ContactKind3 kind = ContactKind3::kFaceFace;
  int patch = 0;  ///< points of one face–face intersection piece share it; others have their own
  int feature_a = -1;  ///< face, vertex or edge index of a (by kind; edges: index into Edges())
  int feature_b = -1;  ///< likewise of b
};

/// The undirected edges of a polyhedron, (smaller, larger) vertex index, in a
/// deterministic order: the index space of PolyhedronContactPoint's edges.
std::vector<std::array<int, 2>> PolyhedronEdges(const Polyhedron& p);

/// The contact points between a (placed by X_WA) and b (by X_WB). A
/// feature touches a face within `length_tol` in front of it, or up to
/// `depth_tol` (length; ≤ length_tol: length_tol) behind it, where parts
/// meant to touch overlap (AssemblyDef::overlap_depth); each point of an
/// overlap deeper than `length_tol` lies midway between the two (the
/// overlap's mid-surface), the others on a's feature.
std::vector<PolyhedronContactPoint> FindPolyhedronContacts(
    const Polyhedron& a, const Eigen::Isometry3d& X_WA, const Polyhedron& b,
    const Eigen::Isometry3d& X_WB, double length_tol, double angle_tol, double depth_tol = 0);

}  // namespace cairn

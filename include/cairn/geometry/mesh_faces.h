#pragma once
/// @file
/// From a triangle mesh (a CAD export: OBJ, STL) to planar polygonal faces.
///
/// Contact between polyhedra is computed face against face: two
/// coplanar faces touching give one contact polygon. A mesh splits every face
/// into triangles, so the same touch would come out as dozens of fragments.
/// MergeCoplanarTriangles rebuilds the faces: edge-adjacent triangles whose
/// planes agree (normals within `angle_tol`, every vertex within `length_tol`
/// of the region's first plane) are grown into one region, and a region whose
/// boundary is a single closed loop becomes one polygonal face (convex or
/// not). A region with holes, a pinched boundary or a boundary that touches
/// itself in its plane (within `length_tol`) keeps its triangles as faces:
/// still planar and exact, only in more pieces.

#include <array>
#include <vector>

#include "cairn/geometry/polyhedron.h"

namespace cairn {

/// What MergeCoplanarTriangles did.
struct MeshMergeStats {
  int triangles_in = 0;        ///< triangles given (degenerate ones included)
  int degenerate_dropped = 0;  ///< triangles of zero area (below length_tol²) left out
  /// Triangles listed more than once with the same orientation (an export
  /// that wrote a face twice): the copies left out, one kept.
  int duplicates_dropped = 0;
  /// Triangles listed with both orientations (an internal wall, both of its
  /// sides written: material on both sides, so no surface): both left out.
  int internal_dropped = 0;
  int faces_out = 0;                  ///< faces of the result
  int regions_kept_as_triangles = 0;  ///< coplanar regions with holes or pinches, not merged
};

/// Merges the coplanar edge-adjacent triangles of a mesh into polygonal faces.
/// `vertices` must be welded (one index per position: shared edges are found
/// by index). The result keeps every vertex (unused ones included) and the
/// triangles' orientation. `angle_tol` in radians, `length_tol` in length.
PolyhedronDef MergeCoplanarTriangles(const std::vector<Vector3>& vertices,
                                     const std::vector<std::array<int, 3>>& triangles,
                                     double angle_tol, double length_tol,
                                     MeshMergeStats* stats = nullptr);

}  // namespace cairn

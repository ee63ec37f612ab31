#pragma once
/// @file
/// Closed polyhedra in 3-D: validation, outward orientation, exact
/// mass properties. A polyhedron is given as vertices and planar polygonal
/// faces (any vertex count, convex or not) that close a 2-manifold surface.
///
/// Validation reports the first fault with the face index and the reason, so
/// the readers can say which face of which part of which file is wrong.
/// Orientation is Cairn's job, not the user's: faces are oriented
/// consistently across shared edges and then outward (positive volume).

#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "cairn/core/types.h"

namespace cairn {

/// Vertices and faces as given (a scene's `polyhedron`, a mesh, a COMPAS
/// block). faces[f] lists vertex indices around face f, either orientation.
struct PolyhedronDef {
  std::vector<Vector3> vertices;
  std::vector<std::vector<int>> faces;
};

/// What is wrong with a PolyhedronDef.
struct PolyhedronFault {
  int face = -1;        ///< the face at fault (−1: the solid as a whole)
  std::string message;  ///< e.g. "face 3 is not planar: vertex 7 is 0.02 off its plane"
};

/// Exact mass properties of a solid of unit density (divergence theorem).
struct PolyhedronMass {
  double volume = 0;          ///< length³
  Vector3 centroid{0, 0, 0};  ///< length
  Eigen::Matrix3d inertia =
      Eigen::Matrix3d::Zero();  ///< ∫ (|r|² I − r rᵀ) dV about the centroid, length⁵
};

/// A validated polyhedron: every face planar, simple and of nonzero area;
/// every edge shared by exactly two faces in opposite directions (closed,
/// manifold, consistently oriented); faces oriented outward (their normals by
/// the right-hand rule point out of the solid); no two faces intersecting
/// except along their shared edges and vertices.
class Polyhedron {
 public:
  /// Validates and orients `def` (it may be inside out or inconsistently
  /// oriented: Cairn fixes that). `tol` (length) is the planarity and
  /// intersection tolerance. Returns the fault instead when there is one.
  static std::optional<PolyhedronFault> Check(const PolyhedronDef& def, double tol);
  /// As Check, but builds the polyhedron. @throws std::invalid_argument with
  /// the fault's message when Check finds one.
  static Polyhedron Create(const PolyhedronDef& def, double tol);
  /// Check and Create in one validation (the costly part of both, O(faces²)
  /// for a mesh): the polyhedron, or the fault Check would return.
  static std::variant<Polyhedron, PolyhedronFault> CheckAndCreate(const PolyhedronDef& def,
                                                                  double tol);

  const std::vector<Vector3>& vertices() const { return vertices_; }
  /// Faces oriented outward (counter-clockwise seen from outside).
  const std::vector<std::vector<int>>& faces() const { return faces_; }
  /// Outward unit normal of each face.
  const std::vector<Vector3>& face_normals() const { return normals_; }
  /// Triangles of each face (indices into vertices()), outward, covering the
  /// face exactly (non-convex faces included).
  const std::vector<std::vector<std::array<int, 3>>>& face_triangles() const { return triangles_; }
  /// Volume, centroid and inertia at unit density.
  const PolyhedronMass& mass() const { return mass_; }
  /// How deep the centroid lies inside the solid (length; −SignedDistance:
  /// negative when it lies outside, as a U's or an arch's may), found once
  /// for the overlap tests, which sample it.
  double centroid_depth() const { return centroid_depth_; }

 private:
  std::vector<Vector3> vertices_;
  std::vector<std::vector<int>> faces_;
  std::vector<Vector3> normals_;
  std::vector<std::vector<std::array<int, 3>>> triangles_;
  PolyhedronMass mass_;
  double centroid_depth_ = 0;
};

/// The signed distance (length) from the world point `p_W` to the surface of
/// `poly` placed by X_WB: negative inside. Inside is decided by the winding
/// number of the surface about the point (robust for non-convex solids).
double SignedDistance(const Polyhedron& poly, const Eigen::Isometry3d& X_WB, const Vector3& p_W);

/// How deep the interiors of `a` (placed by X_WA) and `b` (by X_WB)
/// overlap (length): the greatest distance from one's sample points (those
/// of FindPolyhedronOverlap) lying deeper than `tol` inside the other to the
/// other's surface; 0 when none does. `deepest`, when given, gets that point
/// (world). Exact where the overlap's deepest point is a vertex of either
/// (two blocks pressed into each other face to face); a lower bound
/// otherwise.
double PolyhedronOverlapDepth(const Polyhedron& a, const Eigen::Isometry3d& X_WA,
                              const Polyhedron& b, const Eigen::Isometry3d& X_WB, double tol,
                              Vector3* deepest = nullptr);

/// A point where the interiors of `a` (placed by X_WA) and `b` (by X_WB)
/// overlap by more than `tol` (length), or nothing when they only touch or
/// are apart. Tested: every vertex, edge midpoint, face-triangle centroid and
/// the centroid of each solid against the other (deeper than tol inside), and
/// every edge of each crossing a face of the other with both ends more than
/// tol off the face's plane and the crossing more than tol inside the face.
/// Exact for the overlaps of assembly planning (parts pushed into each other,
/// coincident parts); a sliver overlap that reaches none of those points is
/// missed (it is thinner than the parts' features).
std::optional<Vector3> FindPolyhedronOverlap(const Polyhedron& a, const Eigen::Isometry3d& X_WA,
                                             const Polyhedron& b, const Eigen::Isometry3d& X_WB,
                                             double tol);

/// A polyhedron made ready for many overlap tests at one tolerance (length):
/// its triangles and its faces in grids, its sample points, all in its own
/// frame. A swept test places one pair at hundreds of times; with both
/// prepared once, each FindPolyhedronOverlap costs only the queries. A
/// query uses the grids' scratch space: one thread at a time per object.
class PreparedSolid {
 public:
  PreparedSolid(const Polyhedron& poly, double tol);
  ~PreparedSolid();
  PreparedSolid(PreparedSolid&&) noexcept;
  PreparedSolid& operator=(PreparedSolid&&) noexcept;

  const Polyhedron& polyhedron() const { return *poly_; }
  double tol() const { return tol_; }

  struct Grids;  ///< polyhedron.cpp
  const Grids& grids() const { return *grids_; }

 private:
  const Polyhedron* poly_;
  double tol_;
  std::unique_ptr<Grids> grids_;
};

/// FindPolyhedronOverlap of two prepared solids at their common tolerance
/// (they must share it): the same tests, the same answers.
std::optional<Vector3> FindPolyhedronOverlap(const PreparedSolid& a, const Eigen::Isometry3d& X_WA,
                                             const PreparedSolid& b, const Eigen::Isometry3d& X_WB);

/// SignedDistance of a point to a prepared solid (the same number, found
/// from its grids: the triangles near p, and a ray's parity).
double SignedDistance(const PreparedSolid& b, const Eigen::Isometry3d& X_WB, const Vector3& p_W);

/// Exact mass properties of a closed, outward-oriented triangle mesh
/// (divergence theorem over the triangles; exact for any polyhedron).
PolyhedronMass ComputePolyhedronMass(const std::vector<Vector3>& vertices,
                                     const std::vector<std::array<int, 3>>& triangles);

}  // namespace cairn

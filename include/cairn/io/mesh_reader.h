#pragma once
/// @file
/// Triangle meshes (Wavefront OBJ, STL ASCII or binary, and whatever else
/// Assimp reads) as polyhedra with planar polygonal faces: the scene format's
/// `"mesh": "parts/e.obj"`.
///
/// The file is read with Assimp (Debian libassimp-dev), identical vertices are
/// welded, every mesh in the file joins one solid (one part per file), and
/// coplanar triangles are merged into planar faces (MergeCoplanarTriangles).
/// The result is not yet validated: Polyhedron::Check says whether it is a
/// closed, manifold, non-self-intersecting solid.

#include <string>

#include "cairn/geometry/mesh_faces.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// Tolerances of ReadMesh's face merging.
struct MeshReadOptions {
  /// rad: triangles whose normals differ more are not coplanar. CAD exports
  /// print coordinates to 7–9 digits, so exact planarity is not on offer.
  double angle_tol = 1e-5;
  /// length (the file's units): largest distance of a vertex from its face's
  /// plane; ≤ 0 means 1e-6 × the diagonal of the mesh's bounding box.
  double length_tol = 0;
  /// bytes: the largest mesh file read (CheckInputFile).
  std::uint64_t max_input_size = kDefaultMaxInputSize;
};

/// Reads `path` and returns its faces. @throws InputError(path, "", why) when
/// the file is not a regular file of at most `options.max_input_size` bytes
/// (CheckInputFile: a folder, a FIFO, a device, a loop of links, ...), cannot
/// be read, has no triangles, or is not a mesh.
PolyhedronDef ReadMesh(const std::string& path, const MeshReadOptions& options = {},
                       MeshMergeStats* stats = nullptr);

/// What MergeCoplanarTriangles repaired in a mesh (triangles written twice,
/// internal walls), as a note about `part` ("part 'p': mesh m.obj: 80
/// triangles written twice and 12 of internal walls left out"); empty when
/// it repaired nothing.
std::string MeshRepairNote(const std::string& part, const std::string& path,
                           const MeshMergeStats& stats);

}  // namespace cairn

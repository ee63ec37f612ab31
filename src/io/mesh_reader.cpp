#include "cairn/io/mesh_reader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <map>

#include "cairn/core/error.h"
#include "cairn/core/tolerances.h"
#include "cairn/io/input_file.h"

namespace cairn {

PolyhedronDef ReadMesh(const std::string& path, const MeshReadOptions& options,
                       MeshMergeStats* stats) {
  // Assimp opens the file itself: checked first (a FIFO would block it, a
  // device would be read without end).
  CheckInputFile(path, options.max_input_size, "mesh file");
  Assimp::Importer importer;
  // Triangulate polygons, weld identical vertices (STL stores every triangle's
  // corners apart); keep the file's units and frame (no scaling, no axis
  // conversion).
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices);
  if (scene == nullptr)
    throw InputError(path, "", std::string("cannot read the mesh: ") + importer.GetErrorString());
  std::vector<Vector3> vertices;
  std::vector<std::array<int, 3>> triangles;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const int base = static_cast<int>(vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      triangles.push_back({base + static_cast<int>(face.mIndices[0]),
                           base + static_cast<int>(face.mIndices[1]),
                           base + static_cast<int>(face.mIndices[2])});
    }
  }
  if (triangles.empty()) throw InputError(path, "", "the mesh has no triangles");
  // Meshes of one file share no vertex indices: weld equal positions across
  // them too, so their shared edges are found.
  std::map<std::array<double, 3>, int> index_of;
  std::vector<int> weld(vertices.size());
  std::vector<Vector3> welded;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const std::array<double, 3> key{vertices[i].x(), vertices[i].y(), vertices[i].z()};
    const auto [it, added] = index_of.emplace(key, static_cast<int>(welded.size()));
    if (added) welded.push_back(vertices[i]);
    weld[i] = it->second;
  }
  for (auto& t : triangles)
    for (int& v : t) v = weld[v];
  Vector3 lo = welded[0], hi = welded[0];
  for (const Vector3& v : welded) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double length_tol = options.length_tol > 0
                                ? options.length_tol
                                : ToleranceFactors{}.length * std::max((hi - lo).norm(), 1e-300);
  return MergeCoplanarTriangles(welded, triangles, options.angle_tol, length_tol, stats);
}

std::string MeshRepairNote(const std::string& part, const std::string& path,
                           const MeshMergeStats& stats) {
  if (stats.duplicates_dropped == 0 && stats.internal_dropped == 0) return "";
  std::string what;
  if (stats.duplicates_dropped > 0)
    what = std::to_string(stats.duplicates_dropped) + " triangle" +
           (stats.duplicates_dropped == 1 ? "" : "s") + " written twice";
  if (stats.internal_dropped > 0)
    what += (what.empty() ? "" : " and ") + std::to_string(stats.internal_dropped) +
            " triangles of internal walls (both sides written)";
  return "part '" + EscapedName(part) + "': mesh " + path + ": " + what + " left out";
}

}  // namespace cairn

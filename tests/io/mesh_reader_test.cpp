// Meshes to planar faces: MergeCoplanarTriangles on built meshes with known
// faces, ReadMesh on OBJ and STL files written here, and the ASAP beam
// assembly's CAD meshes when ../shared is present.
#include "cairn/io/mesh_reader.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>  // IWYU pragma: keep
#include <filesystem>
#include <fstream>
#include <set>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn {
namespace {

// A unit cube as 12 triangles, outward.
std::vector<Vector3> CubeVertices() {
  return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
}
std::vector<std::array<int, 3>> CubeTriangles() {
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                           {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<std::array<int, 3>> t;
  for (const auto& q : quads) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return t;
}

// The largest distance of a face's vertices from the plane of its first three.
double Planarity(const PolyhedronDef& def, const std::vector<int>& face) {
  const Vector3 a = def.vertices[face[0]];
  Vector3 n = Vector3::Zero();
  for (size_t i = 0; i < face.size(); ++i)  // Newell's normal
    n += def.vertices[face[i]].cross(def.vertices[face[(i + 1) % face.size()]]);
  n.normalize();
  double worst = 0;
  for (int v : face) worst = std::max(worst, std::abs(n.dot(def.vertices[v] - a)));
  return worst;
}

TEST(MergeCoplanarTriangles, ATriangulatedCubeHasSixSquareFaces) {
  MeshMergeStats st;
  const PolyhedronDef def =
      MergeCoplanarTriangles(CubeVertices(), CubeTriangles(), 1e-9, 1e-9, &st);
  ASSERT_EQ(def.faces.size(), 6u);
  EXPECT_EQ(st.triangles_in, 12);
  EXPECT_EQ(st.faces_out, 6);
  for (const auto& f : def.faces) {
    EXPECT_EQ(f.size(), 4u);
    EXPECT_LE(Planarity(def, f), 1e-12);
  }
  // Orientation is kept: the bottom face (z = 0) still runs 0 → 3 → 2 → 1
  // (clockwise from above, i.e. outward), from some starting vertex.
  for (const auto& f : def.faces) {
    if (std::set<int>(f.begin(), f.end()) != std::set<int>{0, 1, 2, 3}) continue;
    const auto at = [&](int v) { return std::find(f.begin(), f.end(), v) - f.begin(); };
    EXPECT_EQ((at(3) - at(0) + 4) % 4, 1);
  }
}

// A face split into a fan around an interior vertex merges into its outline;
// a face with a hole (a square frame) cannot be one simple polygon and keeps
// its triangles.
TEST(MergeCoplanarTriangles, FansMergeFramesWithHolesStayTriangles) {
  std::vector<Vector3> v = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {1, 1, 0}};
  const PolyhedronDef fan =
      MergeCoplanarTriangles(v, {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}, 1e-9, 1e-9);
  ASSERT_EQ(fan.faces.size(), 1u);
  EXPECT_EQ(std::set<int>(fan.faces[0].begin(), fan.faces[0].end()), (std::set<int>{0, 1, 2, 3}));

  // Frame: outer square 0–3 (side 3), inner square 4–7 (side 1), 8 triangles.
  v = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}, {1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  const std::vector<std::array<int, 3>> frame = {{0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                                 {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  MeshMergeStats st;
  const PolyhedronDef kept = MergeCoplanarTriangles(v, frame, 1e-9, 1e-9, &st);
  EXPECT_EQ(kept.faces.size(), 8u);
  EXPECT_EQ(st.regions_kept_as_triangles, 1);
}

// Two triangles at a small angle are merged only within angle_tol.
TEST(MergeCoplanarTriangles, AFoldBeyondTheAngleToleranceIsKept) {
  const double lift = 1e-3;  // the fold's angle is about 1e-3 rad
  const std::vector<Vector3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, lift}};
  const std::vector<std::array<int, 3>> t = {{0, 1, 2}, {1, 3, 2}};
  EXPECT_EQ(MergeCoplanarTriangles(v, t, 1e-5, 1e-9).faces.size(), 2u);
  EXPECT_EQ(MergeCoplanarTriangles(v, t, 1e-2, 1e-2).faces.size(), 1u);
}

std::string Write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(ReadMesh, ObjAndAsciiStlCubesGiveSixFacesOnEightVertices) {
  std::string obj;
  for (const Vector3& p : CubeVertices())
    obj += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
           std::to_string(p.z()) + "\n";
  for (const auto& t : CubeTriangles())
    obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
           std::to_string(t[2] + 1) + "\n";
  std::string stl = "solid cube\n";
  const auto cv = CubeVertices();
  for (const auto& t : CubeTriangles()) {
    const Vector3 n = (cv[t[1]] - cv[t[0]]).cross(cv[t[2]] - cv[t[0]]).normalized();
    stl += "facet normal " + std::to_string(n.x()) + " " + std::to_string(n.y()) + " " +
           std::to_string(n.z()) + "\n outer loop\n";
    for (int k = 0; k < 3; ++k)
      stl += "  vertex " + std::to_string(cv[t[k]].x()) + " " + std::to_string(cv[t[k]].y()) + " " +
             std::to_string(cv[t[k]].z()) + "\n";
    stl += " endloop\nendfacet\n";
  }
  stl += "endsolid cube\n";
  for (const std::string& path : {Write("cairn_cube.obj", obj), Write("cairn_cube.stl", stl)}) {
    SCOPED_TRACE(path);
    const PolyhedronDef def = ReadMesh(path);
    EXPECT_EQ(def.vertices.size(), 8u);
    ASSERT_EQ(def.faces.size(), 6u);
    for (const auto& f : def.faces) EXPECT_EQ(f.size(), 4u);
  }
}

TEST(ReadMesh, MissingAndMalformedFilesAreInputErrors) {
  EXPECT_THROW(ReadMesh("/nonexistent/cairn_part.obj"), InputError);
  EXPECT_THROW(ReadMesh(Write("cairn_garbage.obj", "this is not a mesh\n")), InputError);
  try {
    ReadMesh("/nonexistent/cairn_part.obj");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cairn_part.obj"), std::string::npos) << e.what();
  }
}

// ASAP's beams are CAD meshes of 4904–24606 triangles with fillets: their
// flat faces merge into a few large polygons, every face planar.
TEST(ReadMesh, AsapBeamMeshesMergeIntoPlanarFaces) {
  const std::string shared = testing::SharedDir();
  if (shared.empty()) GTEST_SKIP() << "shared/datasets not found: skipping the ASAP meshes";
  for (const char* part : {"0", "2", "6"}) {
    SCOPED_TRACE(part);
    MeshMergeStats st;
    const PolyhedronDef def =
        ReadMesh(shared + "/datasets/asap_beam_assembly/" + std::string(part) + ".obj", {}, &st);
    EXPECT_GT(st.triangles_in, 4000);
    EXPECT_LT(st.faces_out, st.triangles_in) << "no triangles were merged";
    Vector3 lo = def.vertices[0], hi = def.vertices[0];
    for (const Vector3& v : def.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double tol = 1e-6 * (hi - lo).norm();
    for (const auto& f : def.faces) ASSERT_LE(Planarity(def, f), 2 * tol);
  }
}

}  // namespace
}  // namespace cairn

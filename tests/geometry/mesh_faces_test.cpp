// mesh_faces.h: a triangle mesh's coplanar triangles merged back into the
// solid's planar faces, the solid itself unchanged (same volume, exactly the
// faces a modeller would draw).
#include "cairn/geometry/mesh_faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

namespace cairn {
namespace {

using Triangles = std::vector<std::array<int, 3>>;

// A prism of height 1 over a counter-clockwise base polygon `base` (z = 0),
// each face fanned into triangles, outward.
void Prism(const std::vector<Vector3>& base, std::vector<Vector3>* v, Triangles* t) {
  const int n = static_cast<int>(base.size());
  for (const Vector3& p : base) v->push_back(p);
  for (const Vector3& p : base) v->push_back(p + Vector3(0, 0, 1));
  for (int i = 1; i + 1 < n; ++i) {  // fans (the bases are star-shaped from vertex 0)
    t->push_back({0, i + 1, i});     // bottom, facing −z
    t->push_back({n, n + i, n + i + 1});
  }
  for (int i = 0; i < n; ++i) {  // each side as two triangles
    const int j = (i + 1) % n;
    t->push_back({i, j, n + j});
    t->push_back({i, n + j, n + i});
  }
}

TEST(MergeCoplanarTriangles, ACubesTwelveTrianglesBecomeSixSquares) {
  std::vector<Vector3> v;
  Triangles t;
  Prism({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, &v, &t);
  MeshMergeStats stats;
  const PolyhedronDef def = MergeCoplanarTriangles(v, t, 1e-6, 1e-9, &stats);
  EXPECT_EQ(stats.triangles_in, 12);
  EXPECT_EQ(stats.faces_out, 6);
  ASSERT_EQ(def.faces.size(), 6u);
  for (const auto& f : def.faces) EXPECT_EQ(f.size(), 4u);
  EXPECT_NEAR(Polyhedron::Create(def, 1e-9).mass().volume, 1.0, 1e-12);
}

// A non-convex (L-shaped) cap merges into one six-sided face; the sides stay
// separate faces (they meet at angles).
TEST(MergeCoplanarTriangles, ANonConvexFaceBecomesOnePolygon) {
  std::vector<Vector3> v;
  Triangles t;
  Prism({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, &v, &t);
  const PolyhedronDef def = MergeCoplanarTriangles(v, t, 1e-6, 1e-9);
  ASSERT_EQ(def.faces.size(), 8u);  // two L caps and six sides
  const auto caps = std::count_if(def.faces.begin(), def.faces.end(),
                                  [](const std::vector<int>& f) { return f.size() == 6; });
  EXPECT_EQ(caps, 2);
  EXPECT_NEAR(Polyhedron::Create(def, 1e-9).mass().volume, 3.0, 1e-12);
}

TEST(MergeCoplanarTriangles, DegenerateTrianglesAreDroppedAndCounted) {
  std::vector<Vector3> v;
  Triangles t;
  Prism({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, &v, &t);
  t.push_back({0, 1, 1});  // zero area
  MeshMergeStats stats;
  const PolyhedronDef def = MergeCoplanarTriangles(v, t, 1e-6, 1e-9, &stats);
  EXPECT_EQ(stats.degenerate_dropped, 1);
  EXPECT_EQ(def.faces.size(), 6u);
}

}  // namespace
}  // namespace cairn

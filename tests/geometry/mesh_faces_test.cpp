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

// Two unit cubes side by side exported as one mesh that kept their shared
// face x = 1 (both sides: an internal wall), with one outer triangle written
// twice: the wall's four triangles and the copy are left out, and what is
// left is the 2 × 1 × 1 box, a valid solid of volume 2 (with them its edges
// on x = 1 bound four triangles each, and Polyhedron refuses it).
TEST(MergeCoplanarTriangles, TrianglesWrittenTwiceAndInternalWallsAreLeftOut) {
  std::vector<Vector3> v;
  for (int x = 0; x <= 2; ++x)
    for (int k = 0; k < 4; ++k) v.emplace_back(x, k & 1, (k >> 1) & 1);
  // Vertex (x, y, z) is 4x + y + 2z.
  const auto at = [](int x, int y, int z) { return 4 * x + y + 2 * z; };
  Triangles t;
  const auto quad = [&](int a, int b, int c, int d) {  // counter-clockwise seen from outside
    t.push_back({a, b, c});
    t.push_back({a, c, d});
  };
  quad(at(0, 0, 0), at(0, 0, 1), at(0, 1, 1), at(0, 1, 0));  // x = 0, facing −x
  quad(at(2, 0, 0), at(2, 1, 0), at(2, 1, 1), at(2, 0, 1));  // x = 2, facing +x
  for (int x = 0; x < 2; ++x) {
    quad(at(x, 0, 0), at(x + 1, 0, 0), at(x + 1, 0, 1), at(x, 0, 1));  // y = 0
    quad(at(x, 1, 0), at(x, 1, 1), at(x + 1, 1, 1), at(x + 1, 1, 0));  // y = 1
    quad(at(x, 0, 0), at(x, 1, 0), at(x + 1, 1, 0), at(x + 1, 0, 0));  // z = 0
    quad(at(x, 0, 1), at(x + 1, 0, 1), at(x + 1, 1, 1), at(x, 1, 1));  // z = 1
  }
  const Triangles outer = t;
  quad(at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1));  // the wall, facing +x
  quad(at(1, 0, 0), at(1, 0, 1), at(1, 1, 1), at(1, 1, 0));  // and −x
  t.push_back(t[5]);                                         // an outer triangle again
  MeshMergeStats stats;
  const PolyhedronDef def = MergeCoplanarTriangles(v, t, 1e-6, 1e-9, &stats);
  EXPECT_EQ(stats.triangles_in, static_cast<int>(outer.size()) + 5);
  EXPECT_EQ(stats.internal_dropped, 4);
  EXPECT_EQ(stats.duplicates_dropped, 1);
  EXPECT_EQ(stats.faces_out, 6);
  EXPECT_NEAR(Polyhedron::Create(def, 1e-9).mass().volume, 2.0, 1e-12);
  // The same mesh without them gives the same faces.
  MeshMergeStats clean;
  EXPECT_EQ(MergeCoplanarTriangles(v, outer, 1e-6, 1e-9, &clean).faces, def.faces);
  EXPECT_EQ(clean.internal_dropped + clean.duplicates_dropped, 0);
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

#include "cairn/geometry/polyhedron.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>  // IWYU pragma: keep
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cairn {
namespace {

constexpr double kTol = 1e-6;  // planarity / intersection tolerance (length)
constexpr double kPolyhedronEps = 1e-12;

using Faces = std::vector<std::vector<int>>;

// The box [x0, x0 + a] × [y0, y0 + b] × [z0, z0 + c]. Vertex i + 2j + 4k is the
// corner (x0 + i a, y0 + j b, z0 + k c). Faces outward, in the order
// z = low, z = high, y = low, y = high, x = low, x = high.
PolyhedronDef Box(double a, double b, double c, const Vector3& origin = Vector3::Zero()) {
  PolyhedronDef def;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) def.vertices.push_back(origin + Vector3(i * a, j * b, k * c));
    }
  }
  def.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return def;
}

PolyhedronDef UnitCube() { return Box(1, 1, 1); }

// The unit cube with each face split into two triangles along a diagonal.
PolyhedronDef TriangulatedCube() {
  PolyhedronDef def = UnitCube();
  Faces tris;
  for (const auto& f : def.faces) {
    tris.push_back({f[0], f[1], f[2]});
    tris.push_back({f[0], f[2], f[3]});
  }
  def.faces = tris;
  return def;
}

// The prism of height h over the L [0, 3] × [0, 1] ∪ [0, 1] × [1, 3]: bottom
// vertices 0..5, top 6..11; faces: bottom, top, then the six sides.
PolyhedronDef LPrism(double h) {
  const std::vector<Vector2> l = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  PolyhedronDef def;
  for (double z : {0.0, h}) {
    for (const Vector2& p : l) def.vertices.push_back(Vector3(p.x(), p.y(), z));
  }
  def.faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    def.faces.push_back({i, j, j + 6, i + 6});
  }
  return def;
}

// Mass properties of the box, from the closed forms.
PolyhedronMass BoxMass(double a, double b, double c, const Vector3& origin) {
  PolyhedronMass m;
  m.volume = a * b * c;
  m.centroid = origin + Vector3(a, b, c) / 2;
  m.inertia = Eigen::Vector3d(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal();
  m.inertia *= m.volume / 12;
  return m;
}

// The union of two disjoint solids, by the parallel-axis theorem.
PolyhedronMass Combine(const PolyhedronMass& p, const PolyhedronMass& q) {
  PolyhedronMass m;
  m.volume = p.volume + q.volume;
  m.centroid = (p.volume * p.centroid + q.volume * q.centroid) / m.volume;
  for (const PolyhedronMass* part : {&p, &q}) {
    const Vector3 d = part->centroid - m.centroid;
    m.inertia += part->inertia +
                 part->volume * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return m;
}

void ExpectMassNear(const PolyhedronMass& actual, const PolyhedronMass& expected, double tol) {
  EXPECT_NEAR(actual.volume, expected.volume, tol);
  EXPECT_LE((actual.centroid - expected.centroid).norm(), tol)
      << actual.centroid.transpose() << " vs " << expected.centroid.transpose();
  EXPECT_LE((actual.inertia - expected.inertia).norm(), tol) << actual.inertia << "\nvs\n"
                                                             << expected.inertia;
}

// Every face's normal points away from the solid's centroid (for convex
// solids), and every face's triangles run the same way as its normal and
// cover its area.
void ExpectOutwardConvex(const Polyhedron& p) {
  const Vector3 c = p.mass().centroid;
  for (size_t f = 0; f < p.faces().size(); ++f) {
    Vector3 center = Vector3::Zero();
    for (int v : p.faces()[f]) center += p.vertices()[v];
    center /= static_cast<double>(p.faces()[f].size());
    EXPECT_GT(p.face_normals()[f].dot(center - c), 0) << "face " << f;
  }
}

void ExpectTrianglesMatchNormals(const Polyhedron& p) {
  ASSERT_EQ(p.face_triangles().size(), p.faces().size());
  for (size_t f = 0; f < p.faces().size(); ++f) {
    EXPECT_EQ(p.face_triangles()[f].size(), p.faces()[f].size() - 2) << "face " << f;
    for (const auto& t : p.face_triangles()[f]) {
      const auto& x = p.vertices();
      const Vector3 n = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
      EXPECT_GT(n.dot(p.face_normals()[f]), 0) << "face " << f;
    }
  }
}

std::vector<std::array<int, 3>> AllTriangles(const Polyhedron& p) {
  std::vector<std::array<int, 3>> all;
  for (const auto& ts : p.face_triangles()) all.insert(all.end(), ts.begin(), ts.end());
  return all;
}

// Check's fault, which the test requires to exist.
PolyhedronFault FaultOf(const PolyhedronDef& def, double tol = kTol) {
  const std::optional<PolyhedronFault> fault = Polyhedron::Check(def, tol);
  if (!fault) {
    ADD_FAILURE() << "no fault found";
    return {};
  }
  return *fault;
}

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// ---------------------------------------------------------------------------
// Mass properties.

TEST(ComputePolyhedronMass, UnitCube) {
  const Polyhedron p = Polyhedron::Create(UnitCube(), kTol);
  const PolyhedronMass& m = p.mass();
  EXPECT_NEAR(m.volume, 1, kPolyhedronEps);
  EXPECT_LE((m.centroid - Vector3(0.5, 0.5, 0.5)).norm(), kPolyhedronEps);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(m.inertia(i, j), i == j ? 1.0 / 6 : 0.0, kPolyhedronEps);
  }
  // The free function on the triangles agrees with the polyhedron's own.
  ExpectMassNear(ComputePolyhedronMass(p.vertices(), AllTriangles(p)), m, kPolyhedronEps);
}

TEST(ComputePolyhedronMass, BoxMatchesClosedForm) {
  const double a = 2, b = 3, c = 0.5;
  const Vector3 origin(-1, 4, 2);
  const Polyhedron p = Polyhedron::Create(Box(a, b, c, origin), kTol);
  ExpectMassNear(p.mass(), BoxMass(a, b, c, origin), 1e-12);
  EXPECT_NEAR(p.mass().inertia(0, 0), a * b * c * (b * b + c * c) / 12, 1e-12);
}

TEST(ComputePolyhedronMass, RightTetrahedronMatchesClosedForm) {
  // Corners 0, a x̂, b ŷ, c ẑ: V = abc/6, centroid (a, b, c)/4; about the
  // centroid ∫x² dV = a³bc/160 and ∫xy dV = −a²b²c/480 (and cyclically).
  const double a = 2, b = 3, c = 5;
  PolyhedronDef def;
  def.vertices = {{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {0, 0, c}};
  def.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const PolyhedronMass m = Polyhedron::Create(def, kTol).mass();
  const double v = a * b * c / 6;
  EXPECT_NEAR(m.volume, v, 1e-12);
  EXPECT_LE((m.centroid - Vector3(a, b, c) / 4).norm(), 1e-12);
  const double xx = a * a * a * b * c / 160, yy = a * b * b * b * c / 160,
               zz = a * b * c * c * c / 160;
  EXPECT_NEAR(m.inertia(0, 0), yy + zz, 1e-12);
  EXPECT_NEAR(m.inertia(1, 1), xx + zz, 1e-12);
  EXPECT_NEAR(m.inertia(2, 2), xx + yy, 1e-12);
  EXPECT_NEAR(m.inertia(0, 1), a * a * b * b * c / 480, 1e-12);
  EXPECT_NEAR(m.inertia(0, 2), a * a * b * c * c / 480, 1e-12);
  EXPECT_NEAR(m.inertia(1, 2), a * b * b * c * c / 480, 1e-12);
  EXPECT_LE((m.inertia - m.inertia.transpose()).norm(), 1e-15);
}

TEST(ComputePolyhedronMass, NonConvexLPrismIsTheSumOfItsBoxes) {
  const double h = 2;
  const Polyhedron p = Polyhedron::Create(LPrism(h), kTol);
  const PolyhedronMass expected =
      Combine(BoxMass(3, 1, h, Vector3(0, 0, 0)), BoxMass(1, 2, h, Vector3(0, 1, 0)));
  ExpectMassNear(p.mass(), expected, 1e-12);
  EXPECT_NEAR(p.mass().volume, 5 * h, 1e-12);
  // The L's product of inertia is nonzero: the test is not trivially diagonal.
  EXPECT_GT(std::abs(p.mass().inertia(0, 1)), 0.1);
  ExpectTrianglesMatchNormals(p);
}

TEST(ComputePolyhedronMass, TranslationMovesCentroidKeepsInertia) {
  const Vector3 shift(1e4, -2e4, 5e3);
  PolyhedronDef moved = LPrism(2);
  for (Vector3& x : moved.vertices) x += shift;
  const PolyhedronMass m0 = Polyhedron::Create(LPrism(2), kTol).mass();
  const PolyhedronMass m1 = Polyhedron::Create(moved, kTol).mass();
  EXPECT_NEAR(m1.volume, m0.volume, 1e-9);
  EXPECT_LE((m1.centroid - (m0.centroid + shift)).norm(), 1e-9);
  EXPECT_LE((m1.inertia - m0.inertia).norm(), 1e-8);
}

TEST(ComputePolyhedronMass, RotationGivesRotatedInertia) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Vector3(1, 2, -0.5).normalized()).toRotationMatrix();
  PolyhedronDef turned = LPrism(2);
  for (Vector3& x : turned.vertices) x = r * x;
  const PolyhedronMass m0 = Polyhedron::Create(LPrism(2), kTol).mass();
  const PolyhedronMass m1 = Polyhedron::Create(turned, kTol).mass();
  EXPECT_NEAR(m1.volume, m0.volume, 1e-12);
  EXPECT_LE((m1.centroid - r * m0.centroid).norm(), 1e-12);
  EXPECT_LE((m1.inertia - r * m0.inertia * r.transpose()).norm(), 1e-11);
}

// ---------------------------------------------------------------------------
// Orientation.

TEST(PolyhedronOrientation, OutwardInputIsKept) {
  const PolyhedronDef def = UnitCube();
  const Polyhedron p = Polyhedron::Create(def, kTol);
  EXPECT_EQ(p.faces(), def.faces);
  ExpectOutwardConvex(p);
  ExpectTrianglesMatchNormals(p);
  EXPECT_LE((p.face_normals()[0] - Vector3(0, 0, -1)).norm(), kPolyhedronEps);
  EXPECT_LE((p.face_normals()[5] - Vector3(1, 0, 0)).norm(), kPolyhedronEps);
}

TEST(PolyhedronOrientation, InsideOutInputIsTurnedOutward) {
  PolyhedronDef def = LPrism(2);
  const Polyhedron reference = Polyhedron::Create(def, kTol);
  for (auto& f : def.faces) std::reverse(f.begin(), f.end());
  const Polyhedron p = Polyhedron::Create(def, kTol);
  ExpectMassNear(p.mass(), reference.mass(), 1e-12);
  ASSERT_EQ(p.face_normals().size(), reference.face_normals().size());
  for (size_t f = 0; f < p.face_normals().size(); ++f) {
    EXPECT_LE((p.face_normals()[f] - reference.face_normals()[f]).norm(), kPolyhedronEps) << f;
  }
  ExpectTrianglesMatchNormals(p);
}

TEST(PolyhedronOrientation, InconsistentFacesAreFlipped) {
  for (int seed_face : {0, 3}) {
    PolyhedronDef def = UnitCube();
    std::reverse(def.faces[seed_face].begin(), def.faces[seed_face].end());
    std::reverse(def.faces[4].begin(), def.faces[4].end());
    const Polyhedron p = Polyhedron::Create(def, kTol);
    ExpectMassNear(p.mass(), BoxMass(1, 1, 1, Vector3::Zero()), kPolyhedronEps);
    ExpectOutwardConvex(p);
    ExpectTrianglesMatchNormals(p);
  }
}

TEST(PolyhedronOrientation, StraightAngleVerticesAreNotIntersections) {
  // Vertex 8 splits the edge (4, 5) of the cube: the top and front faces have
  // a straight angle there. Faces meeting at edges and vertices are fine.
  PolyhedronDef def = UnitCube();
  def.vertices.push_back({0.5, 0, 1});
  def.faces[1] = {4, 8, 5, 7, 6};
  def.faces[2] = {0, 1, 5, 8, 4};
  const std::optional<PolyhedronFault> fault = Polyhedron::Check(def, kTol);
  EXPECT_FALSE(fault) << fault->message;
  const Polyhedron p = Polyhedron::Create(def, kTol);
  ExpectMassNear(p.mass(), BoxMass(1, 1, 1, Vector3::Zero()), kPolyhedronEps);
  ExpectTrianglesMatchNormals(p);
}

TEST(PolyhedronOrientation, TriangulatedCubeIsValid) {
  const Polyhedron p = Polyhedron::Create(TriangulatedCube(), kTol);
  ExpectMassNear(p.mass(), BoxMass(1, 1, 1, Vector3::Zero()), kPolyhedronEps);
}

// ---------------------------------------------------------------------------
// Faults.

TEST(PolyhedronFaults, FaceWithTooFewVertices) {
  PolyhedronDef def = UnitCube();
  def.faces[3] = {2, 6};
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_EQ(fault.face, 3);
  EXPECT_TRUE(Contains(fault.message, "at least 3")) << fault.message;
}

TEST(PolyhedronFaults, VertexIndexOutOfRange) {
  PolyhedronDef def = UnitCube();
  def.faces[2][1] = 8;
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_EQ(fault.face, 2);
  EXPECT_TRUE(Contains(fault.message, "vertex index 8 is out of range")) << fault.message;
  def.faces[2][1] = -1;
  EXPECT_EQ(FaultOf(def).face, 2);
}

TEST(PolyhedronFaults, RepeatedVertex) {
  PolyhedronDef def = UnitCube();
  def.faces[4] = {0, 4, 6, 4, 2};
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_EQ(fault.face, 4);
  EXPECT_TRUE(Contains(fault.message, "vertex 4 twice")) << fault.message;
}

TEST(PolyhedronFaults, DegenerateFace) {
  PolyhedronDef def = UnitCube();
  def.vertices.push_back({2, 0, 0});  // 8: on the line through 0 and 1
  def.faces[5] = {0, 1, 8};
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_EQ(fault.face, 5);
  EXPECT_TRUE(Contains(fault.message, "degenerate")) << fault.message;
}

TEST(PolyhedronFaults, NonPlanarFace) {
  PolyhedronDef def = UnitCube();
  def.vertices[7].z() += 0.01;  // only the top face (1) leaves its plane
  const PolyhedronFault fault = FaultOf(def, 1e-6);
  EXPECT_EQ(fault.face, 1);
  EXPECT_TRUE(Contains(fault.message, "not planar")) << fault.message;
  EXPECT_TRUE(Contains(fault.message, "vertex")) << fault.message;
  // With a looser tolerance the same solid passes.
  EXPECT_FALSE(Polyhedron::Check(def, 0.01));
}

TEST(PolyhedronFaults, BowTieFace) {
  PolyhedronDef def = UnitCube();
  // A bow-tie with unequal lobes (nonzero area): edges (9, 10) and (11, 8)
  // cross at (2/3, 2/3, 1).
  def.vertices.push_back({0, 0, 1});  // 8
  def.vertices.push_back({2, 0, 1});  // 9
  def.vertices.push_back({0, 1, 1});  // 10
  def.vertices.push_back({3, 3, 1});  // 11
  def.faces[1] = {8, 9, 10, 11};
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_EQ(fault.face, 1);
  EXPECT_TRUE(Contains(fault.message, "self-intersecting")) << fault.message;
  EXPECT_TRUE(Contains(fault.message, "(9, 10)")) << fault.message;
  EXPECT_TRUE(Contains(fault.message, "(11, 8)")) << fault.message;
}

TEST(PolyhedronFaults, OpenSurface) {
  PolyhedronDef def = UnitCube();
  def.faces.pop_back();  // the face x = 1: {1, 3, 7, 5}
  const PolyhedronFault fault = FaultOf(def);
  // Face 0 {0, 2, 3, 1} is the first to border the hole, along (3, 1).
  EXPECT_EQ(fault.face, 0);
  EXPECT_TRUE(Contains(fault.message, "open")) << fault.message;
  EXPECT_TRUE(Contains(fault.message, "edge (3, 1)")) << fault.message;
}

TEST(PolyhedronFaults, NonManifoldEdge) {
  // Two unit cubes sharing only the edge x = y = 1 (vertices 3 and 7).
  PolyhedronDef def = UnitCube();
  const PolyhedronDef b = Box(1, 1, 1, Vector3(1, 1, 0));
  std::vector<int> map(8);
  for (int v = 0; v < 8; ++v) {
    if (v == 0 || v == 4) {
      map[v] = v == 0 ? 3 : 7;
    } else {
      map[v] = static_cast<int>(def.vertices.size());
      def.vertices.push_back(b.vertices[v]);
    }
  }
  for (const auto& f : b.faces) {
    std::vector<int> g;
    for (int v : f) g.push_back(map[v]);
    def.faces.push_back(g);
  }
  const PolyhedronFault fault = FaultOf(def);
  // Faces 3 and 5 of the first cube, 8 and 10 of the second use the edge;
  // the third of them is at fault.
  EXPECT_EQ(fault.face, 8);
  EXPECT_TRUE(Contains(fault.message, "non-manifold")) << fault.message;
  EXPECT_TRUE(Contains(fault.message, "4 faces (3, 5, 8, 10)")) << fault.message;
}

TEST(PolyhedronFaults, NonOrientable) {
  // The 6-vertex real projective plane (every edge in exactly two triangles,
  // no consistent orientation), its vertices in general position.
  PolyhedronDef def;
  def.vertices = {{0, 0, 0},     {1, 0, 0.1},     {0.3, 1, 0.2},
                  {0.1, 0.4, 1}, {0.7, 0.6, 0.8}, {0.2, 0.9, 0.5}};
  def.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
               {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}};
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_GE(fault.face, 0);
  EXPECT_LT(fault.face, 10);
  EXPECT_TRUE(Contains(fault.message, "not orientable")) << fault.message;
  EXPECT_TRUE(Contains(fault.message, "face " + std::to_string(fault.face))) << fault.message;
}

TEST(PolyhedronFaults, TwoShells) {
  PolyhedronDef def = UnitCube();
  const PolyhedronDef b = Box(1, 1, 1, Vector3(3, 0, 0));
  for (const Vector3& x : b.vertices) def.vertices.push_back(x);
  for (auto f : b.faces) {
    for (int& v : f) v += 8;
    def.faces.push_back(f);
  }
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_EQ(fault.face, 6);
  EXPECT_TRUE(Contains(fault.message, "2 separate shells")) << fault.message;
}

TEST(PolyhedronFaults, ZeroVolume) {
  // A "tetrahedron" with its four corners in one plane.
  PolyhedronDef def;
  def.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  def.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_EQ(fault.face, -1);
  EXPECT_TRUE(Contains(fault.message, "zero volume")) << fault.message;
}

TEST(PolyhedronFaults, TooFewFacesAndNonFiniteVertex) {
  PolyhedronDef def = UnitCube();
  def.faces.resize(3);
  EXPECT_TRUE(Contains(FaultOf(def).message, "at least 4 faces"));
  def = UnitCube();
  def.vertices[2].y() = std::nan("");
  EXPECT_TRUE(Contains(FaultOf(def).message, "vertex 2 is not finite"));
}

TEST(PolyhedronFaults, FacesCrossing) {
  // The triangulated unit cube with corner 7 = (1, 1, 1) pushed down through
  // the bottom face: the triangles around it pierce the bottom.
  PolyhedronDef def = TriangulatedCube();
  def.vertices[7] = {0.4, 0.6, -0.5};
  const PolyhedronFault fault = FaultOf(def);
  EXPECT_TRUE(Contains(fault.message, "intersects")) << fault.message;
  EXPECT_TRUE(Contains(fault.message, "self-intersecting")) << fault.message;
  // One of the two faces named has corner 7, the other lies in z = 0.
  ASSERT_GE(fault.face, 0);
  const auto& faces = def.faces;
  const int other = std::stoi(fault.message.substr(fault.message.find("intersects face ") + 16));
  ASSERT_GE(other, 0);
  ASSERT_LT(other, static_cast<int>(faces.size()));
  auto has7 = [&](int f) {
    return std::find(faces[f].begin(), faces[f].end(), 7) != faces[f].end();
  };
  auto bottom = [&](int f) { return f == 0 || f == 1; };  // z = 0: faces 0 and 1
  EXPECT_TRUE((has7(fault.face) && bottom(other)) || (bottom(fault.face) && has7(other)))
      << fault.message;
}

// The box [0, 2] × [0, 2] × [0, 1] with an inverted pyramid pit in its top,
// apex 8 at (1, 1, depth_left) over the bottom face. Faces: bottom 0, sides
// 1..4, the pit's triangles 5..8 (none shares a vertex with the bottom).
PolyhedronDef BoxWithPit(double depth_left) {
  PolyhedronDef def = Box(2, 2, 1);
  def.vertices.push_back({1, 1, depth_left});
  def.faces.erase(def.faces.begin() + 1);
  for (const std::vector<int>& t : Faces{{4, 5, 8}, {5, 7, 8}, {7, 6, 8}, {6, 4, 8}}) {
    def.faces.push_back(t);
  }
  return def;
}

TEST(PolyhedronFaults, FacesTouchingWithinTolerance) {
  // Apex well above the bottom: a valid non-convex solid, volume 4 − 4/3 · 0.5.
  const Polyhedron p = Polyhedron::Create(BoxWithPit(0.5), kTol);
  EXPECT_NEAR(p.mass().volume, 4 - 4.0 / 3 * 0.5, 1e-12);
  // Apex closer than tol to the bottom face: the pit touches it.
  const PolyhedronFault fault = FaultOf(BoxWithPit(kTol / 2));
  EXPECT_EQ(fault.face, 0);
  EXPECT_TRUE(Contains(fault.message, "face 0 intersects face 5")) << fault.message;
  // Just farther than tol: valid again.
  EXPECT_FALSE(Polyhedron::Check(BoxWithPit(2 * kTol), kTol));
}

// The unit cube with corner 0 cut off by the plane x + y + z = 1 (vertex 0
// unused) and corner 7 moved to `v7`, its faces triangulated so that every
// face at vertex 7 also has a vertex of the cut face 0 = (1, 2, 4). Faces 4..9
// are those at vertex 7.
PolyhedronDef CornerCutCube(const Vector3& v7) {
  PolyhedronDef def = UnitCube();
  def.vertices[7] = v7;
  def.faces = {{1, 2, 4}, {2, 3, 1}, {1, 5, 4}, {4, 6, 2}, {4, 5, 7},
               {4, 7, 6}, {2, 6, 7}, {2, 7, 3}, {1, 3, 7}, {1, 7, 5}};
  return def;
}

TEST(PolyhedronFaults, FacesCrossingFromASharedVertex) {
  const Polyhedron p = Polyhedron::Create(CornerCutCube({1, 1, 1}), kTol);
  EXPECT_NEAR(p.mass().volume, 5.0 / 6, 1e-12);
  // Corner 7 pushed through the cut face: every pair of faces that cross has a
  // vertex in common (the faces without one stay apart), so only the test
  // of faces meeting beyond a shared vertex can see it.
  const PolyhedronFault fault = FaultOf(CornerCutCube({0.2, 0.2, 0.2}));
  EXPECT_EQ(fault.face, 0);
  EXPECT_TRUE(Contains(fault.message, "face 0 intersects face 4")) << fault.message;
}

TEST(PolyhedronFaults, BadToleranceThrows) {
  EXPECT_THROW(Polyhedron::Check(UnitCube(), -1), std::invalid_argument);
  EXPECT_THROW(Polyhedron::Check(UnitCube(), std::nan("")), std::invalid_argument);
}

TEST(PolyhedronFaults, CreateThrowsTheMessage) {
  PolyhedronDef def = UnitCube();
  def.faces.pop_back();
  const std::string expected = FaultOf(def).message;
  try {
    Polyhedron::Create(def, kTol);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
}

// The L prism's centroid, (1.1, 1.1), lies outside the L, in its inner
// corner: a small box there touches nothing, while one in an arm overlaps.
TEST(PolyhedronOverlap, ANonConvexSolidsCentroidIsNotSampledWhenOutsideIt) {
  const Polyhedron l = Polyhedron::Create(LPrism(2), kTol);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_GT(SignedDistance(l, I, l.mass().centroid), 0);
  const Polyhedron corner = Polyhedron::Create(Box(0.15, 0.15, 1, {1.05, 1.05, 0.5}), kTol);
  EXPECT_FALSE(FindPolyhedronOverlap(l, I, corner, I, kTol));
  EXPECT_FALSE(FindPolyhedronOverlap(corner, I, l, I, kTol));
  const Polyhedron in_arm = Polyhedron::Create(Box(0.3, 0.5, 0.5, {0.5, 1.5, 0.5}), kTol);
  EXPECT_TRUE(FindPolyhedronOverlap(l, I, in_arm, I, kTol));
  EXPECT_TRUE(FindPolyhedronOverlap(in_arm, I, l, I, kTol));
}

// A block whose top is a shallow valley along y (two facets tilted by h/0.5,
// down to 1 − h at x = 0.5), and a long rod lying across it along x with its
// bottom d below the valley's rims: the rod's bottom edges cross both tilted
// facets with their ends far off the facets' planes (h · 4 and h · 5), but no
// point of the rod is deeper than d inside the block. So they overlap by
// more than tol exactly when d > tol, in both orders: what a pin and its
// hole do when their facets are not node on node (EdgeThroughFace).
TEST(PolyhedronOverlap, ALongEdgeUnderTiltedFacetsOverlapsByItsDepthNotItsLength) {
  const double h = 0.05, d = 0.002;
  PolyhedronDef valley;
  valley.vertices = {{0, 0, 0}, {1, 0, 0},       {1, 1, 0}, {0, 1, 0},  // bottom 0-3
                     {0, 0, 1}, {0.5, 0, 1 - h}, {1, 0, 1},             // front top 4-6
                     {0, 1, 1}, {0.5, 1, 1 - h}, {1, 1, 1}};            // back top 7-9
  valley.faces = {{0, 3, 2, 1}, {0, 1, 6, 5, 4}, {3, 7, 8, 9, 2}, {0, 4, 7, 3},
                  {1, 2, 9, 6}, {4, 5, 8, 7},    {5, 6, 9, 8}};
  const Polyhedron block = Polyhedron::Create(valley, kTol);
  EXPECT_NEAR(block.mass().volume, 1 - 0.5 * h, 1e-12);
  const Polyhedron rod = Polyhedron::Create(Box(5, 0.2, 0.1, {-2, 0.4, 1 - d}), kTol);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  for (const double tol : {0.5 * d, 1.5 * d}) {
    SCOPED_TRACE(tol);
    EXPECT_EQ(FindPolyhedronOverlap(rod, I, block, I, tol).has_value(), d > tol);
    EXPECT_EQ(FindPolyhedronOverlap(block, I, rod, I, tol).has_value(), d > tol);
  }
  // Pushed 10 d deeper, it overlaps at either tolerance.
  const Polyhedron deep = Polyhedron::Create(Box(5, 0.2, 0.1, {-2, 0.4, 1 - 11 * d}), kTol);
  EXPECT_TRUE(FindPolyhedronOverlap(deep, I, block, I, 1.5 * d));
  EXPECT_TRUE(FindPolyhedronOverlap(block, I, deep, I, 1.5 * d));
}

// Whether a sample lies inside is decided by the parity of a vertical ray's
// crossings, and by the winding number where the ray grazes an edge or runs
// in a vertical face: small cubes on a grid of step 0.25 over the L prism put
// samples exactly over its vertical faces (x or y = 0, 1, 3) and the diagonals
// of its triangulated caps. Each overlaps exactly when its box meets one of
// the L's two arms (by at least 0.05: the grid keeps the cubes' faces off the
// L's), in both orders.
TEST(PolyhedronOverlap, SamplesOverEdgesAndVerticalFacesAreJudgedRight) {
  const double h = 2;
  const Polyhedron l = Polyhedron::Create(LPrism(h), kTol);
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const std::array<std::array<double, 4>, 2> arms = {{{0, 3, 0, 1}, {0, 1, 1, 3}}};
  int overlaps = 0, cases = 0;
  for (int i = -1; i <= 13; ++i)
    for (int j = -1; j <= 13; ++j)
      for (const double z : {0.5, 1.0, 2.25}) {
        const Vector3 c(0.25 * i, 0.25 * j, z);
        bool expected = false;
        for (const auto& arm : arms)
          expected |= c.x() >= arm[0] && c.x() <= arm[1] && c.y() >= arm[2] && c.y() <= arm[3] &&
                      c.z() <= h;
        const Polyhedron cube =
            Polyhedron::Create(Box(0.1, 0.1, 0.1, c - Vector3(0.05, 0.05, 0.05)), kTol);
        SCOPED_TRACE(::testing::Message() << "cube at " << c.transpose());
        EXPECT_EQ(FindPolyhedronOverlap(l, I, cube, I, kTol).has_value(), expected);
        EXPECT_EQ(FindPolyhedronOverlap(cube, I, l, I, kTol).has_value(), expected);
        overlaps += expected;
        ++cases;
      }
  EXPECT_EQ(cases, 15 * 15 * 3);
  EXPECT_GT(overlaps, 100);
}

// A prepared solid (PreparedSolid: its grids built once, its faces and
// triangles in its own frame) answers as the polyhedron does: the overlaps
// of the L prism and small cubes on a grid over it, the L turned and moved,
// in both orders; and the signed distance of points around the L, inside,
// outside and near its faces.
TEST(PreparedSolid, AnswersAsThePolyhedronDoes) {
  const Polyhedron l = Polyhedron::Create(LPrism(2), kTol);
  const PreparedSolid pl(l, kTol);
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
  X_WL.rotate(Eigen::AngleAxisd(0.3, Vector3(1, 2, 3).normalized()));
  X_WL.pretranslate(Vector3(0.5, -1, 2));
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  int overlaps = 0, cases = 0;
  for (int i = -1; i <= 13; i += 2)
    for (int j = -1; j <= 13; j += 2)
      for (const double z : {0.5, 2.25}) {
        const Vector3 c = X_WL * Vector3(0.25 * i, 0.25 * j, z);
        const Polyhedron cube =
            Polyhedron::Create(Box(0.1, 0.1, 0.1, c - Vector3(0.05, 0.05, 0.05)), kTol);
        const PreparedSolid pc(cube, kTol);
        SCOPED_TRACE(::testing::Message() << "cube at " << c.transpose());
        const bool plain = FindPolyhedronOverlap(l, X_WL, cube, I, kTol).has_value();
        EXPECT_EQ(FindPolyhedronOverlap(pl, X_WL, pc, I).has_value(), plain);
        EXPECT_EQ(FindPolyhedronOverlap(pc, I, pl, X_WL).has_value(), plain);
        overlaps += plain;
        ++cases;
        const double sd = SignedDistance(l, X_WL, c);
        EXPECT_NEAR(SignedDistance(pl, X_WL, c), sd, 1e-12);
        const Vector3 near = c + Vector3(0.013, -0.007, 0.021);
        EXPECT_NEAR(SignedDistance(pl, X_WL, near), SignedDistance(l, X_WL, near), 1e-12);
      }
  EXPECT_EQ(cases, 8 * 8 * 2);
  EXPECT_GT(overlaps, 10);
  EXPECT_LT(overlaps, cases);
  // Solids prepared at different tolerances are refused.
  const PreparedSolid coarse(l, 10 * kTol);
  EXPECT_THROW(FindPolyhedronOverlap(pl, I, coarse, I), std::invalid_argument);
}

}  // namespace
}  // namespace cairn

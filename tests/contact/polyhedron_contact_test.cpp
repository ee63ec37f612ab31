// Contacts between polyhedra: each case has its contact set worked out by
// hand (points, normal, how many patches).
#include "cairn/contact/polyhedron_contact.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace cairn {
namespace {

constexpr double kPatchTol = 1e-9;
constexpr double kPatchAngle = 1e-6;
using Iso = Eigen::Isometry3d;

Polyhedron Box(const Vector3& lo, const Vector3& hi) {
  PolyhedronDef d;
  for (int k = 0; k < 8; ++k)
    d.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                            k & 4 ? hi.z() : lo.z());
  d.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return Polyhedron::Create(d, kPatchTol);
}

// A triangular prism along `axis` (x or y) with its ridge up (apex at z = h)
// or down (apex at z = 0, base on top at z = h), half-width 1.
Polyhedron Prism(char axis, bool ridge_up, double length, double h) {
  PolyhedronDef d;
  const auto put = [&](double along, double across, double z) {
    d.vertices.push_back(axis == 'x' ? Vector3(along, across, z) : Vector3(across, along, z));
  };
  for (double s : {-length / 2, length / 2}) {
    if (ridge_up) {
      put(s, -1, 0), put(s, 1, 0), put(s, 0, h);
    } else {
      put(s, -1, h), put(s, 1, h), put(s, 0, 0);
    }
  }
  d.faces = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
  return Polyhedron::Create(d, kPatchTol);
}

std::vector<PolyhedronContactPoint> Contacts(const Polyhedron& a, const Iso& xa,
                                             const Polyhedron& b, const Iso& xb) {
  return FindPolyhedronContacts(a, xa, b, xb, kPatchTol, kPatchAngle);
}

bool HasPoint(const std::vector<PolyhedronContactPoint>& cs, const Vector3& p) {
  return std::any_of(cs.begin(), cs.end(),
                     [&](const PolyhedronContactPoint& c) { return (c.p_W - p).norm() < 1e-9; });
}

// A unit cube whose two vertical edges at x = 1 carry an extra vertex at
// mid-height (8 on y = 0, 9 on y = 1): the same solid, its faces split.
Polyhedron CubeWithSplitEdges() {
  PolyhedronDef d;
  for (int k = 0; k < 8; ++k) d.vertices.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  d.vertices.emplace_back(1, 0, 0.5);
  d.vertices.emplace_back(1, 1, 0.5);
  d.faces = {{0, 2, 3, 1},    {4, 5, 7, 6}, {0, 1, 8, 5, 4},
             {2, 6, 7, 9, 3}, {0, 4, 6, 2}, {1, 3, 9, 7, 5, 8}};
  return Polyhedron::Create(d, kPatchTol);
}

// The cube beside a wall (x from 1 to 2), touching only its face x = 1: with
// the edges split, the middle vertices lie on the edges of the wall's faces
// y = 0 and y = 1, but the cube is beside those faces, not across them, so
// they add no contact (issue 31: their normals (0, ±1, 0) made a squeeze
// that held the falling cube up). The contacts are the face-face patch
// alone, as without the split, the points at the split vertices aside.
TEST(PolyhedronContact, AVertexInsideAStraightEdgeBesideAFaceAddsNoContact) {
  const Polyhedron wall = Box({1, 0, 0}, {2, 1, 1});
  for (const Polyhedron& cube : {Box({0, 0, 0}, {1, 1, 1}), CubeWithSplitEdges()}) {
    for (const bool swap : {false, true}) {
      const auto cs = swap ? Contacts(wall, Iso::Identity(), cube, Iso::Identity())
                           : Contacts(cube, Iso::Identity(), wall, Iso::Identity());
      ASSERT_FALSE(cs.empty());
      for (const auto& c : cs) {
        EXPECT_EQ(c.kind, ContactKind3::kFaceFace) << c.p_W.transpose();
        EXPECT_NEAR(std::abs(c.n_W.x()), 1.0, 1e-12) << c.p_W.transpose();
        EXPECT_NEAR(c.p_W.x(), 1.0, 1e-12);
      }
      for (const Vector3& p :
           {Vector3(1, 0, 0), Vector3(1, 1, 0), Vector3(1, 1, 1), Vector3(1, 0, 1)})
        EXPECT_TRUE(HasPoint(cs, p)) << p.transpose();
    }
  }
}

// A stepped block (x from 0 to 2, y from 0 to 1; 2 high for x < 1, 1 high
// beyond: an inside step whose riser is the face x = 1, z from 1 to 2) and a
// unit box beside it across y = 0 (x from 1 to 2, y from −1 to 0, 1 high),
// touching it face to face. The box's corner (1, 0, 1) lies at the end of
// the step's inside edge, on the riser's corner, but the box is beside the
// riser, not across it: it may slide along x either way. Only the face-face
// patch on y = 0 touches (the toy truck's wheel arch beside its bumper's
// step gave a contact normal to the riser, and an arc along +x, issue 31).
TEST(PolyhedronContact, ACornerBesideAnInsideStepTouchesOnlyTheFaceItIsAcross) {
  PolyhedronDef d;
  const std::vector<std::array<double, 2>> profile = {{0, 0}, {2, 0}, {2, 1},
                                                      {1, 1}, {1, 2}, {0, 2}};
  const int n = static_cast<int>(profile.size());
  for (const double y : {0.0, 1.0})
    for (const auto& [x, z] : profile) d.vertices.emplace_back(x, y, z);
  std::vector<int> front, back;
  for (int k = 0; k < n; ++k) front.push_back(k), back.push_back(2 * n - 1 - k);
  d.faces = {front, back};
  for (int k = 0; k < n; ++k) d.faces.push_back({k, n + k, n + (k + 1) % n, (k + 1) % n});
  const Polyhedron stepped = Polyhedron::Create(d, kPatchTol);
  const Polyhedron beside = Box({1, -1, 0}, {2, 0, 1});
  for (const bool swap : {false, true}) {
    SCOPED_TRACE(swap);
    const auto cs = swap ? Contacts(beside, Iso::Identity(), stepped, Iso::Identity())
                         : Contacts(stepped, Iso::Identity(), beside, Iso::Identity());
    ASSERT_EQ(cs.size(), 4u);
    for (const auto& c : cs) {
      EXPECT_EQ(c.kind, ContactKind3::kFaceFace) << c.p_W.transpose();
      EXPECT_NEAR(std::abs(c.n_W.y()), 1.0, 1e-12) << c.p_W.transpose();
    }
    EXPECT_TRUE(HasPoint(cs, Vector3(1, 0, 1)));
  }
  // A box in the step's inside corner touches both the tread and the riser.
  const Polyhedron in_corner = Box({1, 0.2, 1}, {1.5, 0.8, 1.5});
  const auto cs = Contacts(in_corner, Iso::Identity(), stepped, Iso::Identity());
  const auto along = [&](const Vector3& m) {
    return std::count_if(cs.begin(), cs.end(), [&](const PolyhedronContactPoint& c) {
      return (c.n_W - m).norm() < 1e-12;
    });
  };
  EXPECT_EQ(along(Vector3::UnitZ()), 4);
  EXPECT_EQ(along(Vector3::UnitX()), 4);
}

// The same cube on a table: the split vertices are above the table, and its
// bottom face is one patch of four points either way.
TEST(PolyhedronContact, SplitEdgesLeaveACubesRestingContactsAsTheyWere) {
  const Polyhedron table = Box({-2, -2, -1}, {2, 2, 0});
  const auto cs = Contacts(CubeWithSplitEdges(), Iso::Identity(), table, Iso::Identity());
  ASSERT_EQ(cs.size(), 4u);
  for (const auto& c : cs) EXPECT_NEAR((c.n_W - Vector3::UnitZ()).norm(), 0.0, 1e-12);
}

TEST(PolyhedronContact, ACubeOnATableTouchesWithItsWholeBottomFace) {
  const Polyhedron table = Box({-2, -2, -1}, {2, 2, 0});
  const Polyhedron cube = Box({0, 0, 0}, {1, 1, 1});
  const auto cs = Contacts(cube, Iso::Identity(), table, Iso::Identity());
  ASSERT_EQ(cs.size(), 4u);
  for (const auto& c : cs) {
    EXPECT_EQ(c.kind, ContactKind3::kFaceFace);
    EXPECT_EQ(c.patch, cs[0].patch);
    EXPECT_NEAR((c.n_W - Vector3::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(c.p_W.z(), 0.0, 1e-12);
  }
  for (const Vector3& p : {Vector3(0, 0, 0), Vector3(1, 0, 0), Vector3(1, 1, 0), Vector3(0, 1, 0)})
    EXPECT_TRUE(HasPoint(cs, p)) << p.transpose();
  // The same pair with the roles swapped: the normal flips (from b into a).
  const auto swapped = Contacts(table, Iso::Identity(), cube, Iso::Identity());
  ASSERT_EQ(swapped.size(), 4u);
  for (const auto& c : swapped) EXPECT_NEAR((c.n_W + Vector3::UnitZ()).norm(), 0.0, 1e-12);
}

// Overhanging the table's edge x = 2 by half: the patch is the part of the
// bottom face over the table.
TEST(PolyhedronContact, AnOverhangingCubeTouchesOnlyOverTheTable) {
  const Polyhedron table = Box({-2, -2, -1}, {2, 2, 0});
  const Polyhedron cube = Box({1.5, 0, 0}, {2.5, 1, 1});
  const auto cs = Contacts(cube, Iso::Identity(), table, Iso::Identity());
  ASSERT_EQ(cs.size(), 4u);
  for (const Vector3& p :
       {Vector3(1.5, 0, 0), Vector3(2, 0, 0), Vector3(2, 1, 0), Vector3(1.5, 1, 0)})
    EXPECT_TRUE(HasPoint(cs, p)) << p.transpose();
}

// A cube turned 45° about z on a cube of the same size: the patch is the
// regular octagon where the two squares overlap.
TEST(PolyhedronContact, TwoSquaresAt45DegreesMeetInAnOctagon) {
  const Polyhedron lower = Box({-0.5, -0.5, -1}, {0.5, 0.5, 0});
  const Polyhedron upper = Box({-0.5, -0.5, 0}, {0.5, 0.5, 1});
  Iso turn = Iso::Identity();
  turn.linear() = Eigen::AngleAxisd(std::numbers::pi / 4, Vector3::UnitZ()).toRotationMatrix();
  const auto cs = Contacts(upper, turn, lower, Iso::Identity());
  ASSERT_EQ(cs.size(), 8u);
  for (const auto& c : cs) {
    EXPECT_EQ(c.patch, cs[0].patch);
    // Every octagon vertex lies on the boundary of both squares.
    const double r = std::max(std::abs(c.p_W.x()), std::abs(c.p_W.y()));
    EXPECT_NEAR(r, 0.5, 1e-12);
  }
}

// A cube tipped 45° about x rests on one edge: two points (the edge's ends),
// normal up; tipped onto a vertex (45° about x, then about y), one point.
TEST(PolyhedronContact, ATippedCubeRestsOnAnEdgeOrAVertex) {
  const Polyhedron table = Box({-3, -3, -1}, {3, 3, 0});
  const Polyhedron cube = Box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
  Iso on_edge = Iso::Identity();
  on_edge.linear() = Eigen::AngleAxisd(std::numbers::pi / 4, Vector3::UnitX()).toRotationMatrix();
  on_edge.translation() = Vector3(0, 0, std::sqrt(0.5));
  const auto edge = Contacts(cube, on_edge, table, Iso::Identity());
  ASSERT_EQ(edge.size(), 2u);
  for (const auto& c : edge) {
    EXPECT_NEAR((c.n_W - Vector3::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(c.p_W.z(), 0.0, 1e-12);
    EXPECT_NEAR(std::abs(c.p_W.x()), 0.5, 1e-12);
  }

  // Vertex down: the cube's diagonal (1, 1, 1) along −z.
  Iso on_vertex = Iso::Identity();
  on_vertex.linear() =
      Eigen::Quaterniond::FromTwoVectors(Vector3(1, 1, 1).normalized(), -Vector3::UnitZ())
          .toRotationMatrix();
  on_vertex.translation() = Vector3(0, 0, std::sqrt(3.0) / 2);
  const auto vertex = Contacts(cube, on_vertex, table, Iso::Identity());
  ASSERT_EQ(vertex.size(), 1u);
  EXPECT_EQ(vertex[0].kind, ContactKind3::kVertexFace);
  EXPECT_NEAR(vertex[0].p_W.norm(), 0.0, 1e-12);
}

// An upside-down prism's lower edge (along y) across an upright prism's ridge
// (along x): one edge–edge point at the origin, normal up into a.
TEST(PolyhedronContact, CrossedRidgesTouchAtOnePoint) {
  const Polyhedron lower = Prism('x', true, 4, 1);
  const Polyhedron upper = Prism('y', false, 4, 1);
  Iso up = Iso::Identity();
  up.translation() = Vector3(0, 0, 1);
  const auto cs = Contacts(upper, up, lower, Iso::Identity());
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(cs[0].kind, ContactKind3::kEdgeEdge);
  EXPECT_NEAR((cs[0].p_W - Vector3(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((cs[0].n_W - Vector3::UnitZ()).norm(), 0.0, 1e-12);
}

// A prism lying on its ridge... on its side face over a table edge: an edge
// of a resting on b's face beyond its vertices gives the clipped segment.
TEST(PolyhedronContact, AnEdgeAcrossAFaceIsClippedToIt) {
  const Polyhedron table = Box({-1, -1, -1}, {1, 1, 0});
  const Polyhedron ridge_down = Prism('x', false, 4, 1);  // lower edge along x, z = 0, x ∈ [−2, 2]
  const auto cs = Contacts(ridge_down, Iso::Identity(), table, Iso::Identity());
  ASSERT_EQ(cs.size(), 2u);
  EXPECT_TRUE(HasPoint(cs, Vector3(-1, 0, 0)));
  EXPECT_TRUE(HasPoint(cs, Vector3(1, 0, 0)));
  for (const auto& c : cs) EXPECT_EQ(c.kind, ContactKind3::kEdgeFace);
}

// An L-shaped prism (non-convex top face, z = 1): a 2 × 2 block over it
// touches the whole L (six points); a block over the notch touches nothing,
// which the L's convex hull would get wrong.
TEST(PolyhedronContact, NonConvexFacesAreClippedExactly) {
  PolyhedronDef l;
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (double z : {0.0, 1.0})
    for (const auto& p : xy) l.vertices.emplace_back(p[0], p[1], z);
  l.faces = {{5, 4, 3, 2, 1, 0}, {6, 7, 8, 9, 10, 11}};
  for (int i = 0; i < 6; ++i) l.faces.push_back({i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6});
  const Polyhedron L = Polyhedron::Create(l, kPatchTol);

  const auto whole = Contacts(Box({0, 0, 1}, {2, 2, 2}), Iso::Identity(), L, Iso::Identity());
  ASSERT_EQ(whole.size(), 6u);
  for (const auto& p : xy) EXPECT_TRUE(HasPoint(whole, Vector3(p[0], p[1], 1))) << p[0] << p[1];
  EXPECT_TRUE(Contacts(Box({1.2, 1.2, 1}, {2, 2, 2}), Iso::Identity(), L, Iso::Identity()).empty());
}

TEST(PolyhedronContact, APartAGapAboveTouchesNothing) {
  const Polyhedron table = Box({-2, -2, -1}, {2, 2, 0});
  const Polyhedron cube = Box({0, 0, 1e-3}, {1, 1, 1});
  EXPECT_TRUE(Contacts(cube, Iso::Identity(), table, Iso::Identity()).empty());
}

// Parts meant to touch that overlap (meshes as exported), read with an
// overlap depth: each pose of a resting on b (a face, an overhanging face,
// an edge, a vertex, an edge across a ridge) pressed into b by δ along the
// normal gives the contacts of the touching pose, each moved to the
// overlap's mid-surface (δ/2 into b) with gap −δ; pressed deeper than the
// depth, or lifted clear of the length tolerance, none.
TEST(PolyhedronContact, AnOverlapWithinTheDepthTouchesOnItsMidSurface) {
  const Polyhedron table = Box({-2, -2, -1}, {2, 2, 0});
  const Polyhedron cube = Box({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
  Iso flat = Iso::Identity(), overhang = Iso::Identity(), on_edge = Iso::Identity(),
      on_vertex = Iso::Identity(), ridge = Iso::Identity();
  flat.translation() = Vector3(0, 0, 0.5);
  overhang.translation() = Vector3(2, 0.5, 0.5);
  on_edge.linear() = Eigen::AngleAxisd(std::numbers::pi / 4, Vector3::UnitX()).toRotationMatrix();
  on_edge.translation() = Vector3(0, 0, std::sqrt(0.5));
  on_vertex.linear() =
      Eigen::Quaterniond::FromTwoVectors(Vector3(1, 1, 1).normalized(), -Vector3::UnitZ())
          .toRotationMatrix();
  on_vertex.translation() = Vector3(0, 0, std::sqrt(3.0) / 2);
  ridge.translation() = Vector3(0, 0, 1);
  const Polyhedron lower = Prism('x', true, 4, 1), upper = Prism('y', false, 4, 1);
  struct Case {
    const char* what;
    const Polyhedron& a;
    Iso X_a;
    const Polyhedron& b;
    size_t points;
  };
  const Case cases[] = {{"face", cube, flat, table, 4},
                        {"overhang", cube, overhang, table, 4},
                        {"edge", cube, on_edge, table, 2},
                        {"vertex", cube, on_vertex, table, 1},
                        {"ridge", upper, ridge, lower, 1}};
  constexpr double kDepth = 0.04, kPressed = 0.03;
  const auto find = [](const Case& c, double down, double depth) {
    Iso X = c.X_a;
    X.translation().z() -= down;
    return FindPolyhedronContacts(c.a, X, c.b, Iso::Identity(), kPatchTol, kPatchAngle, depth);
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const auto touching = find(c, 0, kDepth);
    const auto pressed = find(c, kPressed, kDepth);
    ASSERT_EQ(touching.size(), c.points);
    ASSERT_EQ(pressed.size(), c.points);
    for (const PolyhedronContactPoint& t : touching) {
      EXPECT_NEAR((t.n_W - Vector3::UnitZ()).norm(), 0.0, 1e-12);
      EXPECT_TRUE(HasPoint(pressed, t.p_W - 0.5 * kPressed * Vector3::UnitZ()))
          << "no point at the mid-surface below " << t.p_W.transpose();
    }
    for (const PolyhedronContactPoint& p : pressed) {
      EXPECT_NEAR(p.gap, -kPressed, 1e-12);
      EXPECT_NEAR((p.n_W - Vector3::UnitZ()).norm(), 0.0, 1e-12);
    }
    // Without the depth the same overlap is no contact (the overlap test
    // refuses it); deeper than the depth, none; apart, none.
    EXPECT_TRUE(find(c, kPressed, 0).empty());
    EXPECT_TRUE(find(c, kDepth + 1e-3, kDepth).empty());
    EXPECT_TRUE(find(c, -10 * kPatchTol, kDepth).empty());
  }
}

}  // namespace
}  // namespace cairn

#include "cairn/geometry/polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cairn {
namespace {

constexpr double kEps = 1e-12;

Polygon Rectangle(double x0, double y0, double w, double h) {
  return {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
}

// [0, 3] × [0, 1] ∪ [0, 1] × [1, 3], counter-clockwise.
Polygon LShape() { return {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}}; }

void ExpectSameMass(const PolygonMass& a, const PolygonMass& b, double tol) {
  EXPECT_NEAR(a.area, b.area, tol);
  EXPECT_NEAR(a.centroid.x(), b.centroid.x(), tol);
  EXPECT_NEAR(a.centroid.y(), b.centroid.y(), tol);
  EXPECT_NEAR(a.polar_moment, b.polar_moment, tol);
}

TEST(SignedArea, PositiveCounterClockwiseNegativeClockwise) {
  Polygon p = Rectangle(0, 0, 4, 2);
  EXPECT_DOUBLE_EQ(SignedArea(p), 8.0);
  std::reverse(p.begin(), p.end());
  EXPECT_DOUBLE_EQ(SignedArea(p), -8.0);
}

TEST(MakeCounterClockwise, ReversesClockwiseKeepingVertexZero) {
  Polygon p = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};  // clockwise
  MakeCounterClockwise(p);
  EXPECT_GT(SignedArea(p), 0);
  EXPECT_EQ(p[0], Vector2(0, 0));
  EXPECT_EQ(p[1], Vector2(1, 0));
  // Already counter-clockwise: unchanged.
  const Polygon before = p;
  MakeCounterClockwise(p);
  EXPECT_EQ(p, before);
}

TEST(ComputePolygonMass, RectangleFarFromOrigin) {
  const double w = 4, h = 2;
  const PolygonMass m = ComputePolygonMass(Rectangle(1000, -500, w, h));
  EXPECT_NEAR(m.area, w * h, 1e-9);
  EXPECT_NEAR(m.centroid.x(), 1002, 1e-9);
  EXPECT_NEAR(m.centroid.y(), -499, 1e-9);
  // I = m (w² + h²) / 12 with unit density: polar_moment = A (w² + h²) / 12.
  EXPECT_NEAR(m.polar_moment, w * h * (w * w + h * h) / 12, 1e-8);
}

TEST(ComputePolygonMass, RightTriangle) {
  const double a = 3, b = 2;
  const PolygonMass m = ComputePolygonMass({{0, 0}, {a, 0}, {0, b}});
  EXPECT_NEAR(m.area, a * b / 2, kEps);
  EXPECT_NEAR(m.centroid.x(), a / 3, kEps);
  EXPECT_NEAR(m.centroid.y(), b / 3, kEps);
  // I_x + I_y about the centroid: a b³/36 + b a³/36.
  EXPECT_NEAR(m.polar_moment, a * b * (a * a + b * b) / 36, kEps);
}

TEST(ComputePolygonMass, LShapeIsTheSumOfTwoRectangles) {
  // Rectangle 1: [0, 3] × [0, 1]; rectangle 2: [0, 1] × [1, 3].
  const double a1 = 3, a2 = 2;
  const Vector2 c1(1.5, 0.5), c2(0.5, 2);
  const double j1 = a1 * (9 + 1) / 12.0, j2 = a2 * (1 + 4) / 12.0;
  const double area = a1 + a2;
  const Vector2 c = (a1 * c1 + a2 * c2) / area;
  // Parallel-axis theorem moves each rectangle's moment to the common centroid.
  const double j = j1 + a1 * (c1 - c).squaredNorm() + j2 + a2 * (c2 - c).squaredNorm();
  const PolygonMass m = ComputePolygonMass(LShape());
  EXPECT_NEAR(m.area, 5.0, kEps);
  EXPECT_NEAR(m.centroid.x(), 1.1, kEps);
  EXPECT_NEAR(m.centroid.y(), 1.1, kEps);
  EXPECT_NEAR(m.polar_moment, j, kEps);
}

TEST(ComputePolygonMass, InvariantUnderVertexRotationAndReversal) {
  const Polygon l = LShape();
  const PolygonMass ref = ComputePolygonMass(l);
  for (size_t k = 0; k < l.size(); ++k) {
    Polygon rotated = l;
    std::rotate(rotated.begin(), rotated.begin() + k, rotated.end());
    ExpectSameMass(ComputePolygonMass(rotated), ref, kEps);
    std::reverse(rotated.begin(), rotated.end());
    ExpectSameMass(ComputePolygonMass(rotated), ref, kEps);
  }
}

TEST(ComputePolygonMass, DegenerateGivesZero) {
  EXPECT_EQ(ComputePolygonMass({{0, 0}, {1, 1}}).area, 0.0);
  EXPECT_EQ(ComputePolygonMass({{0, 0}, {1, 0}, {2, 0}}).area, 0.0);
}

TEST(FindSelfIntersection, BowTieCrosses) {
  const auto s = FindSelfIntersection({{0, 0}, {2, 2}, {2, 0}, {0, 2}}, 1e-9);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->edge_a, 0);
  EXPECT_EQ(s->edge_b, 2);
}

TEST(FindSelfIntersection, RepeatedConsecutiveVertex) {
  // Vertex 3 repeats vertex 2: edge 2 has no length; edges 1 and 3 meet.
  const auto s = FindSelfIntersection({{0, 0}, {2, 0}, {2, 2}, {2, 2}, {0, 2}}, 1e-9);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->edge_a, 1);
  EXPECT_EQ(s->edge_b, 3);
}

TEST(FindSelfIntersection, RepeatedDistantVertexTouches) {
  // Two triangles meeting at (2, 2), vertex 2 == vertex 5: a pinched polygon.
  const auto s = FindSelfIntersection({{0, 0}, {4, 0}, {2, 2}, {4, 4}, {0, 4}, {2, 2}}, 1e-9);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->edge_a, 1);
  EXPECT_EQ(s->edge_b, 4);
}

TEST(FindSelfIntersection, FoldBackOfAdjacentEdges) {
  // Edge 1 goes up x = 4 to y = 2, edge 2 comes back down to y = 1.
  const auto s = FindSelfIntersection({{0, 0}, {4, 0}, {4, 2}, {4, 1}, {0, 2}}, 1e-9);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->edge_a, 1);
  EXPECT_EQ(s->edge_b, 2);
}

TEST(FindSelfIntersection, FoldBackAcrossTheClosingVertex) {
  // Edges 3 and 0 share vertex 0; edge 0 runs back along edge 3.
  const auto s = FindSelfIntersection({{0, 0}, {0, 1}, {2, 2}, {0, 3}}, 1e-9);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->edge_a, 0);
  EXPECT_EQ(s->edge_b, 3);
}

TEST(FindSelfIntersection, SimplePolygonsAreNotFlagged) {
  EXPECT_FALSE(FindSelfIntersection(Rectangle(0, 0, 1, 1), 1e-9));
  EXPECT_FALSE(FindSelfIntersection(LShape(), 1e-9));
  // A non-convex comb with narrow (0.01) slots.
  const Polygon comb = {{0, 0},    {3, 0},    {3, 2},    {2.01, 2}, {2.01, 1}, {1.99, 1},
                        {1.99, 2}, {1.01, 2}, {1.01, 1}, {0.99, 1}, {0.99, 2}, {0, 2}};
  EXPECT_FALSE(FindSelfIntersection(comb, 1e-6));
  // ... but edges closer than the tolerance touch.
  EXPECT_TRUE(FindSelfIntersection(comb, 0.05));
  // Either orientation.
  Polygon l = LShape();
  std::reverse(l.begin(), l.end());
  EXPECT_FALSE(FindSelfIntersection(l, 1e-9));
}

TEST(DistanceToSegment, InteriorEndpointsAndDegenerate) {
  const Vector2 a(0, 0), b(4, 0);
  EXPECT_DOUBLE_EQ(DistanceToSegment({2, 3}, a, b), 3.0);
  EXPECT_DOUBLE_EQ(DistanceToSegment({-3, 4}, a, b), 5.0);
  EXPECT_DOUBLE_EQ(DistanceToSegment({7, -4}, a, b), 5.0);
  EXPECT_DOUBLE_EQ(DistanceToSegment({3, 4}, a, a), 5.0);
}

TEST(PointQueries, LShape) {
  const Polygon l = LShape();
  EXPECT_TRUE(ContainsPoint(l, {0.5, 2.5}));
  EXPECT_TRUE(ContainsPoint(l, {2.5, 0.5}));
  EXPECT_FALSE(ContainsPoint(l, {2, 2}));  // in the notch
  EXPECT_FALSE(ContainsPoint(l, {-1, 0.5}));
  EXPECT_DOUBLE_EQ(DistanceToBoundary(l, {2, 2}), 1.0);
  EXPECT_DOUBLE_EQ(DistanceToBoundary(l, {0.5, 0.25}), 0.25);
  EXPECT_DOUBLE_EQ(SignedDepth(l, {0.5, 0.25}), 0.25);
  EXPECT_DOUBLE_EQ(SignedDepth(l, {2, 2}), -1.0);
  EXPECT_DOUBLE_EQ(SignedDepth(l, {1.5, 1.5}), -0.5);  // below the edge y = 1
  // A point level with a vertex (the ray passes through vertex 3) is counted once.
  EXPECT_TRUE(ContainsPoint(l, {0.5, 1}));
  EXPECT_FALSE(ContainsPoint(l, {-0.5, 1}));
}

TEST(BoundingBox, Corners) {
  const auto [lo, hi] = BoundingBox({{1, 5}, {-2, 3}, {4, -1}});
  EXPECT_EQ(lo, Vector2(-2, -1));
  EXPECT_EQ(hi, Vector2(4, 5));
}

TEST(EdgeNormal, OutwardForCounterClockwise) {
  const Polygon sq = Rectangle(0, 0, 2, 2);
  EXPECT_TRUE(EdgeNormal(sq, 0).isApprox(Vector2(0, -1)));
  EXPECT_TRUE(EdgeNormal(sq, 1).isApprox(Vector2(1, 0)));
  EXPECT_TRUE(EdgeNormal(sq, 2).isApprox(Vector2(0, 1)));
  EXPECT_TRUE(EdgeNormal(sq, 3).isApprox(Vector2(-1, 0)));
  const Vector2 n = EdgeNormal({{0, 0}, {3, 4}, {0, 4}}, 0);
  EXPECT_NEAR(n.norm(), 1.0, kEps);
  EXPECT_TRUE(n.isApprox(Vector2(0.8, -0.6)));
}

}  // namespace
}  // namespace cairn

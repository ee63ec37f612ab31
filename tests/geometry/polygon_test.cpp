#include "cairn/geometry/polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

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

// FindSelfIntersection above 64 vertices is a sweep over the edges' boxes:
// it must agree with the test of every pair of edges (written here) on
// whether a polygon is simple, and name a pair that truly touches.
namespace sweep_check {

double Cross(const Vector2& o, const Vector2& a, const Vector2& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

// The distance between segments [a0, a1] and [b0, b1]: 0 where they cross,
// else the least distance of an end to the other segment.
double SegmentDistance(const Vector2& a0, const Vector2& a1, const Vector2& b0, const Vector2& b1) {
  const double d1 = Cross(a0, a1, b0), d2 = Cross(a0, a1, b1);
  const double d3 = Cross(b0, b1, a0), d4 = Cross(b0, b1, a1);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return 0;
  return std::min({DistanceToSegment(a0, b0, b1), DistanceToSegment(a1, b0, b1),
                   DistanceToSegment(b0, a0, a1), DistanceToSegment(b1, a0, a1)});
}

bool TouchesBruteForce(const Polygon& p, double tol, int* a, int* b) {
  const int n = static_cast<int>(p.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) continue;  // adjacent edges share a vertex by construction
      if (SegmentDistance(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]) <= tol) {
        *a = i, *b = j;
        return true;
      }
    }
  return false;
}

}  // namespace sweep_check

TEST(SelfIntersection, TheSweepAgreesWithEveryPairOnLargePolygons) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(0.7, 1.3);
  int simple = 0, crossing = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 65 + trial * 3;
    Polygon p;
    for (int k = 0; k < n; ++k) {  // a star-shaped polygon: simple
      const double t = 2 * 3.141592653589793 * k / n;
      const double r = jitter(rng);
      p.push_back(Vector2(r * std::cos(t), r * std::sin(t)));
    }
    if (trial % 2) std::swap(p[n / 3], p[2 * n / 3]);  // two far vertices swapped: crossings
    int a = -1, b = -1;
    const bool brute = sweep_check::TouchesBruteForce(p, 1e-9, &a, &b);
    const auto found = FindSelfIntersection(p, 1e-9);
    ASSERT_EQ(found.has_value(), brute) << "trial " << trial;
    if (!found) {
      ++simple;
      continue;
    }
    ++crossing;
    const int i = found->edge_a, j = found->edge_b;
    EXPECT_LT(i, j);
    EXPECT_LE(sweep_check::SegmentDistance(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]), 1e-9);
  }
  EXPECT_GT(simple, 0);
  EXPECT_GT(crossing, 0);
}

TEST(SelfIntersection, ASixtyThousandGonIsSimple) {
  const int n = 60000;
  Polygon p;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * 3.141592653589793 * k / n;
    p.push_back(Vector2(2 * std::cos(t), 2 + 2 * std::sin(t)));
  }
  EXPECT_FALSE(FindSelfIntersection(p, 1e-6 * 4).has_value());
  // One vertex pulled across the disc and out the other side: its two
  // edges cross the boundary there.
  p[n / 2] = Vector2(2.5, 2.0);
  EXPECT_TRUE(FindSelfIntersection(p, 1e-6 * 4).has_value());
}

// Ear clipping: the triangles are counter-clockwise, not slivers, inside the
// polygon, and their areas add up to its area (so they do not overlap).
void ExpectTriangulates(const Polygon& p, double tol) {
  const auto tris = Triangulate(p, tol);
  ASSERT_FALSE(tris.empty());
  double area = 0;
  for (const auto& t : tris) {
    const Polygon tri = {p[t[0]], p[t[1]], p[t[2]]};
    const double a = SignedArea(tri);
    EXPECT_GT(a, 0);
    EXPECT_GT(LineSide(tri[0], tri[1], tri[2]), tol);
    EXPECT_TRUE(ContainsPoint(p, (tri[0] + tri[1] + tri[2]) / 3));
    area += a;
  }
  EXPECT_NEAR(area, SignedArea(p), 1e-9 * std::abs(SignedArea(p)));
  EXPECT_LE(tris.size(), p.size() - 2);
}

TEST(Triangulate, LShapeAndCollinearVertices) {
  ExpectTriangulates(LShape(), 1e-9);
  EXPECT_EQ(Triangulate(LShape(), 1e-9).size(), 4u);
  // A square with a vertex in the middle of every edge: two triangles.
  const Polygon square = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  ExpectTriangulates(square, 1e-9);
  EXPECT_EQ(Triangulate(square, 1e-9).size(), 2u);
  // Paper Fig. 4's base: a U.
  ExpectTriangulates({{0, -1}, {10, -1}, {10, 4}, {9, 4}, {9, 0}, {1, 0}, {1, 4}, {0, 4}}, 1e-9);
}

TEST(Triangulate, StarShapedPolygonsAndCombs) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(0.3, 1.3);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 5 + trial * 7;
    Polygon p;
    for (int k = 0; k < n; ++k) {
      const double t = 2 * 3.141592653589793 * k / n;
      const double r = jitter(rng);
      p.push_back(Vector2(r * std::cos(t), r * std::sin(t)));
    }
    SCOPED_TRACE("trial " + std::to_string(trial));
    ExpectTriangulates(p, 1e-12);
  }
  // A comb: teeth whose ears are hidden behind the others.
  Polygon comb = {{0, 0}, {20, 0}};
  for (int k = 9; k >= 0; --k) {
    comb.push_back({2.0 * k + 2, 5});
    comb.push_back({2.0 * k + 1, 1});
  }
  comb.push_back({0, 5});
  ExpectTriangulates(comb, 1e-12);
}

TEST(Triangulate, ClockwiseHasNoEar) {
  Polygon p = LShape();
  std::reverse(p.begin(), p.end());
  EXPECT_TRUE(Triangulate(p, 1e-9).empty());
}

}  // namespace
}  // namespace cairn

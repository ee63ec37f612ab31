#include "cairn/contact/detect_contacts.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "scene_builders.h"

namespace cairn {
namespace {

constexpr double kTol = 1e-6;
constexpr double kAngle = 1e-6;

Polygon Rect(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

std::vector<Contact> Touch(const Polygon& a, const Polygon& b, double mu = 0.0) {
  std::vector<Contact> out;
  DetectPairContacts(a, b, 0, 1, mu, kTol, kAngle, out);
  return out;
}

std::vector<double> Xs(const std::vector<Contact>& cs) {
  std::vector<double> xs;
  for (const Contact& c : cs) xs.push_back(c.p_WC.x());
  std::sort(xs.begin(), xs.end());
  return xs;
}

TEST(EdgeEdge, StackedBlocksTouchAtTheTwoEndsOfTheirOverlap) {
  // a = [1,3]x[1,2] on b = [0,2]x[0,1]: the overlap of the edges is x ∈ [1, 2].
  const auto cs = Touch(Rect(1, 1, 3, 2), Rect(0, 0, 2, 1), 0.4);
  ASSERT_EQ(cs.size(), 2u);
  EXPECT_THAT(Xs(cs), ::testing::ElementsAre(1.0, 2.0));
  for (const Contact& c : cs) {
    EXPECT_DOUBLE_EQ(c.p_WC.y(), 1.0);
    EXPECT_EQ(c.n_W, Vector3(0, 1, 0)) << "the normal points from b into a";
    EXPECT_EQ(c.mu, 0.4);
    EXPECT_EQ(c.part_a, 0);
    EXPECT_EQ(c.part_b, 1);
  }
}

TEST(EdgeEdge, EqualWidthBlocksGiveTwoContactsNotFour) {
  // The overlap ends are vertices of both: each is found twice and merged.
  const auto cs = Touch(Rect(0, 1, 2, 2), Rect(0, 0, 2, 1));
  EXPECT_THAT(Xs(cs), ::testing::ElementsAre(0.0, 2.0));
}

TEST(EdgeEdge, SideBySideBlocksPushHorizontally) {
  const auto cs = Touch(Rect(1, 0, 2, 1), Rect(0, 0, 1, 1));
  ASSERT_EQ(cs.size(), 2u);
  for (const Contact& c : cs) EXPECT_EQ(c.n_W, Vector3(1, 0, 0));
}

TEST(Tolerance, AGapWithinToleranceTouchesAndLargerDoesNot) {
  const auto near = Touch(Rect(0, 1 + 0.5 * kTol, 2, 2), Rect(0, 0, 2, 1));
  ASSERT_EQ(near.size(), 2u);
  for (const Contact& c : near) EXPECT_NEAR(c.gap, 0.5 * kTol, 1e-15);
  EXPECT_TRUE(Touch(Rect(0, 1 + 3 * kTol, 2, 2), Rect(0, 0, 2, 1)).empty());
}

TEST(VertexEdge, ATriangleStandingOnItsTipTouchesOnce) {
  const Polygon tri = {{1, 0}, {2, 1}, {0, 1}};  // tip down at (1, 0)
  const auto cs = Touch(tri, Rect(-1, -1, 3, 0));
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(cs[0].p_WC, Vector3(1, 0, 0));
  EXPECT_EQ(cs[0].n_W, Vector3(0, 1, 0));
  EXPECT_EQ(cs[0].feature, ContactFeature::kVertexOfAOnEdgeOfB);
}

TEST(VertexEdge, ATiltedBlockOnItsCornerTouchesOnceWithTheTableNormal) {
  const double c = std::cos(0.3), s = std::sin(0.3);
  Polygon blk = {{0, 0}, {c, s}, {c - s, s + c}, {-s, c}};
  const auto cs = Touch(blk, Rect(-3, -1, 3, 0));
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_EQ(cs[0].n_W, Vector3(0, 1, 0));
}

TEST(VertexEdge, TheTableCornerUnderABlockIsAContactWithTheBlocksNormal) {
  // Block overhanging the table's right corner: the corner (0, 0) touches the
  // block's bottom edge; the normal is still up (from the table into the block).
  const auto cs = Touch(Rect(-1, 0, 1, 1), Rect(-5, -1, 0, 0));
  ASSERT_EQ(cs.size(), 2u);
  EXPECT_THAT(Xs(cs), ::testing::ElementsAre(-1.0, 0.0));
  for (const Contact& c : cs) EXPECT_EQ(c.n_W, Vector3(0, 1, 0));
}

TEST(NonConvex, ABlockInTheInnerCornerOfAnLTouchesFloorAndWall) {
  // L-shape: floor along y ∈ [0,1], wall along x ∈ [0,1].
  const Polygon ell = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  const auto cs = Touch(Rect(1, 1, 2, 2), ell);
  int up = 0, right = 0;
  for (const Contact& c : cs) {
    if (c.n_W == Vector3(0, 1, 0)) ++up;
    if (c.n_W == Vector3(1, 0, 0)) ++right;
  }
  EXPECT_EQ(up, 2);     // (1,1) and (2,1) on the floor
  EXPECT_EQ(right, 2);  // (1,1) and (1,2) on the wall
  EXPECT_EQ(cs.size(), 4u);
}

TEST(NonConvex, AReflexVertexNeverRestsOnALine) {
  // The L's reflex vertex (1,1) lies on the line y = 1 of a block's bottom
  // edge placed above it, but the L's material around it spans more than a
  // half-plane: it cannot be a contact, while the flat top of the L can.
  const Polygon ell = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  for (const Contact& c : Touch(ell, Rect(1.5, 1, 3, 2))) EXPECT_NE(c.p_WC, Vector3(1, 1, 0));
}

TEST(CornerCorner, DiagonalCornersKeepBothNormals) {
  // a's lower-left corner on b's upper-right corner: ambiguous; the pair
  // detector returns both the horizontal and the vertical normal as
  // candidates (DetectContacts then applies the corner rule to them:
  // corner_touches_test.cpp).
  const auto cs = Touch(Rect(1, 1, 2, 2), Rect(0, 0, 1, 1));
  ASSERT_FALSE(cs.empty());
  for (const Contact& c : cs) EXPECT_EQ(c.p_WC, Vector3(1, 1, 0));
}

TEST(Separated, FarApartPolygonsDoNotTouch) {
  EXPECT_TRUE(Touch(Rect(0, 0, 1, 1), Rect(3, 3, 4, 4)).empty());
}

// PairContactCache: along a path one part moves; the pairs of the others are
// answered from the cache, and the contacts are exactly (bitwise, in order)
// those DetectContacts finds without it, at every step, including the steps
// where the moved block's contacts change (it slides off its support's
// edge onto the table).
TEST(PairContactCache, GivesExactlyTheContactsOfComputingThemAgain) {
  AssemblyDef def;
  def.friction = 0.5;
  def.gravity = Vector3(0, 0, -9.81);
  def.parts.push_back(testing::Box3("table", {-2, -1, -0.1}, {2, 1, 0}, true));
  def.parts.push_back(testing::Box3("base", {-0.5, -0.5, 0}, {0.5, 0.5, 0.2}));
  def.parts.push_back(testing::Box3("top", {-0.2, -0.2, 0.2}, {0.2, 0.2, 0.4}));
  def.parts.push_back(testing::Box3("side", {0.5, -0.2, 0}, {0.7, 0.2, 0.2}));
  const Assembly a = Assembly::Create(def);
  Configuration config = Configuration::Assembled(a);
  PairContactCache cache;
  const int top = a.FindPart("top");
  int compared = 0;
  for (int step = 0; step <= 12; ++step) {
    config.poses[top].translation = Vector3(0.05 * step, 0, 0);  // over base, then past its edge
    const std::vector<Contact> cold = DetectContacts(a, config, kTol, kAngle);
    const int hits_before = cache.hits();
    const std::vector<Contact> warm = DetectContacts(a, config, kTol, kAngle, nullptr, &cache);
    ASSERT_EQ(cold.size(), warm.size()) << "step " << step;
    for (size_t k = 0; k < cold.size(); ++k) {
      EXPECT_EQ(cold[k].part_a, warm[k].part_a);
      EXPECT_EQ(cold[k].part_b, warm[k].part_b);
      EXPECT_EQ(cold[k].p_WC, warm[k].p_WC);
      EXPECT_EQ(cold[k].n_W, warm[k].n_W);
      EXPECT_EQ(cold[k].gap, warm[k].gap);
      EXPECT_EQ(cold[k].feature, warm[k].feature);
      EXPECT_EQ(cold[k].index_a, warm[k].index_a);
      EXPECT_EQ(cold[k].index_b, warm[k].index_b);
      EXPECT_EQ(cold[k].patch, warm[k].patch);
      ++compared;
    }
    // From the second step on, every pair without the moved block is a hit:
    // base-table, side-table, base-side.
    if (step > 0) {
      EXPECT_EQ(cache.hits() - hits_before, 3) << "step " << step;
    }
  }
  EXPECT_GT(compared, 0);
}

}  // namespace
}  // namespace cairn

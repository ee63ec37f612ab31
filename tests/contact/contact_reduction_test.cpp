#include "cairn/contact/contact_reduction.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cairn/mechanics/contact_model.h"
#include "contact/reduced_lcp.h"

namespace cairn {
namespace {

using ::testing::ElementsAre;

constexpr double kG = 9.81;  // m/s²

// A contact of part 0 on the world at p, normal +z.
Contact At(double x, double y, double z = 0, double mu = 0.5, double gap = 0) {
  Contact c;
  c.part_a = 0;
  c.part_b = kWorld;
  c.p_WC = {x, y, z};
  c.n_W = {0, 0, 1};
  c.mu = mu;
  c.gap = gap;
  c.feature = ContactFeature::kFaceFace;
  c.patch = 0;
  return c;
}

// The unit square [−½, ½]²: corners (indices 0-3), edge midpoints (4-7),
// centre (8) and two interior points (9, 10).
std::vector<Contact> SquarePatch(double mu = 0.5) {
  return {At(-0.5, -0.5, 0, mu), At(0.5, -0.5, 0, mu), At(0.5, 0.5, 0, mu), At(-0.5, 0.5, 0, mu),
          At(0, -0.5, 0, mu),    At(0.5, 0, 0, mu),    At(0, 0.5, 0, mu),   At(-0.5, 0, 0, mu),
          At(0, 0, 0, mu),       At(0.2, -0.3, 0, mu), At(-0.1, 0.4, 0, mu)};
}

TEST(HullContactSubset, SquareKeepsItsFourCorners) {
  EXPECT_THAT(HullContactSubset(SquarePatch()), ElementsAre(0, 1, 2, 3));
}

TEST(HullContactSubset, CornersAnywhereInTheListAreFound) {
  std::vector<Contact> cs = SquarePatch();
  std::swap(cs[0], cs[8]);   // the centre first, a corner at 8
  std::swap(cs[2], cs[10]);  // an interior point at 2, a corner at 10
  EXPECT_THAT(HullContactSubset(cs), ElementsAre(1, 3, 8, 10));
}

TEST(HullContactSubset, EmptyAndSmallPatchesAreKept) {
  EXPECT_TRUE(HullContactSubset({}).empty());
  EXPECT_THAT(HullContactSubset({At(0, 0)}), ElementsAre(0));
  EXPECT_THAT(HullContactSubset({At(0, 0), At(1, 0)}), ElementsAre(0, 1));
}

TEST(HullContactSubset, CollinearPointsKeepTheirEnds) {
  // An edge lying on a face (or a 2-D edge contact): only the two ends.
  EXPECT_THAT(HullContactSubset({At(0.3, 0), At(0, 0), At(1, 0), At(0.7, 0)}), ElementsAre(1, 2));
}

TEST(HullContactSubset, RepeatedPointsKeepOne) {
  EXPECT_THAT(HullContactSubset({At(0, 0), At(0, 0), At(0, 0)}), ElementsAre(0));
}

TEST(HullContactSubset, PointsOffThePlaneAreKept) {
  std::vector<Contact> cs = SquarePatch();
  cs[8].p_WC.z() = 1e-3;  // the centre, 1 mm above the plane: its own patch
  EXPECT_THAT(HullContactSubset(cs), ElementsAre(0, 1, 2, 3, 8));
  // Within the length tolerance it is coplanar again.
  ContactReductionTolerances tol;
  tol.length = 2e-3;
  EXPECT_THAT(HullContactSubset(cs, tol), ElementsAre(0, 1, 2, 3));
}

TEST(HullContactSubset, DifferentNormalsMuGapsOrPartsAreNotOnePatch) {
  std::vector<Contact> cs = SquarePatch();
  cs[8].n_W = Vector3(0.01, 0, 1).normalized();
  cs[9].mu = 0.3;
  cs[10].gap = 1e-4;
  cs[4].part_b = 1;
  EXPECT_THAT(HullContactSubset(cs), ElementsAre(0, 1, 2, 3, 4, 8, 9, 10));
  // A gap tolerance merges the gap (for a caller that ignores gaps).
  ContactReductionTolerances tol;
  tol.gap = std::numeric_limits<double>::infinity();
  EXPECT_THAT(HullContactSubset(cs, tol), ElementsAre(0, 1, 2, 3, 4, 8, 9));
}

TEST(HullContactSubset, TwoPatchesOfOnePairReduceSeparately) {
  // The square at z = 0 and the same square at z = 1 (a part between two).
  std::vector<Contact> cs = SquarePatch();
  for (Contact c : SquarePatch()) {
    c.p_WC.z() = 1;
    cs.push_back(c);
  }
  EXPECT_THAT(HullContactSubset(cs), ElementsAre(0, 1, 2, 3, 11, 12, 13, 14));
}

TEST(HullContactSubset, RejectsNegativeTolerances) {
  ContactReductionTolerances tol;
  tol.length = -1;
  EXPECT_THROW(HullContactSubset(SquarePatch(), tol), std::invalid_argument);
}

// --- The LCP: the reduced solution, extended, solves the full LCP. ----------

// A 1 kg, 1 m cube whose bottom face is the square patch (centroid 0.5 m
// above it), pushed by a horizontal force F_x at height h above the centroid.
BodyDynamics Cube(double F_x, double h) {
  BodyDynamics b;
  b.part = 0;
  b.mass = 1;
  b.inertia = Matrix3::Identity() / 6.0;
  b.p_WBcm = {0, 0, 0.5};
  b.F_ext << F_x, 0, -kG, 0, F_x * h, 0;  // τ_y = h · F_x (r = h ẑ, F = F_x x̂)
  return b;
}

struct Outcome {
  bool extension_solves;
  double max_dropped_lambda;  // largest λ given to a dropped contact
  Vector6 nu;                 // the cube's motion
};

Outcome SolveReducedAndExtend(const BodyDynamics& body, Formulation formulation,
                              const std::vector<Contact>& contacts) {
  const ContactLcp full = BuildContactLcp(
      {body}, contacts, LcpBuildOptions{formulation, 0.01, false, LcpStorage::kDense, 3, 4});
  const std::vector<int> keep = HullContactSubset(contacts);
  std::vector<Contact> kept;
  for (int i : keep) kept.push_back(contacts[i]);
  const ContactLcp reduced = BuildContactLcp(
      {body}, kept, LcpBuildOptions{formulation, 0.01, false, LcpStorage::kDense, 3, 4});
  const LcpResult r = SolveContactLcp(reduced);
  EXPECT_EQ(r.status, LcpStatus::kSolved);
  const VectorX z = testing::ExtendReducedSolution(full, reduced, keep, r.z);
  Outcome o;
  o.extension_solves =
      IsContactLcpSolution(full, z, 1e-9 * std::max(1.0, full.q.cwiseAbs().maxCoeff()));
  o.max_dropped_lambda = 0;
  const int nc = static_cast<int>(contacts.size());
  for (int c = 0; c < nc; ++c) {
    const bool dropped = std::find(keep.begin(), keep.end(), c) == keep.end();
    if (dropped && full.friction_of[c] >= 0)
      o.max_dropped_lambda =
          std::max(o.max_dropped_lambda,
                   z[nc + full.num_directions * full.num_friction + full.friction_of[c]]);
  }
  o.nu = RecoverSolution(reduced, r.z).body_motion[0];
  return o;
}

TEST(HullContactSubsetLcp, AtRestTheExtensionSolvesTheFullLcp) {
  const Outcome o = SolveReducedAndExtend(Cube(0, 0), Formulation::kStewartTrinkle, SquarePatch());
  EXPECT_TRUE(o.extension_solves);
  EXPECT_LT(o.nu.norm(), 1e-9);  // gravity alone: the cube stays
}

TEST(HullContactSubsetLcp, SlidingNeedsLambdaAtTheDroppedPoints) {
  // F_x = 0.8 m g > μ m g (μ = 0.5), at the height of the centroid: it does
  // not tip (0.5 m · F_x < 0.5 m · m g about the leading edge), it slides;
  // d_0 = +x, so the pyramid is exact: v_x = (F_x − μ m g) Δt after one step.
  const Outcome o =
      SolveReducedAndExtend(Cube(0.8 * kG, 0), Formulation::kStewartTrinkle, SquarePatch());
  EXPECT_TRUE(o.extension_solves);
  EXPECT_NEAR(o.nu[0], 0.01 * (0.8 - 0.5) * kG, 1e-9);
  EXPECT_NEAR(o.nu[4], 0.0, 1e-9);
  EXPECT_GT(o.max_dropped_lambda, 0.0);  // the sliding speed at the dropped points
}

TEST(HullContactSubsetLcp, TippingOpensTheDroppedPoints) {
  // F_x = 9.81 N, 1 m above the centroid on a μ = 5 square (no sliding): the
  // moment 1.5 m · F_x about the leading bottom edge beats 0.5 m · m g.
  const Outcome o =
      SolveReducedAndExtend(Cube(kG, 1.0), Formulation::kStewartTrinkle, SquarePatch(/*mu=*/5.0));
  EXPECT_TRUE(o.extension_solves);
  EXPECT_GT(o.nu[4], 0.0);  // ω_y > 0: tipping over the +x edge
}

TEST(HullContactSubsetLcp, FrictionlessTippingToo) {
  const Outcome o =
      SolveReducedAndExtend(Cube(kG, 1.0), Formulation::kBaraff, SquarePatch(/*mu=*/0.0));
  EXPECT_TRUE(o.extension_solves);
  EXPECT_GT(o.nu.head<3>().x(), 0.0);  // pushed along +x, nothing holds it
}

TEST(HullContactSubsetLcp, DroppingAPointOutsideTheHullWouldNotBeExact) {
  // The check above can fail: keep only three corners of the tipping cube
  // (dropping the leading corner (0.5, 0.5), which is not inside their hull),
  // and the extension penetrates there.
  const std::vector<Contact> contacts = SquarePatch(5.0);
  const BodyDynamics body = Cube(kG, 1.0);
  const ContactLcp full = BuildContactLcp(
      {body}, contacts,
      LcpBuildOptions{Formulation::kStewartTrinkle, 0.01, false, LcpStorage::kDense, 3, 4});
  const std::vector<int> keep = {0, 1, 3};
  std::vector<Contact> kept;
  for (int i : keep) kept.push_back(contacts[i]);
  const ContactLcp reduced = BuildContactLcp(
      {body}, kept,
      LcpBuildOptions{Formulation::kStewartTrinkle, 0.01, false, LcpStorage::kDense, 3, 4});
  const LcpResult r = SolveContactLcp(reduced);
  ASSERT_EQ(r.status, LcpStatus::kSolved);
  const VectorX z = testing::ExtendReducedSolution(full, reduced, keep, r.z);
  EXPECT_FALSE(IsContactLcpSolution(full, z, 1e-9 * std::max(1.0, full.q.cwiseAbs().maxCoeff())));
}

}  // namespace
}  // namespace cairn

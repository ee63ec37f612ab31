// rest_solution.h: the rest hypothesis as a linear program. A block pulled
// across a fixed table (support "none") with nothing on it can keep every
// other part at rest: the LP finds an LCP solution whose normal impulses carry
// the block's weight over the step and whose friction is kinetic (μ p_n, all
// of it against the slip). A block riding on the pulled one cannot stay at
// rest: no solution. The LP's basis warm-starts the next one.
#include "cairn/mechanics/rest_solution.h"

#include <gtest/gtest.h>

#include "cairn/stability/analyze.h"
#include "pull_drive.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::Box3;

constexpr double kMu = 0.5, kG = 9.81, kDt = 0.1, kSpeed = 0.1;

// A (0.4 × 0.2 × 0.1 m, density 1: 8 kg) on a fixed table; with `rider`, B
// (0.2 m cube) on A.
Assembly Blocks(bool rider) {
  AssemblyDef def;
  def.friction = kMu;
  def.gravity = Vector3(0, 0, -kG);
  def.parts.push_back(Box3("table", {-1, -1, -0.1}, {1, 1, 0}, true));
  def.parts.push_back(Box3("A", {-0.2, -0.1, 0}, {0.2, 0.1, 0.1}));
  if (rider) def.parts.push_back(Box3("B", {-0.1, -0.1, 0.1}, {0.1, 0.1, 0.2}));
  return Assembly::Create(def);
}

// The Stewart–Trinkle LCP of A pulled along +x (guided), the rest judged;
// A moved `dx` along its path first.
ContactLcp PulledLcp(const Assembly& a, double dx = 0) {
  const DriveInputs d = testing::PullAlongX(a, a.FindPart("A"), kSpeed);
  StabilityOptions options;
  options.dt = kDt;
  Configuration config = Configuration::Assembled(a);
  config.poses[a.FindPart("A")].translation.x() += dx;
  const std::vector<ContactLcp> lcps = BuildComponentLcps(a, config, options, &d);
  EXPECT_EQ(lcps.size(), 1u);
  return lcps.at(0);
}

TEST(FindRestSolution, APulledBlockAloneSlidesWithKineticFrictionAndItsWeightCarried) {
  const Assembly a = Blocks(false);
  const ContactLcp lcp = PulledLcp(a);
  const RestSolution r = FindRestSolution(lcp);
  ASSERT_EQ(r.outcome, RestSolution::Outcome::kFound) << r.message;
  EXPECT_TRUE(IsContactLcpSolution(lcp, r.z, 1e-9));
  const int nc = static_cast<int>(lcp.contacts.size());
  const int nb = lcp.num_friction * lcp.num_directions;
  const double normal = r.z.head(nc).sum(), friction = r.z.segment(nc, nb).sum();
  const double weight_impulse = a.part(a.FindPart("A")).mass * kG * kDt;  // N·s
  EXPECT_NEAR(normal, weight_impulse, 1e-9 * weight_impulse);
  EXPECT_NEAR(friction, kMu * normal, 1e-9 * weight_impulse);
}

TEST(FindRestSolution, ABlockRidingOnThePulledOneCannotStayAtRest) {
  const RestSolution r = FindRestSolution(PulledLcp(Blocks(true)));
  EXPECT_EQ(r.outcome, RestSolution::Outcome::kNone) << r.message;
}

TEST(FindRestSolution, TheLastBasisWarmStartsTheSameLpWithTheSameAnswer) {
  const ContactLcp lcp = PulledLcp(Blocks(false));
  RestLpBasis basis;
  const RestSolution cold = FindRestSolution(lcp, &basis);
  ASSERT_EQ(cold.outcome, RestSolution::Outcome::kFound);
  EXPECT_FALSE(basis.cols.empty());
  const RestSolution warm = FindRestSolution(lcp, &basis);
  ASSERT_EQ(warm.outcome, RestSolution::Outcome::kFound);
  EXPECT_EQ(warm.iterations, 0);  // the optimal basis again
  EXPECT_LE((warm.z - cold.z).cwiseAbs().maxCoeff(), 1e-12 * cold.z.cwiseAbs().maxCoeff());
}

// The guided-free LP (the pulled block's own contacts solved first, its rows
// and forces then held) has another shape than the full one; started from
// the full LP's final basis, mapped by key, it gives the same answer as
// from scratch, in no more iterations.
TEST(FindRestSolution, ABasisOfAnotherShapeWarmStartsByKey) {
  const ContactLcp lcp = PulledLcp(Blocks(true));
  RestLpBasis basis;
  ASSERT_EQ(FindRestSolution(lcp, &basis).outcome, RestSolution::Outcome::kNone);
  ASSERT_EQ(basis.row_keys.size(), basis.rows.size());  // kept although infeasible
  const RestSolution cold = FindRestSolution(lcp, nullptr, RestHypothesis::kGuidedFree);
  RestLpBasis from_full = basis;
  const RestSolution warm = FindRestSolution(lcp, &from_full, RestHypothesis::kGuidedFree);
  ASSERT_EQ(warm.outcome, cold.outcome) << warm.message;
  EXPECT_LE(warm.iterations, cold.iterations);
  if (cold.outcome == RestSolution::Outcome::kFound) {
    EXPECT_TRUE(IsContactLcpSolution(lcp, warm.z, 1e-9));
    EXPECT_NEAR(warm.z.sum(), cold.z.sum(), 1e-9 * cold.z.cwiseAbs().sum());  // least total force
  }
  EXPECT_NE(from_full.rows.size(), basis.rows.size());  // another shape indeed
}

// Along a path the LP of the next tick has the same rows and columns, with
// the moved part's coefficients changed: the kept problem is updated in place
// (the same object), and its answer is the one a fresh LP gives: an LCP
// solution with the least total force, in no more iterations.
TEST(FindRestSolution, TheNextTicksLpIsTheKeptProblemUpdatedInPlace) {
  const Assembly a = Blocks(false);
  RestLpBasis basis;
  ASSERT_EQ(FindRestSolution(PulledLcp(a), &basis).outcome, RestSolution::Outcome::kFound);
  ASSERT_NE(basis.problem, nullptr);
  const RestLpProblem* kept = basis.problem.get();
  for (double dx : {0.01, 0.02, 0.05}) {
    const ContactLcp lcp = PulledLcp(a, dx);
    const RestSolution fresh = FindRestSolution(lcp);
    const RestSolution updated = FindRestSolution(lcp, &basis);
    ASSERT_EQ(updated.outcome, RestSolution::Outcome::kFound) << updated.message;
    EXPECT_EQ(basis.problem.get(), kept) << "dx " << dx;
    EXPECT_TRUE(IsContactLcpSolution(lcp, updated.z, 1e-9));
    EXPECT_NEAR(updated.z.sum(), fresh.z.sum(), 1e-9 * fresh.z.cwiseAbs().sum());
    EXPECT_LE(updated.iterations, fresh.iterations);
  }
  // A copy that solves an LP of another shape (the guided-free one) takes a
  // problem of its own and leaves the kept one to the original.
  RestLpBasis copy = basis;
  FindRestSolution(PulledLcp(Blocks(true)), &copy, RestHypothesis::kGuidedFree);
  EXPECT_NE(copy.problem.get(), kept);
  EXPECT_EQ(basis.problem.get(), kept);
}

}  // namespace
}  // namespace cairn

// The complete weak/strong search (mechanics/moving_solution.h) on cases
// whose LCP solutions are known by hand: two solutions (a block wedged
// between walls, a book held between two books: rest by a squeeze, or a
// slide), found in every order of the parts and the contacts; one solution at
// rest (a block on an incline below its friction angle, a ladder above its
// critical friction, a box on the ground): proved; no rest (the incline above
// its friction angle): a motion.
#include "cairn/mechanics/moving_solution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "cairn/io/compas_reader.h"
#include "cairn/mechanics/static_equilibrium.h"
#include "cairn/stability/analyze.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn::moving_solution_test {
namespace {

using testing::BlockOnIncline;
using testing::Box;
using testing::Box3;
using testing::JammedBlock;
using testing::Ladder;
using testing::LadderCriticalMu;
using testing::SharedDir;

ContactLcp OnlyComponent(const Assembly& a) {
  std::vector<ContactLcp> lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  EXPECT_EQ(lcps.size(), 1u);
  return std::move(lcps.at(0));
}

// The same LCP with its contacts in another order.
ContactLcp WithContactsIn(const ContactLcp& lcp, const std::vector<int>& order) {
  std::vector<Contact> contacts;
  for (int c : order) contacts.push_back(lcp.contacts[c]);
  return BuildContactLcp(lcp.bodies, std::move(contacts), lcp.build);
}

// The postconditions of a found motion: an LCP solution, in which gravity
// does positive work (so some body moves), and whose kinetic energy is the
// work less friction's dissipation (νᵀMν ≤ Δt Fᵀν).
void ExpectMoves(const ContactLcp& lcp, const MovingSolution& r) {
  ASSERT_EQ(r.outcome, MovingSolution::Outcome::kFound) << r.message;
  EXPECT_TRUE(IsContactLcpSolution(lcp, r.z, 1e-8));
  const ContactSolution s = RecoverSolution(lcp, r.z);
  double energy = 0, work = 0;
  for (size_t k = 0; k < lcp.bodies.size(); ++k) {
    const BodyDynamics& b = lcp.bodies[k];
    const Vector6& nu = s.body_motion[k];
    energy += b.mass * nu.head<3>().squaredNorm() + nu.tail<3>().dot(b.inertia * nu.tail<3>());
    work += lcp.dt * b.F_ext.dot(nu);
  }
  EXPECT_GT(work, r.power_scale * kMotionPowerFraction);
  EXPECT_NEAR(work / lcp.dt, r.power, 1e-6 * r.power_scale);
  EXPECT_LE(energy, work * (1 + 1e-6));
}

// Two books on a fixed shelf, a third held between them above the shelf,
// touching only their sides: a squeeze could hold it (an equilibrium), and
// it can slide down (a motion). Parts in the order `order` of {shelf, left,
// middle, right}.
AssemblyDef BookBetweenBooks(double mu, const std::vector<int>& order) {
  const std::vector<PartDef> parts = {Box("shelf", -1, -1, 4, 0, true), Box("left", 0, 0, 1, 1.5),
                                      Box("middle", 1, 0.3, 2, 1.3), Box("right", 2, 0, 3, 1.5)};
  AssemblyDef def;
  def.friction = mu;
  for (int k : order) def.parts.push_back(parts[k]);
  return def;
}

TEST(MovingSolution, TheWedgedBlockSlidesInEveryOrderOfItsContacts) {
  for (const double mu : {0.5, 2.0}) {
    const Assembly a = Assembly::Create(JammedBlock(mu), "jammed");
    const ContactLcp lcp = OnlyComponent(a);
    ASSERT_TRUE(FindStaticEquilibrium(lcp).exists);
    std::vector<int> order(lcp.contacts.size());
    std::iota(order.begin(), order.end(), 0);
    std::mt19937 shuffle(7);
    for (int trial = 0; trial < 6; ++trial) {
      const ContactLcp permuted = WithContactsIn(lcp, order);
      SCOPED_TRACE("mu " + std::to_string(mu) + ", order " + std::to_string(trial));
      ExpectMoves(permuted, SearchMovingSolution(permuted));
      std::shuffle(order.begin(), order.end(), shuffle);
    }
  }
}

TEST(MovingSolution, TheBookBetweenTwoBooksSlidesInEveryOrderOfPartsAndContacts) {
  std::vector<int> parts = {0, 1, 2, 3};
  do {
    const Assembly a = Assembly::Create(BookBetweenBooks(0.6, parts), "books");
    const ContactLcp lcp = OnlyComponent(a);
    ASSERT_TRUE(FindStaticEquilibrium(lcp).exists);
    std::vector<int> contacts(lcp.contacts.size());
    std::iota(contacts.begin(), contacts.end(), 0);
    std::reverse(contacts.begin(), contacts.end());
    for (const ContactLcp& each : {lcp, WithContactsIn(lcp, contacts)}) {
      const MovingSolution r = SearchMovingSolution(each);
      ExpectMoves(each, r);
      // The middle book moves down.
      const ContactSolution s = RecoverSolution(each, r.z);
      for (size_t k = 0; k < each.bodies.size(); ++k)
        if (a.part(each.bodies[k].part).name == "middle") {
          EXPECT_LT(s.body_motion[k].y(), 0);
        }
    }
  } while (std::next_permutation(parts.begin(), parts.end()));
}

// Below the friction angle the only solution is rest (the block sticks: any
// slide would need friction below μ N opposing it, and gravity's pull along
// the slope is less than that); the frictionless certificate cannot say so.
TEST(MovingSolution, ABlockOnAnInclineBelowItsFrictionAngleIsProvedAtRest) {
  for (const double mu : {0.3, 0.8}) {
    const double theta = std::atan(mu) - 0.05;
    const Assembly a = Assembly::Create(BlockOnIncline(theta, mu), "incline");
    const ContactLcp lcp = OnlyComponent(a);
    EquilibriumOptions frictionless;
    frictionless.frictionless = true;
    ASSERT_FALSE(FindStaticEquilibrium(lcp, frictionless).exists);
    const MovingSolution r = SearchMovingSolution(lcp);
    EXPECT_EQ(r.outcome, MovingSolution::Outcome::kNone) << "mu " << mu << ": " << r.message;
  }
}

TEST(MovingSolution, ABlockOnAnInclineAboveItsFrictionAngleSlides) {
  const double mu = 0.3, theta = std::atan(mu) + 0.05;
  const Assembly a = Assembly::Create(BlockOnIncline(theta, mu), "incline");
  const ContactLcp lcp = OnlyComponent(a);
  ExpectMoves(lcp, SearchMovingSolution(lcp));
}

// The ladder (frictionless wall, floor of friction μ) above its critical μ:
// it stands, and nothing moves in any solution.
TEST(MovingSolution, ALadderAboveItsCriticalFrictionIsProvedAtRest) {
  const double theta = 1.1, mu = 1.2 * LadderCriticalMu(theta);
  const Assembly a = Assembly::Create(Ladder(theta, mu), "ladder");
  const ContactLcp lcp = OnlyComponent(a);
  const MovingSolution r = SearchMovingSolution(lcp);
  EXPECT_EQ(r.outcome, MovingSolution::Outcome::kNone) << r.message;
}

TEST(MovingSolution, ABoxOnTheGroundIsProvedAtRestIn3D) {
  AssemblyDef def;
  def.friction = 0.5;
  def.gravity = Vector3(0, 0, -9.81);
  def.parts = {Box3("ground", {-2, -2, -1}, {2, 2, 0}, true), Box3("box", {0, 0, 0}, {1, 1, 1})};
  const Assembly a = Assembly::Create(def, "box");
  const ContactLcp lcp = OnlyComponent(a);
  const MovingSolution r = SearchMovingSolution(lcp);
  EXPECT_EQ(r.outcome, MovingSolution::Outcome::kNone) << r.message;
}

// A shared compas_cra model at μ, with the blocks `fixed` (by key) fixed and
// the blocks in reverse order when `reversed`: its one component's LCP and
// the assembly.
std::pair<Assembly, ContactLcp> CraComponent(const std::string& file, double mu,
                                             const std::vector<std::string>& fixed, bool reversed) {
  CompasOptions options;
  options.friction = mu;
  const std::string path = SharedDir() + "/datasets/compas_cra/" + file;
  CompasModel model = CompasToModel(ReadCompasAssembly(path), options, path);
  for (PartDef& p : model.def.parts)
    p.fixed = std::find(fixed.begin(), fixed.end(), p.name) != fixed.end();
  if (reversed) std::reverse(model.def.parts.begin(), model.def.parts.end());
  Assembly a = Assembly::Create(model.def, path);
  ContactLcp lcp = OnlyComponent(a);
  return {std::move(a), std::move(lcp)};
}

// The H frame (compas_cra, supports 0 and 1, μ 0.84): a bar between two
// posts, touching only their vertical faces. An equilibrium squeezes it; the
// search finds the other solution, in either order of the blocks: the bar
// slides straight down.
TEST(MovingSolution, TheHFramesBarSlidesDown) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  for (const bool reversed : {false, true}) {
    const auto [a, lcp] = CraComponent("H.json", 0.84, {"0", "1"}, reversed);
    ASSERT_TRUE(FindStaticEquilibrium(lcp).exists);
    const MovingSolution r = SearchMovingSolution(lcp);
    ExpectMoves(lcp, r);
    const ContactSolution s = RecoverSolution(lcp, r.z);
    for (size_t k = 0; k < lcp.bodies.size(); ++k) {
      const Vector6& nu = s.body_motion[k];
      if (a.part(lcp.bodies[k].part).name != "2") continue;
      EXPECT_LT(nu.z(), 0) << "the bar moves down";
      EXPECT_NEAR(nu.head<2>().norm(), 0, 1e-6 * std::abs(nu.z()));
      EXPECT_NEAR(nu.tail<3>().norm(), 0, 1e-6 * std::abs(nu.z()));
    }
  }
}

// The snake (compas_cra, support 0) at μ 0.7: an equilibrium exists and
// Lemke's method finds only rest; the check's search (its LCP in the
// canonical order, stability/analyze.h) finds a solution in which blocks move
// within its default budget: weakly stable, in either order of the blocks.
TEST(MovingSolution, TheSnakeAtMu07IsOnlyWeaklyStable) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  for (const bool reversed : {false, true}) {
    const auto [a, lcp] = CraComponent("snake.json", 0.7, {"0"}, reversed);
    const StabilityResult r = AnalyzeConfiguration(a, Configuration::Assembled(a));
    ASSERT_EQ(r.components.size(), 1u);
    EXPECT_EQ(r.components[0].search, std::optional(MovingSolution::Outcome::kFound));
    EXPECT_EQ(r.stability, StabilityProof::kWeak);
    EXPECT_FALSE(r.components[0].rigid_motion_parts.empty());
  }
}

// A budget too small to finish says so, with how far it got.
TEST(MovingSolution, ABudgetThatRunsOutSaysHowFarItGot) {
  const Assembly a = Assembly::Create(BookBetweenBooks(0.6, {0, 1, 2, 3}), "books");
  const ContactLcp lcp = OnlyComponent(a);
  MovingSearchOptions o;
  o.max_work = 1;
  const MovingSolution r = SearchMovingSolution(lcp, o);
  if (r.outcome == MovingSolution::Outcome::kFound) GTEST_SKIP() << "found at the root";
  EXPECT_EQ(r.outcome, MovingSolution::Outcome::kBudget);
  EXPECT_EQ(r.nodes, 1);
  EXPECT_GT(r.open, 0);
}

}  // namespace
}  // namespace cairn::moving_solution_test

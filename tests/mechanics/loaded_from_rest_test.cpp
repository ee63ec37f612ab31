// Loading from rest with compliant contacts (mechanics/loaded_from_rest.h)
// against hand derivations: a block on an incline, a wedge in a V notch
// (where the tangential stiffness decides the friction a rigid analysis
// leaves open), a block jammed between walls (an equilibrium exists, nothing
// produces it from rest), a box on the ground in 3-D; and the model's
// independence of the absolute stiffness.
#include "cairn/mechanics/loaded_from_rest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cairn/mechanics/static_equilibrium.h"
#include "cairn/stability/analyze.h"
#include "scene_builders.h"

namespace cairn::loaded_from_rest_test {
namespace {

using testing::BlockOnIncline;
using testing::Box3;
using testing::JammedBlock;

constexpr double kDeg = std::numbers::pi / 180.0;

ContactLcp OnlyComponent(const Assembly& a) {
  std::vector<ContactLcp> lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  EXPECT_EQ(lcps.size(), 1u);
  return std::move(lcps.at(0));
}

double Weight(const Assembly& a, int part) { return a.part(part).mass * a.gravity().norm(); }

// On an incline of angle θ the block stands iff tan θ < μ, as in the rigid
// analysis (one contact face: the rigid equilibrium is the compliant one),
// with N = W cos θ and F = W sin θ.
TEST(LoadedFromRest, ABlockOnAnInclineStandsIffTanThetaIsBelowMu) {
  for (const double mu : {0.3, 0.6}) {
    for (const double theta : {std::atan(mu) - 2 * kDeg, std::atan(mu) + 2 * kDeg}) {
      const Assembly a = Assembly::Create(BlockOnIncline(theta, mu), "incline");
      const LoadedFromRest r = LoadFromRest(OnlyComponent(a));
      const bool holds = std::tan(theta) < mu;
      ASSERT_EQ(r.outcome,
                holds ? LoadedFromRest::Outcome::kStands : LoadedFromRest::Outcome::kGivesWay)
          << "mu " << mu << " theta " << theta / kDeg << ": " << r.message;
      if (!holds) continue;
      const double W = Weight(a, 1);
      EXPECT_NEAR(r.normal_force.sum(), W * std::cos(theta), 1e-6 * W);
      Vector3 friction = Vector3::Zero();
      for (const Vector3& f : r.friction_force) friction += f;
      EXPECT_NEAR(friction.norm(), W * std::sin(theta), 1e-6 * W);
    }
  }
}

// A block that just fits between two walls: friction could hold it if the
// walls squeezed it, so a rigid equilibrium exists at any μ > 0; loaded from
// rest nothing squeezes it, at any μ: it gives way.
TEST(LoadedFromRest, ABlockJammedBetweenWallsGivesWayAtAnyFriction) {
  for (const double mu : {0.5, 2.0, 10.0}) {
    const Assembly a = Assembly::Create(JammedBlock(mu), "jammed");
    const ContactLcp lcp = OnlyComponent(a);
    const StaticEquilibrium eq = FindStaticEquilibrium(lcp);
    ASSERT_TRUE(eq.solved && eq.exists) << "mu " << mu;
    const LoadedFromRest r = LoadFromRest(lcp);
    EXPECT_EQ(r.outcome, LoadedFromRest::Outcome::kGivesWay) << "mu " << mu << ": " << r.message;
  }
}

// A wedge whose sides rest on the two faces of a V notch, each at α from the
// horizontal. Loaded from rest it sinks by δ: each face's springs are
// pressed by δ cos α (N = k_n δ cos α) and sheared by δ sin α along the face
// (T = k_t δ sin α, up the face) while they stick, that is while
// T / N = κ tan α ≤ μ (κ = k_t / k_n); beyond, they slip and T = μ N.
// Vertical balance, 2 (N cos α + T sin α) = W, gives
//     N = W / (2 (cos α + r sin α)),  r = min(κ tan α, μ).
// A rigid analysis leaves r anywhere in [0, μ]: the contacts' stiffness picks it.
AssemblyDef WedgeInNotch(double alpha, double mu) {
  const double t = std::tan(alpha), a = 0.5;
  AssemblyDef def;
  def.friction = mu;
  PartDef left, right, wedge;
  left.name = "left";
  left.fixed = true;
  left.polygon = {{-a - 5, -1}, {-a, -1}, {-a, 0}, {-a - 3 / t, 3}, {-a - 5, 3}};
  right.name = "right";
  right.fixed = true;
  right.polygon = {{a, -1}, {a + 5, -1}, {a + 5, 3}, {a + 3 / t, 3}, {a, 0}};
  wedge.name = "wedge";
  wedge.polygon = {
      {-a - 0.5 / t, 0.5}, {a + 0.5 / t, 0.5}, {a + 1.5 / t, 1.5}, {-a - 1.5 / t, 1.5}};
  def.parts = {left, right, wedge};
  return def;
}

TEST(LoadedFromRest, AWedgeInANotchTakesTheFrictionItsSpringsGiveIt) {
  const double alpha = 60 * kDeg;
  const double kappa = kTangentialStiffnessRatio;
  for (const double mu : {0.0, 0.84, 3.0}) {  // slips, slips, sticks (κ tan α = 1.54)
    const Assembly a = Assembly::Create(WedgeInNotch(alpha, mu), "wedge");
    const LoadedFromRest r = LoadFromRest(OnlyComponent(a));
    ASSERT_EQ(r.outcome, LoadedFromRest::Outcome::kStands) << "mu " << mu << ": " << r.message;
    const double W = Weight(a, 2);
    const double ratio = std::min(kappa * std::tan(alpha), mu);
    const double N = W / (2 * (std::cos(alpha) + ratio * std::sin(alpha)));
    EXPECT_NEAR(r.normal_force.sum(), 2 * N, 1e-4 * W) << "mu " << mu;
    double T = 0;
    for (const Vector3& f : r.friction_force) T += f.norm();
    EXPECT_NEAR(T, 2 * ratio * N, 1e-4 * W) << "mu " << mu;
    bool slips = false;
    for (bool s : r.slipping) slips = slips || s;
    // (Without friction there is nothing to slip: the LCP has no friction rows.)
    if (mu > 0) {
      EXPECT_EQ(slips, mu < kappa * std::tan(alpha)) << "mu " << mu;
    }
  }
}

// A box on the ground: its weight, on its four corners.
TEST(LoadedFromRest, ABoxOnTheGroundStandsOnItsWeight) {
  AssemblyDef def;
  def.friction = 0.5;
  def.parts = {Box3("ground", {-2, -2, -1}, {2, 2, 0}, true),
               Box3("box", {0, 0, 0}, {1, 0.5, 0.3})};
  const Assembly a = Assembly::Create(def, "box");
  const LoadedFromRest r = LoadFromRest(OnlyComponent(a));
  ASSERT_EQ(r.outcome, LoadedFromRest::Outcome::kStands) << r.message;
  const double W = Weight(a, 1);
  EXPECT_NEAR(r.normal_force.sum(), W, 1e-6 * W);
  EXPECT_LT(r.equilibrium_residual, 1e-5);
}

// Three boxes stacked in 3-D, each offset along x on the one below (an LCP
// of more than kMaxDenseLcp variables: solved in factored form). Stacked
// within the edges, it stands, each interface carrying the weight above it;
// with the top box's centroid past the edge of the one below, the top tips:
// it gives way, and the collapse step says the top box moves most.
TEST(LoadedFromRest, AStackOfBoxesStandsOrTipsByItsCentroids) {
  for (const double offset : {0.3, 0.7}) {
    SCOPED_TRACE(offset);
    AssemblyDef def;
    def.friction = 0.5;
    def.parts = {Box3("ground", {-3, -3, -1}, {3, 3, 0}, true), Box3("a", {0, 0, 0}, {1, 1, 0.5}),
                 Box3("b", {0.3, 0, 0.5}, {1.3, 1, 1}),
                 Box3("c", {0.3 + offset, 0, 1}, {1.3 + offset, 1, 1.5})};
    const Assembly a = Assembly::Create(def, "stack");
    const ContactLcp lcp = OnlyComponent(a);
    const LoadedFromRest r = LoadFromRest(lcp);
    ASSERT_GT(r.variables, kMaxDenseLcp);
    const double W = Weight(a, 1);  // the three weigh the same
    if (offset < 0.5) {             // c's centroid at 0.8 + offset over b's top [0.3, 1.3]
      ASSERT_EQ(r.outcome, LoadedFromRest::Outcome::kStands) << r.message;
      EXPECT_NEAR(r.normal_force.sum(), (3 + 2 + 1) * W, 1e-6 * W);
      EXPECT_LT(r.equilibrium_residual, 1e-6);
    } else {
      ASSERT_EQ(r.outcome, LoadedFromRest::Outcome::kGivesWay) << r.message;
      ASSERT_EQ(r.displacement.size(), 3u);
      int fastest = 0;
      for (int b = 0; b < 3; ++b)
        if (r.displacement[b].norm() > r.displacement[fastest].norm()) fastest = b;
      EXPECT_EQ(a.part(lcp.bodies[fastest].part).name, "c");
    }
  }
}

// Every stiffness × 10: the same outcome and the same forces (the problem is
// homogeneous in the stiffness); only the displacements shrink tenfold.
TEST(LoadedFromRest, NoAnswerDependsOnTheAbsoluteStiffness) {
  const Assembly wedge = Assembly::Create(WedgeInNotch(60 * kDeg, 0.84), "wedge");
  const Assembly jammed = Assembly::Create(JammedBlock(1.0), "jammed");
  for (const Assembly* a : {&wedge, &jammed}) {
    const ContactLcp lcp = OnlyComponent(*a);
    LoadFromRestOptions stiff;
    stiff.stiffness_scale = 10;
    const LoadedFromRest r1 = LoadFromRest(lcp), r10 = LoadFromRest(lcp, stiff);
    ASSERT_EQ(r1.outcome, r10.outcome) << a->name();
    if (r1.outcome != LoadedFromRest::Outcome::kStands) continue;
    const double W = r1.normal_force.sum();
    for (int c = 0; c < r1.normal_force.size(); ++c)
      EXPECT_NEAR(r1.normal_force[c], r10.normal_force[c], 1e-6 * W);
    EXPECT_NEAR((r1.displacement[0] - 10 * r10.displacement[0]).norm(), 0,
                1e-4 * r1.displacement[0].norm());
  }
}

// A conservative caller's options (LoadFromRestOptions::explain off, no
// retry after a ray): the tipping stack gives way at once, with no
// displacements, in no more pivots than the full answer.
TEST(LoadedFromRest, WithoutTheExplanationAGiveWayIsSaidAtOnce) {
  AssemblyDef def;
  def.friction = 0.5;
  def.parts = {Box3("ground", {-3, -3, -1}, {3, 3, 0}, true), Box3("a", {0, 0, 0}, {1, 1, 0.5}),
               Box3("b", {0.3, 0, 0.5}, {1.3, 1, 1}), Box3("c", {1.0, 0, 1}, {2.0, 1, 1.5})};
  const ContactLcp lcp = OnlyComponent(Assembly::Create(def, "stack"));
  LoadFromRestOptions quick;
  quick.explain = false;
  quick.lemke.retry_after_ray = false;
  const LoadedFromRest full = LoadFromRest(lcp), fast = LoadFromRest(lcp, quick);
  ASSERT_EQ(full.outcome, LoadedFromRest::Outcome::kGivesWay);
  ASSERT_EQ(fast.outcome, LoadedFromRest::Outcome::kGivesWay);
  EXPECT_FALSE(full.displacement.empty());
  EXPECT_TRUE(fast.displacement.empty());
  EXPECT_LE(fast.pivots, full.pivots);
}

}  // namespace
}  // namespace cairn::loaded_from_rest_test

// The static-equilibrium LP against analytic answers, and against the LCP's
// verdict where the two must agree (strong stability) and where they must not
// (a block jammed between two walls: weakly stable).
#include "cairn/mechanics/static_equilibrium.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cairn/stability/analyze.h"
#include "equilibrium_check.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::BlockOnIncline;
constexpr auto Check = testing::CheckWithEquilibrium;
using testing::Box;
using testing::JammedBlock;

constexpr double kDeg = std::numbers::pi / 180.0;

// On an incline an equilibrium exists iff tan θ ≤ μ, on both sides of the
// friction angle, and it agrees with the LCP.
TEST(StaticEquilibrium, BlockOnAnInclineHoldsIffTanThetaIsAtMostMu) {
  for (const double mu : {0.3, 0.6}) {
    const double critical = std::atan(mu);
    for (const double theta : {critical - 1 * kDeg, critical + 1 * kDeg}) {
      const StabilityResult r = Check(BlockOnIncline(theta, mu));
      ASSERT_TRUE(r.static_equilibrium.has_value()) << r.diagnostics;
      EXPECT_EQ(*r.static_equilibrium, std::tan(theta) <= mu) << "mu " << mu << " θ " << theta;
      EXPECT_EQ(r.stable(), *r.static_equilibrium);
      EXPECT_FALSE(r.weakly_stable);
    }
  }
}

// The LP's forces balance the block: on the incline, N = m g cos θ and
// F = m g sin θ (the only equilibrium's totals, whichever share of them the
// LP gives each corner).
TEST(StaticEquilibrium, ForcesOnAnInclineAreTheTextbookOnes) {
  const double theta = 20 * kDeg;
  const Assembly a = Assembly::Create(BlockOnIncline(theta, 0.5), "incline");
  const auto lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  ASSERT_EQ(lcps.size(), 1u);
  const StaticEquilibrium eq = FindStaticEquilibrium(lcps[0]);
  ASSERT_TRUE(eq.solved) << eq.message;
  ASSERT_TRUE(eq.exists);
  const double W = a.part(1).mass * a.gravity().norm();
  EXPECT_NEAR(eq.normal_force.sum(), W * std::cos(theta), 1e-9 * W);
  Vector3 friction = Vector3::Zero();
  for (const Vector3& f : eq.friction_force) friction += f;
  EXPECT_NEAR(friction.norm(), W * std::sin(theta), 1e-9 * W);
  EXPECT_LE(eq.residual, 1e-9 * W);
  // As the LCP's unknowns (impulses over Δt, λ = 0), it solves the LCP: the
  // fallback when Lemke's method fails (analyze.cpp).
  ASSERT_EQ(eq.lcp_z.size(), lcps[0].size());
  EXPECT_TRUE(IsContactLcpSolution(lcps[0], eq.lcp_z, 1e-9 * W));
  EXPECT_NEAR(eq.lcp_z.head(lcps[0].contacts.size()).sum(), W * std::cos(theta) * lcps[0].dt,
              1e-9 * W);
}

TEST(StaticEquilibrium, ABlockJammedBetweenTwoWallsIsWeaklyStable) {
  const StabilityResult r = Check(JammedBlock(0.5));
  EXPECT_EQ(r.verdict, Verdict::kUnstable) << r.diagnostics;
  ASSERT_TRUE(r.static_equilibrium.has_value());
  EXPECT_TRUE(*r.static_equilibrium);
  EXPECT_TRUE(r.weakly_stable);

  const StabilityResult frictionless = Check(JammedBlock(0.0));
  EXPECT_EQ(frictionless.verdict, Verdict::kUnstable);
  ASSERT_TRUE(frictionless.static_equilibrium.has_value());
  EXPECT_FALSE(*frictionless.static_equilibrium);
  EXPECT_FALSE(frictionless.weakly_stable);
}

// Statically indeterminate and stable: the 10 × 10 running-bond wall has an
// equilibrium (and the LCP agrees); without an end brick of the bottom
// course, the half brick above it has nothing to stand on: no equilibrium.
TEST(StaticEquilibrium, TheWallHasOneAndLosesItWithoutItsSupport) {
  const StabilityResult whole = Check(testing::RunningBondWall(10, 10));
  EXPECT_TRUE(whole.stable());
  ASSERT_TRUE(whole.static_equilibrium.has_value()) << whole.diagnostics;
  EXPECT_TRUE(*whole.static_equilibrium);

  const Assembly a = Assembly::Create(testing::RunningBondWall(4, 5), "wall");
  Configuration config = Configuration::Assembled(a);
  config.present[a.FindPart("r0_4")] = false;
  StabilityOptions options;
  options.check_equilibrium = true;
  const StabilityResult gap = AnalyzeConfiguration(a, config, options);
  ASSERT_TRUE(gap.static_equilibrium.has_value()) << gap.diagnostics;
  EXPECT_FALSE(*gap.static_equilibrium);
  EXPECT_FALSE(gap.weakly_stable);
}

// ---- What is proved about rest (stability/solve_component.h) ---------------

// Strong: a box on a table, with friction. The frictionless equilibrium (each
// corner carries part of the weight straight up) exists, so every solution of
// the Stewart–Trinkle LCP from rest is at rest (static_equilibrium.h).
// Not certified: a block on a 20° incline with μ = 0.5 > tan 20° = 0.364
// stands (Lemke's method finds it at rest, and an equilibrium exists), but
// only friction holds it: without friction the normal forces cannot balance
// the weight's component m g sin 20° along the slope, so the certificate does
// not apply. Rest is possible; that it is guaranteed is not proved.
// Weak: the block jammed between two walls (above) has an equilibrium and
// also falls. With no friction there is no equilibrium at all: none.
// The mechanism of a frictionless block on a 20° incline: the virtual motion
// of largest gravity power within |v_x|, |v_y| ≤ 1 that no contact resists
// (v_n ≥ 0) slides it straight down the slope (lifting off costs power,
// tipping about either lower corner raises the centroid), without turning.
TEST(Mechanism, AFrictionlessBlockOnAnInclineSlidesDownIt) {
  const double theta = 20 * kDeg;
  const Assembly a = Assembly::Create(BlockOnIncline(theta, 0.0), "incline");
  const auto lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  ASSERT_EQ(lcps.size(), 1u);
  EXPECT_FALSE(FindStaticEquilibrium(lcps[0]).exists);
  const Mechanism m = FindMechanism(lcps[0]);
  ASSERT_TRUE(m.found) << m.message;
  ASSERT_EQ(m.moving, std::vector<int>{0});
  const Vector3 v = m.nu[0].head<3>();
  const Vector3 down(std::cos(theta), -std::sin(theta), 0);
  EXPECT_NEAR(v.normalized().dot(down), 1.0, 1e-9) << v.transpose();
  EXPECT_NEAR(m.nu[0].tail<3>().norm(), 0.0, 1e-9);
  // Gravity's power along it: m g |v| sin θ.
  EXPECT_NEAR(m.power, a.part(1).mass * a.gravity().norm() * v.norm() * std::sin(theta), 1e-9);
  // With friction above the friction angle nothing is left to find.
  const Assembly held = Assembly::Create(BlockOnIncline(theta, 0.5), "incline");
  EXPECT_FALSE(FindMechanism(BuildComponentLcps(held, Configuration::Assembled(held))[0]).found);
}

// The frictionless equilibrium LP (the certificate) on the same block: none
// on the incline, one on the level.
TEST(StaticEquilibrium, FrictionlessOptionDropsTheFrictionColumns) {
  const Assembly a = Assembly::Create(BlockOnIncline(20 * kDeg, 0.5), "incline");
  const auto lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  EXPECT_TRUE(FindStaticEquilibrium(lcps[0]).exists);
  const StaticEquilibrium fl = FindStaticEquilibrium(lcps[0], {.frictionless = true});
  EXPECT_TRUE(fl.solved);
  EXPECT_FALSE(fl.exists);
  AssemblyDef table;
  table.friction = 0.5;
  table.parts = {Box("table", -3, -1, 3, 0, true), Box("box", -0.5, 0, 0.5, 1)};
  const Assembly level = Assembly::Create(table, "level");
  const StaticEquilibrium on_level = FindStaticEquilibrium(
      BuildComponentLcps(level, Configuration::Assembled(level))[0], {.frictionless = true});
  ASSERT_TRUE(on_level.exists);
  for (const Vector3& f : on_level.friction_force) EXPECT_EQ(f.norm(), 0.0);
}

}  // namespace
}  // namespace cairn

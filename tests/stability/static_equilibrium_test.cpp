// The static-equilibrium LP against analytic answers, and against the LCP's
// verdict where the two must agree (strong stability) and where they must not
// (a block jammed between two walls: weakly stable).
#include "cairn/mechanics/static_equilibrium.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cairn/stability/analyze.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::BlockOnIncline;
using testing::Box;

constexpr double kDeg = std::numbers::pi / 180.0;

StabilityResult Check(const AssemblyDef& def) {
  const Assembly a = Assembly::Create(def, "test");
  StabilityOptions options;
  options.check_equilibrium = true;
  return AnalyzeConfiguration(a, Configuration::Assembled(a), options);
}

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

// A block that just fits between two fixed walls, with nothing under it.
// Friction on the walls could hold it if they squeezed it (2 μ N ≥ m g for a
// large enough N), so an equilibrium exists; but nothing produces N from rest,
// so the contact LCP lets it fall: weakly stable. Without friction no
// equilibrium exists at all.
AssemblyDef JammedBlock(double mu) {
  AssemblyDef def;
  def.friction = mu;
  def.parts = {Box("left", -1, -2, 0, 2, true), Box("right", 1, -2, 2, 2, true),
               Box("block", 0, 0, 1, 1)};
  return def;
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

}  // namespace
}  // namespace cairn

// mechanics/margin_lp.h: the parametric equilibrium LP and the friction
// deficit LP, against closed forms on a block on a floor and on an incline.
#include "cairn/mechanics/margin_lp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cairn/stability/analyze.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::BlockOnIncline;
using testing::Box;

// The one component of a scene with one movable part.
ContactLcp OnlyComponent(const Assembly& a) {
  const std::vector<ContactLcp> lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  EXPECT_EQ(lcps.size(), 1u);
  return lcps.front();
}

// A 1 × 0.5 block on a floor, μ = 0.5: pushed sideways at its centroid it
// slides at s = μ m g (it would tip only at m g w / h = 2 m g); pushed down,
// the floor carries any push; no push of at least 10 m g is carried.
TEST(OptimizeLoadParameter, APushOnABlockSlidesAtMuTimesItsWeight) {
  AssemblyDef def;
  def.friction = 0.5;
  def.parts = {Box("floor", -2, -1, 3, 0, true), Box("block", 0, 0, 1, 0.5)};
  const Assembly a = Assembly::Create(def);
  const ContactLcp lcp = OnlyComponent(a);
  const double weight = a.part(1).mass * a.gravity().norm();
  const auto push = [&](const Vector3& d) {
    std::vector<Vector6> load(1, Vector6::Zero());
    load[0].head<3>() = d;  // at the centroid: no moment
    return load;
  };
  const LoadParameterResult side = OptimizeLoadParameter(lcp, push({1, 0, 0}), true, 0.0, false);
  ASSERT_EQ(side.status, LoadParameterResult::Status::kOptimal) << side.message;
  EXPECT_NEAR(side.value, 0.5 * weight, 1e-9 * weight);
  EXPECT_TRUE(side.equilibrium.exists);
  EXPECT_LE(side.equilibrium.residual, 1e-9 * weight);
  // Frictionless, the least push moves it.
  const LoadParameterResult smooth = OptimizeLoadParameter(lcp, push({1, 0, 0}), true, 0.0, true);
  ASSERT_EQ(smooth.status, LoadParameterResult::Status::kOptimal) << smooth.message;
  EXPECT_NEAR(smooth.value, 0.0, 1e-9 * weight);
  EXPECT_EQ(OptimizeLoadParameter(lcp, push({0, -1, 0}), true, 0.0, false).status,
            LoadParameterResult::Status::kUnbounded);
  EXPECT_EQ(OptimizeLoadParameter(lcp, push({1, 0, 0}), true, 10 * weight, false).status,
            LoadParameterResult::Status::kInfeasible);
  // Past the end the LP's dual motion is the block sliding along +x with the
  // lift of limit analysis' associated flow: every generator n + μ t of the
  // cone does no negative work, so it rises at slope μ (v_y = μ v_x).
  ASSERT_FALSE(side.motion.empty());
  EXPECT_GT(side.motion[0].x(), 0.0);
  EXPECT_NEAR(side.motion[0].y(), 0.5 * side.motion[0].x(), 1e-9 * side.motion[0].x());
  EXPECT_NEAR(side.motion[0][5], 0.0, 1e-9 * side.motion[0].x());  // no turn
}

// A block on a 20° incline at friction factor k (μ = 1 scaled by k): the
// deficit φ(k) is positive below tan 20° and zero from it on, where the
// equilibrium found needs a factor between tan 20° and k.
TEST(FrictionDeficitLp, TheDeficitVanishesAtTheTangentOfTheSlope) {
  const double theta = 20.0 * M_PI / 180.0, t = std::tan(theta);
  const Assembly a = Assembly::Create(BlockOnIncline(theta, 1.0));
  FrictionDeficitLp deficit(OnlyComponent(a));
  for (double k : {0.0, 0.5 * t, 0.99 * t}) {
    SCOPED_TRACE(k);
    const FrictionDeficit d = deficit.Solve(k);
    ASSERT_TRUE(d.solved) << d.message;
    EXPECT_GT(d.deficit, 0.0);
    EXPECT_FALSE(d.exists);
    EXPECT_LE(d.slope, 0.0);
  }
  for (double k : {1.001 * t, 2 * t}) {
    SCOPED_TRACE(k);
    const FrictionDeficit d = deficit.Solve(k);
    ASSERT_TRUE(d.solved) << d.message;
    EXPECT_NEAR(d.deficit, 0.0, 1e-9);
    ASSERT_TRUE(d.exists);
    // The factor its forces need (of μ = 1): at least tan 20° at one of the
    // block's two corners, at most k.
    const double use = FrictionUse(OnlyComponent(a), d.equilibrium);
    EXPECT_GE(use, t * (1 - 1e-9));
    EXPECT_LE(use, k * (1 + 1e-9));
  }
  EXPECT_EQ(deficit.lps(), 5);
}

TEST(WithFrictionFactor, ScalesEveryContactsMu) {
  const Assembly a = Assembly::Create(BlockOnIncline(0.3, 0.8));
  const ContactLcp lcp = OnlyComponent(a);
  const ContactLcp half = WithFrictionFactor(lcp, 0.5);
  ASSERT_EQ(half.contacts.size(), lcp.contacts.size());
  for (size_t c = 0; c < lcp.contacts.size(); ++c)
    EXPECT_EQ(half.contacts[c].mu, 0.5 * lcp.contacts[c].mu);
}

}  // namespace
}  // namespace cairn

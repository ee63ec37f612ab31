// The solve policy's proof of rest (solve_component.h): strong, weak or not
// certified, on hand-checked scenes.
#include "cairn/stability/solve_component.h"

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

constexpr double kOneDegree = std::numbers::pi / 180.0;

TEST(StabilityProof, ABoxOnATableIsStronglyStable) {
  AssemblyDef def;
  def.friction = 0.5;
  def.parts = {Box("table", -3, -1, 3, 0, true), Box("box", -0.5, 0, 0.5, 1)};
  const StabilityResult r = Check(def);
  EXPECT_EQ(r.verdict, Verdict::kStable) << r.diagnostics;
  EXPECT_EQ(r.stability, StabilityProof::kStrong);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].frictionless_equilibrium, std::optional<bool>(true));
  // Frictionless (Baraff) too: the equilibrium LP is then the certificate.
  def.friction = 0;
  const StabilityResult f = Check(def);
  EXPECT_EQ(f.formulation, Formulation::kBaraff);
  EXPECT_EQ(f.stability, StabilityProof::kStrong);
}

// The certificate cannot prove it (no frictionless equilibrium), the
// complete search can: below the friction angle no solution of the LCP
// slides, so rest is guaranteed without loading from rest.
TEST(StabilityProof, ABlockHeldByFrictionIsProvedStrongByTheSearch) {
  const StabilityResult r = Check(BlockOnIncline(20 * kOneDegree, 0.5));
  EXPECT_EQ(r.verdict, Verdict::kStable) << r.diagnostics;
  EXPECT_EQ(r.stability, StabilityProof::kStrong);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].frictionless_equilibrium, std::optional<bool>(false));
  EXPECT_EQ(r.components[0].search, std::optional(MovingSolution::Outcome::kNone));
  EXPECT_EQ(r.components[0].decided_by, DecidedBy::kLemke);
  EXPECT_FALSE(r.loaded_from_rest.has_value());
  // The rigid-block-equilibrium rule: an equilibrium is enough.
  StabilityOptions rbe;
  rbe.rule = VerdictRule::kEquilibrium;
  const Assembly a = Assembly::Create(BlockOnIncline(20 * kOneDegree, 0.5), "incline");
  const StabilityResult e = AnalyzeConfiguration(a, Configuration::Assembled(a), rbe);
  EXPECT_TRUE(e.stable());
  EXPECT_EQ(e.components[0].decided_by, DecidedBy::kLemke);
  EXPECT_FALSE(e.loaded_from_rest.has_value());
}

TEST(StabilityProof, JammingIsWeakAndNoEquilibriumIsNone) {
  const StabilityResult jammed = Check(JammedBlock(0.5));
  EXPECT_EQ(jammed.stability, StabilityProof::kWeak);
  EXPECT_EQ(jammed.components.at(0).stability, StabilityProof::kWeak);
  const StabilityResult falls = Check(JammedBlock(0.0));
  EXPECT_EQ(falls.stability, StabilityProof::kNone);
  EXPECT_EQ(falls.moving, std::vector<int>{2});
}
}  // namespace
}  // namespace cairn

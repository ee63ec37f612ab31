// The rest hypothesis (mechanics/rest_solution.h, StabilityOptions::rest_first):
// in driven 3-D analyses with friction, a solution that keeps every judged
// part at rest is looked for first (a linear program), Lemke's method is used
// only when there is none. Checked on two layers of Jenga blocks (the middle
// bottom block pulled out: the layer above can rest on the side blocks), on a
// block riding on a pulled one (nothing holds it: it is dragged along), and on
// examples/jenga.json with its plan.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "cairn/stability/analyze.h"
#include "failure_brief.h"
#include "pull_drive.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Box3;

constexpr double kH = 0.015, kW = 0.025, kL = 0.075, kGap = 0.0005, kMu = 0.5;

// Jenga blocks (metres) on a fixed table: `layers` layers of three, odd
// layers along x, even ones along y, 0.5 mm apart within a layer.
AssemblyDef Tower(int layers) {
  AssemblyDef def;
  def.name = "tower";
  def.friction = kMu;
  def.gravity = Vector3(0, 0, -9.81);
  def.parts.push_back(Box3("table", {-0.1, -0.1, -0.02}, {0.1, 0.1, 0}, true));
  for (int k = 1; k <= layers; ++k)
    for (int i = 1; i <= 3; ++i) {
      const double c = (i - 2) * (kW + kGap);
      const Vector3 lo = k % 2 ? Vector3(-kL / 2, c - kW / 2, (k - 1) * kH)
                               : Vector3(c - kW / 2, -kL / 2, (k - 1) * kH);
      const Vector3 hi =
          k % 2 ? Vector3(kL / 2, c + kW / 2, k * kH) : Vector3(c + kW / 2, kL / 2, k * kH);
      def.parts.push_back(Box3("L" + std::to_string(k) + "_" + std::to_string(i), lo, hi));
      def.parts.back().density = 600;
    }
  return def;
}

TEST(RestHypothesis, TheLayerAboveRestsOnTheSideBlocksWhileTheMiddleOneIsPulled) {
  const Assembly a = Assembly::Create(Tower(2));
  const int pulled = a.FindPart("L1_2");
  StabilityOptions options;
  options.dt = 0.04;
  const DriveInputs drive = testing::PullAlongX(a, pulled, 0.04);
  const StabilityResult r = AnalyzeConfiguration(a, Configuration::Assembled(a), options, &drive);
  ASSERT_EQ(r.verdict, Verdict::kStable) << r.diagnostics;
  EXPECT_TRUE(r.unsupported.empty());
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_TRUE(r.components[0].rest_solution);
  EXPECT_EQ(r.components[0].pivots, 0);
  // The pulled block slides on the table and under the layer above: kinetic
  // friction μ N against its motion at every one of those contacts.
  double drag = 0, weight_on_it = 0;
  for (const ContactReport& c : r.contacts) {
    const bool mine = c.contact.part_a == pulled || c.contact.part_b == pulled;
    if (!mine) {
      EXPECT_LE(c.friction_force.norm(), kMu * c.normal_force + 1e-9);
      continue;
    }
    // The force on the pulled block (a's force, negated when it is b).
    const double sign = c.contact.part_a == pulled ? 1.0 : -1.0;
    EXPECT_NEAR(c.friction_force.norm(), kMu * c.normal_force, 1e-9);
    drag += sign * c.friction_force.x();
    if (c.contact.part_b == pulled) weight_on_it += c.normal_force;
  }
  EXPECT_LT(drag, 0) << "friction opposes the pull";
  // What rests on the pulled block can be held by the side blocks' friction:
  // the least-force solution puts nothing on it.
  EXPECT_NEAR(weight_on_it, 0, 1e-9);
}

// B (0.2 m cube) resting on A (0.4 × 0.2 × 0.1 m) on a fixed table, μ = 0.5.
AssemblyDef BlockOnAPulledBlock() {
  AssemblyDef def;
  def.friction = kMu;
  def.gravity = Vector3(0, 0, -9.81);
  def.parts.push_back(Box3("table", {-1, -1, -0.1}, {1, 1, 0}, true));
  def.parts.push_back(Box3("A", {-0.2, -0.1, 0}, {0.2, 0.1, 0.1}));
  def.parts.push_back(Box3("B", {-0.1, -0.1, 0.1}, {0.1, 0.1, 0.2}));
  return def;
}

TEST(RestHypothesis, ABlockRidingOnThePulledOneIsDraggedAlong) {
  const Assembly a = Assembly::Create(BlockOnAPulledBlock());
  StabilityOptions options;
  options.dt = 0.1;
  const DriveInputs drive = testing::PullAlongX(a, a.FindPart("A"), 0.1);
  const StabilityResult r = AnalyzeConfiguration(a, Configuration::Assembled(a), options, &drive);
  // No forces hold B at rest on a sliding A: Lemke's method says how it moves.
  ASSERT_EQ(r.verdict, Verdict::kUnstable) << r.diagnostics;
  EXPECT_EQ(r.moving, std::vector<int>{a.FindPart("B")});
  EXPECT_FALSE(r.components.at(0).rest_solution);
  for (const PartMotion& m : r.parts) {
    if (m.part == a.FindPart("B")) {
      EXPECT_GT(m.linear.x(), 0);
    }
  }

  // The rest hypothesis alone says there is no rest.
  const std::vector<ContactLcp> lcps =
      BuildComponentLcps(a, Configuration::Assembled(a), options, &drive);
  ASSERT_EQ(lcps.size(), 1u);
  EXPECT_EQ(FindRestSolution(lcps[0]).outcome, RestSolution::Outcome::kNone);
}

TEST(RestHypothesis, OffItGivesLemkesAnswer) {
  // rest_first = false: Lemke's method only (whatever solution it finds, it
  // is checked); the same verdict on the dragged block.
  const Assembly a = Assembly::Create(BlockOnAPulledBlock());
  StabilityOptions options;
  options.dt = 0.1;
  options.rest_first = false;
  const DriveInputs drive = testing::PullAlongX(a, a.FindPart("A"), 0.1);
  const StabilityResult r = AnalyzeConfiguration(a, Configuration::Assembled(a), options, &drive);
  EXPECT_EQ(r.verdict, Verdict::kUnstable) << r.diagnostics;
  EXPECT_FALSE(r.components.at(0).rest_solution);
  EXPECT_EQ(r.components.at(0).lp_iterations, 0);
}

// examples/jenga.json: the tower stands, and the layer-9 middle block slides
// out with everything else at rest until it is nearly out: its last 1.9 mm
// between layers 8 and 10 can no longer hold its overhanging weight (tick 46
// of 50, 7.36 cm pulled of the 7.5 cm block).
TEST(RestHypothesis, JengaExampleStandsUntilThePulledBlockIsNearlyOut) {
  const Assembly a = ReadScene(testing::ExamplePath("jenga.json"));
  EXPECT_EQ(a.num_parts(), 55);
  EXPECT_TRUE(AnalyzeConfiguration(a, Configuration::Assembled(a)).stable());
  const Plan plan = ReadPlan(testing::ExamplePath("plans/jenga_pull_l9.plan.json"), a);
  ASSERT_EQ(plan.steps.size(), 1u);
  EXPECT_NEAR(plan.steps[0].Length() / (plan.speed * plan.dt), 50, 1e-9);
  const SimulationResult r = SimulatePlan(a, plan);
  ASSERT_TRUE(r.failure);
  const double pulled = r.failure->time * plan.speed;  // how far the block has come
  EXPECT_GT(pulled, 0.07) << testing::Brief(*r.failure);
  EXPECT_LT(pulled, kL + kGap + 1e-9) << testing::Brief(*r.failure);
  // The failure names what moves: the pulled block itself, whose
  // overhanging weight the gripper (support "none") must now carry; nothing
  // else moves, and it is decided, not a solver failure.
  EXPECT_EQ(r.failure->verdict, MotionVerdict::kUnsupported) << testing::Brief(*r.failure);
  EXPECT_EQ(r.failure->parts, std::vector<int>{a.FindPart("L09_2")}) << testing::Brief(*r.failure);
  EXPECT_EQ(testing::Brief(*r.failure).find("could not be solved"), std::string::npos);
}

}  // namespace
}  // namespace cairn

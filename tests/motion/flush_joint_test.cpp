// Flush joints: a block B is pushed (support "none": the gripper
// drives it along the path only, its weight rests on the parts under it) off
// its movable support S, across a gap, onto a fixed ledge L whose top is
// flush with S's; and back in assemble mode. In 2-D (examples/flush_joint.json
// and its plan) and in 3-D. The contact rule that makes the slide possible is
// the corner rule of DetectContacts (docs/contacts.md).
//
// The physics, with unit density and g = 1 (mass = area in 2-D, volume in
// 3-D): while B slides on S, kinetic friction μ_BS N_BS acts on S along B's
// motion, N_BS ≤ m_B g being the part of B's weight on S. The floor holds S
// with static friction up to μ_SF (m_S g + N_BS). S stays put when
//     μ_BS N_BS ≤ μ_SF (m_S g + N_BS)   for every N_BS ∈ [0, m_B g],
// i.e. (the left side grows faster) when μ_BS m_B ≤ μ_SF (m_S + m_B).
//  - Low friction under B (μ_BS = 0.1, μ_SF = 0.5): 0.1 m_B ≪ 0.5 (m_S + m_B):
//    S is never dragged; B is supported all the way (its centroid stays
//    between its contacts on S and on L, the gap being narrower than B), so
//    the plan is stable in both modes, provided B can slide over the joint.
//  - High friction under B (μ_BS = 0.8, μ_SF = 0.1): μ_BS m_B > μ_SF (m_S +
//    m_B) (2-D: 1.6 > 0.6; 3-D: 0.96 > 0.52): B drags S along with it. A
//    fixed wall W against S's far side (away from L) stops S when it is
//    dragged towards W, i.e. when B moves from L to S (assemble mode), and
//    not when B moves from S to L (disassembly: S slides into the gap). So
//    the disassembly is unstable (S slides towards L) and the assembly is
//    stable: a step that cannot be inverted (paper Section VIII). Without
//    the wall both are unstable (the control that shows the wall matters).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "failure_brief.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Box;
using testing::Box3;
using testing::ExamplePath;

constexpr double kJointGap = 0.5;  // between S and L (length)

// B [1, 3] on S [0, 4]; L from 4 + gap; the tops at 1 (2-D: y, 3-D: z).
AssemblyDef Scene(int dimension, double mu_bs, double mu_sf, bool wall, double gap = kJointGap) {
  AssemblyDef def;
  def.friction = mu_sf;
  def.friction_pairs = {{"B", "S", mu_bs}};
  const double l0 = 4 + gap;
  if (dimension == 2) {
    def.gravity = Vector3(0, -1, 0);
    def.parts = {Box("floor", -2, -1, 10, 0, true), Box("L", l0, 0, 9, 1, true),
                 Box("S", 0, 0, 4, 1), Box("B", 1, 1, 3, 2)};
    if (wall) def.parts.push_back(Box("W", -1, 0, 0, 2, true));
  } else {
    def.gravity = Vector3(0, 0, -1);
    def.parts = {Box3("floor", {-2, -1, -1}, {10, 2, 0}, true),
                 Box3("L", {l0, 0, 0}, {9, 1, 1}, true), Box3("S", {0, 0, 0}, {4, 1, 1}),
                 Box3("B", {1, 0.2, 1}, {3, 0.8, 2})};
    if (wall) def.parts.push_back(Box3("W", {-1, 0, 0}, {0, 1, 2}, true));
  }
  return def;
}

// B pushed 4 along +x (from S onto L), support "none", in steps of 0.25: its
// lower-right corner reaches L's corner exactly at tick 6 (x = 4.5), its
// lower-left corner S's corner at tick 12 (x = 4).
Plan Slide(const Assembly& a, PlanMode mode) {
  PlanDef def;
  def.mode = mode;
  def.dt = 0.25;
  PlanStepDef s;
  s.remove = {"B"};
  s.has_direction = true;
  s.direction = Vector3(1, 0, 0);
  s.distance = 4;
  s.support = SupportMode::kNone;
  def.steps = {s};
  return Plan::Create(def, a);
}

std::string Explain(const SimulationResult& r) {
  return r.failure ? testing::Brief(*r.failure) : r.diagnostics;
}

TEST(FlushJoint, TheExampleSlideIsStableInBothModes) {
  const Assembly a = ReadScene(ExamplePath("flush_joint.json"));
  const Plan plan = ReadPlan(ExamplePath("plans/flush_joint_slide.plan.json"), a);
  const SimulationResult r = SimulatePlan(a, plan);
  EXPECT_EQ(r.verdict, MotionVerdict::kStable) << Explain(r);
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].ticks, 17);  // 16 moves of 0.25, and the end
  const SimulationResult back = SimulatePlan(a, Slide(a, PlanMode::kAssemble));
  EXPECT_EQ(back.verdict, MotionVerdict::kStable) << Explain(back);
}

// examples/flush_joint_wall.json is the non-invertible variant below (2-D):
// pulling B out drags S into the gap at the first move; putting B in drags
// S against the wall W, which holds it.
TEST(FlushJoint, TheExampleWithTheWallIsStableOnlyInAssembleMode) {
  const Assembly a = ReadScene(ExamplePath("flush_joint_wall.json"));
  const SimulationResult out =
      SimulatePlan(a, ReadPlan(ExamplePath("plans/flush_joint_wall_slide.plan.json"), a));
  ASSERT_EQ(out.verdict, MotionVerdict::kUnstable) << Explain(out);
  EXPECT_EQ(out.failure->parts, std::vector<int>{a.FindPart("S")});
  EXPECT_EQ(out.failure->tick, 1);
  const SimulationResult in =
      SimulatePlan(a, ReadPlan(ExamplePath("plans/flush_joint_wall_insert.plan.json"), a));
  EXPECT_EQ(in.verdict, MotionVerdict::kStable) << Explain(in);
}

class FlushJointIn : public ::testing::TestWithParam<int> {};

// With and without the gap (without it, B's corner meets S's and L's at a
// vertex of three parts when it reaches the joint).
TEST_P(FlushJointIn, LowFrictionUnderTheBlockSlidesAcrossInBothModes) {
  for (double gap : {kJointGap, 0.0}) {
    const Assembly a = Assembly::Create(Scene(GetParam(), 0.1, 0.5, false, gap));
    for (PlanMode mode : {PlanMode::kDisassemble, PlanMode::kAssemble}) {
      SCOPED_TRACE(std::string(mode == PlanMode::kAssemble ? "assemble" : "disassemble") +
                   ", gap " + std::to_string(gap));
      const SimulationResult r = SimulatePlan(a, Slide(a, mode));
      EXPECT_EQ(r.verdict, MotionVerdict::kStable) << Explain(r);
      ASSERT_EQ(r.steps.size(), 1u);
      // Assembling, one more: the block let go where it arrived.
      EXPECT_EQ(r.steps[0].ticks, mode == PlanMode::kAssemble ? 18 : 17);
    }
  }
}

// The same slide with the wall, and enough friction under B to drag S.
TEST_P(FlushJointIn, AWallBehindTheSupportMakesTheSlideNonInvertible) {
  const Assembly a = Assembly::Create(Scene(GetParam(), 0.8, 0.1, true));
  const int S = a.FindPart("S");
  const SimulationResult out = SimulatePlan(a, Slide(a, PlanMode::kDisassemble));
  ASSERT_EQ(out.verdict, MotionVerdict::kUnstable) << Explain(out);
  ASSERT_TRUE(out.failure);
  EXPECT_EQ(out.failure->parts, std::vector<int>{S});
  // Dragged at the first move, before B reaches the joint (tick 6).
  EXPECT_LE(out.failure->tick, 1);
  ASSERT_FALSE(out.failure->motions.empty());
  EXPECT_GT(out.failure->motions[0].linear.x(), 0.0) << "S slides towards L, with B";
  const SimulationResult in = SimulatePlan(a, Slide(a, PlanMode::kAssemble));
  EXPECT_EQ(in.verdict, MotionVerdict::kStable) << Explain(in);
}

// The control: without the wall, the assembly drags S away from L.
TEST_P(FlushJointIn, WithoutTheWallTheAssemblyDragsTheSupportToo) {
  const Assembly a = Assembly::Create(Scene(GetParam(), 0.8, 0.1, false));
  const SimulationResult in = SimulatePlan(a, Slide(a, PlanMode::kAssemble));
  ASSERT_EQ(in.verdict, MotionVerdict::kUnstable) << Explain(in);
  ASSERT_TRUE(in.failure);
  EXPECT_EQ(in.failure->parts, std::vector<int>{a.FindPart("S")});
  ASSERT_FALSE(in.failure->motions.empty());
  EXPECT_LT(in.failure->motions[0].linear.x(), 0.0) << "S slides away from L, with B";
}

// Without the gap, L itself stops S in the disassembly (S pushes on L's side
// face), and the wall in the assembly: both directions are stable.
TEST_P(FlushJointIn, WithoutAGapTheLedgeStopsTheSupportAndBothModesAreStable) {
  const Assembly a = Assembly::Create(Scene(GetParam(), 0.8, 0.1, true, 0.0));
  for (PlanMode mode : {PlanMode::kDisassemble, PlanMode::kAssemble}) {
    SCOPED_TRACE(mode == PlanMode::kAssemble ? "assemble" : "disassemble");
    const SimulationResult r = SimulatePlan(a, Slide(a, mode));
    EXPECT_EQ(r.verdict, MotionVerdict::kStable) << Explain(r);
  }
}

INSTANTIATE_TEST_SUITE_P(Dimension, FlushJointIn, ::testing::Values(2, 3),
                         [](const ::testing::TestParamInfo<int>& p) {
                           return p.param == 2 ? "2D" : "3D";
                         });

}  // namespace
}  // namespace cairn

#include "cairn/motion/simulate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "failure_brief.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Box;
using testing::ExamplePath;

// One step removing `part` along a straight path.
PlanStepDef Straight(const std::string& part, Vector2 direction, double distance,
                     SupportMode support = SupportMode::kFull) {
  PlanStepDef s;
  s.remove = {part};
  s.has_direction = true;
  s.direction = Embed(direction);
  s.distance = distance;
  s.support = support;
  return s;
}

Plan MakePlan(const Assembly& a, std::vector<PlanStepDef> steps, double dt = 1.0,
              PlanMode mode = PlanMode::kDisassemble) {
  PlanDef def;
  def.dt = dt;
  def.mode = mode;
  def.steps = std::move(steps);
  return Plan::Create(def, a);
}

// A T-stand: pedestal P on a table, plank B on P, block C on B's middle.
// Sliding C right with its weight on B (support "none") tips B once the
// centroid of B and C passes P's right edge (eq. 8): x_C · m_C / (m_B + m_C)
// > 0.5, i.e. x_C > 0.5 (m_B + m_C) / m_C = 1.1.
Assembly TStand() {
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  def.parts = {Box("table", -5, -1, 5, 0, true), Box("P", -0.5, 0, 0.5, 1), Box("B", -3, 1, 3, 1.2),
               Box("C", -0.5, 1.2, 0.5, 2.2)};
  return Assembly::Create(def);
}

TEST(Simulate, SlidingAPartOnANarrowBaseTipsItWhereEquationEightSays) {
  const Assembly a = TStand();
  const SimulationResult r =
      SimulatePlan(a, MakePlan(a, {Straight("C", {1, 0}, 2.5, SupportMode::kNone)}, 0.05));
  ASSERT_EQ(r.verdict, MotionVerdict::kUnstable) << r.diagnostics;
  ASSERT_TRUE(r.failure);
  // The first tick past x_C = 1.1 (ticks of 0.05).
  EXPECT_NEAR(r.failure->time, 1.15, 1e-9);
  EXPECT_EQ(r.failure->parts, std::vector<int>{a.FindPart("B")});
  ASSERT_FALSE(r.failure->motions.empty());
  EXPECT_EQ(r.failure->motions[0].kind, MotionKind::kTips);
  EXPECT_LT(r.failure->motions[0].angular.z(), 0.0) << "B tips clockwise";
  // C's weight tips B (Proposition 3), C sinking with it; the gripper's
  // motion (along x, tangent to the contact) pushes nothing.
  EXPECT_TRUE(r.failure->pushed.empty()) << testing::Brief(*r.failure);
}

// A plank O on the pedestal P (x in [-0.5, 0.5]) reaching right, its
// centroid at x = 0.7 past P's edge: alone it tips clockwise. The block K on
// its left end brings the pair's centroid to (0.8 · 0.7 + 1 · (-0.8)) / 1.8
// = -0.13, over P: together they stand.
Assembly Counterweighted() {
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  def.parts = {Box("table", -5, -1, 5, 0, true), Box("P", -0.5, 0, 0.5, 1),
               Box("O", -1.3, 1, 2.7, 1.2), Box("K", -1.3, 1.2, -0.3, 2.2)};
  return Assembly::Create(def);
}

PlanStepDef Held(PlanStepDef step, std::vector<std::string> hold,
                 std::optional<std::vector<std::string>> at_rest = std::nullopt) {
  step.hold = std::move(hold);
  if (at_rest) step.hold_at_rest = *at_rest, step.has_hold_at_rest = true;
  return step;
}

TEST(Simulate, AssembledPartsAreCheckedWhenLetGoAndHoldsKeepThemInPlace) {
  const Assembly a = Counterweighted();
  const int O = a.FindPart("O");
  // Assembling O then K (the file lists K's step first): O tips when the
  // gripper lets go of it on P.
  const SimulationResult bare = SimulatePlan(
      a,
      MakePlan(a, {Straight("K", {0, 1}, 2), Straight("O", {0, 1}, 2)}, 1.0, PlanMode::kAssemble));
  ASSERT_EQ(bare.verdict, MotionVerdict::kUnstable);
  EXPECT_EQ(bare.failure->step, 1);
  EXPECT_TRUE(bare.failure->released) << testing::Brief(*bare.failure);
  EXPECT_EQ(bare.failure->parts, std::vector<int>{O});
  ASSERT_FALSE(bare.failure->motions.empty());
  EXPECT_EQ(bare.failure->motions[0].kind, MotionKind::kTips);
  EXPECT_LT(bare.failure->motions[0].angular.z(), 0.0) << "O tips clockwise";
  // O kept in its gripper when it arrives, and held while K comes in; K
  // let go with O let go too: every state stands.
  const SimulationResult held =
      SimulatePlan(a, MakePlan(a,
                               {Held(Straight("K", {0, 1}, 2), {"O"}, std::vector<std::string>{}),
                                Held(Straight("O", {0, 1}, 2), {}, std::vector<std::string>{"O"})},
                               1.0, PlanMode::kAssemble));
  EXPECT_EQ(held.verdict, MotionVerdict::kStable)
      << (held.failure ? testing::Brief(*held.failure) : std::string());
  // The hold let go before K arrives: O tips as K's step starts.
  const SimulationResult early =
      SimulatePlan(a, MakePlan(a,
                               {Straight("K", {0, 1}, 2),
                                Held(Straight("O", {0, 1}, 2), {}, std::vector<std::string>{"O"})},
                               1.0, PlanMode::kAssemble));
  ASSERT_EQ(early.verdict, MotionVerdict::kUnstable);
  EXPECT_EQ(early.failure->step, 0);
  EXPECT_FALSE(early.failure->released);
  EXPECT_EQ(early.failure->parts, std::vector<int>{O});
  // A prop under O's right end instead of the hold: O stands on P and the
  // prop when let go; with the prop taken out before K comes, it tips.
  PlanStepDef o_propped = Straight("O", {0, 1}, 2);
  o_propped.props_at_rest = {{"O", {2.5, 1, 0}, {0, 1, 0}}};
  o_propped.has_props_at_rest = true;
  PlanStepDef k_propped = Straight("K", {0, 1}, 2);
  k_propped.props = o_propped.props_at_rest;
  k_propped.has_props_at_rest = true;  // props_at_rest []: let go with K in place
  const SimulationResult propped =
      SimulatePlan(a, MakePlan(a, {k_propped, o_propped}, 1.0, PlanMode::kAssemble));
  EXPECT_EQ(propped.verdict, MotionVerdict::kStable)
      << (propped.failure ? testing::Brief(*propped.failure) : std::string());
  const SimulationResult unpropped =
      SimulatePlan(a, MakePlan(a, {Straight("K", {0, 1}, 2), o_propped}, 1.0, PlanMode::kAssemble));
  ASSERT_EQ(unpropped.verdict, MotionVerdict::kUnstable);
  EXPECT_EQ(unpropped.failure->step, 0);
  EXPECT_EQ(unpropped.failure->parts, std::vector<int>{O});
  // Disassembling, K lifted off tips O unless O is held while K leaves.
  const SimulationResult lift = SimulatePlan(a, MakePlan(a, {Straight("K", {0, 1}, 2)}));
  ASSERT_EQ(lift.verdict, MotionVerdict::kUnstable);
  EXPECT_EQ(lift.failure->parts, std::vector<int>{O});
  const SimulationResult lift_held =
      SimulatePlan(a, MakePlan(a, {Held(Straight("K", {0, 1}, 2), {"O"})}));
  EXPECT_EQ(lift_held.verdict, MotionVerdict::kStable)
      << (lift_held.failure ? testing::Brief(*lift_held.failure) : std::string());
}

TEST(Simulate, WithTheWeightCarriedEveryPathIsStable) {
  // Proposition 2: support "full" makes the same path stable to the end.
  const Assembly a = TStand();
  const SimulationResult r =
      SimulatePlan(a, MakePlan(a, {Straight("C", {1, 0}, 2.5, SupportMode::kFull)}, 0.05));
  EXPECT_EQ(r.verdict, MotionVerdict::kStable)
      << (r.failure ? testing::Brief(*r.failure) : std::string());
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].ticks, 51);
  EXPECT_GT(r.steps[0].warm_starts, 0) << "consecutive ticks reuse the LCP basis";
}

TEST(Simulate, PaperFig1_DCBAIsStableAndLiftingCFirstTopplesBWhenCLeaves) {
  const Assembly a = ReadScene(ExamplePath("paper_fig1.json"));
  std::vector<PlanStepDef> dcba;
  for (const char* p : {"D", "C", "B", "A"}) dcba.push_back(Straight(p, {0, 1}, 6));
  const SimulationResult ok = SimulatePlan(a, MakePlan(a, dcba));
  EXPECT_EQ(ok.verdict, MotionVerdict::kStable)
      << (ok.failure ? testing::Brief(*ok.failure) : std::string());
  EXPECT_EQ(ok.steps.size(), 4u);

  const SimulationResult c_first = SimulatePlan(a, MakePlan(a, {Straight("C", {0, 1}, 6)}));
  ASSERT_EQ(c_first.verdict, MotionVerdict::kUnstable);
  // At 0 s C still rests on B; at 1 s it has left and B topples.
  EXPECT_EQ(c_first.failure->tick, 1);
  EXPECT_NEAR(c_first.failure->time, 1.0, 1e-12);
  EXPECT_NE(
      std::find(c_first.failure->parts.begin(), c_first.failure->parts.end(), a.FindPart("B")),
      c_first.failure->parts.end());
}

TEST(Simulate, PaperFig4_LiftingAMakesBSlideRightUnlessTwoFixelsHoldIt) {
  const Assembly a = ReadScene(ExamplePath("paper_fig4.json"));
  const SimulationResult r = SimulatePlan(a, MakePlan(a, {Straight("A", {0, 1}, 4)}));
  ASSERT_EQ(r.verdict, MotionVerdict::kUnstable);
  bool b_slides_right = false;
  for (const PartMotion& m : r.failure->motions)
    if (m.part == a.FindPart("B")) b_slides_right = m.linear.x() > 0;
  EXPECT_TRUE(b_slides_right) << testing::Brief(*r.failure);

  const Assembly f = ReadScene(ExamplePath("paper_fig4_fixels.json"));
  const SimulationResult held = SimulatePlan(f, MakePlan(f, {Straight("A", {0, 1}, 4)}));
  EXPECT_EQ(held.verdict, MotionVerdict::kStable)
      << (held.failure ? testing::Brief(*held.failure) : std::string());
}

TEST(Simulate, DrivingAPartIntoAWallIsInfeasible) {
  AssemblyDef def;
  def.parts = {Box("floor", -5, -1, 5, 0, true), Box("wall", 3, 0, 4, 3, true),
               Box("block", 0, 0, 1, 1)};
  const Assembly a = Assembly::Create(def);
  const SimulationResult r = SimulatePlan(a, MakePlan(a, {Straight("block", {1, 0}, 4)}, 0.5));
  ASSERT_EQ(r.verdict, MotionVerdict::kInfeasible);
  // The block's right face reaches the wall (x = 3) after 2 s, still driven
  // towards it: no contact force allows that motion (jammed).
  EXPECT_NEAR(r.failure->time, 2.0, 1e-12);
  EXPECT_EQ(r.failure->parts, (std::vector<int>{2}));
}

// Paper Fig. 1 with B lifted first: C and D rest on B and are
// free, so B pushes them up from the first instant: unstable at t = 0 (not
// "B runs into C"), C and D riding up with B at the gripper's velocity
// (analytic: a part resting on a rigidly lifted one, frictionless, moves with
// it), A (under B) left at rest.
TEST(Simulate, PaperFig1_LiftingBFirstPushesCAndDFromTheFirstInstant) {
  const Assembly a = ReadScene(ExamplePath("paper_fig1.json"));
  const Plan plan = ReadPlan(ExamplePath("plans/paper_fig1_b_first.plan.json"), a);
  const SimulationResult r = SimulatePlan(a, plan);
  ASSERT_EQ(r.verdict, MotionVerdict::kUnstable)
      << (r.failure ? testing::Brief(*r.failure) : std::string());
  EXPECT_EQ(r.failure->tick, 0);
  EXPECT_EQ(r.failure->time, 0.0);
  const int C = a.FindPart("C"), D = a.FindPart("D");
  EXPECT_EQ(r.failure->parts, (std::vector<int>{C, D}));
  EXPECT_EQ(r.failure->pushed, (std::vector<int>{C, D}));
  for (const int p : {C, D}) {
    const auto m = std::find_if(r.failure->motions.begin(), r.failure->motions.end(),
                                [&](const PartMotion& pm) { return pm.part == p; });
    ASSERT_NE(m, r.failure->motions.end()) << a.part(p).name;
    EXPECT_NEAR(m->linear.y(), plan.speed, 1e-6) << a.part(p).name << " rides up with B";
    EXPECT_NEAR(m->linear.x(), 0.0, 1e-6);
    EXPECT_NEAR(m->angular.z(), 0.0, 1e-6);
  }
  EXPECT_EQ(r.failure->pushers, (std::vector<int>{a.FindPart("B")}));  // "B pushes C, D"
}

// A free block in a driven block's way, reached between two ticks, is
// pushed from the moment they touch (bisection: the gap 1.5 at speed 1 closes
// at t = 1.5 s, between the ticks at 1 s and 2 s), moving with the pusher;
// the same block fixed cannot give way: infeasible, as is a fixed wall.
TEST(Simulate, AFreePartInTheWayIsPushedAFixedOneBlocks) {
  for (const bool fixed : {false, true}) {
    AssemblyDef def;
    def.parts = {Box("floor", -5, -1, 9, 0, true), Box("mover", 0, 0, 1, 1),
                 Box("box", 2.5, 0, 3.5, 1, fixed)};
    const Assembly a = Assembly::Create(def);
    const int mover = a.FindPart("mover"), box = a.FindPart("box");
    const SimulationResult r = SimulatePlan(a, MakePlan(a, {Straight("mover", {1, 0}, 4)}, 1.0));
    ASSERT_TRUE(r.failure.has_value()) << (fixed ? "fixed" : "free");
    const MotionFailure& f = *r.failure;
    EXPECT_EQ(f.tick, 2) << testing::Brief(f);
    if (fixed) {
      EXPECT_EQ(r.verdict, MotionVerdict::kInfeasible) << testing::Brief(f);
      EXPECT_EQ(f.parts, (std::vector<int>{mover, box}));
      EXPECT_TRUE(f.pushed.empty());
      continue;
    }
    EXPECT_EQ(r.verdict, MotionVerdict::kUnstable) << testing::Brief(f);
    EXPECT_EQ(f.parts, (std::vector<int>{box}));
    EXPECT_EQ(f.pushed, (std::vector<int>{box}));
    // Touch at 1.5 s; overlap beyond the length tolerance a moment later.
    EXPECT_NEAR(f.time, 1.5, 1e-4) << testing::Brief(f);
    EXPECT_GE(f.time, 1.5);
    ASSERT_EQ(f.motions.size(), 1u);
    EXPECT_EQ(f.motions[0].part, box);
    EXPECT_NEAR(f.motions[0].linear.x(), 1.0, 1e-12);
    EXPECT_EQ(f.pushers, (std::vector<int>{mover}));  // "mover pushes box"
  }
}

// Paper Fig. 19–20: μ = 0.2 between A and B, 0.05 between B and the floor,
// frictionless wall on B's left. Dragging A right with its weight on B drags B
// (unstable); the same path as an assembly, A coming in from the right, pushes
// B against the wall (stable): assembly and disassembly are not inverses.
Assembly Fig19() {
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  def.friction_pairs = {{"A", "B", 0.2}, {"B", "floor", 0.05}};
  def.parts = {Box("floor", -2, -1, 10, 0, true), Box("wall", -2, 0, 0, 3, true),
               Box("B", 0, 0, 2, 1), Box("A", 0, 1, 2, 2)};
  return Assembly::Create(def);
}

TEST(Simulate, PaperFig19_FrictionMakesAssemblyAndDisassemblyNonInvertible) {
  // The path keeps A's centroid over B (x ≤ 1.8 < 2), so A rests on B all
  // along it: with support "none" A is never unsupported, in either direction.
  const Assembly a = Fig19();
  const SimulationResult out =
      SimulatePlan(a, MakePlan(a, {Straight("A", {1, 0}, 0.8, SupportMode::kNone)}, 0.2));
  ASSERT_EQ(out.verdict, MotionVerdict::kUnstable)
      << (out.failure ? testing::Brief(*out.failure) : std::string());
  EXPECT_EQ(out.failure->parts, std::vector<int>{a.FindPart("B")});
  EXPECT_GT(out.failure->motions[0].linear.x(), 0.0) << "B is dragged to the right";

  const SimulationResult in = SimulatePlan(
      a, MakePlan(a, {Straight("A", {1, 0}, 0.8, SupportMode::kNone)}, 0.2, PlanMode::kAssemble));
  EXPECT_EQ(in.steps[0].ticks, 6);  // 5 along the path, then A let go in place
  EXPECT_EQ(in.verdict, MotionVerdict::kStable)
      << (in.failure ? testing::Brief(*in.failure) : std::string()) << in.diagnostics;
}

TEST(Simulate, AGrippedToolPushesACarriedPartAndIsNeverJudged) {
  // A pusher pad T (a tool: not part of the assembly) touches block X's left
  // face; gripping T and moving it right pushes X (removed, not gripped) along.
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  PartDef pad = Box("T", -0.5, 0.2, 0, 0.8);
  pad.tool = true;
  def.parts = {Box("floor", -5, -1, 10, 0, true), Box("X", 0, 0, 1, 1), pad, Box("Y", 6, 0, 7, 1)};
  const Assembly a = Assembly::Create(def);
  EXPECT_FALSE(Configuration::Assembled(a).present[a.FindPart("T")]) << "tools start absent";
  PlanStepDef s = Straight("X", {1, 0}, 3);
  s.grip = {"T"};
  SimulationOptions opt;
  opt.record_timeline = true;
  const SimulationResult r = SimulatePlan(a, MakePlan(a, {s}, 0.5), opt);
  EXPECT_EQ(r.verdict, MotionVerdict::kStable)
      << (r.failure ? testing::Brief(*r.failure) : std::string());
  // The pad pushed X all the way: at the last tick T and X still touch at x = 3.
  bool touching_at_end = false;
  for (const TimelineRow& row : r.timeline)
    if (row.time == 3.0 && row.contact.contact.part_b == a.FindPart("T"))
      touching_at_end = std::abs(row.contact.contact.p_WC.x() - 3.0) < 1e-6;
  EXPECT_TRUE(touching_at_end);
}

TEST(Simulate, DeterministicTwice) {
  const Assembly a = Fig19();
  const Plan plan = MakePlan(a, {Straight("A", {1, 0}, 4, SupportMode::kNone)}, 0.25);
  SimulationOptions opt;
  opt.record_timeline = true;
  opt.continue_after_failure = true;
  const SimulationResult r1 = SimulatePlan(a, plan, opt), r2 = SimulatePlan(a, plan, opt);
  ASSERT_EQ(r1.timeline.size(), r2.timeline.size());
  for (size_t i = 0; i < r1.timeline.size(); ++i) {
    EXPECT_EQ(r1.timeline[i].contact.normal_force, r2.timeline[i].contact.normal_force);
    EXPECT_EQ(r1.timeline[i].contact.friction_force, r2.timeline[i].contact.friction_force);
  }
}

}  // namespace
}  // namespace cairn

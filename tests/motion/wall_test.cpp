// Algorithm 1 on the 100-brick running-bond wall (105 parts in one contact
// component, a Stewart–Trinkle LCP of ~2280 variables at every tick).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::ExamplePath;

Plan PullRight(const Assembly& a, const std::string& part, SupportMode support) {
  PlanDef def;
  def.dt = 0.04;
  PlanStepDef s;
  s.remove = {part};
  s.has_direction = true;
  s.direction = Vector3(1, 0, 0);
  s.distance = 2;
  s.support = support;
  def.steps = {s};
  return Plan::Create(def, a);
}

int Course(const Assembly& a, int part) { return std::stoi(a.part(part).name.substr(1)); }

// Pulling the end brick of course 4 out along its course drags the bricks
// resting on it by friction (μ = 0.6) at the first move: they slide right,
// along with the bricks stacked on them; nothing below course 5 moves.
// The half brick r5_10 rests on the pulled brick alone and must move: the
// kinetic drag on it, μ (W + N'), exceeds any hold μ N' the brick above it
// can give (N' its load). r5_9, which spans the pulled brick and its
// neighbour r4_8, need not: the contact LCP with friction also has solutions
// in which r4_8 carries enough of it to hold it (weight shared unequally
// along its base), and which solution Lemke's method returns depends on its
// pivoting, so it is not asserted.
TEST(Wall, PullingAnEndBrickOutDragsTheBricksAboveIt) {
  const Assembly a = ReadScene(ExamplePath("wall.json"));
  ASSERT_EQ(a.num_parts(), 106);
  for (const char* plan : {"wall_pull_r4_9.plan.json", "wall_pull_r4_9_full.plan.json"}) {
    SCOPED_TRACE(plan);
    const SimulationResult r =
        SimulatePlan(a, ReadPlan(ExamplePath(std::string("plans/") + plan), a));
    ASSERT_EQ(r.verdict, MotionVerdict::kUnstable) << r.diagnostics;
    ASSERT_TRUE(r.failure);
    EXPECT_EQ(r.failure->tick, 1);
    EXPECT_NEAR(r.failure->time, 0.04, 1e-12);
    ASSERT_FALSE(r.failure->parts.empty());
    const auto moved = [&](const std::string& name) {
      const int i = a.FindPart(name);
      return std::find(r.failure->parts.begin(), r.failure->parts.end(), i) !=
             r.failure->parts.end();
    };
    EXPECT_TRUE(moved("r5_10"));  // the half brick resting on it alone
    for (int p : r.failure->parts) EXPECT_GE(Course(a, p), 5) << a.part(p).name;
    for (const PartMotion& m : r.failure->motions) {
      EXPECT_EQ(m.kind, MotionKind::kSlides) << a.part(m.part).name;
      EXPECT_GT(m.linear.x(), 0.0) << a.part(m.part).name;
    }
  }
}

// The half brick at the top of the end face (r9_10, 1 × 1 on r8_9 alone) can
// be pulled out with its weight carried: the friction it drags r8_9 with,
// μ m g = 5.9, is less than what holds r8_9 (μ times the weight on it), so the
// whole path is stable. Resting its weight on the wall instead (support
// "none", pushed at its centroid), friction μ N at its base, h/2 = 0.5 below
// the push, tips it forward about the wall's end edge x = 20 once the normal
// force, which can act no further forward than that edge, no longer balances
// it: (20 − x_c) N < μ N h/2, i.e. x_c > 19.7, after 0.2 of travel (the first
// tick past it, 0.24, or the one at it, 0.20, within roundoff).
TEST(Wall, ThePathOfTheTopHalfBrickIsStableCarriedAndUnsupportedPastTheEdge) {
  const Assembly a = ReadScene(ExamplePath("wall.json"));
  const SimulationResult full = SimulatePlan(a, PullRight(a, "r9_10", SupportMode::kFull));
  EXPECT_EQ(full.verdict, MotionVerdict::kStable) << full.diagnostics;
  ASSERT_EQ(full.steps.size(), 1u);
  EXPECT_EQ(full.steps[0].ticks, 51);

  const SimulationResult none = SimulatePlan(a, PullRight(a, "r9_10", SupportMode::kNone));
  ASSERT_EQ(none.verdict, MotionVerdict::kUnsupported) << none.diagnostics;
  ASSERT_TRUE(none.failure);
  EXPECT_GE(none.failure->time, 0.2 - 1e-9);
  EXPECT_LE(none.failure->time, 0.24 + 1e-9);
  EXPECT_EQ(none.failure->parts, std::vector<int>{a.FindPart("r9_10")});
}

// Determinism over a whole path of the big component.
TEST(Wall, TheSameSimulationTwiceGivesIdenticalResults) {
  const Assembly a = ReadScene(ExamplePath("wall.json"));
  const Plan plan = PullRight(a, "r9_10", SupportMode::kFull);
  SimulationOptions options;
  options.record_timeline = true;
  const SimulationResult r1 = SimulatePlan(a, plan, options);
  const SimulationResult r2 = SimulatePlan(a, plan, options);
  ASSERT_EQ(r1.timeline.size(), r2.timeline.size());
  EXPECT_EQ(r1.steps[0].pivots, r2.steps[0].pivots);
  for (size_t i = 0; i < r1.timeline.size(); ++i) {
    EXPECT_EQ(r1.timeline[i].contact.normal_force, r2.timeline[i].contact.normal_force) << i;
    EXPECT_EQ(r1.timeline[i].contact.friction_force, r2.timeline[i].contact.friction_force) << i;
  }
}

}  // namespace
}  // namespace cairn

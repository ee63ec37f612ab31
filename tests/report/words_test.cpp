// words.h: Cairn's results in words, phrased only by the report stage from the
// structured results of the stages below (PartMotion, MotionFailure,
// PathTrial, FixtureSuggestion).
#include "cairn/report/words.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "example_scene.h"

namespace cairn {
namespace {

// A failure at `step`, tick 0, t = 0, of `verdict` with `parts`.
MotionFailure Failure(MotionVerdict verdict, int step, std::vector<int> parts) {
  MotionFailure f;
  f.verdict = verdict;
  f.step = step;
  f.tick = 0;
  f.parts = std::move(parts);
  return f;
}

PartMotion Tipping(const Vector3& pivot, const Vector3& angular) {
  PartMotion m;
  m.moving = true;
  m.kind = MotionKind::kTips;
  m.pivot = pivot;
  m.angular = angular;
  return m;
}

TEST(DescribeMotion, TipsAboutAPivotWithItsSenseIn2D) {
  EXPECT_EQ(DescribeMotion(Tipping({1, 1.25, 0}, {0, 0, -2}), 2), "tips about (1, 1.25) clockwise");
  EXPECT_EQ(DescribeMotion(Tipping({1, 1.25, 0}, {0, 0, 3}), 2),
            "tips about (1, 1.25) counter-clockwise");
}

TEST(DescribeMotion, TipsAboutAnAxisIn3DAndSlidesAlongAUnitDirection) {
  EXPECT_EQ(DescribeMotion(Tipping({0, 2, 1}, {0, 0, 5}), 3),
            "tips about the axis through (0, 2, 1) along (0, 0, 1)");
  PartMotion slide;
  slide.moving = true;
  slide.kind = MotionKind::kSlides;
  slide.linear = Vector3(3, 4, 1e-20);  // dust prints as 0
  EXPECT_EQ(DescribeMotion(slide, 3), "slides along (0.6, 0.8, 0)");
  // With gravity: more than 15° off the horizontal, down or up; less, not.
  const Vector3 g(0, 0, -9.81);
  EXPECT_EQ(DescribeMotion(slide, 3, g), "slides along (0.6, 0.8, 0)");
  slide.linear = Vector3(0.6, 0, -0.8);
  EXPECT_EQ(DescribeMotion(slide, 3, g), "slides down along (0.6, 0, -0.8)");
  slide.linear = Vector3(0.6, 0, 0.8);
  EXPECT_EQ(DescribeMotion(slide, 3, g), "slides up along (0.6, 0, 0.8)");
  slide.linear = Vector3(0.99, 0, -0.14);  // 8° down
  EXPECT_EQ(DescribeMotion(slide, 3, g), DescribeMotion(slide, 3));
  EXPECT_EQ(DescribeMotion(PartMotion{}, 2), "at rest");
}

// Paper Fig. 1 with B lifted before C: B pushes C from the first instant.
TEST(DescribeFailure, NamesWhoPushesWhomAndHowEachPartMoves) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  const Plan plan = ReadPlan(testing::ExamplePath("plans/paper_fig1_b_first.plan.json"), a);
  const SimulationResult r = SimulatePlan(a, plan);
  ASSERT_TRUE(r.failure);
  const std::string words = DescribeFailure(a, *r.failure);
  // C and D ride up with B (analytic: parts resting on a rigidly lifted one).
  EXPECT_EQ(words,
            "t = 0 s (step 1, tick 0): B pushes C, D: C slides up along (0, 1); D slides up along "
            "(0, 1)");
  EXPECT_EQ(r.failure->step, 0);  // the index counts from 0, the words from 1

  MotionFailure noted = *r.failure;
  noted.solver_note = "a ray";
  EXPECT_EQ(DescribeFailure(a, noted), words + "; the contact LCP could not be solved: a ray");
}

TEST(DescribeFailure, InfeasibleAndUnsupportedSteps) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  MotionFailure f;
  f.verdict = MotionVerdict::kInfeasible;
  f.step = 1;
  f.tick = 3;
  f.time = 0.25;
  f.parts = {a.FindPart("B"), a.FindPart("C")};
  EXPECT_EQ(DescribeFailure(a, f), "t = 0.25 s (step 2, tick 3): B runs into C");
  f.verdict = MotionVerdict::kUnsupported;
  f.parts = {a.FindPart("B")};
  EXPECT_EQ(DescribeFailure(a, f),
            "t = 0.25 s (step 2, tick 3): B can no longer rest on the assembly: the gripper must "
            "carry it here");
}

TEST(PathTrialFailure, SaysWhichDirectionFailedOrWhyNoPathCanHelp) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  PathTrial t;
  EXPECT_EQ(PathTrialFailure(a, t), "");
  t.decided_by = "proposition 1";
  EXPECT_EQ(PathTrialFailure(a, t), "the rest does not stand without the removed parts");
  t.decided_by = "simulation";
  t.failure = Failure(MotionVerdict::kInfeasible, 0, {a.FindPart("B")});
  t.failure_mode = PlanMode::kAssemble;
  EXPECT_EQ(PathTrialFailure(a, t),
            "assembly: t = 0 s (step 1, tick 0): the motion of B is blocked");
}

TEST(FixtureMessage, FoundNoneNeededOrWhereAndWhyTheSearchStopped) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Assembly& a = fig1.assembly;
  FixtureSuggestion s;
  s.found = true;
  EXPECT_EQ(FixtureMessage(a, s), "the plan is stable without fixels");
  s.fixels.resize(1);
  EXPECT_EQ(FixtureMessage(a, s), "1 fixel makes the plan stable");
  s.fixels.resize(2);
  EXPECT_EQ(FixtureMessage(a, s), "2 fixels make the plan stable");
  s = FixtureSuggestion{};
  s.stopped_at = Failure(MotionVerdict::kInfeasible, 2, {a.FindPart("C")});
  s.stop_reason = " is infeasible: fixels cannot free a blocked motion";
  EXPECT_EQ(FixtureMessage(a, s),
            "no fixels found: step 3 (t = 0 s (step 3, tick 0): the motion of C is blocked) is "
            "infeasible: fixels cannot free a blocked motion");
}

}  // namespace
}  // namespace cairn

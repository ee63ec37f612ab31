// Fixel suggestions (planning/fixtures.h): the paper's Figs. 4-5, a part
// that needs two fixels where one cannot hold it (forces checked against the
// statics), and the cases fixels cannot help.
#include "cairn/planning/fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "example_scene.h"
#include "failure_brief.h"

namespace cairn {
namespace {

using Scene = testing::ExampleScene;
using testing::ExamplePath;

// The largest normal force of fixture `index` over a run's timeline, and
// over its last tick only.
double MaxFixtureForce(const SimulationResult& r, int index) {
  double most = 0;
  for (const TimelineRow& row : r.timeline)
    if (row.contact.contact.feature == ContactFeature::kFixture &&
        row.contact.contact.index_a == index)
      most = std::max(most, row.contact.normal_force);
  return most;
}
double LastFixtureForce(const SimulationResult& r, int index) {
  double f = -1;
  for (const TimelineRow& row : r.timeline)
    if (row.time == r.timeline.back().time &&
        row.contact.contact.feature == ContactFeature::kFixture &&
        row.contact.contact.index_a == index)
      f = row.contact.normal_force;
  return f;
}

// ---------------------------------------------------------------------------
// Paper Figs. 4-5: lifting A makes B slide right (and C tip); fixels on B's
// right face (the edge x = 7 from (7, 0) to (7, 3)) pushing left hold it.

TEST(SuggestFixtures, PaperFig4_FixelsOnBsRightFaceMakeTheLiftStable) {
  const Scene s("paper_fig4.json");
  const Plan plan = ReadPlan(ExamplePath("plans/paper_fig4_lift_a.plan.json"), s.assembly);
  const SimulationResult failed = SimulatePlan(s.assembly, plan);
  ASSERT_EQ(failed.verdict, MotionVerdict::kUnstable);
  const int b = s.assembly.FindPart("B");

  const FixtureSuggestion fx = SuggestFixtures(s.def, s.assembly, plan, failed);
  ASSERT_TRUE(fx.found) << fx.stop_reason;
  ASSERT_FALSE(fx.fixels.empty());
  EXPECT_LE(fx.fixels.size(), 2u);  // the paper uses two; fewer is better
  for (const SuggestedFixel& f : fx.fixels) {
    EXPECT_EQ(f.part, b);
    EXPECT_EQ(f.fixture.part, "B");
    EXPECT_EQ(f.step, 0);
    EXPECT_DOUBLE_EQ(f.fixture.point.x(), 7.0);
    EXPECT_GE(f.fixture.point.y(), 0.0);
    EXPECT_LE(f.fixture.point.y(), 3.0);
    EXPECT_DOUBLE_EQ(f.fixture.normal.x(), -1.0);
    EXPECT_DOUBLE_EQ(f.fixture.normal.y(), 0.0);
    EXPECT_NE(f.face.find("(7, 0)-(7, 3)"), std::string::npos) << f.face;
  }
  EXPECT_TRUE(fx.verification.stable()) << testing::Brief(*fx.verification.failure);
  EXPECT_GT(fx.candidates, 0);
  EXPECT_GE(fx.simulations, 2);  // the run with the timeline, then one per subset tried

  // Re-run independently on the scene with the fixels: stable, and each
  // fixel's greatest force is what that timeline shows (and positive: it
  // carries B's push to the right).
  AssemblyDef with = s.def;
  for (const SuggestedFixel& f : fx.fixels) with.fixtures.push_back(f.fixture);
  const Assembly a2 = Assembly::Create(with);
  SimulationOptions timeline;
  timeline.record_timeline = true;
  const SimulationResult rerun = SimulatePlan(a2, plan, timeline);
  EXPECT_TRUE(rerun.stable());
  for (size_t i = 0; i < fx.fixels.size(); ++i) {
    EXPECT_GT(fx.fixels[i].max_force, 0.0);
    EXPECT_DOUBLE_EQ(fx.fixels[i].max_force, MaxFixtureForce(rerun, static_cast<int>(i)));
    EXPECT_DOUBLE_EQ(fx.fixels[i].max_force, MaxFixtureForce(fx.verification, static_cast<int>(i)));
  }
}

TEST(SuggestFixtures, PaperFig4_PapersOwnFixelsNeedNoMore) {
  // examples/paper_fig4_fixels.json has the paper's two fixels: stable, so
  // nothing is suggested and nothing simulated.
  const Scene s("paper_fig4_fixels.json");
  const Plan plan = ReadPlan(ExamplePath("plans/paper_fig4_lift_a.plan.json"), s.assembly);
  const SimulationResult r = SimulatePlan(s.assembly, plan);
  ASSERT_TRUE(r.stable());
  const FixtureSuggestion fx = SuggestFixtures(s.def, s.assembly, plan, r);
  EXPECT_TRUE(fx.found);
  EXPECT_TRUE(fx.fixels.empty());
  EXPECT_EQ(fx.simulations, 0);
  EXPECT_TRUE(fx.verification.stable());
  EXPECT_FALSE(fx.stopped_at);
  EXPECT_EQ(fx.stop_reason, "");
}

TEST(SuggestFixtures, PaperFig4_Deterministic) {
  const Scene s("paper_fig4.json");
  const Plan plan = ReadPlan(ExamplePath("plans/paper_fig4_lift_a.plan.json"), s.assembly);
  const SimulationResult failed = SimulatePlan(s.assembly, plan);
  const FixtureSuggestion x = SuggestFixtures(s.def, s.assembly, plan, failed);
  const FixtureSuggestion y = SuggestFixtures(s.def, s.assembly, plan, failed);
  ASSERT_EQ(x.fixels.size(), y.fixels.size());
  for (size_t i = 0; i < x.fixels.size(); ++i) {
    EXPECT_EQ(x.fixels[i].fixture.point, y.fixels[i].fixture.point);
    EXPECT_EQ(x.fixels[i].fixture.normal, y.fixels[i].fixture.normal);
    EXPECT_EQ(x.fixels[i].max_force, y.fixels[i].max_force);  // bit for bit
    EXPECT_EQ(x.fixels[i].face, y.fixels[i].face);
  }
  EXPECT_EQ(x.candidates, y.candidates);
  EXPECT_EQ(x.simulations, y.simulations);
  EXPECT_EQ(x.stop_reason, y.stop_reason);
  // The timeline given with `failed` or not: the same answer.
  SimulationOptions timeline;
  timeline.record_timeline = true;
  const FixtureSuggestion z =
      SuggestFixtures(s.def, s.assembly, plan, SimulatePlan(s.assembly, plan, timeline));
  ASSERT_EQ(z.fixels.size(), x.fixels.size());
  for (size_t i = 0; i < x.fixels.size(); ++i)
    EXPECT_EQ(z.fixels[i].fixture.point, x.fixels[i].fixture.point);
  EXPECT_EQ(z.simulations, x.simulations - 1);  // no re-run for the timeline
}

TEST(SuggestFixtures, FixelsNeverGoOnPartsThePlanRemovesLater) {
  // Lift A, then lift B out: B is removed later, so a fixel on it would have
  // to leave with it. No fixel goes on B; C (which tips) may get some.
  const Scene s("paper_fig4.json");
  PlanDef pd;
  pd.steps.resize(2);
  pd.steps[0].remove = {"A"};
  pd.steps[0].path = {{0, 0, 0}, {0, 4, 0}};
  pd.steps[0].has_path = true;
  pd.steps[1].remove = {"B"};
  pd.steps[1].path = {{0, 0, 0}, {0, 6, 0}};
  pd.steps[1].has_path = true;
  const Plan plan = Plan::Create(pd, s.assembly);
  const SimulationResult failed = SimulatePlan(s.assembly, plan);
  ASSERT_FALSE(failed.stable());
  const FixtureSuggestion fx = SuggestFixtures(s.def, s.assembly, plan, failed);
  for (const SuggestedFixel& f : fx.fixels) EXPECT_NE(f.fixture.part, "B");
  EXPECT_FALSE(fx.found) << fx.stop_reason;  // C alone cannot keep B from sliding
  ASSERT_TRUE(fx.stopped_at);                // where the search stopped
  EXPECT_EQ(fx.stopped_at->verdict, MotionVerdict::kUnstable);
  EXPECT_FALSE(fx.stop_reason.empty());
}

// ---------------------------------------------------------------------------
// A part that needs two fixels. B (a hexagon whose flat bottom spans
// x = -0.25 .. 0.25, centroid x = c ≈ 0.133) sits on a post A, which slides
// out to the right (off B within one tick): B falls. Frictionless fixels can
// hold B's weight m g only by vertical forces whose moments about the
// centroid cancel: one fixel would have to sit right under the centroid
// pushing straight up, and no candidate does (the bottom's points are at
// x = -0.25, 0, 0.25; the slanted faces push sideways too). Two do: at
// x = 0 and 0.25, carrying m g (1 - 4c) and 4 m g c.

struct Post {
  AssemblyDef def;
  Assembly assembly;
  Plan plan;
};

Post MakePost(const Vector3& direction) {
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  PartDef d;
  d.name = "D";
  d.fixed = true;
  d.polygon = {{-3, -3}, {4, -3}, {4, -2}, {-3, -2}};
  PartDef a;
  a.name = "A";
  a.polygon = {{-0.25, -2}, {0.25, -2}, {0.25, 0}, {-0.25, 0}};
  PartDef b;
  b.name = "B";
  b.polygon = {{-0.25, 0}, {0.25, 0}, {1.5, 1.25}, {1.5, 2}, {-1.25, 2}, {-1.25, 1.5}};
  def.parts = {d, a, b};
  Assembly assembly = Assembly::Create(def);
  PlanDef pd;
  pd.steps.resize(1);
  pd.steps[0].remove = {"A"};
  pd.steps[0].direction = direction;
  pd.steps[0].distance = 2;
  pd.steps[0].has_direction = true;
  Plan plan = Plan::Create(pd, assembly);
  return {std::move(def), std::move(assembly), std::move(plan)};
}

TEST(SuggestFixtures, FallingHexagon_OneFixelCannotHoldItTwoDo) {
  const Post p = MakePost({1, 0, 0});
  const SimulationResult failed = SimulatePlan(p.assembly, p.plan);
  ASSERT_EQ(failed.verdict, MotionVerdict::kUnstable);
  const Part& b = p.assembly.part(2);
  const double c = b.centroid.x();
  ASSERT_GT(c, 0.0);
  ASSERT_LT(c, 0.25);

  // At most one: none found, and every candidate was tried.
  FixtureSearchOptions one;
  one.max_fixels = 1;
  const FixtureSuggestion none = SuggestFixtures(p.def, p.assembly, p.plan, failed, one);
  EXPECT_FALSE(none.found);
  EXPECT_TRUE(none.fixels.empty());
  EXPECT_GT(none.candidates, 0);
  EXPECT_EQ(none.simulations, 1 + none.candidates);
  EXPECT_NE(none.stop_reason.find("no set of at most 1"), std::string::npos) << none.stop_reason;

  // At most two (or the default three): exactly two, on B's bottom, pushing up.
  for (int most : {2, 3}) {
    FixtureSearchOptions opt;
    opt.max_fixels = most;
    const FixtureSuggestion fx = SuggestFixtures(p.def, p.assembly, p.plan, failed, opt);
    ASSERT_TRUE(fx.found) << fx.stop_reason;
    ASSERT_EQ(fx.fixels.size(), 2u);
    EXPECT_TRUE(fx.verification.stable());
    std::vector<double> xs;
    for (const SuggestedFixel& f : fx.fixels) {
      EXPECT_EQ(f.fixture.part, "B");
      EXPECT_DOUBLE_EQ(f.fixture.point.y(), 0.0);
      EXPECT_EQ(f.fixture.normal, Vector3(0, 1, 0));
      xs.push_back(f.fixture.point.x());
    }
    ASSERT_EQ(xs, (std::vector<double>{0.0, 0.25}));
    // Statics once A has left: the two forces hold m g with no moment about
    // the centroid.
    const double mg = b.mass;  // |g| = 1
    EXPECT_NEAR(LastFixtureForce(fx.verification, 0), mg * (1 - 4 * c), 1e-6 * mg);
    EXPECT_NEAR(LastFixtureForce(fx.verification, 1), mg * 4 * c, 1e-6 * mg);
    for (int i = 0; i < 2; ++i) {
      EXPECT_GE(fx.fixels[i].max_force, LastFixtureForce(fx.verification, i) - 1e-12);
      EXPECT_DOUBLE_EQ(fx.fixels[i].max_force, MaxFixtureForce(fx.verification, i));
    }
  }
}

TEST(SuggestFixtures, InfeasibleStepGetsNoFixels) {
  // Pushing the post down into the table: blocked, and no fixel frees it.
  const Post p = MakePost({0, -1, 0});
  const SimulationResult failed = SimulatePlan(p.assembly, p.plan);
  ASSERT_EQ(failed.verdict, MotionVerdict::kInfeasible);
  const FixtureSuggestion fx = SuggestFixtures(p.def, p.assembly, p.plan, failed);
  EXPECT_FALSE(fx.found);
  EXPECT_TRUE(fx.fixels.empty());
  EXPECT_EQ(fx.candidates, 0);
  EXPECT_NE(fx.stop_reason.find("infeasible: fixels cannot free a blocked motion"),
            std::string::npos)
      << fx.stop_reason;
  EXPECT_EQ(fx.verification.verdict, MotionVerdict::kInfeasible);
}

TEST(SuggestFixtures, BudgetAndBadOptions) {
  const Post p = MakePost({1, 0, 0});
  const SimulationResult failed = SimulatePlan(p.assembly, p.plan);
  FixtureSearchOptions tight;
  tight.max_simulations = 3;
  const FixtureSuggestion fx = SuggestFixtures(p.def, p.assembly, p.plan, failed, tight);
  EXPECT_FALSE(fx.found);
  EXPECT_LE(fx.simulations, 3);
  EXPECT_NE(fx.stop_reason.find("budget of 3 simulations"), std::string::npos) << fx.stop_reason;

  FixtureSearchOptions bad;
  bad.max_fixels = 0;
  EXPECT_THROW(SuggestFixtures(p.def, p.assembly, p.plan, failed, bad), std::invalid_argument);
  bad.max_fixels = 1;
  bad.max_candidates = 0;
  EXPECT_THROW(SuggestFixtures(p.def, p.assembly, p.plan, failed, bad), std::invalid_argument);
}

}  // namespace
}  // namespace cairn

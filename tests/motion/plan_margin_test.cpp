// motion/plan_margin.h: `simulate --margin friction` on a plan whose only
// friction-critical part stands still: the block on the 20° incline, while a
// lid is lifted off a table beside it. The plan's margin is the block's
// static one, μ* = tan 20° (analytic), and below it the block slides.
#include "cairn/motion/plan_margin.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "test_paths.h"

namespace cairn {
namespace {

TEST(PlanFrictionMargin, LiftingALidBesideTheInclineIsTheInclinesMargin) {
  AssemblyDef def = ReadSceneDef(testing::ExamplePath("incline.json"));
  PartDef table;
  table.name = "table";
  table.fixed = true;
  table.polygon = {{10, 0}, {14, 0}, {14, 1}, {10, 1}};
  PartDef lid;
  lid.name = "lid";
  lid.polygon = {{11, 1}, {13, 1}, {13, 1.5}, {11, 1.5}};
  def.parts.push_back(table);
  def.parts.push_back(lid);
  const Assembly assembly = Assembly::Create(def);
  const nlohmann::json plan_json = nlohmann::json::parse(
      R"({"cairn_plan": 1, "steps": [{"remove": ["lid"], "direction": [0, 1], "distance": 1}]})");
  const Plan plan = Plan::Create(ParsePlanJson(plan_json, "plan", 2), assembly, "plan");
  const PlanMargin m = PlanFrictionMargin(def, plan);
  const double mu_star = std::tan(20 * std::numbers::pi / 180);
  ASSERT_TRUE(m.critical.has_value());
  EXPECT_FALSE(m.factor);  // no friction pairs: the margin is μ itself
  EXPECT_EQ(m.nominal, 0.5);
  EXPECT_NEAR(*m.critical, mu_star, 1e-3);
  ASSERT_TRUE(m.failing_at.has_value());
  EXPECT_LT(*m.failing_at, *m.critical);
  EXPECT_LE(*m.critical - *m.failing_at, m.tolerance * (1 + 1e-12));
  ASSERT_TRUE(m.failure.has_value());
  EXPECT_EQ(m.failure->parts, std::vector<int>{assembly.FindPart("block")});
  EXPECT_GT(m.simulations, 2);
}

}  // namespace
}  // namespace cairn

// fixture_report.h: a fixel suggestion as JSON and text: every fixel with its
// part, face, step and largest force, the scene entries to paste, and the
// verification's verdict.
#include "cairn/report/fixture_report.h"

#include <gtest/gtest.h>

#include "cairn/io/plan_reader.h"
#include "cairn/report/words.h"
#include "example_scene.h"

namespace cairn {
namespace {

// Paper Figs. 4-5: lifting A makes B slide; fixels on B's right face hold it.
class FixtureReportFig4 : public ::testing::Test {
 protected:
  const testing::ExampleScene fig4_{"paper_fig4.json"};
  const Plan plan_ =
      ReadPlan(testing::ExamplePath("plans/paper_fig4_lift_a.plan.json"), fig4_.assembly);
  const FixtureSuggestion fx_ =
      SuggestFixtures(fig4_.def, fig4_.assembly, plan_, SimulatePlan(fig4_.assembly, plan_));
};

TEST_F(FixtureReportFig4, JsonListsEveryFixelAndTheVerification) {
  ASSERT_TRUE(fx_.found);
  const FixtureSearchOptions search;
  const nlohmann::json doc = FixtureSuggestionToJson(fig4_.assembly, fx_, search, {});
  EXPECT_EQ(doc["found"], true);
  EXPECT_EQ(doc["message"], FixtureMessage(fig4_.assembly, fx_));
  EXPECT_EQ(doc["max_fixels"], search.max_fixels);
  ASSERT_EQ(doc["fixels"].size(), fx_.fixels.size());
  ASSERT_EQ(doc["scene_fixtures"].size(), fx_.fixels.size());
  for (size_t i = 0; i < fx_.fixels.size(); ++i) {
    EXPECT_EQ(doc["fixels"][i]["part"], "B");
    EXPECT_EQ(doc["fixels"][i]["face"], fx_.fixels[i].face);
    EXPECT_GT(doc["fixels"][i]["max_force"].get<double>(), 0) << "a fixel that holds carries force";
  }
  EXPECT_EQ(doc["verification"]["stable"], true);
  EXPECT_TRUE(doc["verification"]["failure"].is_null());
}

TEST_F(FixtureReportFig4, TextSaysFoundThenOneLinePerFixel) {
  const std::string text = FixtureSuggestionToText(fig4_.assembly, fx_, {}, {});
  EXPECT_EQ(text.rfind("Fixel suggestion (at most 3): FOUND - ", 0), 0u) << text;
  for (size_t i = 0; i < fx_.fixels.size(); ++i)
    EXPECT_NE(text.find("fixel " + std::to_string(i + 1) + ": B at "), std::string::npos) << text;
  EXPECT_NE(text.find("verified: the plan with"), std::string::npos) << text;
}

}  // namespace
}  // namespace cairn

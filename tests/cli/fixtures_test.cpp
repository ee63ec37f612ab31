// `cairn simulate --suggest-fixtures`, run as a user runs it
// (docs/fixtures.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/cli_run.h"

namespace cairn {
namespace {

using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;

const std::string kFig4 = ExamplePath("paper_fig4.json");
const std::string kLiftA = ExamplePath("plans/paper_fig4_lift_a.plan.json");

TEST(SuggestFixturesCli, PaperFig4_JsonHasFixelsOnBsRightFace) {
  const CliRun r = Cairn("simulate " + kFig4 + " " + kLiftA + " --suggest-fixtures --json");
  // The exit code is the plan's own verdict, without fixels.
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["verdict"], "unstable");
  ASSERT_TRUE(doc.contains("fixtures")) << r.out;
  const auto& fx = doc["fixtures"];
  EXPECT_EQ(fx["found"], true);
  EXPECT_EQ(fx["max_fixels"], 3);
  EXPECT_GT(fx["candidates"].get<int>(), 0);
  EXPECT_GE(fx["simulations"].get<int>(), 2);
  EXPECT_EQ(fx["force_unit"], "force units");
  ASSERT_TRUE(fx["fixels"].is_array());
  ASSERT_GE(fx["fixels"].size(), 1u);
  ASSERT_EQ(fx["scene_fixtures"].size(), fx["fixels"].size());
  for (const auto& f : fx["fixels"]) {
    EXPECT_EQ(f["part"], "B");
    EXPECT_EQ(f["point"][0].get<double>(), 7.0);
    EXPECT_GE(f["point"][1].get<double>(), 0.0);
    EXPECT_LE(f["point"][1].get<double>(), 3.0);
    EXPECT_EQ(f["normal"], nlohmann::json::parse("[-1.0, 0.0]"));
    EXPECT_EQ(f["step"], 0);
    EXPECT_GT(f["max_force"].get<double>(), 0.0);
    EXPECT_EQ(f["face"], "edge 1 (7, 0)-(7, 3)");
  }
  EXPECT_EQ(fx["verification"]["verdict"], "stable");
  EXPECT_EQ(fx["verification"]["stable"], true);
  EXPECT_TRUE(fx["verification"]["failure"].is_null());

  // The scene_fixtures pasted into the scene: `cairn simulate` is stable.
  nlohmann::json scene = nlohmann::json::parse(testing::Slurp(kFig4));
  scene["fixtures"] = fx["scene_fixtures"];
  const std::string path = testing::TempFile("cairn_fig4_suggested.json", scene.dump(2));
  const CliRun again = Cairn("simulate " + path + " " + kLiftA + " --json");
  std::filesystem::remove(path);
  EXPECT_EQ(again.exit_code, 0) << again.out << again.err;
  EXPECT_EQ(nlohmann::json::parse(again.out)["verdict"], "stable");
}

TEST(SuggestFixturesCli, PaperFig4_TextListsTheFixels) {
  const CliRun r = Cairn("simulate " + kFig4 + " " + kLiftA + " --suggest-fixtures");
  ASSERT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("Fixel suggestion (at most 3): FOUND"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fixel 1: B at (7, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("normal (-1, 0) (edge 1 (7, 0)-(7, 3)), for step 1: max force"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("is stable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("scene fixtures to add: [{\"normal\":[-1.0,0.0],\"part\":\"B\""),
            std::string::npos)
      << r.out;
  // --normalize divides the forces by A's weight.
  const CliRun n = Cairn("simulate " + kFig4 + " " + kLiftA + " --suggest-fixtures --normalize A");
  EXPECT_NE(n.out.find("weight of A"), std::string::npos) << n.out;
}

TEST(SuggestFixturesCli, StablePlanGetsNullAndNoText) {
  const CliRun r = Cairn("simulate " + ExamplePath("paper_fig4_fixels.json") + " " + kLiftA +
                         " --suggest-fixtures --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  ASSERT_TRUE(doc.contains("fixtures"));
  EXPECT_TRUE(doc["fixtures"].is_null());
  const CliRun t = Cairn("simulate " + ExamplePath("paper_fig4_fixels.json") + " " + kLiftA +
                         " --suggest-fixtures");
  EXPECT_EQ(t.exit_code, 0);
  EXPECT_EQ(t.out.find("Fixel suggestion"), std::string::npos) << t.out;
  // Without the flag, no key at all.
  const CliRun plain = Cairn("simulate " + kFig4 + " " + kLiftA + " --json");
  EXPECT_FALSE(nlohmann::json::parse(plain.out).contains("fixtures"));
}

TEST(SuggestFixturesCli, MaxFixelsOneStillFindsFig4sSingleFixel) {
  const CliRun r =
      Cairn("simulate " + kFig4 + " " + kLiftA + " --suggest-fixtures --max-fixels 1 --json");
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const auto fx = nlohmann::json::parse(r.out)["fixtures"];
  EXPECT_EQ(fx["max_fixels"], 1);
  EXPECT_EQ(fx["found"], true);
  EXPECT_EQ(fx["fixels"].size(), 1u);
}

TEST(SuggestFixturesCli, MaxFixelsBadValuesAreBadInput) {
  for (const std::string bad : {"0", "-1", "21", "two", "1.5"}) {
    const CliRun r =
        Cairn("simulate " + kFig4 + " " + kLiftA + " --suggest-fixtures --max-fixels " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.out << r.err;
    EXPECT_NE(r.err.find("--max-fixels"), std::string::npos) << bad << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace cairn

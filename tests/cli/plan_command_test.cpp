// `cairn plan`, run as a user runs it: the sequences it prints, the plan
// files it writes (which `cairn simulate` replays with the verdict the
// planner gave), the dot graph, fixtures, bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/cli_run.h"

namespace cairn {
namespace {

using nlohmann::json;
using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;
using testing::Slurp;
using testing::TempDir;
using testing::TempFile;

TEST(PlanCli, PaperFig1_OneLinearSequenceWrittenAsPlansThatReplayStably) {
  const std::string dir = TempDir("cairn_plan_fig1");
  const std::string scene = ExamplePath("paper_fig1.json");
  const CliRun r = Cairn("plan " + scene + " --single-parts --json --emit-plans " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json doc = json::parse(r.out);
  ASSERT_EQ(doc["sequences"].size(), 1u);
  const json& seq = doc["sequences"][0];
  EXPECT_EQ(seq["invertible"], true);
  std::vector<std::string> order;
  for (const json& step : seq["steps"]) {
    order.push_back(step["remove"][0]);
    EXPECT_EQ(step["support"], "full");
    EXPECT_TRUE(step.contains("direction") || step.contains("path"));
  }
  EXPECT_EQ(order, (std::vector<std::string>{"D", "C", "B", "A"}));
  EXPECT_EQ(doc["stats"]["sequences_total"], 1.0);
  EXPECT_GT(doc["stats"]["nodes"].get<int>(), 0);
  EXPECT_GT(doc["stats"]["checks"].get<int>(), 0);
  EXPECT_TRUE(doc["stats"]["time"].is_number());
  // The plan files: the disassembly and its reverse replay stably.
  const std::string dis = dir + "/sequence_001.plan.json";
  const std::string as = dir + "/sequence_001.assemble.plan.json";
  ASSERT_TRUE(std::filesystem::exists(dis));
  EXPECT_EQ(json::parse(Slurp(as))["mode"], "assemble");
  const CliRun d = Cairn("simulate " + scene + " " + dis);
  EXPECT_EQ(d.exit_code, 0) << d.out << d.err;
  const CliRun a = Cairn("simulate " + scene + " " + as);
  EXPECT_EQ(a.exit_code, 0) << a.out << a.err;
  std::filesystem::remove_all(dir);
}

TEST(PlanCli, PaperFig17_NothingWithSinglePartsSubassembliesOtherwise) {
  const std::string scene = ExamplePath("paper_fig17.json");
  const CliRun single = Cairn("plan " + scene + " --single-parts");
  EXPECT_EQ(single.exit_code, 1) << single.out << single.err;
  EXPECT_NE(single.out.find("no stable disassembly sequence"), std::string::npos) << single.out;
  const CliRun sub = Cairn("plan " + scene + " --max 1");
  EXPECT_EQ(sub.exit_code, 0) << sub.out << sub.err;
  EXPECT_NE(sub.out.find("B+A"), std::string::npos) << sub.out;
  EXPECT_NE(sub.out.find("D+C"), std::string::npos) << sub.out;
}

TEST(PlanCli, DotMarksStableAndUnstableEdges) {
  const std::string dot = TempFile("cairn_plan_fig1.dot", "");
  std::filesystem::remove(dot);
  const CliRun r = Cairn("plan " + ExamplePath("paper_fig1.json") + " --single-parts --dot " + dot);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = Slurp(dot);
  EXPECT_EQ(text.rfind("digraph andor {", 0), 0u);
  EXPECT_NE(text.find("color=darkgreen"), std::string::npos) << "a stable edge";
  EXPECT_NE(text.find("color=red, style=dashed"), std::string::npos) << "an unstable edge";
  EXPECT_NE(text.find("fillcolor"), std::string::npos) << "an unstable node";
  std::filesystem::remove(dot);
}

TEST(PlanCli, SameDocumentOnOneAndTwoThreads) {
  // Paths simulated in parallel (Fig. 6's exits) and node checks.
  const std::string args = "plan " + ExamplePath("paper_fig6.json") + " --keep D,E --paths " +
                           ExamplePath("paths/paper_fig6_exits.paths.json") + " --json --threads ";
  json a = json::parse(Cairn(args + "1").out);
  json b = json::parse(Cairn(args + "2").out);
  ASSERT_FALSE(a["sequences"].empty());
  for (json* j : {&a, &b}) {
    (*j)["stats"].erase("time");
    (*j)["stats"].erase("threads");
  }
  EXPECT_EQ(a.dump(), b.dump());
}

TEST(PlanCli, PaperFig4_FixelOnBsRightFaceWhenNothingElseIsStable) {
  const std::string dir = TempDir("cairn_plan_fig4");
  const std::string scene = ExamplePath("paper_fig4.json");
  EXPECT_EQ(Cairn("plan " + scene).exit_code, 1);
  const CliRun r = Cairn("plan " + scene + " --allow-fixtures 2 --json --emit-plans " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const json doc = json::parse(r.out);
  ASSERT_FALSE(doc["sequences"].empty());
  const json& fixels = doc["sequences"][0]["fixels"];
  ASSERT_EQ(fixels.size(), 1u);
  EXPECT_EQ(fixels[0]["part"], "B");
  EXPECT_DOUBLE_EQ(fixels[0]["point"][0].get<double>(), 7.0) << "B's right face";
  EXPECT_DOUBLE_EQ(fixels[0]["normal"][0].get<double>(), -1.0);
  // The scene with the fixel and the plan written beside it replay stably.
  const CliRun sim =
      Cairn("simulate " + dir + "/sequence_001.scene.json " + dir + "/sequence_001.plan.json");
  EXPECT_EQ(sim.exit_code, 0) << sim.out << sim.err;
  std::filesystem::remove_all(dir);
}

TEST(PlanCli, GivenPathsAreUsedAndBadOnesNamed) {
  const std::string scene = ExamplePath("paper_fig6.json");
  const CliRun ok = Cairn("plan " + scene + " --keep D,E --json --paths " +
                          ExamplePath("paths/paper_fig6_exits.paths.json"));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const json doc = json::parse(ok.out);
  bool exit_ii_tried = false;
  for (const json& e : doc["graph"]["edges"])
    for (const json& t : e["trials"]) exit_ii_tried = exit_ii_tried || t["label"] == "II";
  EXPECT_TRUE(exit_ii_tried);

  const std::string bad = TempFile("cairn_bad_paths.json", R"({"Q": [[[0, 0], [0, 1]]]})");
  const CliRun r1 = Cairn("plan " + scene + " --paths " + bad);
  EXPECT_EQ(r1.exit_code, 2);
  EXPECT_NE(r1.err.find("no part named 'Q'"), std::string::npos) << r1.err;
  const std::string zero =
      TempFile("cairn_zero_paths.json", R"({"C": [{"direction": [0, 0], "distance": 1}]})");
  const CliRun r2 = Cairn("plan " + scene + " --paths " + zero);
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_NE(r2.err.find("C (\"C\")[0].direction"), std::string::npos) << r2.err;
  const CliRun r3 = Cairn("plan " + scene + " --keep Z");
  EXPECT_EQ(r3.exit_code, 2);
  EXPECT_NE(r3.err.find("--keep"), std::string::npos) << r3.err;
  const CliRun r4 = Cairn("plan " + scene + " --support sideways");
  EXPECT_EQ(r4.exit_code, 2);
}

}  // namespace
}  // namespace cairn

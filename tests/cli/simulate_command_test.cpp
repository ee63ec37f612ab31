// `cairn simulate`, run as a user runs it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/cli_run.h"

namespace cairn {
namespace {

using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;
using testing::Slurp;
using testing::TempFile;

std::string Plan(const std::string& name) { return ExamplePath("plans/" + name + ".plan.json"); }

// A timeline CSV: its header line and its rows split at the commas.
struct Csv {
  std::string header;
  std::vector<std::vector<std::string>> rows;
};

Csv ReadCsv(const std::string& path) {
  Csv csv;
  std::istringstream in(Slurp(path));
  std::getline(in, csv.header);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string>& f = csv.rows.emplace_back();
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
  }
  return csv;
}

TEST(Simulate, PaperFig1_DCBAStandsAndCFirstFailsWhenCLeaves) {
  const CliRun ok =
      Cairn("simulate " + ExamplePath("paper_fig1.json") + " " + Plan("paper_fig1_dcba"));
  EXPECT_EQ(ok.exit_code, 0) << ok.out << ok.err;
  EXPECT_NE(ok.out.find("STABLE"), std::string::npos);

  const CliRun bad = Cairn("simulate " + ExamplePath("paper_fig1.json") + " " +
                           Plan("paper_fig1_c_first") + " --json");
  ASSERT_EQ(bad.exit_code, 1) << bad.err;
  const auto doc = nlohmann::json::parse(bad.out);
  EXPECT_EQ(doc["verdict"], "unstable");
  EXPECT_EQ(doc["stable"], false);
  ASSERT_TRUE(doc["failure"].is_object());
  EXPECT_EQ(doc["failure"]["step"], 0);
  EXPECT_DOUBLE_EQ(doc["failure"]["time"].get<double>(), 1.0);
  EXPECT_NE(doc["failure"]["parts"].dump().find("\"B\""), std::string::npos);
  ASSERT_EQ(doc["steps"].size(), 1u) << "stops at the first failure";
  EXPECT_EQ(doc["steps"][0]["verdict"], "unstable");
  EXPECT_EQ(doc["steps"][0]["time_steps"], 2);
}

// Paper Fig. 1 with B lifted first. C rests on B and is free: B
// pushes it up from the first instant, so the plan is unstable at t = 0 with
// C named and moving up (exit 1), not infeasible ("B runs into C", exit 3).
TEST(Simulate, PaperFig1_BFirstPushesCUpAtTimeZero) {
  const CliRun r = Cairn("simulate " + ExamplePath("paper_fig1.json") + " " +
                         Plan("paper_fig1_b_first") + " --json");
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["verdict"], "unstable");
  const auto& f = doc["failure"];
  ASSERT_TRUE(f.is_object());
  EXPECT_EQ(f["verdict"], "unstable");
  EXPECT_EQ(f["step"], 0);
  EXPECT_EQ(f["tick"], 0);
  EXPECT_EQ(f["time"].get<double>(), 0.0);
  EXPECT_NE(f["parts"].dump().find("\"C\""), std::string::npos) << f.dump();
  EXPECT_NE(f["pushed"].dump().find("\"C\""), std::string::npos) << f.dump();
  bool c_moves_up = false;
  for (const auto& m : f["motions"])
    if (m["part"] == "C") c_moves_up = m["velocity"]["linear"][1].get<double>() > 0;
  EXPECT_TRUE(c_moves_up) << f.dump();
  EXPECT_NE(f["description"].get<std::string>().find("B pushes C"), std::string::npos);

  const CliRun text =
      Cairn("simulate " + ExamplePath("paper_fig1.json") + " " + Plan("paper_fig1_b_first"));
  EXPECT_EQ(text.exit_code, 1);
  EXPECT_NE(text.out.find("UNSTABLE"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("runs into"), std::string::npos) << text.out;
}

// The 105-part wall from the CLI: `check` stands, pulling an end brick out
// fails at the first move with the bricks above it named: at least r5_10,
// which rests on the pulled brick alone (tests/motion/wall_test.cpp).
TEST(Simulate, WallChecksStableAndPullingAnEndBrickDragsTheBricksAbove) {
  const CliRun check = Cairn("check " + ExamplePath("wall.json") + " --json");
  ASSERT_EQ(check.exit_code, 0) << check.err;
  EXPECT_EQ(nlohmann::json::parse(check.out)["verdict"], "stable");

  const CliRun pull =
      Cairn("simulate " + ExamplePath("wall.json") + " " + Plan("wall_pull_r4_9") + " --json");
  ASSERT_EQ(pull.exit_code, 1) << pull.err;
  const auto doc = nlohmann::json::parse(pull.out);
  EXPECT_EQ(doc["verdict"], "unstable");
  ASSERT_TRUE(doc["failure"].is_object());
  EXPECT_DOUBLE_EQ(doc["failure"]["time"].get<double>(), 0.04);
  const std::string parts = doc["failure"]["parts"].dump();
  EXPECT_NE(parts.find("\"r5_10\""), std::string::npos) << parts;
  EXPECT_EQ(parts.find("\"r4_"), std::string::npos) << parts;
}

TEST(Simulate, ContinueGivesEveryStepAVerdict) {
  const CliRun r = Cairn("simulate " + ExamplePath("paper_fig1.json") + " " +
                         Plan("paper_fig1_c_first") + " --json --continue");
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["steps"].size(), 4u);
  EXPECT_EQ(doc["failure"]["step"], 0) << "the first failure is still reported";
}

TEST(Simulate, PaperFig4_FixelsMakeLiftingAStable) {
  EXPECT_EQ(Cairn("simulate " + ExamplePath("paper_fig4.json") + " " + Plan("paper_fig4_lift_a"))
                .exit_code,
            1);
  EXPECT_EQ(
      Cairn("simulate " + ExamplePath("paper_fig4_fixels.json") + " " + Plan("paper_fig4_lift_a"))
          .exit_code,
      0);
}

TEST(Simulate, PaperFig19_SlidingAOutDragsBButInsertingItIsStable) {
  // Friction makes assembly and disassembly noninvertible: the same path.
  const CliRun out = Cairn("simulate " + ExamplePath("paper_fig19.json") + " " +
                           Plan("paper_fig19_slide_a") + " --json");
  ASSERT_EQ(out.exit_code, 1) << out.err;
  EXPECT_EQ(nlohmann::json::parse(out.out)["failure"]["parts"], nlohmann::json::array({"B"}));
  const CliRun in =
      Cairn("simulate " + ExamplePath("paper_fig19.json") + " " + Plan("paper_fig19_insert_a"));
  EXPECT_EQ(in.exit_code, 0) << in.out << in.err;
}

TEST(Simulate, TimelineHasARowPerTickAndContactWithNormalisedForces) {
  const std::string csv =
      (std::filesystem::temp_directory_path() / "cairn_timeline_test.csv").string();
  std::filesystem::remove(csv);
  const CliRun r = Cairn("simulate " + ExamplePath("paper_fig1.json") + " " +
                         Plan("paper_fig1_dcba") + " --timeline " + csv + " --normalize B");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Csv t = ReadCsv(csv);
  EXPECT_EQ(t.header,
            "time,step,tick,part_a,part_b,x,y,normal_x,normal_y,normal_force,friction_force,"
            "normal_velocity,sliding_velocity,breaks,slides");
  // At t = 0 the table carries everything: Σ (A on E) = total mass / m_B
  // (g = 1, unit density: A 2, B 3, C 1.5, D 3, over m_B = 3).
  double table_at_0 = 0;
  for (const auto& f : t.rows) {
    ASSERT_EQ(f.size(), 15u);
    if (std::stod(f[0]) == 0.0 && f[4] == "E") table_at_0 += std::stod(f[9]);
  }
  EXPECT_GT(t.rows.size(), 20u);
  EXPECT_NEAR(table_at_0, 9.5 / 3.0, 1e-9);
  std::filesystem::remove(csv);
}

// In 3-D the timeline has a column per coordinate and the contact's patch.
// Fig. 9, A lifted first: at t = 0 the table carries the whole weight
// (g = 1; A 1.5 × 2 × 0.5 at density 1, B (2 + 6) × 0.5, C 1.5 × 2.5: 9.25).
TEST(Simulate, TimelineIn3dHasPatchesAndVectors) {
  const std::string csv =
      (std::filesystem::temp_directory_path() / "cairn_timeline3d_test.csv").string();
  std::filesystem::remove(csv);
  const CliRun r = Cairn("simulate " + ExamplePath("paper_fig9.json") + " " +
                         Plan("paper_fig9_acb") + " --timeline " + csv);
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const Csv t = ReadCsv(csv);
  EXPECT_EQ(t.header,
            "time,step,tick,part_a,part_b,patch,x,y,z,normal_x,normal_y,normal_z,normal_force,"
            "friction_x,friction_y,friction_z,normal_velocity,sliding_x,sliding_y,sliding_z,"
            "breaks,slides");
  double table_at_0 = 0;
  for (const auto& f : t.rows) {
    ASSERT_EQ(f.size(), 22u);
    if (std::stod(f[0]) == 0.0 && f[4] == "table") table_at_0 += std::stod(f[12]);
  }
  EXPECT_GT(t.rows.size(), 12u);
  EXPECT_NEAR(table_at_0, 9.25, 1e-9);
  std::filesystem::remove(csv);
}

TEST(Simulate, DrivingIntoAWallIsInfeasibleWithExitCodeThree) {
  const std::string scene = TempFile("cairn_wall_scene.json", R"({"cairn": 1, "parts": [
    {"name": "floor", "fixed": true, "box": {"min": [-5, -1], "max": [5, 0]}},
    {"name": "wall", "fixed": true, "box": {"min": [3, 0], "max": [4, 3]}},
    {"name": "block", "box": {"min": [0, 0], "max": [1, 1]}}]})");
  const std::string plan = TempFile("cairn_wall_plan.json", R"({"cairn_plan": 1, "dt": 0.5,
    "steps": [{"remove": ["block"], "direction": [1, 0], "distance": 4}]})");
  const CliRun r = Cairn("simulate " + scene + " " + plan + " --json");
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["verdict"], "infeasible");
}

TEST(Simulate, BadPlanExitsTwoAndWritesNothing) {
  const std::string plan = TempFile("cairn_bad_plan.json", R"({"cairn_plan": 1,
    "steps": [{"remove": ["Z"], "direction": [0, 1], "distance": 1}]})");
  const std::string csv =
      (std::filesystem::temp_directory_path() / "cairn_never_written.csv").string();
  std::filesystem::remove(csv);
  const CliRun r =
      Cairn("simulate " + ExamplePath("paper_fig1.json") + " " + plan + " --timeline " + csv);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("steps[0].remove[0]"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(csv));
}

}  // namespace
}  // namespace cairn

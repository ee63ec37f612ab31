// The `cairn blocking` command, run as a user runs it: the real binary, its
// stdout, stderr and exit code.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_run.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;
using testing::Slurp;
using testing::TempDir;

// The removable parts of the cell whose direction is `direction`.
std::vector<std::string> RemovableAt(const nlohmann::json& doc, const nlohmann::json& direction) {
  for (const auto& cell : doc["cells"])
    if (cell["direction"] == direction) return cell["removable"].get<std::vector<std::string>>();
  ADD_FAILURE() << "no cell with direction " << direction.dump();
  return {};
}

TEST(CliBlocking, PegInSlotJson) {
  const CliRun r = Cairn("blocking " + ExamplePath("peg_in_slot.json") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["dimension"], 2);
  EXPECT_EQ(doc["normals"].size(), 2u);
  ASSERT_EQ(doc["cells"].size(), 4u);
  const nlohmann::json& up = doc["cells"][0];
  EXPECT_EQ(up["dimension"], 0);
  EXPECT_EQ(up["direction"], nlohmann::json::parse("[0, 1]"));
  EXPECT_EQ(up["angles_deg"], nlohmann::json::parse("[90, 90]"));
  EXPECT_EQ(up["removable"], nlohmann::json::parse(R"(["peg"])"));
  EXPECT_EQ(up["infinity"], nlohmann::json::parse(R"([["base", "peg"]])"));
  const nlohmann::json& left = doc["cells"][1];
  EXPECT_EQ(left["angles_deg"], nlohmann::json::parse("[90, 270]"));
  EXPECT_EQ(left["direction"], nlohmann::json::parse("[-1, 0]"));
  EXPECT_TRUE(left["removable"].empty());
  EXPECT_EQ(left["infinitesimal"].size(), 2u);
  EXPECT_FALSE(up.contains("signs"));
}

TEST(CliBlocking, LShapesText) {
  const CliRun r = Cairn("blocking " + ExamplePath("l_shapes.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("NDBG (2-D), 8 cells"), std::string::npos) << r.out;
  // The arc between 135° and 180°: B is blocked by A only at infinity.
  EXPECT_NE(r.out.find("(135°, 180°)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("leave: none   blocked: A by B*; B by A\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("leave: B"), std::string::npos) << r.out;
}

TEST(CliBlocking, PaperFig1UpwardAndWithout) {
  const nlohmann::json up = nlohmann::json::parse("[0, 1]");
  CliRun r = Cairn("blocking " + ExamplePath("paper_fig1.json") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(RemovableAt(nlohmann::json::parse(r.out), up), (std::vector<std::string>{"C", "D"}));
  r = Cairn("blocking " + ExamplePath("paper_fig1.json") + " --json --without D,C");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["without"], nlohmann::json::parse(R"(["D", "C"])"));
  EXPECT_EQ(RemovableAt(doc, up), (std::vector<std::string>{"B"}));
}

TEST(CliBlocking, ThreeDimensionalJson) {
  const CliRun r = Cairn("blocking " + ExamplePath("jenga.json") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["dimension"], 3);
  EXPECT_EQ(doc["normals"], nlohmann::json::parse("[[0, 0, 1]]"));
  ASSERT_EQ(doc["cells"].size(), 3u);
  EXPECT_EQ(doc["cells"][2]["signs"], nlohmann::json::parse("[1]"));
  EXPECT_FALSE(doc["cells"][2].contains("angles_deg"));
  EXPECT_EQ(RemovableAt(doc, nlohmann::json::parse("[0, 0, 1]")),
            (std::vector<std::string>{"L18_1", "L18_2", "L18_3"}));
}

// A 2-D scene takes a direction of 2 numbers, a 3-D one 3; the other count
// is refused, saying which the scene takes.
TEST(CliBlocking, DirectionHasTheScenesDimension) {
  CliRun r = Cairn("blocking " + ExamplePath("paper_fig1.json") + " --direction 0,1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json doc = nlohmann::json::parse(r.out);
  ASSERT_EQ(doc["cells"].size(), 1u);
  EXPECT_EQ(RemovableAt(doc, nlohmann::json::parse("[0, 1]")),
            (std::vector<std::string>{"C", "D"}));
  // X,Y,0 is the same direction in the scene's plane; any other Z is not in it.
  r = Cairn("blocking " + ExamplePath("paper_fig1.json") + " --direction 0,1,0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(RemovableAt(nlohmann::json::parse(r.out), nlohmann::json::parse("[0, 1]")),
            (std::vector<std::string>{"C", "D"}));
  r = Cairn("blocking " + ExamplePath("paper_fig1.json") + " --direction 0,1,1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(r.err,
            "cairn: error: --direction: a 2-D scene takes a direction of 2 numbers X,Y (or X,Y,0), "
            "not 3 with Z = 1\n");
  r = Cairn("blocking " + ExamplePath("jenga.json") + " --direction 0,1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "cairn: error: --direction: a 3-D scene takes a direction of 3 numbers X,Y,Z, not 2\n");
  r = Cairn("blocking " + ExamplePath("jenga.json") + " --direction 0,0,1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(RemovableAt(doc, nlohmann::json::parse("[0, 0, 1]")),
            (std::vector<std::string>{"L18_1", "L18_2", "L18_3"}));
}

TEST(CliBlocking, UnknownWithoutPartIsBadInput) {
  const CliRun r = Cairn("blocking " + ExamplePath("paper_fig1.json") + " --without Z");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_NE(r.err.find("cairn: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--without"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no part named 'Z'"), std::string::npos) << r.err;
}

TEST(CliBlocking, MissingSceneIsBadInput) {
  const CliRun r = Cairn("blocking " + ExamplePath("no_such_scene.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cairn: error: "), std::string::npos) << r.err;
}

// paper_fig4 with a free regular n-gon of radius 0.9 about (x, y), as a
// scene file in `dir`; its path.
std::string SceneWithFreeNGon(const std::string& dir, int n, double x, double y) {
  nlohmann::json scene = nlohmann::json::parse(Slurp(ExamplePath("paper_fig4.json")));
  std::ostringstream polygon;
  polygon.precision(17);
  polygon << "[";
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    polygon << (k ? "," : "") << "[" << x + 0.9 * std::cos(a) << "," << y + 0.9 * std::sin(a)
            << "]";
  }
  polygon << "]";
  scene["parts"].push_back({{"name", "free"}, {"polygon", nlohmann::json::parse(polygon.str())}});
  const std::string path = dir + "/free_ngon.json";
  std::ofstream(path) << scene.dump();
  return path;
}

// A free 500-gon beside the slot, touching nothing and above nothing: upward
// the other parts leave as they do without it, and so does the polygon.
TEST(CliBlocking, FreePolygonAnswersForEveryPart) {
  const std::string dir = TempDir("cairn_blocking_ngon");
  std::filesystem::create_directories(dir);
  const std::string scene = SceneWithFreeNGon(dir, 500, 12.5, 1.5);
  const CliRun r = Cairn("blocking " + scene + " --json --direction 0,1,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CliRun alone =
      Cairn("blocking " + ExamplePath("paper_fig4.json") + " --json --direction 0,1,0");
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  std::vector<std::string> expected =
      nlohmann::json::parse(alone.out)["cells"][0]["removable"].get<std::vector<std::string>>();
  expected.push_back("free");
  EXPECT_EQ(nlohmann::json::parse(r.out)["cells"][0]["removable"], nlohmann::json(expected));
  const CliRun all = Cairn("blocking " + scene + " --json");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_EQ(RemovableAt(nlohmann::json::parse(all.out), nlohmann::json::parse("[0, 1]")), expected);
  std::filesystem::remove_all(dir);
}

// A batch's blocking job polls the job's deadline while the NDBG is computed:
// the NDBG with a free 200 000-gon over the slot (its 3.2 million candidate
// directions against the slot's walls, a non-convex part, each tested
// against all its edges: hours) is abandoned at --job-timeout, recorded as
// timed out, and the batch goes on.
TEST(CliBlocking, BatchJobStopsAtItsTimeout) {
  const std::string dir = TempDir("cairn_blocking_timeout");
  std::filesystem::create_directories(dir);
  const std::string scene = SceneWithFreeNGon(dir, 200000, 5, 6.5);
  const std::string jobs = dir + "/jobs.jsonl";
  std::ofstream(jobs) << "{\"id\": 1, \"command\": \"blocking\", \"model\": \"" << scene
                      << "\"}\n{\"id\": 2, \"command\": \"blocking\", \"model\": \""
                      << ExamplePath("paper_fig1.json") << "\"}\n";
  const CliRun r = Cairn("batch " + jobs + " -o " + dir + "/out --job-timeout 1 --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream out(Slurp(dir + "/out"));
  std::string slow_line, fast_line;
  ASSERT_TRUE(std::getline(out, slow_line) && std::getline(out, fast_line));
  const nlohmann::json slow = nlohmann::json::parse(slow_line);
  const nlohmann::json fast = nlohmann::json::parse(fast_line);
  EXPECT_EQ(slow["id"], 1);
  EXPECT_EQ(slow["exit"], 5) << slow_line;
  EXPECT_EQ(slow["error"], "exceeded --job-timeout 1 s") << slow_line;
  EXPECT_FALSE(slow.contains("result"));
  EXPECT_EQ(fast["exit"], 0) << fast_line;
  EXPECT_EQ(RemovableAt(fast["result"], nlohmann::json::parse("[0, 1]")),
            (std::vector<std::string>{"C", "D"}));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cairn

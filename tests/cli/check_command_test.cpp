// The `cairn check` command, run as a user runs it: the real binary, its
// stdout, stderr and exit code.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_run.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Cairn;
using testing::CliPath;
using testing::CliRun;
using testing::ExamplePath;

struct ExampleVerdict {
  const char* file;
  const char* without;
  int exit_code;
};

// Its CTest name's "GetParam() = ...": the case, not the struct's bytes.
void PrintTo(const ExampleVerdict& c, std::ostream* os) {
  *os << c.file << " without '" << c.without << "'";
}

class BundledExamples : public ::testing::TestWithParam<ExampleVerdict> {};

TEST_P(BundledExamples, ExitCodeIsTheVerdict) {
  const ExampleVerdict& e = GetParam();
  std::string args = "check " + ExamplePath(e.file);
  if (*e.without) args += std::string(" --without ") + e.without;
  const CliRun r = Cairn(args);
  EXPECT_EQ(r.exit_code, e.exit_code) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find(e.exit_code == 0 ? "STABLE" : "UNSTABLE"), std::string::npos) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Verdicts, BundledExamples,
    ::testing::Values(
        ExampleVerdict{"incline.json", "", 0}, ExampleVerdict{"incline_slides.json", "", 1},
        ExampleVerdict{"overhang.json", "", 0}, ExampleVerdict{"overhang_tips.json", "", 1},
        ExampleVerdict{"stack3.json", "", 0}, ExampleVerdict{"stack3_tips.json", "", 1},
        ExampleVerdict{"ladder.json", "", 0}, ExampleVerdict{"paper_fig1.json", "", 0},
        ExampleVerdict{"paper_fig1.json", "C", 1}, ExampleVerdict{"paper_fig1.json", "D", 0},
        ExampleVerdict{"paper_fig1.json", "D,C", 0}, ExampleVerdict{"paper_fig4.json", "", 0},
        ExampleVerdict{"paper_fig4.json", "A", 1}, ExampleVerdict{"paper_fig4_fixels.json", "A", 0},
        ExampleVerdict{"paper_fig9.json", "", 0}, ExampleVerdict{"paper_fig9.json", "A", 1},
        ExampleVerdict{"jenga.json", "", 0}, ExampleVerdict{"pyramid10.json", "", 0},
        ExampleVerdict{"pyramid14.json", "", 0}),
    [](const ::testing::TestParamInfo<ExampleVerdict>& param_info) {
      std::string name = std::string(param_info.param.file);
      name = name.substr(0, name.size() - 5);
      if (*param_info.param.without) name += std::string("_without_") + param_info.param.without;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

TEST(CheckJson, HasTheContractKeysAndNamesTheMovingPart) {
  const CliRun r = Cairn("check " + ExamplePath("paper_fig4.json") + " --without A --json");
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["stable"], false);
  EXPECT_EQ(doc["verdict"], "unstable");
  // B slides right; C, no longer held, tips after it.
  EXPECT_EQ(doc["moving"], nlohmann::json::array({"B", "C"}));
  ASSERT_TRUE(doc["parts"].is_array());
  bool saw_b = false;
  for (const auto& p : doc["parts"]) {
    for (const char* key : {"name", "mass", "centroid", "fixed"})
      EXPECT_TRUE(p.contains(key)) << key;
    if (p["name"] == "A") ADD_FAILURE() << "A was taken away";
    if (p["name"] == "B") {
      saw_b = true;
      EXPECT_EQ(p["motion"], "slides");
      EXPECT_GT(p["acceleration"]["linear"][0].get<double>(), 0.0);
    }
  }
  EXPECT_TRUE(saw_b);
  ASSERT_FALSE(doc["contacts"].empty());
  for (const auto& c : doc["contacts"])
    for (const char* key :
         {"parts", "point", "normal", "normal_force", "friction_force", "breaks", "slides"})
      EXPECT_TRUE(c.contains(key)) << key;
}

// A block that just fits between two walls, nothing under it: it falls (the
// LCP from rest), though friction could hold it if the walls squeezed it.
TEST(CheckJson, AJammedBlockIsReportedWeaklyStable) {
  const auto path = std::filesystem::temp_directory_path() / "cairn_jammed_block.json";
  std::ofstream(path) << R"({"cairn": 1, "name": "jammed", "friction": 0.5, "parts": [
    {"name": "left", "fixed": true, "box": {"min": [-1, -2], "max": [0, 2]}},
    {"name": "right", "fixed": true, "box": {"min": [1, -2], "max": [2, 2]}},
    {"name": "block", "box": {"min": [0, 0], "max": [1, 1]}}]})";
  const CliRun run = Cairn("check " + path.string() + " --json");
  ASSERT_EQ(run.exit_code, 1) << run.err;
  const auto doc = nlohmann::json::parse(run.out);
  EXPECT_EQ(doc["verdict"], "unstable");
  EXPECT_EQ(doc["static_equilibrium"], true);
  EXPECT_EQ(doc["weakly_stable"], true);
  const CliRun text = Cairn("check " + path.string());
  EXPECT_NE(text.out.find("WEAKLY STABLE"), std::string::npos) << text.out;
}

TEST(CheckJson, NormalizeDividesForcesByThatPartsWeight) {
  // Frictionless Fig. 1 with g = 1: the four table contacts under A carry the
  // whole weight of A–D; normalised by A's weight they sum to (total / m_A).
  const CliRun plain = Cairn("check " + ExamplePath("paper_fig1.json") + " --json");
  const CliRun norm = Cairn("check " + ExamplePath("paper_fig1.json") + " --json --normalize A");
  ASSERT_EQ(plain.exit_code, 0);
  ASSERT_EQ(norm.exit_code, 0);
  const auto a = nlohmann::json::parse(plain.out), b = nlohmann::json::parse(norm.out);
  EXPECT_EQ(b["force_unit"], "weight of A");
  double table_load = 0, mass_total = 0, mass_a = 0;
  for (const auto& p : a["parts"]) {
    if (p["fixed"]) continue;
    mass_total += p["mass"].get<double>();
    if (p["name"] == "A") mass_a = p["mass"].get<double>();
  }
  for (size_t i = 0; i < a["contacts"].size(); ++i) {
    const auto& ca = a["contacts"][i];
    const auto& cb = b["contacts"][i];
    EXPECT_NEAR(cb["normal_force"].get<double>() * mass_a, ca["normal_force"].get<double>(), 1e-9);
    if (ca["parts"][1] == "E") table_load += ca["normal_force"].get<double>();
  }
  EXPECT_NEAR(table_load, mass_total, 1e-9);
}

TEST(CheckErrors, BadArgumentsExitTwoAndWriteNothingToStdout) {
  for (const std::string& args : std::vector<std::string>{
           "check " + ExamplePath("paper_fig1.json") + " --without Z",
           "check " + ExamplePath("paper_fig1.json") + " --normalize nobody",
           "check " + ExamplePath("does_not_exist.json"), "check", "frobnicate"}) {
    const CliRun r = Cairn(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(r.out.empty()) << args << ": " << r.out;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  const CliRun r = Cairn("check " + ExamplePath("paper_fig1.json") + " --without Z");
  EXPECT_NE(r.err.find("no part named 'Z'"), std::string::npos) << r.err;
}

TEST(CheckErrors, BadSceneNamesFileAndJsonPath) {
  const auto path = std::filesystem::temp_directory_path() / "cairn_bad_scene_test.json";
  std::ofstream(path)
      << R"({"cairn": 1, "parts": [{"name": "A", "polygon": [[0,0],[1,0],[1,1],[0,1]]},
    {"name": "B", "polygon": [[0,0],[1,1],[1,0],[0,1]]}]})";
  const CliRun r = Cairn("check " + path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find(path.string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("parts[1] (\"B\").polygon"), std::string::npos) << r.err;
  std::filesystem::remove(path);
}

// The 3-D document (docs/cli.md): 3-vectors everywhere, contact patches, and
// for a part that tips the axis through its pivot. Fig. 9 without A: C's
// weight on B's slab overhang tips B (and C with it) about lines along y.
TEST(CheckJson, ThreeDimensionalDocument) {
  const CliRun r = Cairn("check " + ExamplePath("paper_fig9.json") + " --without A --json");
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["dimension"], 3);
  EXPECT_EQ(doc["formulation"], "baraff");
  EXPECT_EQ(doc["moving"], nlohmann::json::array({"B", "C"}));
  for (const auto& p : doc["parts"]) {
    EXPECT_EQ(p["centroid"].size(), 3u) << p["name"];
    if (p["fixed"] || p["name"] == "G") continue;
    EXPECT_EQ(p["motion"], "tips") << p["name"];
    ASSERT_EQ(p["axis"].size(), 3u);
    EXPECT_NEAR(std::abs(p["axis"][1].get<double>()), 1.0, 1e-12) << p["name"];
    EXPECT_EQ(p["pivot"].size(), 3u);
    EXPECT_EQ(p["acceleration"]["angular"].size(), 3u);
    EXPECT_EQ(p["acceleration"]["linear"].size(), 3u);
  }
  // 2 face patches of 4 corners: B on the table, C on B (A is away, the pad G
  // absent until a step grips it).
  std::map<int, int> corners;
  for (const auto& c : doc["contacts"]) {
    EXPECT_EQ(c["feature"], "face-face");
    EXPECT_EQ(c["point"].size(), 3u);
    EXPECT_EQ(c["friction_force"].size(), 3u);
    EXPECT_EQ(c["tangential_acceleration"].size(), 3u);
    ++corners[c["patch"].get<int>()];
  }
  EXPECT_EQ(corners.size(), 2u);
  for (const auto& [patch, n] : corners) EXPECT_EQ(n, 4) << "patch " << patch;
}

// Nothing fixed (l_shapes.json: two L-shapes, neither fixed): the verdict
// stays UNSTABLE (everything falls), and the text and the JSON say why and
// how to fix parts.
TEST(CheckNothingFixed, SaysNoPartIsFixedAndHowToFixSome) {
  CliRun r = Cairn("check " + ExamplePath("l_shapes.json"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("UNSTABLE"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("nothing is fixed: no part is fixed and no fixture holds one"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("--fixed PART,..."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"fixed\": true"), std::string::npos) << r.out;
  r = Cairn("check " + ExamplePath("l_shapes.json") + " --json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["nothing_fixed"], true);
  // With a part fixed, or in a scene with a fixed part, no such note.
  r = Cairn("check " + ExamplePath("l_shapes.json") + " --fixed A --json");
  EXPECT_EQ(nlohmann::json::parse(r.out)["nothing_fixed"], false) << r.err;
  r = Cairn("check " + ExamplePath("paper_fig1.json"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("nothing is fixed"), std::string::npos) << r.out;
  // A compas_cra sample stores no support: the note until --supports names one.
  const std::string cubes = testing::SharedDir() + "/datasets/compas_cra/cubes.json";
  if (testing::SharedDir().empty() || !std::filesystem::exists(cubes))
    GTEST_SKIP() << "the shared data (CAIRN_SHARED_DIR) is absent";
  r = Cairn("check " + cubes + " --format compas --friction 0.84");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("nothing is fixed"), std::string::npos) << r.out;
  r = Cairn("check " + cubes + " --format compas --friction 0.84 --supports 0 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["nothing_fixed"], false);
}

// A state the sequence met on the cross vault (compas_assembly, μ 0.84): 131
// blocks, 7 of them held. Its large component (110 blocks) is beyond loading
// from rest, so its equilibrium decides; the interior-point method's forces
// balance to 4·10⁻⁸ of the largest load, and a light block's imbalance
// failed the LCP check at rest (w −4·10⁻⁷ against 10⁻⁷): "solver failure".
// The simplex's vertex balances to roundoff: it stands, decided by the
// equilibrium, and its forces solve the LCP at rest.
TEST(CheckVerdict, AnInteriorPointsForcesThatFailTheCheckAtRestGiveWayToTheVertex) {
  const std::string vault =
      testing::SharedDir() + "/datasets/compas_assembly/crossvault_assembly.json";
  if (testing::SharedDir().empty() || !std::filesystem::exists(vault))
    GTEST_SKIP() << "the shared data (CAIRN_SHARED_DIR) is absent";
  const std::string without =
      "2,3,5,7,9,10,11,34,36,40,41,42,43,44,45,46,47,48,69,71,72,73,74,78,79,80,81,82,83,84,91,93,"
      "95,96,131,133,134,141,142,143,148,149,150,151,157,159,160,164,165";
  const CliRun r = Cairn("check " + vault + " --format compas --friction 0.84 --without " +
                         without + " --supports 12,35,77,86,132,158,161 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out.substr(0, 2000);
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["verdict"], "stable");
  const std::string diagnostics = doc["diagnostics"];
  EXPECT_NE(diagnostics.find("component 0 (110 parts"), std::string::npos) << diagnostics;
  EXPECT_NE(diagnostics.find("decided by equilibrium"), std::string::npos) << diagnostics;
  EXPECT_NE(diagnostics.find("the static equilibrium (dual simplex) solves the LCP"),
            std::string::npos)
      << diagnostics;
}

// The cross vault at its critical friction (`cairn margin`: μ* = 0.5471339;
// the check stands from there): its equilibrium LP's feasible set is nearly
// a point. The interior-point method's first 60 iterations give no point
// that passes the re-check, the mechanism LP finds none; the method run on
// with its crossover to a vertex at the simplex's tolerance decides it (the
// dual simplex from the slack basis took three times as long; on the
// Armadillo at its μ*, 9 s against 3 s).
TEST(CheckVerdict, AtTheCriticalFrictionTheVertexOfTheInteriorPointDecides) {
  const std::string vault =
      testing::SharedDir() + "/datasets/compas_assembly/crossvault_assembly.json";
  if (testing::SharedDir().empty() || !std::filesystem::exists(vault))
    GTEST_SKIP() << "the shared data (CAIRN_SHARED_DIR) is absent";
  const CliRun r = Cairn("check " + vault + " --format compas --friction 0.547133863767352 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out.substr(0, 2000);
  const nlohmann::json doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["verdict"], "stable");
  EXPECT_EQ(doc["static_equilibrium"], true);
  const std::string diagnostics = doc["diagnostics"];
  EXPECT_NE(diagnostics.find("the static equilibrium (barrier with crossover) solves the LCP"),
            std::string::npos)
      << diagnostics;
}

// The lines of `text` that list a contact or a pair ("X pushes Y").
size_t PushLines(const std::string& text) {
  std::istringstream in(text);
  size_t n = 0;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("    ", 0) == 0 && line.find(" pushes ") != std::string::npos) ++n;
  return n;
}

// --contacts: the summary (default) lists the most loaded contacts and the
// pairs' resultants, 10 of each at most; all lists every contact, as the
// JSON does; none lists none. The solver's notes are said once (no
// "diagnostics:" line repeating a component's).
TEST(CheckContacts, SummaryByDefaultEveryContactWithAll) {
  const std::string wall = ExamplePath("wall.json");
  const CliRun json = Cairn("check " + wall + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const size_t contacts = nlohmann::json::parse(json.out)["contacts"].size();
  ASSERT_GT(contacts, 100u);
  const CliRun summary = Cairn("check " + wall);
  ASSERT_EQ(summary.exit_code, 0) << summary.err;
  EXPECT_NE(summary.out.find(" contacts carry a normal force; the 10 most loaded (every contact: "
                             "--contacts all):\n"),
            std::string::npos)
      << summary.out;
  EXPECT_NE(summary.out.find("per pair of parts, the resultant of its contact forces (force "
                             "units): the 10 largest of "),
            std::string::npos)
      << summary.out;
  EXPECT_EQ(PushLines(summary.out), 20u) << summary.out;
  EXPECT_EQ(summary.out.find("diagnostics:"), std::string::npos) << summary.out;
  const CliRun all = Cairn("check " + wall + " --contacts all");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_EQ(PushLines(all.out), contacts);
  const CliRun none = Cairn("check " + wall + " --contacts none");
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_EQ(PushLines(none.out), 0u) << none.out;
  EXPECT_NE(none.out.find("STABLE"), std::string::npos) << none.out;
  const CliRun bad = Cairn("check " + wall + " --contacts some");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--contacts"), std::string::npos) << bad.err;
}

// The pairs' resultants are the sums of their contacts' forces, on the part
// pushed: the incline carries the whole weight of the block resting on it,
// straight up (m g = 0.5 × 9.81 = 4.905), friction included.
TEST(CheckContacts, APairsResultantIsTheSumOfItsContactForces) {
  const CliRun json = Cairn("check " + ExamplePath("incline.json") + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json doc = nlohmann::json::parse(json.out);
  double weight = 0;
  for (const auto& part : doc["parts"])
    if (part["name"] == "block") weight = part["mass"].get<double>() * 9.81;
  ASSERT_NEAR(weight, 4.905, 1e-9);
  const CliRun r = Cairn("check " + ExamplePath("incline.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  per pair of parts, the resultant of its contact forces (force units): "
                       "1 pair with a force:\n"
                       "    incline pushes block (2 contacts): (0, 4.905), magnitude 4.905\n"),
            std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace cairn

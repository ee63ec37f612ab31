// `--format step` and `--format asap` end to end, and `cairn blocking
// --direction`: a STEP file OpenCASCADE writes here gives the same answers as
// the same model written as a scene; the Bourjault pen (FreeCAD-APLAN, LGPL,
// read from ../shared) gives the published blocking graphs along +x, +y, +z
// and disassembly sequences; ASAP's beam assembly loads and is blocked as its
// README says; bad STEP input exits 2.
#include <gtest/gtest.h>

#include <BRepAlgoAPI_Fuse.hxx>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "cli/cli_run.h"
#include "step_writer.h"
#include "test_paths.h"

namespace cairn {
namespace {

using nlohmann::json;
using testing::Cairn;
using Arcs = std::set<std::pair<std::string, std::string>>;

// The arcs [blocked, blocker] to infinity of the one cell of `blocking --json`.
Arcs InfinityArcs(const std::string& out) {
  const json doc = json::parse(out);
  EXPECT_EQ(doc["cells"].size(), 1u);
  Arcs arcs;
  for (const json& a : doc["cells"][0]["infinity"])
    arcs.insert({a[0].get<std::string>(), a[1].get<std::string>()});
  return arcs;
}

// `cairn blocking STEP --format step --direction d` for each (d, arcs): exit
// 0, and exactly those arcs to infinity.
void ExpectArcsAlong(const std::string& step,
                     const std::vector<std::pair<std::string, Arcs>>& cases) {
  for (const auto& [d, expected] : cases) {
    SCOPED_TRACE(d);
    const auto r = Cairn("blocking " + step + " --format step --direction " + d + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(InfinityArcs(r.out), expected);
  }
}

std::string PegFiles(std::string& scene) {
  const std::string dir = testing::TempDir("step_cli");
  std::filesystem::create_directories(dir);
  const std::string step = dir + "/pegs.step";
  EXPECT_TRUE(testing::WritePegAssembly(step));
  scene = dir + "/pegs.json";
  std::ofstream(scene) << testing::PegSceneJson();
  return step;
}

// The same model from STEP and from a scene: the same verdict and forces'
// summary, the same blocking graphs; convert writes a scene that reads back.
TEST(StepCommand, RoundTripsThePegAssemblyAsItsSceneFile) {
  std::string scene;
  const std::string step = PegFiles(scene);
  const auto a = Cairn("check " + step + " --format step --fixed table --json");
  const auto b = Cairn("check " + scene + " --supports table --json");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(json::parse(a.out)["verdict"], json::parse(b.out)["verdict"]);
  EXPECT_EQ(a.err, "") << "nothing is approximated: no notes";
  for (const char* d : {"0,0,1", "1,0,0", "0,1,0", "0,0.6,0.8"}) {
    SCOPED_TRACE(d);
    const auto sa = Cairn("blocking " + step + " --format step --direction " + d + " --json");
    const auto sb = Cairn("blocking " + scene + " --direction " + d + " --json");
    ASSERT_EQ(sa.exit_code, 0) << sa.err;
    ASSERT_EQ(sb.exit_code, 0) << sb.err;
    EXPECT_EQ(InfinityArcs(sa.out), InfinityArcs(sb.out));
  }
  // Straight up, the standing peg and the lying one leave; the block is held
  // by the standing peg (in its pocket) and the lying one (on it).
  const auto up = Cairn("blocking " + step + " --format step --direction 0,0,1 --json");
  const json cell = json::parse(up.out)["cells"][0];
  EXPECT_EQ(cell["removable"], json::array({"peg", "peg_2"}));
  EXPECT_TRUE(InfinityArcs(up.out).count({"block", "peg"}));
  EXPECT_TRUE(InfinityArcs(up.out).count({"block", "peg_2"}));
  // Convert: a scene file a user can edit, that reads back to the same answer.
  const std::string out = std::filesystem::path(scene).parent_path() / "converted.json";
  const auto c = Cairn("convert " + step + " " + out + " --format step --fixed table");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const auto d = Cairn("check " + out + " --json");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(json::parse(d.out)["verdict"], json::parse(a.out)["verdict"]);
  std::filesystem::remove_all(std::filesystem::path(scene).parent_path());
}

TEST(StepCommand, SidecarGivesWhatStepDoesNotCarry) {
  std::string scene;
  const std::string step = PegFiles(scene);
  const std::string dir = std::filesystem::path(scene).parent_path();
  std::ofstream(dir + "/side.json") << R"({"cairn_sidecar": 1, "friction": 0.4, "density": 7800,
             "parts": {"table": {"fixed": true}, "peg_2": {"mass": 0.5}}})";
  const auto r = Cairn("convert " + step + " " + dir + "/out.json --format step --sidecar " + dir +
                       "/side.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json s = json::parse(testing::Slurp(dir + "/out.json"));
  EXPECT_EQ(s["friction"], 0.4);
  for (const json& p : s["parts"]) {
    if (p["name"] == "table") {
      EXPECT_EQ(p.value("fixed", false), true);
    }
    if (p["name"] == "peg_2") {
      EXPECT_EQ(p["mass"], 0.5);
    } else {
      EXPECT_EQ(p["density"], 7800);
    }
  }
  // A part the model does not have: exit 2, naming the sidecar and the key.
  std::ofstream(dir + "/bad.json") << R"({"cairn_sidecar": 1, "parts": {"bolt": {"fixed": true}}})";
  const auto bad = Cairn("check " + step + " --format step --sidecar " + dir + "/bad.json");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.json: parts.bolt: the model has no part of this name"),
            std::string::npos)
      << bad.err;
  std::filesystem::remove_all(dir);
}

TEST(StepCommand, BadStepInputExitsTwoNamingTheFileAndPart) {
  const std::string dir = testing::TempDir("step_bad");
  std::filesystem::create_directories(dir);
  // Not STEP.
  std::ofstream(dir + "/scene.stp") << "{\"cairn\": 1}";
  auto r = Cairn("check " + dir + "/scene.stp --format step");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("scene.stp: not a STEP file"), std::string::npos) << r.err;
  // Interpenetrating parts: the error names both, with the volume their
  // exact solids share (a 5 mm cube), and the ways on.
  ASSERT_TRUE(testing::WriteStepAssembly(dir + "/overlap.stp", "overlap",
                                         {{"a", testing::Box(0, 0, 0, 10, 10, 10), gp_Trsf()},
                                          {"b", testing::Box(5, 5, 5, 15, 15, 15), gp_Trsf()}}));
  r = Cairn("blocking " + dir + "/overlap.stp --format step");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("overlap.stp: parts[1] (\"b\"): 1 pair of parts interfere: 'a' and 'b': "
                       "1.25e-07 m^3 in common (exact solids)"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--fastened a:b"), std::string::npos) << r.err;
  // Flags: --mesh-tolerance belongs to step; --direction needs a direction.
  r = Cairn("check " + dir + "/overlap.stp --mesh-tolerance 0.001");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--mesh-tolerance: applies to --format step only"), std::string::npos)
      << r.err;
  r = Cairn("blocking " + testing::ExamplePath("stack3.json") + " --direction 0,0,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--direction: must not be the zero vector"), std::string::npos) << r.err;
  std::filesystem::remove_all(dir);
}

// A mass or density the sidecar sets that the model refuses is the
// sidecar's fault, at its JSON path (not the STEP file's `parts[i].mass`).
TEST(StepCommand, SidecarMassFaultsNameTheSidecar) {
  std::string scene;
  const std::string step = PegFiles(scene);
  const std::string dir = std::filesystem::path(scene).parent_path();
  struct Case {
    const char* sidecar;
    const char* where;
  };
  for (const Case& c : {
           Case{R"({"cairn_sidecar": 1, "parts": {"peg_2": {"mass": 1e40}}})",
                "side.json: parts.peg_2.mass: the part's mass 1e+40 is out of range"},
           Case{R"({"cairn_sidecar": 1, "parts": {"peg_2": {"mass": 1e-20}}})",
                "side.json: parts.peg_2.mass: the part's mass 1e-20 is less than 1/1e+09"},
           Case{R"({"cairn_sidecar": 1, "density": 1e-40})", "side.json: density: the part's mass"},
           Case{R"({"cairn_sidecar": 1, "parts": {"peg": {"density": 1e35}}})",
                "side.json: parts.peg.density: the part's mass"},
       }) {
    std::ofstream(dir + "/side.json") << c.sidecar;
    const auto r = Cairn("check " + step + " --format step --sidecar " + dir + "/side.json");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(c.where), std::string::npos) << c.sidecar << "\n" << r.err;
    EXPECT_EQ(r.err.find("pegs.step"), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

// --mesh-tolerance out of what OpenCASCADE tessellates, or so coarse that
// the facets cross: the option's fault, said as such (the pen's cap.stp).
TEST(StepCommand, MeshToleranceFaultsNameTheOption) {
  const std::string shared = testing::SharedDir();
  if (shared.empty()) GTEST_SKIP() << "shared/datasets not found: skipping the pen's cap.stp";
  const std::string cap = shared + "/datasets/aplan_bourjault_pen_simple/cap.stp";
  for (const auto& [tolerance, phrase] : std::vector<std::pair<std::string, std::string>>{
           {"1e306", "m is larger than the part 'Body' of " + cap},
           {"1e300", "m is larger than the part 'Body' of " + cap},
           {"1e-12", "m is finer than OpenCASCADE tessellates " + cap + ": at least 1e-10 m"},
           {"1e-9", "m is finer than 1e-05 of the part 'Body' of " + cap},
           {"0.005", "the tessellation of part 'Body' is not a valid solid"}}) {
    SCOPED_TRACE(tolerance);
    const auto r = Cairn("check " + cap + " --format step --mesh-tolerance " + tolerance);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("cairn: error: --mesh-tolerance: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(phrase), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(the default for this file is"), std::string::npos) << r.err;
  }
}

// A STEP file is untrusted input: the pen's part files edited as the
// reproducers edit them (a dangling reference, NUL bytes, NAN and 1.E400
// coordinates; read in shared/repro) exit 2 naming the file, never a crash
// or a hang; and so do a device, a loop of links and a name too long.
TEST(StepCommand, BrokenStepFilesExitTwoNamingTheFile) {
  const std::string shared = testing::SharedDir();
  if (shared.empty()) GTEST_SKIP() << "shared/repro not found: skipping the STEP reproducers";
  const std::string repro = shared + "/repro/hostile3/";
  for (const std::string& file : {repro + "step_dangling_ref_segv/head_del_line24.stp",
                                  repro + "step_dangling_ref_segv/head_del_edge_loop.stp",
                                  repro + "step_dangling_ref_segv/cartridge_100nul_at_4147.stp",
                                  repro + "step_dangling_ref_segv/body_nan_inf_point.stp",
                                  repro + "step_nan_point_hang/body_nan.stp",
                                  repro + "step_nan_point_hang/body_multi_mutation.stp"}) {
    SCOPED_TRACE(file);
    const auto r = Cairn("check " + file + " --format step");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("cairn: error: " + file + ": ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  const auto r = Cairn("blocking " + repro + "step_nan_point_hang/body_multi_mutation.stp " +
                       "--format step --direction 1,0,0");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const auto z = Cairn("check /dev/zero --format step");
  EXPECT_EQ(z.exit_code, 2);
  EXPECT_EQ(z.err, "cairn: error: /dev/zero: is a character device, not a regular file\n");
  const std::string dir = testing::TempDir("step_paths");
  std::filesystem::create_directories(dir);
  std::filesystem::create_symlink("loop.stp", dir + "/loop.stp");
  const auto loop = Cairn("check " + dir + "/loop.stp --format step");
  EXPECT_EQ(loop.exit_code, 2);
  EXPECT_NE(loop.err.find(dir + "/loop.stp: cannot open the STEP file: a loop of symbolic links"),
            std::string::npos)
      << loop.err;
  const std::string long_name = dir + "/" + std::string(300, 'a') + ".stp";
  const auto named = Cairn("check " + long_name + " --format step");
  EXPECT_EQ(named.exit_code, 2);
  EXPECT_NE(named.err.find(long_name + ": cannot open the STEP file: the file name is too long"),
            std::string::npos)
      << named.err;
  std::filesystem::remove_all(dir);
}

// The pen's part files mutated at random (a fixed seed): a line deleted, NUL
// bytes inserted, a number replaced by NAN or 1E400. Each gives a verdict
// (exit 0 or 1: the edit broke nothing that matters; a part file alone has
// nothing fixed and falls) or exit 2 naming the file: never a crash, an
// internal error or a hang.
TEST(StepCommand, MutatedPenFilesGiveAVerdictOrExitTwo) {
  const std::string shared = testing::SharedDir();
  if (shared.empty()) GTEST_SKIP() << "shared/datasets not found: skipping the pen's part files";
  const std::string pen = shared + "/datasets/aplan_bourjault_pen_simple/";
  const std::vector<std::string> parts = {"body.stp",      "button.stp", "cap.stp",
                                          "cartridge.stp", "head.stp",   "ink.stp"};
  const std::string dir = testing::TempDir("step_mutated");
  std::filesystem::create_directories(dir);
  std::mt19937 random(20261127);
  const auto pick = [&](size_t n) {
    return std::uniform_int_distribution<size_t>(0, n - 1)(random);
  };
  int verdicts = 0, exit_two = 0;
  for (int k = 0; k < 30; ++k) {
    const std::string part = parts[pick(parts.size())];
    std::string text = testing::Slurp(pen + part);
    const int kind = k % 3;
    if (kind == 0) {  // delete a line
      std::vector<size_t> starts = {0};
      for (size_t i = 0; i + 1 < text.size(); ++i)
        if (text[i] == '\n') starts.push_back(i + 1);
      const size_t line = pick(starts.size());
      const size_t end = text.find('\n', starts[line]);
      text.erase(starts[line],
                 end == std::string::npos ? std::string::npos : end + 1 - starts[line]);
    } else if (kind == 1) {  // insert NUL bytes
      text.insert(pick(text.size()), std::string(1 + pick(100), '\0'));
    } else {  // a number replaced by NAN or 1E400
      std::vector<std::pair<size_t, size_t>> numbers;
      for (size_t i = text.find("DATA;"); i < text.size(); ++i) {
        if (!std::isdigit(static_cast<unsigned char>(text[i])) || text[i - 1] == '#' ||
            std::isdigit(static_cast<unsigned char>(text[i - 1])))
          continue;
        size_t j = i;
        while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) ||
                                   text[j] == '.' || text[j] == 'E' || text[j] == '-'))
          ++j;
        numbers.push_back({i, j - i});
        i = j;
      }
      const auto [at, length] = numbers[pick(numbers.size())];
      text.replace(at, length, random() % 2 ? "NAN" : "1E400");
    }
    const std::string file = dir + "/" + std::to_string(k) + "_" + part;
    std::ofstream(file, std::ios::binary) << text;
    SCOPED_TRACE(file);
    const auto r = Cairn("check " + file + " --format step");
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1 || r.exit_code == 2)
        << r.exit_code << ": " << r.err;
    if (r.exit_code == 2) {
      EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    }
    (r.exit_code == 2 ? exit_two : verdicts)++;
  }
  EXPECT_EQ(verdicts + exit_two, 30);
  EXPECT_GT(exit_two, 0);  // the mutations do break files
  std::filesystem::remove_all(dir);
}

// The pen against FreeCAD-APLAN's ground truth. Its arcs (source, target) are
// "source moving along +axis is blocked by target": Cairn's [blocked,
// blocker], the same orientation (the +x graph, which is not symmetric,
// decides: the cap, at the −x end, is blocked by all five others).
TEST(StepCommand, BourjaultPenBlockingEqualsTheGroundTruth) {
  const std::string shared = testing::SharedDir();
  if (shared.empty())
    GTEST_SKIP() << "shared/datasets not found: skipping the Bourjault pen (FreeCAD-APLAN)";
  const std::string dir = shared + "/datasets/aplan_bourjault_pen_simple";
  const std::string pen = dir + "/asm_bourjault_ballpoint.stp";
  for (const auto& [axis, direction] : std::vector<std::pair<std::string, std::string>>{
           {"X", "1,0,0"}, {"Y", "0,1,0"}, {"Z", "0,0,1"}}) {
    SCOPED_TRACE(axis);
    const auto r = Cairn("blocking " + pen + " --format step --direction " + direction + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(dir + "/GroundTruth/GeomConstraints_POS_" + axis + ".json");
    const json truth = json::parse(in);
    Arcs expected;
    for (const json& link : truth["links"])
      expected.insert({link["source"].get<std::string>(), link["target"].get<std::string>()});
    EXPECT_EQ(InfinityArcs(r.out), expected);
    // Every part approximated, and said so.
    for (const char* part :
         {"body_001", "button_001", "cap_001", "cartridge_001", "head_001", "ink_001"})
      EXPECT_NE(r.err.find("part '" + std::string(part) + "' approximated"), std::string::npos);
  }
}

// FreeCAD-APLAN's shear mold (17 parts: plates, guide pins in holes, bushes,
// a stepped rod through two bushes whose cone OpenCASCADE cannot mesh) loads
// at the defaults: its pins and holes, tessellated within the chordal
// tolerance but not node on node, cross by less than that, which the overlap
// test allows (AssemblyDef::overlap_allowance). Its blocking graphs along
// +X, +Y and +Z equal the ground truth (37, 52 and 34 arcs): no arc from
// edges crossing on a flush face (the rod's end in its plate's plane) or
// along the same tessellated cylinder (the rod in its bushes, whose edge
// crossings have normals within the facets' accuracy of the axis).
void ExpectShearMoldBlocking(const std::string& axis, const std::string& direction) {
  const std::string shared = testing::SharedDir();
  if (shared.empty())
    GTEST_SKIP() << "shared/datasets not found: skipping the shear mold (FreeCAD-APLAN)";
  const std::string dir = shared + "/datasets/aplan_shear_mold";
  const std::string mold = dir + "/asm_shear_mold.step";
  const auto r = Cairn("blocking " + mold + " --format step --direction " + direction + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("part '14_001': face 6 (a cone) could not be meshed by OpenCASCADE"),
            std::string::npos)
      << r.err;
  std::ifstream in(dir + "/GroundTruth/GeomConstraints_POS_" + axis + ".json");
  const json truth = json::parse(in);
  Arcs expected;
  for (const json& link : truth["links"])
    expected.insert({link["source"].get<std::string>(), link["target"].get<std::string>()});
  EXPECT_EQ(InfinityArcs(r.out), expected);
}

TEST(StepCommand, ShearMoldBlockingAlongXEqualsTheGroundTruth) {
  ExpectShearMoldBlocking("X", "1,0,0");
}
TEST(StepCommand, ShearMoldBlockingAlongYEqualsTheGroundTruth) {
  ExpectShearMoldBlocking("Y", "0,1,0");
}
TEST(StepCommand, ShearMoldBlockingAlongZEqualsTheGroundTruth) {
  ExpectShearMoldBlocking("Z", "0,0,1");
}

// The shear mold's plan: its top plate 1_001 fixed and no gravity (the
// ground truth is geometric: a die set's moving plate slides on its guide
// pins, held by the press), along the axes. A sequence takes the 16 other
// parts out, each once, and every step's move is free in the ground truth:
// no part moved is blocked, along the step's axis, by a part still in (GT
// holds +X, +Y, +Z; a part moving along −X is blocked by the parts that are
// blocked by it along +X).
TEST(StepCommand, ShearMoldPlanTakesEveryPartOutAsTheGroundTruthAllows) {
  const std::string shared = testing::SharedDir();
  if (shared.empty())
    GTEST_SKIP() << "shared/datasets not found: skipping the shear mold (FreeCAD-APLAN)";
  const std::string dir = shared + "/datasets/aplan_shear_mold";
  const auto r = Cairn("plan " + dir +
                       "/asm_shear_mold.step --format step --fixed 1_001 --gravity 0,0,0 "
                       "--directions axes --max 1 --threads 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, Arcs> truth;
  for (const std::string axis : {"X", "Y", "Z"}) {
    std::ifstream in(dir + "/GroundTruth/GeomConstraints_POS_" + axis + ".json");
    const json links = json::parse(in)["links"];
    for (const json& link : links)
      truth[axis].insert({link["source"].get<std::string>(), link["target"].get<std::string>()});
  }
  const json doc = json::parse(r.out);
  ASSERT_EQ(doc["sequences"].size(), 1u) << r.out.substr(0, 2000);
  std::set<std::string> in;
  for (int k = 2; k <= 17; ++k) in.insert(std::to_string(k) + "_001");
  for (const json& step : doc["sequences"][0]["steps"]) {
    std::set<std::string> moved;
    for (const json& part : step["remove"]) moved.insert(part.get<std::string>());
    const std::vector<double> d = step["direction"].get<std::vector<double>>();
    int axis = -1;
    for (int k = 0; k < 3; ++k)
      if (std::abs(std::abs(d[k]) - 1) < 1e-12) axis = k;
    ASSERT_GE(axis, 0) << step.dump();
    const Arcs& arcs = truth[std::string(1, "XYZ"[axis])];
    const bool positive = d[axis] > 0;
    std::set<std::string> staying = in;
    staying.insert("1_001");
    for (const std::string& m : moved) staying.erase(m);
    for (const std::string& m : moved) {
      ASSERT_EQ(in.erase(m), 1u) << m << " taken out twice or never in: " << step.dump();
      for (const std::string& other : staying)
        EXPECT_FALSE(arcs.count(positive ? std::pair(m, other) : std::pair(other, m)))
            << m << " is blocked by " << other << ": " << step.dump();
    }
  }
  EXPECT_TRUE(in.empty()) << in.size() << " parts left in, e.g. " << *in.begin();
}

// The pen lying along x on its fixed body: the sequences take the cap off to
// −x and the button end to +x, and the head comes out last of all.
TEST(StepCommand, BourjaultPenPlanFindsDisassemblySequences) {
  const std::string shared = testing::SharedDir();
  if (shared.empty())
    GTEST_SKIP() << "shared/datasets not found: skipping the Bourjault pen (FreeCAD-APLAN)";
  const std::string pen =
      shared + "/datasets/aplan_bourjault_pen_simple/asm_bourjault_ballpoint.stp";
  const auto r =
      Cairn("plan " + pen + " --format step --fixed body_001 --directions axes --threads 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json doc = json::parse(r.out);
  ASSERT_FALSE(doc["sequences"].empty()) << r.out.substr(0, 2000);
  // Each sequence takes the five movable parts out, each exactly once, and
  // the ink never before the button (along +X the ground truth has the ink
  // blocked by the button, and the axes offer it no other way out first).
  const std::set<std::string> movable = {"cap_001", "button_001", "ink_001", "cartridge_001",
                                         "head_001"};
  for (const json& seq : doc["sequences"]) {
    std::multiset<std::string> removed;
    std::map<std::string, size_t> step_of;
    for (size_t k = 0; k < seq["steps"].size(); ++k)
      for (const json& part : seq["steps"][k]["remove"]) {
        removed.insert(part.get<std::string>());
        step_of[part.get<std::string>()] = k;
      }
    EXPECT_EQ(std::set<std::string>(removed.begin(), removed.end()), movable) << seq.dump();
    EXPECT_EQ(removed.size(), movable.size()) << seq.dump();
    EXPECT_LE(step_of["button_001"], step_of["ink_001"]) << seq.dump();
  }
}

// Pins in the holes of a plate (mm), written by OpenCASCADE: `tight` of the
// hole's radius, 5 (the surfaces coincide), and `line` of radius 4.9 moved 0.1
// along +x, touching its hole along one line; each pin's seam turned 0.1 rad
// from its hole's. They load at the defaults. Along the pins' axis everything
// slides free; across it each pin and the plate block each other (a pin with
// its 0.2 mm of play is still blocked on the way to infinity), and along x
// the pins block each other.
TEST(StepCommand, PinsInHolesLoadAndBlockAcrossTheirAxisOnly) {
  const std::string dir = testing::TempDir("step_pins");
  std::filesystem::create_directories(dir);
  const std::string step = dir + "/pins.step";
  const TopoDS_Shape plate = BRepAlgoAPI_Cut(BRepAlgoAPI_Cut(testing::Box(0, 0, 0, 60, 40, 10),
                                                             testing::Cylinder(15, 20, -1, 5, 12))
                                                 .Shape(),
                                             testing::Cylinder(45, 20, -1, 5, 12))
                                 .Shape();
  ASSERT_TRUE(
      testing::WriteStepAssembly(step, "pins",
                                 {{"plate", plate, gp_Trsf()},
                                  {"tight", testing::Cylinder(15, 20, -10, 5, 30), gp_Trsf()},
                                  {"line", testing::Cylinder(45.1, 20, -10, 4.9, 30), gp_Trsf()}}));
  const auto up = Cairn("blocking " + step + " --format step --direction 0,0,1 --json");
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_EQ(InfinityArcs(up.out), Arcs{});
  const Arcs pins_and_plate = {
      {"line", "plate"}, {"plate", "line"}, {"plate", "tight"}, {"tight", "plate"}};
  // Along ±x the pins also meet each other on the way out.
  Arcs plus_x = pins_and_plate, minus_x = pins_and_plate;
  plus_x.insert({"tight", "line"});
  minus_x.insert({"line", "tight"});
  ExpectArcsAlong(step, {{"1,0,0", plus_x}, {"-1,0,0", minus_x}, {"0,1,0", pins_and_plate}});
  std::filesystem::remove_all(dir);
}

// A block sitting in the inside corner of an L-shaped plate (mm, written by
// OpenCASCADE: the plate one solid, its floor z = 10 and its wall x = 10),
// touching the floor and the wall, its edge along the plate's inside corner.
// Along the plate's faces (+x, +z and ±y) and away from them the block
// leaves free, blocked only into the floor (−z) and into the wall (−x); the
// plate is blocked by it only where its floor or wall would push it. The
// corner edge, where the block's edge lies in the plate's, adds no
// constraint of its own (issue 31: zero-area contacts there forbade sliding
// along the faces).
TEST(StepCommand, ABlockInTheInsideCornerOfAnLPlateBlocksNothingAlongItsFaces) {
  const std::string dir = testing::TempDir("step_l_plate");
  std::filesystem::create_directories(dir);
  const std::string step = dir + "/l_plate.step";
  const TopoDS_Shape plate =
      BRepAlgoAPI_Cut(testing::Box(0, 0, 0, 100, 80, 60), testing::Box(10, -1, 10, 101, 81, 61))
          .Shape();
  ASSERT_TRUE(testing::WriteStepAssembly(
      step, "l_plate",
      {{"plate", plate, gp_Trsf()}, {"block", testing::Box(10, 20, 10, 40, 50, 30), gp_Trsf()}}));
  const Arcs block_held = {{"block", "plate"}}, plate_held = {{"plate", "block"}};
  ExpectArcsAlong(step, {{"0,1,0", {}},
                         {"0,-1,0", {}},
                         {"1,0,0", plate_held},
                         {"0,0,1", plate_held},
                         {"1,0,1", plate_held},
                         {"-1,0,0", block_held},
                         {"0,0,-1", block_held}});
  std::filesystem::remove_all(dir);
}

// A bolt modelled 1 mm into the plate it stands on (mm, OpenCASCADE: a 1 × 1
// mm key under its head, 1 mm deep in the plate: 1 mm³ of interference, as
// modelled threads and press fits have). Refused with exit 2 naming the
// pair, the exact common volume (1e-9 m³) and the ways on; with --fastened
// the two load as one rigid part "plate+bolt"; with --touching the bolt
// loses its 1 mm³ and stands on the plate: free upwards, held downwards.
TEST(StepCommand, AnInterferenceIsListedWithItsVolumeThenFastenedOrMadeToTouch) {
  const std::string dir = testing::TempDir("step_interference");
  std::filesystem::create_directories(dir);
  const std::string step = dir + "/bolt.step";
  const TopoDS_Shape bolt =
      BRepAlgoAPI_Fuse(testing::Box(10, 10, 10, 20, 20, 15), testing::Box(14, 14, 9, 15, 15, 10))
          .Shape();
  ASSERT_TRUE(testing::WriteStepAssembly(
      step, "bolted",
      {{"plate", testing::Box(0, 0, 0, 30, 30, 10), gp_Trsf()}, {"bolt", bolt, gp_Trsf()}}));
  const auto refused = Cairn("check " + step + " --format step");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("1 pair of parts interfere: 'plate' and 'bolt': 1e-09 m^3 in common "
                             "(exact solids)"),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--fastened plate:bolt"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--touching plate:bolt"), std::string::npos) << refused.err;

  const auto fastened =
      Cairn("check " + step + " --format step --fastened plate:bolt --fixed plate+bolt --json");
  ASSERT_EQ(fastened.exit_code, 0) << fastened.err;
  const json one = json::parse(fastened.out);
  ASSERT_EQ(one["parts"].size(), 1u) << fastened.out.substr(0, 500);
  EXPECT_EQ(one["parts"][0]["name"], "plate+bolt");
  EXPECT_NE(fastened.err.find("parts 'plate', 'bolt' fastened (--fastened)"), std::string::npos)
      << fastened.err;

  const auto up =
      Cairn("blocking " + step + " --format step --touching plate:bolt --direction 0,0,1 --json");
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_EQ(InfinityArcs(up.out), (Arcs{{"plate", "bolt"}}));
  EXPECT_NE(up.err.find("part 'bolt': cut by part 'plate' where they overlap (--touching): 1e-09 "
                        "m^3 less"),
            std::string::npos)
      << up.err;
  const auto down =
      Cairn("blocking " + step + " --format step --touching plate:bolt --direction 0,0,-1 --json");
  ASSERT_EQ(down.exit_code, 0) << down.err;
  EXPECT_EQ(InfinityArcs(down.out), (Arcs{{"bolt", "plate"}}));

  // Bad pairs: exit 2 naming the option.
  for (const auto& [flags, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--fastened plate", "--fastened: \"plate\" is not a pair of part names A:B"},
           {"--fastened plate:nut", "--fastened: no part named 'nut' in " + step},
           {"--touching bolt:bolt", "--touching: part 'bolt' is paired with itself"}}) {
    const auto bad = Cairn("check " + step + " --format step " + flags);
    EXPECT_EQ(bad.exit_code, 2) << flags << ": " << bad.err;
    EXPECT_NE(bad.err.find(expected), std::string::npos) << flags << ": " << bad.err;
  }
  const auto scene = Cairn("check " + testing::ExamplePath("stack3.json") + " --fastened A:B");
  EXPECT_EQ(scene.exit_code, 2);
  EXPECT_NE(scene.err.find("--fastened: applies to --format step only"), std::string::npos)
      << scene.err;
  std::filesystem::remove_all(dir);
}

// ASAP's beams on their posts (README): every mesh loads; a top beam leaves
// straight up, and the post under it is held by it. (Beam 0 and its post 2
// only: the full assembly, whose base beam has 24 606 triangles, takes 35 s
// in Release and many minutes under the sanitizers; it gives 0, 1 leaving,
// 2 by 0, 3 by 1 and 6 by 0, 1, 2, 3, docs/step-format.md.)
TEST(StepCommand, AsapBeamAssemblyBlocking) {
  const std::string shared = testing::SharedDir();
  if (shared.empty()) GTEST_SKIP() << "shared/datasets not found: skipping the ASAP beam assembly";
  // The meshes interpenetrate by up to ~1e-4 (inches): that is the tolerance.
  const auto r = Cairn("blocking " + shared +
                       "/datasets/asap_beam_assembly --format asap --tolerance 1e-4 "
                       "--without 1,3,6 --direction 0,0,1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json cell = json::parse(r.out)["cells"][0];
  EXPECT_EQ(cell["removable"], json::array({"0"}));
  EXPECT_EQ(InfinityArcs(r.out), (Arcs{{"2", "0"}}));
}

}  // namespace
}  // namespace cairn

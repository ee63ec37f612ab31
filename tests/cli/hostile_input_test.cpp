// Hostile input: every reproducer of a hostile-input round, run as a user runs
// it (the real binary), with the exit code and the message it must give. Bad
// input is exit 2 with the file, the JSON path (or the option) and what is
// wrong, on one line; never a crash (exit ≥ 128), an internal error (4), a
// hang or a silent wrong answer.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_run.h"
#include "test_paths.h"

namespace cairn {
namespace {

using nlohmann::json;
using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;
using testing::TempFile;

json Load(const std::string& example) {
  std::ifstream in(ExamplePath(example));
  return json::parse(in);
}

std::string Write(const std::string& name, const json& doc) { return TempFile(name, doc.dump()); }

// One line on stderr, starting "cairn: error: ", containing every `parts`.
void ExpectBadInput(const CliRun& r, std::initializer_list<const char*> parts) {
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("cairn: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const char* p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << p << " in " << r.err;
}

// stack3.json with part `index` changed by `edit`.
std::string EditedStack(const std::string& name, int index,
                        const std::function<void(json&)>& edit) {
  json doc = Load("stack3.json");
  edit(doc["parts"][index]);
  return Write(name, doc);
}

// --- Extreme but finite numbers: refused where read, with the part's path.

TEST(HostileScene, AHugeOrDenormalMassIsOutOfRangeNotAnAbort) {
  for (const double m : {1e308, 1e-320, 1e100}) {
    const std::string f = EditedStack("hostile_mass.json", 1, [&](json& p) { p["mass"] = m; });
    ExpectBadInput(Cairn("check " + f),
                   {"hostile_mass.json", "parts[1] (\"A\").mass", "out of range"});
  }
}

TEST(HostileScene, ADenormalDensityIsOutOfRange) {
  const std::string f =
      EditedStack("hostile_density.json", 1, [](json& p) { p["density"] = 5e-324; });
  ExpectBadInput(Cairn("check " + f), {"parts[1] (\"A\").density", "out of range"});
}

TEST(HostileScene, HugeGravityIsOutOfRangeInTheFileOrOnTheCommandLine) {
  json doc = Load("stack3.json");
  doc["gravity"] = {0, -1e308};
  ExpectBadInput(Cairn("check " + Write("hostile_gravity.json", doc)),
                 {"hostile_gravity.json", "gravity: out of range"});
  const CliRun r = Cairn("check " + ExamplePath("stack3.json") + " --gravity=0,-1e100");
  ExpectBadInput(r, {"--gravity: out of range"});
  EXPECT_EQ(r.err.find("stack3.json"), std::string::npos) << "blames the option, not the file";
}

TEST(HostileScene, APartFarAwayNamesTheScaleNotAnInnocentPart) {
  for (const double far : {1e9, 1e12}) {
    const std::string f = EditedStack("hostile_far.json", 3, [&](json& p) {
      p["box"] = {{"min", {far, 0}}, {"max", {far + 1, 1}}};
    });
    const CliRun r = Cairn("check " + f);
    ExpectBadInput(r, {"parts[3] (\"C\")"});
    EXPECT_EQ(r.err.find("self-intersecting"), std::string::npos) << r.err;
  }
}

// In 3-D: a box with faces of area 64, and another 1e9 away; the face used
// to be "zero area" under the tolerance the far box made.
TEST(HostileScene, AFarThreeDPartNamesTheScaleNotAZeroAreaFace) {
  const json doc = json::parse(R"({"cairn": 1, "parts": [
      {"name": "table", "fixed": true, "box": {"min": [-10, -10, -1], "max": [10, 10, 0]}},
      {"name": "slab", "box": {"min": [0, 0, 0], "max": [8, 8, 1]}},
      {"name": "far", "box": {"min": [1e9, 0, 0], "max": [1000000001, 1, 1]}}]})");
  const CliRun r = Cairn("check " + Write("hostile_far3.json", doc));
  ExpectBadInput(r, {"spans too many orders of magnitude"});
  EXPECT_EQ(r.err.find("zero area"), std::string::npos) << r.err;
}

TEST(HostileScene, ACoarseToleranceIsTheOptionsFault) {
  const CliRun r = Cairn("check " + ExamplePath("stack3.json") + " --tolerance 10");
  ExpectBadInput(r, {"--tolerance: too coarse", "'A'"});
  EXPECT_EQ(r.err.find("self-intersecting"), std::string::npos) << r.err;
}

TEST(HostileScene, AThreeDPartAt1e300IsOutOfRange) {
  json doc = Load("paper_fig9.json");
  json& part = doc["parts"][1];
  ASSERT_TRUE(part.contains("box"));
  part["box"]["min"][0] = 1e300;
  part["box"]["max"][0] = 2e300;
  ExpectBadInput(Cairn("check " + Write("hostile_3d_far.json", doc)), {"out of range"});
}

TEST(HostileScene, AValidSceneFollowedByANulByteAndJunkIsRefused) {
  std::ifstream in(ExamplePath("stack3.json"), std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text += std::string(1, '\0') + "junk";
  ExpectBadInput(Cairn("check " + TempFile("hostile_nul.json", text)), {"NUL byte"});
}

TEST(HostileScene, AnEmptyKeyIsNamed) {
  ExpectBadInput(
      Cairn("check " + TempFile("hostile_empty_key.json", R"({"cairn": 1, "": 2, "parts": []})")),
      {"\"\": unknown key"});
}

TEST(HostileScene, APartNameWithANewlineKeepsTheErrorOnOneLine) {
  const std::string f = EditedStack("hostile_newline.json", 2, [](json& p) {
    p["name"] = "B\nC";
    p["box"] = {{"min", {0, 0.5}}, {"max", {2, 1.5}}};  // overlaps A
  });
  ExpectBadInput(Cairn("check " + f), {"B\\nC"});
}

// A single light part decides as a unit-mass one does: the numerics scale
// with the masses (it used to read "UNDECIDED (solver failure)").
TEST(HostileScene, ALightBoxOnATableStandsAsAHeavyOneDoes) {
  for (const double m : {1e-15, 1e-25, 1e25}) {
    json doc = Load("stack3.json");
    doc["parts"] = {doc["parts"][0], doc["parts"][1]};
    doc["parts"][1]["mass"] = m;
    const CliRun r = Cairn("check " + Write("hostile_light.json", doc) + " --json");
    ASSERT_EQ(r.exit_code, 0) << "mass " << m << ": " << r.out << r.err;
    const json out = json::parse(r.out);
    EXPECT_EQ(out["verdict"], "stable");
    double total = 0;
    for (const json& c : out["contacts"]) total += c["normal_force"].get<double>();
    EXPECT_NEAR(total, m * 9.81, 1e-9 * m * 9.81) << "the table carries the weight";
  }
}

// --- Plans: bounded time steps, ranges, a huge direction.

json Fig6Plan() {
  return json::parse(R"({"cairn_plan": 1, "dt": 0.2, "steps": [{"remove": ["C"],
      "path": [[0, 0], [-6, 0], [-6, 4]], "support": "none"}]})");
}

TEST(HostilePlan, TooManyTimeStepsIsAnErrorNotASilentStable) {
  json tiny = Fig6Plan();
  tiny["dt"] = 4e-9;  // 2.5e9 steps: past 2³¹, once "stable" in 2 steps
  ExpectBadInput(
      Cairn("simulate " + ExamplePath("paper_fig6.json") + " " + Write("hostile_dt.json", tiny)),
      {"steps[0] (\"C\")", "time steps", "--max-ticks"});
  json far = Fig6Plan();
  far["dt"] = 1;
  far["steps"][0] = {{"remove", {"C"}}, {"direction", {-1, 0}}, {"distance", 2147483648.0}};
  ExpectBadInput(Cairn("simulate " + ExamplePath("paper_fig6.json") + " " +
                       Write("hostile_distance.json", far)),
                 {"time steps"});
  // Allowed explicitly, a long plan runs (here: the real verdict, unstable).
  json fine = Fig6Plan();
  fine["dt"] = 1e-3;  // 10 000 steps
  const CliRun r = Cairn("simulate " + ExamplePath("paper_fig6.json") + " " +
                         Write("hostile_fine.json", fine) + " --max-ticks 5000");
  ExpectBadInput(r, {"10000 time steps", "5000"});
}

TEST(HostilePlan, HugeDtAndSpeedAreOutOfRange) {
  json plan = Fig6Plan();
  plan["dt"] = 1e308;
  ExpectBadInput(Cairn("simulate " + ExamplePath("paper_fig6.json") + " " +
                       Write("hostile_dt_huge.json", plan)),
                 {"dt: is out of range"});
  plan = Fig6Plan();
  plan["speed"] = 1e308;
  ExpectBadInput(
      Cairn("simulate " + ExamplePath("paper_fig6.json") + " " + Write("hostile_speed.json", plan)),
      {"speed: is out of range"});
}

TEST(HostilePlan, AHugeDirectionIsADirection) {
  json plan = Fig6Plan();
  plan["steps"][0] = {{"remove", {"C"}}, {"direction", {1e308, 0}}, {"distance", 2}};
  json unit = plan;
  unit["steps"][0]["direction"] = {1, 0};
  const CliRun huge = Cairn("simulate " + ExamplePath("paper_fig6.json") + " " +
                            Write("hostile_dir.json", plan) + " --json");
  const CliRun one = Cairn("simulate " + ExamplePath("paper_fig6.json") + " " +
                           Write("hostile_dir1.json", unit) + " --json");
  EXPECT_EQ(huge.exit_code, one.exit_code) << huge.err;
  EXPECT_EQ(json::parse(huge.out)["verdict"], json::parse(one.out)["verdict"]);
}

// --- The candidate-paths file: nesting, duplicate keys, overflow.

TEST(HostilePaths, AMillionNestedArraysIsRefusedNotAStackOverflow) {
  const std::string text = "{\"C\": " + std::string(1000000, '[') + std::string(1000000, ']') + "}";
  ExpectBadInput(Cairn("plan " + ExamplePath("paper_fig6.json") + " --paths " +
                       TempFile("hostile_deep.json", text)),
                 {"nested more than 256"});
}

TEST(HostilePaths, DuplicateKeysAndOverflowingNumbersAreRefused) {
  ExpectBadInput(Cairn("plan " + ExamplePath("paper_fig6.json") + " --paths " +
                       TempFile("hostile_dup.json", R"({"C": [{"direction": [0, 1], "distance": 4}],
                                             "C": [{"direction": [0, 1], "distance": 5}]})")),
                 {"C: duplicate key"});
  ExpectBadInput(
      Cairn("plan " + ExamplePath("paper_fig6.json") + " --paths " +
            TempFile("hostile_1e400.json", R"({"C": [{"direction": [0, 1e400], "distance": 4}]})")),
      {"number overflow"});
}

// --- Options: empty values, nothing left, zero weight, one-line parser errors.

TEST(HostileOptions, EmptyValuesAreRefused) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  const std::string plan = ExamplePath("plans/paper_fig1_c_first.plan.json");
  ExpectBadInput(Cairn("check " + fig1 + " --normalize ''"), {"--normalize: must not be empty"});
  ExpectBadInput(Cairn("simulate " + fig1 + " " + plan + " --timeline ''"),
                 {"--timeline: must not be empty"});
  ExpectBadInput(Cairn("plan " + fig1 + " --dot ''"), {"--dot: must not be empty"});
  ExpectBadInput(Cairn("plan " + fig1 + " --emit-plans ''"), {"--emit-plans: must not be empty"});
  ExpectBadInput(Cairn("check " + fig1 + " --without ,,"), {"--without"});
  ExpectBadInput(Cairn("plan " + fig1 + " --dt 0"), {"--dt: must be a positive number (got 0)"});
}

TEST(HostileOptions, WithoutEveryPartLeavesNothingToCheck) {
  ExpectBadInput(Cairn("check " + ExamplePath("stack3.json") + " --without table,A,B,C"),
                 {"--without", "nothing is left"});
}

TEST(HostileOptions, NormalizingByAWeightlessPartIsRefused) {
  json doc = Load("stack3.json");
  doc["gravity"] = {0, 0};
  ExpectBadInput(Cairn("check " + Write("hostile_nograv.json", doc) + " --normalize A"),
                 {"--normalize", "no weight"});
}

// --- Output files: never over a device or a folder; links followed; all or
// nothing.

TEST(HostileOutput, ADeviceOrAFolderIsNeverReplaced) {
  const std::string sim = "simulate " + ExamplePath("paper_fig1.json") + " " +
                          ExamplePath("plans/paper_fig1_c_first.plan.json");
  ExpectBadInput(Cairn(sim + " --timeline /dev/full"), {"not a regular file"});
  struct stat st {};
  ASSERT_EQ(::stat("/dev/full", &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full is still a device";
  ExpectBadInput(Cairn(sim + " --timeline " + std::filesystem::temp_directory_path().string()),
                 {"a folder"});
}

TEST(HostileOutput, AFailedWriteLeavesNoPlanFileBehind) {
  const std::string dir = testing::TempDir("hostile_emit");
  // --dot names a folder: refused, and none of the plans may be left.
  const CliRun r = Cairn("plan " + ExamplePath("paper_fig1.json") + " --emit-plans " + dir +
                         " --dot " + std::filesystem::temp_directory_path().string());
  ExpectBadInput(r, {"--dot"});
  EXPECT_FALSE(std::filesystem::exists(dir)) << "not even the folder is left";
  std::filesystem::remove_all(dir);
}

// --- Determinism: byte-identical documents across runs and thread counts.

std::string WithoutTimes(const std::string& doc) {
  json j = json::parse(doc);
  if (j.contains("stats")) j["stats"].erase("time"), j["stats"].erase("threads");
  return j.dump();
}

// --- Input files that are not regular files, or too large: refused at once
// (a FIFO never waited on, /dev/zero never read), saying what they are;
// every failure of the file system exit 2 naming the file.

// A fresh folder for one test's files.
std::string Folder(const std::string& name) {
  const std::string dir = testing::TempDir(name);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(HostileInputFiles, WhatIsNotARegularFileIsRefusedSayingWhatItIs) {
  const std::string dir = Folder("hostile_files");
  std::filesystem::create_directories(dir + "/adir.json");
  ASSERT_EQ(::mkfifo((dir + "/fifo.json").c_str(), 0600), 0);
  std::filesystem::create_symlink("loop.json", dir + "/loop.json");
  const std::string long_name = dir + "/" + std::string(300, 'a') + ".json";
  struct Case {
    std::string args, message;
  };
  for (const Case& c : std::vector<Case>{
           {dir + "/adir.json", dir + "/adir.json: is a directory, not a file"},
           {dir + "/fifo.json", dir + "/fifo.json: is a FIFO (named pipe), not a regular file"},
           {"/dev/zero", "/dev/zero: is a character device, not a regular file"},
           {dir + "/loop.json", dir + "/loop.json: cannot open the file: a loop of symbolic links"},
           {long_name, long_name + ": cannot open the file: the file name is too long"},
           {dir + "/fifo.json --format compas --friction 0.5", "is a FIFO (named pipe)"},
           {dir + "/loop.json --format asap", "a loop of symbolic links"},
           {dir + "/fifo.json --format asap", "is a FIFO (named pipe)"},
           {long_name + " --format asap", "the file name is too long"},
           {ExamplePath("stack3.json") + " --max-input-size 100", "stack3.json: the file is "},
       }) {
    SCOPED_TRACE(c.args);
    ExpectBadInput(Cairn("check " + c.args), {c.message.c_str()});
  }
  // The other commands read their model alike; simulate's plan too.
  ExpectBadInput(Cairn("simulate " + dir + "/fifo.json " + dir + "/fifo.json"), {"is a FIFO"});
  ExpectBadInput(Cairn("simulate " + ExamplePath("paper_fig1.json") + " " + dir + "/adir.json"),
                 {"adir.json: is a directory"});
  ExpectBadInput(Cairn("blocking /dev/zero"), {"/dev/zero: is a character device"});
  std::filesystem::remove_all(dir);
}

TEST(HostileInputFiles, MaxInputSizeBoundsWhatIsReadAndCanBeRaised) {
  const CliRun small = Cairn("check " + ExamplePath("stack3.json") + " --max-input-size 100");
  ExpectBadInput(small, {"stack3.json: the file is ",
                         "bytes, more than the maximum input size "
                         "100 bytes (--max-input-size raises it)"});
  EXPECT_EQ(Cairn("check " + ExamplePath("stack3.json") + " --max-input-size 64K").exit_code, 0);
  EXPECT_EQ(Cairn("check " + ExamplePath("stack3.json") + " --max-input-size 2G").exit_code, 0);
  for (const char* bad : {"0", "1.5G", "lots", "-5", "1T"}) {
    SCOPED_TRACE(bad);
    const CliRun r = Cairn("check " + ExamplePath("stack3.json") + " --max-input-size " + bad);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--max-input-size"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("must be a positive number of bytes"), std::string::npos) << r.err;
  }
}

TEST(HostileInputFiles, AMeshThatIsNotARegularFileSaysWhatItIs) {
  const std::string dir = Folder("hostile_mesh");
  std::filesystem::create_directories(dir + "/folder.obj");
  ASSERT_EQ(::mkfifo((dir + "/fifo.obj").c_str(), 0600), 0);
  std::filesystem::create_symlink("loop.obj", dir + "/loop.obj");
  for (const std::string& mesh :
       {std::string("folder.obj"), std::string("fifo.obj"), std::string("loop.obj"),
        std::string("/dev/zero"), std::string(300, 'a') + ".obj"}) {
    SCOPED_TRACE(mesh);
    json doc = {{"cairn", 1},
                {"parts",
                 {{{"name", "floor"},
                   {"fixed", true},
                   {"box", {{"min", {-2, -2, -1}}, {"max", {3, 3, 0}}}}},
                  {{"name", "A"}, {"mesh", mesh}}}}};
    std::ofstream(dir + "/scene.json") << doc.dump();
    const CliRun r = Cairn("check " + dir + "/scene.json");
    ExpectBadInput(r, {"scene.json: parts[1] (\"A\").mesh: cannot read mesh '"});
    EXPECT_EQ(r.err.find("no such file"), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

// A mesh as some exporters write it: two unit cubes side by side as one OBJ
// that kept their shared face (both of its sides: an internal wall), and one
// outer triangle written twice. It loads, with a note saying what was left
// out, as the 2 × 1 × 1 box it is, resting on the floor.
TEST(HostileInputFiles, AMeshWithAnInternalWallAndATriangleWrittenTwiceLoadsWithANote) {
  const std::string dir = Folder("hostile_mesh_repair");
  std::ofstream obj(dir + "/boxes.obj");
  for (int x = 0; x <= 2; ++x)
    for (int k = 0; k < 4; ++k) obj << "v " << x << " " << (k & 1) << " " << ((k >> 1) & 1) << "\n";
  // OBJ counts from 1; vertex (x, y, z) is 4x + y + 2z + 1.
  const auto at = [](int x, int y, int z) { return 4 * x + y + 2 * z + 1; };
  const auto quad = [&](int a, int b, int c, int d) {
    obj << "f " << a << " " << b << " " << c << "\nf " << a << " " << c << " " << d << "\n";
  };
  quad(at(0, 0, 0), at(0, 0, 1), at(0, 1, 1), at(0, 1, 0));
  quad(at(2, 0, 0), at(2, 1, 0), at(2, 1, 1), at(2, 0, 1));
  for (int x = 0; x < 2; ++x) {
    quad(at(x, 0, 0), at(x + 1, 0, 0), at(x + 1, 0, 1), at(x, 0, 1));
    quad(at(x, 1, 0), at(x, 1, 1), at(x + 1, 1, 1), at(x + 1, 1, 0));
    quad(at(x, 0, 0), at(x, 1, 0), at(x + 1, 1, 0), at(x + 1, 0, 0));
    quad(at(x, 0, 1), at(x + 1, 0, 1), at(x + 1, 1, 1), at(x, 1, 1));
  }
  quad(at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1));  // the wall, both sides
  quad(at(1, 0, 0), at(1, 0, 1), at(1, 1, 1), at(1, 1, 0));
  obj << "f " << at(0, 0, 0) << " " << at(0, 0, 1) << " " << at(0, 1, 1) << "\n";  // again
  obj.close();
  const json doc = {
      {"cairn", 1},
      {"parts",
       {{{"name", "floor"}, {"fixed", true}, {"box", {{"min", {-2, -2, -1}}, {"max", {3, 3, 0}}}}},
        {{"name", "A"}, {"mesh", "boxes.obj"}}}}};
  std::ofstream(dir + "/scene.json") << doc.dump();
  const CliRun r = Cairn("check " + dir + "/scene.json --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("scene.json: part 'A': mesh " + dir +
                       "/boxes.obj: 1 triangle written twice and 4 triangles of internal walls "
                       "(both sides written) left out"),
            std::string::npos)
      << r.err;
  const json out = json::parse(r.out);
  EXPECT_EQ(out["stable"], true);
  std::filesystem::remove_all(dir);
}

TEST(HostileInputFiles, ASidecarThatIsAFifoIsRefused) {
  const std::string shared = testing::SharedDir();
  if (shared.empty()) GTEST_SKIP() << "shared/datasets not found: skipping the pen";
  const std::string dir = Folder("hostile_sidecar");
  ASSERT_EQ(::mkfifo((dir + "/side.json").c_str(), 0600), 0);
  std::filesystem::create_directories(dir + "/sided.json");
  const std::string cap = shared + "/datasets/aplan_bourjault_pen_simple/cap.stp";
  ExpectBadInput(Cairn("check " + cap + " --format step --sidecar " + dir + "/side.json"),
                 {"side.json: is a FIFO (named pipe), not a regular file"});
  ExpectBadInput(Cairn("check " + cap + " --format step --sidecar " + dir + "/sided.json"),
                 {"sided.json: is a directory, not a file"});
  std::filesystem::remove_all(dir);
}

TEST(Determinism, PlanGivesTheSameDocumentWithOneOrTwoThreads) {
  for (const std::string& args : {"plan " + ExamplePath("jenga.json") + " --max 2 --json",
                                  "plan " + ExamplePath("paper_fig6.json") + " --json"}) {
    const CliRun one = Cairn(args + " --threads 1");
    const CliRun two = Cairn(args + " --threads 2");
    ASSERT_EQ(one.exit_code, two.exit_code) << args;
    EXPECT_EQ(WithoutTimes(one.out), WithoutTimes(two.out)) << args;
  }
}

TEST(Determinism, CheckSimulateAndBlockingRepeatToTheByte) {
  const std::string timeline1 = TempFile("det_timeline1.csv", "");
  const std::string timeline2 = TempFile("det_timeline2.csv", "");
  const std::string sim = "simulate " + ExamplePath("jenga.json") + " " +
                          ExamplePath("plans/jenga_pull_l9.plan.json") + " --json --timeline ";
  const CliRun s1 = Cairn(sim + timeline1), s2 = Cairn(sim + timeline2);
  EXPECT_EQ(testing::Slurp(timeline1), testing::Slurp(timeline2));
  EXPECT_FALSE(testing::Slurp(timeline1).empty());
  auto strip = [](const std::string& doc) {
    json j = json::parse(doc);
    for (json& step : j["steps"]) step.erase("time");
    return j.dump();
  };
  EXPECT_EQ(strip(s1.out), strip(s2.out));
  for (const std::string& args : {"check " + ExamplePath("wall.json") + " --json",
                                  "blocking " + ExamplePath("paper_fig9.json") + " --json"})
    EXPECT_EQ(Cairn(args).out, Cairn(args).out) << args;
}

}  // namespace
}  // namespace cairn

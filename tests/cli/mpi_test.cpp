// `cairn plan` and `cairn batch` under mpirun (CAIRN_MPI): the documents of
// 1, 2 and 3 ranks are the same but for the timings and the rank counts, on
// the planning examples with and without friction, full enumeration and
// best-first; a batch's results are the same as with threads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_run.h"

namespace cairn {
namespace {

using nlohmann::json;
using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;
using testing::Slurp;
using testing::SourcePath;
using testing::TempDir;

// `cairn ARGS` on `ranks` ranks (more ranks than cores: --oversubscribe).
CliRun Mpirun(int ranks, const std::string& args) {
  return testing::RunCommand(std::string(CAIRN_MPIRUN) + " --oversubscribe -n " +
                             std::to_string(ranks) + " " + testing::CliPath() + " " + args);
}

// The document without what may differ between runs and rank counts.
json WithoutTimings(json doc) {
  for (const char* k : {"time", "threads", "ranks", "rank_time", "communication_time"})
    doc["stats"].erase(k);
  return doc;
}

struct PlanCase {
  const char* name;  // the test's
  const char* scene;
  const char* options;
};

void PrintTo(const PlanCase& c, std::ostream* os) { *os << c.scene << ' ' << c.options; }

class MpiPlan : public ::testing::TestWithParam<PlanCase> {};

TEST_P(MpiPlan, OneTwoAndThreeRanks_TheSameDocument) {
  if (std::string(CAIRN_MPIRUN).empty()) GTEST_SKIP() << "built without MPI (CAIRN_MPI off)";
  const std::string args =
      "plan " + ExamplePath(GetParam().scene) + " --json " + GetParam().options;
  const CliRun one = Cairn(args);
  ASSERT_LE(one.exit_code, 1) << one.err;
  const json alone = json::parse(one.out);
  EXPECT_EQ(alone["stats"]["ranks"], 1);
  for (int ranks : {2, 3}) {
    const CliRun r = Mpirun(ranks, args);
    EXPECT_EQ(r.exit_code, one.exit_code) << ranks << " ranks: " << r.err;
    json doc = json::parse(r.out);  // rank 0's alone: one document
    EXPECT_EQ(doc["stats"]["ranks"], ranks);
    EXPECT_EQ(doc["stats"]["rank_time"].size(), static_cast<size_t>(ranks));
    EXPECT_EQ(doc["stats"]["communication_time"].size(), static_cast<size_t>(ranks));
    EXPECT_EQ(WithoutTimings(doc).dump(2), WithoutTimings(alone).dump(2)) << ranks << " ranks";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Examples, MpiPlan,
    ::testing::Values(
        // Frictionless: node checks decide; with friction (the scene's or
        // --friction) and both supports: path simulations spread over the
        // ranks (tens to hundreds: small enough for the sanitized build,
        // whose leak checker unwinds every allocation fully under mpirun).
        PlanCase{"Fig1", "paper_fig1.json", ""}, PlanCase{"Fig19", "paper_fig19.json", ""},
        PlanCase{"Fig19FrictionBothSupports", "paper_fig19.json", "--friction 0.4 --support both"},
        PlanCase{"FlushJointBothSupports", "flush_joint.json", "--support both"},
        PlanCase{"LadderBothSupports", "ladder.json", "--support both"},
        PlanCase{"Stack3FrictionBothSupports", "stack3.json", "--friction 0.4 --support both"},
        // Best-first (--max K): the same sequences.
        PlanCase{"Fig14BestFirstFriction", "paper_fig14.json",
                 "--max 2 --friction 0.4 --support both"},
        PlanCase{"Fig6BestFirst", "paper_fig6.json", "--max 3"},
        PlanCase{"Fig4NothingStable", "paper_fig4.json", ""}),
    [](const ::testing::TestParamInfo<PlanCase>& p) { return std::string(p.param.name); });

TEST(MpiBatch, ThreeRanks_TheSameResultsAsThreads) {
  if (std::string(CAIRN_MPIRUN).empty()) GTEST_SKIP() << "built without MPI (CAIRN_MPI off)";
  const std::string dir = TempDir("cairn_mpi_batch");
  const std::string gen = "python3 " + SourcePath("scripts/batch_scenes.py") + " " + dir + " 60";
  ASSERT_EQ(std::system(gen.c_str()), 0);
  const CliRun threads = Cairn("batch " + dir + "/jobs.jsonl -o " + dir + "/threads --threads 2");
  ASSERT_EQ(threads.exit_code, 0) << threads.err;
  const CliRun ranks = Mpirun(3, "batch " + dir + "/jobs.jsonl -o " + dir + "/ranks");
  ASSERT_EQ(ranks.exit_code, 0) << ranks.err;
  EXPECT_NE(ranks.out.find("60 jobs run"), std::string::npos) << ranks.out;
  EXPECT_EQ(Slurp(dir + "/ranks"), Slurp(dir + "/threads"));
  // A bad batch (no jobs file) under mpirun: exit 2, and no rank waits.
  const CliRun bad = Mpirun(2, "batch " + dir + "/none.jsonl -o " + dir + "/bad");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  std::filesystem::remove_all(dir);
}

// Rank 0 resuming a RESULTS line whose id is nested 100 000 deep: exit 2
// naming the file and the line (no rank crashes, none waits), RESULTS as it
// was; and margin jobs on the ranks give the threads' results.
TEST(MpiBatch, DeepResultsLineRefused_MarginJobsOnRanks) {
  if (std::string(CAIRN_MPIRUN).empty()) GTEST_SKIP() << "built without MPI (CAIRN_MPI off)";
  const std::string dir = TempDir("cairn_mpi_batch_deep");
  std::filesystem::create_directories(dir);
  const std::string stack = ExamplePath("stack3.json");
  std::ofstream(dir + "/jobs.jsonl")
      << "{\"id\":\"c\",\"command\":\"check\",\"model\":\"" << stack << "\"}\n"
      << "{\"id\":\"m\",\"command\":\"margin\",\"model\":\"" << stack
      << "\",\"options\":{\"tilt\":[0,0,1]}}\n";
  const std::string deep =
      "{\"id\":" + std::string(100000, '[') + std::string(100000, ']') + ",\"exit\":0}\n";
  std::ofstream(dir + "/deep") << deep;
  const CliRun bad = Mpirun(2, "batch " + dir + "/jobs.jsonl -o " + dir + "/deep");
  EXPECT_EQ(bad.exit_code, 2) << bad.err.substr(0, 300);
  EXPECT_NE(bad.err.find(dir + "/deep: line 1: not a result of cairn batch"), std::string::npos)
      << bad.err.substr(0, 300);
  EXPECT_EQ(Slurp(dir + "/deep"), deep);
  const CliRun threads = Cairn("batch " + dir + "/jobs.jsonl -o " + dir + "/threads");
  ASSERT_EQ(threads.exit_code, 0) << threads.err;
  const CliRun ranks = Mpirun(2, "batch " + dir + "/jobs.jsonl -o " + dir + "/ranks");
  ASSERT_EQ(ranks.exit_code, 0) << ranks.err;
  EXPECT_EQ(Slurp(dir + "/ranks"), Slurp(dir + "/threads"));
  EXPECT_NE(Slurp(dir + "/ranks").find("\"id\":\"m\",\"exit\":0,\"result\":"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cairn

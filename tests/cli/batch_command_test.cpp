// `cairn batch`, run as a user runs it: verdicts of a generated data set
// known analytically (scripts/batch_scenes.py), results identical to the
// commands' own --json documents, in the jobs' order for any number of
// threads, a batch killed part-way and resumed, bad jobs recorded, time-outs.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

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

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// N generated scenes (scripts/batch_scenes.py) in a fresh folder: the
// folder, with jobs.jsonl and expected.jsonl.
std::string Generate(const std::string& name, int n) {
  const std::string dir = TempDir(name);
  const std::string cmd = "python3 " + SourcePath("scripts/batch_scenes.py") + " " + dir + " " +
                          std::to_string(n) + " >/dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return dir;
}

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(BatchCli, GeneratedStacksArchesAndWalls_VerdictsAsComputedAnalytically) {
  const std::string dir = Generate("cairn_batch200", 200);
  const std::string results = dir + "/results.jsonl";
  const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + results + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::map<std::string, json> expected;
  for (const std::string& line : Lines(Slurp(dir + "/expected.jsonl"))) {
    const json e = json::parse(line);
    expected[e["id"]] = e;
  }
  const std::vector<std::string> lines = Lines(Slurp(results));
  ASSERT_EQ(lines.size(), 200u);
  std::map<std::string, int> stable_by_kind, unstable_by_kind;
  for (size_t k = 0; k < lines.size(); ++k) {
    const json got = json::parse(lines[k]);
    const json& want = expected.at(got["id"]);
    char id[24];
    std::snprintf(id, sizeof id, "%04zu", k);
    EXPECT_EQ(got["id"], id) << "the jobs' order";
    const bool stable = want["stable"];
    EXPECT_EQ(got["exit"], stable ? 0 : 1) << lines[k].substr(0, 200);
    EXPECT_EQ(got["result"]["stable"], stable) << want.dump();
    (stable ? stable_by_kind : unstable_by_kind)[want["kind"]]++;
  }
  // The data set has both verdicts of every kind (else it would test little).
  for (const char* kind : {"stack", "arch", "wall"}) {
    EXPECT_GT(stable_by_kind[kind], 5) << kind;
    EXPECT_GT(unstable_by_kind[kind], 5) << kind;
  }
  std::filesystem::remove_all(dir);
}

TEST(BatchCli, ResultsInTheJobsOrderWhateverTheThreads) {
  const std::string dir = Generate("cairn_batch_order", 60);
  const CliRun one = Cairn("batch " + dir + "/jobs.jsonl -o " + dir + "/r1 --threads 1");
  const CliRun three = Cairn("batch " + dir + "/jobs.jsonl -o " + dir + "/r3 --threads 3");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_EQ(Lines(Slurp(dir + "/r1")).size(), 60u);
  EXPECT_EQ(Slurp(dir + "/r1"), Slurp(dir + "/r3"));
  std::filesystem::remove_all(dir);
}

TEST(BatchCli, ResumeAfterAKillMidLine_SameResultsAsOneRun) {
  const std::string dir = Generate("cairn_batch_resume", 40);
  const std::string jobs = dir + "/jobs.jsonl";
  ASSERT_EQ(Cairn("batch " + jobs + " -o " + dir + "/whole").exit_code, 0);
  const std::string whole = Slurp(dir + "/whole");
  const std::vector<std::string> lines = Lines(whole);
  ASSERT_EQ(lines.size(), 40u);
  // What a batch killed while writing its 18th line leaves: 17 whole lines
  // and part of one.
  std::string cut;
  for (size_t k = 0; k < 17; ++k) cut += lines[k] + "\n";
  cut += lines[17].substr(0, lines[17].size() / 2);
  WriteText(dir + "/resumed", cut);
  const CliRun r = Cairn("batch " + jobs + " -o " + dir + "/resumed");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("23 jobs run, 17 already in RESULTS"), std::string::npos) << r.out;
  EXPECT_EQ(Slurp(dir + "/resumed"), whole);
  // Again: nothing left to do, nothing changes.
  ASSERT_EQ(Cairn("batch " + jobs + " -o " + dir + "/resumed --resume").exit_code, 0);
  EXPECT_EQ(Slurp(dir + "/resumed"), whole);
  // --fresh starts over (and gives the same).
  WriteText(dir + "/fresh", lines[3] + "\n");
  ASSERT_EQ(Cairn("batch " + jobs + " -o " + dir + "/fresh --fresh").exit_code, 0);
  EXPECT_EQ(Slurp(dir + "/fresh"), whole);
  std::filesystem::remove_all(dir);
}

// A real kill (SIGKILL, no chance to clean up) once some results are out:
// wherever it landed, the resumed batch ends with the uninterrupted one's
// results.
TEST(BatchCli, KilledPartWayAndResumed_SameResultsAsOneRun) {
  const std::string dir = Generate("cairn_batch_kill", 200);
  const std::string jobs = dir + "/jobs.jsonl", out = dir + "/killed";
  ASSERT_EQ(Cairn("batch " + jobs + " -o " + dir + "/whole --threads 2").exit_code, 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const std::string cli = testing::CliPath();
    ::execl(cli.c_str(), cli.c_str(), "batch", jobs.c_str(), "-o", out.c_str(), "--threads", "1",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Until the first result is out (or the batch is over), then the kill.
  for (int i = 0; i < 20000; ++i) {
    if (!Slurp(out).empty() || ::waitpid(pid, nullptr, WNOHANG) == pid) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
  const CliRun r = Cairn("batch " + jobs + " -o " + out + " --threads 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Slurp(out), Slurp(dir + "/whole"));
  std::filesystem::remove_all(dir);
}

// A job's result is the document its command prints with --json; bad jobs
// are recorded with exit 2 and one message, and the others run.
TEST(BatchCli, BadJobsRecordedTheRestRun_ResultsAreTheCommandsDocuments) {
  const std::string dir = TempDir("cairn_batch_mixed");
  std::filesystem::create_directories(dir);
  const std::string stack = ExamplePath("stack3.json"), fig14 = ExamplePath("paper_fig14.json");
  const std::string plan = ExamplePath("plans/paper_fig14_left.plan.json");
  const std::string jobs = dir + "/jobs.jsonl";
  WriteText(jobs, "{\"id\": \"check\", \"command\": \"check\", \"model\": \"" + stack +
                      "\", \"options\": {\"without\": [\"C\"], \"friction\": 0.3}}\n"
                      "{\"id\": \"missing\", \"command\": \"check\", \"model\": \"" +
                      dir +
                      "/nope.json\"}\n"
                      "\n"
                      "{\"id\": \"sim\", \"command\": \"simulate\", \"model\": \"" +
                      fig14 + "\", \"plan\": \"" + plan +
                      "\"}\n"
                      "{\"id\": 4, \"command\": \"fly\", \"model\": \"" +
                      stack +
                      "\"}\n"
                      "{\"id\": 5, \"command\": \"check\", \"model\": \"" +
                      stack +
                      "\", \"options\": {\"frobnicate\": true}}\n"
                      "{\"id\": 6, \"command\": \"plan\", \"model\": \"" +
                      stack +
                      "\", \"options\": {\"dot\": \"x.dot\"}}\n"
                      "{\"id\": 7, \"command\": \"simulate\", \"model\": \"" +
                      stack +
                      "\"}\n"
                      "{\"id\": 8, \"command\": \"check\", \"model\": \"" +
                      stack +
                      "\", \"options\": {\"gravity\": [-9.81, 0]}}\n"
                      "{\"id\": \"plan\", \"command\": \"plan\", \"model\": \"" +
                      stack +
                      "\", \"options\": {\"friction\": 0.4, \"max\": 2}}\n"
                      "{\"id\": \"ndbg\", \"command\": \"blocking\", \"model\": \"" +
                      stack + "\"}\n");
  const CliRun r = Cairn("batch " + jobs + " -o " + dir + "/out.jsonl");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = Lines(Slurp(dir + "/out.jsonl"));
  ASSERT_EQ(lines.size(), 10u);
  std::vector<json> got;
  for (const std::string& line : lines) got.push_back(json::parse(line));
  // The documents, as the CLI prints them.
  const auto cli = [](const std::string& args, int exit) {
    const CliRun c = Cairn(args + " --json");
    EXPECT_EQ(c.exit_code, exit) << args << c.err;
    return json::parse(c.out);
  };
  EXPECT_EQ(got[0]["id"], "check");
  EXPECT_EQ(got[0]["exit"], 0);
  EXPECT_EQ(got[0]["result"], cli("check " + stack + " --without C --friction 0.3", 0));
  EXPECT_EQ(got[2]["id"], "sim");
  EXPECT_EQ(got[2]["exit"], 1);
  EXPECT_EQ(got[2]["result"], cli("simulate " + fig14 + " " + plan, 1));
  EXPECT_EQ(got[7]["exit"], 1);  // gravity from the right: the stack falls
  EXPECT_EQ(got[7]["result"], cli("check " + stack + " --gravity=-9.81,0", 1));
  json planned = got[8]["result"], alone = cli("plan " + stack + " --friction 0.4 --max 2", 0);
  for (json* doc : {&planned, &alone})
    for (const char* k : {"time", "threads", "rank_time", "communication_time"})
      (*doc)["stats"].erase(k);
  EXPECT_EQ(got[8]["exit"], 0);
  EXPECT_EQ(planned, alone);
  EXPECT_EQ(got[9]["result"], cli("blocking " + stack, 0));
  // Bad jobs: exit 2, one message naming what is wrong, no result.
  const std::map<size_t, std::string> errors = {
      {1, "nope.json"}, {3, "command"}, {4, "frobnicate"}, {5, "options.dot"}, {6, "plan"}};
  for (const auto& [k, what] : errors) {
    EXPECT_EQ(got[k]["exit"], 2) << lines[k];
    EXPECT_FALSE(got[k].contains("result")) << lines[k];
    EXPECT_NE(got[k]["error"].get<std::string>().find(what), std::string::npos) << lines[k];
  }
  EXPECT_NE(r.out.find("5 bad input (exit 2)"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(BatchCli, JobOverItsTimeout_RecordedAndTheBatchGoesOn) {
  const std::string dir = TempDir("cairn_batch_timeout");
  std::filesystem::create_directories(dir);
  const std::string jobs = dir + "/jobs.jsonl";
  // Planning every sequence of the 10-block pyramid with friction and both
  // supports simulates tens of thousands of paths: far beyond 0.2 s.
  WriteText(jobs, "{\"id\": 1, \"command\": \"plan\", \"model\": \"" +
                      ExamplePath("pyramid10.json") +
                      "\", \"options\": {\"friction\": 0.4, \"support\": \"both\"}}\n"
                      "{\"id\": 2, \"command\": \"check\", \"model\": \"" +
                      ExamplePath("stack3.json") + "\"}\n");
  const CliRun r = Cairn("batch " + jobs + " -o " + dir + "/out --job-timeout 0.2 --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = Lines(Slurp(dir + "/out"));
  ASSERT_EQ(lines.size(), 2u);
  const json slow = json::parse(lines[0]), fast = json::parse(lines[1]);
  EXPECT_EQ(slow["exit"], 5);
  EXPECT_NE(slow["error"].get<std::string>().find("--job-timeout"), std::string::npos);
  EXPECT_EQ(fast["exit"], 0);
  EXPECT_EQ(fast["result"]["stable"], true);
  std::filesystem::remove_all(dir);
}

TEST(BatchCli, BadBatchInput_Exit2NothingWritten) {
  const std::string dir = TempDir("cairn_batch_bad");
  std::filesystem::create_directories(dir);
  const std::string out = dir + "/out";
  const std::string stack = ExamplePath("stack3.json");
  struct Case {
    std::string jobs, results, expect;
  };
  const std::vector<Case> cases = {
      {"", "", "cannot read"},  // no jobs file
      {"{\"id\": 1, \"command\": \"check\", \"model\": \"m\"}\nnot json\n", "", "line 2"},
      {"{\"command\": \"check\", \"model\": \"m\"}\n", "", "\"id\""},
      {"{\"id\": 1, \"command\": \"check\", \"model\": \"m\"}\n{\"id\": 1}\n", "", "given twice"},
      {"{\"id\": 1, \"command\": \"check\", \"model\": \"" + stack + "\"}\n", "garbage\n",
       "not a result"},
  };
  for (size_t k = 0; k < cases.size(); ++k) {
    const std::string jobs = dir + "/jobs" + std::to_string(k);
    if (!cases[k].jobs.empty()) WriteText(jobs, cases[k].jobs);
    std::filesystem::remove(out);
    if (!cases[k].results.empty()) WriteText(out, cases[k].results);
    const CliRun r = Cairn("batch " + jobs + " -o " + out);
    EXPECT_EQ(r.exit_code, 2) << k << r.err;
    EXPECT_NE(r.err.find(cases[k].expect), std::string::npos) << k << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
    EXPECT_EQ(Slurp(out), cases[k].results) << k;  // untouched, or not made
  }
  const CliRun both = Cairn("batch " + dir + "/jobs4 -o " + out + " --fresh --resume");
  EXPECT_EQ(both.exit_code, 2);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cairn

// `cairn batch`, run as a user runs it: verdicts of a generated data set
// known analytically (scripts/batch_scenes.py), results identical to the
// commands' own --json documents, in the jobs' order for any number of
// threads, a batch killed part-way and resumed, bad jobs recorded, time-outs.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
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

// ---- Hostile RESULTS, JOBS and job lines -------------------------------------

// A jobs file of one check of stack3 in a fresh folder: the folder.
std::string OneCheck(const std::string& name) {
  const std::string dir = TempDir(name);
  std::filesystem::create_directories(dir);
  WriteText(dir + "/jobs.jsonl", "{\"id\": \"c\", \"command\": \"check\", \"model\": \"" +
                                     ExamplePath("stack3.json") + "\"}\n");
  return dir;
}

// An id nested 100 000 arrays deep: a recursive reader (or dump) of it
// overflows the stack. The results line is refused, naming file and line.
TEST(BatchCli, ResultsLineNestedTooDeep_Exit2NamingFileAndLine) {
  const std::string dir = OneCheck("cairn_batch_deep");
  const std::string out = dir + "/results.jsonl";
  const std::string deep =
      "{\"id\":" + std::string(100000, '[') + std::string(100000, ']') + ",\"exit\":0}\n";
  WriteText(out, deep);
  const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + out);
  EXPECT_EQ(r.exit_code, 2) << r.err.substr(0, 300);
  EXPECT_NE(r.err.find(out + ": line 1: not a result of cairn batch"), std::string::npos)
      << r.err.substr(0, 300);
  EXPECT_NE(r.err.find("nested more than 256"), std::string::npos) << r.err.substr(0, 300);
  EXPECT_EQ(Slurp(out), deep);
  // In JOBS too (a job's options nested as deep).
  WriteText(dir + "/deep_jobs.jsonl",
            "{\"id\": 1, \"command\": \"check\", \"model\": \"m\", "
            "\"options\": {\"x\": " +
                std::string(100000, '[') + std::string(100000, ']') + "}}\n");
  const CliRun j = Cairn("batch " + dir + "/deep_jobs.jsonl -o " + dir + "/r2");
  EXPECT_EQ(j.exit_code, 2) << j.err.substr(0, 300);
  EXPECT_NE(j.err.find("deep_jobs.jsonl: line 1: options.x"), std::string::npos)
      << j.err.substr(0, 300);
  EXPECT_FALSE(std::filesystem::exists(dir + "/r2"));
  std::filesystem::remove_all(dir);
}

// A last line without its newline that is not the start of a result is
// refused as the same line with its newline is; the start of one (a batch
// killed while it wrote) is still cut off.
TEST(BatchCli, ResultsEndingInANonResultWithOrWithoutNewline_BothRefused) {
  const std::string dir = OneCheck("cairn_batch_noeol");
  for (const std::string& text :
       {std::string("precious notes, not cairn results"), std::string("hello\n"),
        std::string("{\"id\": \"x\", \"exit\": 0}\nprecious"),
        std::string("{\"id\":\"c\",\"exit\":0} trailing")}) {
    const std::string out = dir + "/notes.txt";
    WriteText(out, text);
    const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + out);
    EXPECT_EQ(r.exit_code, 2) << text << r.err;
    EXPECT_NE(r.err.find("not a result of cairn batch"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(out + ": line "), std::string::npos) << r.err;
    EXPECT_EQ(Slurp(out), text) << "untouched";
  }
  // What a write cut short leaves, however short: cut off, the job run.
  const std::string whole = dir + "/whole";
  ASSERT_EQ(Cairn("batch " + dir + "/jobs.jsonl -o " + whole).exit_code, 0);
  for (const size_t keep : {size_t{1}, size_t{3}, size_t{7}, Slurp(whole).size() - 1}) {
    const std::string out = dir + "/cut";
    WriteText(out, Slurp(whole).substr(0, keep));
    const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + out);
    EXPECT_EQ(r.exit_code, 0) << keep << r.err;
    EXPECT_EQ(Slurp(out), Slurp(whole)) << keep;
  }
  std::filesystem::remove_all(dir);
}

TEST(BatchCli, HugeJobTimeout_MeansNoDeadline) {
  const std::string dir = OneCheck("cairn_batch_huge_timeout");
  for (const char* t : {"9.3e9", "1e10", "1e308"}) {
    const std::string out = dir + "/r_" + t;
    const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + out + " --job-timeout " + t);
    ASSERT_EQ(r.exit_code, 0) << t << r.err;
    json line = json::parse(Slurp(out));
    EXPECT_EQ(line["exit"], 0) << t << " " << line.dump().substr(0, 200);
    EXPECT_EQ(line["result"]["stable"], true) << t;
  }
  std::filesystem::remove_all(dir);
}

// A FIFO (or a folder, or a device) as JOBS, as RESULTS or as a job's file
// is refused: the read would block forever, past any --job-timeout.
TEST(BatchCli, FifoAsJobsResultsOrAJobsModel_RefusedNotBlocked) {
  const std::string dir = OneCheck("cairn_batch_fifo");
  const std::string fifo = dir + "/fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const std::string cairn = "timeout 60 " + testing::CliPath() + " ";
  const CliRun jobs = testing::RunCommand(cairn + "batch " + fifo + " -o " + dir + "/r1");
  EXPECT_EQ(jobs.exit_code, 2) << jobs.err;
  EXPECT_NE(jobs.err.find(fifo + ": is a FIFO (named pipe), not a regular file"), std::string::npos)
      << jobs.err;
  const CliRun dev = Cairn("batch /dev/zero -o " + dir + "/r1");
  EXPECT_EQ(dev.exit_code, 2) << dev.err;
  EXPECT_NE(dev.err.find("/dev/zero: is a character device, not a regular file"), std::string::npos)
      << dev.err;
  const CliRun results = testing::RunCommand(cairn + "batch " + dir + "/jobs.jsonl -o " + fifo);
  EXPECT_EQ(results.exit_code, 2) << results.err;
  EXPECT_NE(results.err.find("not a regular file"), std::string::npos) << results.err;
  // A job whose model (or sidecar, or plan) is a FIFO: that job is bad
  // input, the next one runs.
  WriteText(dir + "/fifo_jobs.jsonl",
            "{\"id\": \"f\", \"command\": \"check\", \"model\": \"" + fifo +
                "\"}\n"
                "{\"id\": \"s\", \"command\": \"check\", \"model\": \"" +
                ExamplePath("stack3.json") + "\", \"options\": {\"sidecar\": \"" + fifo +
                "\"}}\n"
                "{\"id\": \"c\", \"command\": \"check\", \"model\": \"" +
                ExamplePath("stack3.json") + "\"}\n");
  const std::string out = dir + "/r2";
  const CliRun r = testing::RunCommand(cairn + "batch " + dir + "/fifo_jobs.jsonl -o " + out +
                                       " --job-timeout 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = Lines(Slurp(out));
  ASSERT_EQ(lines.size(), 3u);
  for (size_t k = 0; k < 2; ++k) {
    json bad = json::parse(lines[k]);
    EXPECT_EQ(bad["exit"], 2) << lines[k];
    EXPECT_NE(bad.value("error", std::string())
                  .find(fifo + ": is a FIFO (named pipe), not a regular file"),
              std::string::npos)
        << lines[k];
  }
  EXPECT_EQ(json::parse(lines[2])["exit"], 0) << lines[2];
  std::filesystem::remove_all(dir);
}

// -o naming JOBS (itself, through a link or a hard link) would overwrite the
// jobs with results: refused, JOBS untouched.
TEST(BatchCli, ResultsNamingTheJobsFile_RefusedJobsUntouched) {
  const std::string dir = OneCheck("cairn_batch_is_jobs");
  const std::string jobs = dir + "/jobs.jsonl";
  const std::string before = Slurp(jobs);
  std::filesystem::create_symlink(jobs, dir + "/link.jsonl");
  std::filesystem::create_hard_link(jobs, dir + "/hard.jsonl");
  for (const std::string& out :
       {jobs, dir + "/link.jsonl", dir + "/hard.jsonl",
        dir + "/../" + std::filesystem::path(dir).filename().string() + "/jobs.jsonl"}) {
    for (const char* mode : {" --fresh", ""}) {
      const CliRun r = Cairn("batch " + jobs + " -o " + out + mode);
      EXPECT_EQ(r.exit_code, 2) << out << mode << r.err;
      EXPECT_NE(r.err.find("-o and the jobs file name the same file '" + out + "'"),
                std::string::npos)
          << r.err;
      EXPECT_EQ(Slurp(jobs), before) << out << mode;
    }
  }
  std::filesystem::remove_all(dir);
}

// Job lines: output options however spelled, `true` for an option that takes
// a value, a model that is not a string, a key given twice.
TEST(BatchCli, BadJobOptionsAndKeys_SaySo) {
  const std::string dir = TempDir("cairn_batch_options");
  std::filesystem::create_directories(dir);
  const std::string stack = "\"" + ExamplePath("stack3.json") + "\"";
  const std::string fig1 = "\"" + ExamplePath("paper_fig1.json") + "\"";
  const std::string plan1 = "\"" + ExamplePath("plans/paper_fig1_b_first.plan.json") + "\"";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"\"command\":\"check\",\"model\":" + stack + ",\"options\":{\"html\":\"x.html\"}",
       "options.html: not in a batch: the output options"},
      {"\"command\":\"check\",\"model\":" + stack + ",\"options\":{\"html=x.html\":true}",
       "options.html=x.html: not in a batch: the output options"},
      {"\"command\":\"simulate\",\"model\":" + fig1 + ",\"plan\":" + plan1 +
           ",\"options\":{\"timeline=t.csv\":true}",
       "options.timeline=t.csv: not in a batch"},
      {"\"command\":\"plan\",\"model\":" + stack + ",\"options\":{\"emit-plans=emitdir\":true}",
       "options.emit-plans=emitdir: not in a batch"},
      {"\"command\":\"plan\",\"model\":" + stack + ",\"options\":{\"dot=g.dot\":1}",
       "options.dot=g.dot: not in a batch"},
      {"\"command\":\"check\",\"model\":" + stack + ",\"options\":{\"friction=0.3\":true}",
       "options.friction=0.3: an option's name has no '='"},
      {"\"command\":\"check\",\"model\":" + stack + ",\"options\":{\"without\":true}",
       "options.without: takes a value (a string, a number or a list), not true"},
      {"\"command\":\"check\",\"model\":" + stack + ",\"options\":{\"\":true}",
       "options.\"\": not an option name"},
      {"\"command\":\"check\",\"model\":5", "model: must be a file name (a string), not a number"},
      {"\"command\":7,\"model\":" + stack,
       "command: must be check, simulate, plan, blocking, margin or sequence (a string), not a "
       "number"},
  };
  std::string text;
  for (size_t k = 0; k < cases.size(); ++k)
    text += "{\"id\":" + std::to_string(k) + "," + cases[k].first + "}\n";
  WriteText(dir + "/jobs.jsonl", text);
  const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + dir + "/out.jsonl");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = Lines(Slurp(dir + "/out.jsonl"));
  ASSERT_EQ(lines.size(), cases.size());
  for (size_t k = 0; k < cases.size(); ++k) {
    json got = json::parse(lines[k]);
    EXPECT_EQ(got["exit"], 2) << lines[k];
    EXPECT_NE(got.value("error", std::string()).find(cases[k].second), std::string::npos)
        << lines[k];
  }
  for (const char* made : {"x.html", "t.csv", "emitdir", "g.dot"})
    EXPECT_FALSE(std::filesystem::exists(made)) << made;
  // A key given twice: the whole jobs file is refused (which one counts?).
  WriteText(dir + "/dup.jsonl",
            "{\"id\":1,\"command\":\"check\",\"model\":\"nope.json\","
            "\"model\":" +
                stack + "}\n");
  const CliRun dup = Cairn("batch " + dir + "/dup.jsonl -o " + dir + "/dup_out.jsonl");
  EXPECT_EQ(dup.exit_code, 2) << dup.err;
  EXPECT_NE(dup.err.find("dup.jsonl: line 1: model: duplicate key in one object"),
            std::string::npos)
      << dup.err;
  std::filesystem::remove_all(dir);
}

// A margin job's result is the document of `cairn margin ... --json`.
TEST(BatchCli, MarginJobs_ResultIsTheMarginDocument) {
  const std::string dir = TempDir("cairn_batch_margin");
  std::filesystem::create_directories(dir);
  const std::string stack = ExamplePath("stack3.json"), fig6 = ExamplePath("paper_fig6.json");
  WriteText(dir + "/jobs.jsonl",
            "{\"id\":\"mu\",\"command\":\"margin\",\"model\":\"" + stack +
                "\",\"options\":{\"friction\":true}}\n"
                "{\"id\":\"tilt\",\"command\":\"margin\",\"model\":\"" +
                stack +
                "\",\"options\":{\"tilt\":[0,0,1]}}\n"
                "{\"id\":\"none\",\"command\":\"margin\",\"model\":\"" +
                stack +
                "\"}\n"
                "{\"id\":\"load\",\"command\":\"margin\",\"model\":\"" +
                stack +
                "\",\"options\":{\"load\":\"Nope\",\"point\":[0,0],\"direction\":[1,0]}}\n");
  const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + dir + "/out.jsonl --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = Lines(Slurp(dir + "/out.jsonl"));
  ASSERT_EQ(lines.size(), 4u);
  const auto cli = [](const std::string& args) {
    const CliRun c = Cairn(args + " --json");
    EXPECT_EQ(c.exit_code, 0) << args << c.err;
    return json::parse(c.out);
  };
  json mu = json::parse(lines[0]), tilt = json::parse(lines[1]);
  EXPECT_EQ(mu["exit"], 0) << lines[0].substr(0, 300);
  EXPECT_EQ(mu["result"], cli("margin " + stack + " --friction"));
  EXPECT_EQ(tilt["exit"], 0) << lines[1].substr(0, 300);
  EXPECT_EQ(tilt["result"], cli("margin " + stack + " --tilt 0,0,1"));
  json none = json::parse(lines[2]), load = json::parse(lines[3]);
  EXPECT_EQ(none["exit"], 2);
  EXPECT_NE(none.value("error", std::string()).find("say which margin"), std::string::npos)
      << lines[2];
  EXPECT_EQ(load["exit"], 2);
  EXPECT_NE(load.value("error", std::string()).find("--load: no part named 'Nope'"),
            std::string::npos)
      << lines[3];
  std::filesystem::remove_all(dir);
}

// A sequence job's result is the document of `cairn sequence ... --json`, but
// for its wall-clock seconds.
TEST(BatchCli, SequenceJobs_ResultIsTheSequenceDocument) {
  const std::string dir = TempDir("cairn_batch_sequence");
  std::filesystem::create_directories(dir);
  const std::string stack = ExamplePath("stack3.json");
  WriteText(dir + "/jobs.jsonl", "{\"id\":\"up\",\"command\":\"sequence\",\"model\":\"" + stack +
                                     "\"}\n"
                                     "{\"id\":\"axes\",\"command\":\"sequence\",\"model\":\"" +
                                     stack +
                                     "\",\"options\":{\"directions\":\"axes\",\"beam\":1}}\n"
                                     "{\"id\":\"bad\",\"command\":\"sequence\",\"model\":\"" +
                                     stack + "\",\"options\":{\"temporary\":\"crane\"}}\n");
  const CliRun r = Cairn("batch " + dir + "/jobs.jsonl -o " + dir + "/out.jsonl --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = Lines(Slurp(dir + "/out.jsonl"));
  ASSERT_EQ(lines.size(), 3u);
  const auto without_clock = [](json doc) {
    doc["stats"].erase("seconds");
    return doc;
  };
  const auto cli = [&](const std::string& args) {
    const CliRun c = Cairn(args + " --json");
    EXPECT_EQ(c.exit_code, 0) << args << c.err;
    return without_clock(json::parse(c.out));
  };
  const json up = json::parse(lines[0]), axes = json::parse(lines[1]), bad = json::parse(lines[2]);
  EXPECT_EQ(up["exit"], 0) << lines[0].substr(0, 300);
  EXPECT_EQ(without_clock(up["result"]), cli("sequence " + stack));
  EXPECT_EQ(axes["exit"], 0) << lines[1].substr(0, 300);
  EXPECT_EQ(without_clock(axes["result"]),
            cli("sequence " + stack + " --directions axes --beam 1"));
  EXPECT_EQ(bad["exit"], 2) << lines[2];
  std::filesystem::remove_all(dir);
}

// --retry-failed runs again the jobs recorded with exit 2, 4 or 5, keeps the
// others' lines as they were, and a job fixed since is recorded as it is now.
TEST(BatchCli, RetryFailed_RunsAgainTheFailedJobsOnly) {
  const std::string dir = TempDir("cairn_batch_retry");
  std::filesystem::create_directories(dir);
  const std::string model = dir + "/model.json", out = dir + "/out.jsonl";
  const std::string jobs = dir + "/jobs.jsonl";
  WriteText(jobs, "{\"id\":\"a\",\"command\":\"check\",\"model\":\"" + ExamplePath("stack3.json") +
                      "\"}\n"
                      "{\"id\":\"b\",\"command\":\"check\",\"model\":\"" +
                      model +
                      "\"}\n"
                      "{\"id\":\"c\",\"command\":\"check\",\"model\":\"" +
                      ExamplePath("overhang_tips.json") + "\"}\n");
  ASSERT_EQ(Cairn("batch " + jobs + " -o " + out).exit_code, 0);
  std::vector<std::string> first = Lines(Slurp(out));
  ASSERT_EQ(first.size(), 3u);
  EXPECT_EQ(json::parse(first[1])["exit"], 2) << "the model is missing";
  // A line of a timed-out job (exit 5), as an earlier run may have left.
  first[2] = "{\"id\":\"c\",\"exit\":5,\"error\":\"exceeded --job-timeout 1 s\"}";
  WriteText(out, first[0] + "\n" + first[1] + "\n" + first[2] + "\n");
  // The plain resume runs nothing; --retry-failed runs b and c again.
  const CliRun resume = Cairn("batch " + jobs + " -o " + out);
  ASSERT_EQ(resume.exit_code, 0) << resume.err;
  EXPECT_NE(resume.out.find("0 jobs run, 3 already in RESULTS"), std::string::npos) << resume.out;
  std::filesystem::copy_file(ExamplePath("stack3.json"), model);
  const CliRun retry = Cairn("batch " + jobs + " -o " + out + " --retry-failed");
  ASSERT_EQ(retry.exit_code, 0) << retry.err;
  EXPECT_NE(retry.out.find("2 jobs run (2 of them again: --retry-failed), 1 already in RESULTS"),
            std::string::npos)
      << retry.out;
  const std::vector<std::string> lines = Lines(Slurp(out));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], first[0]) << "kept as it was";
  json b = json::parse(lines[1]), c = json::parse(lines[2]);
  EXPECT_EQ(b["id"], "b");
  EXPECT_EQ(b["exit"], 0) << lines[1].substr(0, 200);
  EXPECT_EQ(c["id"], "c");
  EXPECT_EQ(c["exit"], Cairn("check " + ExamplePath("overhang_tips.json")).exit_code);
  EXPECT_TRUE(c.contains("result"));
  // Nothing failed now: nothing to run again.
  const CliRun again = Cairn("batch " + jobs + " -o " + out + " --retry-failed");
  EXPECT_NE(again.out.find("0 jobs run, 3 already in RESULTS"), std::string::npos) << again.out;
  EXPECT_EQ(Cairn("batch " + jobs + " -o " + out + " --retry-failed --fresh").exit_code, 2);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cairn

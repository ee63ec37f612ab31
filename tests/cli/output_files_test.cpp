// OutputFiles (src/cli/output_files.h): the files of a command all or none,
// never over a device or a folder, links followed, no temporary left.
#include "cli/output_files.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "cairn/core/error.h"
#include "cli/cli_run.h"

namespace cairn::cli {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A fresh folder of this test's own.
fs::path Folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Nothing but `expected` in `dir` (no temporary files).
void ExpectOnly(const fs::path& dir, std::set<std::string> expected) {
  std::set<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) found.insert(e.path().filename().string());
  EXPECT_EQ(found, expected);
}

TEST(OutputFiles, WritesEveryFileOnCommit) {
  const fs::path dir = Folder("of_commit");
  OutputFiles files;
  files.Add((dir / "a.txt").string(), "alpha", "--a");
  files.Add((dir / "b.txt").string(), "beta", "--b");
  ExpectOnly(dir, {});  // nothing before the commit
  files.Commit();
  EXPECT_EQ(Read(dir / "a.txt"), "alpha");
  EXPECT_EQ(Read(dir / "b.txt"), "beta");
  ExpectOnly(dir, {"a.txt", "b.txt"});
  fs::remove_all(dir);
}

TEST(OutputFiles, ADeviceOrAFolderIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = Folder("of_device");
  OutputFiles files;
  files.Add((dir / "a.txt").string(), "alpha", "--a");
  EXPECT_THROW(files.Add("/dev/null", "x", "--timeline"), InputError);
  EXPECT_THROW(files.Add(dir.string(), "x", "--dot"), InputError);
  ExpectOnly(dir, {});
  fs::remove_all(dir);
}

TEST(OutputFiles, ALinkIsFollowedAndKept) {
  const fs::path dir = Folder("of_link");
  fs::create_symlink(dir / "real.csv", dir / "link.csv");  // dangling until written
  OutputFiles files;
  files.Add((dir / "link.csv").string(), "data", "--timeline");
  files.Commit();
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "link.csv")));
  EXPECT_EQ(Read(dir / "real.csv"), "data");
  fs::remove_all(dir);
}

TEST(OutputFiles, AFailedWriteLeavesNoFileAndNoTemporary) {
  const fs::path dir = Folder("of_fail");
  {
    std::ofstream(dir / "old.txt") << "before";
    OutputFiles files;
    files.Add((dir / "old.txt").string(), "after", "--a");
    files.Add((dir / "missing" / "b.txt").string(), "beta", "--b");  // its folder does not exist
    try {
      files.Commit();
      ADD_FAILURE() << "the commit should have failed";
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), "--b");
    }
  }
  EXPECT_EQ(Read(dir / "old.txt"), "before");  // untouched
  ExpectOnly(dir, {"old.txt"});
  fs::remove_all(dir);
}

// The message of the InputError `f` throws ("" when it throws none).
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputFiles, AnInputIsNeverAnOutput_ThroughLinksAndHardLinksToo) {
  const fs::path dir = Folder("of_input");
  std::ofstream(dir / "scene.json") << "scene";
  fs::create_symlink(dir / "scene.json", dir / "link.json");
  fs::create_hard_link(dir / "scene.json", dir / "hard.json");
  const std::vector<NamedFile> inputs = {{(dir / "scene.json").string(), "the model file"}};
  for (const fs::path& out : {dir / "scene.json", dir / "link.json", dir / "hard.json",
                              dir / "." / ".." / dir.filename() / "scene.json"}) {
    OutputFiles files(inputs);
    const std::string error = ErrorOf([&] { files.Add(out.string(), "page", "--html"); });
    EXPECT_EQ(error, "--html and the model file name the same file '" + out.string() +
                         "': an output never replaces an input");
  }
  EXPECT_EQ(Read(dir / "scene.json"), "scene");
  // Beside it is fine.
  OutputFiles files(inputs);
  files.Add((dir / "page.html").string(), "page", "--html");
  files.Commit();
  ExpectOnly(dir, {"scene.json", "link.json", "hard.json", "page.html"});
  fs::remove_all(dir);
}

// An input folder (an ASAP assembly): its files are not replaced, new files
// may go in it.
TEST(OutputFiles, AFileOfAnInputFolderIsNotReplaced) {
  const fs::path dir = Folder("of_input_folder");
  fs::create_directories(dir / "asap");
  std::ofstream(dir / "asap" / "config.json") << "{}";
  const std::vector<NamedFile> inputs = {{(dir / "asap").string(), "the model file"}};
  OutputFiles files(inputs);
  const std::string error =
      ErrorOf([&] { files.Add((dir / "asap" / "config.json").string(), "x", "--html"); });
  EXPECT_NE(error.find("--html: '" + (dir / "asap" / "config.json").string() +
                       "' is inside the model file ('" + (dir / "asap").string() +
                       "'), a folder read as input"),
            std::string::npos)
      << error;
  files.Add((dir / "asap" / "page.html").string(), "x", "--html");
  files.Commit();
  EXPECT_EQ(Read(dir / "asap" / "config.json"), "{}");
  EXPECT_EQ(Read(dir / "asap" / "page.html"), "x");
  fs::remove_all(dir);
}

TEST(OutputFiles, TwoOutputsNamingOneFile_SaySo) {
  const fs::path dir = Folder("of_twice");
  fs::create_symlink(dir / "same.out", dir / "link.out");
  const std::string same = (dir / "same.out").string();
  EXPECT_EQ(ErrorOf([&] {
              CheckOutputs({{same, "--timeline"}, {same, "--html"}}, {});
            }),
            "--timeline and --html name the same file '" + same + "'");
  EXPECT_EQ(ErrorOf([&] {
              CheckOutputs({{same, "--dot"}, {(dir / "link.out").string(), "--html"}}, {});
            }),
            "--dot and --html name the same file '" + (dir / "link.out").string() + "'");
  EXPECT_EQ(ErrorOf([&] { CheckOutputs({{same, "--dot"}, {"", "--html"}}, {}); }), "");
  ExpectOnly(dir, {"link.out"});
  fs::remove_all(dir);
}

// The commands: every output checked against every input, exit 2 naming
// both, nothing written.
TEST(OutputFilesCli, NoCommandWritesOverItsInput) {
  using testing::Cairn;
  const fs::path dir = Folder("of_cli");
  const std::string scene = (dir / "s.json").string(), plan = (dir / "p.json").string();
  fs::copy_file(testing::ExamplePath("paper_fig1.json"), scene);
  fs::copy_file(testing::ExamplePath("plans/paper_fig1_b_first.plan.json"), plan);
  fs::create_symlink(scene, dir / "link.json");
  const std::string link = (dir / "link.json").string();
  const std::string scene_text = Read(scene), plan_text = Read(plan);
  struct Case {
    std::string args, expect;
  };
  const std::vector<Case> cases = {
      {"check " + scene + " --html " + scene, "--html and the model file name the same file"},
      {"check " + scene + " --html " + link, "--html and the model file name the same file"},
      {"simulate " + scene + " " + plan + " --timeline " + plan,
       "--timeline and the plan file name the same file"},
      {"simulate " + scene + " " + plan + " --html " + scene,
       "--html and the model file name the same file"},
      {"plan " + scene + " --dot " + scene, "--dot and the model file name the same file"},
      {"plan " + scene + " --html " + link, "--html and the model file name the same file"},
      {"plan " + scene + " --emit-plans " + dir.string() + " --max 1 --threads 1",
       ""},  // the scene's folder: new files beside it
      {"convert " + scene + " " + link, "the output file and the input file name the same file"},
      {"simulate " + scene + " " + plan + " --html " + (dir / "same.out").string() +
           " --timeline " + (dir / "same.out").string(),
       "--timeline and --html name the same file '" + (dir / "same.out").string() + "'"},
  };
  for (const Case& c : cases) {
    const testing::CliRun r = Cairn(c.args);
    if (c.expect.empty()) {
      EXPECT_LE(r.exit_code, 1) << c.args << r.err;
      continue;
    }
    EXPECT_EQ(r.exit_code, 2) << c.args << r.err;
    EXPECT_EQ(r.err.rfind("cairn: error: " + c.expect, 0), 0u) << c.args << "\n" << r.err;
    EXPECT_EQ(Read(scene), scene_text) << c.args;
    EXPECT_EQ(Read(plan), plan_text) << c.args;
  }
  EXPECT_TRUE(fs::exists(dir / "sequence_001.plan.json"));
  EXPECT_FALSE(fs::exists(dir / "same.out"));
  // A scene named as the first emitted plan, in the --emit-plans folder.
  fs::create_directories(dir / "em");
  const std::string named = (dir / "em" / "sequence_001.plan.json").string();
  fs::copy_file(scene, named);
  const testing::CliRun r =
      Cairn("plan " + named + " --max 1 --threads 1 --emit-plans " + (dir / "em").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err, "cairn: error: --emit-plans and the model file name the same file '" + named +
                       "': an output never replaces an input\n");
  EXPECT_EQ(Read(named), scene_text);
  ExpectOnly(dir / "em", {"sequence_001.plan.json"});
  fs::remove_all(dir);
}

// SIGTERM while `plan --emit-plans` commits its thousands of files (4 000:
// the 2 000 best sequences of the pyramid, a plan each way): the handler
// removes every temporary, every target the run made and the folder it made,
// whatever their number.
TEST(OutputFilesCli, SigtermDuringEmitPlans_LeavesNothing) {
  const fs::path dir = Folder("of_sigterm");
  const fs::path em = dir / "em";
  const std::string cli = testing::CliPath(), scene = testing::ExamplePath("pyramid10.json");
  const std::string html = (dir / "x.html").string(), dot = (dir / "g.dot").string();
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (!std::freopen("/dev/null", "w", stdout)) ::_exit(126);
    ::execl(cli.c_str(), cli.c_str(), "plan", scene.c_str(), "--threads", "1", "--max", "2000",
            "--html", html.c_str(), "--dot", dot.c_str(), "--emit-plans", em.string().c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Until the commit has begun to fill the folder (or the run is over), then
  // the signal.
  int status = 0;
  bool ended = false;
  for (int i = 0; i < 600000 && !ended; ++i) {
    std::error_code ec;
    if (fs::is_directory(em, ec) && !fs::is_empty(em, ec) && !ec) break;
    ended = ::waitpid(pid, &status, WNOHANG) == pid;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ASSERT_FALSE(ended) << "the run ended before its files were written";
  ::kill(pid, SIGTERM);
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM)
      << "the run finished its commit before the signal (status " << status << ")";
  EXPECT_FALSE(fs::exists(em)) << "the folder the run made, with "
                               << (fs::exists(em) ? std::distance(fs::directory_iterator(em),
                                                                  fs::directory_iterator())
                                                  : 0)
                               << " entries";
  ExpectOnly(dir, {});  // no temporary, no page, no graph
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cairn::cli

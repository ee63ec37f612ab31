// `--html FILE` on every command that computes a result (docs/html.md): the page is
// written whole, beside the command's usual output, with the same exit code;
// a target it cannot write is refused with exit 2 before anything is
// written. The pages in a real browser: tests/web.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_run.h"

namespace cairn::testing {
namespace {

namespace fs = std::filesystem;

// The page data of a page file.
nlohmann::json PageData(const std::string& page) {
  const std::string open = "<script id=\"cairn-data\" type=\"application/json\">";
  const size_t begin = page.find(open) + open.size();
  return nlohmann::json::parse(page.substr(begin, page.find("</script>", begin) - begin));
}

TEST(Html, EveryCommandWritesItsPageWithItsJsonDocumentAndKeepsItsExitCode) {
  const std::string dir = TempDir("cairn_html");
  fs::create_directories(dir);
  const std::string fig1 = ExamplePath("paper_fig1.json");
  struct Case {
    std::string kind, args;
    int exit_code;
  };
  const Case cases[] = {
      {"check", "check " + fig1 + " --without C", 1},
      {"check", "check " + fig1, 0},
      {"simulate", "simulate " + fig1 + " " + ExamplePath("plans/paper_fig1_b_first.plan.json"), 1},
      {"plan", "plan " + fig1 + " --threads 1", 0},
      {"sequence", "sequence " + ExamplePath("paper_fig17.json"), 0},
      {"margin", "margin " + fig1 + " --tilt 0,0,1", 0},
      {"margin", "margin " + fig1 + " --without C --tilt 0,0,1", 1},
      {"blocking", "blocking " + fig1, 0},
  };
  for (const Case& c : cases) {
    const std::string page = dir + "/page.html";
    fs::remove(page);
    const CliRun json = Cairn(c.args + " --json");
    const CliRun run = Cairn(c.args + " --json --html " + page);
    EXPECT_EQ(run.exit_code, c.exit_code) << c.args << "\n" << run.err;
    EXPECT_EQ(json.exit_code, c.exit_code) << c.args;
    ASSERT_TRUE(fs::exists(page)) << c.args;
    const nlohmann::json data = PageData(Slurp(page));
    EXPECT_EQ(data["kind"], c.kind);
    // The page holds the document --json prints, but the plan's and the
    // sequence's timings.
    nlohmann::json doc = nlohmann::json::parse(json.out), shown = data["result"];
    EXPECT_EQ(nlohmann::json::parse(run.out).dump(), shown.dump()) << c.args;
    if (c.kind == "sequence") {
      doc["stats"].erase("seconds");
      shown["stats"].erase("seconds");
    }
    if (c.kind == "plan") {
      doc.erase("stats");
      shown.erase("stats");
    }
    EXPECT_EQ(doc, shown) << c.args;
  }
  fs::remove_all(dir);
}

TEST(Html, ATargetThatCannotBeWrittenIsRefusedAndNothingIsWritten) {
  const std::string dir = TempDir("cairn_html_refused");
  fs::create_directories(dir + "/a_folder");
  const std::string timeline = dir + "/timeline.csv";
  const CliRun r = Cairn("simulate " + ExamplePath("paper_fig1.json") + " " +
                         ExamplePath("plans/paper_fig1_b_first.plan.json") + " --timeline " +
                         timeline + " --html " + dir + "/a_folder");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--html"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a_folder"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "") << "nothing is printed when the files fail";
  EXPECT_FALSE(fs::exists(timeline)) << "all files or none";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  const CliRun empty = Cairn("check " + ExamplePath("paper_fig1.json") + " --html ''");
  EXPECT_EQ(empty.exit_code, 2) << empty.err;
  // margin and blocking: a folder, and the model file itself, are refused
  // before any work, naming the flag.
  for (const std::string& args :
       {"margin " + ExamplePath("paper_fig1.json") + " --friction --html " + dir + "/a_folder",
        "blocking " + ExamplePath("paper_fig1.json") + " --html " + dir + "/a_folder",
        "margin " + ExamplePath("paper_fig1.json") + " --tilt 0,0,1 --html " +
            ExamplePath("paper_fig1.json")}) {
    const CliRun refused = Cairn(args);
    EXPECT_EQ(refused.exit_code, 2) << args;
    EXPECT_NE(refused.err.find("--html"), std::string::npos) << refused.err;
    EXPECT_EQ(refused.out, "") << args;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cairn::testing

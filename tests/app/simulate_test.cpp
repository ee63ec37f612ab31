// app/simulate.h: `cairn simulate` as the CLI, batch and Python run it.
#include "cairn/app/simulate.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn::app {
namespace {

using testing::ExamplePath;

// The plan read from its file or given as data runs the same; the timeline
// and the page come only when asked; the monitor hears every step.
TEST(SimulateDocument, APlanFromItsFileOrAsDataRunsTheSame) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  SimulateQuery q;
  q.plan_file = ExamplePath("plans/paper_fig1_c_first.plan.json");
  std::vector<std::string> statuses;
  const CommandResult by_file =
      SimulateDocument(m, q, {{}, [&](const std::string& s) { statuses.push_back(s); }});
  EXPECT_EQ(by_file.exit, by_file.document["stable"] == true ? kExitStable : kExitUnstable);
  EXPECT_TRUE(by_file.timeline.empty());
  EXPECT_TRUE(by_file.page.empty());
  ASSERT_FALSE(statuses.empty());
  EXPECT_EQ(statuses.front().rfind("step 1/", 0), 0u) << statuses.front();
  std::ifstream in(q.plan_file);
  q.plan_data = nlohmann::json::parse(in);
  q.timeline = q.page = true;
  const CommandResult by_data = SimulateDocument(m, q);
  EXPECT_EQ(by_data.document, by_file.document);
  EXPECT_EQ(by_data.timeline.rfind("time,", 0), 0u);
  EXPECT_NE(by_data.page.find("<html"), std::string::npos);
}

TEST(SimulateDocument, AnUnknownMarginNamesTheOption) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  SimulateQuery q;
  q.plan_file = ExamplePath("plans/paper_fig1_c_first.plan.json");
  q.margin = "tilt";
  try {
    SimulateDocument(m, q);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "--margin");
  }
}

}  // namespace
}  // namespace cairn::app

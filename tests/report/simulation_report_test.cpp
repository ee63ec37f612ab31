// simulation_report.h: the timeline CSV behind the paper's force-versus-time
// figures and the `cairn simulate --json` document.
#include "cairn/report/simulation_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "cairn/io/plan_reader.h"
#include "example_scene.h"

namespace cairn {
namespace {

TEST(TimelineToCsv, AHeaderThenOneRowPerTickAndContact) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Plan plan =
      ReadPlan(testing::ExamplePath("plans/paper_fig1_dcba.plan.json"), fig1.assembly);
  SimulationOptions options;
  options.record_timeline = true;
  const SimulationResult r = SimulatePlan(fig1.assembly, plan, options);
  ASSERT_TRUE(r.stable());
  const std::string csv = TimelineToCsv(fig1.assembly, r, {});
  std::istringstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header,
            "time,step,tick,part_a,part_b,x,y,normal_x,normal_y,normal_force,friction_force,"
            "normal_velocity,sliding_velocity,breaks,slides");
  size_t rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 14) << line;
  }
  EXPECT_EQ(rows, r.timeline.size());
  const nlohmann::json doc = SimulationToJson(fig1.assembly, plan, r, {});
  EXPECT_EQ(doc["verdict"], "stable");
  EXPECT_EQ(doc["steps"].size(), plan.steps.size());
}

}  // namespace
}  // namespace cairn

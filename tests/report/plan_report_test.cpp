// plan_report.h: what PlanDisassembly found, as JSON, text, dot and plan
// files, says the same as the result: every sequence, every edge, and plan
// files that read back as the sequence.
#include "cairn/report/plan_report.h"

#include <gtest/gtest.h>

#include "cairn/io/plan_reader.h"
#include "example_scene.h"

namespace cairn {
namespace {

class PlanReportFig1 : public ::testing::Test {
 protected:
  const testing::ExampleScene fig1_{"paper_fig1.json"};
  const PlannerResult r_ = PlanDisassembly(fig1_.def, fig1_.assembly);
};

TEST_F(PlanReportFig1, JsonHasEverySequenceNodeAndEdge) {
  ASSERT_FALSE(r_.sequences.empty());
  const nlohmann::json doc = PlannerToJson(fig1_.assembly, r_, {});
  EXPECT_EQ(doc["dimension"], 2);
  EXPECT_EQ(doc["complete"], r_.complete);
  ASSERT_EQ(doc["sequences"].size(), r_.sequences.size());
  EXPECT_EQ(doc["graph"]["nodes"].size(), r_.nodes.size());
  EXPECT_EQ(doc["graph"]["edges"].size(), r_.edges.size());
  EXPECT_EQ(doc["stats"]["nodes"], r_.stats.nodes);
}

TEST_F(PlanReportFig1, TheDotGraphHasANodeLinePerNode) {
  const std::string dot = PlannerToDot(fig1_.assembly, r_);
  EXPECT_EQ(dot.rfind("digraph", 0), 0u) << dot.substr(0, 40);
  EXPECT_EQ(dot.back(), '\n');
  for (size_t i = 0; i < r_.nodes.size(); ++i)
    EXPECT_NE(dot.find("  n" + std::to_string(i) + " [label="), std::string::npos) << i;
}

// A sequence written as a plan file reads back as the same steps.
TEST_F(PlanReportFig1, PlanFilesReadBackAsTheSequence) {
  for (const PlanMode mode : {PlanMode::kDisassemble, PlanMode::kAssemble}) {
    const PlanDef def = SequenceToPlanDef(r_.sequences.front(), r_, mode);
    const nlohmann::json doc = PlanDefToJson(def, 2);
    EXPECT_EQ(doc["cairn_plan"], 1);
    const PlanDef back = ParsePlanJson(doc, "written", 2);
    EXPECT_EQ(back.mode, def.mode);
    ASSERT_EQ(back.steps.size(), def.steps.size());
    for (size_t k = 0; k < def.steps.size(); ++k) {
      EXPECT_EQ(back.steps[k].remove, def.steps[k].remove) << k;
      EXPECT_EQ(back.steps[k].path, def.steps[k].path) << k;
      EXPECT_EQ(back.steps[k].direction, def.steps[k].direction) << k;
      EXPECT_EQ(back.steps[k].distance, def.steps[k].distance) << k;
    }
  }
}

}  // namespace
}  // namespace cairn

// app/plan.h: `cairn plan` as the CLI, batch and Python run it.
#include "cairn/app/plan.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn::app {
namespace {

using testing::ExamplePath;

// Paper Fig. 1 comes apart (exit 0); its plan files, graph and page come
// only when asked, one disassembly and one assembly plan per sequence.
TEST(PlanDocument, PaperFig1WithItsFiles) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  PlanQuery q;
  q.max = 1;
  q.threads = 1;
  const CommandResult bare = PlanDocument(m, q);
  EXPECT_EQ(bare.exit, kExitStable);
  EXPECT_TRUE(bare.plans.empty() && bare.dot.empty() && bare.page.empty());
  q.emit_plans = q.dot = q.page = true;
  const CommandResult r = PlanDocument(m, q);
  EXPECT_EQ(r.document["sequences"], bare.document["sequences"]);
  ASSERT_EQ(r.plans.size(), 2u);
  EXPECT_EQ(r.plans[0].first, "sequence_001.plan.json");
  EXPECT_EQ(r.plans[1].first, "sequence_001.assemble.plan.json");
  EXPECT_EQ(r.dot.rfind("digraph", 0), 0u);
  EXPECT_NE(r.page.find("<html"), std::string::npos);
}

TEST(PlanDocument, OptionValuesAreCheckedNamingTheOption) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  for (const auto& [directions, support, option] :
       {std::tuple("diagonals", "full", "--directions"), std::tuple("ndbg", "some", "--support")}) {
    PlanQuery q;
    q.directions = directions;
    q.support = support;
    try {
      PlanDocument(m, q);
      ADD_FAILURE() << option;
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), option);
    }
  }
}

}  // namespace
}  // namespace cairn::app

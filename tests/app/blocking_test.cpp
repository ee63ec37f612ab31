// app/blocking.h: `cairn blocking` as the CLI, batch and Python run it.
#include "cairn/app/blocking.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn::app {
namespace {

using testing::ExamplePath;

TEST(BlockingDirection, TwoNumbersInTwoDAndErrorsNameTheOption) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  EXPECT_TRUE(BlockingDirection({3, 4}, m.assembly).isApprox(Vector3(0.6, 0.8, 0)));
  EXPECT_TRUE(BlockingDirection({0, 2, 0}, m.assembly).isApprox(Vector3(0, 1, 0)));
  // Unit length without overflow (a direction of huge components).
  EXPECT_TRUE(
      BlockingDirection({1e155, 1e155}, m.assembly).isApprox(Vector3(1, 1, 0) / std::sqrt(2.0)));
  for (const std::vector<double>& bad :
       {std::vector<double>{1, 0, 1}, {0, 0}, {1}, {std::nan(""), 1}}) {
    try {
      BlockingDirection(bad, m.assembly, "direction");
      ADD_FAILURE();
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), "direction");
    }
  }
}

// Along +y nothing holds paper Fig. 1's top block down: the one cell at
// that direction is the NDBG's cell that holds it.
TEST(BlockingDocument, OneDirectionIsTheCellThatHoldsIt) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  const CommandResult all = BlockingDocument(m, {});
  const CommandResult up = BlockingDocument(m, {{}, {0, 1}});
  ASSERT_EQ(up.document["cells"].size(), 1u);
  bool found = false;
  for (const auto& cell : all.document["cells"])
    found |= cell["removable"] == up.document["cells"][0]["removable"];
  EXPECT_TRUE(found);
  EXPECT_EQ(up.exit, kExitStable);
}

}  // namespace
}  // namespace cairn::app

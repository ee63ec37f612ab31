// app/margin.h: `cairn margin` as the CLI, batch and Python run it.
#include "cairn/app/margin.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn::app {
namespace {

using testing::ExamplePath;

TEST(ResolveMarginQuery, OneQuantityAndErrorsNameTheFlag) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  const auto refused = [&](const MarginQuery& q) {
    try {
      ResolveMarginQuery(m.assembly, q, m.file);
    } catch (const InputError& e) {
      return e.json_path();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused({}), "margin");
  EXPECT_EQ(refused({true, {0, 0, 1}, "", {}, {}, {}}), "margin");
  EXPECT_EQ(refused({false, {1, 0, 0}, "", {}, {}, {}}), "--tilt");  // 2-D: about z only
  EXPECT_EQ(refused({false, {}, "B", {}, {0, -1}, {}}), "--point");
  EXPECT_EQ(refused({false, {}, "Z", {0, 0}, {0, -1}, {}}), "--load");
  EXPECT_EQ(ResolveMarginQuery(m.assembly, {false, {0, 0, 2}, "", {}, {}, {}}, m.file).axis,
            Vector3(0, 0, 1));
}

// Paper Fig. 1 stands as given (exit 0, the margin solved, no failure) and
// its tilt margin about z comes back in the document and in words.
TEST(MarginDocument, PaperFig1Tilts) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  const CommandResult r = MarginDocument(m, {false, {0, 0, 1}, "", {}, {}, {}});
  EXPECT_EQ(r.exit, kExitStable);
  EXPECT_TRUE(r.failure.empty());
  EXPECT_TRUE(r.document.contains("margin")) << r.document.dump();
  EXPECT_FALSE(r.text.empty());
}

}  // namespace
}  // namespace cairn::app

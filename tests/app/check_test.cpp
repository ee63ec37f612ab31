// app/check.h: `cairn check` as the CLI, batch and Python run it.
#include "cairn/app/check.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn::app {
namespace {

using testing::ExamplePath;

// Paper Fig. 1 stands; without block B, C and D lose their support and the
// check says so (exit 1), in the document and in words.
TEST(CheckDocument, PaperFig1StandsAndFallsWithoutB) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  int polls = 0;
  const CommandResult r = CheckDocument(m, {}, {[&] { ++polls; }, {}});
  EXPECT_EQ(r.exit, kExitStable);
  EXPECT_EQ(r.document["stable"], true);
  EXPECT_EQ(r.document["scene_file"], m.file);
  EXPECT_EQ(polls, 1);  // one solve: polled before it
  EXPECT_TRUE(r.page.empty());
  EXPECT_FALSE(r.text.empty());
  CheckQuery without_b;
  without_b.without = {"B"};
  const CommandResult fall = CheckDocument(m, without_b);
  EXPECT_EQ(fall.exit, kExitUnstable);
  EXPECT_EQ(fall.document["stable"], false);
  EXPECT_FALSE(fall.document["moving"].empty());
}

TEST(CheckDocument, ThePageOnlyWhenAskedAndItHoldsTheDocument) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  CheckQuery q;
  q.page = true;
  const CommandResult r = CheckDocument(m, q);
  EXPECT_NE(r.page.find("<html"), std::string::npos);
  EXPECT_NE(r.page.find("paper_fig1.json"), std::string::npos);
}

TEST(CheckDocument, AnUnknownPartNamesTheOption) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  CheckQuery q;
  q.without = {"nope"};
  try {
    CheckDocument(m, q);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "--without");
  }
}

}  // namespace
}  // namespace cairn::app

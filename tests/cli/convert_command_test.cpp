// convert_command.h: `cairn convert` writes the scene whole and says where,
// and a conversion that cannot be written leaves nothing behind (the scene
// text itself: tests/io/scene_writer_test.cpp).
#include "cli/convert_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "cairn/io/scene_reader.h"
#include "cairn/io/scene_writer.h"
#include "cli/cli_run.h"
#include "cli/command.h"

namespace cairn::cli {
namespace {

TEST(RunConvert, WritesTheSceneWholeAndSaysWhere) {
  ConvertArgs args;
  args.input = testing::ExamplePath("paper_fig1.json");
  args.output = testing::TempDir("convert") + ".json";
  std::ostringstream out, err;
  ASSERT_EQ(RunConvert(args, out, err), kExitStable) << err.str();
  EXPECT_NE(out.str().find("wrote " + args.output), std::string::npos) << out.str();
  // The same model: written again, the same text (the writer is exact:
  // tests/io/scene_writer_test.cpp).
  EXPECT_EQ(WriteSceneJson(ReadSceneDef(args.output)), WriteSceneJson(ReadSceneDef(args.input)));
  std::filesystem::remove(args.output);
}

TEST(RunConvert, AnOutputThatCannotBeWrittenIsBadInputWithNothingLeftBehind) {
  ConvertArgs args;
  args.input = testing::ExamplePath("paper_fig1.json");
  const std::string dir = testing::TempDir("convert_missing");  // absent
  args.output = dir + "/scene.json";
  std::ostringstream out, err;
  EXPECT_EQ(RunConvert(args, out, err), kExitBadInput);
  EXPECT_NE(err.str().find("cannot write"), std::string::npos) << err.str();
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
}  // namespace cairn::cli

// convert_command.h and scene_writer.h: a model written back as a scene file
// is the same model, bit for bit (masses, centroids, contacts), and a
// conversion that cannot be written leaves nothing behind.
#include "cli/convert_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cairn/io/scene_reader.h"
#include "cairn/io/scene_writer.h"
#include "cli/cli_run.h"
#include "cli/command.h"

namespace cairn::cli {
namespace {

// The scene text parsed back as a model.
AssemblyDef Reparse(const AssemblyDef& def) {
  return ParseSceneJson(nlohmann::json::parse(WriteSceneJson(def)), "written");
}

void ExpectSameModel(const Assembly& a, const Assembly& b) {
  ASSERT_EQ(a.num_parts(), b.num_parts());
  EXPECT_EQ(a.dimension(), b.dimension());
  for (int i = 0; i < a.num_parts(); ++i) {
    EXPECT_EQ(a.part(i).name, b.part(i).name);
    EXPECT_EQ(a.part(i).fixed, b.part(i).fixed) << a.part(i).name;
    EXPECT_EQ(a.part(i).mass, b.part(i).mass) << a.part(i).name;  // exact numbers
    EXPECT_EQ(a.part(i).centroid, b.part(i).centroid) << a.part(i).name;
  }
  EXPECT_EQ(a.length_tolerance(), b.length_tolerance());
}

TEST(WriteSceneJson, A2DAndA3DSceneReadBackAsTheSameModel) {
  for (const char* name : {"paper_fig1.json", "paper_fig9.json", "jenga.json"}) {
    SCOPED_TRACE(name);
    const AssemblyDef def = ReadSceneDef(testing::ExamplePath(name));
    ExpectSameModel(Assembly::Create(def), Assembly::Create(Reparse(def)));
  }
}

TEST(RunConvert, WritesTheSceneWholeAndSaysWhere) {
  ConvertArgs args;
  args.input = testing::ExamplePath("paper_fig1.json");
  args.output = testing::TempDir("convert") + ".json";
  std::ostringstream out, err;
  ASSERT_EQ(RunConvert(args, out, err), kExitStable) << err.str();
  EXPECT_NE(out.str().find("wrote " + args.output), std::string::npos) << out.str();
  ExpectSameModel(ReadScene(args.input), ReadScene(args.output));
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

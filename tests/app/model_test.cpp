// app/model.h: the model read as every front end reads it.
#include "cairn/app/model.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn::app {
namespace {

using testing::ExamplePath;

TEST(LoadModel, RemembersItsFileAndAppliesTheOptions) {
  ModelArgs args;
  args.friction = 0.25;
  args.supports = {"C"};
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), args);
  EXPECT_EQ(m.file, ExamplePath("paper_fig1.json"));
  EXPECT_EQ(m.def.friction, 0.25);
  EXPECT_TRUE(m.assembly.part(m.assembly.FindPart("C")).fixed);
}

TEST(LoadModel, RefusesAnUnknownFormatOrInterfacesNamingTheOption) {
  for (const auto& [format, interfaces, option] :
       {std::tuple("obj", "detect", "--format"), std::tuple("scene", "guess", "--interfaces")}) {
    ModelArgs args;
    args.format = format;
    args.interfaces = interfaces;
    try {
      LoadModel(ExamplePath("paper_fig1.json"), args);
      ADD_FAILURE() << format << " " << interfaces;
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), option);
    }
  }
}

TEST(ResolvePart, NamesTheFlagAndTheFile) {
  const Model m = LoadModel(ExamplePath("paper_fig1.json"), {});
  EXPECT_EQ(ResolvePart(m.assembly, "B", "--keep", m.file), m.assembly.FindPart("B"));
  try {
    ResolvePart(m.assembly, "Z", "--keep", m.file);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "--keep");
    EXPECT_NE(e.message().find("no part named 'Z'"), std::string::npos);
  }
}

}  // namespace
}  // namespace cairn::app

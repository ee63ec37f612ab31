// io/sidecar_reader.h: what a CAD model does not carry, applied to it, and
// every fault named in the sidecar with its JSON path.
#include "cairn/io/sidecar_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cairn/core/error.h"
#include "cairn/io/scene_reader.h"
#include "test_paths.h"

namespace cairn {
namespace {

std::string WriteSidecar(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(ApplySidecar, SetsFrictionDensityMassAndFixedAndSaysWhere) {
  AssemblyDef def = ReadSceneDef(testing::ExamplePath("paper_fig1.json"));
  const std::string path = WriteSidecar("cairn_sidecar_ok.json",
                                        R"({"cairn_sidecar": 1, "friction": 0.5, "density": 3,
          "parts": {"A": {"fixed": true}, "B": {"mass": 2}}})");
  const auto set_by = ApplySidecar(path, def);
  EXPECT_EQ(def.friction, 0.5);
  for (const PartDef& p : def.parts) {
    if (p.name == "A") {
      EXPECT_TRUE(p.fixed);
    }
    if (p.name == "B") {
      EXPECT_EQ(p.mass, 2.0);
    }
    if (p.name == "C") {
      EXPECT_EQ(p.density, 3.0);
    }
  }
  EXPECT_EQ(set_by.at("B"), "parts.B.mass");
  EXPECT_EQ(set_by.at("C"), "density");
  std::filesystem::remove(path);
}

TEST(ApplySidecar, FaultsNameTheSidecarAndTheJsonPath) {
  for (const auto& [text, json_path] :
       {std::pair(R"({"cairn_sidecar": 1, "parts": {"Z": {"fixed": true}}})", "parts.Z"),
        std::pair(R"({"cairn_sidecar": 1, "frction": 0.5})", "frction"),
        std::pair(R"({"cairn_sidecar": 1, "parts": {"B": {"mass": -1}}})", "parts.B.mass"),
        std::pair(R"({"cairn_sidecar": 2})", "cairn_sidecar")}) {
    AssemblyDef def = ReadSceneDef(testing::ExamplePath("paper_fig1.json"));
    const std::string path = WriteSidecar("cairn_sidecar_bad.json", text);
    try {
      ApplySidecar(path, def);
      ADD_FAILURE() << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path) << text;
      EXPECT_EQ(e.json_path(), json_path) << e.what();
    }
    std::filesystem::remove(path);
  }
}

}  // namespace
}  // namespace cairn

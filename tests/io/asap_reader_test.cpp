// io/asap_reader.h: an ASAP folder written here (a unit cube twice), its
// parts named by key in numeric order and placed by `final_state`.
#include "cairn/io/asap_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cairn/core/error.h"
#include "cairn/geometry/assembly.h"

namespace cairn {
namespace {

namespace fs = std::filesystem;

// The unit cube [0, 1]³ as an OBJ of 12 triangles, outward.
constexpr const char* kCube = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
)";

// A folder of its own per test (ctest runs the tests of one file at once).
fs::path Folder(const std::string& name, const std::string& config) {
  const fs::path dir = fs::temp_directory_path() / ("cairn_asap_reader_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* key : {"0", "10"}) std::ofstream(dir / (std::string(key) + ".obj")) << kCube;
  std::ofstream(dir / "config.json") << config;
  return dir;
}

// Part "10" sits at the origin; part "0" is turned a quarter about z and
// moved to (5, 0, 1): its cube spans x 4..5, y 0..1, z 1..2.
TEST(ReadAsapAssembly, NamesInKeyOrderAndPlacesByFinalState) {
  const fs::path dir = Folder("placed", R"({"10": {"final_state": [0, 0, 0, 0, 0, 0]},
      "0": {"initial_state": [9, 9, 9, 0, 0, 0], "final_state": [5, 0, 1, 0, 0, 1.5707963267948966]}})");
  const AssemblyDef def = ReadAsapAssembly(dir.string());
  ASSERT_EQ(def.parts.size(), 2u);
  EXPECT_EQ(def.parts[0].name, "0");
  EXPECT_EQ(def.parts[1].name, "10");
  const Assembly assembly = Assembly::Create(def);
  const Configuration config = Configuration::Assembled(assembly);
  Vector3 lo = Vector3::Constant(1e9), hi = -lo;
  for (const Vector3& v : config.WorldVertices(assembly, 0)) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  EXPECT_TRUE(lo.isApprox(Vector3(4, 0, 1), 1e-12)) << lo.transpose();
  EXPECT_TRUE(hi.isApprox(Vector3(5, 1, 2), 1e-12)) << hi.transpose();
  fs::remove_all(dir);
}

TEST(ReadAsapAssembly, AFinalStateOfFiveNumbersIsNamed) {
  const fs::path dir = Folder("five", R"({"0": {"final_state": [0, 0, 0, 0, 0]},
                                  "10": {"final_state": [3, 0, 0, 0, 0, 0]}})");
  try {
    ReadAsapAssembly(dir.string());
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("config.json"), std::string::npos) << e.what();
    EXPECT_NE(e.json_path().find("final_state"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cairn

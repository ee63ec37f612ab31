#pragma once
// Paths for tests: the source tree, the shared data folder, the CLI binary.
#include <filesystem>
#include <string>

namespace cairn::testing {

inline std::string SourcePath(const std::string& rel) {
  return std::string(CAIRN_SOURCE_DIR) + "/" + rel;
}
inline std::string ExamplePath(const std::string& name) { return SourcePath("examples/" + name); }
/// The shared data folder, or "" when it is absent (tests then GTEST_SKIP()
/// with a message saying so).
inline std::string SharedDir() {
  const std::string dir = CAIRN_SHARED_DIR;
  return std::filesystem::is_directory(dir) ? dir : std::string();
}
inline std::string CliPath() { return CAIRN_CLI_PATH; }

}  // namespace cairn::testing

#pragma once
// Runs the real `cairn` binary as a user does and captures what it says.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_paths.h"

namespace cairn::testing {

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

inline std::string Slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Writes `text` to a file of that name in the temporary folder; its path.
inline std::string TempFile(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

/// A fresh, absent folder path in the temporary folder, unique to this
/// process (the command under test creates it).
inline std::string TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   (name + "_" + std::to_string(::getpid()) + "_" + std::to_string(std::rand()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

/// A shell command line (e.g. `mpirun ... cairn ...`), its output captured.
inline CliRun RunCommand(const std::string& command) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(std::rand());
  const std::string out = (dir / ("cairn_out_" + tag)).string();
  const std::string err = (dir / ("cairn_err_" + tag)).string();
  const std::string cmd = command + " >" + out + " 2>" + err;
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = Slurp(out);
  r.err = Slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

inline CliRun Cairn(const std::string& args) {
  std::string command = CliPath();  // appended, not `a + " " + b`: GCC 12's
  command += ' ';                   // -Warray-bounds false positive (bug 105329)
  command += args;
  return RunCommand(command);
}

}  // namespace cairn::testing

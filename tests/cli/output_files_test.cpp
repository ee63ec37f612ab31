// OutputFiles (src/cli/output_files.h): the files of a command all or none,
// never over a device or a folder, links followed, no temporary left.
#include "cli/output_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "cairn/core/error.h"

namespace cairn::cli {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A fresh folder of this test's own.
fs::path Folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Nothing but `expected` in `dir` (no temporary files).
void ExpectOnly(const fs::path& dir, std::set<std::string> expected) {
  std::set<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) found.insert(e.path().filename().string());
  EXPECT_EQ(found, expected);
}

TEST(OutputFiles, WritesEveryFileOnCommit) {
  const fs::path dir = Folder("of_commit");
  OutputFiles files;
  files.Add((dir / "a.txt").string(), "alpha", "--a");
  files.Add((dir / "b.txt").string(), "beta", "--b");
  ExpectOnly(dir, {});  // nothing before the commit
  files.Commit();
  EXPECT_EQ(Read(dir / "a.txt"), "alpha");
  EXPECT_EQ(Read(dir / "b.txt"), "beta");
  ExpectOnly(dir, {"a.txt", "b.txt"});
  fs::remove_all(dir);
}

TEST(OutputFiles, ADeviceOrAFolderIsRefusedBeforeAnythingIsWritten) {
  const fs::path dir = Folder("of_device");
  OutputFiles files;
  files.Add((dir / "a.txt").string(), "alpha", "--a");
  EXPECT_THROW(files.Add("/dev/null", "x", "--timeline"), InputError);
  EXPECT_THROW(files.Add(dir.string(), "x", "--dot"), InputError);
  ExpectOnly(dir, {});
  fs::remove_all(dir);
}

TEST(OutputFiles, ALinkIsFollowedAndKept) {
  const fs::path dir = Folder("of_link");
  fs::create_symlink(dir / "real.csv", dir / "link.csv");  // dangling until written
  OutputFiles files;
  files.Add((dir / "link.csv").string(), "data", "--timeline");
  files.Commit();
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "link.csv")));
  EXPECT_EQ(Read(dir / "real.csv"), "data");
  fs::remove_all(dir);
}

TEST(OutputFiles, AFailedWriteLeavesNoFileAndNoTemporary) {
  const fs::path dir = Folder("of_fail");
  {
    std::ofstream(dir / "old.txt") << "before";
    OutputFiles files;
    files.Add((dir / "old.txt").string(), "after", "--a");
    files.Add((dir / "missing" / "b.txt").string(), "beta", "--b");  // its folder does not exist
    try {
      files.Commit();
      ADD_FAILURE() << "the commit should have failed";
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), "--b");
    }
  }
  EXPECT_EQ(Read(dir / "old.txt"), "before");  // untouched
  ExpectOnly(dir, {"old.txt"});
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cairn::cli

// Opening user-given files (CheckInputFile, ReadInputFile): what is not a
// regular file is refused at once, saying what it is (a FIFO without a writer
// must not block); every failure of the file system names the file; what is
// read is bounded; sizes as --max-input-size takes them.
#include "cairn/io/input_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cairn/core/error.h"

namespace cairn {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A fresh folder of this test process, removed at the end of the test.
class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cairn_input_file_" + std::to_string(::getpid()) + "_" + std::to_string(std::rand()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& text) const {
    std::ofstream(Path(name), std::ios::binary) << text;
    return Path(name);
  }
  fs::path dir_;
};

// The InputError of ReadInputFile(path, max_size), checked to name the file.
std::string ReadError(const std::string& path, std::uint64_t max_size = kDefaultMaxInputSize) {
  try {
    ReadInputFile(path, max_size);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    return e.message();
  }
  ADD_FAILURE() << "no error reading " << path;
  return "";
}

TEST_F(InputFile, ReadsARegularFileWhole) {
  const std::string text("a\0b\nc", 5);
  const std::string path = Write("f.json", text);
  EXPECT_EQ(ReadInputFile(path), text);
  EXPECT_EQ(CheckInputFile(path), 5u);
  EXPECT_EQ(ReadInputFile(Write("empty", "")), "");
}

TEST_F(InputFile, RefusesWhatIsNotARegularFileSayingWhatItIs) {
  fs::create_directories(Path("folder.json"));
  EXPECT_EQ(ReadError(Path("folder.json")), "is a directory, not a file");
  // A FIFO without a writer: refused at once, never waited on.
  ASSERT_EQ(::mkfifo(Path("fifo.json").c_str(), 0600), 0);
  EXPECT_EQ(ReadError(Path("fifo.json")), "is a FIFO (named pipe), not a regular file");
  EXPECT_THAT(ReadError("/dev/zero"), HasSubstr("is a character device, not a regular file"));
  // A socket cannot even be opened: what it is, all the same.
  const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(s, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const std::string socket_path = Path("s.json");
  if (socket_path.size() < sizeof address.sun_path) {
    std::copy(socket_path.begin(), socket_path.end(), address.sun_path);
    ASSERT_EQ(::bind(s, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    EXPECT_EQ(ReadError(socket_path), "is a socket, not a regular file");
  }
  ::close(s);
  // CheckInputFile says the same, naming what the file is for.
  try {
    CheckInputFile(Path("fifo.json"), kDefaultMaxInputSize, "mesh file");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "is a FIFO (named pipe), not a regular file");
  }
}

TEST_F(InputFile, FileSystemFailuresNameTheFile) {
  EXPECT_EQ(ReadError(Path("absent.json")), "cannot open the file: no such file");
  fs::create_symlink("loop.json", Path("loop.json"));
  EXPECT_THAT(ReadError(Path("loop.json")), HasSubstr("a loop of symbolic links"));
  EXPECT_THAT(ReadError(Path(std::string(300, 'a') + ".json")),
              HasSubstr("the file name is too long"));
  EXPECT_THAT(ReadError(Write("plain", "x") + "/below.json"), HasSubstr("no such file"));
  EXPECT_THAT(ReadError(""), HasSubstr("name is empty"));
  // Permissions (root reads everything).
  if (::geteuid() != 0) {
    const std::string locked = Write("locked.json", "{}");
    fs::permissions(locked, fs::perms::none);
    EXPECT_EQ(ReadError(locked), "cannot open the file: permission denied");
  }
}

TEST_F(InputFile, ReadsNoMoreThanTheMaximumSize) {
  const std::string path = Write("big.json", std::string(100, ' '));
  EXPECT_EQ(ReadInputFile(path, 100).size(), 100u);
  const std::string why = ReadError(path, 99);
  EXPECT_THAT(why, HasSubstr("the file is 100 bytes, more than the maximum input size 99 bytes"));
  EXPECT_THAT(why, HasSubstr("--max-input-size"));
  EXPECT_THROW(CheckInputFile(path, 10), InputError);
}

TEST(ByteSize, ParsesSuffixesOfPowersOf1024) {
  EXPECT_EQ(ParseByteSize("1"), 1u);
  EXPECT_EQ(ParseByteSize("1073741824"), kDefaultMaxInputSize);
  EXPECT_EQ(ParseByteSize("1G"), kDefaultMaxInputSize);
  EXPECT_EQ(ParseByteSize("1GiB"), kDefaultMaxInputSize);
  EXPECT_EQ(ParseByteSize("512k"), 512u * 1024);
  EXPECT_EQ(ParseByteSize("3M"), 3u << 20);
  EXPECT_EQ(ParseByteSize("8589934592G"), std::uint64_t{1} << 63);
  for (const char* bad :
       {"", "0", "0K", "-1", "1.5G", "1T", "G", "12 M", "99999999999999999999", "17179869184G"})
    EXPECT_FALSE(ParseByteSize(bad).has_value()) << bad;
  EXPECT_EQ(DescribeByteSize(kDefaultMaxInputSize), "1073741824 bytes (1 GiB)");
  EXPECT_EQ(DescribeByteSize(1), "1 byte");
}

TEST_F(InputFile, IsDirectoryNeverThrows) {
  EXPECT_TRUE(IsDirectory(dir_.string()));
  EXPECT_FALSE(IsDirectory(Write("f", "")));
  fs::create_symlink("loop", Path("loop"));
  EXPECT_FALSE(IsDirectory(Path("loop")));
  EXPECT_FALSE(IsDirectory(std::string(5000, 'a')));
  EXPECT_FALSE(IsDirectory(""));
}

}  // namespace
}  // namespace cairn

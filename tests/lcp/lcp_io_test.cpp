// Tests of the LCP file readers (plain and Siconos .dat formats).
#include "cairn/lcp/lcp_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn {
namespace {

// Writes `text` to a file in the test's temporary directory.
std::string WriteTemp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(LcpIo, PlainFormatIsRowMajorWithComments) {
  const auto path = WriteTemp("p.txt", "# a comment\n2 # n\n1 2\n3 4\n-1 -2\n");
  const LcpProblem p = ReadLcpPlain(path);
  ASSERT_EQ(p.M.rows(), 2);
  EXPECT_EQ(p.M(0, 1), 2.0);
  EXPECT_EQ(p.M(1, 0), 3.0);
  EXPECT_EQ(p.q[1], -2.0);
  EXPECT_EQ(ReadLcpFile(path).M, p.M);
}

TEST(LcpIo, SiconosDenseIsColumnMajor) {
  // lcp_CPS_2 of the Siconos suite: the printed lines are columns of M.
  const auto path = WriteTemp(
      "cps2.dat", "3\n0\n3\n3\n3\t3\n0 2 -1\n-1 0 1\n2 -2 0\n-3 6 -1\n\nExample 4.4.7 CPS 2009\n");
  const LcpProblem p = ReadLcpFile(path);
  MatrixX expected(3, 3);
  expected << 0, -1, 2, 2, 0, -2, -1, 1, 0;
  EXPECT_EQ(p.M, expected);
  EXPECT_EQ(p.q, (VectorX(3) << -3, 6, -1).finished());
}

TEST(LcpIo, SiconosSparseBlock) {
  // lcp_ortiz_block: 2 x 2 blocks of size 2, blocks stored column-major.
  const auto path = WriteTemp("ortiz.dat",
                              "4\n1\n4\n4\n4\n2\n2\n2 4\n2 4\n3\n4\n0 2 4\n0 1 0 1\n"
                              "0\n3\n-1\n1\n2\n1\n0\n1\n-1\n1\n2\n0\n0\n1\n0\n3\n3\n1\n-1\n2\n"
                              "-2 1 -1 1\n");
  const LcpProblem p = ReadLcpSiconos(path);
  MatrixX expected(4, 4);
  expected << 3, 1, 0, -1, -1, 2, 1, 1, 0, 1, 3, -1, 0, 0, 1, 2;
  EXPECT_EQ(p.M, expected);
  EXPECT_EQ(p.q, (VectorX(4) << -2, 1, -1, 1).finished());
}

TEST(LcpIo, MalformedFilesThrowInputError) {
  EXPECT_THROW(ReadLcpPlain("/nonexistent/file.txt"), InputError);
  EXPECT_THROW(ReadLcpPlain(WriteTemp("short.txt", "2\n1 2\n3\n")), InputError);
  EXPECT_THROW(ReadLcpPlain(WriteTemp("word.txt", "1\nx\n1\n")), InputError);
  EXPECT_THROW(ReadLcpPlain(WriteTemp("neg.txt", "-1\n")), InputError);
  EXPECT_THROW(ReadLcpPlain(WriteTemp("extra.txt", "1\n1\n1\n5\n")), InputError);
  EXPECT_THROW(ReadLcpPlain(WriteTemp("nan.txt", "1\nnan\n1\n")), InputError);
  EXPECT_THROW(ReadLcpSiconos(WriteTemp("csc.dat", "1\n2\n1\n1\n")), InputError);
  EXPECT_THROW(ReadLcpSiconos(WriteTemp("size.dat", "2\n0\n3\n3\n")), InputError);
  try {
    ReadLcpPlain(WriteTemp("where.txt", "2\n1 2\n3 oops\n0 0\n"));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find("where.txt"), std::string::npos);
    EXPECT_NE(e.message().find("oops"), std::string::npos);
  }
}

// Every Siconos .dat of the shared suite reads to the same problem as its
// plain twin (dense files transposed, sparse-block files densified).
TEST(LcpIo, SharedSiconosFilesMatchTheirPlainTwins) {
  if (testing::SharedDir().empty()) {
    GTEST_SKIP() << "shared/lcp_data not found: skipping the .dat/plain comparison";
  }
  const std::string dir = testing::SharedDir() + "/lcp_data";
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/siconos")) {
    const std::string stem = entry.path().stem().string();
    const LcpProblem dat = ReadLcpFile(entry.path().string());
    const LcpProblem plain = ReadLcpFile(dir + "/plain/" + stem + ".txt");
    EXPECT_EQ(dat.M, plain.M) << stem;
    EXPECT_EQ(dat.q, plain.q) << stem;
    ++compared;
  }
  EXPECT_EQ(compared, 20);
}

}  // namespace
}  // namespace cairn

// Readers for LCP problem files: the plain row-major format and Siconos'
// LinearComplementarityProblem `.dat` serialisation (dense column-major, or
// sparse-block). Both are whitespace-separated token streams; every malformed
// input throws InputError naming the file and what is wrong.

#include "cairn/lcp/lcp_io.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "cairn/core/error.h"

namespace cairn {

namespace {

// A whitespace token stream over a file, with typed reads that throw
// InputError on a missing or malformed token.
class TokenReader {
 public:
  TokenReader(const std::string& path, bool strip_comments) : path_(path) {
    std::ifstream in(path);
    if (!in) throw InputError(path, "", "cannot open the file");
    std::ostringstream text;
    std::string line;
    while (std::getline(in, line)) {
      // '#' starts a comment that runs to the end of the line.
      if (strip_comments) {
        const auto hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
      }
      text << line << '\n';
    }
    std::istringstream tokens(text.str());
    std::string token;
    while (tokens >> token) tokens_.push_back(token);
  }

  bool AtEnd() const { return next_ >= tokens_.size(); }

  // The next token as a finite double.
  double Double(const std::string& what) {
    const std::string& token = Next(what);
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
      Fail("expected a finite number for " + what + ", got '" + token + "'");
    }
    return value;
  }

  // The next token as an integer in [lo, hi].
  long Int(const std::string& what, long lo, long hi) {
    const std::string& token = Next(what);
    errno = 0;
    char* end = nullptr;
    const long value = std::strtol(token.c_str(), &end, 10);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE) {
      Fail("expected an integer for " + what + ", got '" + token + "'");
    }
    if (value < lo || value > hi) {
      Fail(what + " = " + token + " is out of range [" + std::to_string(lo) + ", " +
           std::to_string(hi) + "]");
    }
    return value;
  }

  [[noreturn]] void Fail(const std::string& message) const { throw InputError(path_, "", message); }

 private:
  const std::string& Next(const std::string& what) {
    if (AtEnd()) Fail("unexpected end of file while reading " + what);
    return tokens_[next_++];
  }

  std::string path_;
  std::vector<std::string> tokens_;
  size_t next_ = 0;
};

// A sanity bound on n so a corrupt header cannot request a huge allocation.
constexpr long kMaxSize = 100000;

// Reads n values of q.
VectorX ReadVector(TokenReader& in, Eigen::Index n, const std::string& name) {
  VectorX v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = in.Double(name + "[" + std::to_string(i) + "]");
  return v;
}

// Siconos NM_write_in_file, storage 0: "size0 size1" then the column-major array.
MatrixX ReadSiconosDense(TokenReader& in, Eigen::Index rows, Eigen::Index cols) {
  if (in.Int("dense size0", 0, kMaxSize) != rows || in.Int("dense size1", 0, kMaxSize) != cols) {
    in.Fail("the dense matrix header repeats different sizes");
  }
  MatrixX M(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) {
      M(i, j) = in.Double("M(" + std::to_string(i) + "," + std::to_string(j) + ")");
    }
  }
  return M;
}

// Siconos NM_write_in_file, storage 1 (SparseBlockStructuredMatrix): block
// counts, cumulative row/column block sizes, the row pointers index1 and the
// block column indices index2, then each block (its number, then its entries
// column-major).
MatrixX ReadSiconosSparseBlock(TokenReader& in, Eigen::Index rows, Eigen::Index cols) {
  const long nbblocks = in.Int("nbblocks", 0, kMaxSize * kMaxSize);
  const long row_blocks = in.Int("blocknumber0", 0, kMaxSize);
  const long col_blocks = in.Int("blocknumber1", 0, kMaxSize);
  std::vector<long> row_end(static_cast<size_t>(row_blocks));
  std::vector<long> col_end(static_cast<size_t>(col_blocks));
  for (auto& e : row_end) e = in.Int("blocksize0", 0, rows);
  for (auto& e : col_end) e = in.Int("blocksize1", 0, cols);
  // Cumulative sizes must increase and end at the matrix size.
  auto check_cumulative = [&](const std::vector<long>& ends, long total, const char* what) {
    long prev = 0;
    for (long e : ends) {
      if (e <= prev) in.Fail(std::string(what) + " is not strictly increasing");
      prev = e;
    }
    if (prev != total) in.Fail(std::string(what) + " does not end at the matrix size");
  };
  check_cumulative(row_end, rows, "blocksize0");
  check_cumulative(col_end, cols, "blocksize1");
  const long filled1 = in.Int("filled1", 0, row_blocks + 1);
  const long filled2 = in.Int("filled2", 0, nbblocks);
  if (filled1 != row_blocks + 1) in.Fail("filled1 must be blocknumber0 + 1");
  if (filled2 != nbblocks) in.Fail("filled2 must equal nbblocks");
  std::vector<long> index1(static_cast<size_t>(filled1));
  std::vector<long> index2(static_cast<size_t>(filled2));
  for (auto& e : index1) e = in.Int("index1_data", 0, nbblocks);
  for (auto& e : index2) e = in.Int("index2_data", 0, col_blocks - 1);
  if (index1.front() != 0 || index1.back() != nbblocks) {
    in.Fail("index1_data must run from 0 to nbblocks");
  }
  MatrixX M = MatrixX::Zero(rows, cols);
  for (long bi = 0; bi < row_blocks; ++bi) {
    const long r0 = bi == 0 ? 0 : row_end[static_cast<size_t>(bi - 1)];
    const long nr = row_end[static_cast<size_t>(bi)] - r0;
    const long k_begin = index1[static_cast<size_t>(bi)];
    const long k_end = index1[static_cast<size_t>(bi + 1)];
    if (k_end < k_begin) in.Fail("index1_data is not nondecreasing");
    for (long k = k_begin; k < k_end; ++k) {
      if (in.Int("block number", 0, nbblocks - 1) != k) in.Fail("blocks are out of order");
      const long bj = index2[static_cast<size_t>(k)];
      const long c0 = bj == 0 ? 0 : col_end[static_cast<size_t>(bj - 1)];
      const long nc = col_end[static_cast<size_t>(bj)] - c0;
      for (long j = 0; j < nc; ++j) {
        for (long i = 0; i < nr; ++i) {
          M(r0 + i, c0 + j) = in.Double("block " + std::to_string(k) + " entry");
        }
      }
    }
  }
  return M;
}

}  // namespace

LcpProblem ReadLcpPlain(const std::string& path) {
  TokenReader in(path, /*strip_comments=*/true);
  const Eigen::Index n = in.Int("n", 0, kMaxSize);
  LcpProblem problem;
  problem.M.resize(n, n);
  // Row-major rows of M.
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      problem.M(i, j) = in.Double("M(" + std::to_string(i) + "," + std::to_string(j) + ")");
    }
  }
  problem.q = ReadVector(in, n, "q");
  if (!in.AtEnd()) in.Fail("unexpected data after q");
  return problem;
}

LcpProblem ReadLcpSiconos(const std::string& path) {
  TokenReader in(path, /*strip_comments=*/false);
  const Eigen::Index n = in.Int("n", 0, kMaxSize);
  const long storage = in.Int("storageType", 0, 2);
  const Eigen::Index rows = in.Int("size0", 0, kMaxSize);
  const Eigen::Index cols = in.Int("size1", 0, kMaxSize);
  if (rows != n || cols != n) in.Fail("M is not n x n");
  LcpProblem problem;
  if (storage == 0) {
    problem.M = ReadSiconosDense(in, rows, cols);
  } else if (storage == 1) {
    problem.M = ReadSiconosSparseBlock(in, rows, cols);
  } else {
    in.Fail("storageType 2 (sparse) is not supported");
  }
  // Anything after q is a free-text remark and is ignored.
  problem.q = ReadVector(in, n, "q");
  return problem;
}

LcpProblem ReadLcpFile(const std::string& path) {
  const bool dat = path.size() >= 4 && path.compare(path.size() - 4, 4, ".dat") == 0;
  return dat ? ReadLcpSiconos(path) : ReadLcpPlain(path);
}

}  // namespace cairn

// block_lu.h: the block-LU update solves C x = b for the basis the exchanges
// leave, as a fresh LU of that C does, through any sequence of rows and
// columns joining and leaving (re-joining included), and refuses a singular C.
#include "lcp/block_lu.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace cairn::lcp_internal {
namespace {

class DenseEntries final : public Entries {
 public:
  explicit DenseEntries(MatrixX a) : a_(std::move(a)) {}
  int num_rows() const override { return static_cast<int>(a_.rows()); }
  int num_cols() const override { return static_cast<int>(a_.cols()); }
  void Column(int key, VectorX* out) const override { *out = a_.col(key); }
  void Row(int row, VectorX* out) const override { *out = a_.row(row).transpose(); }
  const MatrixX& a() const { return a_; }

 private:
  MatrixX a_;
};

MatrixX Reduced(const MatrixX& a, const std::vector<int>& rows, const std::vector<int>& cols) {
  MatrixX c(rows.size(), cols.size());
  for (size_t s = 0; s < rows.size(); ++s)
    for (size_t p = 0; p < cols.size(); ++p) c(s, p) = a(rows[s], cols[p]);
  return c;
}

// The solve's error against a fresh LU, relative to the solution.
double SolveError(BlockLu& lu, const DenseEntries& e, const std::vector<int>& rows,
                  const std::vector<int>& cols, std::mt19937& rng) {
  std::normal_distribution<double> g;
  VectorX b(rows.size());
  for (auto& v : b) v = g(rng);
  VectorX x;
  lu.Solve(rows, cols, b, &x);
  const VectorX ref = Reduced(e.a(), rows, cols).partialPivLu().solve(b);
  return (x - ref).cwiseAbs().maxCoeff() / std::max(1.0, ref.cwiseAbs().maxCoeff());
}

// Random exchanges of the four kinds a Lemke pivot makes (grow, replace a
// column, replace a row, shrink), 300 of them from a 20 × 20 start, the
// border left to grow to 24 before a refactor: every solve matches.
TEST(BlockLu, SolvesLikeAFreshLuThroughRandomExchanges) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  const int n = 60;
  MatrixX a(n, n + 1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= n; ++j) a(i, j) = g(rng);
  const DenseEntries e(a);
  BlockLu lu(e);
  std::vector<int> rows, cols;
  for (int i = 0; i < 20; ++i) rows.push_back(i), cols.push_back(i + 3);
  ASSERT_TRUE(lu.Factor(rows, cols));
  const auto outside = [](const std::vector<int>& in, int size, std::mt19937& r) {
    std::vector<int> out;
    for (int i = 0; i < size; ++i)
      if (std::find(in.begin(), in.end(), i) == in.end()) out.push_back(i);
    return out[std::uniform_int_distribution<size_t>(0, out.size() - 1)(r)];
  };
  int refactors = 0;
  for (int step = 0; step < 300; ++step) {
    const int kind = std::uniform_int_distribution<int>(0, 3)(rng);
    const size_t k = rows.size();
    const auto pick = [&] { return std::uniform_int_distribution<size_t>(0, k - 1)(rng); };
    if ((kind == 0 && k < 40) || k < 5) {  // grow
      const int r = outside(rows, n, rng), c = outside(cols, n + 1, rng);
      rows.push_back(r), cols.push_back(c);
      lu.AddColumn(c), lu.AddRow(r);
    } else if (kind == 1) {  // replace a column
      const size_t p = pick();
      const int c = outside(cols, n + 1, rng);
      lu.RemoveColumn(cols[p]), lu.AddColumn(c);
      cols[p] = c;
    } else if (kind == 2) {  // replace a row
      const size_t s = pick();
      const int r = outside(rows, n, rng);
      lu.RemoveRow(rows[s]), lu.AddRow(r);
      rows[s] = r;
    } else {  // shrink (the last position moves into the holes)
      const size_t s = pick(), p = pick();
      lu.RemoveRow(rows[s]), lu.RemoveColumn(cols[p]);
      rows[s] = rows.back(), rows.pop_back();
      cols[p] = cols.back(), cols.pop_back();
    }
    ASSERT_TRUE(lu.Finish()) << "step " << step;
    ASSERT_LT(SolveError(lu, e, rows, cols, rng), 1e-8)
        << "step " << step << ", border " << lu.border();
    if (lu.border() > 24) {
      ASSERT_TRUE(lu.Factor(rows, cols));
      ++refactors;
    }
  }
  EXPECT_GT(refactors, 0);  // the border did grow past 24: both regimes were checked
}

// A large sparse A (a band of width 3 and a few entries besides, its
// diagonal dominant): C₀ from order 150 is factored sparse, and through 200
// random exchanges (a column or a row replaced) with refactors every 32,
// every solve matches a fresh dense LU; a C₀ with a repeated column is
// refused as the dense one is.
TEST(BlockLu, ALargeSparseBasisIsFactoredSparseAndSolvesTheSame) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  std::uniform_int_distribution<int> any(0, 299);
  const int n = 300;
  MatrixX a = MatrixX::Zero(n, n + 1);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 20.0 + g(rng);
    for (int d : {-1, 1, 3})
      if (i + d >= 0 && i + d < n) a(i, i + d) = g(rng);
    a(i, any(rng)) += g(rng);
  }
  for (int i = 0; i < n; ++i) a(i, n) = a(i, 0);  // column n repeats column 0
  const DenseEntries e(a);
  BlockLu lu(e);
  std::vector<int> rows, cols;
  for (int i = 0; i < 150; ++i) rows.push_back(i), cols.push_back(i);
  ASSERT_TRUE(lu.Factor(rows, cols));
  EXPECT_TRUE(lu.sparse());
  const auto outside = [&](const std::vector<int>& in) {
    while (true) {
      const int i = any(rng);
      if (std::find(in.begin(), in.end(), i) == in.end()) return i;
    }
  };
  for (int step = 0; step < 200; ++step) {
    const size_t at = std::uniform_int_distribution<size_t>(0, rows.size() - 1)(rng);
    // Rows and columns the same set: C is a principal submatrix of a
    // diagonally dominant A, so regular.
    if (step % 2 == 0) {
      const int r = outside(rows), v = cols[at];
      const auto row_of_v = std::find(rows.begin(), rows.end(), v);
      lu.RemoveRow(v), lu.RemoveColumn(v);
      lu.AddRow(r), lu.AddColumn(r);
      *row_of_v = r;
      cols[at] = r;
    } else {
      std::swap(rows[at], rows[(at + 1) % rows.size()]);  // positions only: no exchange
    }
    ASSERT_TRUE(lu.Finish()) << "step " << step;
    ASSERT_LT(SolveError(lu, e, rows, cols, rng), 1e-10) << "step " << step;
    if (lu.border() >= 32) {
      ASSERT_TRUE(lu.Factor(rows, cols));
      ASSERT_TRUE(lu.sparse());
    }
  }
  std::vector<int> repeated = cols;
  repeated[1] = n;  // column 0's copy beside it
  repeated[0] = 0;
  EXPECT_FALSE(lu.Factor(rows, repeated));
}

// A column exchanged for a copy of another makes C singular: S says so.
TEST(BlockLu, ASingularExchangeIsRefused) {
  MatrixX a = MatrixX::Identity(4, 5);
  a(0, 4) = 1.0;  // column 4 = column 0
  const DenseEntries e(a);
  BlockLu lu(e);
  ASSERT_TRUE(lu.Factor({0, 1, 2}, {0, 1, 2}));
  lu.RemoveColumn(1);
  lu.AddColumn(4);
  EXPECT_FALSE(lu.Finish());
  EXPECT_FALSE(lu.Factor({0, 1, 2}, {0, 4, 2}));
}

// Refactor when the border costs more than a fresh LU (1.41 k^(3/4)), within
// [16, 64].
TEST(BlockLu, TheBorderBoundBalancesRefactorsAndStaysSmall) {
  EXPECT_EQ(BlockLu::MaxBorder(1), 16);
  EXPECT_NEAR(BlockLu::MaxBorder(40), 1.41 * std::pow(40.0, 0.75), 1.0);
  EXPECT_EQ(BlockLu::MaxBorder(1500), 64);
}

}  // namespace
}  // namespace cairn::lcp_internal

#include "block_lu.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cairn/core/check.h"

namespace cairn::lcp_internal {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// C₀ is factored sparse from this order up when at most this share of its
// entries are nonzero (dimensionless). Below, the dense LU's blocked kernels
// win; the loading LCP's bases have a few entries a column (docs/benchmarks.md,
// "`bench/sequence_bench.sh`, sixth stop").
constexpr int kSparseFromOrder = 128;
constexpr double kSparseDensity = 0.05;

// An LU with partial pivoting is taken as singular when its smallest pivot is
// below order · ε · the largest entry: below the roundoff of the entries.
bool Regular(const Eigen::PartialPivLU<MatrixX>& lu, const MatrixX& a) {
  const int k = static_cast<int>(a.rows());
  if (k == 0) return true;
  const double u_min = lu.matrixLU().diagonal().cwiseAbs().minCoeff();
  return u_min > k * kEps * a.cwiseAbs().maxCoeff() && std::isfinite(u_min);
}

void EraseRow(MatrixX& m, int r) {
  const int rows = static_cast<int>(m.rows()), cols = static_cast<int>(m.cols());
  if (r + 1 < rows) m.middleRows(r, rows - r - 1) = m.bottomRows(rows - r - 1).eval();
  m.conservativeResize(rows - 1, cols);
}

void EraseCol(MatrixX& m, int c) {
  const int rows = static_cast<int>(m.rows()), cols = static_cast<int>(m.cols());
  if (c + 1 < cols) m.middleCols(c, cols - c - 1) = m.rightCols(cols - c - 1).eval();
  m.conservativeResize(rows, cols - 1);
}

}  // namespace

int BlockLu::MaxBorder(int k) {
  // Between refactors the border grows by about one per pivot, and S is
  // factored each time: Σ (2/3) m³ over P pivots ≈ P⁴/6, against (2/3) k³
  // for refactoring C₀. Equal at P = (4 k³)^(1/4) ≈ 1.41 k^(3/4). Capped at
  // kMaxBorder: the error of a solve grows with the border (through W and
  // S), and Lemke's ratio test reads it. Measured on the Jenga tick-20 LCP
  // (n = 3696, k ≈ 1500; docs/benchmarks.md, "Degenerate contact LCPs"):
  // border 8: solved in 8481 pivots, 32: 5426, 64: 4142 (1.4 s), 128: 6226,
  // uncapped (≈ 340): no solution within the pivot limit.
  constexpr int kMinBorder = 16, kMaxBorder = 64;
  const int balance = static_cast<int>(1.41 * std::pow(static_cast<double>(k), 0.75));
  return std::clamp(balance, kMinBorder, kMaxBorder);
}

bool BlockLu::Factor(const std::vector<int>& rows, const std::vector<int>& cols) {
  CAIRN_CHECK(rows.size() == cols.size());
  const int k = static_cast<int>(rows.size());
  rows0_ = rows;
  cols0_ = cols;
  row0_of_.assign(a_.num_rows(), -1);
  col0_of_.assign(a_.num_cols(), -1);
  for (int s = 0; s < k; ++s) row0_of_[rows[s]] = s;
  for (int p = 0; p < k; ++p) col0_of_[cols[p]] = p;
  border_cols_.clear();
  border_rows_.clear();
  w_.clear();
  ut_.clear();
  s_.resize(0, 0);
  sparse0_ = false;
  if (k == 0) return true;
  MatrixX c0(k, k);
  for (int p = 0; p < k; ++p) {
    a_.Column(cols0_[p], &line_);
    for (int s = 0; s < k; ++s) c0(s, p) = line_[rows0_[s]];
  }
  if (k >= kSparseFromOrder && FactorSparse(c0)) return true;
  lu0_.compute(c0);
  return Regular(lu0_, c0);
}

// C₀ by the sparse LU, when it is sparse enough (kSparseDensity) and the
// factors are regular (the same test as the dense LU's, on U's diagonal,
// which SparseLU keeps in the supernodes of L). False: the dense LU decides.
bool BlockLu::FactorSparse(const MatrixX& c0) {
  const int k = static_cast<int>(c0.rows());
  if (static_cast<double>((c0.array() != 0.0).count()) > kSparseDensity * k * k) return false;
  const double largest = c0.cwiseAbs().maxCoeff();
  const Eigen::SparseMatrix<double> sparse = c0.sparseView();
  sparse_lu0_.compute(sparse);
  if (sparse_lu0_.info() != Eigen::Success) return false;
  double u_min = std::numeric_limits<double>::infinity();
  const auto& l = sparse_lu0_.matrixL().m_mapL;
  for (int j = 0; j < k; ++j)
    for (typename std::decay_t<decltype(l)>::InnerIterator it(l, j); it; ++it)
      if (it.index() == j) {
        u_min = std::min(u_min, std::abs(it.value()));
        break;
      }
  if (!(u_min > k * kEps * largest && std::isfinite(u_min))) return false;
  sparse0_ = true;
  return true;
}

VectorX BlockLu::Solve0(const VectorX& b) const {
  if (sparse0_) return sparse_lu0_.solve(b);
  return lu0_.solve(b);
}

void BlockLu::AddColumn(int key) {
  const int p0 = col0_of_[key];
  if (p0 >= 0)  // back in Z₀: drop the constraint that held it at 0
    EraseBorderRow(FindBorderRow(-1 - p0));
  else
    PushBorderColumn(key);
}

void BlockLu::RemoveColumn(int key) {
  const int p0 = col0_of_[key];
  if (p0 >= 0)
    PushBorderRow(-1 - p0);
  else
    EraseBorderColumn(FindBorderColumn(key));
}

void BlockLu::AddRow(int row) {
  const int s0 = row0_of_[row];
  if (s0 >= 0)  // back in R₀: drop the slack that freed its equation
    EraseBorderColumn(FindBorderColumn(-1 - s0));
  else
    PushBorderRow(row);
}

void BlockLu::RemoveRow(int row) {
  const int s0 = row0_of_[row];
  if (s0 >= 0)
    PushBorderColumn(-1 - s0);
  else
    EraseBorderRow(FindBorderRow(row));
}

bool BlockLu::Finish() {
  if (s_.rows() != s_.cols()) return false;
  if (s_.rows() == 0) return true;
  lu_s_.compute(s_);
  return Regular(lu_s_, s_);
}

void BlockLu::PushBorderColumn(int key) {
  const int k0 = static_cast<int>(rows0_.size());
  VectorX v = VectorX::Zero(k0);
  if (key >= 0) {
    a_.Column(key, &line_);
    for (int s = 0; s < k0; ++s) v[s] = line_[rows0_[s]];
  } else {
    v[-1 - key] = 1.0;
  }
  VectorX w = k0 > 0 ? Solve0(v) : VectorX();
  // S(:, new) = D(:, new) − Uᵀ w; D is A(row, key) for an added row and
  // an added column, else 0.
  const int m_rows = static_cast<int>(border_rows_.size());
  s_.conservativeResize(m_rows, s_.cols() + 1);
  for (int r = 0; r < m_rows; ++r) {
    const double d = key >= 0 && border_rows_[r] >= 0 ? line_[border_rows_[r]] : 0.0;
    s_(r, s_.cols() - 1) = d - ut_[r].dot(w);
  }
  border_cols_.push_back(key);
  w_.push_back(std::move(w));
}

void BlockLu::PushBorderRow(int key) {
  const int k0 = static_cast<int>(cols0_.size());
  VectorX u = VectorX::Zero(k0);
  if (key >= 0) {
    a_.Row(key, &line_);
    for (int p = 0; p < k0; ++p) u[p] = line_[cols0_[p]];
  } else {
    u[-1 - key] = 1.0;
  }
  const int m_cols = static_cast<int>(border_cols_.size());
  s_.conservativeResize(s_.rows() + 1, m_cols);
  for (int c = 0; c < m_cols; ++c) {
    const double d = key >= 0 && border_cols_[c] >= 0 ? line_[border_cols_[c]] : 0.0;
    s_(s_.rows() - 1, c) = d - u.dot(w_[c]);
  }
  border_rows_.push_back(key);
  ut_.push_back(std::move(u));
}

void BlockLu::EraseBorderColumn(int index) {
  CAIRN_CHECK(index >= 0);
  EraseCol(s_, index);
  border_cols_.erase(border_cols_.begin() + index);
  w_.erase(w_.begin() + index);
}

void BlockLu::EraseBorderRow(int index) {
  CAIRN_CHECK(index >= 0);
  EraseRow(s_, index);
  border_rows_.erase(border_rows_.begin() + index);
  ut_.erase(ut_.begin() + index);
}

int BlockLu::FindBorderColumn(int key) const {
  const auto it = std::find(border_cols_.begin(), border_cols_.end(), key);
  return it == border_cols_.end() ? -1 : static_cast<int>(it - border_cols_.begin());
}

int BlockLu::FindBorderRow(int key) const {
  const auto it = std::find(border_rows_.begin(), border_rows_.end(), key);
  return it == border_rows_.end() ? -1 : static_cast<int>(it - border_rows_.begin());
}

void BlockLu::Solve(const std::vector<int>& rows, const std::vector<int>& cols, const VectorX& b,
                    VectorX* x) {
  const int k = static_cast<int>(rows.size()), k0 = static_cast<int>(rows0_.size());
  const int m = border();
  row_at_.resize(a_.num_rows(), -1);
  border_col_of_.resize(a_.num_cols(), -1);
  for (int s = 0; s < k; ++s) row_at_[rows[s]] = s;
  // The right-hand sides: b on the rows of R₀ still in R (0 on those that
  // left: their slack absorbs the equation), on the added rows, and 0 on
  // the constraints of the columns that left.
  b0_.resize(k0);
  for (int s0 = 0; s0 < k0; ++s0) {
    const int at = row_at_[rows0_[s0]];
    b0_[s0] = at >= 0 ? b[at] : 0.0;
  }
  VectorX xh = k0 > 0 ? Solve0(b0_) : VectorX();
  y_.resize(m);
  if (m > 0) {
    c_.resize(m);
    for (int r = 0; r < m; ++r)
      c_[r] = (border_rows_[r] >= 0 ? b[row_at_[border_rows_[r]]] : 0.0) - ut_[r].dot(xh);
    y_ = lu_s_.solve(c_);
    for (int j = 0; j < m; ++j) xh -= y_[j] * w_[j];
  }
  for (int s = 0; s < k; ++s) row_at_[rows[s]] = -1;
  for (int j = 0; j < m; ++j)
    if (border_cols_[j] >= 0) border_col_of_[border_cols_[j]] = j;
  x->resize(k);
  for (int p = 0; p < k; ++p) {
    const int p0 = col0_of_[cols[p]];
    (*x)[p] = p0 >= 0 ? xh[p0] : y_[border_col_of_[cols[p]]];
  }
  for (int j = 0; j < m; ++j)
    if (border_cols_[j] >= 0) border_col_of_[border_cols_[j]] = -1;
}

}  // namespace cairn::lcp_internal

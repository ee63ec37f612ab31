// Lemke's method on a factored LCP matrix M = G W Gᵀ + K (see factored_lcp.h).
//
// Notation. The system is w − M z − d z₀ = q with covering vector d. A basis
// of Lemke's path splits the indices i into
//   kW    w_i basic (z_i = 0),
//   kZ    z_i basic (w_i = 0),
//   kNone both nonbasic: the one index whose complement enters next
// (and z₀ basic or not). The rows R = {i : w_i nonbasic} and the basic
// "columns" Z = {basic z_j} ∪ {z₀ if basic} have equal size k, and the basic
// values solve the reduced system
//
//     C x = −q_R,   C = [M(R, Z) | d_R]   (k × k),
//
// while every basic w is w_i = q_i + M(i, Z) x (+ d_i z₀). C is kept as an
// updated block-LU factorisation (block_lu.h: the LU of C₀, the basis at the
// last refactor, and the Schur complement of the rows and columns exchanged
// since), never as an inverse, with the values x and w.
//
// Entering variable at level t. For z_c or z₀ with column a of [M | d]:
// x(t) = x − t C⁻¹ a_R, w(t) = w + t (a − M(:, Z) C⁻¹ a_R). For w_c, c at
// position s of R: x(t) = x + t C⁻¹ e_s, w(t) = w + t M(:, Z) C⁻¹ e_s. In
// both, Δ (the rate of x) and ω (the rate of w) give the ratio test; the
// pivot changes C by one row, one column, or both, each a border row or
// column of the block-LU (one solve with C₀ and O(k m) each, m the border):
//   z enters, w_i leaves   C grows by row i and column a
//   z enters, z_l leaves   column of z_l replaced by a
//   w_c enters, w_i leaves row c replaced by row i
//   w_c enters, z_l leaves row c and column z_l removed
// Every kRevalueEvery pivots the values are recomputed by a solve with q;
// the tight rows' residual |q_R + C x| then measures the drift, and C₀ is
// refactored from the data when that exceeds a tenth of the tie-breaking
// perturbation or k/4 pivots have passed since the last factorisation (k the
// basis order), when the border outgrows BlockLu::MaxBorder(k), and after a
// zero pivot element, before that pivot is retried once.
//
// Ratio test: Harris's two passes with the pivot tolerance as the value
// slack: of the candidates tied within roundoff, the largest pivot element
// leaves (see Follow).
//
// Scale. The data are divided by s = max(|q|∞, M's magnitude bound): z is
// unchanged, w and z₀ scale by 1/s, so the tolerances are relative.

#include "cairn/lcp/factored_lcp.h"

#include <Eigen/LU>  // IWYU pragma: keep
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>

#include "block_lu.h"
#include "cairn/core/check.h"
#include "perturbation.h"

namespace cairn {

FactoredLcpMatrix::FactoredLcpMatrix(const SparseMatrixX& G, const SparseMatrixX& W,
                                     const SparseMatrixX& K)
    : G_(G), K_(K) {
  const Eigen::Index n = G.rows(), d = G.cols();
  CAIRN_THROW_UNLESS(W.rows() == d && W.cols() == d && K.rows() == n && K.cols() == n,
                     "FactoredLcpMatrix: G is " << n << "x" << d << ", W " << W.rows() << "x"
                                                << W.cols() << ", K " << K.rows() << "x"
                                                << K.cols());
  const auto finite = [](const SparseMatrixX& A) {
    for (Eigen::Index i = 0; i < A.nonZeros(); ++i)
      if (!std::isfinite(A.valuePtr()[i])) return false;
    return true;
  };
  CAIRN_THROW_UNLESS(finite(G) && finite(W) && finite(K),
                     "FactoredLcpMatrix: a NaN or infinite entry");
  G_.makeCompressed();
  K_.makeCompressed();
  Y_ = (W * G.transpose()).pruned();
  Kt_ = K.transpose();
  // M_ii = G_i W G_iᵀ + K_ii bounds |(G W Gᵀ)_ij| (W PSD). Row j of G
  // against column j of Y, both sorted by their inner index (G by rows: a
  // scan of G's whole column per entry of Y costs O(n · nnz(column)), 10 ms
  // on a 3744-variable LCP); the terms are added in the same order as before.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Gr = G_;
  double m = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    double mjj = 0;
    Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator g(Gr, j);
    for (SparseMatrixX::InnerIterator y(Y_, j); y; ++y) {
      while (g && g.col() < y.row()) ++g;
      if (g && g.col() == y.row()) mjj += g.value() * y.value();
    }
    m = std::max(m, std::abs(mjj));
  }
  for (Eigen::Index i = 0; i < K_.nonZeros(); ++i) m = std::max(m, std::abs(K_.valuePtr()[i]));
  magnitude_ = m;
}

void FactoredLcpMatrix::Multiply(const VectorX& z, VectorX* out) const {
  const VectorX u = Y_ * z;
  *out = G_ * u;
  *out += K_ * z;
}

void FactoredLcpMatrix::Column(int j, VectorX* out) const {
  out->setZero(size());
  for (SparseMatrixX::InnerIterator y(Y_, j); y; ++y)
    for (SparseMatrixX::InnerIterator g(G_, y.row()); g; ++g)
      (*out)[g.row()] += g.value() * y.value();
  for (SparseMatrixX::InnerIterator k(K_, j); k; ++k) (*out)[k.row()] += k.value();
}

void FactoredLcpMatrix::Row(int i, VectorX* out) const {
  // (G W Gᵀ)(i, :) = (G W Gᵀ)(:, i)ᵀ since W is symmetric.
  out->setZero(size());
  for (SparseMatrixX::InnerIterator y(Y_, i); y; ++y)
    for (SparseMatrixX::InnerIterator g(G_, y.row()); g; ++g)
      (*out)[g.row()] += g.value() * y.value();
  for (SparseMatrixX::InnerIterator k(Kt_, i); k; ++k) (*out)[k.row()] += k.value();
}

void FactoredLcpMatrix::AddColumns(const std::vector<int>& cols, const double* coef, VectorX* out,
                                   VectorX* u) const {
  u->setZero(inner_size());
  for (size_t p = 0; p < cols.size(); ++p) {
    const double c = coef[p];
    if (c == 0.0) continue;
    for (SparseMatrixX::InnerIterator y(Y_, cols[p]); y; ++y) (*u)[y.row()] += c * y.value();
    for (SparseMatrixX::InnerIterator k(K_, cols[p]); k; ++k) (*out)[k.row()] += c * k.value();
  }
  out->noalias() += G_ * (*u);
}

MatrixX FactoredLcpMatrix::ToDense() const {
  MatrixX M = MatrixX(G_ * Y_);
  M += MatrixX(K_);
  return M;
}

double LcpResidual(const FactoredLcpMatrix& M, const VectorX& q, const VectorX& z) {
  CAIRN_THROW_UNLESS(z.size() == M.size() && q.size() == M.size(),
                     "LcpResidual: sizes " << M.size() << ", " << q.size() << ", " << z.size());
  VectorX w;
  M.Multiply(z, &w);
  w += q;
  return NaturalMapResidual(z, w);
}

bool IsLcpSolution(const FactoredLcpMatrix& M, const VectorX& q, const VectorX& z, double tol) {
  if (z.size() != M.size() || q.size() != M.size()) return false;
  VectorX w;
  M.Multiply(z, &w);
  w += q;
  return IsComplementarySolution(z, w, tol);
}

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Pivots between recomputations of the values from H (O(k² + nnz)), at
// which H is also checked for drift.
constexpr int kRevalueEvery = 25;
// C₀ is refactored (O(k³)) when the tight rows' residual exceeds this
// fraction of the perturbation δ: drift that large could reorder the ties the
// perturbation breaks.
constexpr double kDriftFraction = 0.1;
// ... when the block-LU border outgrows BlockLu::MaxBorder(k), and at the
// latest after kRefactorPerOrder · k pivots (k the basis order). The last
// rule was measured with the explicit inverse this solver used before the
// block-LU update (on the 9 COMPAS shelf, snake, bridge and cube-curve
// components, docs/benchmarks.md, "Degenerate contact LCPs": refactoring on
// drift alone solved 4, every k pivots 6, every k/4 pivots 7); it is kept as
// a bound on the work between fresh factorisations.
constexpr double kRefactorPerOrder = 0.25;

enum class Role : unsigned char { kW, kZ, kNone };

// How one attempt along Lemke's path ended.
enum class PathEnd { kSolution, kRay, kPivotLimit, kSingular };

// [M/s | d] as block_lu.h's matrix A: rows 0 … n−1, column key 0 the
// covering vector d (z₀'s column), key j + 1 the column j of M/s.
class ScaledColumns final : public lcp_internal::Entries {
 public:
  ScaledColumns(const FactoredLcpMatrix& M, const VectorX& d, double inv_s)
      : M_(M), d_(d), inv_s_(inv_s) {}
  int num_rows() const override { return M_.size(); }
  int num_cols() const override { return M_.size() + 1; }
  void Column(int key, VectorX* out) const override {
    if (key == 0) {
      *out = d_;
      return;
    }
    M_.Column(key - 1, out);
    *out *= inv_s_;
  }
  void Row(int row, VectorX* out) const override {
    M_.Row(row, &row_);
    out->resize(M_.size() + 1);
    (*out)[0] = d_[row];
    out->tail(M_.size()) = row_ * inv_s_;
  }

 private:
  const FactoredLcpMatrix& M_;
  const VectorX& d_;
  double inv_s_;
  mutable VectorX row_;
};

// Lemke's path on the factored LCP. The reduced basis C = [M/s | d](R, Z)
// (R the rows whose w is nonbasic, Z the basic z and z₀) is kept as an
// updated block-LU factorisation (block_lu.h); every rate and value is a
// solve with it.
class Path {
 public:
  Path(const FactoredLcpMatrix& M, const VectorX& q_scaled, double inv_scale, double tol,
       double drift_tol)
      : M_(M),
        n_(M.size()),
        q_(q_scaled),
        inv_s_(inv_scale),
        tol_(tol),
        drift_tol_(drift_tol),
        role_(n_, Role::kW),
        row_pos_(n_, -1),
        col_pos_(n_, -1),
        w_(VectorX::Zero(n_)),
        d_(VectorX::Ones(n_)),
        a_(n_),
        omega_(n_),
        scratch_(n_),
        entries_(M, d_, inv_scale),
        lu_(entries_) {}

  int pivots() const { return pivots_; }

  // Sets the complementary basis {z_i basic : basic_z[i]} and factors it;
  // with `values`, also its values for the current q. Returns false when its
  // reduced matrix is singular.
  bool SetBasis(const std::vector<bool>& basic_z, bool values = true) {
    rows_.clear();
    cols_.clear();
    for (int i = 0; i < n_; ++i) {
      role_[i] = basic_z[i] ? Role::kZ : Role::kW;
      row_pos_[i] = col_pos_[i] = -1;
      if (basic_z[i]) {
        row_pos_[i] = col_pos_[i] = static_cast<int>(rows_.size());
        rows_.push_back(i);
        cols_.push_back(i);
      }
    }
    z0_pos_ = -1;
    if (!Refactor()) return false;
    if (values) RecomputeValues();
    return true;
  }

  // Replaces q (scaled) and recomputes the values.
  void SetQ(const VectorX& q_scaled) {
    q_ = q_scaled;
    RecomputeValues();
  }

  // z of the current complementary basis (z₀ not basic) for the scaled
  // right-hand side `q_scaled`: a solve with C and one step of iterative
  // refinement through the data (the residual q_R + M(R, Z) x).
  void SolveWith(const VectorX& q_scaled, VectorX* z) {
    CAIRN_CHECK(z0_pos_ < 0);
    const int kk = k();
    Restrict(q_scaled, &aR_);
    VectorX x, dx;
    SolveC(-aR_, &x);
    scratch_.setZero(n_);
    M_.AddColumns(cols_, x.data(), &scratch_, &u_);
    VectorX r(kk);
    for (int s = 0; s < kk; ++s) r[s] = q_scaled[rows_[s]] + scratch_[rows_[s]] * inv_s_;
    SolveC(r, &dx);
    x -= dx;
    z->setZero(n_);
    for (int p = 0; p < kk; ++p) (*z)[cols_[p]] = x[p];
  }

  // True when the current complementary basis is feasible (up to `slack`).
  bool Feasible(double slack) const {
    for (int p = 0; p < k(); ++p)
      if (x_[p] < -slack) return false;
    for (int i = 0; i < n_; ++i)
      if (role_[i] == Role::kW && w_[i] < -slack) return false;
    return true;
  }

  // Follows Lemke's path from the current complementary basis until z₀
  // leaves, a ray, the pivot limit or a singular basis.
  PathEnd Follow(int max_pivots) {
    if (!EnterZ0()) return PathEnd::kSingular;
    ++pivots_;
    bool retried = false;
    while (true) {
      if (pivots_ >= max_pivots) return PathEnd::kPivotLimit;
      if (!KeepAccurate()) return PathEnd::kSingular;
      // The entering variable: the complement of the last one to leave.
      const int c = none_;
      const bool enter_w = last_left_z_;
      EnteringRates(c, enter_w);
      const std::optional<Leaving> leave = RatioTest();
      if (!leave) return PathEnd::kRay;
      if (!Exchange(enter_w ? -1 : c, enter_w ? c : -1, leave->row, leave->col, leave->theta)) {
        // A zero pivot element from drifted rates: refactor and redo the
        // ratio test once (the basis is unchanged); twice is a real failure.
        if (retried) return PathEnd::kSingular;
        retried = true;
        if (!Refactor()) return PathEnd::kSingular;
        RecomputeValues();
        continue;
      }
      retried = false;
      ++pivots_;
      if (broken_) return PathEnd::kSingular;
      if (z0_pos_ < 0) return PathEnd::kSolution;
    }
  }

  // The first pivot: the covering vector d = B·1, so that every basic value
  // grows at unit rate with z₀. On the rows R, C·1 + d_R = 0 ⇒ d_R =
  // −M(R, Z)·1; on a basic w, M(i, Z)·1 + d_i = 1. z₀ enters at −min(basic
  // values); the most negative leaves.
  bool EnterZ0() {
    {
      std::vector<double> ones(cols_.size(), 1.0);
      scratch_.setZero(n_);
      M_.AddColumns(cols_, ones.data(), &scratch_, &u_);
      scratch_ *= inv_s_;
      for (int i = 0; i < n_; ++i) d_[i] = role_[i] == Role::kW ? 1.0 - scratch_[i] : -scratch_[i];
    }
    double v_min = std::numeric_limits<double>::infinity();
    int first_row = -1, first_col = -1;
    for (int i = 0; i < n_; ++i)
      if (role_[i] == Role::kW && w_[i] < v_min) v_min = w_[i], first_row = i, first_col = -1;
    for (int p = 0; p < k(); ++p)
      if (x_[p] < v_min) v_min = x_[p], first_col = p, first_row = -1;
    CAIRN_CHECK(v_min < 0);
    // Rates: Δ = +1 on x, ω = +1 on w (by the choice of d).
    delta_.setOnes(k());
    omega_.setZero(n_);
    for (int i = 0; i < n_; ++i)
      if (role_[i] == Role::kW) omega_[i] = 1.0;
    a_ = d_;
    return Exchange(/*enter_z=*/-1, /*enter_w=*/-1, first_row, first_col, -v_min) && !broken_;
  }

  // C₀ afresh when the border has outgrown MaxBorder; every kRevalueEvery
  // pivots, the values afresh, and C₀ afresh when they have drifted (the
  // tight rows' residual) or k/4 pivots have passed. False when C is
  // singular.
  bool KeepAccurate() {
    if (lu_.border() > lcp_internal::BlockLu::MaxBorder(k())) {
      if (!Refactor()) return false;
      RecomputeValues();
    }
    if (pivots_ % kRevalueEvery != 0 || pivots_ == last_revalue_) return true;
    last_revalue_ = pivots_;
    RecomputeValues();
    if (TightResidual() > drift_tol_ ||
        pivots_ - last_refactor_ >= kRefactorPerOrder * std::max(k(), 1)) {
      if (!Refactor()) return false;
      RecomputeValues();
    }
    return true;
  }

  // The rates Δ of x and ω of w as the entering variable grows: for w_c
  // (position s of R), x(t) = x + t C⁻¹ e_s; for z_c, with column
  // a = M(:, c)/s, x(t) = x − t C⁻¹ a_R and w(t) = w + t (a − M(:, Z) C⁻¹ a_R).
  void EnteringRates(int c, bool enter_w) {
    if (enter_w) {
      unit_.setZero(k());
      unit_[row_pos_[c]] = 1.0;
      SolveC(unit_, &delta_);
      omega_.setZero(n_);
      M_.AddColumns(cols_z_view(), delta_view().data(), &omega_, &u_);
      omega_ *= inv_s_;
      if (z0_pos_ >= 0) omega_ += delta_[z0_pos_] * d_;
      return;
    }
    M_.Column(c, &a_);
    a_ *= inv_s_;
    Restrict(a_, &aR_);
    SolveC(aR_, &delta_);
    delta_ = -delta_;
    omega_ = a_;
    scratch_.setZero(n_);
    M_.AddColumns(cols_z_view(), delta_view().data(), &scratch_, &u_);
    omega_ += scratch_ * inv_s_;
    if (z0_pos_ >= 0) omega_ += delta_[z0_pos_] * d_;
  }

  // The leaving variable: a basic w (row) or position col of Z, at step θ.
  struct Leaving {
    int row = -1, col = -1;
    double theta = 0;
  };

  // Ratio test (Harris's two passes): basic values decrease where Δ_p < 0 or
  // ω_i < 0. Pass 1 finds the largest step θ_max that keeps every value ≥ −τ
  // (τ = tol_, the roundoff of a value); pass 2 takes, of the candidates
  // whose exact ratio is ≤ θ_max, the one with the largest pivot element
  // relative to its column's scale. Values tied within roundoff thus never
  // leave on a roundoff-sized pivot element (which made the basis
  // numerically singular on the Jenga ticks); the ties the perturbation
  // separates (by δ ≫ τ) are still told apart. Empty: a ray.
  std::optional<Leaving> RatioTest() {
    const double col_scale = std::max(1.0, delta_.head(k()).cwiseAbs().maxCoeff());
    double row_scale = 1.0;
    for (int i = 0; i < n_; ++i)
      if (role_[i] == Role::kW) row_scale = std::max(row_scale, std::abs(omega_[i]));
    candidates_.clear();
    for (int p = 0; p < k(); ++p)
      if (-delta_[p] > tol_ * col_scale)
        candidates_.push_back({x_[p], -delta_[p], -delta_[p] / col_scale, -1, p});
    for (int i = 0; i < n_; ++i)
      if (role_[i] == Role::kW && -omega_[i] > tol_ * row_scale)
        candidates_.push_back({w_[i], -omega_[i], -omega_[i] / row_scale, i, -1});
    if (candidates_.empty()) return std::nullopt;
    double theta_max = std::numeric_limits<double>::infinity();
    for (const Candidate& cd : candidates_)
      theta_max = std::min(theta_max, (std::max(cd.value, 0.0) + tol_) / cd.rate);
    Leaving out;
    double best = -1;
    for (const Candidate& cd : candidates_) {
      const double ratio = std::max(cd.value, 0.0) / cd.rate;
      if (ratio > theta_max) continue;
      // z₀ leaves whenever it can: the path ends.
      const bool is_z0 = cd.col >= 0 && cd.col == z0_pos_;
      const double key = is_z0 ? std::numeric_limits<double>::infinity() : cd.relative;
      if (key > best) best = key, out.theta = ratio, out.row = cd.row, out.col = cd.col;
    }
    return out;
  }

  // max |q_R + M(R, Z) x| over the tight rows (scaled; their w, 0 exactly),
  // after RecomputeValues: how far the solves with C have drifted.
  double TightResidual() const {
    double r = 0;
    for (int s = 0; s < k(); ++s) r = std::max(r, std::abs(w_[rows_[s]]));
    return r;
  }

  // The complementary basis and z of the current iterate (z₀ dropped).
  void Extract(VectorX* z, LcpBasis* basis) const {
    z->setZero(n_);
    basis->basic_z.assign(n_, false);
    for (int p = 0; p < k(); ++p) {
      if (cols_[p] < 0) continue;
      (*z)[cols_[p]] = x_[p];
      basis->basic_z[cols_[p]] = true;
    }
  }

 private:
  int k() const { return static_cast<int>(cols_.size()); }

  // The z columns of Z with their Δ, for AddColumns (z₀'s column is d, added
  // separately): a copy with z₀'s slot given coefficient 0.
  const std::vector<int>& cols_z_view() {
    cols_z_.assign(cols_.begin(), cols_.end());
    for (auto& j : cols_z_)
      if (j < 0) j = 0;
    return cols_z_;
  }
  const VectorX& delta_view() {
    delta_z_ = delta_.head(k());
    if (z0_pos_ >= 0) delta_z_[z0_pos_] = 0.0;
    return delta_z_;
  }

  void Restrict(const VectorX& full, VectorX* out) const {
    out->resize(k());
    for (int s = 0; s < k(); ++s) (*out)[s] = full[rows_[s]];
  }

  // Row i of [M/s | d] over the columns Z.
  void RowOverZ(int i, VectorX* r) {
    M_.Row(i, &scratch_);
    r->resize(k());
    for (int p = 0; p < k(); ++p) (*r)[p] = cols_[p] < 0 ? d_[i] : scratch_[cols_[p]] * inv_s_;
  }

  void EnsureCapacity(int size) {
    if (x_.size() >= size) return;
    x_.conservativeResize(std::max(size, 2 * static_cast<int>(x_.size()) + 8));
  }

  // The keys of Z for BlockLu (z₀: 0, z_j: j + 1).
  const std::vector<int>& ColKeys() {
    col_keys_.resize(cols_.size());
    for (size_t p = 0; p < cols_.size(); ++p) col_keys_[p] = cols_[p] + 1;
    return col_keys_;
  }

  // x = C⁻¹ b for the current basis.
  void SolveC(const VectorX& b, VectorX* x) { lu_.Solve(rows_, ColKeys(), b, x); }

  // The block-LU exchanges of one pivot are done: S factored, or C₀
  // refactored when S is singular to working precision (the pivot element
  // passed its test, so that is roundoff); `broken_` when C itself is.
  void FinishExchange() {
    if (!lu_.Finish() && !Refactor()) broken_ = true;
  }

  // Factors C afresh from the data (BlockLu::Factor). False when C is
  // singular.
  bool Refactor() {
    EnsureCapacity(k() + 1);
    last_refactor_ = pivots_;
    return lu_.Factor(rows_, ColKeys());
  }

  // x = −C⁻¹ q_R and w = q + [M/s | d](:, Z) x on the basic w.
  void RecomputeValues() {
    Restrict(q_, &aR_);
    SolveC(aR_, &delta_);
    delta_ = -delta_;
    x_.head(k()) = delta_;
    scratch_.setZero(n_);
    M_.AddColumns(cols_z_view(), delta_view().data(), &scratch_, &u_);
    w_ = q_ + scratch_ * inv_s_;
    if (z0_pos_ >= 0) w_ += x_[z0_pos_] * d_;
  }

  // The pivot. The entering variable is z_{enter_z} (or z₀ when both enter_z
  // and enter_w are −1), or w_{enter_w}; the leaving one is the basic w of
  // row `leave_row` or the variable at position `leave_col` of Z. Rates Δ, ω
  // (and for an entering column, a) are those of the ratio test; θ the step.
  bool Exchange(int enter_z, int enter_w, int leave_row, int leave_col, double theta) {
    const int kk = k();
    // Move every basic value by θ along the rates.
    x_.head(kk) += theta * delta_.head(kk);
    for (int i = 0; i < n_; ++i)
      if (role_[i] == Role::kW) w_[i] += theta * omega_[i];
    if (enter_w < 0) {
      // A column enters: z_{enter_z}, or z₀ with column d (var −1).
      const bool ok = leave_row >= 0 ? Border(enter_z, leave_row, theta)
                                     : ReplaceColumn(enter_z, leave_col, theta);
      if (ok && enter_z >= 0) role_[enter_z] = Role::kZ;
      return ok;
    }
    // w_c enters: row c leaves R.
    return leave_row >= 0 ? ReplaceRow(enter_w, leave_row, theta)
                          : Shrink(enter_w, leave_col, theta);
  }

  // z_var (−1: z₀) is now basic at position p of Z with value theta.
  void PlaceColumn(int var, int p, double theta) {
    if (var >= 0)
      col_pos_[var] = p;
    else
      z0_pos_ = p;
    x_[p] = theta;
  }

  // w_i has left the basis (its row joined R): it becomes the nonbasic pair
  // whose complement z_i enters next.
  void LeaveRow(int i) {
    role_[i] = Role::kNone;
    w_[i] = 0;
    none_ = i;
    last_left_z_ = false;
  }

  // The variable `leaving` (−1: z₀) has left Z: with z₀ the path ends
  // (the basis is complementary); else w_leaving enters next.
  void LeaveColumn(int leaving) {
    if (leaving < 0) {
      z0_pos_ = -1;
      return;
    }
    col_pos_[leaving] = -1;
    role_[leaving] = Role::kNone;
    none_ = leaving;
    last_left_z_ = true;
  }

  // z_var enters, w_i leaves: C grows by row i and the entering column
  // (bordering). Its pivot element is the Schur complement a_i − r C⁻¹ a_R
  // = ω_i.
  bool Border(int var, int i, double theta) {
    const int kk = k();
    const double s = omega_[i];
    if (!(std::abs(s) > 0) || !std::isfinite(s)) return false;
    EnsureCapacity(kk + 1);
    rows_.push_back(i);
    row_pos_[i] = kk;
    cols_.push_back(var);
    lu_.AddColumn(var + 1);
    lu_.AddRow(i);
    FinishExchange();
    PlaceColumn(var, kk, theta);
    LeaveRow(i);
    return true;
  }

  // z_var enters, the variable at position p of Z leaves: column p of C
  // replaced by a. Pivot element (C⁻¹ a)_p = −Δ_p.
  bool ReplaceColumn(int var, int p, double theta) {
    const double hp = -delta_[p];
    if (!(std::abs(hp) > 0) || !std::isfinite(hp)) return false;
    const int leaving = cols_[p];
    lu_.RemoveColumn(leaving + 1);
    lu_.AddColumn(var + 1);
    cols_[p] = var;
    FinishExchange();
    PlaceColumn(var, p, theta);
    LeaveColumn(leaving);
    return true;
  }

  // w_c enters, w_i leaves: row c of C (position s) replaced by row i.
  // Pivot element r C⁻¹ e_s = r · Δ, r = row i over Z.
  bool ReplaceRow(int c, int i, double theta) {
    const int s = row_pos_[c];
    RowOverZ(i, &r_);
    const double den = r_.dot(delta_.head(k()));
    if (!(std::abs(den) > 0) || !std::isfinite(den)) return false;
    lu_.RemoveRow(c);
    lu_.AddRow(i);
    rows_[s] = i;
    row_pos_[i] = s;
    row_pos_[c] = -1;
    FinishExchange();
    role_[c] = Role::kW;
    w_[c] = theta;
    LeaveRow(i);
    return true;
  }

  // w_c enters, the variable at position p of Z leaves: row c (position s)
  // and column p removed, the last position moved into the holes. Pivot
  // element (C⁻¹ e_s)_p = Δ_p.
  bool Shrink(int c, int p, double theta) {
    const int kk = k();
    const int s = row_pos_[c];
    const double hps = delta_[p];
    if (!(std::abs(hps) > 0) || !std::isfinite(hps)) return false;
    const int last = kk - 1;
    const int leaving = cols_[p];
    lu_.RemoveRow(c);
    lu_.RemoveColumn(leaving + 1);
    if (p != last) {
      x_[p] = x_[last];
      cols_[p] = cols_[last];
      if (cols_[p] >= 0)
        col_pos_[cols_[p]] = p;
      else
        z0_pos_ = p;
    }
    if (s != last) {
      rows_[s] = rows_[last];
      row_pos_[rows_[s]] = s;
    }
    cols_.pop_back();
    rows_.pop_back();
    row_pos_[c] = -1;
    FinishExchange();
    role_[c] = Role::kW;
    w_[c] = theta;
    LeaveColumn(leaving);
    return true;
  }

  const FactoredLcpMatrix& M_;
  int n_;
  VectorX q_;  // scaled, perturbed
  double inv_s_;
  double tol_;
  double drift_tol_;  // TightResidual above which H is refactored (scaled)
  int last_revalue_ = -1;
  int last_refactor_ = 0;  // pivots_ at the last factorisation of C
  std::vector<Role> role_;
  std::vector<int> row_pos_, col_pos_;
  std::vector<int> rows_, cols_;  // R and Z (−1 = z₀) by position
  int z0_pos_ = -1;
  int none_ = -1;             // the index with w and z nonbasic
  bool last_left_z_ = false;  // the last variable to leave was a z
  int pivots_ = 0;
  bool broken_ = false;  // C became singular in an exchange: the path ends
  VectorX x_, w_, d_;
  VectorX a_, aR_, r_, delta_, omega_, scratch_, u_, delta_z_, unit_;
  std::vector<int> cols_z_, col_keys_;
  ScaledColumns entries_;  // [M/s | d], read by lu_
  lcp_internal::BlockLu lu_;
  // A basic variable that decreases along the entering direction.
  struct Candidate {
    double value;     // its value (scaled)
    double rate;      // its rate of decrease (> 0)
    double relative;  // rate over its column's scale: the pivot element's size
    int row, col;     // a basic w (row) or position col of Z
  };
  std::vector<Candidate> candidates_;
};

struct Attempt {
  PathEnd end = PathEnd::kSingular;
  bool start_solves = false;  ///< the starting basis solves the true problem (no pivot)
  int pivots = 0;
  VectorX z;        ///< the path's iterate (perturbed problem)
  VectorX z_exact;  ///< kSolution: the final basis solved with the true q (from H)
  LcpBasis basis;
};

// The problem as every attempt sees it: the data, its scale and tolerances.
struct Problem {
  const FactoredLcpMatrix& M;
  const VectorX& q;
  int n = 0;
  double accept = 0;  // the natural-map residual a solution must reach
  double inv_s = 1;   // 1 / the scale of the data
  double tol = 0;     // the pivot tolerance (relative)
};

// Fills `result` with z, w = M z + q, the residual and the basis; true when
// z solves the LCP to the acceptance tolerance.
bool Finish(const Problem& pb, VectorX z, const LcpBasis& basis, LcpResult* result) {
  VectorX w;
  pb.M.Multiply(z, &w);
  w += pb.q;
  const double res = NaturalMapResidual(z, w);
  result->z = std::move(z);
  result->w = std::move(w);
  result->residual = res;
  result->basis = basis;
  return res <= pb.accept && IsComplementarySolution(result->z, result->w, pb.accept);
}

// The basis re-solved with the true q: z_α = −M_αα⁻¹ q_α by LU (no inverse:
// this is the whole cost of a warm start that needs no pivot), one
// refinement step. False when M_αα is singular.
bool Resolve(const Problem& pb, const LcpBasis& basis, VectorX* z) {
  std::vector<int> alpha;
  for (int i = 0; i < pb.n; ++i)
    if (basis.basic_z[i]) alpha.push_back(i);
  z->setZero(pb.n);
  const int k = static_cast<int>(alpha.size());
  if (k == 0) return true;
  MatrixX C(k, k);
  VectorX col, rhs(k);
  for (int p = 0; p < k; ++p) {
    pb.M.Column(alpha[p], &col);
    for (int s = 0; s < k; ++s) C(s, p) = col[alpha[s]];
    rhs[p] = -pb.q[alpha[p]];
  }
  const Eigen::PartialPivLU<MatrixX> lu(C);
  const double u_min = lu.matrixLU().diagonal().cwiseAbs().minCoeff();
  if (!(u_min > k * kEps * C.cwiseAbs().maxCoeff())) return false;
  VectorX x = lu.solve(rhs);
  x += lu.solve(rhs - C * x);
  if (!x.allFinite()) return false;
  for (int p = 0; p < k; ++p) (*z)[alpha[p]] = x[p];
  return true;
}

// One attempt from `start` (all false: cold) with perturbation seed `seed`.
// The starting basis is factorised once: with the true q it may already
// solve the problem (a warm start without pivots: `result` is then filled);
// otherwise the same factorisation starts the path on the perturbed q.
Attempt RunAttempt(const Problem& pb, const std::vector<bool>& start, uint64_t seed,
                   double perturbation, int limit, LcpResult* result) {
  Attempt a;
  const VectorX q_true = pb.q * pb.inv_s;
  Path path(pb.M, q_true, pb.inv_s, pb.tol, kDriftFraction * std::max(perturbation, pb.tol));
  if (!path.SetBasis(start, /*values=*/false)) return a;
  if (std::find(start.begin(), start.end(), true) != start.end()) {
    VectorX z;
    path.SolveWith(q_true, &z);
    if (Finish(pb, z, LcpBasis{start}, result)) {
      a.end = PathEnd::kSolution;
      a.start_solves = true;
      return a;
    }
  }
  VectorX qs = q_true;
  for (int i = 0; i < pb.n; ++i) qs[i] += perturbation * internal::PerturbationWeight(seed, i);
  path.SetQ(qs);
  a.end = path.Feasible(0.0) ? PathEnd::kSolution : path.Follow(limit);
  a.pivots = path.pivots();
  path.Extract(&a.z, &a.basis);
  if (a.end == PathEnd::kSolution) path.SolveWith(q_true, &a.z_exact);
  return a;
}

// What an attempt's end means for the solve: done (the result is final), or
// on to the next round. `ray` records a cold path's secondary ray.
bool Concludes(const Problem& pb, Attempt& a, bool from_warm, LcpResult* result, bool* ray) {
  if (a.start_solves) {  // Finish() has filled the result
    result->status = LcpStatus::kSolved;
    result->warm_start_used = true;
    return true;
  }
  switch (a.end) {
    case PathEnd::kSolution: {
      // The final basis with the true q: from the path's H, else by a fresh
      // LU of the basis (when H has drifted), else the perturbed iterate if
      // it is the better answer.
      VectorX z;
      if (Finish(pb, a.z_exact, a.basis, result) ||
          (Resolve(pb, a.basis, &z) && Finish(pb, z, a.basis, result)) ||
          Finish(pb, a.z, a.basis, result)) {
        result->status = LcpStatus::kSolved;
        result->message.clear();
        return true;
      }
      result->status = LcpStatus::kNumericalFailure;
      std::ostringstream why;
      why << "final basis does not solve the LCP: natural-map residual " << result->residual
          << " > " << pb.accept;
      result->message = why.str();
      return false;
    }
    case PathEnd::kRay:
      // A ray from the cold start proves there is no solution (M
      // copositive-plus, or Stewart–Trinkle's with physical q); one from a
      // warm start proves nothing: retry cold.
      if (from_warm) return false;
      if (Finish(pb, a.z, a.basis, result)) {  // ended a roundoff away from a solution
        result->status = LcpStatus::kSolved;
        return true;
      }
      // On the degenerate 3-D LCPs a perturbed path can also end on a ray
      // when the LCP has a solution (the bridge of compas_cra): the other
      // rounds are tried, and the ray is reported only if none solves it.
      *ray = true;
      return false;
    case PathEnd::kPivotLimit:
      result->status = LcpStatus::kPivotLimit;
      result->message = "pivot limit reached";
      return !from_warm;
    case PathEnd::kSingular:
      break;
  }
  result->status = LcpStatus::kNumericalFailure;
  result->message = "singular basis on the path";
  return false;
}

}  // namespace

LcpResult SolveLemkeFactored(const FactoredLcpMatrix& M, const VectorX& q,
                             const LemkeParameters& params, const LcpBasis* warm_start) {
  const int n = M.size();
  CAIRN_THROW_UNLESS(q.size() == n, "SolveLemkeFactored: M is " << n << "x" << n << " but q has "
                                                                << q.size() << " entries");
  CAIRN_THROW_UNLESS(q.allFinite(), "SolveLemkeFactored: q has a NaN or infinite entry");
  LcpResult result;
  if (n == 0) {
    result.status = LcpStatus::kTrivial;
    return result;
  }
  const double q_inf = q.cwiseAbs().maxCoeff();
  Problem pb{
      M,
      q,
      n,
      params.solution_tolerance * std::max(1.0, q_inf),
      1.0 / std::max(M.MagnitudeBound(), q_inf),
      params.pivot_tolerance > 0.0 ? params.pivot_tolerance : static_cast<double>(n) * kEps * 16.0};
  if (q.minCoeff() >= 0.0) {
    result.status = LcpStatus::kTrivial;
    Finish(pb, VectorX::Zero(n), LcpBasis{std::vector<bool>(n, false)}, &result);
    return result;
  }
  const int max_pivots = params.max_pivots > 0 ? params.max_pivots : std::max(1000, 50 * (n + 1));
  // The tie-breaking perturbation (relative, like tol): between the pivot
  // tolerance and the solution tolerance (perturbation.h).
  const double delta = internal::PerturbationSize(pb.tol, params.solution_tolerance);
  const bool warm = warm_start != nullptr && warm_start->basic_z.size() == static_cast<size_t>(n);
  bool ray = false;  // a cold path ended on a secondary ray
  for (int round = 0; round < 4; ++round) {
    // Round 0: from the warm basis (if any), else cold; then cold with two
    // other perturbations; last, cold without perturbation (Harris's ratio
    // test alone). On the degenerate 3-D LCPs which of these succeeds varies
    // from problem to problem (docs/benchmarks.md, "Degenerate contact
    // LCPs"): each is tried only when the ones before it failed.
    const bool from_warm = warm && round == 0;
    const std::vector<bool> from = from_warm ? warm_start->basic_z : std::vector<bool>(n, false);
    const int limit = from_warm ? std::min(max_pivots, 2 * n + 100) : max_pivots;
    Attempt a =
        RunAttempt(pb, from, static_cast<uint64_t>(round), round < 3 ? delta : 0.0, limit, &result);
    result.pivots += a.pivots;
    if (Concludes(pb, a, from_warm, &result, &ray)) return result;
    // Without retries, a ray ends the solve, a warm path's too (it is taken
    // as the answer, which it does not prove).
    if (!params.retry_after_ray && (ray || a.end == PathEnd::kRay)) {
      ray = true;
      break;
    }
  }
  if (ray) {
    result.status = LcpStatus::kRayTermination;
    result.message = "secondary ray: the entering column has no positive entry";
  }
  return result;
}

}  // namespace cairn

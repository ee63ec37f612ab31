// Lemke's complementary pivoting method with a lexicographic ratio test.
//
// Derivation. With the artificial variable z₀ and the covering vector e, the
// LCP w = M z + q, z, w ≥ 0, zᵀw = 0 becomes the system of n equations in the
// 2n + 1 variables x = (w, z, z₀)
//
//     I w − M z − e z₀ = q.                                             (1)
//
// A basis B (n columns of [I  −M  −e]) splits x into basic x_B and nonbasic
// x_N; (1) reads x_B = B⁻¹q − B⁻¹N x_N. We keep the *compact tableau*
//
//     A = [ b | T ],   b = B⁻¹q (n),   T = B⁻¹N (n × (n + 1)),
//
// i.e. only the n + 1 nonbasic columns, not the n unit columns of the basic
// variables (half the memory traffic of the full n × (2n + 1) tableau). At the
// start B = I, b = q and T = [−M  −e]. Raising z₀ to −min(q) makes all w ≥ 0
// and drives the w_r of the smallest q_r to zero: z₀ replaces w_r (the first
// pivot). From then on the basis is almost complementary and the complement of
// the variable that just left enters. As the entering variable x_c grows,
// x_B = b − x_c T(:, c) decreases where T(i, c) > 0; the first row to reach
// zero, r = argmin { b_i / T(i, c) : T(i, c) > 0 } (the ratio test), leaves.
// If no T(i, c) is positive we are on a secondary ray; if z₀ leaves, the basis
// is complementary and b gives the solution.
//
// Exchanging x_c (nonbasic, column c) with the basic variable of row r, with
// pivot p = T(r, c), updates the compact tableau by one rank-1 update:
//
//     A(i, j) ← A(i, j) − A(i, c) A(r, j) / p   (i ≠ r, j ≠ c),
//     A(r, j) ← A(r, j) / p,   A(i, c) ← −A(i, c) / p,   A(r, c) ← 1 / p,
//
// and the leaving variable takes column c. Column-major storage makes each
// column an axpy, which Eigen vectorises; a pivot-row entry that is exactly
// zero skips its column.
//
// Degeneracy. Ties in the ratio test are broken lexicographically: among the
// tied rows choose the lexicographic minimum of the rows of [b | B⁻¹] divided
// by T(i, c). This keeps every row of [b | B⁻¹] lexicographically positive, so
// no basis repeats and the method is finite [Cottle, Pang & Stone 1992, §4.9].
// B⁻¹ is not stored: its column j is the tableau column of w_j when w_j is
// nonbasic and the unit vector e_(row of w_j) when w_j is basic. Ties and the
// lexicographic comparisons are exact (a tolerance there breaks the invariant
// and makes the massively degenerate lcp_tobenna cycle); the one tolerant rule
// is that z₀ leaves whenever its ratio is within the tolerance of the minimum.
//
// Scale. The data are divided by s = max |entry| of [M q] (z is unchanged, w
// and z₀ scale by 1/s), so the absolute tolerances used on the scaled tableau
// are relative to the data magnitude, as LemkeParameters documents: an entry
// T(i, c) ≤ tol is not a pivot candidate, with tol = pivot_tolerance or
// n · 16 · 2⁻⁵².
//
// Ending on a ray with z₀ already tiny means the path ended a roundoff away
// from a solution; the iterate (z₀ dropped, then re-solved as below) is
// returned as kSolved only if the independent check IsLcpSolution passes.
//
// Accuracy. The pivoted tableau drifts on ill-conditioned bases, so at the end
// the final complementary basis is re-solved from the original data
// (M_αα z_α = −q_α, LU with partial pivoting and one refinement step) and the
// z with the smaller natural-map residual is returned.

#include "cairn/lcp/lemke.h"

#include <Eigen/LU>  // IWYU pragma: keep
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "cairn/core/check.h"
#include "perturbation.h"

namespace cairn {

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The perturbed retry after a ray: this many times the first path's pivots
// (plus n + 1) at most (dimensionless; SolveLemke).
constexpr int kRayRetryPivots = 2;

// Solves the complementary basis {z_i basic : basic_z[i]} from the original
// data: M_αα z_α = −q_α by LU with partial pivoting plus one refinement step,
// z = 0 off α. Returns false when M_αα is numerically singular or the result
// is not finite. kMaxN bounds |α| at compile time (Eigen::Dynamic: no bound):
// with a bound, nothing goes on the heap, which is most of the cost of the
// warm start of a small LCP.
template <int kMaxN>
bool SolveBasis(const MatrixX& M, const VectorX& q, const std::vector<bool>& basic_z, VectorX* z) {
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxN, kMaxN>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxN, 1>;
  using Index = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1, 0, kMaxN, 1>;
  const Eigen::Index n = q.size();
  Index alpha(n);
  Eigen::Index k = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (basic_z[static_cast<size_t>(i)]) alpha[k++] = i;
  z->setZero(n);
  if (k == 0) return true;
  Matrix M_aa(k, k);
  Vector rhs(k);
  for (Eigen::Index c = 0; c < k; ++c) {
    for (Eigen::Index r = 0; r < k; ++r) M_aa(r, c) = M(alpha[r], alpha[c]);
    rhs[c] = -q[alpha[c]];
  }
  const Eigen::PartialPivLU<Matrix> lu(M_aa);
  // A pivot of U that is tiny against the largest entry of M_αα means singular.
  const double u_min = lu.matrixLU().diagonal().cwiseAbs().minCoeff();
  const double m_max = M_aa.cwiseAbs().maxCoeff();
  if (!(u_min > static_cast<double>(k) * kEps * m_max)) return false;
  Vector x = lu.solve(rhs);
  // One step of iterative refinement.
  const Vector r = rhs - M_aa * x;
  x += lu.solve(r);
  if (!x.allFinite()) return false;
  for (Eigen::Index c = 0; c < k; ++c) (*z)[alpha[c]] = x[c];
  return true;
}

// Problems up to this size are solved without heap allocation (the tableau
// is then at most 32 × 34 doubles, 8.7 kB of stack). 32 covers the LCPs of
// one or two bodies with a handful of frictional contacts (the T-stand's 24,
// paper Fig. 6's 18).
constexpr int kSmallN = 32;

bool SolveComplementaryBasis(const MatrixX& M, const VectorX& q, const std::vector<bool>& basic_z,
                             VectorX* z) {
  return q.size() <= kSmallN ? SolveBasis<kSmallN>(M, q, basic_z, z)
                             : SolveBasis<Eigen::Dynamic>(M, q, basic_z, z);
}

// The pivoting engine: the compact tableau and the bookkeeping of which
// variable sits in which row (basic) or tableau column (nonbasic).
// Variables: 0..n−1 are w, n..2n−1 are z, 2n is z₀.
//
// kMaxN bounds n at compile time (Eigen::Dynamic: no bound). Contact LCPs are
// mostly tiny (one per contact-graph component), and for them the heap
// allocations of a dynamic tableau cost more than the pivots: with kMaxN =
// kSmallN every array lives on the stack.
template <int kMaxN>
class LemkeTableau {
  static constexpr int kMaxCols = kMaxN == Eigen::Dynamic ? Eigen::Dynamic : kMaxN + 2;
  static constexpr int kMaxVars = kMaxN == Eigen::Dynamic ? Eigen::Dynamic : 2 * kMaxN + 1;
  using Tableau =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxN, kMaxCols>;
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxN, 1>;
  using Indices = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxVars, 1>;
  using RowList = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxN, 1>;
  using Flags = Eigen::Matrix<unsigned char, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxVars, 1>;

 public:
  LemkeTableau(const MatrixX& M, const VectorX& q, double scale, double tol)
      : n_(q.size()),
        tol_(tol),
        A_(n_, n_ + 2),
        col_(n_),
        basic_var_(n_),
        is_basic_(2 * n_ + 1),
        pos_(2 * n_ + 1),
        ties_(n_),
        keep_(n_) {
    // A = [q | −M | −e] / s; all w basic, w_i in row i; z_j in column j, z₀ in n.
    const double inv_s = 1.0 / scale;
    A_.col(0) = q * inv_s;
    A_.middleCols(1, n_) = M * (-inv_s);
    A_.col(n_ + 1).setConstant(-inv_s);
    for (Eigen::Index i = 0; i < n_; ++i) {
      basic_var_[i] = i;
      is_basic_[i] = true;
      pos_[i] = i;
      is_basic_[n_ + i] = false;
      pos_[n_ + i] = i;
    }
    is_basic_[2 * n_] = false;
    pos_[2 * n_] = n_;
  }

  Eigen::Index z0() const { return 2 * n_; }
  Eigen::Index Complement(Eigen::Index v) const { return v < n_ ? v + n_ : v - n_; }
  Eigen::Index BasicVar(Eigen::Index row) const { return basic_var_[row]; }

  // The first pivot: z₀ enters and w_r leaves, r = argmin q. Among ties the
  // largest index is taken: after the pivot row i of [b | B⁻¹] is
  // [q_i − q_r | e_i − e_r], lexicographically positive for a tied i iff i < r.
  Eigen::Index FirstRow() const {
    const double q_min = A_.col(0).minCoeff();
    Eigen::Index r = 0;
    for (Eigen::Index i = 0; i < n_; ++i) {
      if (A_(i, 0) <= q_min + tol_ * std::max(1.0, std::abs(q_min))) r = i;
    }
    return r;
  }

  // Ratio test for entering variable `v`; returns the leaving row or −1 on a
  // secondary ray (no entry of the entering column above the tolerance).
  Eigen::Index RatioTest(Eigen::Index v) {
    const Eigen::Index c = 1 + pos_[v];
    const double* d = A_.col(c).data();
    const double* b = A_.col(0).data();
    // Minimum ratio over rows with a positive entry.
    double theta_min = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < n_; ++i) {
      if (d[i] > tol_) theta_min = std::min(theta_min, b[i] / d[i]);
    }
    if (theta_min == std::numeric_limits<double>::infinity()) return -1;
    // If z₀ can leave within the tolerance, let it: that ends the path at a
    // solution (without this, roundoff in b can hand the exit to another row
    // and lead the path onto a ray one pivot before the end).
    const Eigen::Index z0_row = pos_[z0()];
    if (is_basic_[z0()] && d[z0_row] > tol_ &&
        b[z0_row] / d[z0_row] <= theta_min + tol_ * std::max(1.0, std::abs(theta_min))) {
      return z0_row;
    }
    // The rows tied exactly with the minimum. (A tolerance here would break
    // the lexicographic invariant on massively degenerate problems such as
    // Siconos' lcp_tobenna, which then cycle.)
    Eigen::Index num_ties = 0;
    for (Eigen::Index i = 0; i < n_; ++i) {
      if (d[i] > tol_ && b[i] / d[i] == theta_min) ties_[num_ties++] = i;
    }
    if (num_ties == 1) return ties_[0];
    // Lexicographic minimum of the rows of B⁻¹ / d_i, column by column.
    for (Eigen::Index j = 0; j < n_ && num_ties > 1; ++j) {
      const bool w_basic = is_basic_[j];
      const Eigen::Index where = pos_[j];
      auto binv = [&](Eigen::Index i) {
        if (w_basic) return i == where ? 1.0 : 0.0;
        return A_(i, 1 + where);
      };
      double v_min = std::numeric_limits<double>::infinity();
      for (Eigen::Index t = 0; t < num_ties; ++t)
        v_min = std::min(v_min, binv(ties_[t]) / d[ties_[t]]);
      Eigen::Index kept = 0;
      for (Eigen::Index t = 0; t < num_ties; ++t) {
        if (binv(ties_[t]) / d[ties_[t]] == v_min) keep_[kept++] = ties_[t];
      }
      ties_.head(kept) = keep_.head(kept);
      num_ties = kept;
    }
    // B⁻¹ is nonsingular so one row remains unless roundoff blurred it: then
    // take the largest pivot.
    Eigen::Index best = ties_[0];
    for (Eigen::Index t = 0; t < num_ties; ++t) {
      if (d[ties_[t]] > d[best]) best = ties_[t];
    }
    return best;
  }

  // Exchanges entering variable `v` with the basic variable of row `r`.
  // Returns false when the pivot element is not a finite nonzero number.
  bool Pivot(Eigen::Index r, Eigen::Index v) {
    const Eigen::Index c = 1 + pos_[v];
    const double p = A_(r, c);
    if (!std::isfinite(p) || p == 0.0) return false;
    const double inv_p = 1.0 / p;
    col_ = A_.col(c);
    // Rank-1 update column by column; the entry in row r becomes A(r, j) / p.
    const Eigen::Index cols = A_.cols();
    for (Eigen::Index j = 0; j < cols; ++j) {
      if (j == c) continue;
      const double f = A_(r, j) * inv_p;
      if (f == 0.0) continue;
      A_.col(j).noalias() -= f * col_;
      A_(r, j) = f;
    }
    // The pivot column now holds the leaving variable's column of B⁻¹N.
    A_.col(c) = col_ * (-inv_p);
    A_(r, c) = inv_p;
    // Bookkeeping: the leaving variable takes column c − 1, v takes row r.
    const Eigen::Index leaving = BasicVar(r);
    is_basic_[leaving] = false;
    pos_[leaving] = c - 1;
    is_basic_[v] = true;
    pos_[v] = r;
    basic_var_[r] = v;
    return true;
  }

  // The z part of the current basic solution (z₀ and w are dropped).
  void ExtractZ(VectorX* z) const {
    z->setZero(n_);
    for (Eigen::Index i = 0; i < n_; ++i) {
      const Eigen::Index v = BasicVar(i);
      if (v >= n_ && v < 2 * n_) (*z)[v - n_] = A_(i, 0);
    }
  }

  // The complementary basis (valid once z₀ has left).
  LcpBasis Basis() const {
    LcpBasis basis;
    basis.basic_z.resize(static_cast<size_t>(n_));
    for (Eigen::Index i = 0; i < n_; ++i) {
      basis.basic_z[i] = is_basic_[n_ + i];
    }
    return basis;
  }

 private:
  Eigen::Index n_;
  double tol_;
  Tableau A_;            // [b | T], column-major.
  Column col_;           // The pivot column, copied before the update.
  RowList basic_var_;    // Row → basic variable.
  Flags is_basic_;       // Variable → basic?
  Indices pos_;          // Variable → row (basic) or column of T.
  RowList ties_, keep_;  // Rows tied in the ratio test (scratch).
};

// Lemke's path from the start (z₀ enters) until z₀ leaves, a ray, the pivot
// limit or a numerical failure. Fills result->{status, message, pivots, z, w,
// residual} and *basis; returns true when z₀ left (the basis is complementary).
template <int kMaxN>
bool FollowPath(const MatrixX& M, const VectorX& q, double scale, double tol, int max_pivots,
                LcpResult* out, LcpBasis* basis) {
  LcpResult& result = *out;
  LemkeTableau<kMaxN> tableau(M, q, scale, tol);
  // Pivot 1: z₀ enters, the w of the most negative q leaves.
  Eigen::Index row = tableau.FirstRow();
  Eigen::Index leaving = tableau.BasicVar(row);
  tableau.Pivot(row, tableau.z0());
  result.pivots = 1;
  Eigen::Index entering = tableau.Complement(leaving);

  // Follow the almost-complementary path until z₀ leaves.
  bool at_solution = false;
  while (true) {
    if (result.pivots >= max_pivots) {
      result.status = LcpStatus::kPivotLimit;
      result.message = "pivot limit reached";
      break;
    }
    row = tableau.RatioTest(entering);
    if (row < 0) {
      result.status = LcpStatus::kRayTermination;
      result.message = "secondary ray: the entering column has no positive entry";
      break;
    }
    leaving = tableau.BasicVar(row);
    if (!tableau.Pivot(row, entering)) {
      result.status = LcpStatus::kNumericalFailure;
      result.message = "non-finite pivot element";
      break;
    }
    ++result.pivots;
    if (leaving == tableau.z0()) {
      at_solution = true;
      break;
    }
    entering = tableau.Complement(leaving);
  }

  // The tableau's z (z₀ dropped) and the basis it implies.
  tableau.ExtractZ(&result.z);
  result.w.noalias() = M * result.z;  // no temporary: w = M z, then + q
  result.w += q;
  result.residual = NaturalMapResidual(result.z, result.w);
  *basis = tableau.Basis();

  return at_solution;
}

}  // namespace

double NaturalMapResidual(const VectorX& z, const VectorX& w) {
  double r = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) r = std::max(r, std::abs(std::min(z[i], w[i])));
  return r;
}

const char* to_string(LcpStatus status) {
  switch (status) {
    case LcpStatus::kSolved:
      return "solved";
    case LcpStatus::kTrivial:
      return "trivial";
    case LcpStatus::kRayTermination:
      return "ray termination";
    case LcpStatus::kPivotLimit:
      return "pivot limit";
    case LcpStatus::kNumericalFailure:
      return "numerical failure";
  }
  return "unknown";
}

double LcpResidual(const MatrixX& M, const VectorX& q, const VectorX& z) {
  CAIRN_THROW_UNLESS(M.rows() == q.size() && M.cols() == q.size() && z.size() == q.size(),
                     "LcpResidual: M is " << M.rows() << "x" << M.cols() << ", q has " << q.size()
                                          << " and z " << z.size() << " entries");
  if (q.size() == 0) return 0.0;
  const VectorX w = M * z + q;
  return NaturalMapResidual(z, w);
}

bool IsComplementarySolution(const VectorX& z, const VectorX& w, double tol) {
  if (!z.allFinite() || !w.allFinite()) return false;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    if (!(z[i] >= -tol) || !(w[i] >= -tol)) return false;
    const double scale = std::max({1.0, std::abs(z[i]), std::abs(w[i])});
    if (!(std::abs(z[i] * w[i]) <= tol * scale)) return false;
  }
  return true;
}

bool IsLcpSolution(const MatrixX& M, const VectorX& q, const VectorX& z, double tol) {
  if (M.rows() != q.size() || M.cols() != q.size() || z.size() != q.size()) return false;
  return IsComplementarySolution(z, M * z + q, tol);
}

namespace {

// The problem as the dense path sees it: data, scale and tolerances.
struct DenseProblem {
  const MatrixX& M;
  const VectorX& q;
  Eigen::Index n = 0;
  double q_inf = 0, m_max = 0, scale = 1;
  double accept = 0;  // the natural-map residual a solution must reach
  double tol = 0;     // the pivot tolerance (relative)
  int max_pivots = 0;
};

// The warm start: one LU of the previous basis, accepted if it solves the
// LCP. (It comes before the input check, which it implies: a NaN or infinite
// entry of M or q makes w = M z + q non-finite, and the check of w fails.)
bool SolvedByWarmStart(const DenseProblem& pb, const LcpBasis& warm, LcpResult* result) {
  VectorX z;
  if (!SolveComplementaryBasis(pb.M, pb.q, warm.basic_z, &z)) return false;
  VectorX w = pb.M * z + pb.q;
  const double res = NaturalMapResidual(z, w);
  if (!(res <= pb.accept && IsComplementarySolution(z, w, pb.accept))) return false;
  result->status = LcpStatus::kSolved;
  result->z = std::move(z);
  result->w = std::move(w);
  result->residual = res;
  result->warm_start_used = true;
  result->basis = warm;
  return true;
}

// Follows the path on q_path (q, or q perturbed), on the stack for small
// problems; re-solves the final basis with the true q and checks it.
void FollowAndCheck(const DenseProblem& pb, const VectorX& q_path, LcpResult* out) {
  const MatrixX& M = pb.M;
  const VectorX& q = pb.q;
  const Eigen::Index n = pb.n;
  const double accept = pb.accept;
  LcpResult& res = *out;
  bool at_solution = false;
  LcpBasis basis;
  if (n <= kSmallN) {
    at_solution = FollowPath<kSmallN>(M, q_path, pb.scale, pb.tol, pb.max_pivots, &res, &basis);
  } else {
    at_solution =
        FollowPath<Eigen::Dynamic>(M, q_path, pb.scale, pb.tol, pb.max_pivots, &res, &basis);
  }
  const bool perturbed = &q_path != &q;
  if (perturbed) {  // the tableau's z and w answer the perturbed problem
    res.w.noalias() = M * res.z;
    res.w += q;
    res.residual = NaturalMapResidual(res.z, res.w);
  }

  // Re-solve the basis from the data; keep the better of the two z. When
  // the tableau's answer is already exact to roundoff (residual within a
  // few ulps of the data), the re-solve cannot improve it: skip it, which
  // is most of the fixed cost of the small LCPs that single contact
  // components produce. (A looser bound lets the drift of long paths
  // through: Murty's n = 8 problem ends 256 pivots later with w off by
  // 2e-12, which the re-solve removes.)
  const double roundoff = 4.0 * kEps * (pb.m_max * res.z.cwiseAbs().maxCoeff() + pb.q_inf);
  VectorX z_lu;
  if (!(at_solution && res.residual <= roundoff) &&
      SolveComplementaryBasis(M, q, basis.basic_z, &z_lu)) {
    VectorX w_lu = M * z_lu + q;
    const double res_lu = NaturalMapResidual(z_lu, w_lu);
    if (res_lu < res.residual) {
      res.z = std::move(z_lu);
      res.w = std::move(w_lu);
      res.residual = res_lu;
    }
  }
  const bool verified = res.residual <= accept && IsComplementarySolution(res.z, res.w, accept);

  // A ray met with z₀ already below the solution tolerance is the end of
  // the path up to roundoff: the iterate with z₀ dropped solves
  // LCP(M, q + e z₀), and it is returned as a solution only when the
  // independent check passes. Every other failure keeps its status.
  if (at_solution || (res.status == LcpStatus::kRayTermination && verified)) {
    res.basis = basis;
    if (verified) {
      res.status = LcpStatus::kSolved;
      res.message.clear();
    } else {
      res.status = LcpStatus::kNumericalFailure;
      std::ostringstream os;
      os << "final basis does not solve the LCP: natural-map residual " << res.residual << " > "
         << accept;
      res.message = os.str();
    }
  }
}

}  // namespace

namespace {

// Symmetric equilibration of an LCP (Ruiz's iteration on the symmetric
// scaling): D = diag(d) with d_i = 1 / √(max_j |(D M D)_ij|) repeated, and a
// scalar c = |D q|∞ / max |D M D|. LCP(M, q) and LCP(c D M D, D q) have the
// same solutions up to z = c D ẑ, w = D⁻¹ ŵ (positive diagonal scalings keep
// z ≥ 0, w ≥ 0 and z_i w_i = 0). The contact LCPs of light parts have
// W M⁻¹ Wᵀ ~ 1/m (1e15 for a milligram part in kilograms) against a q of
// accelerations ~10: in those units Lemke's relative tolerances see q as
// roundoff. Empty when the problem is balanced already (every d within
// kBalanced of 1): then nothing changes, to the last bit. The scalar alone
// is no reason to scale: Lemke's method divides by max(|M|, |q|).
struct Equilibration {
  VectorX d;
  double c = 1;
  MatrixX M;  // c D M D
  VectorX q;  // D q
};
constexpr int kRuizPasses = 8;
constexpr double kBalanced = 1e3;

std::optional<Equilibration> Equilibrate(const MatrixX& M, const VectorX& q) {
  const Eigen::Index n = q.size();
  Equilibration e;
  e.d = VectorX::Ones(n);
  for (int pass = 0; pass < kRuizPasses; ++pass) {
    bool moved = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      double row = 0;
      for (Eigen::Index j = 0; j < n; ++j) row = std::max(row, std::abs(M(i, j)) * e.d[j]);
      row *= e.d[i];
      if (!(row > 0) || !std::isfinite(row)) continue;
      const double f = 1.0 / std::sqrt(row);
      moved = moved || f < 0.5 || f > 2.0;
      e.d[i] *= f;
    }
    if (!moved) break;
  }
  // Balanced already: nothing more to compute (the common case, on the path
  // of every small contact LCP).
  if (!e.d.allFinite() || (e.d.maxCoeff() <= kBalanced && e.d.minCoeff() >= 1.0 / kBalanced))
    return std::nullopt;
  e.M = e.d.asDiagonal() * M * e.d.asDiagonal();
  e.q = e.d.cwiseProduct(q);
  const double m = e.M.cwiseAbs().maxCoeff(), qs = e.q.cwiseAbs().maxCoeff();
  if (m > 0 && qs > 0) e.c = qs / m;
  if (!std::isfinite(e.c)) return std::nullopt;
  e.M *= e.c;
  return e;
}

LcpResult SolveLemkeScaled(const MatrixX& M, const VectorX& q, const LemkeParameters& params,
                           const LcpBasis* warm_start);

}  // namespace

LcpResult SolveLemke(const MatrixX& M, const VectorX& q, const LemkeParameters& params,
                     const LcpBasis* warm_start) {
  const Eigen::Index n = q.size();
  CAIRN_THROW_UNLESS(M.rows() == n && M.cols() == n, "SolveLemke: M is "
                                                         << M.rows() << "x" << M.cols()
                                                         << " but q has " << n << " entries");
  const bool finite = (M.array() * 0.0).sum() == 0.0 && (q.array() * 0.0).sum() == 0.0;
  const std::optional<Equilibration> e =
      n > 0 && finite ? Equilibrate(M, q) : std::optional<Equilibration>();
  if (!e) return SolveLemkeScaled(M, q, params, warm_start);
  LcpResult r = SolveLemkeScaled(e->M, e->q, params, warm_start);
  if (r.z.size() == n) {
    r.z = e->c * e->d.cwiseProduct(r.z);
    r.w = M * r.z + q;
    r.residual = NaturalMapResidual(r.z, r.w);
  }
  return r;
}

namespace {

LcpResult SolveLemkeScaled(const MatrixX& M, const VectorX& q, const LemkeParameters& params,
                           const LcpBasis* warm_start) {
  const Eigen::Index n = q.size();
  CAIRN_THROW_UNLESS(M.rows() == n && M.cols() == n, "SolveLemke: M is "
                                                         << M.rows() << "x" << M.cols()
                                                         << " but q has " << n << " entries");
  LcpResult result;
  if (n == 0) {
    result.status = LcpStatus::kTrivial;
    return result;
  }
  DenseProblem pb{M, q, n};
  pb.q_inf = q.cwiseAbs().maxCoeff();
  pb.accept = params.solution_tolerance * std::max(1.0, pb.q_inf);
  if (warm_start != nullptr && warm_start->basic_z.size() == static_cast<size_t>(n) &&
      SolvedByWarmStart(pb, *warm_start, &result))
    return result;
  // Every entry finite: (M · 0) sums to 0 exactly, else to NaN (vectorised,
  // unlike a test per entry).
  CAIRN_THROW_UNLESS((M.array() * 0.0).sum() == 0.0 && (q.array() * 0.0).sum() == 0.0,
                     "SolveLemke: M or q has a NaN or infinite entry");

  // Tolerances: relative to s = max |entry| of [M q] through the scaling.
  pb.m_max = M.cwiseAbs().maxCoeff();
  pb.scale = std::max(pb.m_max, pb.q_inf);
  pb.tol =
      params.pivot_tolerance > 0.0 ? params.pivot_tolerance : static_cast<double>(n) * kEps * 16.0;
  pb.max_pivots =
      params.max_pivots > 0 ? params.max_pivots : std::max(1000, 50 * (static_cast<int>(n) + 1));

  // q ≥ 0: z = 0 with all w basic. (A q that is nonnegative only up to
  // roundoff takes one pivot and ends on the near-zero-z₀ rule below.)
  if (q.minCoeff() >= 0.0) {
    result.status = LcpStatus::kTrivial;
    result.z.setZero(n);
    result.w = q;
    result.residual = NaturalMapResidual(result.z, result.w);
    result.basis.basic_z.assign(static_cast<size_t>(n), false);
    return result;
  }
  FollowAndCheck(pb, q, &result);
  // The exact lexicographic rule cannot see ties that roundoff has blurred
  // (massively degenerate contact sets: a basis built on pivots of roundoff
  // size). Then the ties are broken by a perturbation of q instead (see
  // factored_lcp.h) and the final basis is re-solved with the true q.
  // A path that cycles (the pivot limit) or ends on a secondary ray of an LCP
  // that has a solution is the same trouble seen later: ties blurred on the
  // way. The perturbed path is tried for those too. After a ray it gets
  // kRayRetryPivots times the first path's pivots and n more: the perturbed
  // problem's path is the same one with its ties untied, no longer than the
  // first where the ray was spurious (measured: docs/benchmarks.md,
  // "`bench/sequence_bench.sh`, fifth stop"), and a ray that is the answer (a
  // collapse loaded from rest) would otherwise cost the whole pivot budget
  // again.
  if (result.status == LcpStatus::kNumericalFailure || result.status == LcpStatus::kPivotLimit ||
      (result.status == LcpStatus::kRayTermination && params.retry_after_ray)) {
    VectorX q_pert = q;
    for (Eigen::Index i = 0; i < n; ++i)
      q_pert[i] += internal::PerturbationSize(pb.tol, params.solution_tolerance) * pb.scale *
                   internal::PerturbationWeight(0, static_cast<uint64_t>(i));
    if (result.status == LcpStatus::kRayTermination)
      pb.max_pivots = static_cast<int>(std::min<Eigen::Index>(
          pb.max_pivots, Eigen::Index{kRayRetryPivots} * result.pivots + n + 1));
    LcpResult retry;
    FollowAndCheck(pb, q_pert, &retry);
    retry.pivots += result.pivots;
    if (retry.status == LcpStatus::kSolved) return retry;
  }
  return result;
}

}  // namespace

}  // namespace cairn

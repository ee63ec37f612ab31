#pragma once
/// @file
/// LCPs whose matrix comes in factored form
///
///     M = G W Gᵀ + K,   G (n × d) sparse,  W (d × d) sparse symmetric PSD,
///                       K (n × n) sparse,
///
/// and Lemke's method on them without ever forming M.
///
/// Contact LCPs have this form: G is the contact Jacobian (normal and friction
/// rows, each touching two bodies), W the block-diagonal (effective) inverse
/// mass and K the sparse friction-cone coupling of Stewart–Trinkle. A wall of
/// 105 bricks has n = 2280 LCP variables but d = 315: the dense M (42 MB, 40 ms
/// to form) and a dense Lemke tableau (≈ 2 ms per pivot) are both wasted on
/// it. SolveLemkeFactored keeps instead
///
///  - the basic variables' values, updated along the path, and
///  - the explicit inverse of the *reduced* basis matrix: the rows of M whose
///    w is nonbasic against the columns of the basic z (and z₀). Its order k
///    is the number of basic z's, at most rank(M) + 1: about 200 for the
///    wall, whose contacts are far more than its bodies can load independently.
///
/// A pivot costs O(k²) for the rank-one update of that inverse plus O(nnz(G))
/// for one product with G, instead of O(n²): for the wall about 40 µs
/// against 2 ms.
///
/// Degeneracy. Redundant contacts (four bricks resting on one edge, a
/// statically indeterminate wall) make the LCP massively degenerate: at the
/// solution hundreds of contacts have both w = 0 and z = 0. In floating point
/// the exact lexicographic rule of SolveLemke cannot see those ties (the zeros
/// come out as ±1e-17 and the pivot columns' zeros as ±1e-14), picks pivots
/// out of roundoff and ends on a wrong basis. Here the ties are broken by
/// perturbing q by δ·ρ (δ = √(τ ε) relative to the data, the geometric mean
/// of the pivot tolerance τ and the solution tolerance ε, derived in
/// src/lcp/perturbation.h; ρᵢ ∈ [½, 1) fixed pseudo-random numbers, the same
/// on every run): the perturbed problem is
/// nondegenerate, every degenerate w or z becomes a small positive number
/// rather than a signed zero, and a pivot on a roundoff-sized entry would need
/// a ratio ~δ/1e-14, which never wins. The final basis is then re-solved with
/// the original q and accepted only when it passes the independent check, so
/// the perturbation does not change the answer beyond roundoff. Ties that
/// roundoff still blurs (within τ) are settled by Harris's two-pass ratio
/// test in favour of the largest pivot element, and the inverse is refactored
/// when it drifts and every k/4 pivots. Three perturbed cold paths and one
/// unperturbed path are tried in turn (docs/benchmarks.md, "Degenerate
/// contact LCPs").
///
/// Warm start. Lemke's method may start from any complementary basis: with
/// the covering vector d = B·1 (B the basis matrix) every basic variable grows
/// at unit rate with z₀, so z₀ enters at −min(basic values) and the path
/// proceeds as from the cold start, which is the special case of the empty
/// basis (d = e) [Cottle, Pang & Stone 1992, §4.4.5]. Along a motion path the
/// previous step's basis is nearly right, so a handful of pivots repair it.
/// For PSD matrices (frictionless contact) the warm start keeps Lemke's
/// guarantees (a principal pivot transform of a PSD matrix is PSD); for the
/// Stewart–Trinkle matrix it need not, so a warm path that ends on a ray or
/// the pivot limit is retried cold, and only a cold ray is reported.

#include <Eigen/SparseCore>

#include "cairn/lcp/lemke.h"

namespace cairn {

/// Column-major sparse matrix.
using SparseMatrixX = Eigen::SparseMatrix<double>;

/// M = G W Gᵀ + K (see the file comment).
class FactoredLcpMatrix {
 public:
  FactoredLcpMatrix() = default;
  /// @throws std::invalid_argument on inconsistent sizes or non-finite entries.
  FactoredLcpMatrix(const SparseMatrixX& G, const SparseMatrixX& W, const SparseMatrixX& K);

  /// n.
  int size() const { return static_cast<int>(G_.rows()); }
  /// d, the number of columns of G (rank(G W Gᵀ) ≤ d).
  int inner_size() const { return static_cast<int>(G_.cols()); }

  /// out = M z.
  void Multiply(const VectorX& z, VectorX* out) const;
  /// out = M(:, j), dense.
  void Column(int j, VectorX* out) const;
  /// out = M(i, :)ᵀ, dense.
  void Row(int i, VectorX* out) const;
  /// out += Σ_p coef[p] · M(:, cols[p]); `u` is scratch of size d.
  void AddColumns(const std::vector<int>& cols, const double* coef, VectorX* out, VectorX* u) const;
  /// The largest |M_ij| bound max(max_i M_ii, max |K_ij|) (M_ii ≥ |M_ij| for the
  /// PSD part), used to scale tolerances.
  double MagnitudeBound() const { return magnitude_; }
  /// The dense M (for small problems, tests and diagnostics).
  MatrixX ToDense() const;

 private:
  SparseMatrixX G_;   // n × d
  SparseMatrixX Y_;   // d × n, W Gᵀ: column j is the motion of unit z_j
  SparseMatrixX K_;   // n × n
  SparseMatrixX Kt_;  // Kᵀ, for rows of K
  double magnitude_ = 0;
};

/// The natural-map residual max_i |min(z_i, (M z + q)_i)|.
double LcpResidual(const FactoredLcpMatrix& M, const VectorX& q, const VectorX& z);

/// IsLcpSolution for a factored M.
bool IsLcpSolution(const FactoredLcpMatrix& M, const VectorX& q, const VectorX& z, double tol);

/// Solves LCP(M, q) by Lemke's method on the factored M, with the perturbation
/// tie-breaking and warm start described in the file comment. Same contract as
/// SolveLemke: kSolved/kTrivial answers pass IsLcpSolution(M, q, z,
/// solution_tolerance · max(1, ‖q‖∞)); `basis` is returned for a later warm
/// start; `pivots` counts the pivots of every attempt.
/// @throws std::invalid_argument if q's size is not M.size() or q is not finite.
LcpResult SolveLemkeFactored(const FactoredLcpMatrix& M, const VectorX& q,
                             const LemkeParameters& params = {},
                             const LcpBasis* warm_start = nullptr);

}  // namespace cairn

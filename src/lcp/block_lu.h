#pragma once
// An updated LU factorisation of a basis matrix whose rows and columns are
// exchanged one at a time: the block-LU (Schur-complement) update of Bisschop
// and Meeraus, as used by active-set QP solvers (Gill, Murray, Saunders and
// Wright, "A Schur-complement method for sparse quadratic programming",
// 1990). Lemke's method on the factored LCP (factored_lcp.cpp) keeps its
// reduced basis C = A(R, Z) this way instead of an explicit inverse.
//
// The mathematics. A is a fixed matrix given by its rows and columns
// (Entries). At the last Factor, C₀ = A(R₀, Z₀) was factored, P C₀ = L U.
// Since then rows and columns have joined and left R and Z. The current
// system C x = b is the bordered system
//
//     [ C₀  V ] [x₀]   [b₀]       V = [A(R₀, Z⁺)  E_{R⁻}],
//     [ Uᵀ  D ] [y ] = [c ],      Uᵀ = [A(R⁺, Z₀); E_{Z⁻}ᵀ],
//                                 D = [A(R⁺, Z⁺) 0; 0 0],
//
// with Z⁺ the columns added since (their unknowns are part of y), R⁻ the rows
// of R₀ that left (a free slack in y absorbs each one's equation, whose b₀ is
// 0), R⁺ the rows added (their equations are rows of Uᵀ, right-hand side in
// c) and Z⁻ the columns of Z₀ that left (the row e_pᵀ of Uᵀ with c = 0 holds
// their unknown at 0). |Z⁺| + |R⁻| = |R⁺| + |Z⁻| = m whenever C is square.
// Eliminating x₀ leaves the m × m Schur complement S = D − Uᵀ C₀⁻¹ V:
//
//     x̂ = C₀⁻¹ b₀,   S y = c − Uᵀ x̂,   x₀ = x̂ − W y   (W = C₀⁻¹ V),
//
// and C is nonsingular exactly when S is (det C = ± det C₀ det S). Each
// border column costs one solve with C₀ (its column of W, kept) and one new
// column of S (m dot products of length k₀); each border row one new row of S.
// A solve costs one solve with C₀, O(k₀ m) and a solve with S. S is
// refactored (dense LU, O(m³)) after each exchange; the caller refactors C₀
// when m grows past MaxBorder(k) (where the refactor O(k³) and the S
// factorisations balance, at most 64: measured) or when the solutions drift.
//
// C₀ itself is factored densely (partial pivoting), or, when it is large and
// sparse (the loading LCP's basis, whose matrix is the bodies' skew coupling
// and the contacts' blocks: a few entries a column), by a sparse LU with a
// fill-reducing column order (Eigen's SparseLU: COLAMD, supernodes, partial
// pivoting), whose factors and solves cost about nnz(L + U) rather than k³
// and k².
//
// Unlike an explicit inverse updated by Sherman–Morrison, the factors of C₀
// are never modified, so rounding does not accumulate in them from pivot to
// pivot: the error of a solve is that of C₀'s LU and of S's, both backward
// stable with partial pivoting as long as S is not nearly singular.
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <vector>

#include "cairn/core/types.h"

namespace cairn::lcp_internal {

// The matrix A, by whole rows and columns. Column keys are 0 … num_cols − 1.
class Entries {
 public:
  virtual ~Entries() = default;
  virtual int num_rows() const = 0;
  virtual int num_cols() const = 0;
  // Column `key` of A (length num_rows).
  virtual void Column(int key, VectorX* out) const = 0;
  // Row `row` of A (length num_cols).
  virtual void Row(int row, VectorX* out) const = 0;
};

class BlockLu {
 public:
  explicit BlockLu(const Entries& a) : a_(a) {}

  // Factors C₀ = A(rows, cols) (square; positions as given) and clears the
  // border. False when C₀ is singular to working precision.
  bool Factor(const std::vector<int>& rows, const std::vector<int>& cols);

  // Exchanges, by key: a column or row joining or leaving the basis. Call
  // Finish after the exchanges of one pivot (the border must be square).
  void AddColumn(int key);
  void RemoveColumn(int key);
  void AddRow(int row);
  void RemoveRow(int row);
  // Factors S. False when it is singular (then so is C: refactor or give up).
  bool Finish();

  // Solves C x = b, where C(s, p) = A(rows[s], cols[p]) for the caller's
  // current positions (the rows and columns Factor and the exchanges left).
  void Solve(const std::vector<int>& rows, const std::vector<int>& cols, const VectorX& b,
             VectorX* x);

  // Whether the last Factor factored C₀ sparse.
  bool sparse() const { return sparse0_; }
  // The order m of the border (of S).
  int border() const { return static_cast<int>(border_cols_.size()); }
  // The border size past which a refactor of C₀ is cheaper than going on.
  static int MaxBorder(int k);

 private:
  // A border column: an added column of A (key ≥ 0) or the slack of the row
  // of R₀ at position s0 (key = −1 − s0). A border row: an added row of A
  // (key ≥ 0) or the constraint holding the column of Z₀ at position p0 at 0
  // (key = −1 − p0).
  void PushBorderColumn(int key);
  void PushBorderRow(int key);
  void EraseBorderColumn(int index);
  void EraseBorderRow(int index);
  int FindBorderColumn(int key) const;
  int FindBorderRow(int key) const;

  const Entries& a_;
  std::vector<int> rows0_, cols0_;      // R₀, Z₀ by position in C₀
  std::vector<int> row0_of_, col0_of_;  // key → position in R₀ / Z₀, or −1
  // C₀'s factors: dense, or sparse (sparse0_) when FactorSparse chose it.
  bool FactorSparse(const MatrixX& c0);
  VectorX Solve0(const VectorX& b) const;
  bool sparse0_ = false;
  Eigen::PartialPivLU<MatrixX> lu0_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> sparse_lu0_;
  std::vector<int> border_cols_, border_rows_;  // keys as above
  std::vector<VectorX> w_;                      // W(:, j) = C₀⁻¹ V(:, j)
  std::vector<VectorX> ut_;                     // Uᵀ(r, :), length k₀
  MatrixX s_;                                   // S, border rows × border columns
  Eigen::PartialPivLU<MatrixX> lu_s_;
  VectorX line_, b0_, c_, y_;                // scratch
  std::vector<int> row_at_, border_col_of_;  // scratch: row → position, column → border index
};

}  // namespace cairn::lcp_internal

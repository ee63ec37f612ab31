#pragma once
/// @file
/// Lemke's complementary pivoting method for the linear complementarity
/// problem LCP(M, q):
///
///     find z ∈ ℝⁿ  with  w = M z + q,  z ≥ 0,  w ≥ 0,  zᵀ w = 0.
///
/// Lemke's method [Cottle, Pang & Stone 1992, §4.4] augments the problem with
/// an artificial variable z₀ and covering vector d = e (all ones):
/// w = M z + q + d z₀. Starting from the almost-complementary basis in which z₀
/// enters at the level −min(q), it pivots along the path of almost
/// complementary bases until z₀ leaves (a solution) or the entering column has
/// no positive entry (a secondary ray). Ties in the ratio test are broken by
/// the lexicographic rule [CPS 1992, §4.9], which makes the method finite on
/// degenerate problems (e.g. the cycling circulant matrix).
///
/// Termination guarantees [CPS 1992, Thm 4.4.13]: for M copositive-plus (PSD
/// matrices: the frictionless contact LCP) ray termination proves that
/// LCP(M, q) has no solution. The Stewart–Trinkle friction LCP is copositive
/// but not copositive-plus in general (zᵀMz = 0 allows λ > 0 with p_n = 0);
/// for it Stewart & Trinkle (1996) prove that Lemke's method processes the
/// LCP whenever q has the physical structure the mechanics stage builds. For
/// P-matrices the method always finds the unique solution.
///
/// Numerical robustness: after the last pivot the basic system is re-solved
/// from the original data (LU with partial pivoting and one step of iterative
/// refinement), which repairs the drift of the pivoted tableau on
/// ill-conditioned problems (Siconos' FC2D_SliderCrankLagrangian00001).
///
/// Warm start: given the basis of a previous solve, the solver first tries that
/// basis (one LU factorisation); if it is complementary and feasible for the new
/// q and M, no pivot is made. Otherwise it falls back to a cold start.

#include <string>
#include <vector>

#include "cairn/core/types.h"

namespace cairn {

/// How a solve ended.
enum class LcpStatus {
  kSolved,            ///< z solves the LCP (verified by the natural-map residual).
  kTrivial,           ///< q ≥ 0: z = 0 solves it, with zero pivots.
  kRayTermination,    ///< Lemke stopped on a secondary ray (no solution found).
  kPivotLimit,        ///< The pivot limit was reached.
  kNumericalFailure,  ///< Lost accuracy: the final basis did not give a solution.
};

/// "solved", "trivial", "ray termination", "pivot limit", "numerical failure".
const char* to_string(LcpStatus status);

/// Parameters of SolveLemke.
struct LemkeParameters {
  /// Largest number of pivots; ≤ 0 means max(1000, 50 (n + 1)).
  int max_pivots = 0;
  /// A pivot element or ratio-test entry of magnitude ≤ this is zero
  /// (dimensionless, relative to the largest |entry| of [M q]); ≤ 0 means
  /// n · 2⁻⁵² · 16.
  double pivot_tolerance = 0.0;
  /// Tolerance of the solution check, relative to max(1, ‖q‖∞): a returned z
  /// with status kSolved satisfies IsLcpSolution(M, q, z, solution_tolerance ·
  /// max(1, ‖q‖∞)).
  double solution_tolerance = 1e-8;
  /// Whether a secondary ray sends the solve on to its other paths (the
  /// perturbed ones) before it is reported. On degenerate contact LCPs a
  /// perturbed path can end on a ray when a solution exists (factored_lcp.h),
  /// so without the retries a ray only says "no solution found on the first
  /// path": for callers that may answer conservatively.
  bool retry_after_ray = true;
};

/// A complementary basis: basic_z[i] is true when z_i is basic (so w_i = 0),
/// false when w_i is basic (so z_i = 0). Empty means "no basis".
struct LcpBasis {
  std::vector<bool> basic_z;
};

/// The outcome of a solve. On kSolved/kTrivial, z and w = M z + q hold the
/// solution; on any other status they hold the last iterate (or are empty) and
/// must not be used as a solution.
struct LcpResult {
  LcpStatus status = LcpStatus::kNumericalFailure;
  VectorX z;                     ///< (n) the solution.
  VectorX w;                     ///< (n) w = M z + q, recomputed from the data.
  int pivots = 0;                ///< Pivots made, including the one in which z₀ enters.
  double residual = 0.0;         ///< max_i |min(z_i, w_i)|, the natural-map residual.
  bool warm_start_used = false;  ///< The warm-start basis solved it with 0 pivots.
  LcpBasis basis;                ///< The final complementary basis (for a later warm start).
  std::string message;           ///< Diagnostics for a failure (empty on success).
};

/// Solves LCP(M, q) by Lemke's method with the lexicographic ratio test.
/// `warm_start`, when non-null and of size n, is tried first.
/// @throws std::invalid_argument if M is not n × n with n = q.size(), or if M
///         or q has a NaN or infinite entry.
LcpResult SolveLemke(const MatrixX& M, const VectorX& q, const LemkeParameters& params = {},
                     const LcpBasis* warm_start = nullptr);

/// The natural-map residual max_i |min(z_i, w_i)| of z and w = M z + q, both
/// given (0 for n = 0): the one measure of an LCP answer every solver and
/// check reports.
double NaturalMapResidual(const VectorX& z, const VectorX& w);

/// The natural-map residual max_i |min(z_i, (M z + q)_i)| (0 for n = 0).
double LcpResidual(const MatrixX& M, const VectorX& q, const VectorX& z);

/// True when z solves LCP(M, q) to within `tol`: z ≥ −tol, w = M z + q ≥ −tol,
/// and |z_i w_i| ≤ tol · max(1, |z_i|, |w_i|) for every i. Independent of the
/// solver, it re-checks any answer.
bool IsLcpSolution(const MatrixX& M, const VectorX& q, const VectorX& z, double tol);

/// IsLcpSolution with w = M z + q already computed: z ≥ −tol, w ≥ −tol and
/// |z_i w_i| ≤ tol · max(1, |z_i|, |w_i|).
bool IsComplementarySolution(const VectorX& z, const VectorX& w, double tol);

}  // namespace cairn

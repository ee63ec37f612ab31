// Tests of SolveLemke: classic problems with known answers and pivot counts,
// failure statuses, warm start, and agreement with a brute-force enumeration
// of all complementary bases on hundreds of seeded random problems.
#include "cairn/lcp/lemke.h"

#include <gtest/gtest.h>

#include <Eigen/LU>  // IWYU pragma: keep
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace cairn {
namespace {

// Murty's (1978) problem, lower-triangular form: M_ii = 1, M_ij = 2 (i > j),
// q_i = −Σ_{j = n−i+1..n} 2^j (1-based). Unique solution 2^n e_1; Lemke with
// covering vector e makes exactly 2^n pivots.
void Murty(int n, MatrixX* M, VectorX* q) {
  *M = MatrixX::Zero(n, n);
  *q = VectorX::Zero(n);
  for (int i = 0; i < n; ++i) {
    (*M)(i, i) = 1.0;
    for (int j = 0; j < i; ++j) (*M)(i, j) = 2.0;
    for (int j = n - i; j <= n; ++j) (*q)[i] -= std::ldexp(1.0, j);
  }
}

// Fathi's (1979) problem: m_ii = 1 + 4(n − i), m_ij = 2 + 4(n − max(i, j))
// (1-based), q = −e. Symmetric PD; unique solution e_n in 2 Lemke pivots.
void Fathi(int n, MatrixX* M, VectorX* q) {
  M->resize(n, n);
  for (int i = 1; i <= n; ++i) {
    for (int j = 1; j <= n; ++j) {
      (*M)(i - 1, j - 1) = i == j ? 1.0 + 4.0 * (n - i) : 2.0 + 4.0 * (n - std::max(i, j));
    }
  }
  *q = -VectorX::Ones(n);
}

// The degenerate cycling circulant (a P-matrix) with q = −e.
MatrixX Circulant() {
  MatrixX M(3, 3);
  M << 1, 2, 0, 0, 1, 2, 2, 0, 1;
  return M;
}

double Tol(const VectorX& q) { return 1e-8 * std::max(1.0, q.cwiseAbs().maxCoeff()); }

TEST(Lemke, CyclingCirculantIsSolvedByTheLexicographicRule) {
  const MatrixX M = Circulant();
  const VectorX q = -VectorX::Ones(3);
  const LcpResult r = SolveLemke(M, q);
  ASSERT_EQ(r.status, LcpStatus::kSolved) << r.message;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.z[i], 1.0 / 3.0, 1e-14);
  EXPECT_NEAR(r.w.cwiseAbs().maxCoeff(), 0.0, 1e-14);
  EXPECT_TRUE(IsLcpSolution(M, q, r.z, Tol(q)));
  EXPECT_TRUE(r.message.empty());
  EXPECT_EQ(r.basis.basic_z, std::vector<bool>({true, true, true}));
}

TEST(Lemke, CottlePsdTieBreaking) {
  // M = ones(2) (symmetric PSD, singular), q = −e: both rows tie in the first
  // ratio test; every z ≥ 0 with z1 + z2 = 1 solves it, w = 0.
  const MatrixX M = MatrixX::Ones(2, 2);
  const VectorX q = -VectorX::Ones(2);
  const LcpResult r = SolveLemke(M, q);
  ASSERT_EQ(r.status, LcpStatus::kSolved) << r.message;
  EXPECT_NEAR(r.z.sum(), 1.0, 1e-14);
  EXPECT_GE(r.z.minCoeff(), 0.0);
  EXPECT_NEAR(r.w.cwiseAbs().maxCoeff(), 0.0, 1e-14);
  EXPECT_EQ(r.pivots, 2);
}

TEST(Lemke, MurtyNeedsExactly2ToTheNPivots) {
  for (int n : {4, 6, 8}) {
    MatrixX M;
    VectorX q;
    Murty(n, &M, &q);
    const LcpResult r = SolveLemke(M, q);
    ASSERT_EQ(r.status, LcpStatus::kSolved) << "n = " << n << ": " << r.message;
    EXPECT_EQ(r.pivots, 1 << n) << "n = " << n;
    VectorX expected = VectorX::Zero(n);
    expected[0] = std::ldexp(1.0, n);
    EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-12) << "n = " << n;
    // w = (0, 2^(n−1), ..., 2).
    for (int i = 1; i < n; ++i) EXPECT_NEAR(r.w[i], std::ldexp(1.0, n - i), 1e-12);
  }
}

TEST(Lemke, FathiTakesTwoPivots) {
  for (int n : {4, 8, 12}) {
    MatrixX M;
    VectorX q;
    Fathi(n, &M, &q);
    const LcpResult r = SolveLemke(M, q);
    ASSERT_EQ(r.status, LcpStatus::kSolved) << r.message;
    EXPECT_EQ(r.pivots, 2);
    VectorX expected = VectorX::Zero(n);
    expected[n - 1] = 1.0;
    EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_NEAR(r.w.head(n - 1).minCoeff(), 1.0, 1e-12);
  }
}

TEST(Lemke, EmptyProblemIsTrivial) {
  const LcpResult r = SolveLemke(MatrixX(0, 0), VectorX(0));
  EXPECT_EQ(r.status, LcpStatus::kTrivial);
  EXPECT_EQ(r.z.size(), 0);
  EXPECT_EQ(r.pivots, 0);
  EXPECT_EQ(LcpResidual(MatrixX(0, 0), VectorX(0), VectorX(0)), 0.0);
}

TEST(Lemke, NonnegativeQIsTrivialWithZeroPivots) {
  MatrixX M(2, 2);
  M << -1, 3, 2, -5;  // Any M: z = 0 solves it.
  const VectorX q = (VectorX(2) << 0.0, 2.0).finished();
  const LcpResult r = SolveLemke(M, q);
  EXPECT_EQ(r.status, LcpStatus::kTrivial);
  EXPECT_EQ(r.pivots, 0);
  EXPECT_EQ(r.z, VectorX::Zero(2));
  EXPECT_EQ(r.w, q);
  EXPECT_EQ(r.basis.basic_z, std::vector<bool>({false, false}));
}

TEST(Lemke, InfeasibleProblemsEndOnARay) {
  // M = 0, q = (−1, 1): w1 = −1 whatever z.
  const LcpResult r0 = SolveLemke(MatrixX::Zero(2, 2), (VectorX(2) << -1, 1).finished());
  EXPECT_EQ(r0.status, LcpStatus::kRayTermination);
  EXPECT_FALSE(r0.message.empty());
  // M = [[1, −1], [−1, 1]] (PSD), q = −e: w1 + w2 = −2 < 0.
  MatrixX M(2, 2);
  M << 1, -1, -1, 1;
  const LcpResult r1 = SolveLemke(M, -VectorX::Ones(2));
  EXPECT_EQ(r1.status, LcpStatus::kRayTermination);
  // M = −1, q = −1 (n = 1).
  const LcpResult r2 = SolveLemke(-MatrixX::Ones(1, 1), -VectorX::Ones(1));
  EXPECT_EQ(r2.status, LcpStatus::kRayTermination);
}

TEST(Lemke, PivotLimitIsReported) {
  MatrixX M;
  VectorX q;
  Murty(6, &M, &q);  // Needs 64 pivots.
  LemkeParameters params;
  params.max_pivots = 10;
  const LcpResult r = SolveLemke(M, q, params);
  EXPECT_EQ(r.status, LcpStatus::kPivotLimit);
  EXPECT_EQ(r.pivots, 10);
  params.max_pivots = 64;  // Exactly enough.
  EXPECT_EQ(SolveLemke(M, q, params).status, LcpStatus::kSolved);
  params.max_pivots = 63;
  EXPECT_EQ(SolveLemke(M, q, params).status, LcpStatus::kPivotLimit);
}

TEST(Lemke, InvalidInputThrows) {
  EXPECT_THROW(SolveLemke(MatrixX::Identity(2, 2), VectorX::Ones(3)), std::invalid_argument);
  EXPECT_THROW(SolveLemke(MatrixX::Identity(2, 3), VectorX::Ones(2)), std::invalid_argument);
  MatrixX M = MatrixX::Identity(2, 2);
  M(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SolveLemke(M, -VectorX::Ones(2)), std::invalid_argument);
  VectorX q = -VectorX::Ones(2);
  q[1] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(SolveLemke(MatrixX::Identity(2, 2), q), std::invalid_argument);
  // Also with a warm start, which is tried before the input check: a NaN off
  // the basis (M(0, 1), z_1 = 0) or an infinite q still makes it throw.
  for (const auto& flags : {std::vector<bool>{true, false}, std::vector<bool>{true, true},
                            std::vector<bool>{false, false}}) {
    const LcpBasis basis{flags};
    EXPECT_THROW(SolveLemke(M, -VectorX::Ones(2), {}, &basis), std::invalid_argument);
    EXPECT_THROW(SolveLemke(MatrixX::Identity(2, 2), q, {}, &basis), std::invalid_argument);
  }
}

TEST(Lemke, StatusNames) {
  EXPECT_STREQ(to_string(LcpStatus::kSolved), "solved");
  EXPECT_STREQ(to_string(LcpStatus::kTrivial), "trivial");
  EXPECT_STREQ(to_string(LcpStatus::kRayTermination), "ray termination");
  EXPECT_STREQ(to_string(LcpStatus::kPivotLimit), "pivot limit");
  EXPECT_STREQ(to_string(LcpStatus::kNumericalFailure), "numerical failure");
}

TEST(Lemke, IsLcpSolutionRejectsWrongAnswers) {
  const MatrixX M = Circulant();
  const VectorX q = -VectorX::Ones(3);
  const VectorX good = VectorX::Constant(3, 1.0 / 3.0);
  EXPECT_TRUE(IsLcpSolution(M, q, good, 1e-12));
  EXPECT_LE(LcpResidual(M, q, good), 1e-15);
  // w = (0, −1, 1): infeasible w.
  EXPECT_FALSE(IsLcpSolution(M, q, (VectorX(3) << 1, 0, 0).finished(), 1e-8));
  // z = (1, 1, 1) gives w = (2, 2, 2): feasible but not complementary.
  EXPECT_FALSE(IsLcpSolution(M, q, VectorX::Ones(3), 1e-8));
  EXPECT_NEAR(LcpResidual(M, q, VectorX::Ones(3)), 1.0, 1e-15);
  // Negative z.
  EXPECT_FALSE(IsLcpSolution(MatrixX::Identity(1, 1), VectorX::Ones(1), -VectorX::Ones(1), 1e-8));
  // Wrong size and NaN.
  EXPECT_FALSE(IsLcpSolution(M, q, VectorX::Ones(2), 1e-8));
  VectorX nan = good;
  nan[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(IsLcpSolution(M, q, nan, 1e-8));
  // A small violation is accepted or rejected by the tolerance.
  const VectorX near = good + VectorX::Constant(3, 1e-6);
  EXPECT_FALSE(IsLcpSolution(M, q, near, 1e-8));
  EXPECT_TRUE(IsLcpSolution(M, q, near, 1e-4));
}

// A seeded P-matrix: BᵀB + I plus a skew-symmetric part (positive definite).
MatrixX RandomPd(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixX B(n, n), S(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      B(i, j) = u(rng);
      S(i, j) = u(rng);
    }
  }
  return B.transpose() * B + MatrixX::Identity(n, n) + (S - S.transpose());
}

VectorX RandomQ(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VectorX q(n);
  for (int i = 0; i < n; ++i) q[i] = u(rng);
  return q;
}

TEST(Lemke, WarmStartFromThePreviousBasisMakesNoPivot) {
  std::mt19937 rng(11);
  const int n = 8;
  const MatrixX M = RandomPd(n, rng);
  const VectorX q = RandomQ(n, rng);
  const LcpResult cold = SolveLemke(M, q);
  ASSERT_EQ(cold.status, LcpStatus::kSolved);
  ASSERT_GT(cold.pivots, 1);
  // Perturb q and M slightly; the optimal basis does not change.
  const VectorX q2 = q + 1e-9 * RandomQ(n, rng);
  MatrixX M2 = M;
  M2(0, 0) += 1e-9;
  const LcpResult warm = SolveLemke(M2, q2, {}, &cold.basis);
  ASSERT_EQ(warm.status, LcpStatus::kSolved);
  EXPECT_TRUE(warm.warm_start_used);
  EXPECT_EQ(warm.pivots, 0);
  EXPECT_EQ(warm.basis.basic_z, cold.basis.basic_z);
  const LcpResult reference = SolveLemke(M2, q2);
  EXPECT_LE((warm.z - reference.z).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE(IsLcpSolution(M2, q2, warm.z, Tol(q2)));
}

TEST(Lemke, WarmStartFromAWrongBasisStillSolves) {
  std::mt19937 rng(12);
  const int n = 8;
  const MatrixX M = RandomPd(n, rng);
  const VectorX q = RandomQ(n, rng);
  const LcpResult cold = SolveLemke(M, q);
  ASSERT_EQ(cold.status, LcpStatus::kSolved);
  LcpBasis wrong = cold.basis;
  for (size_t i = 0; i < wrong.basic_z.size(); ++i) wrong.basic_z[i] = !wrong.basic_z[i];
  const LcpResult r = SolveLemke(M, q, {}, &wrong);
  ASSERT_EQ(r.status, LcpStatus::kSolved);
  EXPECT_FALSE(r.warm_start_used);
  EXPECT_EQ(r.pivots, cold.pivots);
  EXPECT_LE((r.z - cold.z).cwiseAbs().maxCoeff(), 1e-12);
  // A basis of the wrong size is ignored.
  LcpBasis short_basis;
  short_basis.basic_z.assign(3, true);
  const LcpResult r2 = SolveLemke(M, q, {}, &short_basis);
  EXPECT_EQ(r2.status, LcpStatus::kSolved);
  EXPECT_FALSE(r2.warm_start_used);
}

TEST(Lemke, DeterministicBitForBit) {
  std::mt19937 rng(13);
  const MatrixX M = RandomPd(10, rng);
  const VectorX q = RandomQ(10, rng);
  const LcpResult a = SolveLemke(M, q);
  const LcpResult b = SolveLemke(M, q);
  ASSERT_EQ(a.status, LcpStatus::kSolved);
  EXPECT_EQ(a.pivots, b.pivots);
  ASSERT_EQ(a.z.size(), b.z.size());
  for (int i = 0; i < a.z.size(); ++i) EXPECT_EQ(a.z[i], b.z[i]);  // Bit-identical.
  EXPECT_EQ(a.basis.basic_z, b.basis.basic_z);
}

// All solutions at nonsingular complementary bases: for each subset α,
// M_αα z_α = −q_α, z ≥ 0, w ≥ 0 (to 1e-9).
std::vector<VectorX> EnumerateSolutions(const MatrixX& M, const VectorX& q) {
  const int n = static_cast<int>(q.size());
  std::vector<VectorX> solutions;
  for (unsigned mask = 0; mask < (1u << n); ++mask) {
    std::vector<int> alpha;
    for (int i = 0; i < n; ++i) {
      if (mask & (1u << i)) alpha.push_back(i);
    }
    VectorX z = VectorX::Zero(n);
    if (!alpha.empty()) {
      const MatrixX M_aa = M(alpha, alpha);
      const Eigen::FullPivLU<MatrixX> lu(M_aa);
      if (!lu.isInvertible()) continue;
      const VectorX rhs = -q(alpha);
      z(alpha) = lu.solve(rhs);
    }
    const VectorX w = M * z + q;
    if (z.minCoeff() >= -1e-9 && w.minCoeff() >= -1e-9) solutions.push_back(z);
  }
  return solutions;
}

bool IsSolved(const LcpResult& r) {
  return r.status == LcpStatus::kSolved || r.status == LcpStatus::kTrivial;
}

// Hundreds of seeded random problems, n ≤ 10, checked against enumeration:
//  - P-matrices (PD with skew part, and diagonally dominant): the unique
//    solution must match;
//  - symmetric PSD (rank-deficient too): solvable ⇔ Lemke solves (Lemke's ray
//    proves infeasibility for copositive-plus M), and w is unique;
//  - monotone (PSD plus skew): solvable ⇔ Lemke solves.
TEST(Lemke, AgreesWithBruteForceEnumeration) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int solved = 0, rays = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + trial % 10;
    const int kind = (trial / 10) % 4;
    MatrixX M;
    if (kind == 0) {
      M = RandomPd(n, rng);
    } else if (kind == 1) {
      // Strictly diagonally dominant with a positive diagonal: a P-matrix.
      M.resize(n, n);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) M(i, j) = u(rng);
        M(i, i) = M.row(i).cwiseAbs().sum() + 0.1;
      }
    } else {
      // BᵀB with B of rank k ≤ n (rank-deficient when k < n).
      const int k = 1 + static_cast<int>(rng() % static_cast<unsigned>(n));
      MatrixX B(k, n);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < k; ++i) B(i, j) = u(rng);
      }
      M = B.transpose() * B;
      if (kind == 3) {
        MatrixX S(n, n);
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) S(i, j) = u(rng);
        }
        M += S - S.transpose();
      }
    }
    const VectorX q = RandomQ(n, rng);
    const auto solutions = EnumerateSolutions(M, q);
    const LcpResult r = SolveLemke(M, q);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", kind " + std::to_string(kind) + ", n " +
                 std::to_string(n));
    if (kind <= 1) {
      ASSERT_EQ(solutions.size(), 1u);
      ASSERT_TRUE(IsSolved(r)) << to_string(r.status) << " " << r.message;
      EXPECT_LE((r.z - solutions[0]).cwiseAbs().maxCoeff(), 1e-8);
    } else if (!solutions.empty()) {
      ASSERT_TRUE(IsSolved(r)) << to_string(r.status) << " " << r.message;
      EXPECT_TRUE(IsLcpSolution(M, q, r.z, Tol(q)));
      if (kind == 2) {
        const VectorX w_ref = M * solutions[0] + q;
        EXPECT_LE((r.w - w_ref).cwiseAbs().maxCoeff(), 1e-7);
      }
    } else {
      // Copositive-plus and no solution at any basis: Lemke must not solve.
      EXPECT_EQ(r.status, LcpStatus::kRayTermination);
    }
    if (IsSolved(r)) {
      EXPECT_TRUE(IsLcpSolution(M, q, r.z, Tol(q)));
      ++solved;
    } else {
      ++rays;
    }
  }
  // The mix must exercise both outcomes.
  EXPECT_GT(solved, 200);
  EXPECT_GT(rays, 0);
}

}  // namespace
}  // namespace cairn

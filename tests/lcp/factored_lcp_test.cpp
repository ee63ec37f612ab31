// Tests of SolveLemkeFactored (Lemke on M = G W Gᵀ + K): agreement with the
// dense solver and with the LCP's own conditions on seeded random contact-like
// problems with far more rows than rank (the degenerate case it exists for),
// rays, warm starts from right and wrong bases, determinism.
#include "cairn/lcp/factored_lcp.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

namespace cairn {
namespace {

double ResidualTol(const VectorX& q) { return 1e-8 * std::max(1.0, q.cwiseAbs().maxCoeff()); }

// A random contact-like problem: `rows` rows of G, each touching one or two of
// `bodies` bodies with 3 coordinates each; W block-diagonal SPD. With
// `friction`, every group of 3 rows (n, +t, −t) gets a λ row and the
// Stewart–Trinkle K blocks (E, μ, −Eᵀ), as in the mechanics stage, and q is
// physical (below); else q is built around a known, partly degenerate solution.
struct Problem {
  FactoredLcpMatrix M;
  MatrixX dense;
  VectorX q;
};
Problem RandomContactProblem(int contacts, int bodies, bool friction, unsigned seed,
                             double degenerate_fraction) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> body(0, bodies - 1);
  const int rows = friction ? 3 * contacts : contacts;
  const int n = friction ? 4 * contacts : contacts;
  std::vector<Eigen::Triplet<double>> g, w, k;
  for (int c = 0; c < contacts; ++c) {
    const int a = body(rng), b = body(rng);
    Eigen::Vector3d ga(u(rng), u(rng), u(rng)), gb(u(rng), u(rng), u(rng));
    const int per = friction ? 3 : 1;
    for (int r = 0; r < per; ++r) {
      const double sign = r == 2 ? -1.0 : 1.0;
      const Eigen::Vector3d ra = r == 0 ? ga : sign * Eigen::Vector3d(-ga.y(), ga.x(), ga.z());
      const Eigen::Vector3d rb = r == 0 ? gb : sign * Eigen::Vector3d(-gb.y(), gb.x(), gb.z());
      for (int i = 0; i < 3; ++i) {
        g.emplace_back(per * c + r, 3 * a + i, ra[i]);
        if (b != a) g.emplace_back(per * c + r, 3 * b + i, -rb[i]);
      }
    }
    if (friction) {
      const int lam = rows + c;
      k.emplace_back(3 * c + 1, lam, 1.0);
      k.emplace_back(3 * c + 2, lam, 1.0);
      k.emplace_back(lam, 3 * c, 0.5);
      k.emplace_back(lam, 3 * c + 1, -1.0);
      k.emplace_back(lam, 3 * c + 2, -1.0);
    }
  }
  for (int b = 0; b < bodies; ++b) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A.data()[i] = u(rng);
    const Eigen::Matrix3d Wb = A * A.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) w.emplace_back(3 * b + i, 3 * b + j, Wb(i, j));
  }
  SparseMatrixX G(n, 3 * bodies), W(3 * bodies, 3 * bodies), K(n, n);
  G.setFromTriplets(g.begin(), g.end());
  W.setFromTriplets(w.begin(), w.end());
  K.setFromTriplets(k.begin(), k.end());
  Problem p{FactoredLcpMatrix(G, W, K), MatrixX(), VectorX()};
  p.dense = p.M.ToDense();
  std::uniform_real_distribution<double> unit(0, 1);
  if (friction) {
    // As in the mechanics stage: q = G ν (the rows' velocities under a free
    // motion ν), 0 in the λ rows; such a problem always has a solution
    // [Anitescu & Potra 1997] and Lemke's method finds it [Stewart & Trinkle
    // 1996].
    VectorX nu(3 * bodies);
    for (int i = 0; i < nu.size(); ++i) nu[i] = u(rng);
    p.q = G * nu;
    return p;
  }
  // q = w* − M z* with complementary z*, w* ≥ 0: solvable by construction;
  // `degenerate_fraction` of the indices get z* = w* = 0.
  VectorX z = VectorX::Zero(n), ws = VectorX::Zero(n);
  for (int i = 0; i < n; ++i) {
    if (unit(rng) < degenerate_fraction) continue;
    (unit(rng) < 0.5 ? z[i] : ws[i]) = unit(rng);
  }
  p.q = ws - p.dense * z;
  return p;
}

TEST(FactoredLcpMatrix, ProductsAgreeWithTheDenseMatrix) {
  const Problem p = RandomContactProblem(12, 4, true, 7, 0.0);
  const int n = p.M.size();
  ASSERT_EQ(n, 48);
  EXPECT_EQ(p.M.inner_size(), 12);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  VectorX z(n);
  for (int i = 0; i < n; ++i) z[i] = u(rng);
  VectorX mz;
  p.M.Multiply(z, &mz);
  EXPECT_LE((mz - p.dense * z).cwiseAbs().maxCoeff(), 1e-13);
  VectorX col, row;
  for (int j = 0; j < n; ++j) {
    p.M.Column(j, &col);
    p.M.Row(j, &row);
    EXPECT_LE((col - p.dense.col(j)).cwiseAbs().maxCoeff(), 1e-14) << j;
    EXPECT_LE((row - p.dense.row(j).transpose()).cwiseAbs().maxCoeff(), 1e-14) << j;
  }
  // The magnitude bound bounds every entry.
  EXPECT_GE(p.M.MagnitudeBound(), p.dense.cwiseAbs().maxCoeff() - 1e-14);
}

TEST(FactoredLemke, InvalidInputThrows) {
  const Problem p = RandomContactProblem(3, 2, false, 1, 0.0);
  EXPECT_THROW(SolveLemkeFactored(p.M, VectorX::Zero(2)), std::invalid_argument);
  VectorX q = p.q;
  q[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SolveLemkeFactored(p.M, q), std::invalid_argument);
  const SparseMatrixX G(3, 2), W(3, 3), K(3, 3);
  EXPECT_THROW(FactoredLcpMatrix(G, W, K), std::invalid_argument);
}

TEST(FactoredLemke, NonnegativeQIsTrivial) {
  const Problem p = RandomContactProblem(5, 2, false, 2, 0.0);
  const LcpResult r = SolveLemkeFactored(p.M, VectorX::Ones(5));
  EXPECT_EQ(r.status, LcpStatus::kTrivial);
  EXPECT_EQ(r.pivots, 0);
  EXPECT_EQ(r.z, VectorX::Zero(5));
}

// M = [1 −1; −1 1] = g gᵀ with q = (−1, −1): w₁ + w₂ = −2 for every z, so
// there is no solution; M is PSD, so Lemke must end on a ray, also when
// warm-started from any basis.
TEST(FactoredLemke, InfeasibleProblemEndsOnARayFromEveryStart) {
  SparseMatrixX G(2, 1), W(1, 1), K(2, 2);
  G.insert(0, 0) = 1;
  G.insert(1, 0) = -1;
  W.insert(0, 0) = 1;
  const FactoredLcpMatrix M(G, W, K);
  const VectorX q = -VectorX::Ones(2);
  EXPECT_EQ(SolveLemkeFactored(M, q).status, LcpStatus::kRayTermination);
  for (const auto& flags : {std::vector<bool>{true, false}, std::vector<bool>{false, true},
                            std::vector<bool>{true, true}}) {
    const LcpBasis basis{flags};
    EXPECT_EQ(SolveLemkeFactored(M, q, {}, &basis).status, LcpStatus::kRayTermination);
  }
}

// Frictionless (symmetric PSD) problems with 4–10 rows per body (1.3–3.3
// times more rows than the rank bound 3 × bodies), half of them degenerate: the factored solver
// solves every one, and w (unique for symmetric PSD M) agrees with the dense solver's wherever that
// one succeeds.
TEST(FactoredLemke, SolvesRedundantPsdProblemsAndAgreesWithTheDenseSolver) {
  int dense_solved = 0;
  for (unsigned seed = 0; seed < 60; ++seed) {
    const int bodies = 2 + static_cast<int>(seed % 5);
    const int contacts = (4 + static_cast<int>(seed % 7)) * bodies;
    const Problem p = RandomContactProblem(contacts, bodies, false, 100 + seed, 0.5);
    const LcpResult r = SolveLemkeFactored(p.M, p.q);
    ASSERT_EQ(r.status, LcpStatus::kSolved) << "seed " << seed << ": " << r.message;
    EXPECT_TRUE(IsLcpSolution(p.dense, p.q, r.z, ResidualTol(p.q))) << "seed " << seed;
    const LcpResult d = SolveLemke(p.dense, p.q);
    if (d.status != LcpStatus::kSolved) continue;
    ++dense_solved;
    EXPECT_LE((r.w - d.w).cwiseAbs().maxCoeff(), 1e-7 * std::max(1.0, p.q.cwiseAbs().maxCoeff()))
        << "seed " << seed;
  }
  EXPECT_GE(dense_solved, 30);
}

// Stewart–Trinkle-structured problems (nonsymmetric, copositive-plus).
TEST(FactoredLemke, SolvesRedundantFrictionProblems) {
  for (unsigned seed = 0; seed < 40; ++seed) {
    const int bodies = 2 + static_cast<int>(seed % 4);
    const Problem p = RandomContactProblem(5 * bodies, bodies, true, 500 + seed, 0.5);
    const LcpResult r = SolveLemkeFactored(p.M, p.q);
    ASSERT_EQ(r.status, LcpStatus::kSolved) << "seed " << seed << ": " << r.message;
    EXPECT_TRUE(IsLcpSolution(p.dense, p.q, r.z, ResidualTol(p.q))) << "seed " << seed;
    EXPECT_LE(LcpResidual(p.M, p.q, r.z), ResidualTol(p.q));
  }
}

TEST(FactoredLemke, WarmStartFromThePreviousBasisMakesNoPivot) {
  const Problem p = RandomContactProblem(60, 8, true, 11, 0.5);
  const LcpResult cold = SolveLemkeFactored(p.M, p.q);
  ASSERT_EQ(cold.status, LcpStatus::kSolved) << cold.message;
  ASSERT_GT(cold.pivots, 10);
  const LcpResult warm = SolveLemkeFactored(p.M, p.q, {}, &cold.basis);
  ASSERT_EQ(warm.status, LcpStatus::kSolved);
  EXPECT_TRUE(warm.warm_start_used);
  EXPECT_EQ(warm.pivots, 0);
  EXPECT_LE((warm.z - cold.z).cwiseAbs().maxCoeff(), 1e-9);
}

// After a change of q the old basis is infeasible: Lemke's path from it (not
// a cold restart) repairs it, in fewer pivots than a cold start.
TEST(FactoredLemke, WarmPathFromAnInfeasibleBasisIsShorterThanACold) {
  const Problem p = RandomContactProblem(60, 8, false, 12, 0.3);
  const LcpResult first = SolveLemkeFactored(p.M, p.q);
  ASSERT_EQ(first.status, LcpStatus::kSolved) << first.message;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  VectorX q2 = p.q;
  for (int i = 0; i < q2.size(); ++i) q2[i] += 0.05 * u(rng);
  const LcpResult cold = SolveLemkeFactored(p.M, q2);
  const LcpResult warm = SolveLemkeFactored(p.M, q2, {}, &first.basis);
  ASSERT_EQ(cold.status, LcpStatus::kSolved) << cold.message;
  ASSERT_EQ(warm.status, LcpStatus::kSolved) << warm.message;
  EXPECT_FALSE(warm.warm_start_used);
  EXPECT_TRUE(IsLcpSolution(p.dense, q2, warm.z, ResidualTol(q2)));
  EXPECT_LT(warm.pivots, cold.pivots);
}

TEST(FactoredLemke, WarmStartFromAWrongBasisStillSolves) {
  const Problem p = RandomContactProblem(30, 5, true, 13, 0.5);
  std::mt19937 rng(9);
  for (int trial = 0; trial < 10; ++trial) {
    LcpBasis wrong;
    for (int i = 0; i < p.M.size(); ++i) wrong.basic_z.push_back(rng() % 4 == 0);
    const LcpResult r = SolveLemkeFactored(p.M, p.q, {}, &wrong);
    ASSERT_EQ(r.status, LcpStatus::kSolved) << "trial " << trial << ": " << r.message;
    EXPECT_TRUE(IsLcpSolution(p.dense, p.q, r.z, ResidualTol(p.q)));
  }
}

TEST(FactoredLemke, DeterministicBitForBit) {
  const Problem p = RandomContactProblem(80, 10, true, 21, 0.5);
  const LcpResult a = SolveLemkeFactored(p.M, p.q);
  const LcpResult b = SolveLemkeFactored(p.M, p.q);
  ASSERT_EQ(a.status, LcpStatus::kSolved);
  EXPECT_EQ(a.pivots, b.pivots);
  EXPECT_EQ(a.basis.basic_z, b.basis.basic_z);
  for (int i = 0; i < a.z.size(); ++i) EXPECT_EQ(a.z[i], b.z[i]) << i;
}

}  // namespace
}  // namespace cairn

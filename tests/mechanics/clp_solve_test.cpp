// mechanics/clp_solve.h and cairn/mechanics/lp_policy.h: the one LP policy
// (which method first, by form and size) and Clp's statuses by name, on LPs
// whose answers are known.
#include "mechanics/clp_solve.h"

#include <gtest/gtest.h>

#include <coin/CoinPackedMatrix.hpp>
#include <string>
#include <vector>

namespace cairn {
namespace {

TEST(FirstLpMethod, TheThresholdsOfEachForm) {
  EXPECT_EQ(FirstLpMethod(LpForm::kFeasibility, kFeasibilityBarrierColumns - 1),
            LpMethod::kDualSimplex);
  EXPECT_EQ(FirstLpMethod(LpForm::kFeasibility, kFeasibilityBarrierColumns), LpMethod::kBarrier);
  EXPECT_EQ(FirstLpMethod(LpForm::kDeficit, kFeasibilityBarrierColumns), LpMethod::kBarrier);
  // The elastic LP's duals are the mechanism: a vertex, by crossover.
  EXPECT_EQ(FirstLpMethod(LpForm::kElastic, kFeasibilityBarrierColumns),
            LpMethod::kBarrierCrossover);
  EXPECT_EQ(FirstLpMethod(LpForm::kElastic, 10), LpMethod::kDualSimplex);
  EXPECT_EQ(FirstLpMethod(LpForm::kParametric, kParametricBarrierColumns - 1),
            LpMethod::kDualSimplex);
  EXPECT_EQ(FirstLpMethod(LpForm::kParametric, kParametricBarrierColumns), LpMethod::kBarrier);
  EXPECT_LT(kParametricBarrierColumns, kFeasibilityBarrierColumns);
  EXPECT_EQ(std::string(to_string(LpMethod::kDualSimplex)), "dual simplex");
  EXPECT_EQ(std::string(to_string(LpMethod::kBarrier)), "barrier");
}

// min cᵀx over {x ≥ 0 : A x = b} with a dense A (rows × cols, row-major).
void Load(ClpSimplex& lp, int rows, int cols, const std::vector<double>& A,
          const std::vector<double>& b, const std::vector<double>& c) {
  std::vector<int> r, k;
  std::vector<double> v;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      if (A[i * cols + j] != 0) r.push_back(i), k.push_back(j), v.push_back(A[i * cols + j]);
  const CoinPackedMatrix m(true, r.data(), k.data(), v.data(), static_cast<int>(v.size()));
  const std::vector<double> lo(cols, 0.0), hi(cols, COIN_DBL_MAX);
  lp.setLogLevel(0);
  lp.loadProblem(m, lo.data(), hi.data(), c.data(), b.data(), b.data());
}

// x₁ + x₂ = 1, min x₁ − 2 x₂: optimal at (0, 1), −2.
TEST(ClpSolve, AnOptimumByEitherMethodAndItsStatusNamed) {
  for (LpMethod m : {LpMethod::kDualSimplex, LpMethod::kBarrier, LpMethod::kBarrierCrossover}) {
    SCOPED_TRACE(to_string(m));
    ClpSimplex lp;
    Load(lp, 1, 2, {1, 1}, {1}, {1, -2});
    if (m == LpMethod::kDualSimplex) {
      EXPECT_EQ(std::string(clp::SolveBySimplex(lp)), "dual simplex");
    } else {
      clp::SolveByBarrier(lp, m);
    }
    ASSERT_EQ(clp::StatusOf(lp), clp::Status::kOptimal);
    EXPECT_NEAR(lp.objectiveValue(), -2.0, 1e-7);
    EXPECT_NEAR(lp.primalColumnSolution()[1], 1.0, 1e-7);
  }
}

// x₁ + x₂ = −1 has no x ≥ 0; min −x₁ over x₁ − x₂ = 0 has no end.
TEST(ClpSolve, InfeasibleAndUnboundedAreNamedAndNoFailureHidesThem) {
  ClpSimplex infeasible;
  Load(infeasible, 1, 2, {1, 1}, {-1}, {0, 0});
  EXPECT_EQ(std::string(clp::SolveBySimplex(infeasible)), "dual simplex");
  EXPECT_EQ(clp::StatusOf(infeasible), clp::Status::kPrimalInfeasible);
  const std::string message = clp::Failure("test LP", infeasible);
  EXPECT_EQ(message.rfind("Clp (test LP): primal infeasible (status 1, secondary ", 0), 0u)
      << message;
  ClpSimplex unbounded;
  Load(unbounded, 1, 2, {1, -1}, {0}, {-1, 0});
  clp::SolveBySimplex(unbounded);
  EXPECT_EQ(clp::StatusOf(unbounded), clp::Status::kDualInfeasible);
  EXPECT_NE(clp::Failure("test LP", unbounded).find("unbounded"), std::string::npos);
}

// An iteration budget that runs out is kStopped, not a failure of the method.
TEST(ClpSolve, ABudgetThatRunsOutIsStopped) {
  const int n = 30;
  std::vector<double> A(n * n, 0.0), b(n), c(n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j <= i; ++j) A[i * n + j] = 1.0;
    b[i] = i + 1;
  }
  ClpSimplex lp;
  Load(lp, n, n, A, b, c);
  lp.setMaximumIterations(1);
  EXPECT_EQ(std::string(clp::SolveBySimplex(lp)), "dual simplex");
  EXPECT_EQ(clp::StatusOf(lp), clp::Status::kStopped);
}

}  // namespace
}  // namespace cairn

// The factored Lemke on degenerate 3-D contact LCPs: components
// whose contacts are many coplanar points per interface, from the shared
// COMPAS data sets (skipped when absent). Regressions: before the Harris ratio
// test and the k/4 refactor schedule each of these ended on a secondary ray
// or a numerically singular basis (docs/benchmarks.md, "Degenerate contact
// LCPs").

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cairn/io/compas_reader.h"
#include "cairn/lcp/factored_lcp.h"
#include "cairn/stability/analyze.h"
#include "lcp/perturbation.h"

namespace cairn {
namespace {

TEST(Perturbation, GeometricMeanOfPivotAndSolutionTolerances) {
  // δ = √(τ ε): the same margin on both sides.
  const double tau = 16 * 3000 * 0x1.0p-52, eps = 1e-8;
  const double delta = internal::PerturbationSize(tau, eps);
  EXPECT_NEAR(delta / tau, eps / delta, 1e-9 * eps / delta);
  EXPECT_GT(delta / tau, 25.0);  // n = 3000: margin ≈ 30
  // No room (τ ≥ ε): a fixed margin over τ.
  EXPECT_DOUBLE_EQ(internal::PerturbationSize(1e-6, 1e-8), internal::kMinMargin * 1e-6);
}

TEST(Perturbation, WeightsAreInHalfOpenUnitHalfAndDeterministic) {
  for (uint64_t i = 0; i < 1000; ++i) {
    const double r = internal::PerturbationWeight(3, i);
    EXPECT_GE(r, 0.5);
    EXPECT_LT(r, 1.0);
    EXPECT_EQ(r, internal::PerturbationWeight(3, i));
  }
}

// The single component LCP of a compas_cra assembly with block "0" fixed.
std::vector<ContactLcp> CompasLcps(const std::string& file, double mu) {
  const std::string path = std::string(CAIRN_SHARED_DIR) + "/datasets/compas_cra/" + file;
  if (!std::filesystem::exists(path)) return {};
  CompasOptions options;
  options.friction = mu;
  CompasModel model = CompasToModel(ReadCompasAssembly(path), options, path);
  for (PartDef& p : model.def.parts) p.fixed = p.name == "0";
  const Assembly assembly = CreateCompasAssembly(model, path);
  StabilityOptions so;
  so.lcp_storage = LcpStorage::kFactored;
  return BuildComponentLcps(assembly, Configuration::Assembled(assembly), so);
}

class DegenerateCompasLcp : public ::testing::TestWithParam<std::pair<const char*, double>> {};

TEST_P(DegenerateCompasLcp, SolvedAndVerified) {
  const auto [file, mu] = GetParam();
  const std::vector<ContactLcp> lcps = CompasLcps(file, mu);
  if (lcps.empty()) GTEST_SKIP() << "shared/datasets/compas_cra/" << file << " not found";
  ASSERT_EQ(lcps.size(), 1u);
  const ContactLcp& lcp = lcps[0];
  // A large component, stored factored (after the hull reduction of its
  // patches: the snake keeps 174 of its 228 variables).
  ASSERT_GT(lcp.size(), kMaxDenseLcp);
  ASSERT_GT(lcp.factored.size(), 0);
  const LcpResult r = SolveLemkeFactored(lcp.factored, lcp.q);
  EXPECT_EQ(r.status, LcpStatus::kSolved) << r.message;
  EXPECT_TRUE(
      IsLcpSolution(lcp.factored, lcp.q, r.z, 1e-8 * std::max(1.0, lcp.q.cwiseAbs().maxCoeff())));
}

INSTANTIATE_TEST_SUITE_P(Issue13, DegenerateCompasLcp,
                         ::testing::Values(std::make_pair("shelf-stable.json", 0.28),
                                           std::make_pair("snake.json", 0.48),
                                           std::make_pair("shelf-s3.json", 0.84),
                                           std::make_pair("cube-curve-short.json", 0.84)));

}  // namespace
}  // namespace cairn

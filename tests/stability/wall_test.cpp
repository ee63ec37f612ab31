// The 100-brick running-bond wall: a statically indeterminate assembly of 105
// parts in one contact component (570 contacts, a Stewart–Trinkle LCP of 2280
// variables of rank ≤ 315) — the degenerate, large case the factored Lemke
// solver exists for. The exact lexicographic dense solver ends on a wrong
// basis here (residual 0.3–30); the answers below are checked against the
// physics, not against a solver.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cairn/stability/analyze.h"
#include "equilibrium.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::ExpectStaticEquilibrium;
using testing::RunningBondWall;

// Σ of the ground's normal forces.
double GroundLoad(const Assembly& a, const StabilityResult& r) {
  const int ground = a.FindPart("ground");
  double sum = 0;
  for (const ContactReport& c : r.contacts)
    if (c.contact.part_b == ground || c.contact.part_a == ground) sum += c.normal_force;
  return sum;
}

double TotalWeight(const Assembly& a) {
  double m = 0;
  for (int i = 0; i < a.num_parts(); ++i)
    if (!a.part(i).fixed) m += a.part(i).mass;
  return m * a.gravity().norm();
}

class Wall : public ::testing::TestWithParam<double> {};  // μ

// The wall stands, with friction and without (its loads are all vertical),
// every brick in equilibrium and the ground carrying the whole weight.
TEST_P(Wall, TenCoursesOfTenBricksStandInEquilibrium) {
  const Assembly a = Assembly::Create(RunningBondWall(10, 10, GetParam()), "wall");
  const Configuration config = Configuration::Assembled(a);
  const StabilityResult r = AnalyzeConfiguration(a, config);
  ASSERT_EQ(r.components.size(), 1u);
  EXPECT_EQ(r.components[0].parts.size(), 105u);
  EXPECT_EQ(r.components[0].num_contacts, 570);
  EXPECT_EQ(r.components[0].lcp_size, GetParam() > 0 ? 2280 : 570);
  ASSERT_EQ(r.verdict, Verdict::kStable) << r.diagnostics;
  EXPECT_TRUE(r.moving.empty());
  ExpectStaticEquilibrium(a, config, r);
  EXPECT_NEAR(GroundLoad(a, r), TotalWeight(a), 1e-6 * TotalWeight(a));
}

INSTANTIATE_TEST_SUITE_P(Friction, Wall, ::testing::Values(0.6, 0.0));

// Without the end brick of the bottom course, the half brick above it
// (r1_5, x ∈ [9, 10]) rests on nothing: it falls, while the far end of the
// wall stays put.
TEST(Wall, TheHalfBrickOverAMissingEndBrickFalls) {
  const Assembly a = Assembly::Create(RunningBondWall(4, 5, 0.6), "wall");
  Configuration config = Configuration::Assembled(a);
  config.present[a.FindPart("r0_4")] = false;
  const StabilityResult r = AnalyzeConfiguration(a, config);
  ASSERT_EQ(r.verdict, Verdict::kUnstable) << r.diagnostics;
  const auto moves = [&](const std::string& name) {
    const int i = a.FindPart(name);
    return std::find(r.moving.begin(), r.moving.end(), i) != r.moving.end();
  };
  EXPECT_TRUE(moves("r1_5"));
  EXPECT_FALSE(moves("r0_0"));
  EXPECT_FALSE(moves("r1_0"));
}

// The dense and the factored solver on the same LCPs (a 6-course wall, small
// enough for the dense tableau): the same verdict, and frictionless, where the
// body accelerations of a symmetric PSD LCP are unique, the same moving parts
// with the same accelerations.
TEST(Wall, DenseAndFactoredSolversAgree) {
  for (const double mu : {0.0, 0.6}) {
    const Assembly a = Assembly::Create(RunningBondWall(6, 5, mu), "wall");
    for (const char* without : {"", "r0_4", "r2_0"}) {
      SCOPED_TRACE(std::string("mu ") + std::to_string(mu) + " without " + without);
      Configuration config = Configuration::Assembled(a);
      if (*without) config.present[a.FindPart(without)] = false;
      StabilityOptions dense, factored;
      dense.lcp_storage = LcpStorage::kDense;
      factored.lcp_storage = LcpStorage::kFactored;
      const StabilityResult d = AnalyzeConfiguration(a, config, dense);
      const StabilityResult f = AnalyzeConfiguration(a, config, factored);
      ASSERT_NE(d.verdict, Verdict::kSolverFailure) << d.diagnostics;
      ASSERT_EQ(f.verdict, d.verdict) << f.diagnostics;
      if (d.stable()) {
        ExpectStaticEquilibrium(a, config, d);
        ExpectStaticEquilibrium(a, config, f);
      }
      if (mu > 0) continue;
      EXPECT_EQ(f.moving, d.moving);
      ASSERT_EQ(f.parts.size(), d.parts.size());
      for (size_t i = 0; i < d.parts.size(); ++i) {
        EXPECT_NEAR((f.parts[i].linear - d.parts[i].linear).norm(), 0.0, 1e-7) << i;
        EXPECT_NEAR(f.parts[i].angular.z(), d.parts[i].angular.z(), 1e-7) << i;
      }
    }
  }
}

}  // namespace
}  // namespace cairn

// mechanics/subset_equilibrium.h: the warm LP of sub-assemblies against a
// fresh equilibrium LP of each sub-assembly, on every subset of the parts and
// every single hold.
#include "cairn/mechanics/subset_equilibrium.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cairn/io/scene_reader.h"
#include "cairn/mechanics/static_equilibrium.h"
#include "cairn/stability/analyze.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::ExamplePath;

// Whether every component of the parts `present` (with `held` fixed) has a
// static equilibrium: the fresh LPs (FindStaticEquilibrium).
bool FreshEquilibrium(const Assembly& a, const std::vector<bool>& present, int held) {
  const Assembly state = held >= 0 ? a.WithHeld({held}) : a;
  Configuration config = Configuration::Assembled(state);
  for (int p = 0; p < a.num_parts(); ++p) config.present[p] = a.part(p).fixed || present[p];
  for (const ContactLcp& lcp : BuildComponentLcps(state, config))
    if (!FindStaticEquilibrium(lcp).exists) return false;
  return true;
}

// Every subset of the movable parts, with no hold or one: the warm LP's
// answer is the fresh LP's, whatever order the states come in (here: by
// subset number, each solve starting from the last one's basis), and a
// state without equilibrium names at least one part among the free ones.
void EverySubsetAgrees(const std::string& example) {
  SCOPED_TRACE(example);
  const Assembly a = ReadScene(ExamplePath(example));
  const std::vector<ContactLcp> lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  ASSERT_EQ(lcps.size(), 1u);
  const ContactLcp& lcp = lcps[0];
  SubsetEquilibrium warm(lcp);
  const int nb = warm.num_bodies();
  ASSERT_LE(nb, 12);
  int infeasible = 0, feasible = 0;
  for (int mask = 1; mask < (1 << nb); ++mask) {
    for (int h = -1; h < nb; ++h) {
      if (h >= 0 && !(mask & (1 << h))) continue;
      std::vector<bool> present(nb), free(nb), parts_present(a.num_parts(), false);
      for (int b = 0; b < nb; ++b) {
        present[b] = (mask >> b) & 1;
        free[b] = present[b] && b != h;
        if (present[b]) parts_present[lcp.bodies[b].part] = true;
      }
      const SubsetEquilibrium::Answer answer = warm.Solve(present, free);
      ASSERT_TRUE(answer.solved) << "mask " << mask << " held " << h;
      const bool fresh = FreshEquilibrium(a, parts_present, h >= 0 ? lcp.bodies[h].part : -1);
      EXPECT_EQ(answer.exists, fresh) << "mask " << mask << " held " << h;
      (answer.exists ? feasible : infeasible)++;
      for (int b : answer.unbalanced) EXPECT_TRUE(free[b]) << "mask " << mask;
    }
  }
  // Both answers occur (a test that cannot fail is a defect).
  EXPECT_GT(feasible, 0);
  EXPECT_GT(infeasible, 0);
}

TEST(SubsetEquilibrium, EverySubsetAndHoldAsAFreshLp) {
  for (const char* example : {"stack3.json", "paper_fig1.json", "paper_fig4.json"})
    EverySubsetAgrees(example);
}

// The stack without its bottom block: the two above have nothing to stand on
// (the ray moves them); holding the middle one, the top one stands on it.
TEST(SubsetEquilibrium, AStackWithoutItsBaseAndWithAHold) {
  const Assembly a = ReadScene(ExamplePath("stack3.json"));
  const std::vector<ContactLcp> lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  ASSERT_EQ(lcps.size(), 1u);
  SubsetEquilibrium warm(lcps[0]);
  std::vector<int> body(a.num_parts(), -1);
  for (size_t b = 0; b < lcps[0].bodies.size(); ++b) body[lcps[0].bodies[b].part] = int(b);
  const int A = body[a.FindPart("A")], B = body[a.FindPart("B")];
  std::vector<bool> present(3, true), free(3, true);
  EXPECT_TRUE(warm.Solve(present, free).exists);
  present[A] = free[A] = false;
  const SubsetEquilibrium::Answer no_base = warm.Solve(present, free);
  ASSERT_TRUE(no_base.solved);
  EXPECT_FALSE(no_base.exists);
  free[B] = false;  // held
  EXPECT_TRUE(warm.Solve(present, free).exists);
}

}  // namespace
}  // namespace cairn

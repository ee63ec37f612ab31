// The paper's claims about sequences and paths, checked by enumeration and by
// random property tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "failure_brief.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Box;
using testing::ExamplePath;

// True when some present part other than p rests above p (overlapping in x,
// its bottom at or above p's top): p cannot be lifted straight up.
bool SomethingAbove(const Assembly& a, const std::vector<bool>& present, int p) {
  const auto [lo, hi] = BoundingBox(a.part(p).polygon);
  for (int j = 0; j < a.num_parts(); ++j) {
    if (j == p || !present[j] || a.part(j).fixed) continue;
    const auto [jlo, jhi] = BoundingBox(a.part(j).polygon);
    if (jlo.y() >= hi.y() - 1e-9 && jlo.x() < hi.x() && jhi.x() > lo.x()) return true;
  }
  return false;
}

// A removal along a geometrically feasible path: straight up when nothing
// rests on the part, else sideways (to the right) out from under its load.
PlanStepDef FeasibleRemoval(const Assembly& a, const std::vector<bool>& present, int p) {
  PlanStepDef s;
  s.remove = {a.part(p).name};
  s.has_direction = true;
  s.direction = SomethingAbove(a, present, p) ? Vector3(1, 0, 0) : Vector3(0, 1, 0);
  s.distance = 8;
  return s;
}

TEST(PaperFig1, OfAll24SequencesOnlyDCBAIsStable) {
  const Assembly a = ReadScene(ExamplePath("paper_fig1.json"));
  std::vector<std::string> order = {"A", "B", "C", "D"};
  int stable = 0;
  do {
    PlanDef def;
    std::vector<bool> present(a.num_parts(), true);
    for (const std::string& name : order) {
      const int p = a.FindPart(name);
      def.steps.push_back(FeasibleRemoval(a, present, p));
      present[p] = false;
    }
    const SimulationResult r = SimulatePlan(a, Plan::Create(def, a));
    const std::string seq = order[0] + order[1] + order[2] + order[3];
    if (r.stable()) {
      ++stable;
      EXPECT_EQ(seq, "DCBA");
    }
    // Starting with A, B or C fails at once, and by instability (not a blocked path).
    if (order[0] != "D") {
      EXPECT_EQ(r.verdict, MotionVerdict::kUnstable) << seq;
      ASSERT_TRUE(r.failure) << seq;
      EXPECT_EQ(r.failure->step, 0) << seq;
    }
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(stable, 1);
}

// Proposition 4: for path-independent disassembly (the gripper carries the
// part's weight), stable at both ends of a path means stable all along it.
// Random stacks of three boxes on a table; the top box first slides along the
// box below it (its contacts change at every tick, its weight carried), then
// is lifted and moved away along a random polyline.
TEST(Proposition4, StableAtBothEndsMeansStableAllAlong) {
  std::mt19937 rng(20140821);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    AssemblyDef def;
    def.gravity = Vector3(0, -1, 0);
    const double w0 = 2 + u(rng), w1 = 2 + u(rng), w2 = 1.5 + 0.5 * u(rng);
    const double x0 = -w0 / 2, x1 = x0 + 0.8 * u(rng) * w0 / 2, x2 = x1 + 0.8 * u(rng) * w1 / 2;
    def.parts = {Box("table", -20, -1, 20, 0, true), Box("P", x0, 0, x0 + w0, 1),
                 Box("Q", x1, 1, x1 + w1, 1.7), Box("R", x2, 1.7, x2 + w2, 2.3)};
    const Assembly a = Assembly::Create(def);
    // Both ends: with the top box R, and without it.
    Configuration with = Configuration::Assembled(a), without = with;
    without.present[a.FindPart("R")] = false;
    if (!AnalyzeConfiguration(a, with).stable() || !AnalyzeConfiguration(a, without).stable())
      continue;
    PlanDef plan;
    plan.dt = 0.25;
    PlanStepDef s;
    s.remove = {"R"};
    s.has_path = true;
    const double slide = 1.5 * u(rng);
    s.path = {{0, 0, 0},
              {slide, 0, 0},
              {slide, 3 + u(rng), 0},
              {4 * u(rng), 4 + u(rng), 0},
              {8 * u(rng), 6, 0}};
    plan.steps = {s};
    const SimulationResult r = SimulatePlan(a, Plan::Create(plan, a));
    EXPECT_TRUE(r.stable()) << "trial " << trial << ": "
                            << (r.failure ? testing::Brief(*r.failure) : std::string());
    ++checked;
  }
  EXPECT_GE(checked, 10) << "too few random cases were stable at both ends to test anything";
}

}  // namespace
}  // namespace cairn

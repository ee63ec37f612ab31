// The paper's 3-D example (Section V-B, Figs. 9-13), rebuilt as
// examples/paper_fig9.json with plans in examples/plans/paper_fig9_*.plan.json
// (see examples/README.md for the design). Frictionless blocks on a fixed
// table: B is a non-convex "mushroom" (a 1 × 1 pillar under a 4 × 3 slab), A
// and C rest on the slab on either side of the pillar, G is the gripper's
// support pad of Fig. 12 (a tool). Every expectation that involves a number is
// derived here from the scene's masses and centroids (the paper's eq. 8), not
// copied from a run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "failure_brief.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::ExamplePath;

class PaperFig9 : public ::testing::Test {
 protected:
  const Assembly a_ = ReadScene(ExamplePath("paper_fig9.json"));
  const int A_ = a_.FindPart("A"), B_ = a_.FindPart("B"), C_ = a_.FindPart("C"),
            G_ = a_.FindPart("G"), table_ = a_.FindPart("table");

  SimulationResult Run(const std::string& plan, bool timeline = false) const {
    SimulationOptions options;
    options.record_timeline = timeline;
    return SimulatePlan(a_, ReadPlan(ExamplePath("plans/" + plan), a_), options);
  }
  // The first tick at which the gripped part, moving speed·dt per tick, has
  // gone further than `critical` along its path.
  static int FirstTickBeyond(double critical, const Plan& plan) {
    return static_cast<int>(std::floor(critical / (plan.speed * plan.dt))) + 1;
  }
  // Σ m_i ((c_i · axis) − edge) over `parts`: the moment (per unit g) of
  // their weights about the edge of B's foot at `edge` along `axis`. B stays
  // on its foot while the weights' centroid is on the foot's side of every
  // edge: the moment about the foot's +x edge (edge 0.5, axis x) must be ≤ 0,
  // about its −y edge (edge −0.5, axis y) ≥ 0.
  double Moment(const Vector3& axis, double edge, std::vector<int> parts) const {
    double m = 0;
    for (int p : parts) m += a_.part(p).mass * (a_.part(p).centroid.dot(axis) - edge);
    return m;
  }
  static std::string Why(const SimulationResult& r) {
    return (r.failure ? testing::Brief(*r.failure) : std::string("no failure")) + " " +
           r.diagnostics;
  }
  static bool Contains(const std::vector<int>& v, int x) {
    return std::find(v.begin(), v.end(), x) != v.end();
  }
};

TEST_F(PaperFig9, TheMushroomBHasExactMassPropertiesAndTheAssemblyStands) {
  // B: pillar 1 × 1 × 2 (centroid z = 1) and slab 4 × 3 × 0.5 (z = 2.25), density 0.5.
  const Part& b = a_.part(B_);
  EXPECT_NEAR(b.area, 8.0, 1e-12);  // volume
  EXPECT_NEAR(b.mass, 4.0, 1e-12);
  EXPECT_TRUE(b.centroid.isApprox(Vector3(0, 0, (2 * 1 + 6 * 2.25) / 8), 1e-12));
  // Iyy of pillar + slab about the common centroid (parallel axes).
  const double zc = b.centroid.z();
  const double iyy = 0.5 * (2 * (1 + 4) / 12.0 + 2 * std::pow(1 - zc, 2) + 6 * (16 + 0.25) / 12.0 +
                            6 * std::pow(2.25 - zc, 2));
  EXPECT_NEAR(b.inertia(1, 1), iyy, 1e-9);

  const StabilityResult r = AnalyzeConfiguration(a_, Configuration::Assembled(a_));
  EXPECT_TRUE(r.stable()) << r.diagnostics;
  // Three contact polygons of four vertices each, as Fig. 9(b): I (A on B),
  // II (C on B), III (B on the table). G, a tool, is absent.
  std::map<int, std::vector<const ContactReport*>> patches;
  for (const ContactReport& cr : r.contacts) patches[cr.contact.patch].push_back(&cr);
  ASSERT_EQ(patches.size(), 3u);
  double on_table = 0;
  for (const auto& [id, points] : patches) {
    EXPECT_EQ(points.size(), 4u) << "patch " << id;
    for (const ContactReport* cr : points) {
      EXPECT_EQ(cr->contact.part_a, points[0]->contact.part_a);
      if (cr->contact.part_b == table_) on_table += cr->normal_force;
    }
  }
  // Vertical equilibrium of everything on the table (g = 1).
  EXPECT_NEAR(on_table, a_.part(A_).mass + a_.part(B_).mass + a_.part(C_).mass, 1e-9);
}

TEST_F(PaperFig9, ACBIsUnstableLiftingAToppleB) {
  // Without A's counterweight the weights of B and C press beyond the +x edge
  // of B's foot: B topples, vertices 9 and 12 (x = −0.5) lift off the table.
  ASSERT_LT(Moment(Vector3::UnitX(), 0.5, {A_, B_, C_}), 0.0);
  ASSERT_GT(Moment(Vector3::UnitX(), 0.5, {B_, C_}), 0.0);
  const SimulationResult r = Run("paper_fig9_acb.plan.json");
  ASSERT_EQ(r.verdict, MotionVerdict::kUnstable) << Why(r);
  EXPECT_EQ(r.failure->step, 0);
  EXPECT_EQ(r.failure->tick, 1) << "as soon as A leaves B";
  EXPECT_TRUE(Contains(r.failure->parts, B_)) << Why(r);
  int lifting = 0;
  for (const ContactReport& cr : r.failure->contacts) {
    if (cr.contact.part_a != B_ || cr.contact.part_b != table_) continue;
    const bool left = std::abs(cr.contact.p_WC.x() + 0.5) < 1e-9;
    EXPECT_EQ(cr.breaking, left) << cr.contact.p_WC.transpose();
    lifting += cr.breaking;
  }
  EXPECT_EQ(lifting, 2);
  for (const PartMotion& m : r.failure->motions) {
    if (m.part == B_) {
      EXPECT_GT(m.angular.y(), 0.0) << "B turns towards +x";
    }
  }
}

TEST_F(PaperFig9, SlidingCAlongMinusYTipsTheAssemblyWhereEquationEightSays) {
  // C's weight rests on B (support "none"). The weights press B's foot onto
  // its −y edge (y = −0.5) once Σ m_i (y_i + 0.5) < 0: eq. 8 with the moment
  // arm of the table's contact polygon, d = 1.
  const Plan plan = ReadPlan(ExamplePath("plans/paper_fig9_cab_minus_y.plan.json"), a_);
  const double critical = Moment(Vector3::UnitY(), -0.5, {A_, B_, C_}) / a_.part(C_).mass;
  ASSERT_GT(critical, 0.0);
  ASSERT_LT(critical, plan.steps[0].Length());
  // C is still over the slab (y ≥ −1.5) when B tips: the tipping is B's.
  ASSERT_GT(a_.part(C_).centroid.y() - critical, -1.5);

  const SimulationResult r = Run("paper_fig9_cab_minus_y.plan.json", true);
  ASSERT_EQ(r.verdict, MotionVerdict::kUnstable) << Why(r);
  EXPECT_EQ(r.failure->step, 0);
  EXPECT_EQ(r.failure->tick, FirstTickBeyond(critical, plan)) << Why(r);
  EXPECT_TRUE(Contains(r.failure->parts, B_)) << Why(r);
  // Vertices 11 and 12 (y = +0.5) lose contact with the table (Fig. 11).
  int lifting = 0;
  for (const ContactReport& cr : r.failure->contacts) {
    if (cr.contact.part_a != B_ || cr.contact.part_b != table_) continue;
    EXPECT_EQ(cr.breaking, cr.contact.p_WC.y() > 0) << cr.contact.p_WC.transpose();
    lifting += cr.breaking;
  }
  EXPECT_EQ(lifting, 2);

  // Before that, the load moves from 11, 12 to 9, 10 (Fig. 11): the table's
  // force on the y = −0.5 side grows and on the y = +0.5 side shrinks.
  std::map<int, double> front, back;  // tick → Σ normal force
  for (const TimelineRow& row : r.timeline) {
    const Contact& c = row.contact.contact;
    if (c.part_a != B_ || c.part_b != table_) continue;
    (c.p_WC.y() < 0 ? front : back)[row.tick] += row.contact.normal_force;
  }
  ASSERT_GT(front.size(), 10u);
  const int last = r.failure->tick - 1;
  EXPECT_GT(front.at(last), front.at(0) + 1e-3);
  EXPECT_LT(back.at(last), back.at(0) - 1e-3);
  EXPECT_NEAR(back.at(last), 0.0, 0.1 * back.at(0))
      << "just before the tip, 11 and 12 are nearly bare";
}

TEST_F(PaperFig9, SlidingCAlongPlusXOnTheGrippersPadIsStableToTheEnd) {
  // Fig. 12-13: the pad G under C's leading end carries what B cannot. C-A-B
  // along this path is stable, every step.
  const SimulationResult r = Run("paper_fig9_cab_plus_x_pad.plan.json", true);
  ASSERT_EQ(r.verdict, MotionVerdict::kStable) << Why(r);
  ASSERT_EQ(r.steps.size(), 3u);
  // Fig. 13: along the path, the table's load moves to B's +x side (10, 11)
  // and the pad takes a growing share of C's weight.
  std::map<int, double> plus_x, minus_x, pad;
  for (const TimelineRow& row : r.timeline) {
    if (row.step != 0) continue;
    const Contact& c = row.contact.contact;
    if (c.part_a == B_ && c.part_b == table_)
      (c.p_WC.x() > 0 ? plus_x : minus_x)[row.tick] += row.contact.normal_force;
    if ((c.part_a == C_ && c.part_b == G_) || (c.part_a == G_ && c.part_b == C_))
      pad[row.tick] += row.contact.normal_force;
  }
  const int end = r.steps[0].ticks - 1;
  EXPECT_GT(plus_x.at(end), plus_x.at(0));
  EXPECT_LT(minus_x.at(end), minus_x.at(0));
  // (Never less: how C's weight is shared between B and the pad is one of a
  // family of rigid solutions, and the one the solver meets in the LCP's
  // canonical order keeps the pad's share from tick 1 on.)
  EXPECT_GE(pad.at(end), pad.at(1) * (1 - 1e-9));
  EXPECT_GT(pad.at(end), 0.5 * a_.part(C_).mass) << "at the end the pad carries most of C";
}

TEST_F(PaperFig9, SlidingCAlongPlusXWithoutThePadTipsTheAssembly) {
  // Without G, C's weight rests on B alone and moves towards B's +x side:
  // B tips about its foot's +x edge once Σ m_i (x_i − 0.5) > 0.
  const Plan plan = ReadPlan(ExamplePath("plans/paper_fig9_cab_plus_x.plan.json"), a_);
  const double critical = -Moment(Vector3::UnitX(), 0.5, {A_, B_, C_}) / a_.part(C_).mass;
  ASSERT_GT(critical, 0.0);
  const SimulationResult r = Run("paper_fig9_cab_plus_x.plan.json");
  ASSERT_EQ(r.verdict, MotionVerdict::kUnstable) << Why(r);
  EXPECT_EQ(r.failure->tick, FirstTickBeyond(critical, plan)) << Why(r);
  EXPECT_TRUE(Contains(r.failure->parts, B_)) << Why(r);
}

TEST_F(PaperFig9, AssemblingInTheReverseOrdersGivesTheSameVerdicts) {
  // Frictionless, assembly is disassembly run backwards. B, C, A (the reverse
  // of A-C-B) fails once C rests on B without A: C is held until it is in
  // place, and B topples when the gripper lets go of C there (the check at
  // the end of C's step). B, A, C, each lowered from above, is stable
  // throughout.
  Plan acb = ReadPlan(ExamplePath("plans/paper_fig9_acb.plan.json"), a_);
  acb.mode = PlanMode::kAssemble;
  const SimulationResult bad = SimulatePlan(a_, acb);
  ASSERT_EQ(bad.verdict, MotionVerdict::kUnstable) << Why(bad);
  EXPECT_EQ(bad.failure->step, 1) << "C's step (file order), the second placed";
  EXPECT_TRUE(bad.failure->released) << "as soon as C is let go";
  EXPECT_TRUE(Contains(bad.failure->parts, B_)) << Why(bad);

  PlanDef def;
  def.mode = PlanMode::kAssemble;
  for (const char* name : {"C", "A", "B"}) {
    PlanStepDef step;
    step.remove = {name};
    step.has_direction = true;
    step.direction = Vector3::UnitZ();
    step.distance = 2;
    def.steps.push_back(step);
  }
  const SimulationResult good = SimulatePlan(a_, Plan::Create(def, a_));
  EXPECT_EQ(good.verdict, MotionVerdict::kStable) << Why(good);
  EXPECT_EQ(good.steps.size(), 3u);
}

TEST_F(PaperFig9, FullSupportMakesEveryPathGiveTheSameVerdict) {
  // Proposition 2: a part whose weight the gripper carries acts on the rest
  // only through what it runs into. Each removal's verdict is the static
  // verdict of the assembly without the part, whatever the path.
  // Paths that run into nothing that stays (C never heads for A, nor A for C;
  // a path into the slab is simply infeasible, one that presses down into B
  // pushes B).
  const std::map<std::string, std::vector<Vector3>> paths = {
      {"C", {{1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, 1}, {1, -1, 1}, {1, 1, 0.2}, {0, 1, -0.1}}},
      {"A", {{-1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 1, 2}, {-1, -1, 0.1}}}};
  for (const auto& [name, directions] : paths) {
    const int p = a_.FindPart(name);
    Configuration without = Configuration::Assembled(a_);
    without.present[p] = false;
    const bool expected = AnalyzeConfiguration(a_, without).stable();
    EXPECT_EQ(expected, name == "C") << "A and B stand without C; B and C fall without A";
    int feasible = 0;
    for (const Vector3& d : directions) {
      PlanDef def;
      def.dt = 0.25;
      PlanStepDef step;
      step.remove = {name};
      step.has_direction = true;
      step.direction = d;
      step.distance = 5;
      def.steps = {step};
      const SimulationResult r = SimulatePlan(a_, Plan::Create(def, a_));
      SCOPED_TRACE(name + " along " + ::testing::PrintToString(d.transpose()));
      // Runs into the table (infeasible) or, heading down into B, pushes it
      // from the first instant (unstable, pushed): not a path that leaves.
      if (r.verdict == MotionVerdict::kInfeasible || (r.failure && !r.failure->pushed.empty()))
        continue;
      ++feasible;
      EXPECT_EQ(r.stable(), expected) << Why(r);
    }
    EXPECT_GE(feasible, 5) << name;
  }
}

}  // namespace
}  // namespace cairn

#include "cairn/stability/analyze.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cairn/io/scene_reader.h"
#include "equilibrium.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::BlockOnIncline;
using testing::Box;
using testing::ExamplePath;
using testing::ExpectStaticEquilibrium;
using testing::Ladder;
using testing::LadderCriticalMu;

constexpr double kDeg = std::numbers::pi / 180.0;

StabilityResult Analyze(const Assembly& a, const std::vector<std::string>& without = {}) {
  Configuration config = Configuration::Assembled(a);
  for (const auto& name : without) config.present[a.FindPart(name)] = false;
  return AnalyzeConfiguration(a, config);
}

StabilityResult AnalyzeExample(const std::string& file,
                               const std::vector<std::string>& without = {}) {
  return Analyze(ReadScene(ExamplePath(file)), without);
}

const PartMotion& MotionOf(const Assembly& a, const StabilityResult& r, const std::string& name) {
  const int i = a.FindPart(name);
  for (const PartMotion& m : r.parts)
    if (m.part == i) return m;
  throw std::runtime_error("no motion for " + name);
}

// --- A block on an incline: holds iff tan θ ≤ μ. ---------------------------

class Incline : public ::testing::TestWithParam<double> {};

TEST_P(Incline, HoldsJustBelowTheFrictionAngleAndSlidesJustAbove) {
  const double theta = GetParam() * kDeg;
  const double t = std::tan(theta);
  for (const double factor : {1.03, 1.0 / 1.03}) {
    const double mu = t * factor;
    const Assembly a = Assembly::Create(BlockOnIncline(theta, mu));
    const StabilityResult r = Analyze(a);
    EXPECT_EQ(r.formulation, Formulation::kStewartTrinkle);
    EXPECT_EQ(r.stable(), mu >= t) << "theta=" << GetParam() << " mu=" << mu;
    if (r.stable()) ExpectStaticEquilibrium(a, Configuration::Assembled(a), r);
  }
}

TEST_P(Incline, SlidingVelocityAfterOneStepIsGTimesSinMinusMuCos) {
  // Kinetic friction: v⁺ = g (sin θ − μ cos θ) Δt down the slope.
  const double theta = GetParam() * kDeg;
  const double mu = 0.5 * std::tan(theta);
  const Assembly a = Assembly::Create(BlockOnIncline(theta, mu));
  const StabilityResult r = Analyze(a);
  ASSERT_FALSE(r.stable());
  const PartMotion& m = MotionOf(a, r, "block");
  const Vector3 down(std::cos(theta), -std::sin(theta), 0);
  const double expected = 9.81 * (std::sin(theta) - mu * std::cos(theta));
  EXPECT_NEAR(m.linear.dot(down), expected, 1e-9);
  EXPECT_NEAR(m.linear.norm(), expected, 1e-9);
  EXPECT_NEAR(m.angular.z(), 0.0, 1e-9);
  EXPECT_EQ(m.kind, MotionKind::kSlides);
}

TEST_P(Incline, FrictionlessBlockSlidesWithZeroNormalAccelerations) {
  // μ = 0: every normal acceleration is zero, yet the block accelerates at
  // g sin θ along the slope: the verdict must look at body motion.
  const double theta = GetParam() * kDeg;
  const Assembly a = Assembly::Create(BlockOnIncline(theta, 0.0));
  const StabilityResult r = Analyze(a);
  EXPECT_EQ(r.formulation, Formulation::kBaraff);
  ASSERT_FALSE(r.stable());
  for (const ContactReport& cr : r.contacts) {
    EXPECT_NEAR(cr.normal_motion, 0.0, 1e-9);
    EXPECT_FALSE(cr.breaking);
    EXPECT_TRUE(cr.sliding);
  }
  const PartMotion& m = MotionOf(a, r, "block");
  EXPECT_NEAR(m.linear.norm(), 9.81 * std::sin(theta), 1e-9);
  EXPECT_NEAR(m.linear.dot(Vector3(std::cos(theta), -std::sin(theta), 0)), 9.81 * std::sin(theta),
              1e-9);
  EXPECT_EQ(m.kind, MotionKind::kSlides);
}

INSTANTIATE_TEST_SUITE_P(Angles, Incline, ::testing::Values(5.0, 15.0, 25.0, 35.0, 50.0));

TEST(Incline, BundledExamples) {
  EXPECT_TRUE(AnalyzeExample("incline.json").stable());
  EXPECT_FALSE(AnalyzeExample("incline_slides.json").stable());
}

// --- A block overhanging a table edge: stable iff its centroid is over it. --

// The 2-D cube beside a wall: a free unit square beside a fixed wall
// (x from 1 to 2), touching only its side x = 1, nothing below it, falls at
// any μ; with every edge of both cut at its midpoint (the same shapes:
// vertices inside straight edges, two of them on the wall's corners' edges)
// the verdict, the motion and the contact normals are the same (issue 31).
TEST(SquareBesideAWall, FallsWithItsEdgesSplitOrNot) {
  const auto split = [](Polygon p) {
    Polygon out;
    for (size_t k = 0; k < p.size(); ++k) {
      out.push_back(p[k]);
      out.push_back(0.5 * (p[k] + p[(k + 1) % p.size()]));
    }
    return out;
  };
  for (const double mu : {0.0, 0.5, 2.0})
    for (const bool cut : {false, true}) {
      SCOPED_TRACE(std::string(cut ? "split edges" : "plain") + ", μ = " + std::to_string(mu));
      AssemblyDef def;
      def.friction = mu;
      def.parts = {Box("wall", 1, 0, 2, 1, true), Box("square", 0, 0, 1, 1)};
      if (cut)
        for (PartDef& p : def.parts) p.polygon = split(p.polygon);
      const Assembly a = Assembly::Create(def);
      const StabilityResult r = Analyze(a);
      EXPECT_FALSE(r.stable());
      ASSERT_TRUE(r.static_equilibrium.has_value());
      EXPECT_FALSE(*r.static_equilibrium);
      ASSERT_FALSE(r.contacts.empty());
      for (const ContactReport& c : r.contacts)
        EXPECT_NEAR(std::abs(c.contact.n_W.x()), 1.0, 1e-12) << c.contact.p_WC.transpose();
      ASSERT_EQ(r.parts.size(), 1u);
      EXPECT_TRUE(r.parts[0].moving);
      EXPECT_LT(r.parts[0].linear.y(), 0.0);
    }
}

TEST(Overhang, StableIffCentroidOverTheTable) {
  // Table top y = 0 for x ≤ 0; a 2 × 1 block with its centroid at x = xc.
  for (const double xc : {-0.9, -0.3, -0.02, 0.02, 0.3, 0.9}) {
    AssemblyDef def;
    def.parts = {Box("table", -5, -1, 0, 0, true), Box("block", xc - 1, 0, xc + 1, 1)};
    const Assembly a = Assembly::Create(def);
    const StabilityResult r = Analyze(a);
    EXPECT_EQ(r.stable(), xc < 0) << "xc=" << xc;
    if (!r.stable()) {
      const PartMotion& m = MotionOf(a, r, "block");
      EXPECT_EQ(m.kind, MotionKind::kTips);
      EXPECT_LT(m.angular.z(), 0.0) << "tips clockwise, over the edge";
      // The table-edge contact stays closed; the inner corner lifts off.
      for (const ContactReport& cr : r.contacts)
        EXPECT_EQ(cr.breaking, cr.contact.p_WC.x() < -1e-6);
    } else {
      ExpectStaticEquilibrium(a, Configuration::Assembled(a), r);
    }
  }
  EXPECT_TRUE(AnalyzeExample("overhang.json").stable());
  EXPECT_FALSE(AnalyzeExample("overhang_tips.json").stable());
}

TEST(Overhang, SupportForcesFollowTheLeverRule) {
  // Block over [-1.5, 0.5] on the table (edge at 0): its weight rests on the
  // two ends of the contact segment [-1.5, 0], split by the lever rule.
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  def.parts = {Box("table", -5, -1, 0, 0, true), Box("block", -1.5, 0, 0.5, 1)};
  const Assembly a = Assembly::Create(def);
  const StabilityResult r = Analyze(a);
  ASSERT_TRUE(r.stable());
  ASSERT_EQ(r.contacts.size(), 2u);
  const double W = a.part(1).mass;  // weight with g = 1
  for (const ContactReport& cr : r.contacts) {
    // Centroid at x = -0.5: the end at 0 carries (1.0/1.5) W, the end at -1.5 carries (0.5/1.5) W.
    const double expected = cr.contact.p_WC.x() > -0.75 ? W / 1.5 : 0.5 * W / 1.5;
    EXPECT_NEAR(cr.normal_force, expected, 1e-9);
  }
}

// --- Stacks. ----------------------------------------------------------------

TEST(Stack, ThreeOffsetBlocksStandAndTheTopOneTipsWhenPushedPastTheEdge) {
  const Assembly a = ReadScene(ExamplePath("stack3.json"));
  const StabilityResult r = Analyze(a);
  EXPECT_TRUE(r.stable());
  ExpectStaticEquilibrium(a, Configuration::Assembled(a), r);
  EXPECT_EQ(r.components.size(), 1u);

  const Assembly b = ReadScene(ExamplePath("stack3_tips.json"));
  const StabilityResult rb = Analyze(b);
  EXPECT_FALSE(rb.stable());
  const PartMotion& c = MotionOf(b, rb, "C");
  EXPECT_TRUE(c.moving);
  EXPECT_EQ(c.kind, MotionKind::kTips);
  EXPECT_FALSE(MotionOf(b, rb, "A").moving);
}

// --- The ladder: stable iff μ ≥ 1/(2 tan θ) (exact: thickness included). ----

TEST(Ladder, StandsIffFloorFrictionReachesTheCriticalValue) {
  for (const double deg : {50.0, 60.0, 70.0}) {
    const double theta = deg * kDeg;
    const double mu_c = LadderCriticalMu(theta);
    EXPECT_NEAR(mu_c, 1.0 / (2 * std::tan(theta)), 0.02);
    for (const double factor : {1.03, 1.0 / 1.03}) {
      const Assembly a = Assembly::Create(Ladder(theta, mu_c * factor));
      const StabilityResult r = Analyze(a);
      EXPECT_EQ(r.stable(), factor > 1) << deg << " deg, mu = " << mu_c * factor;
      if (r.stable()) ExpectStaticEquilibrium(a, Configuration::Assembled(a), r);
    }
  }
  EXPECT_TRUE(AnalyzeExample("ladder.json").stable());
}

// --- The paper's Fig. 1 (blocks A–D on table E, frictionless). --------------

TEST(PaperFig1, WholeStandsWithoutCTopplesWithoutDStands) {
  const Assembly a = ReadScene(ExamplePath("paper_fig1.json"));
  const StabilityResult whole = Analyze(a);
  EXPECT_TRUE(whole.stable());
  ExpectStaticEquilibrium(a, Configuration::Assembled(a), whole);

  const StabilityResult no_c = Analyze(a, {"C"});
  EXPECT_FALSE(no_c.stable());
  EXPECT_TRUE(MotionOf(a, no_c, "B").moving);
  EXPECT_EQ(MotionOf(a, no_c, "B").kind, MotionKind::kTips);
  EXPECT_LT(MotionOf(a, no_c, "B").angular.z(), 0.0) << "B topples clockwise under D";

  EXPECT_TRUE(Analyze(a, {"D"}).stable());
  // Every state of D-C-B-A stands; taking A or B first does not.
  EXPECT_TRUE(Analyze(a, {"D", "C"}).stable());
  EXPECT_TRUE(Analyze(a, {"D", "C", "B"}).stable());
  EXPECT_FALSE(Analyze(a, {"A"}).stable());
  EXPECT_FALSE(Analyze(a, {"B"}).stable());
}

// --- The paper's Fig. 4 (A, B, C on a frictionless base D). ------------------

TEST(PaperFig4, LiftingAMakesBSlideRightAndTwoFixelsHoldIt) {
  const Assembly a = ReadScene(ExamplePath("paper_fig4.json"));
  const StabilityResult whole = Analyze(a);
  EXPECT_TRUE(whole.stable()) << whole.diagnostics;
  ExpectStaticEquilibrium(a, Configuration::Assembled(a), whole);

  const StabilityResult no_a = Analyze(a, {"A"});
  ASSERT_FALSE(no_a.stable());
  const PartMotion& b = MotionOf(a, no_a, "B");
  EXPECT_TRUE(b.moving);
  EXPECT_EQ(b.kind, MotionKind::kSlides);
  EXPECT_GT(b.linear.x(), 0.0) << "B accelerates to the right";
  EXPECT_NEAR(b.linear.y(), 0.0, 1e-9) << "on the frictionless floor";

  const Assembly f = ReadScene(ExamplePath("paper_fig4_fixels.json"));
  const StabilityResult held = Analyze(f, {"A"});
  EXPECT_TRUE(held.stable());
  ExpectStaticEquilibrium(
      f,
      [&] {
        Configuration c = Configuration::Assembled(f);
        c.present[f.FindPart("A")] = false;
        return c;
      }(),
      held);
  // The two fixels on one face are statically indeterminate (the split
  // between them is not unique); together they carry C's push on B.
  int fixel_contacts = 0;
  double fixel_load = 0;
  for (const ContactReport& cr : held.contacts)
    if (cr.contact.part_b == kWorld) {
      ++fixel_contacts;
      EXPECT_GE(cr.normal_force, 0.0);
      fixel_load += cr.normal_force;
    }
  EXPECT_EQ(fixel_contacts, 2);
  EXPECT_GT(fixel_load, 1e-3);
}

// --- Structure: components, free fall, determinism. -------------------------

TEST(Components, SeparateStacksAreSolvedApartWithTheSameAnswer) {
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  def.parts = {Box("table", -10, -1, 10, 0, true), Box("A", -8, 0, -6, 1),
               Box("B", -7.5, 1, -6.5, 2), Box("C", 2, 0, 4, 1), Box("D", 3.5, 1, 5.5, 2)};
  const Assembly both = Assembly::Create(def);
  const StabilityResult r = Analyze(both);
  EXPECT_EQ(r.components.size(), 2u);
  EXPECT_FALSE(r.stable());
  EXPECT_EQ(r.moving, std::vector<int>{4});  // D overhangs C
  EXPECT_FALSE(MotionOf(both, r, "A").moving);
}

TEST(FreeFall, APartTouchingNothingFallsAtG) {
  AssemblyDef def;
  def.parts = {Box("table", -5, -1, 5, 0, true), Box("floating", 0, 1, 1, 2)};
  const Assembly a = Assembly::Create(def);
  const StabilityResult r = Analyze(a);
  ASSERT_FALSE(r.stable());
  const PartMotion& m = MotionOf(a, r, "floating");
  EXPECT_EQ(m.kind, MotionKind::kFalls);
  EXPECT_NEAR(m.linear.y(), -9.81, 1e-12);
}

TEST(Determinism, SameSceneTwiceGivesBitIdenticalForces) {
  const Assembly a = ReadScene(ExamplePath("paper_fig4.json"));
  const StabilityResult r1 = Analyze(a), r2 = Analyze(a);
  ASSERT_EQ(r1.contacts.size(), r2.contacts.size());
  for (size_t i = 0; i < r1.contacts.size(); ++i) {
    EXPECT_EQ(r1.contacts[i].normal_force, r2.contacts[i].normal_force);
    EXPECT_EQ(r1.contacts[i].contact.p_WC, r2.contacts[i].contact.p_WC);
  }
}

// --- Warm starts (StabilityWorkspace). --------------------------------------

// Two identical two-block stacks far apart on a fixed table (μ = 0.5): two
// components whose LCPs are equal (same M and q, nontrivial: the blocks press
// on the table), but whose parts differ.
Assembly TwinStacks() {
  AssemblyDef def;
  def.friction = 0.5;
  def.gravity = Vector3(0, -1, 0);
  def.parts = {Box("table", -10, -1, 10, 0, true), Box("A", -6, 0, -4, 1),
               Box("B", -5.5, 1, -4.5, 2), Box("C", 4, 0, 6, 1), Box("D", 4.5, 1, 5.5, 2)};
  return Assembly::Create(def);
}

int TotalPivots(const StabilityResult& r) {
  int pivots = 0;
  for (const ComponentReport& c : r.components) pivots += c.pivots;
  return pivots;
}

TEST(WarmStart, TheSameAnalysisTwiceIsAnsweredByTheWorkspaceWithTheSameResult) {
  const Assembly a = TwinStacks();
  const Configuration config = Configuration::Assembled(a);
  StabilityWorkspace ws;
  const StabilityResult first = AnalyzeConfiguration(a, config, {}, nullptr, &ws);
  ASSERT_EQ(first.components.size(), 2u);
  EXPECT_EQ(ws.warm_starts(), 0);
  EXPECT_EQ(ws.num_structures(), 2);  // one entry per component structure
  for (const ComponentReport& c : first.components) {
    EXPECT_FALSE(c.warm_start_used);
    EXPECT_GT(c.pivots, 0);  // a cold solve pivots: the second's 0 means something
  }

  const StabilityResult second = AnalyzeConfiguration(a, config, {}, nullptr, &ws);
  EXPECT_EQ(ws.warm_starts(), 2);
  EXPECT_EQ(ws.num_structures(), 2);
  EXPECT_EQ(TotalPivots(second), 0);
  for (const ComponentReport& c : second.components) EXPECT_TRUE(c.warm_start_used);

  // The same answer as a cold analysis.
  const StabilityResult cold = AnalyzeConfiguration(a, config);
  EXPECT_EQ(second.verdict, cold.verdict);
  EXPECT_EQ(second.moving, cold.moving);
  ASSERT_EQ(second.contacts.size(), cold.contacts.size());
  for (size_t i = 0; i < cold.contacts.size(); ++i) {
    EXPECT_NEAR(second.contacts[i].normal_force, cold.contacts[i].normal_force, 1e-12);
    EXPECT_NEAR((second.contacts[i].friction_force - cold.contacts[i].friction_force).norm(), 0.0,
                1e-12);
  }
  ASSERT_EQ(second.parts.size(), cold.parts.size());
  for (size_t i = 0; i < cold.parts.size(); ++i)
    EXPECT_NEAR((second.parts[i].linear - cold.parts[i].linear).norm(), 0.0, 1e-12);
}

TEST(WarmStart, AComponentOfAnotherStructureNeverGetsItsBasis) {
  // C-D's LCP equals A-B's, so A-B's basis would solve it at once; but its
  // parts differ, so it is solved cold and gets its own entry.
  const Assembly a = TwinStacks();
  const Configuration config = Configuration::Assembled(a);
  StabilityWorkspace ws;
  const StabilityResult r = AnalyzeConfiguration(a, config, {}, nullptr, &ws);
  ASSERT_EQ(r.components.size(), 2u);
  ASSERT_EQ(r.components[0].lcp_size, r.components[1].lcp_size);
  EXPECT_EQ(r.components[0].pivots, r.components[1].pivots);
  EXPECT_FALSE(r.components[1].warm_start_used);
  EXPECT_EQ(ws.warm_starts(), 0);

  // Without D, C alone is a third structure (solved cold); A-B is unchanged
  // (warm). Then the whole scene again: both stacks' own bases are still there.
  Configuration without_d = config;
  without_d.present[a.FindPart("D")] = false;
  const StabilityResult r2 = AnalyzeConfiguration(a, without_d, {}, nullptr, &ws);
  ASSERT_EQ(r2.components.size(), 2u);
  EXPECT_TRUE(r2.components[0].warm_start_used);
  EXPECT_FALSE(r2.components[1].warm_start_used);
  EXPECT_GT(r2.components[1].pivots, 0);
  EXPECT_EQ(ws.warm_starts(), 1);
  EXPECT_EQ(ws.num_structures(), 3);

  const StabilityResult r3 = AnalyzeConfiguration(a, config, {}, nullptr, &ws);
  EXPECT_TRUE(r3.components[0].warm_start_used);
  EXPECT_TRUE(r3.components[1].warm_start_used);
  EXPECT_EQ(ws.warm_starts(), 3);
  EXPECT_EQ(ws.num_structures(), 3);
}

TEST(Postconditions, LcpSolutionsAreConsistentWithBodyMotion) {
  for (const char* file :
       {"paper_fig1.json", "paper_fig4.json", "ladder.json", "stack3_tips.json"}) {
    const StabilityResult r = AnalyzeExample(file);
    for (const ComponentReport& c : r.components) {
      EXPECT_LT(c.residual, 1e-9) << file;
      EXPECT_LT(c.consistency_residual, 1e-9) << file;
    }
  }
}

}  // namespace
}  // namespace cairn

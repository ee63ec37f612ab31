// Analytic 3-D cases: a box on an incline against the
// linearised friction cone, a box overhanging an edge diagonally, a cube
// propped on a single vertex of a tilted support, a harmonic stack of five
// boxes. Each verdict is set against a closed-form threshold, on both sides.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/stability/analyze.h"
#include "equilibrium.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::Box3;
using testing::ExpectStaticEquilibrium;

constexpr double kPi = std::numbers::pi;

Eigen::Isometry3d Rotation(double angle, const Vector3& axis,
                           const Vector3& translation = Vector3::Zero()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  X.translation() = translation;
  return X;
}

StabilityResult Analyze3d(const Assembly& a) {
  StabilityOptions options;
  options.check_equilibrium = true;
  return AnalyzeConfiguration(a, Configuration::Assembled(a), options);
}

const PartMotion* FindMotion(const Assembly& a, const StabilityResult& r, const std::string& name) {
  for (const PartMotion& m : r.parts)
    if (a.part(m.part).name == name) return &m;
  return nullptr;
}

// ---------------------------------------------------------------------------
// A 1 × 1 × 0.25 box on a fixed slab tilted by θ about x, the whole scene then
// turned by φ about the vertical. The friction pyramid of the Stewart–Trinkle
// model is the regular D-gon with vertices μN·d_k (d_k at angles 2πk/D from
// TangentBasis(n)'s first axis). Friction can hold the box iff the pyramid
// reaches mg sin θ uphill: along a direction at angle α from the nearest d_k
// the D-gon's boundary is at μN cos(π/D) / cos(π/D − α), so the box holds iff
//   tan θ ≤ μ_eff = μ cos(π/D) / cos(π/D − α)
// (μ itself when the slope runs along a pyramid edge, α = 0; μ cos(π/D) midway
// between edges, α = π/D). The exact cone is the limit D → ∞: μ_eff = μ.
struct TiltedBox {
  AssemblyDef def;
  double alpha = 0;  ///< angle from the downhill direction to the nearest d_k (rad)
};

TiltedBox BoxOnIncline3d(double theta, double mu, int D, double phi) {
  const Eigen::Isometry3d X = Rotation(phi, Vector3::UnitZ()) * Rotation(theta, Vector3::UnitX());
  TiltedBox out;
  out.def.friction = mu;
  out.def.friction_directions = D;
  out.def.parts = {Box3("incline", {-3, -3, -1}, {3, 3, 0}, true, X),
                   Box3("box", {-0.5, -0.5, 0}, {0.5, 0.5, 0.25}, false, X)};
  // The pyramid's directions at the box's contact normal, and downhill.
  const Vector3 n = X.linear() * Vector3::UnitZ();
  const auto [t1, t2] = TangentBasis(n);
  const Vector3 downhill = (-Vector3::UnitZ() + n * n.z()).normalized();
  const double beta = std::atan2(downhill.dot(t2), downhill.dot(t1));
  const double sector = 2 * kPi / D;
  const double r = std::fmod(std::fmod(beta, sector) + sector, sector);
  out.alpha = std::min(r, sector - r);
  return out;
}

double EffectiveMu(double mu, int D, double alpha) {
  return mu * std::cos(kPi / D) / std::cos(kPi / D - alpha);
}

// The turn φ that puts the slope as far as it gets from every pyramid edge.
double PhiBetweenEdges(int D) {
  double best_phi = 0, best_alpha = -1;
  for (int k = 0; k <= 2000; ++k) {
    const double phi = k * (kPi / 2) / 2000;
    const double alpha = BoxOnIncline3d(0.3, 0.5, D, phi).alpha;
    if (alpha > best_alpha) best_alpha = alpha, best_phi = phi;
  }
  return best_phi;
}

struct InclineCase {
  int D;
  bool between;  // slope between pyramid edges (else along one)
};

void PrintTo(const InclineCase& c, std::ostream* os) {
  *os << "D = " << c.D << (c.between ? ", between edges" : ", along an edge");
}

class Incline3d : public ::testing::TestWithParam<InclineCase> {};

TEST_P(Incline3d, HoldsIffTanThetaIsWithinThePyramid) {
  const auto [D, between] = GetParam();
  const double mu = 0.5;
  const double phi = between ? PhiBetweenEdges(D) : 0.0;
  const double alpha = BoxOnIncline3d(0.3, mu, D, phi).alpha;
  if (between) {
    EXPECT_NEAR(alpha, kPi / D, 1e-3) << "the slope is midway between two edges";
  } else {
    EXPECT_NEAR(alpha, 0.0, 1e-12) << "the slope runs along an edge";
  }
  const double critical = std::atan(EffectiveMu(mu, D, alpha));
  for (const double factor : {0.97, 1.03}) {
    const double theta = factor * critical;
    const TiltedBox scene = BoxOnIncline3d(theta, mu, D, phi);
    const Assembly a = Assembly::Create(scene.def);
    const StabilityResult r = Analyze3d(a);
    SCOPED_TRACE("D = " + std::to_string(D) + ", θ = " + std::to_string(theta * 180 / kPi) +
                 "°, critical " + std::to_string(critical * 180 / kPi) + "°");
    EXPECT_EQ(r.formulation, Formulation::kStewartTrinkle);
    EXPECT_EQ(r.contacts.size(), 4u) << "one face-face patch of four vertices";
    if (factor < 1) {
      EXPECT_TRUE(r.stable()) << r.diagnostics;
      ExpectStaticEquilibrium(a, Configuration::Assembled(a), r);
      // Every friction force lies in its contact's pyramid.
      for (const ContactReport& cr : r.contacts) {
        EXPECT_NEAR(cr.friction_force.dot(cr.contact.n_W), 0.0, 1e-9);
        EXPECT_LE(cr.friction_force.norm(), mu * cr.normal_force * (1 + 1e-9) + 1e-12);
      }
    } else {
      ASSERT_FALSE(r.stable());
      const PartMotion* m = FindMotion(a, r, "box");
      ASSERT_NE(m, nullptr);
      EXPECT_EQ(m->kind, MotionKind::kSlides);
      EXPECT_LT(m->linear.z(), 0.0) << "downhill";
    }
    // The static-equilibrium LP uses the same pyramid: it agrees.
    ASSERT_TRUE(r.static_equilibrium.has_value()) << r.diagnostics;
    EXPECT_EQ(*r.static_equilibrium, factor < 1);
  }
}

INSTANTIATE_TEST_SUITE_P(PyramidEdges, Incline3d,
                         ::testing::Values(InclineCase{4, false}, InclineCase{4, true},
                                           InclineCase{8, false}, InclineCase{8, true}),
                         [](const ::testing::TestParamInfo<InclineCase>& param_info) {
                           const InclineCase& c = param_info.param;
                           return "D" + std::to_string(c.D) +
                                  (c.between ? "_between_edges" : "_along_an_edge");
                         });

TEST(Incline3d, EightDirectionsComeCloserToTheExactCone) {
  // Midway between pyramid edges at tan θ = 0.9 μ: the exact cone holds the
  // box (0.9 μ ≤ μ); D = 4 reaches only μ cos 45° = 0.71 μ and lets it slide,
  // D = 8 reaches μ cos 22.5° = 0.92 μ and holds it, as the cone does.
  const double mu = 0.5, theta = std::atan(0.9 * mu);
  const Assembly four = Assembly::Create(BoxOnIncline3d(theta, mu, 4, PhiBetweenEdges(4)).def);
  const Assembly eight = Assembly::Create(BoxOnIncline3d(theta, mu, 8, PhiBetweenEdges(8)).def);
  EXPECT_FALSE(Analyze3d(four).stable());
  EXPECT_TRUE(Analyze3d(eight).stable());
}

// ---------------------------------------------------------------------------
// A 1 × 1 × 0.5 box turned 45° about the vertical, over the straight edge
// x = 0 of a table: its footprint is a diamond, and the contact polygon the
// part of the diamond over the table. It stands iff its centroid is over the
// table (c < 0); beyond, it tips about the edge (an axis along y).
AssemblyDef DiamondOverEdge(double c, double mu) {
  AssemblyDef def;
  def.friction = mu;
  def.parts = {Box3("table", {-4, -3, -1}, {0, 3, 0}, true),
               Box3("box", {-0.5, -0.5, 0}, {0.5, 0.5, 0.5}, false,
                    Rotation(kPi / 4, Vector3::UnitZ(), Vector3(c, 0, 0)))};
  return def;
}

// A free cube beside a fixed wall, touching only its vertical face x = 1 and
// nothing below it, falls: no equilibrium exists at any μ. With the cube's
// vertical edges at x = 1 split at mid-height (the same solid), the verdict
// and the contacts are the same (issue 31: the split vertices gave contacts
// with normals (0, ±1, 0) whose squeeze made it "weakly stable").
TEST(CubeBesideAWall, FallsWithItsEdgesSplitOrNot) {
  for (const bool split : {false, true}) {
    SCOPED_TRACE(split ? "split edges" : "plain");
    AssemblyDef def;
    def.friction = 0.5;
    PartDef cube = Box3("cube", {0, 0, 0}, {1, 1, 1});
    if (split) {
      PolyhedronDef& p = *cube.polyhedron;
      // Box3's vertex k is at (x, y, z) = (k & 1, k & 2, k & 4) of the box.
      p.vertices.emplace_back(1, 0, 0.5);  // 8: on the edge 1–5 (y = 0)
      p.vertices.emplace_back(1, 1, 0.5);  // 9: on the edge 3–7 (y = 1)
      p.faces = {{0, 2, 3, 1},    {4, 5, 7, 6}, {0, 1, 8, 5, 4},
                 {2, 6, 7, 9, 3}, {0, 4, 6, 2}, {1, 3, 9, 7, 5, 8}};
    }
    def.parts = {Box3("wall", {1, 0, 0}, {2, 1, 1}, true), cube};
    const Assembly a = Assembly::Create(def);
    const StabilityResult r = Analyze3d(a);
    EXPECT_FALSE(r.stable());
    ASSERT_TRUE(r.static_equilibrium.has_value());
    EXPECT_FALSE(*r.static_equilibrium);
    for (const ContactReport& c : r.contacts) EXPECT_NEAR(std::abs(c.contact.n_W.x()), 1.0, 1e-12);
    const PartMotion* m = FindMotion(a, r, "cube");
    ASSERT_NE(m, nullptr);
    EXPECT_LT(m->linear.z(), 0.0);
  }
}

TEST(DiagonalOverhang, StandsIffTheCentroidIsOverTheTable) {
  for (const double mu : {0.0, 0.5}) {
    for (const double c : {-0.05, 0.05}) {
      SCOPED_TRACE("μ = " + std::to_string(mu) + ", centroid x = " + std::to_string(c));
      const Assembly a = Assembly::Create(DiamondOverEdge(c, mu));
      const StabilityResult r = Analyze3d(a);
      // The patch: the diamond's vertex at x = c − 0.707 and the two points
      // where its edges cross x = 0 (and the vertices between).
      double min_x = 0, max_x = -1;
      for (const ContactReport& cr : r.contacts) {
        min_x = std::min(min_x, cr.contact.p_WC.x());
        max_x = std::max(max_x, cr.contact.p_WC.x());
      }
      EXPECT_NEAR(min_x, c - std::sqrt(0.5), 1e-9);
      EXPECT_NEAR(max_x, 0.0, 1e-9);
      if (c < 0) {
        EXPECT_TRUE(r.stable()) << r.diagnostics;
        ExpectStaticEquilibrium(a, Configuration::Assembled(a), r);
        continue;
      }
      ASSERT_FALSE(r.stable());
      const PartMotion* m = FindMotion(a, r, "box");
      ASSERT_NE(m, nullptr);
      EXPECT_EQ(m->kind, MotionKind::kTips);
      // About the table's edge: the rotation is about +y (the +x side drops).
      EXPECT_GT(m->angular.y(), 0.0);
      EXPECT_NEAR(m->angular.x(), 0.0, 1e-9 * m->angular.norm());
      EXPECT_NEAR(m->angular.z(), 0.0, 1e-9 * m->angular.norm());
      ASSERT_TRUE(m->pivot.has_value());
      if (mu > 0) {
        EXPECT_NEAR(m->pivot->x(), 0.0, 1e-6) << "it rolls on the edge";
      }
    }
  }
}

// ---------------------------------------------------------------------------
// A unit cube whose centroid is 0.1 beyond a table's edge (x = 0), propped
// under its overhang by the top vertex of a fixed, tilted square rod: a single
// vertex-to-face contact at (v, 0, 0). Frictionless, all normals vertical: the
// cube stands iff its centroid lies over the convex hull of the table patch
// and the vertex, i.e. iff v ≥ 0.1; the vertex then carries at least
// m g · 0.1 / v (moments about the table's edge).
AssemblyDef CubeOnVertex(double v) {
  // A 0.06 × 0.06 × 2 rod leaning away from the table; then translated so that
  // its highest vertex is at (v, 0, 0).
  const Eigen::Isometry3d tilt =
      Rotation(-0.35, Vector3::UnitY()) * Rotation(0.25, Vector3::UnitX());
  PartDef rod = Box3("rod", {-0.03, -0.03, -2}, {0.03, 0.03, 0}, true, tilt);
  Vector3 top = rod.polyhedron->vertices[0];
  for (const Vector3& p : rod.polyhedron->vertices)
    if (p.z() > top.z()) top = p;
  for (Vector3& p : rod.polyhedron->vertices) p += Vector3(v, 0, 0) - top;
  AssemblyDef def;
  def.parts = {Box3("table", {-4, -3, -1}, {0, 3, 0}, true), rod,
               Box3("cube", {-0.4, -0.5, 0}, {0.6, 0.5, 1})};
  return def;
}

TEST(VertexSupport, ACubeStandsOnATiltedVertexIffItsCentroidIsInTheHull) {
  for (const double v : {0.3, 0.08}) {
    SCOPED_TRACE("vertex at x = " + std::to_string(v));
    const AssemblyDef def = CubeOnVertex(v);
    // The rod stays clear of the table and below the cube but at its vertex.
    for (const Vector3& p : def.parts[1].polyhedron->vertices) {
      ASSERT_GT(p.x(), 0.0);
      ASSERT_LE(p.z(), 1e-12);
    }
    const Assembly a = Assembly::Create(def);
    const StabilityResult r = Analyze3d(a);
    const ContactReport* prop = nullptr;
    for (const ContactReport& cr : r.contacts) {
      if (a.part(cr.contact.part_a).name == "cube" && a.part(cr.contact.part_b).name == "rod") {
        EXPECT_EQ(prop, nullptr) << "a single point";
        prop = &cr;
      }
    }
    ASSERT_NE(prop, nullptr) << "the rod's top vertex touches the cube's bottom face";
    EXPECT_TRUE(prop->contact.p_WC.isApprox(Vector3(v, 0, 0), 1e-9));
    EXPECT_TRUE(prop->contact.n_W.isApprox(Vector3::UnitZ(), 1e-9)) << "the face's normal";
    const double W = a.part(2).mass * a.gravity().norm();
    if (v > 0.1) {
      EXPECT_TRUE(r.stable()) << r.diagnostics;
      EXPECT_GE(prop->normal_force, W * 0.1 / v * (1 - 1e-9));
      ExpectStaticEquilibrium(a, Configuration::Assembled(a), r);
    } else {
      ASSERT_FALSE(r.stable());
      const PartMotion* m = FindMotion(a, r, "cube");
      ASSERT_NE(m, nullptr);
      EXPECT_EQ(m->kind, MotionKind::kTips);
      EXPECT_FALSE(*r.static_equilibrium);
    }
  }
}

// ---------------------------------------------------------------------------
// Five unit boxes (1 × 1 × 0.5) stacked over a table's edge as the harmonic
// stack: box k from the top overhangs the box below by s/(2k) (the bottom one
// the table's edge by s/10). At s = 1 every sub-stack's centroid is exactly
// over its support's edge (the maximal overhang, ½ H₅ = 1.14 > 1: the top box
// is wholly beyond the table). s < 1 stands; s > 1 topples.
AssemblyDef HarmonicStack(double s, double mu) {
  AssemblyDef def;
  def.friction = mu;
  def.parts = {Box3("table", {-4, -2, -1}, {0, 2, 0}, true)};
  // Right edges: the table's at 0; box k's (k = 5 bottom … 1 top) at
  // s · Σ_{j ≥ k} 1/(2j).
  for (int k = 5; k >= 1; --k) {
    double right = 0;
    for (int j = k; j <= 5; ++j) right += s / (2.0 * j);
    const double z = 0.5 * (5 - k);
    def.parts.push_back(
        Box3("box" + std::to_string(6 - k), {right - 1, -0.5, z}, {right, 0.5, z + 0.5}));
  }
  return def;
}

TEST(HarmonicStack, FiveBoxesStandUpToTheHarmonicOverhang) {
  for (const double mu : {0.0, 0.5}) {
    SCOPED_TRACE("μ = " + std::to_string(mu));
    const Assembly stands = Assembly::Create(HarmonicStack(0.95, mu));
    const StabilityResult r = Analyze3d(stands);
    EXPECT_TRUE(r.stable()) << r.diagnostics;
    EXPECT_EQ(r.contacts.size(), 20u) << "five face-face patches of four vertices";
    ExpectStaticEquilibrium(stands, Configuration::Assembled(stands), r);
    // Each interface carries the weight of what is above it (all forces vertical).
    for (int level = 0; level < 5; ++level) {
      double load = 0;
      for (const ContactReport& cr : r.contacts) {
        const int lo = std::min(cr.contact.part_a, cr.contact.part_b);
        const int hi = std::max(cr.contact.part_a, cr.contact.part_b);
        if (lo == level && hi == level + 1) load += cr.normal_force;
      }
      const double above = (5 - level) * stands.part(1).mass * stands.gravity().norm();
      EXPECT_NEAR(load, above, 1e-9 * above) << "under box " << level + 1;
    }

    const Assembly topples = Assembly::Create(HarmonicStack(1.05, mu));
    const StabilityResult t = Analyze3d(topples);
    EXPECT_FALSE(t.stable());
    EXPECT_FALSE(*t.static_equilibrium);
    const PartMotion* top = FindMotion(topples, t, "box5");
    ASSERT_NE(top, nullptr);
    EXPECT_TRUE(top->moving);
    EXPECT_GT(top->angular.y(), 0.0) << "it turns over the edge: +y, the +x side drops";
  }
}

// ---------------------------------------------------------------------------
// Jamming (Pang and Trinkle's weak stability): a unit cube that exactly fits
// between two fixed walls, nothing under it, μ = 0.6. Forces exist that hold
// it (squeeze it with N ≥ m g / (2 μ) on each side), but nothing produces the
// squeeze from rest: the LCP lets it fall, the equilibrium LP finds the
// forces, and the configuration is flagged weakly stable. With a floor under
// it, it is simply stable.
TEST(Jamming3d, ACubeWedgedBetweenWallsIsWeaklyStable) {
  AssemblyDef def;
  def.friction = 0.6;
  def.parts = {Box3("left", {-1, -1, -2}, {0, 2, 2}, true),
               Box3("right", {1, -1, -2}, {2, 2, 2}, true), Box3("cube", {0, 0, 0}, {1, 1, 1})};
  const Assembly jammed = Assembly::Create(def);
  const StabilityResult r = Analyze3d(jammed);
  EXPECT_FALSE(r.stable());
  const PartMotion* m = FindMotion(jammed, r, "cube");
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->kind, MotionKind::kSlides) << "it slides down between the walls";
  EXPECT_LT(m->linear.z(), 0.0);
  ASSERT_TRUE(r.static_equilibrium.has_value()) << r.diagnostics;
  EXPECT_TRUE(*r.static_equilibrium);
  EXPECT_TRUE(r.weakly_stable);

  def.parts.push_back(Box3("floor", {0, -1, -1}, {1, 2, 0}, true));
  const StabilityResult floor = Analyze3d(Assembly::Create(def));
  EXPECT_TRUE(floor.stable());
  EXPECT_FALSE(floor.weakly_stable);
}

// The conservative verdict (StabilityOptions::conservative) never says a
// scene stands where the full verdict says it falls: on a stack of three
// boxes whose top one stands within b's top face or tips past it, and on a
// block jammed between two walls (friction could hold it, nothing squeezes
// it) with another on it. Where loading from rest decides that it gives
// way, every part of the component counts as moving (how is not sought).
TEST(ConservativeVerdict, NeverStandsWhereTheFullVerdictFalls) {
  std::vector<Assembly> scenes;
  for (const double offset : {0.3, 0.7}) {
    AssemblyDef def;
    def.friction = 0.5;
    def.parts = {Box3("ground", {-3, -3, -1}, {3, 3, 0}, true), Box3("a", {0, 0, 0}, {1, 1, 0.5}),
                 Box3("b", {0.3, 0, 0.5}, {1.3, 1, 1}),
                 Box3("c", {0.3 + offset, 0, 1}, {1.3 + offset, 1, 1.5})};
    scenes.push_back(Assembly::Create(def, "stack"));
  }
  AssemblyDef jammed = testing::JammedBlock(1.0);
  jammed.parts.push_back(testing::Box("on it", 0, 1, 1, 2));
  scenes.push_back(Assembly::Create(jammed, "jammed"));
  for (const Assembly& a : scenes) {
    SCOPED_TRACE(a.name());
    StabilityOptions full, quick;
    full.prove_strong = quick.prove_strong = false;
    quick.conservative = true;
    const StabilityResult f = AnalyzeConfiguration(a, Configuration::Assembled(a), full);
    const StabilityResult q = AnalyzeConfiguration(a, Configuration::Assembled(a), quick);
    ASSERT_NE(q.verdict, Verdict::kSolverFailure) << q.diagnostics;
    EXPECT_TRUE(!q.stable() || f.stable());
    if (a.name() != "jammed") {  // decided by the equilibrium: the same verdict
      EXPECT_EQ(q.stable(), f.stable());
      continue;
    }
    ASSERT_EQ(q.components.size(), 1u);
    ASSERT_TRUE(q.components[0].loaded_from_rest.has_value());
    EXPECT_EQ(*q.components[0].loaded_from_rest, LoadedFromRest::Outcome::kGivesWay);
    EXPECT_FALSE(q.stable());
    EXPECT_EQ(q.moving, (std::vector<int>{2, 3}));
  }
}

// Reuse mode (StabilityWorkspace::set_reuse_solutions): a scene with one
// more component (a box apart) than the one analysed before answers the
// shared component from the kept solution, and every contact force is the
// fresh check's, exactly.
TEST(ReuseSolutions, ASharedComponentIsAnsweredAsAFreshCheckAnswersIt) {
  AssemblyDef def;
  def.friction = 0.5;
  def.parts = {Box3("ground", {-5, -5, -1}, {5, 5, 0}, true), Box3("a", {0, 0, 0}, {1, 1, 0.5}),
               Box3("b", {0.3, 0, 0.5}, {1.3, 1, 1})};
  const Assembly two = Assembly::Create(def, "two");
  def.parts.push_back(Box3("apart", {3, 3, 0}, {4, 4, 1}));
  const Assembly three = Assembly::Create(def, "three");
  StabilityOptions o;
  o.prove_strong = false;
  StabilityWorkspace w;
  w.set_reuse_solutions(true);
  AnalyzeConfiguration(two, Configuration::Assembled(two), o, nullptr, &w);
  EXPECT_EQ(w.reused(), 0);
  const StabilityResult kept =
      AnalyzeConfiguration(three, Configuration::Assembled(three), o, nullptr, &w);
  EXPECT_EQ(w.reused(), 1);  // a and b's component; the box apart is new
  const StabilityResult fresh = AnalyzeConfiguration(three, Configuration::Assembled(three), o);
  ASSERT_TRUE(fresh.stable());
  EXPECT_EQ(kept.verdict, fresh.verdict);
  ASSERT_EQ(kept.contacts.size(), fresh.contacts.size());
  for (size_t c = 0; c < kept.contacts.size(); ++c) {
    EXPECT_EQ(kept.contacts[c].normal_force, fresh.contacts[c].normal_force) << c;
    EXPECT_EQ(kept.contacts[c].friction_force, fresh.contacts[c].friction_force) << c;
  }
}

}  // namespace
}  // namespace cairn

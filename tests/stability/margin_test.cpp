// cairn margin's physics (stability/margin.h): closed forms, an independent
// LP written here, and bisection over the check itself (AnalyzeConfiguration,
// the code of `cairn check`, with friction or gravity changed).
#include "cairn/stability/margin.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <functional>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/io/compas_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/mechanics/margin_lp.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Box;
using testing::ExamplePath;
using testing::SharedDir;

constexpr double kDegPerRad = 180.0 / M_PI;

struct Scene {
  AssemblyDef def;
  Assembly assembly;
  explicit Scene(AssemblyDef d) : def(std::move(d)), assembly(Assembly::Create(def)) {}
  Configuration config() const { return Configuration::Assembled(assembly); }
  MarginResult Margin(const MarginRequest& r) const {
    return ComputeMargin(def, assembly, config(), r);
  }
};

Scene Example(const std::string& name, std::optional<double> mu = std::nullopt) {
  AssemblyDef def = ReadSceneDef(ExamplePath(name));
  if (mu) def.friction = *mu;
  return Scene(def);
}

MarginRequest Friction() { return {}; }
MarginRequest Tilt(const Vector3& axis) {
  MarginRequest r;
  r.quantity = MarginQuantity::kTilt;
  r.axis = axis;
  return r;
}

// ---------------------------------------------------------------------------
// Bisection over the check: the verdict of AnalyzeConfiguration (what `cairn
// check` prints) on the model with its friction scaled, or its gravity
// turned. `holds(x)` must be true at `lo` and false at `hi` (or the reverse
// for a decreasing quantity); returns the boundary to `tol`.

double Bisect(const std::function<bool(double)>& holds, double lo, double hi, double tol) {
  const bool lo_holds = holds(lo);
  EXPECT_NE(lo_holds, holds(hi)) << "the bracket does not straddle the boundary";
  while (std::abs(hi - lo) > tol) {
    const double mid = 0.5 * (lo + hi);
    (holds(mid) == lo_holds ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The check's weak verdict: its `static_equilibrium` (rest possible), which
// is what the margin measures; `verdict` true: its verdict instead ("stable":
// also no moving solution found), which can fail earlier (jamming).
bool CheckStable(const AssemblyDef& def, bool verdict = false) {
  const Assembly a = Assembly::Create(def);
  StabilityOptions options;
  options.check_equilibrium = true;
  const StabilityResult r = AnalyzeConfiguration(a, Configuration::Assembled(a), options);
  return verdict ? r.stable() : r.static_equilibrium.value_or(false);
}

// μ* by bisection over the check with every μ scaled by k (base μ = 1 when
// the scene has no friction pairs, as the margin's).
double CheckCriticalFriction(const AssemblyDef& def, double hi) {
  AssemblyDef base = def;
  if (base.friction_pairs.empty()) base.friction = 1;
  return Bisect([&](double k) { return !CheckStable(ScaleFriction(base, k)); }, 0.0, hi, 1e-7);
}

// The critical tilt by bisection over the check with gravity turned by θ
// about `axis` in the assembly's frame (Rodrigues, −θ), in degrees.
double CheckCriticalTilt(const AssemblyDef& def, const Vector3& g, const Vector3& axis,
                         double hi_deg, bool verdict = false) {
  const Vector3 a = axis.normalized();
  return Bisect(
      [&](double deg) {
        const double t = deg / kDegPerRad;
        AssemblyDef d = def;
        d.gravity = std::cos(t) * g - std::sin(t) * a.cross(g) + (1 - std::cos(t)) * a.dot(g) * a;
        return CheckStable(d, verdict);
      },
      0.0, hi_deg, 1e-5);
}

// ---------------------------------------------------------------------------
// Closed forms.

// A block on an incline of angle θ slides when μ < tan θ (its weight's
// tangential part m g sin θ against μ m g cos θ); it is short enough (1 ×
// 0.5) not to tip first. examples/incline.json: θ = 20°; incline_slides: 30°.
TEST(Margin, InclineCriticalFrictionIsTanTheta) {
  for (const auto& [file, theta] :
       {std::pair{"incline.json", 20.0}, {"incline_slides.json", 30.0}}) {
    const Scene s = Example(file);
    const MarginResult r = s.Margin(Friction());
    ASSERT_TRUE(r.solved) << r.message;
    ASSERT_TRUE(r.sides[0].critical);
    EXPECT_NEAR(*r.sides[0].critical, std::tan(theta / kDegPerRad), 1e-5) << file;
    EXPECT_LE(r.tolerance, 1e-6);
    EXPECT_FALSE(r.factor);
    EXPECT_EQ(r.holds_at_nominal, theta < 25) << file;  // μ = 0.5 in both
    // Certificates: forces at μ*, a mechanism just below it moving the block.
    ASSERT_TRUE(r.sides[0].equilibrium);
    EXPECT_LT(r.sides[0].equilibrium->residual, 1e-8);
    ASSERT_TRUE(r.sides[0].mechanism);
    EXPECT_TRUE(r.sides[0].mechanism->found);
    ASSERT_EQ(r.failing_below.size(), 1u);
    EXPECT_EQ(r.failing_below[0].kind, MotionKind::kSlides);
    // Agreement with the check.
    EXPECT_NEAR(*r.sides[0].critical, CheckCriticalFriction(s.def, 2.0), 1e-5) << file;
  }
}

// The friction deficit (mechanics/margin_lp.h) of the same block: the
// friction it lacks is its weight's tangential part, m g sin θ, less the
// pyramid's k μ m g cos θ, in units of its weight (the largest load). So
// φ(k) = sin θ − k cos θ up to tan θ, its slope is −cos θ, Newton's first
// step from 0 lands on tan θ, and the margin takes four LPs: the deficit at
// k = 0, tan θ and the factor just below it, and the equilibrium LP that
// proves that factor fails (its deficit, 4e-7 of the weight, is too little
// work for the mechanism's check to tell it from the LP's tolerance).
TEST(Margin, InclineFrictionDeficitIsLinearAndNewtonLandsOnTanTheta) {
  const double theta = 20.0 / kDegPerRad;
  const Scene s = Example("incline.json", 1.0);
  const std::vector<ContactLcp> lcps = BuildComponentLcps(s.assembly, s.config());
  ASSERT_EQ(lcps.size(), 1u);
  FrictionDeficitLp deficit(lcps[0]);
  for (double k : {0.0, 0.1, 0.3}) {
    const FrictionDeficit d = deficit.Solve(k);
    ASSERT_TRUE(d.solved) << d.message;
    EXPECT_FALSE(d.exists) << k;
    EXPECT_NEAR(d.deficit, std::sin(theta) - k * std::cos(theta), 1e-9) << k;
    EXPECT_NEAR(d.slope, -std::cos(theta), 1e-9) << k;
  }
  const FrictionDeficit at = deficit.Solve(0.5);
  ASSERT_TRUE(at.exists);
  EXPECT_EQ(at.deficit, 0.0);
  EXPECT_LT(at.equilibrium.residual, 1e-9);
  const MarginResult r = s.Margin(Friction());
  EXPECT_NEAR(*r.sides[0].critical, std::tan(theta), 1e-6);
  EXPECT_EQ(r.lps, 4);
}

// A box of width w on a table tilted by θ: with friction enough not to slide
// (μ > tan θ), it tips when the gravity line through its centroid (height
// h/2) leaves the base: tan θ* = (w/2) / (h/2). Both senses, by symmetry.
TEST(Margin, BoxOnTableTipsAtAtanHalfWidthOverCentroidHeight) {
  AssemblyDef def;
  def.friction = 3.0;  // tan θ* = 2 < 3: tipping, not sliding
  def.parts = {Box("table", -3, -1, 3, 0, true), Box("box", -0.5, 0, 0.5, 0.5)};
  const Scene s(def);
  const MarginResult r = s.Margin(Tilt({0, 0, 1}));
  ASSERT_TRUE(r.solved) << r.message;
  const double expected = std::atan(0.5 / 0.25) * kDegPerRad;  // 63.43°
  ASSERT_TRUE(r.sides[0].critical && r.sides[1].critical);
  EXPECT_NEAR(*r.sides[0].critical, -expected, 1e-5);
  EXPECT_NEAR(*r.sides[1].critical, expected, 1e-5);
  EXPECT_NE(r.method.find("exact"), std::string::npos);
  // The mechanism just past it tips the box (it turns).
  ASSERT_TRUE(r.sides[1].mechanism && r.sides[1].mechanism->found);
  EXPECT_GT(std::abs(r.sides[1].mechanism->nu[0][5]), 1e-3);
  EXPECT_NEAR(*r.sides[1].critical, CheckCriticalTilt(def, {0, -9.81, 0}, {0, 0, 1}, 80), 1e-3);
  // A frictionless box slides at any tilt (0 both ways), and turned upside
  // down on nothing it holds nowhere.
  def.friction = 0;
  const MarginResult f = Scene(def).Margin(Tilt({0, 0, 1}));
  EXPECT_NEAR(*f.sides[0].critical, 0, 1e-9);
  EXPECT_NEAR(*f.sides[1].critical, 0, 1e-9);
}

// The same in 3-D: a 1 × 1 × 0.5 box on a table, μ 3, turned about x: it
// tips at atan(0.5 / 0.25). About the oblique axis (1, 0, 1) (not ⟂ g: the
// scan-and-bisection method), against bisection over the check with
// gravity turned by Rodrigues' formula.
TEST(Margin, Box3dTiltExactAndOblique) {
  AssemblyDef def;
  def.friction = 3.0;
  def.parts = {testing::Box3("table", {-2, -2, -1}, {2, 2, 0}, true),
               testing::Box3("box", {-0.5, -0.5, 0}, {0.5, 0.5, 0.5})};
  const Scene s(def);
  const MarginResult x = s.Margin(Tilt({1, 0, 0}));
  ASSERT_TRUE(x.solved) << x.message;
  EXPECT_NEAR(*x.sides[1].critical, std::atan(2.0) * kDegPerRad, 1e-5);
  EXPECT_NEAR(*x.sides[0].critical, -std::atan(2.0) * kDegPerRad, 1e-5);
  const Vector3 oblique(1, 0, 1);
  const MarginResult o = s.Margin(Tilt(oblique));
  ASSERT_TRUE(o.solved) << o.message;
  EXPECT_EQ(o.method.find("exact"), std::string::npos);
  ASSERT_TRUE(o.sides[1].critical);
  EXPECT_NEAR(*o.sides[1].critical, CheckCriticalTilt(def, s.assembly.gravity(), oblique, 120),
              1e-3);
  // About the vertical the load never changes: the box holds all the way
  // round, by the one equilibrium LP at 0, as a turned check agrees.
  const MarginResult v = s.Margin(Tilt({0, 0, 1}));
  ASSERT_TRUE(v.solved) << v.message;
  EXPECT_NE(v.method.find("exact"), std::string::npos);
  EXPECT_FALSE(v.sides[0].critical);
  EXPECT_FALSE(v.sides[1].critical);
  EXPECT_EQ(v.lps, 1);
  EXPECT_TRUE(CheckStable(def));
  // On a table too slippery to hold it (tilted 30° about x, μ 0.1 < tan 30°)
  // a turn about the (turned) gravity fails at once, both ways.
  AssemblyDef slippery = def;
  slippery.friction = 0.1;
  slippery.gravity = Vector3(0, 9.81 * std::sin(M_PI / 6), -9.81 * std::cos(M_PI / 6));
  ASSERT_FALSE(CheckStable(slippery));
  const Scene t(slippery);
  const MarginResult w = t.Margin(Tilt(-*slippery.gravity));
  ASSERT_TRUE(w.solved) << w.message;
  ASSERT_TRUE(w.sides[0].critical && w.sides[1].critical);
  EXPECT_EQ(*w.sides[0].critical, 0.0);
  EXPECT_EQ(*w.sides[1].critical, 0.0);
  ASSERT_TRUE(w.sides[1].mechanism);
  EXPECT_TRUE(w.sides[1].mechanism->found);
}

// The leaning ladder (examples/ladder.json: 60°, floor μ 0.35, frictionless
// wall, thickness 0.05): the wall's push N_w balances the floor's friction,
// N_w y_top = m g (x_foot − x_c) (moments about the foot), so μ* = (x_foot −
// x_c)/y_top = (l cos θ/2 − t sin θ/2)/(l sin θ) (LadderCriticalMu). The
// scene has a friction pair, so the margin is the factor k* on every μ:
// k* · 0.35 = μ*.
TEST(Margin, LadderCriticalFrictionMatchesFormulaWithThickness) {
  const Scene s = Example("ladder.json");
  const MarginResult r = s.Margin(Friction());
  ASSERT_TRUE(r.solved) << r.message;
  EXPECT_TRUE(r.factor);
  ASSERT_TRUE(r.sides[0].critical);
  EXPECT_NEAR(*r.sides[0].critical * 0.35, testing::LadderCriticalMu(M_PI / 3), 1e-6);
  EXPECT_TRUE(r.holds_at_nominal);
  EXPECT_NEAR(*r.sides[0].critical, CheckCriticalFriction(s.def, 1.0), 1e-5);
  // Below it the ladder moves (slides at its foot, turning about the wall).
  ASSERT_EQ(r.failing_below.size(), 1u);
  EXPECT_EQ(s.assembly.part(r.failing_below[0].part).name, "ladder");
}

// The paper's Figs. 15–16: part P on a plate Q standing on a base of half
// width d = 0.48 (Fig. 16; Fig. 15's base is as wide as the plate). Eq. 8:
// the moment of the loads about O over d is at most the total vertical
// support force. With a downward load F at x = X on Q's top, about the
// base's edge: F (X − d) ≤ d W, W = (m_Q + m_P) g, so F* = d W / (X − d).
// Fig. 15 (base edge under the plate's end) carries any load at X = 5.
TEST(Margin, PaperFig16LoadMarginIsEquation8) {
  const Scene s = Example("paper_fig16.json");
  MarginRequest req;
  req.quantity = MarginQuantity::kLoad;
  req.part = s.assembly.FindPart("Q");
  req.point = {5, 1.5, 0};
  req.direction = {0, -1, 0};
  const MarginResult r = s.Margin(req);
  ASSERT_TRUE(r.solved) << r.message;
  const double g = s.assembly.gravity().norm();
  const double W =
      (s.assembly.part(req.part).mass + s.assembly.part(s.assembly.FindPart("P")).mass) * g;
  const double d = 0.48;
  ASSERT_TRUE(r.sides[0].critical);
  EXPECT_NEAR(*r.sides[0].critical, d * W / (5 - d), 1e-6 * W);
  EXPECT_NEAR(r.part_weight, s.assembly.part(req.part).mass * g, 1e-12);
  ASSERT_TRUE(r.sides[0].mechanism && r.sides[0].mechanism->found);
  // The same load on Fig. 15's part: carried, however large.
  const Scene wide = Example("paper_fig15.json");
  req.part = wide.assembly.FindPart("Q");
  const MarginResult any = wide.Margin(req);
  ASSERT_TRUE(any.solved) << any.message;
  EXPECT_FALSE(any.sides[0].critical);
}

// The overhang (examples/overhang.json: block [−1.4, 0.6] × [0, 1] on a
// table ending at x = 0; centroid (−0.4, 0.5)), with μ 3 so that it tips
// before it slides. Turned by +θ (counter-clockwise), gravity leans to −x in
// its frame: it tips about its own corner (−1.4, 0), tan θ = 1.0 / 0.5;
// turned by −θ, about the table's edge (0, 0): tan θ = 0.4 / 0.5.
TEST(Margin, OverhangTiltClosedForm) {
  const Scene s = Example("overhang.json", 3.0);
  const MarginResult r = s.Margin(Tilt({0, 0, 1}));
  ASSERT_TRUE(r.solved) << r.message;
  EXPECT_NEAR(*r.sides[1].critical, std::atan(1.0 / 0.5) * kDegPerRad, 1e-5);
  EXPECT_NEAR(*r.sides[0].critical, -std::atan(0.4 / 0.5) * kDegPerRad, 1e-5);
  const Vector3 g = s.assembly.gravity();
  EXPECT_NEAR(*r.sides[0].critical, -CheckCriticalTilt(s.def, g, {0, 0, -1}, 60), 1e-3);
  // overhang_tips.json does not stand: 0 both ways, and a mechanism at 0.
  const MarginResult tips = Example("overhang_tips.json", 3.0).Margin(Tilt({0, 0, 1}));
  EXPECT_FALSE(tips.holds_at_nominal);
  EXPECT_EQ(tips.sides[1].critical, std::optional<double>(0.0));
  ASSERT_TRUE(tips.sides[1].mechanism);
  EXPECT_TRUE(tips.sides[1].mechanism->found);
}

// ---------------------------------------------------------------------------
// An independent LP, written here in the *friction-force* form (not the
// generator form of mechanics/): at contact c, f = N n + a t₁ + b t₂ with
// |a| + |b| ≤ μ N (D = 4: the pyramid conv{±t₁, ±t₂}, the same cone as the
// generators n + μ d_k at angles 0°, 90°, 180°, 270°); in 2-D f = N n + a t,
// |a| ≤ μ N. Per body: Σ f + F = 0 and Σ (p − c) × f = 0, with the load
// F = m (g − s (a × g)) for the tilt (gravity turned by θ, divided by cos θ,
// s = tan θ) or F = m g for friction. Maximise (or minimise) s, or (objective
// 0) test feasibility.
struct IndependentLp {
  // Returns the optimal s (tilt), or for tilt == false whether a solution
  // exists (1 or 0). NaN when Clp fails.
  static double Solve(const ContactLcp& lcp, double mu_scale, const Vector3* tilt_axis,
                      bool maximize) {
    const int nb = static_cast<int>(lcp.bodies.size());
    const bool is3d = lcp.num_directions != 2;
    const int per = is3d ? 5 : 3;  // N, a⁺, a⁻ (, b⁺, b⁻)
    const int nc = static_cast<int>(lcp.contacts.size());
    const int s_col = per * nc;
    const int ncols = s_col + 1;
    const int nrows = 6 * nb + nc;
    std::vector<int> rows, cols;
    std::vector<double> vals;
    const auto add = [&](int r, int c, double v) {
      if (v != 0) rows.push_back(r), cols.push_back(c), vals.push_back(v);
    };
    std::vector<int> body_of(1000000, -1);
    for (int b = 0; b < nb; ++b) body_of[lcp.bodies[b].part] = b;
    for (int c = 0; c < nc; ++c) {
      const Contact& k = lcp.contacts[c];
      const auto [t1, t2] = TangentBasis(k.n_W);
      const Vector3 t = is3d ? t1 : k.t_W();
      std::vector<Vector3> dirs = {k.n_W, t, -t};
      if (is3d) dirs.push_back(t2), dirs.push_back(-t2);
      for (int side = 0; side < 2; ++side) {
        const int part = side == 0 ? k.part_a : k.part_b;
        if (part < 0 || body_of[part] < 0) continue;
        const int b = body_of[part];
        const double sign = side == 0 ? 1.0 : -1.0;
        const Vector3 r = k.p_WC - lcp.bodies[b].p_WBcm;
        for (int j = 0; j < per; ++j) {
          const Vector3 f = sign * dirs[j];
          const Vector3 tau = r.cross(f);
          for (int i = 0; i < 3; ++i) add(6 * b + i, per * c + j, f[i]);
          for (int i = 0; i < 3; ++i) add(6 * b + 3 + i, per * c + j, is3d || i == 2 ? tau[i] : 0);
        }
      }
      // Σ friction components − μ N ≤ 0.
      add(6 * nb + c, per * c, -k.mu * mu_scale);
      for (int j = 1; j < per; ++j) add(6 * nb + c, per * c + j, 1.0);
    }
    std::vector<double> row_lo(nrows), row_hi(nrows);
    for (int b = 0; b < nb; ++b) {
      const Vector3 g = lcp.bodies[b].F_ext.head<3>();  // m g
      for (int i = 0; i < 3; ++i) row_lo[6 * b + i] = row_hi[6 * b + i] = -g[i];
      for (int i = 3; i < 6; ++i) row_lo[6 * b + i] = row_hi[6 * b + i] = 0;
      if (tilt_axis) {
        const Vector3 w = -tilt_axis->cross(g);  // s · (−m a × g) on the load side
        for (int i = 0; i < 3; ++i) add(6 * b + i, s_col, w[i]);
      }
    }
    for (int c = 0; c < nc; ++c) row_lo[6 * nb + c] = -COIN_DBL_MAX, row_hi[6 * nb + c] = 0;
    std::vector<double> col_lo(ncols, 0.0), col_hi(ncols, COIN_DBL_MAX), cost(ncols, 0.0);
    col_lo[s_col] = tilt_axis ? -COIN_DBL_MAX : 0.0;
    col_hi[s_col] = tilt_axis ? COIN_DBL_MAX : 0.0;
    cost[s_col] = maximize ? -1.0 : 1.0;
    CoinPackedMatrix m(true, rows.data(), cols.data(), vals.data(),
                       static_cast<CoinBigIndex>(vals.size()));
    m.setDimensions(nrows, ncols);
    ClpSimplex lp;
    lp.setLogLevel(0);
    lp.loadProblem(m, col_lo.data(), col_hi.data(), cost.data(), row_lo.data(), row_hi.data());
    lp.primal();
    if (!tilt_axis) return lp.status() == 0 ? 1.0 : lp.status() == 1 ? 0.0 : NAN;
    return lp.status() == 0 ? lp.primalColumnSolution()[s_col] : NAN;
  }
};

// The V-notch wedges of compas_cra (type-c: tall, type-d: short; faces 30°
// from horizontal, μ 0.84, supports 0 and 1), turned about +y: the critical
// tilts by the independent LP (max and min of s = tan θ, |θ| < 90°), against
// the margin's. The dataset's README gives 65.71° and 70.03°.
TEST(Margin, CompasWedgesCriticalTiltAgainstIndependentLp) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  for (const auto& [file, known] : {std::pair{"type-c.json", 65.71}, {"type-d.json", 70.03}}) {
    CompasOptions options;
    options.friction = 0.84;
    const std::string path = SharedDir() + "/datasets/compas_cra/" + file;
    CompasModel model = CompasToModel(ReadCompasAssembly(path), options, path);
    for (PartDef& p : model.def.parts)
      if (p.name == "0" || p.name == "1") p.fixed = true;
    const Scene s(model.def);
    const Vector3 axis(0, 1, 0);
    const MarginResult r = s.Margin(Tilt(axis));
    ASSERT_TRUE(r.solved) << r.message;
    const std::vector<ContactLcp> lcps = BuildComponentLcps(s.assembly, s.config());
    ASSERT_EQ(lcps.size(), 1u);
    const double hi = std::atan(IndependentLp::Solve(lcps[0], 1.0, &axis, true)) * kDegPerRad;
    const double lo = std::atan(IndependentLp::Solve(lcps[0], 1.0, &axis, false)) * kDegPerRad;
    ASSERT_TRUE(r.sides[0].critical && r.sides[1].critical) << file;
    EXPECT_NEAR(*r.sides[1].critical, hi, 1e-5) << file;
    EXPECT_NEAR(*r.sides[0].critical, lo, 1e-5) << file;
    EXPECT_NEAR(std::abs(*r.sides[1].critical), known, 0.01) << file;
    // And the check, bisected on the turned gravity: its static equilibrium
    // agrees; its verdict, which also asks Lemke's method for a moving
    // solution, gives way no later (type-c: at 64.50°, where the wedge can
    // still rest but need not: weakly stable).
    const Vector3 g = s.assembly.gravity();
    EXPECT_NEAR(*r.sides[1].critical, CheckCriticalTilt(s.def, g, axis, 85), 1e-3) << file;
    EXPECT_LE(CheckCriticalTilt(s.def, g, axis, 85, true), *r.sides[1].critical + 1e-3) << file;
  }
}

// A semicircular arch of 7 voussoirs (radii 1 and 1.25, radial joints) on a
// fixed ground, μ 1.
AssemblyDef SevenVoussoirArch() {
  AssemblyDef def;
  def.friction = 1.0;
  def.parts.push_back(Box("ground", -3, -1, 3, 0, true));
  const int n = 7;
  for (int i = 0; i < n; ++i) {
    PartDef p;
    p.name = "v";  // (not "v" + …: GCC 12 warns wrongly of an overflow there)
    p.name += std::to_string(i);
    const double a0 = M_PI * i / n, a1 = M_PI * (i + 1) / n;
    for (const auto& [r, a] : {std::pair{1.0, a0}, {1.25, a0}, {1.25, a1}, {1.0, a1}})
      p.polygon.push_back(Vector2(r * std::cos(a), r * std::sin(a)));
    // Counter-clockwise: inner a0, outer a0, outer a1, inner a1 runs clockwise.
    std::reverse(p.polygon.begin(), p.polygon.end());
    def.parts.push_back(p);
  }
  return def;
}

// The arch: its critical μ (the joints near the springing slide first)
// by bisection over the independent LP's feasibility, against the margin's.
TEST(Margin, ArchCriticalFrictionAgainstIndependentLp) {
  const AssemblyDef def = SevenVoussoirArch();
  const Scene s(def);
  const MarginResult r = s.Margin(Friction());
  ASSERT_TRUE(r.solved) << r.message;
  ASSERT_TRUE(r.sides[0].critical);
  const std::vector<ContactLcp> lcps = BuildComponentLcps(s.assembly, s.config());
  ASSERT_EQ(lcps.size(), 1u);
  const double mu =
      Bisect([&](double k) { return IndependentLp::Solve(lcps[0], k, nullptr, true) > 0.5; }, 2.0,
             0.0, 1e-8);
  EXPECT_GT(mu, 0.01);  // the arch needs friction
  EXPECT_NEAR(*r.sides[0].critical, mu, 1e-5);
  EXPECT_NEAR(*r.sides[0].critical, CheckCriticalFriction(def, 2.0), 1e-4);
  // The mechanism just below μ*: at a factor within 10⁻³ of it where the
  // independent LP finds no equilibrium; along it gravity does work and no
  // contact resists: every pyramid edge n ± μ t at that factor has power ≥ 0.
  ASSERT_TRUE(r.sides[0].mechanism);
  const MarginMechanism& m = *r.sides[0].mechanism;
  ASSERT_TRUE(m.found) << m.message;
  EXPECT_LT(m.at, *r.sides[0].critical);
  EXPECT_GE(m.at, *r.sides[0].critical * (1 - 1e-3));
  EXPECT_LT(IndependentLp::Solve(lcps[0], m.at, nullptr, true), 0.5);
  EXPECT_GT(m.power, 0);
  const ContactLcp& lcp = lcps[0];
  std::vector<Vector6> nu(lcp.bodies.size(), Vector6::Zero());
  for (size_t i = 0; i < m.parts.size(); ++i)
    for (size_t b = 0; b < lcp.bodies.size(); ++b)
      if (lcp.bodies[b].part == m.parts[i]) nu[b] = m.nu[i];
  const int D = lcp.num_directions;
  for (size_t c = 0; c < lcp.contacts.size(); ++c) {
    const int f = lcp.friction_of[c];
    ASSERT_GE(f, 0);
    for (int i = 0; i < D; ++i)
      EXPECT_GE(lcp.normal_rows[c].Dot(nu) +
                    m.at * lcp.contacts[c].mu * lcp.direction_rows[D * f + i].Dot(nu),
                -1e-9)
          << "contact " << c << ", direction " << i;
  }
}

// On the arch the deficit is not linear: its slope changes with k as the
// forces redistribute. Newton's step from below, k + φ/|φ'|, still at least
// halves the distance to μ* from every k below it (from 0.99 μ* it lands
// 2e-5 past μ*: φ is not convex there, which is why the steps are
// safeguarded), and the margin needs far fewer LPs than the ~20 of a
// bisection to 1e-6.
TEST(Margin, ArchFrictionDeficitNewtonStepsStayBelowCritical) {
  const AssemblyDef def = SevenVoussoirArch();
  const Scene s(def);
  const MarginResult r = s.Margin(Friction());
  ASSERT_TRUE(r.sides[0].critical);
  const double critical = *r.sides[0].critical;
  EXPECT_LE(r.lps, 12);  // 10: half the bisection's 22
  FrictionDeficitLp deficit(BuildComponentLcps(s.assembly, s.config())[0]);
  for (double f : {0.0, 0.3, 0.6, 0.9, 0.99}) {
    const double k = f * critical;
    const FrictionDeficit d = deficit.Solve(k);
    ASSERT_TRUE(d.solved) << d.message;
    ASSERT_GT(d.deficit, 0) << k;
    ASSERT_LT(d.slope, 0) << k;
    const double newton = k + d.deficit / -d.slope;
    EXPECT_LE(std::abs(newton - critical), 0.5 * (critical - k)) << "from " << k;
  }
}

// The same request gives the same answer, bit for bit.
TEST(Margin, Deterministic) {
  const Scene s = Example("ladder.json");
  const MarginResult a = s.Margin(Friction()), b = s.Margin(Friction());
  EXPECT_EQ(*a.sides[0].critical, *b.sides[0].critical);
  EXPECT_EQ(a.lps, b.lps);
}

// A request that makes no sense is bad input.
TEST(Margin, RejectsNonsense) {
  const Scene s = Example("incline.json");
  MarginRequest req;
  req.quantity = MarginQuantity::kLoad;
  req.part = s.assembly.FindPart("incline");  // fixed
  req.direction = {1, 0, 0};
  EXPECT_THROW(s.Margin(req), InputError);
  req.part = s.assembly.FindPart("block");
  req.direction = {0, 0, 0};
  EXPECT_THROW(s.Margin(req), InputError);
  EXPECT_THROW(s.Margin(Tilt({1, 0, 0})), InputError);  // 2-D: only about z
}

// compas_cra's cube-curve-short on its stored (curved, triangulated)
// interfaces stands without friction: the check's frictionless equilibrium
// LP finds one. The friction deficit LP, solved by the interior-point
// method there, gives φ(0) = 1.7e-9, its objective's tolerance: read as a
// failure, it would put μ* at 0.0437741. The margin is 0, proved by that
// equilibrium, and strong stability holds at every μ.
TEST(Margin, FrictionZeroWhereItStandsFrictionless) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  const std::string path = SharedDir() + "/datasets/compas_cra/cube-curve-short.json";
  CompasOptions options;
  options.friction = 0.84;
  options.stored_interfaces = true;
  CompasModel model = CompasToModel(ReadCompasAssembly(path), options, path);
  for (PartDef& p : model.def.parts) p.fixed = p.name == "0";
  const Scene s(model.def);
  EquilibriumOptions frictionless;
  frictionless.frictionless = true;
  for (const ContactLcp& lcp : BuildComponentLcps(s.assembly, s.config()))
    ASSERT_TRUE(FindStaticEquilibrium(lcp, frictionless).exists);
  const MarginResult r = s.Margin(Friction());
  ASSERT_TRUE(r.solved) << r.message;
  ASSERT_TRUE(r.sides[0].critical.has_value());
  EXPECT_EQ(*r.sides[0].critical, 0.0);
  EXPECT_EQ(r.strong_all, true);
  EXPECT_TRUE(r.holds_at_nominal);
  EXPECT_FALSE(r.failing_at.has_value());
  ASSERT_TRUE(r.sides[0].equilibrium.has_value());
  for (const Vector3& f : r.sides[0].equilibrium->friction_force) EXPECT_EQ(f, Vector3::Zero());
}

// compas_cra's H: a bar between two fixed posts, touching only their
// vertical faces. It stands at every μ > 0 (squeezed, with forces of about
// 1/μ loads) and not at 0. Below μ 1e-6 those forces' roundoff approaches
// the re-check's bound, and the margin stops there: μ* ≤ 1e-6, the bracket
// from 0 (proved: no frictionless equilibrium) to μ*, the check at 0.
TEST(Margin, FrictionOfAJammedBarStopsAtTheLeastResolved) {
  if (SharedDir().empty()) GTEST_SKIP() << "../shared (the COMPAS datasets) is absent";
  const std::string path = SharedDir() + "/datasets/compas_cra/H.json";
  CompasOptions options;
  options.friction = 0.84;
  CompasModel model = CompasToModel(ReadCompasAssembly(path), options, path);
  for (PartDef& p : model.def.parts) p.fixed = p.name == "0" || p.name == "1";
  const Scene s(model.def);
  const MarginResult r = s.Margin(Friction());
  ASSERT_TRUE(r.solved) << r.message;
  ASSERT_TRUE(r.sides[0].critical.has_value());
  const double mu = *r.sides[0].critical;
  EXPECT_GT(mu, 0);
  EXPECT_LE(mu, 1e-6);
  EXPECT_EQ(r.tolerance, mu);
  EXPECT_EQ(r.failing_at, 0.0);
  EXPECT_EQ(r.strong_all, false);
  EXPECT_FALSE(CheckStable(ScaleFriction(s.def, 0.0)));
  EXPECT_TRUE(CheckStable(ScaleFriction(s.def, mu / 0.84 * 1.001)));
  ASSERT_TRUE(r.sides[0].mechanism.has_value());
  EXPECT_TRUE(r.sides[0].mechanism->found);
}

}  // namespace
}  // namespace cairn

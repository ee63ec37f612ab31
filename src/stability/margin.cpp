#include "cairn/stability/margin.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "cairn/core/error.h"
#include "cairn/core/format.h"
#include "cairn/core/tolerances.h"
#include "cairn/core/unit_vector.h"
#include "cairn/mechanics/lp_policy.h"
#include "cairn/mechanics/margin_lp.h"
#include "cairn/mechanics/static_equilibrium.h"

namespace cairn {

namespace {

// The friction margin stops when its bracket [lo, hi] is narrower than this
// fraction of hi (dimensionless).
constexpr double kFrictionTolerance = 1e-6;
// The least friction coefficient the margin resolves (dimensionless): where
// a component stands by jamming (compas_cra's H: a bar squeezed between two
// posts stands at every μ > 0, not at 0), its equilibrium at μ needs forces
// of about 1/μ loads, and below this their roundoff approaches the
// equilibrium re-check's bound (1e-7 of the load). Once hi is below it the
// search stops: μ* is in [lo, hi] (lo proved, often 0) and `tolerance` says
// so.
constexpr double kMinFriction = 1e-6;
// A guard on the friction margin's steps (each at least halves the bracket
// once Newton's steps are slow; 3–12 are taken on the examples and the
// vaults, up to 44 where the safeguard bisects, COMPAS's A.json).
constexpr int kMaxFrictionSteps = 200;

// Where the certificates of failure are taken: this fraction of the
// critical value past it (dimensionless; a mechanism exactly at the critical
// value does no work, and one at 1e-6 past it does too little to pass the
// mechanism's check), and at least kPastAngle past a critical tilt.
constexpr double kPastStep = 1e-3;
constexpr double kPastAngle = 0.01 * M_PI / 180.0;  // rad

// The relative accuracy of a critical value read from an LP's optimum
// (dimensionless): the equilibrium re-check's residual bound.
constexpr double kLpRelative = 1e-7;

// The general tilt (the axis not ⟂ gravity): the scan's step before the
// bisection, and the bisection's final bracket (rad).
constexpr double kTiltScanStep = 5.0 * M_PI / 180.0;
constexpr double kTiltTolerance = 1e-7;

// The axis counts as perpendicular to gravity below this |a·ĝ|, and as
// along gravity above 1 minus it
// (dimensionless).
constexpr double kPerpendicular = 1e-12;

constexpr double kDeg = 180.0 / M_PI;

using Loads = std::vector<Vector6>;

Loads GravityLoads(const ContactLcp& lcp) {
  Loads out;
  for (const BodyDynamics& b : lcp.bodies) out.push_back(b.F_ext);
  return out;
}

Loads Scaled(const Loads& a, double s) {
  Loads out = a;
  for (Vector6& w : out) w *= s;
  return out;
}

Loads Sum(const Loads& a, const Loads& b) {
  Loads out = a;
  for (size_t i = 0; i < out.size(); ++i) out[i] += b[i];
  return out;
}

// Does the component stand under `load` (one equilibrium LP)?
// Only yes or no is wanted, not the mechanism: below kCarriedSimplexColumns
// generator columns the dual simplex alone answers (on Jenga's 2496 columns,
// a load it does not carry took the interior-point method's 60 iterations
// and then the mechanism LP: 53 ms). A budget of kCarriedSimplexIterations
// pivots bounds it; past that the full policy decides.
constexpr int kCarriedSimplexColumns = 8000;
constexpr int kCarriedSimplexIterations = 100000;

// The LPs one margin asks of a component: how many were solved, and the
// first that failed numerically (Clp stopped on trouble, or forces that fail
// their re-check however solved). A failure is a status, as everywhere in
// Cairn: once one is recorded, Carried and End answer at once without solving,
// the searches stop, and the margin is reported unsolved with its message.
struct LpLedger {
  int solved = 0;
  std::string failure;
  bool failed() const { return !failure.empty(); }
  void Fail(std::string message) {
    if (failure.empty()) failure = std::move(message);
  }
};

// Whether `load` is carried (false, too, once the ledger holds a failure).
bool Carried(const ContactLcp& lcp, const Loads& load, bool frictionless, LpLedger* lps) {
  if (lps->failed()) return false;
  EquilibriumOptions options;
  options.frictionless = frictionless;
  int columns = 0;
  for (int f : lcp.friction_of) columns += f < 0 || frictionless ? 1 : lcp.num_directions;
  StaticEquilibrium e;
  if (columns < kCarriedSimplexColumns) {
    EquilibriumOptions simplex = options;
    simplex.max_iterations = kCarriedSimplexIterations;
    e = FindStaticEquilibrium(WithLoads(lcp, load), simplex);
  }
  if (!e.solved) e = FindStaticEquilibrium(WithLoads(lcp, load), options);
  ++lps->solved;
  if (!e.solved) lps->Fail("equilibrium LP failed: " + e.message);
  return e.solved && e.exists;
}

MarginEquilibrium ToCertificate(const ContactLcp& lcp, const StaticEquilibrium& e, double at,
                                double scale = 1.0) {
  MarginEquilibrium out;
  out.at = at;
  out.contacts = lcp.contacts;
  out.normal_force = e.normal_force * scale;
  for (const Vector3& f : e.friction_force) out.friction_force.push_back(f * scale);
  out.residual = e.residual * scale;
  return out;
}

// The mechanism just past an LP's end, checked at `past` (the component
// with the load there): the LP's own duals when they pass the check, which
// saves the mechanism LP; else the mechanism LP.
Mechanism MechanismPast(const ContactLcp& past, const LoadParameterResult& lp) {
  if (lp.status == LoadParameterResult::Status::kOptimal && !lp.motion.empty()) {
    Mechanism m = VerifyMechanism(past, lp.motion);
    if (m.found) return m;
  }
  return FindMechanism(past);
}

// A part's radius about its centroid (length): the reach ClassifyRigidMotion
// measures a turn's axis against.
double PartRadius(const Part& part) {
  double radius = 0;
  for (const Vector3& v : part.vertices) radius = std::max(radius, (v - part.centroid).norm());
  return radius;
}

MarginMechanism ToCertificate(const Assembly& assembly, const ContactLcp& lcp, const Mechanism& m,
                              double at) {
  MarginMechanism out;
  out.at = at;
  out.found = m.found;
  out.message = m.message;
  out.power = m.power;
  for (int b : m.moving) {
    const int p = lcp.bodies[b].part;
    out.parts.push_back(p);
    out.nu.push_back(m.nu[b]);
    out.kinds.push_back(ClassifyRigidMotion(m.nu[b].head<3>(), m.nu[b].tail<3>(), true,
                                            PartRadius(assembly.part(p)), assembly.scene_size()));
  }
  return out;
}

// ---------------------------------------------------------------------------
// The load margin: max s ≥ 0 with F_ext + s F₁ carried, F₁ the wrench of a
// unit force along d at P on the loaded body: (d, (P − c) × d).

struct Interval {
  std::optional<double> end;  // empty: unbounded
  bool empty = false;         // no s on this side holds
  LoadParameterResult lp;     // the optimum's LP (when bounded)
};

// The end of S = {s : F0 + s F1 carried} on one side (max or min): the
// parametric LP; where it finds no finite end, the exact unboundedness test
// of mechanics/margin_lp.h (F1 alone carried) confirms it.
Interval End(const ContactLcp& lcp, const Loads& F0, const Loads& F1, bool maximize,
             double lower_bound, bool frictionless, LpLedger* lps) {
  Interval out;
  if (lps->failed()) return out;
  out.lp = OptimizeLoadParameter(WithLoads(lcp, F0), F1, maximize, lower_bound, frictionless);
  ++lps->solved;
  using S = LoadParameterResult::Status;
  if (out.lp.status == S::kOptimal) {
    out.end = out.lp.value;
    return out;
  }
  if (out.lp.status == S::kInfeasible) {
    out.empty = true;
    return out;
  }
  // No finite end: exactly when the load alone is carried (S is not empty:
  // the LP would have said infeasible). The equilibrium LP confirms it, and
  // decides when the parametric LP failed.
  if (Carried(lcp, maximize ? F1 : Scaled(F1, -1.0), frictionless, lps)) {
    if (out.lp.status == S::kUnbounded || Carried(lcp, F0, frictionless, lps)) {
      out.lp = {};
      return out;
    }
    out.empty = true;
    return out;
  }
  if (!lps->failed())
    lps->Fail("margin LP: " + (out.lp.status == S::kUnbounded
                                   ? std::string("unbounded although the load alone is not carried")
                                   : out.lp.message));
  return out;
}

// A ledger's failure as the result's status. False when the margin stops.
bool Report(const LpLedger& lps, MarginResult& r) {
  if (!lps.failed()) return true;
  r.solved = false;
  r.message = lps.failure;
  return false;
}

// Closes one component's margin: its LP count, and its failure, if any.
bool Close(const LpLedger& lps, ComponentMargin& cm, MarginResult& r) {
  cm.lps = lps.solved;
  return Report(lps, r);
}

void LoadMargin(const Assembly& assembly, const std::vector<ContactLcp>& lcps,
                const MarginRequest& req, MarginResult& r) {
  r.method = "parametric equilibrium LP (max F)";
  r.sides.resize(1);
  MarginSide& side = r.sides[0];
  const Part& part = assembly.part(req.part);
  r.part_weight = part.mass * assembly.gravity().norm();
  for (size_t c = 0; c < lcps.size(); ++c) {
    const ContactLcp& lcp = lcps[c];
    ComponentMargin& cm = r.components[c];
    LpLedger lps;
    int body = -1;
    for (size_t b = 0; b < lcp.bodies.size(); ++b)
      if (lcp.bodies[b].part == req.part) body = static_cast<int>(b);
    const Loads F0 = GravityLoads(lcp);
    if (body < 0) {  // not loaded: it only has to stand
      cm.holds_at_nominal = Carried(lcp, F0, false, &lps);
      cm.critical.push_back(std::nullopt);
      if (!Close(lps, cm, r)) return;
      continue;
    }
    side.component = static_cast<int>(c);
    Loads F1(lcp.bodies.size(), Vector6::Zero());
    F1[body].head<3>() = req.direction;
    F1[body].tail<3>() = (req.point - lcp.bodies[body].p_WBcm).cross(req.direction);
    Interval s = End(lcp, F0, F1, true, 0.0, false, &lps);
    if (!Close(lps, cm, r)) return;
    cm.holds_at_nominal = !s.empty;
    cm.critical.push_back(s.empty ? std::optional<double>(0.0) : s.end);
    if (s.end && !s.empty) {
      side.equilibrium = ToCertificate(lcp, s.lp.equilibrium, *s.end);
      const double past = *s.end * (1 + kPastStep) + kPastStep * r.part_weight;
      side.mechanism = ToCertificate(
          assembly, lcp, MechanismPast(WithLoads(lcp, Sum(F0, Scaled(F1, past))), s.lp), past);
    }
    if (s.empty) side.mechanism = ToCertificate(assembly, lcp, FindMechanism(lcp), 0.0);
    // The strong range: the same LP with normal forces only (left empty when
    // not even the unloaded assembly has a frictionless equilibrium).
    LpLedger strong_lps;
    const Interval strong = End(lcp, F0, F1, true, 0.0, true, &strong_lps);
    if (strong_lps.failed()) lps.Fail(strong_lps.failure);
    if (!Close(lps, cm, r)) return;
    if (!strong.empty) side.strong = strong.end;
    side.critical = cm.critical.back();
  }
  r.tolerance = side.critical ? kLpRelative * std::max(*side.critical, r.part_weight) : 0.0;
}

// ---------------------------------------------------------------------------
// The tilt margin (mechanics/margin_lp.h): with F0 = m g and F1 = −m (a × g),
// the load at angle θ is cos θ F0 + sin θ F1 (a ⟂ g). Per unit |cos θ|:
//   L⁺(t) = F0 + t F1, θ = atan t ∈ (−90°, 90°);
//   L⁻(t) = −F0 − t F1, θ = 180° + atan t ∈ (90°, 270°)
// (θ = ±90°: ±F1). Going up from 0: L⁺ up to its max t, unless F1 is carried
// (then θ = 90° holds and L⁺ is unbounded above); then L⁻ from t = −∞ up to
// its max, unless −F1 is carried (θ = 270° holds); then L⁺ from −∞ back to 0,
// which holds. Going down: the mirror image.

// The angle of the first failure in one sense (rad, signed), empty: none.
struct TiltEnd {
  bool empty = false;  // no t at all is carried (S is empty)
  std::optional<double> theta;
  LoadParameterResult lp;  // the deciding LP
  double cos_scale = 1;    // |cos θ| (the LP's loads are per unit of it)
};

TiltEnd TiltSense(const ContactLcp& lcp, const Loads& F0, const Loads& F1, bool positive,
                  bool frictionless, LpLedger* lps) {
  TiltEnd out;
  const double inf = -std::numeric_limits<double>::infinity();
  const Interval near = End(lcp, F0, F1, positive, inf, frictionless, lps);
  if (near.empty) {
    out.empty = true;
    return out;
  }
  if (near.end) {
    out.theta = std::atan(*near.end);
    out.lp = near.lp;
    out.cos_scale = std::cos(*out.theta);
    return out;
  }
  // Past ±90°: L⁻ = −F0 − t F1, entered from t = ∓∞.
  const Interval far = End(lcp, Scaled(F0, -1), Scaled(F1, -1), positive, inf, frictionless, lps);
  if (far.empty) {
    out.theta = positive ? M_PI / 2 : -M_PI / 2;
    out.cos_scale = 0;
    return out;
  }
  if (!far.end) return out;  // all the way round
  out.theta = positive ? M_PI + std::atan(*far.end) : -M_PI + std::atan(*far.end);
  out.lp = far.lp;
  out.cos_scale = std::abs(std::cos(*out.theta));
  return out;
}

// Gravity turned by θ about a in the assembly's frame (Rodrigues with −θ).
Vector3 TurnedGravity(const Vector3& g, const Vector3& a, double theta) {
  return std::cos(theta) * g - std::sin(theta) * a.cross(g) + (1 - std::cos(theta)) * a.dot(g) * a;
}

Loads TiltLoads(const ContactLcp& lcp, const Vector3& g) {
  Loads out;
  for (const BodyDynamics& b : lcp.bodies) {
    Vector6 w = Vector6::Zero();
    w.head<3>() = b.mass * g;
    out.push_back(w);
  }
  return out;
}

// The general axis (a·g ≠ 0): a scan by kTiltScanStep, then a bisection on
// the first step that fails; every probe one equilibrium LP.
std::optional<double> TiltBisect(const ContactLcp& lcp, const Vector3& g, const Vector3& a,
                                 bool positive, LpLedger* lps) {
  const double sign = positive ? 1.0 : -1.0;
  const auto holds = [&](double theta) {
    return Carried(lcp, TiltLoads(lcp, TurnedGravity(g, a, sign * theta)), false, lps);
  };
  double lo = 0, hi = -1;
  for (double theta = kTiltScanStep; theta < 2 * M_PI + 0.5 * kTiltScanStep;
       theta += kTiltScanStep) {
    if (!holds(std::min(theta, 2 * M_PI))) {
      hi = std::min(theta, 2 * M_PI);
      break;
    }
    lo = theta;
  }
  if (hi < 0) return std::nullopt;
  while (hi - lo > kTiltTolerance) {
    const double mid = 0.5 * (lo + hi);
    (holds(mid) ? lo : hi) = mid;
  }
  return sign * lo;
}

void TiltMargin(const Assembly& assembly, const std::vector<ContactLcp>& lcps,
                const MarginRequest& req, MarginResult& r) {
  const Vector3 g = assembly.gravity();
  const Vector3 a = *UnitVector(req.axis);  // CheckMarginRequest refused a zero axis
  r.axis = a;
  const Vector3 down = UnitVector(g).value_or(Vector3::Zero());
  const bool exact = std::abs(a.dot(down)) <= kPerpendicular;
  // An axis along gravity turns the assembly without changing its load: it
  // holds at every angle or at none.
  const bool along = std::abs(a.dot(down)) >= 1 - kPerpendicular;
  r.method = exact   ? "parametric equilibrium LP in tan θ (exact)"
             : along ? "axis along gravity: the turn leaves the load unchanged (exact)"
                     : "scan by 5° and bisection over equilibrium LPs";
  r.tolerance = exact || along ? 0 : kTiltTolerance * kDeg;
  r.sides.resize(2);
  for (size_t c = 0; c < lcps.size(); ++c) {
    const ContactLcp& lcp = lcps[c];
    ComponentMargin& cm = r.components[c];
    LpLedger lps;
    const Loads F0 = GravityLoads(lcp);
    // Both ends first where the axis is exact: S = {t : F0 + t F1 carried}
    // is an interval, and the assembly stands as it is exactly when it holds
    // 0, so the two LPs of the ends also answer that, without the
    // equilibrium LP. Elsewhere the equilibrium LP answers it.
    TiltEnd ends[2];
    if (exact) {
      const Loads F1 = TiltLoads(lcp, -a.cross(g));
      for (int s = 0; s < 2; ++s) ends[s] = TiltSense(lcp, F0, F1, s == 1, false, &lps);
      cm.holds_at_nominal = !ends[0].empty && (!ends[0].theta || *ends[0].theta <= 0) &&
                            (!ends[1].theta || *ends[1].theta >= 0);
    } else {
      cm.holds_at_nominal = Carried(lcp, F0, false, &lps);
    }
    if (!Close(lps, cm, r)) return;
    cm.critical.assign(2, std::nullopt);
    for (int s = 0; s < 2; ++s) {
      const bool positive = s == 1;
      if (!cm.holds_at_nominal) {
        // It fails as it stands: 0 in both senses, the mechanism at 0.
        cm.critical[s] = 0.0;
        MarginSide& side = r.sides[s];
        if (side.critical && *side.critical == 0.0) continue;
        side.critical = 0.0;
        side.component = static_cast<int>(c);
        side.equilibrium.reset();
        side.mechanism = ToCertificate(assembly, lcp, FindMechanism(lcp), 0.0);
        continue;
      }
      std::optional<double> theta;
      const TiltEnd& end = ends[s];
      if (exact) {
        theta = end.theta;
      } else if (!along) {
        theta = TiltBisect(lcp, g, a, positive, &lps);
        if (!Close(lps, cm, r)) return;
      }
      if (theta) cm.critical[s] = *theta * kDeg;
      // This component decides the sense when it fails first.
      MarginSide& side = r.sides[s];
      const bool first =
          theta && (!side.critical || std::abs(*theta * kDeg) < std::abs(*side.critical));
      if (!first) continue;
      side.critical = *theta * kDeg;
      side.component = static_cast<int>(c);
      const Loads at = TiltLoads(lcp, TurnedGravity(g, a, *theta));
      if (exact && end.lp.status == LoadParameterResult::Status::kOptimal) {
        side.equilibrium = ToCertificate(lcp, end.lp.equilibrium, *side.critical, end.cos_scale);
      } else {
        const StaticEquilibrium e = FindStaticEquilibrium(WithLoads(lcp, at));
        if (e.exists) side.equilibrium = ToCertificate(lcp, e, *side.critical);
      }
      const double step = std::max(kPastStep * std::abs(*theta), kPastAngle);
      const double past = *theta + (positive ? step : -step);
      const ContactLcp past_lcp = WithLoads(lcp, TiltLoads(lcp, TurnedGravity(g, a, past)));
      side.mechanism = ToCertificate(
          assembly, lcp, exact ? MechanismPast(past_lcp, end.lp) : FindMechanism(past_lcp),
          past * kDeg);
      if (exact && end.lp.status == LoadParameterResult::Status::kOptimal)
        r.tolerance = std::max(r.tolerance, kLpRelative * std::abs(*side.critical));
    }
  }
  // The strong range per sense: the frictionless LP's tilt margin (exact axis
  // only), the least over components.
  bool nominal = true;
  for (const ComponentMargin& cm : r.components) nominal = nominal && cm.holds_at_nominal;
  if (!exact || !nominal) return;
  // Each component's frictionless ends, both senses. Where a component has
  // no frictionless equilibrium as it stands, strong stability is certified
  // at no angle, and the strong ranges are left empty. The ends say so
  // themselves (0 ∉ the frictionless S); but where their LPs go to the
  // interior-point method (large components), which is slow to find S empty,
  // and that is common, the equilibrium LP is asked first (on the cross
  // vault: 1.24 s against 3.3–4.0 s for the whole tilt margin).
  std::vector<std::array<TiltEnd, 2>> ends(lcps.size());
  for (size_t c = 0; c < lcps.size(); ++c) {
    const ContactLcp& lcp = lcps[c];
    LpLedger lps;  // not counted: the strong range certifies, like the certificates
    const bool ask_first =
        FirstLpMethod(LpForm::kParametric, static_cast<int>(lcp.contacts.size()) + 1) !=
        LpMethod::kDualSimplex;
    if (ask_first && !Carried(lcp, GravityLoads(lcp), true, &lps)) {
      Report(lps, r);
      return;
    }
    for (int s = 0; s < 2; ++s)
      ends[c][s] =
          TiltSense(lcp, GravityLoads(lcp), TiltLoads(lcp, -a.cross(g)), s == 1, true, &lps);
    if (!Report(lps, r)) return;
    const TiltEnd& below = ends[c][0];
    const TiltEnd& above = ends[c][1];
    if (below.empty || (below.theta && *below.theta > 0) || (above.theta && *above.theta < 0))
      return;
  }
  for (int s = 0; s < 2; ++s) {
    std::optional<double> strong;
    bool all = true;
    for (size_t c = 0; c < lcps.size(); ++c) {
      const TiltEnd& e = ends[c][s];
      if (!e.theta) continue;
      all = false;
      const double deg = *e.theta * kDeg;
      if (!strong || std::abs(deg) < std::abs(*strong)) strong = deg;
    }
    r.sides[s].strong = all ? std::optional<double>() : strong;
  }
}

// ---------------------------------------------------------------------------
// The friction margin: per component the least factor k at which the
// friction deficit φ(k) (mechanics/margin_lp.h) vanishes, by Newton's method
// from below, safeguarded by bisection. Feasibility is monotone in k; the
// component's k* is the least feasible k to kFrictionTolerance, the
// assembly's the largest over components.
//
// Why Newton from below: where φ is convex on [lo, k*] the tangent at lo lies
// below φ, so its root lo + φ(lo)/|φ'(lo)| is at most k*, and near k* the
// steps converge quadratically (φ'(k*) < 0 on every scene measured). φ need
// not be convex (on a 7-voussoir arch the step from 0.99 k* lands 2e-5 past
// k*), so the steps are safeguarded: a probe past k* stands and becomes hi;
// when Newton's factor is at or past hi, the factor just below hi is tried
// once (it fails when k* = hi), then bisection until a new lo brings a new
// tangent; two slow steps in a row also bisect. Every end is proved: hi by
// an equilibrium whose friction use is hi, lo by a mechanism or by the
// equilibrium LP finding none (a positive deficit alone is not a proof: see
// NewtonFriction).

struct FrictionBracket {
  std::optional<double> hi;  // least k found feasible (verified); empty: none up to k_max
  double lo = 0;             // greatest k proved infeasible (0 when none was)
  bool lo_proved = false;    // some probe at lo was proved infeasible
  StaticEquilibrium at_hi;
  // The deficit LP's dual motion at lo (a mechanism there, unverified).
  std::vector<Vector6> motion_at_lo;
};

// What one probe of the friction margin proved at a factor.
enum class Probe {
  kStands,     // an equilibrium, re-checked from its forces
  kFails,      // a mechanism, or the equilibrium LP finds none
  kUndecided,  // a positive deficit that neither proves nor refutes
};

FrictionBracket NewtonFriction(const ContactLcp& lcp, double k_max, LpLedger* lps) {
  FrictionBracket out;
  FrictionDeficitLp deficit(lcp);
  // Below this factor a jammed component's equilibrium needs forces of
  // 1/(k μ) loads (a squeeze), beyond what its re-check can tell from
  // roundoff: the search stops once hi is there (kMinFriction).
  const double k_floor = kMinFriction * k_max / limits::kMaxFriction;
  // `lo` may rest on an undecided probe (its deficit still steers Newton's
  // steps); `proved` is the greatest factor proved to fail.
  double lo = 0, phi_lo = 0, slope_lo = 0;
  std::vector<Vector6> motion_lo;
  // A component whose margin LPs go to the interior-point method.
  int columns = 0;
  for (int f : lcp.friction_of) columns += f < 0 ? 1 : lcp.num_directions;
  const bool large = FirstLpMethod(LpForm::kParametric, columns + 1) != LpMethod::kDualSimplex;
  bool proved_any = false;
  double proved = 0;
  // A factor proved to stand: hi is the friction use ρ ≤ k of its verified
  // equilibrium (the same forces stand from ρ on).
  const auto stands = [&](double k, StaticEquilibrium e) {
    out.hi = std::max(proved, std::min(k, FrictionUse(lcp, e)));
    out.at_hi = std::move(e);
    if (lo > *out.hi) {  // an undecided lo that stands after all
      lo = proved;
      phi_lo = slope_lo = 0;
      motion_lo.clear();
    }
    return Probe::kStands;
  };
  // One probe. The bracket's ends move on proofs: hi on an equilibrium
  // re-checked from its forces; `proved` on a positive deficit whose dual
  // motion passes the mechanism's check at k (VerifyMechanism), or else on
  // the equilibrium LP at k finding none (at k = 0: the frictionless
  // equilibrium, the question `cairn check` asks at μ = 0). A deficit is the
  // optimum of an LP solved to its solver's tolerance (the interior-point
  // method's objective is good to its gap): near 0 it proves nothing.
  const auto probe = [&](double k) {
    if (lps->failed()) return Probe::kUndecided;
    FrictionDeficit d = deficit.Solve(k);
    if (!d.solved) {
      lps->Fail("friction deficit LP failed at factor " + std::to_string(k) + ": " + d.message);
      return Probe::kUndecided;
    }
    if (std::isinf(d.deficit)) {  // no factor holds
      lo = proved = k_max;
      proved_any = true;
      return Probe::kFails;
    }
    if (d.exists) return stands(k, std::move(d.equilibrium));
    const ContactLcp at_k = WithFrictionFactor(lcp, k);
    bool fails = d.deficit > 0 && VerifyMechanism(at_k, d.motion).found;
    if (!fails && (k == 0 || !large)) {
      EquilibriumOptions options;
      options.frictionless = k == 0;
      StaticEquilibrium e = FindStaticEquilibrium(at_k, options);
      ++lps->solved;
      if (e.solved && e.exists) return stands(k, std::move(e));
      fails = e.solved;
    } else if (!fails) {
      // A large component near k*: the equilibrium LP is slow to decide there
      // (on the cross vault 1e-9 below k* its simplex ran for seconds and its
      // forces failed the re-check); the mechanism LP may prove it fails, and
      // otherwise the factor stays undecided.
      fails = FindMechanism(at_k).found;
      ++lps->solved;
    }
    if (k >= lo) {
      lo = k;
      phi_lo = d.deficit, slope_lo = d.slope;
      motion_lo = std::move(d.motion);
    }
    if (!fails) return Probe::kUndecided;
    proved = std::max(proved, k);
    proved_any = true;
    return Probe::kFails;
  };
  // 1. Frictionless? Then k* = 0, proved by that equilibrium.
  probe(0.0);
  int slow = 0;           // steps in a row that left over half the bracket
  double confirmed = -1;  // the lo from which the factor below hi was tried
  double crept = -1;      // the last factor tried just above lo (lo when it failed)
  int proofs = 0;         // factors below hi tried to prove an undecided lo
  const auto within = [&](double below) {
    return out.hi && (*out.hi - below <= kFrictionTolerance * *out.hi || *out.hi <= k_floor);
  };
  for (int i = 0;
       i < kMaxFrictionSteps && !lps->failed() && !within(proved) && (out.hi || proved < k_max);
       ++i) {
    // 2. The next factor: Newton's from lo (a lower estimate of k*); once it
    // is within the tolerance of lo, a factor just above it, which should
    // stand and close the bracket; a bisection when Newton's factor is past
    // hi or its steps are slow, or when lo's deficit gives no step (a
    // deficit at the LP's tolerance, or the factor just above lo failed).
    // Where the bracket closed on an undecided lo, factors further below hi
    // (by 1, 10, 100, 1000 times the tolerance) until one is proved to fail.
    if (!out.hi && lo >= k_max) break;  // undecided at the largest factor
    const double newton = slope_lo < 0 && phi_lo > 0 && crept != lo
                              ? lo + phi_lo / -slope_lo
                              : std::numeric_limits<double>::infinity();
    double k = newton;
    if (within(lo)) {
      k = std::max(proved, *out.hi * (1 - std::pow(10.0, proofs++) * kFrictionTolerance));
      if (proofs > 4) k = proved;  // prove nothing closer: the tolerance is hi − proved
      if (k == proved) break;
      lo = proved;  // the undecided lo no longer steers
    } else if (out.hi && !(newton < *out.hi) && confirmed != lo) {
      // Newton's factor is hi itself (or past it): k* = hi, unless the
      // factor just below hi stands too.
      k = std::max(lo, *out.hi * (1 - 0.9 * kFrictionTolerance));
      confirmed = lo;
    } else if (out.hi && (!(newton < *out.hi) || slow >= 2)) {
      k = 0.5 * (lo + *out.hi);
    } else if (!out.hi && !(newton < k_max)) {
      k = k_max;
    } else if (newton - lo <= 0.4 * kFrictionTolerance * newton) {
      k = lo + 0.9 * kFrictionTolerance * newton;
      crept = k;
    }
    const double before = out.hi ? *out.hi - lo : 0;
    probe(k);
    slow = before > 0 && *out.hi - lo > 0.5 * before ? slow + 1 : 0;
  }
  lps->solved += deficit.lps();
  out.lo = proved;
  out.lo_proved = proved_any;
  if (lo == proved) out.motion_at_lo = std::move(motion_lo);
  return out;
}

// The mechanism just below k*: the deficit LP's own dual motion at lo (the
// greatest factor proved failing, within the tolerance of k*) when it passes
// the mechanism's check there; else the mechanism LP kPastStep below k*, or
// at lo where the bracket is wider than that (near k* gravity does so little
// work along the motion that the check's slack can refuse it).
MarginMechanism FrictionMechanism(const Assembly& scene, const ContactLcp& lcp,
                                  const FrictionBracket& b) {
  if (b.lo_proved && !b.motion_at_lo.empty()) {
    const Mechanism m = VerifyMechanism(WithFrictionFactor(lcp, b.lo), b.motion_at_lo);
    if (m.found) return ToCertificate(scene, lcp, m, b.lo);
  }
  const double past = std::min(*b.hi * (1 - kPastStep), b.lo_proved ? b.lo : *b.hi);
  return ToCertificate(scene, lcp, FindMechanism(WithFrictionFactor(lcp, past)), past);
}

// The verdict's threshold is found to this relative bracket (dimensionless:
// each step is a whole check, seconds on the shelves under the sanitizers),
// and looked for up to this multiple of the larger of k* and the nominal μ
// (dimensionless): friction far beyond any material's is not a margin.
constexpr double kVerdictBracket = 1e-2;
constexpr double kVerdictReach = 10;

// The threshold of the verdict (MarginResult::verdict_critical): the least
// factor at which `cairn check` stands. Below the equilibrium's k* nothing
// can stand; from k* up the check decides: first a bracket by doubling from
// k* (up to k_max), then bisection on the check. It assumes the verdict is
// monotone in μ, as it is on every shared model and bundled example
// (tests/cli/model_test.cpp, FrictionMonotone).
void VerdictThreshold(const FrictionScaling& scaling, const Assembly& scene,
                      const Configuration& config, VerdictRule rule, MarginResult& r) {
  r.verdict_computed = true;
  const MarginSide& side = r.sides[0];
  if (!side.critical) return;  // no equilibrium at any μ: it never stands
  StabilityOptions options;
  options.rule = rule;
  options.prove_strong = false;  // only the verdict
  const auto stands = [&](double k) {
    ++r.verdict_checks;
    return AnalyzeConfiguration(scaling.At(scene, k), config, options).stable();
  };
  double lo = *side.critical, hi = lo;
  const double top =
      std::min(scaling.k_max, kVerdictReach * std::max({lo, r.nominal, kVerdictBracket}));
  r.verdict_searched_to = top;
  if (stands(hi)) {
    r.verdict_critical = hi;
    r.verdict_tolerance = r.tolerance;
    return;
  }
  // Bracket: double from k* until it stands (the check at `top` last).
  do {
    lo = hi;
    hi = std::min(top, std::max(2 * hi, kVerdictBracket));
    if (stands(hi)) break;
    if (hi >= top) return;  // falls at every μ up to `top`
  } while (true);
  while (hi - lo > kVerdictBracket * hi) {
    const double mid = 0.5 * (lo + hi);
    (stands(mid) ? hi : lo) = mid;
  }
  r.verdict_critical = hi;
  r.verdict_tolerance = hi - lo;
}

// The largest value in [0, end] up to which `stands` holds, for a verdict
// that stands at 0 and is monotone along the way (as the equilibrium is: the
// check's threshold is inside the equilibrium's): the end itself when it
// stands there, else bisection to kVerdictBracket of the end. The result's
// tolerance grows to the final bracket.
double LargestStanding(double end, const std::function<bool(double)>& stands, MarginResult& r) {
  if (stands(end)) return end;
  double lo = 0, hi = end;
  while (hi - lo > kVerdictBracket * end) {
    const double mid = 0.5 * (lo + hi);
    (stands(mid) ? lo : hi) = mid;
  }
  r.verdict_tolerance = std::max(r.verdict_tolerance, hi - lo);
  return lo;
}

// The steps (degrees) of the scan for the verdict's tilt where the
// equilibrium holds all the way round, and the largest load (in the part's
// weights) the verdict's load is looked for up to where any load is carried.
constexpr double kVerdictTiltScan = 30;
constexpr double kVerdictLoadReach = 1e3;

// The verdict's threshold per tilt sense (MarginSide::verdict_critical):
// gravity turned by θ about the axis, the check as `cairn check` makes it.
void VerdictTilt(const Assembly& assembly, const Configuration& config, const MarginRequest& req,
                 MarginResult& r) {
  r.verdict_computed = true;
  StabilityOptions options;
  options.rule = req.rule;
  options.prove_strong = false;  // only the verdict
  const Vector3 g = assembly.gravity();
  for (int s = 0; s < 2; ++s) {
    MarginSide& side = r.sides[s];
    const double sign = s == 1 ? 1.0 : -1.0;
    if (!r.stands_at_nominal) {
      side.verdict_critical = 0.0;
      continue;
    }
    const auto stands = [&](double deg) {
      ++r.verdict_checks;
      const Assembly turned = assembly.WithGravity(TurnedGravity(g, r.axis, sign * deg / kDeg));
      return AnalyzeConfiguration(turned, config, options).stable();
    };
    if (side.critical) {
      side.verdict_critical = sign * LargestStanding(std::abs(*side.critical), stands, r);
      continue;
    }
    // The equilibrium holds all the way round: scan for a failing check.
    r.verdict_searched_to = 360;
    double lo = 0;
    for (double deg = kVerdictTiltScan; deg <= 360; deg += kVerdictTiltScan) {
      if (!stands(deg)) {
        const double failing = deg;
        const auto from_lo = [&](double x) { return stands(lo + x); };
        side.verdict_critical = sign * (lo + LargestStanding(failing - lo, from_lo, r));
        break;
      }
      lo = deg;
    }
  }
}

// The verdict's threshold for the load (MarginSide::verdict_critical): the
// force along the direction at the point, added to gravity.
void VerdictLoad(const Assembly& assembly, const Configuration& config, const MarginRequest& req,
                 MarginResult& r) {
  r.verdict_computed = true;
  MarginSide& side = r.sides[0];
  if (!r.stands_at_nominal) {
    side.verdict_critical = 0.0;
    return;
  }
  StabilityOptions options;
  options.rule = req.rule;
  options.prove_strong = false;  // only the verdict
  const auto stands = [&](double f) {
    ++r.verdict_checks;
    options.loads = {PartLoad{req.part, f * req.direction, req.point}};
    return AnalyzeConfiguration(assembly, config, options).stable();
  };
  if (side.critical) {
    side.verdict_critical = LargestStanding(*side.critical, stands, r);
    return;
  }
  // Any load is carried at rest: double from the part's weight.
  const double top = kVerdictLoadReach * std::max(r.part_weight, 1e-300);
  r.verdict_searched_to = top;
  double lo = 0;
  for (double f = std::max(r.part_weight, 1e-300); f <= top; f *= 2) {
    if (!stands(f)) {
      const auto from_lo = [&](double x) { return stands(lo + x); };
      side.verdict_critical = lo + LargestStanding(f - lo, from_lo, r);
      return;
    }
    lo = f;
  }
}

// `lcps` are the components of the base model (scaling.At(scene, 1)).
void FrictionMargin(const FrictionScaling& scaling, const Assembly& scene,
                    const Configuration& config, const std::vector<ContactLcp>& lcps,
                    VerdictRule rule, MarginResult& r) {
  r.factor = scaling.factor;
  r.nominal = scaling.nominal;
  const double k_max = scaling.k_max;
  r.method =
      "Newton's method from below on the friction deficit LP (safeguarded by bisection; "
      "interior point on large components)";
  r.sides.resize(1);
  MarginSide& side = r.sides[0];
  bool any_friction_needed = false, unbounded = false;
  double deciding_lo = 0;  // the deciding component's greatest factor proved to fail
  for (size_t c = 0; c < lcps.size(); ++c) {
    const ContactLcp& lcp = lcps[c];
    ComponentMargin& cm = r.components[c];
    LpLedger lps;
    FrictionBracket b = NewtonFriction(lcp, k_max, &lps);
    if (!Close(lps, cm, r)) return;
    cm.critical.push_back(b.hi);
    cm.holds_at_nominal = b.hi && *b.hi <= r.nominal;
    any_friction_needed = any_friction_needed || !b.hi || *b.hi > 0;
    if (unbounded) continue;  // a component no friction holds decides already
    if (!b.hi) {
      // No friction up to the largest allowed holds this component.
      unbounded = true;
      side.component = static_cast<int>(c);
      side.critical.reset();
      side.equilibrium.reset();
      side.mechanism =
          ToCertificate(scene, lcp, FindMechanism(WithFrictionFactor(lcp, k_max)), k_max);
      continue;
    }
    r.tolerance = std::max(r.tolerance, *b.hi - b.lo);
    if (side.component >= 0 && *side.critical >= *b.hi) continue;
    // The component that needs the most friction decides.
    side.component = static_cast<int>(c);
    side.critical = b.hi;
    deciding_lo = b.lo;
    side.equilibrium = ToCertificate(WithFrictionFactor(lcp, *b.hi), b.at_hi, *b.hi);
    side.mechanism.reset();
    if (*b.hi > 0) side.mechanism = FrictionMechanism(scene, lcp, b);
  }
  // Strong stability: a frictionless equilibrium in every component (k* = 0
  // everywhere, proved by it) certifies it at every μ.
  r.strong_all = !any_friction_needed && !unbounded;
  // Which parts move just below μ*, and how: the check there (at the
  // proved lower end, where the bracket is wider: kMinFriction).
  if (side.critical && *side.critical > 0) {
    const double below = std::min(*side.critical * (1 - kPastStep), deciding_lo);
    r.failing_at = below;
    const Assembly weaker = scaling.At(scene, below);
    StabilityOptions options;
    options.check_equilibrium = true;
    const StabilityResult check = AnalyzeConfiguration(weaker, config, options);
    for (const PartMotion& m : check.parts)
      if (m.moving && m.role == PartRole::kJudged) r.failing_below.push_back(m);
  }
  VerdictThreshold(scaling, scene, config, rule, r);
}

}  // namespace

void CheckMarginRequest(const Assembly& assembly, const MarginRequest& req,
                        const std::string& file) {
  if (req.quantity == MarginQuantity::kTilt) {
    if (!req.axis.allFinite()) throw InputError(file, "--tilt", "must be finite numbers");
    if (!UnitVector(req.axis)) throw InputError(file, "--tilt", "the axis must not be zero");
    if (!assembly.is_3d() && (req.axis.x() != 0 || req.axis.y() != 0))
      throw InputError(file, "--tilt",
                       "a 2-D scene turns in its plane: the axis must be 0,0,1 or 0,0,-1");
  }
  if (req.quantity == MarginQuantity::kLoad) {
    if (req.part < 0 || req.part >= assembly.num_parts())
      throw InputError(file, "--load", "no such part");
    if (assembly.part(req.part).fixed)
      throw InputError(file, "--load",
                       "part \"" + assembly.part(req.part).name +
                           "\" is fixed: a load on it goes to the ground");
    if (!req.point.allFinite()) throw InputError(file, "--point", "must be finite numbers");
    if (req.point.cwiseAbs().maxCoeff() > limits::kMaxCoordinate)
      throw InputError(file, "--point",
                       "must be within the scene's coordinate range, |x| <= " +
                           FormatNumber(limits::kMaxCoordinate));
    if (!req.direction.allFinite()) throw InputError(file, "--direction", "must be finite numbers");
    if (!UnitVector(req.direction))
      throw InputError(file, "--direction", "must not be the zero vector");
    if (!assembly.is_3d() && (req.direction.z() != 0 || req.point.z() != 0))
      throw InputError(file, "--direction", "a 2-D scene takes 2 numbers");
  }
}

const char* to_string(MarginQuantity q) {
  switch (q) {
    case MarginQuantity::kFriction:
      return "friction";
    case MarginQuantity::kTilt:
      return "tilt";
    case MarginQuantity::kLoad:
      return "load";
  }
  return "?";
}

FrictionScaling FrictionScalingOf(const AssemblyDef& def) {
  FrictionScaling s;
  s.factor = !def.friction_pairs.empty();
  s.base_mu = s.factor ? def.friction : 1.0;
  s.nominal = s.factor ? 1.0 : def.friction;
  double largest_mu = s.factor ? def.friction : 1.0;
  for (const FrictionPairDef& p : def.friction_pairs) largest_mu = std::max(largest_mu, p.mu);
  s.k_max = limits::kMaxFriction / std::max(largest_mu, 1e-300);
  return s;
}

AssemblyDef ScaleFriction(const AssemblyDef& def, double factor) {
  AssemblyDef out = def;
  out.friction *= factor;
  for (FrictionPairDef& p : out.friction_pairs) p.mu *= factor;
  return out;
}

MarginResult ComputeMargin(const AssemblyDef& def, const Assembly& assembly,
                           const Configuration& config, const MarginRequest& request) {
  MarginRequest req = request;
  CheckMarginRequest(assembly, req);
  if (req.quantity == MarginQuantity::kLoad && !config.present[req.part])
    throw InputError("", "--load",
                     "part \"" + assembly.part(req.part).name + "\" is taken away (--without)");
  if (req.quantity == MarginQuantity::kLoad) req.direction = *UnitVector(req.direction);
  MarginResult r;
  r.quantity = req.quantity;
  // 1. The components, as the check splits them: of the scene, or for the
  // friction margin of its base model (μ = 1, or the pairs as they are),
  // whose factor k the margin finds.
  const FrictionScaling scaling = FrictionScalingOf(def);
  const bool friction = req.quantity == MarginQuantity::kFriction;
  const std::vector<ContactLcp> lcps =
      BuildComponentLcps(friction ? scaling.At(assembly, 1.0) : assembly, config);
  for (const ContactLcp& lcp : lcps) {
    ComponentMargin cm;
    for (const BodyDynamics& b : lcp.bodies) cm.parts.push_back(b.part);
    r.components.push_back(cm);
  }
  // 2–4. Each component's margin, the worst one's, the certificates (an LP
  // that fails stops them: r.solved, r.message).
  switch (req.quantity) {
    case MarginQuantity::kFriction:
      FrictionMargin(scaling, assembly, config, lcps, req.rule, r);
      break;
    case MarginQuantity::kTilt:
      TiltMargin(assembly, lcps, req, r);
      break;
    case MarginQuantity::kLoad:
      LoadMargin(assembly, lcps, req, r);
      break;
  }
  // 5. The check's verdict as given, and its threshold (tilt, load; the
  // friction margin found its own above). The equilibrium rule's verdict is
  // the equilibrium's: its thresholds are the LPs', with no check.
  StabilityOptions options;
  options.rule = req.rule;
  options.prove_strong = false;  // only the verdict
  r.stands_at_nominal = r.solved && AnalyzeConfiguration(assembly, config, options).stable();
  if (r.solved && req.quantity != MarginQuantity::kFriction) {
    if (req.rule == VerdictRule::kEquilibrium) {
      r.verdict_computed = true;
      for (MarginSide& side : r.sides)
        side.verdict_critical = r.stands_at_nominal ? side.critical : std::optional(0.0);
    } else if (req.quantity == MarginQuantity::kTilt) {
      VerdictTilt(assembly, config, req, r);
    } else {
      VerdictLoad(assembly, config, req, r);
    }
  }
  r.holds_at_nominal = true;
  for (const ComponentMargin& cm : r.components) {
    r.lps += cm.lps;
    r.holds_at_nominal = r.holds_at_nominal && cm.holds_at_nominal;
  }
  return r;
}

}  // namespace cairn

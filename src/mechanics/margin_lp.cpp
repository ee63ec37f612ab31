#include "cairn/mechanics/margin_lp.h"

#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <limits>
#include <optional>
#include <vector>

#include "cairn/mechanics/lp_policy.h"
#include "mechanics/clp_solve.h"
#include "mechanics/equilibrium_lp.h"

namespace cairn {

using equilibrium_internal::EquilibriumLp;
using equilibrium_internal::kSimplexPrimalTolerance;
using equilibrium_internal::Load;
using equilibrium_internal::MakeEquilibriumLp;
using equilibrium_internal::MotionOfDuals;
using equilibrium_internal::ReadEquilibrium;
using equilibrium_internal::Triplets;

namespace {

// The largest generator amount of the margin LP's last attempt, in units of
// the largest load (dimensionless): a force this large leaves a roundoff of
// 1e-10 of the load in the balance, far below the re-check's 1e-7; a vertex
// with a self-stress of 1e9 loads fails it (Fig. 6 tilted in its plane).
constexpr double kMaxGeneratorLoads = 1e6;

// Solves the parametric LP `lp` from scratch by the LP policy
// (cairn/mechanics/lp_policy.h: the interior-point method from
// kParametricBarrierColumns columns on; the cross vault's tilt margin takes
// 1.2 s so, 1.9 s with crossover). Returns the method's name.
//
// The interior-point method gets the parameter s (column `s_col`) boxed to
// ±`s_box`: where the LP is unbounded, Clp 1.17's predictor-corrector
// aborts the process ("dual off to infinity"; compas_cra's cube-curve-short
// tilted about x). An optimum on the box is not taken.
const char* SolveFresh(ClpSimplex& lp, int ncols, int s_col, double s_box) {
  lp.setPrimalTolerance(kSimplexPrimalTolerance);
  const LpMethod first = FirstLpMethod(LpForm::kParametric, ncols);
  if (first != LpMethod::kDualSimplex) {
    const double lo = lp.columnLower()[s_col], hi = lp.columnUpper()[s_col];
    lp.setColumnLower(s_col, std::max(lo, -s_box));
    lp.setColumnUpper(s_col, std::min(hi, s_box));
    clp::SolveByBarrier(lp, first);
    lp.setColumnLower(s_col, lo);
    lp.setColumnUpper(s_col, hi);
    // Only its optimum is taken: a claim of infeasibility or unboundedness
    // is left to the simplex, which proves it.
    const double s = lp.primalColumnSolution()[s_col];
    if (clp::StatusOf(lp) == clp::Status::kOptimal && std::abs(s) < 0.5 * s_box)
      return to_string(first);
    lp.allSlackBasis(true);
  }
  return clp::SolveBySimplex(lp);
}

}  // namespace

ContactLcp WithLoads(const ContactLcp& lcp, const std::vector<Vector6>& load) {
  ContactLcp out = lcp;
  for (size_t b = 0; b < out.bodies.size(); ++b) out.bodies[b].F_ext = load[b];
  return out;
}

ContactLcp WithFrictionFactor(const ContactLcp& lcp, double factor) {
  ContactLcp out = lcp;
  for (Contact& c : out.contacts) c.mu *= factor;
  return out;
}

namespace {

// Reads the optimum of OptimizeLoadParameter's LP (its status, s, the dual
// motion, the forces re-checked as an equilibrium at F_ext + s F₁) into
// `out`. True when that is the answer (an optimum whose forces pass, or a
// proof of infeasibility or unboundedness); false when the solve failed or
// its forces do not balance (`out.message`).
bool ReadOptimum(const ContactLcp& lcp, const std::vector<Vector6>& load, bool frictionless,
                 const EquilibriumLp& e, ClpSimplex& lp, int ng, LoadParameterResult& out) {
  switch (clp::StatusOf(lp)) {
    case clp::Status::kOptimal:
      break;
    case clp::Status::kPrimalInfeasible:
      out.status = LoadParameterResult::Status::kInfeasible;
      return true;
    case clp::Status::kDualInfeasible:
      out.status = LoadParameterResult::Status::kUnbounded;
      return true;
    default:
      out.message = clp::Failure("margin LP", lp);
      return false;
  }
  out.value = lp.primalColumnSolution()[ng];
  out.motion = MotionOfDuals(e, lp.dualRowSolution());
  // The forces at the optimum, re-checked as an equilibrium of F_ext + s F₁
  // (the amounts rescaled to that problem's load unit).
  std::vector<Vector6> at(lcp.bodies.size());
  for (size_t b = 0; b < at.size(); ++b) at[b] = lcp.bodies[b].F_ext + out.value * load[b];
  const ContactLcp lcp_s = WithLoads(lcp, at);
  const EquilibriumLp e_s = MakeEquilibriumLp(lcp_s, frictionless);
  std::vector<double> x(lp.primalColumnSolution(), lp.primalColumnSolution() + ng);
  for (double& v : x) v *= e.load_scale / e_s.load_scale;
  if (ReadEquilibrium(lcp_s, e_s, x.data(), ng, out.equilibrium)) {
    out.equilibrium.solved = out.equilibrium.exists = true;
    out.equilibrium.method = out.method;
    out.status = LoadParameterResult::Status::kOptimal;
    return true;
  }
  // The optimum sits on the boundary, within the solver's tolerance of it:
  // an equilibrium LP at that load decides (and gives verified forces).
  EquilibriumOptions options;
  options.frictionless = frictionless;
  out.equilibrium = FindStaticEquilibrium(lcp_s, options);
  if (out.equilibrium.exists) {
    out.status = LoadParameterResult::Status::kOptimal;
    return true;
  }
  out.message = "the optimum's forces fail the equilibrium re-check (residual " +
                std::to_string(out.equilibrium.residual) + ")";
  return false;
}

// The end of S found by equilibrium LPs alone, for when every read of the
// margin LP's optimum failed (a vertex whose self-stress drowns the load in
// roundoff). S is an interval: a feasible s is looked for at the LP's claim
// `claimed` and at distances δ = kEndProbeSteps[i] · max(1, |claimed|) on
// either side (within s ≥ lower_bound), then at s = 0; from it the end is bracketed by
// steps doubling outward until an LP finds no equilibrium, then bisected to
// a relative width kEndBisectionTolerance. Each probe is a verified
// FindStaticEquilibrium, so the end returned is proved: an equilibrium at
// `value`, none just past it. kNoPoint (out unchanged) when no feasible s is
// found near the claim nor at 0, kNoEnd when S shows no end within
// kEndMaxDoublings steps.
constexpr double kEndProbeSteps[] = {0, 1e-12, 1e-9, 1e-7, 1e-5, 1e-3};
constexpr double kEndBisectionTolerance = 1e-9;
constexpr int kEndMaxDoublings = 60;

enum class Bracket { kFound, kNoPoint, kNoEnd };

Bracket BracketEnd(const ContactLcp& lcp, const std::vector<Vector6>& load, bool maximize,
                   double lower_bound, bool frictionless, double claimed,
                   LoadParameterResult& out) {
  EquilibriumOptions options;
  options.frictionless = frictionless;
  int lps = 0;
  const auto at = [&](double s) {
    std::vector<Vector6> w(lcp.bodies.size());
    for (size_t b = 0; b < w.size(); ++b) w[b] = lcp.bodies[b].F_ext + s * load[b];
    ++lps;
    return FindStaticEquilibrium(WithLoads(lcp, w), options);
  };
  const double unit = std::max(1.0, std::abs(claimed));
  const double sense = maximize ? 1.0 : -1.0;  // outward: towards the end
  std::optional<double> inside;
  StaticEquilibrium inside_eq;
  for (const double step : kEndProbeSteps) {
    for (const double sign : {-1.0, 1.0}) {
      const double s = claimed + sign * step * unit;
      if (s < lower_bound || inside) continue;
      StaticEquilibrium eq = at(s);
      if (eq.exists) inside = s, inside_eq = std::move(eq);
    }
    if (inside) break;
  }
  // s = 0 is the load as given: where S is that one point (a frictionless
  // assembly that stands only untilted), no probe beside the claim finds it.
  if (!inside && 0 >= lower_bound) {
    StaticEquilibrium eq = at(0);
    if (eq.exists) inside = 0.0, inside_eq = std::move(eq);
  }
  if (!inside) return Bracket::kNoPoint;
  // Outward from the feasible point until an LP finds no equilibrium.
  double lo = *inside, width = kEndBisectionTolerance * unit, hi = lo;
  bool bracketed = false;
  for (int k = 0; k < kEndMaxDoublings && !bracketed; ++k, width *= 2) {
    hi = lo + sense * width;
    if (hi < lower_bound) break;
    StaticEquilibrium eq = at(hi);
    if (eq.exists) {
      lo = hi, inside_eq = std::move(eq);
    } else {
      bracketed = true;
    }
  }
  if (!bracketed) return Bracket::kNoEnd;
  while (std::abs(hi - lo) > kEndBisectionTolerance * std::max(1.0, std::abs(lo))) {
    const double mid = 0.5 * (lo + hi);
    StaticEquilibrium eq = at(mid);
    if (eq.exists) {
      lo = mid, inside_eq = std::move(eq);
    } else {
      hi = mid;
    }
  }
  out.status = LoadParameterResult::Status::kOptimal;
  out.value = lo;
  out.equilibrium = std::move(inside_eq);
  out.method = "equilibrium LPs bracketing the end";
  out.iterations += lps;
  return Bracket::kFound;
}

}  // namespace

// The LP of the file comment: columns x (the generators, in load_scale
// units) and s (force units per unit of the load wrench), rows
//     A x + s P F₁ / load_scale = −P F_ext / load_scale,
// objective min −s (maximize) or min s; s ≥ lower_bound.
LoadParameterResult OptimizeLoadParameter(const ContactLcp& lcp, const std::vector<Vector6>& load,
                                          bool maximize, double lower_bound, bool frictionless) {
  LoadParameterResult out;
  EquilibriumLp e = MakeEquilibriumLp(lcp, frictionless);
  const int ng = static_cast<int>(e.generators.size());
  double s_coefficient = 0;  // the largest entry of s's column
  for (size_t b = 0; b < lcp.bodies.size(); ++b) {
    const Vector6 w = e.P[b] * load[b] / e.load_scale;
    for (int k = 0; k < 6; ++k) e.a.Add(6 * static_cast<int>(b) + k, ng, w[k]);
    s_coefficient = std::max(s_coefficient, w.cwiseAbs().maxCoeff());
  }
  const int ncols = ng + 1;
  std::vector<double> col_lo(ncols, 0.0), col_hi(ncols, COIN_DBL_MAX), cost(ncols, 0.0);
  col_lo[ng] = std::isfinite(lower_bound) ? lower_bound : -COIN_DBL_MAX;
  cost[ng] = maximize ? -1.0 : 1.0;
  ClpSimplex lp;
  lp.setLogLevel(0);
  lp.loadProblem(e.a.Matrix(e.nrows, ncols), col_lo.data(), col_hi.data(), cost.data(),
                 e.rhs.data(), e.rhs.data());
  // The interior-point method's box on s: a load of kMaxGeneratorLoads.
  const double s_box = kMaxGeneratorLoads / std::max(s_coefficient, 1e-300);
  out.method = SolveFresh(lp, ncols, ng, s_box);
  out.iterations += lp.numberIterations();
  if (ReadOptimum(lcp, load, frictionless, e, lp, ng, out)) return out;
  const double claimed = out.value;  // the first optimum's s, whose forces failed
  // The barrier's optimum lies inside the optimal face, within its tolerance
  // of the end: should its forces fail the re-check, the dual simplex's
  // vertex is read instead.
  if (std::string(out.method) == to_string(LpMethod::kBarrier)) {
    lp.allSlackBasis(true);
    out.method = clp::SolveBySimplex(lp);
    out.iterations += lp.numberIterations();
    if (ReadOptimum(lcp, load, frictionless, e, lp, ng, out)) return out;
  }
  // A vertex can carry a self-stress (two parts squeezed between parallel
  // faces, which no load resists) of any size: at 1e9 loads its roundoff
  // alone moves the end by 1e-7 and fails the re-check. Every amount bounded
  // by kMaxGeneratorLoads, the dual simplex's vertex carries none that large.
  // Only its optimum is taken (the bounds could cut an equilibrium off).
  const std::string first_message = out.message;
  for (int j = 0; j < ng; ++j) lp.setColumnUpper(j, kMaxGeneratorLoads);
  lp.allSlackBasis(true);
  clp::SolveBySimplex(lp);
  out.method = "dual simplex, bounded forces";
  out.iterations += lp.numberIterations();
  if (clp::StatusOf(lp) == clp::Status::kOptimal &&
      ReadOptimum(lcp, load, frictionless, e, lp, ng, out))
    return out;
  switch (BracketEnd(lcp, load, maximize, col_lo[ng], frictionless, claimed, out)) {
    case Bracket::kFound:
      return out;
    case Bracket::kNoPoint:
      // No load at, near (to 1e-3 of it) or below the LP's claim has a
      // verified equilibrium, nor has s = 0: S is at most a point the
      // contacts hold only exactly (the H frame's bar without friction,
      // pushed up by its own weight at an offset), empty to the re-check's
      // tolerance.
      out.status = LoadParameterResult::Status::kInfeasible;
      out.method = "equilibrium LPs: none verified near the margin LP's claim";
      return out;
    case Bracket::kNoEnd:
      break;
  }
  out.status = LoadParameterResult::Status::kFailed;
  out.message = first_message;
  return out;
}

double FrictionUse(const ContactLcp& lcp, const StaticEquilibrium& e) {
  double use = 0;
  const int D = lcp.num_directions;
  for (size_t c = 0; c < lcp.contacts.size(); ++c) {
    const Eigen::Index ci = static_cast<Eigen::Index>(c);
    const Vector3& ft = e.friction_force[c];
    const double fn = e.normal_force[ci];
    if (ft.norm() == 0) continue;
    const int f = lcp.friction_of[c];
    const double mu = lcp.contacts[c].mu;
    if (f < 0 || !(mu > 0) || !(fn > 0)) return std::numeric_limits<double>::infinity();
    const Vector3 u = ft / (mu * fn);
    double g = 0;
    if (D == 2) {
      g = std::abs(u.dot(lcp.friction_directions[D * f]));
    } else {
      const double denom = 1 + std::cos(2 * M_PI / D);
      for (int k = 0; k < D; ++k) {
        const Vector3& a = lcp.friction_directions[D * f + k];
        const Vector3& b = lcp.friction_directions[D * f + (k + 1) % D];
        g = std::max(g, u.dot(a + b) / denom);
      }
    }
    use = std::max(use, g);
  }
  return use;
}

// ---------------------------------------------------------------------------
// The friction deficit LP (margin_lp.h): the equilibrium LP's generator
// columns at k (in load_scale units), then the extra friction z_ci ≥ 0 along
// each direction d_i of each frictional contact, cost 1; rows: the
// equilibrium's 6 nb.

namespace {

// A deficit below this (in units of the largest load, dimensionless) is 0:
// the LP's answer is read as an equilibrium at k and re-checked. A deficit
// above it does not prove that the component fails at k: the interior-point
// method's objective is good to its gap (1e-8 relative), and on compas_cra's
// cube-curve-short, which stands without friction, it gives φ(0) = 1.7e-9.
// The caller proves a failing factor (stability/margin.cpp).
constexpr double kDeficitZero = 1e-9;

}  // namespace

FrictionDeficit FrictionDeficitLp::Solve(double k) {
  const ContactLcp& lcp = lcp_;
  FrictionDeficit out;
  const ContactLcp lcp_k = WithFrictionFactor(lcp, k);
  // The equilibrium LP's generator columns x at k, then the extra friction
  // z_ci ≥ 0 along each d_i (cost 1): its least total is φ(k).
  const EquilibriumLp e = MakeEquilibriumLp(lcp_k, /*frictionless=*/false);
  const int ng = static_cast<int>(e.generators.size());
  const int D = lcp.num_directions;
  int nf = 0;
  for (int f : lcp.friction_of) nf = std::max(nf, f + 1);
  const int ncols = ng + D * nf;
  const auto direction_wrench = [&](int c, int i, int s) -> Vector6 {
    const int b = lcp.normal_rows[c].body[s];
    return e.P[b] * lcp.direction_rows[D * lcp.friction_of[c] + i].g[s];
  };
  Triplets a = e.a;
  for (int c = 0; c < static_cast<int>(lcp.contacts.size()); ++c) {
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    for (int i = 0; i < D; ++i)
      for (int s = 0; s < 2; ++s) {
        const int b = lcp.normal_rows[c].body[s];
        if (b < 0) continue;
        const Vector6 w = direction_wrench(c, i, s);
        for (int r = 0; r < 6; ++r) a.Add(6 * b + r, ng + D * f + i, w[r]);
      }
  }
  a.DropDust();
  std::vector<double> col_lo(ncols, 0.0), col_hi(ncols, COIN_DBL_MAX), cost(ncols, 0.0);
  for (int j = ng; j < ncols; ++j) cost[j] = 1.0;
  ClpSimplex lp;
  lp.setLogLevel(0);
  lp.loadProblem(a.Matrix(e.nrows, ncols), col_lo.data(), col_hi.data(), cost.data(), e.rhs.data(),
                 e.rhs.data());
  // The interior-point method on large components (a warm-started simplex
  // took 2000–16000 pivots per step on the Armadillo vault: the LP is very
  // degenerate); the dual simplex on small ones, or when the former fails.
  const LpMethod first = FirstLpMethod(LpForm::kDeficit, ncols);
  if (first != LpMethod::kDualSimplex) {
    clp::SolveByBarrier(lp, first);
    out.method = to_string(first);
  }
  if (first == LpMethod::kDualSimplex || clp::StatusOf(lp) != clp::Status::kOptimal) {
    lp.setPrimalTolerance(kSimplexPrimalTolerance);
    out.method = clp::SolveBySimplex(lp);
  }
  ++lps_;
  out.iterations = lp.numberIterations();
  iterations_ += out.iterations;
  switch (clp::StatusOf(lp)) {
    case clp::Status::kOptimal:
      break;
    case clp::Status::kPrimalInfeasible:
      // Infeasible even with unlimited friction: no factor holds.
      out.solved = true;
      out.deficit = std::numeric_limits<double>::infinity();
      return out;
    default:
      out.message = clp::Failure("friction deficit LP", lp);
      return out;
  }
  out.solved = true;
  out.deficit = std::max(0.0, lp.objectiveValue());
  // The slope: moving k by δ turns generator (c, i) by δ μ_c d_i. A
  // contact's normal force f_n,c may go to any of its generators, so the
  // value falls by δ μ_c f_n,c max_i P_ci, P_ci = yᵀ (P Jᵀ d_i) the power of
  // d_i under the duals y (max_i P_ci ≥ 0, as the d_i sum to 0).
  const double* x = lp.primalColumnSolution();
  const double* y = lp.dualRowSolution();
  std::vector<double> fn(lcp.contacts.size(), 0.0);
  for (int j = 0; j < ng; ++j) fn[e.generators[j].contact] += std::max(0.0, x[j]);
  for (int c = 0; c < static_cast<int>(lcp.contacts.size()); ++c) {
    if (lcp.friction_of[c] < 0 || !(fn[c] > 0)) continue;
    double best = 0;
    for (int i = 0; i < D; ++i) {
      double p = 0;
      for (int s = 0; s < 2; ++s) {
        const int b = lcp.normal_rows[c].body[s];
        if (b < 0) continue;
        const Vector6 w = direction_wrench(c, i, s);
        for (int r = 0; r < 6; ++r) p += y[6 * b + r] * w[r];
      }
      best = std::max(best, p);
    }
    out.slope -= lcp.contacts[c].mu * fn[c] * best;
  }
  out.motion = MotionOfDuals(e, y);
  if (out.deficit > kDeficitZero) return out;
  // φ ≈ 0: the generator amounts are an equilibrium at k, refined and
  // re-checked there.
  if (ReadEquilibrium(lcp_k, e, x, ng, out.equilibrium)) {
    out.equilibrium.solved = out.equilibrium.exists = true;
    out.equilibrium.method = out.method;
    out.exists = true;
  }
  return out;
}

}  // namespace cairn

#include "cairn/mechanics/margin_lp.h"

#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <coin/ClpSolve.hpp>
#include <limits>
#include <vector>

#include "mechanics/equilibrium_lp.h"

namespace cairn {

using equilibrium_internal::EquilibriumLp;
using equilibrium_internal::kBarrierColumns;
using equilibrium_internal::kSimplexPrimalTolerance;
using equilibrium_internal::Load;
using equilibrium_internal::MakeEquilibriumLp;
using equilibrium_internal::ReadEquilibrium;

namespace {

// From this many columns on, a margin LP (with an objective) goes to the
// interior-point method with crossover; below, the simplex (measured on the
// Jenga tower's 2400 columns: the simplex is the faster there).
constexpr int kMarginBarrierColumns = 4 * kBarrierColumns;

// Solves `lp` from scratch: the interior-point method with crossover for
// large problems (a vertex, as the dual simplex gives), else Clp's default
// (the dual or primal simplex). Returns the method's name.
const char* SolveFresh(ClpSimplex& lp, int ncols) {
  lp.setPrimalTolerance(kSimplexPrimalTolerance);
  if (ncols >= kMarginBarrierColumns) {
    ClpSolve how;
    how.setSolveType(ClpSolve::useBarrier);
    how.setPresolveType(ClpSolve::presolveOff);
    lp.initialSolve(how);
    if (lp.status() == 0 || lp.status() == 1 || lp.status() == 2) return "barrier + crossover";
  }
  lp.dual();
  if (lp.status() == 0 || lp.status() == 1 || lp.status() == 2) return "dual simplex";
  lp.allSlackBasis(true);
  lp.primal();
  return "primal simplex";
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

// The LP of the file comment: columns x (the generators, in load_scale
// units) and s (force units per unit of the load wrench), rows
//     A x + s P F₁ / load_scale = −P F_ext / load_scale,
// objective min −s (maximize) or min s; s ≥ lower_bound.
LoadParameterResult OptimizeLoadParameter(const ContactLcp& lcp, const std::vector<Vector6>& load,
                                          bool maximize, double lower_bound, bool frictionless) {
  LoadParameterResult out;
  EquilibriumLp e = MakeEquilibriumLp(lcp, frictionless);
  const int ng = static_cast<int>(e.generators.size());
  for (size_t b = 0; b < lcp.bodies.size(); ++b) {
    const Vector6 w = e.P[b] * load[b] / e.load_scale;
    for (int k = 0; k < 6; ++k) e.a.Add(6 * static_cast<int>(b) + k, ng, w[k]);
  }
  const int ncols = ng + 1;
  std::vector<double> col_lo(ncols, 0.0), col_hi(ncols, COIN_DBL_MAX), cost(ncols, 0.0);
  col_lo[ng] = std::isfinite(lower_bound) ? lower_bound : -COIN_DBL_MAX;
  cost[ng] = maximize ? -1.0 : 1.0;
  ClpSimplex lp;
  lp.setLogLevel(0);
  lp.loadProblem(e.a.Matrix(e.nrows, ncols), col_lo.data(), col_hi.data(), cost.data(),
                 e.rhs.data(), e.rhs.data());
  out.method = SolveFresh(lp, ncols);
  out.iterations = lp.numberIterations();
  if (lp.status() == 1) {
    out.status = LoadParameterResult::Status::kInfeasible;
    return out;
  }
  if (lp.status() == 2) {
    out.status = LoadParameterResult::Status::kUnbounded;
    return out;
  }
  if (lp.status() != 0) {
    out.message = "Clp: status " + std::to_string(lp.status()) + ", secondary status " +
                  std::to_string(lp.secondaryStatus());
    return out;
  }
  out.value = lp.primalColumnSolution()[ng];
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
    return out;
  }
  // The optimum sits on the boundary, within the solver's tolerance of it:
  // an equilibrium LP at that load decides (and gives verified forces).
  EquilibriumOptions options;
  options.frictionless = frictionless;
  out.equilibrium = FindStaticEquilibrium(lcp_s, options);
  if (out.equilibrium.exists) {
    out.status = LoadParameterResult::Status::kOptimal;
    return out;
  }
  out.message = "the optimum's forces fail the equilibrium re-check (residual " +
                std::to_string(out.equilibrium.residual) + ")";
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

double MechanismFrictionBound(const ContactLcp& lcp, const Mechanism& m) {
  double bound = std::numeric_limits<double>::infinity();
  const int D = lcp.num_directions;
  for (size_t c = 0; c < lcp.contacts.size(); ++c) {
    const int f = lcp.friction_of[c];
    const double mu = lcp.contacts[c].mu;
    if (f < 0 || !(mu > 0)) continue;
    const double pn = lcp.normal_rows[c].Dot(m.nu);
    for (int k = 0; k < D; ++k) {
      const double pd = lcp.direction_rows[D * f + k].Dot(m.nu);
      if (pd < 0) bound = std::min(bound, std::max(0.0, pn) / (mu * -pd));
    }
  }
  return bound;
}

// ---------------------------------------------------------------------------
// FrictionProbe

struct FrictionProbe::Impl {
  ContactLcp lcp;
  std::vector<unsigned char> basis;  // Clp's status array of the last solve
};

FrictionProbe::FrictionProbe(const ContactLcp& lcp) : impl_(std::make_unique<Impl>()) {
  impl_->lcp = lcp;
}

FrictionProbe::~FrictionProbe() = default;

FrictionProbe::Answer FrictionProbe::Probe(double k) {
  Answer out;
  const ContactLcp lcp_k = WithFrictionFactor(impl_->lcp, k);
  const EquilibriumLp e = MakeEquilibriumLp(lcp_k, /*frictionless=*/false);
  const int ncols = static_cast<int>(e.generators.size());
  ClpSimplex lp;
  Load(e, lp);
  lp.setPrimalTolerance(kSimplexPrimalTolerance);
  // The same generators in the same order at every k: the last basis fits.
  // With no objective it is dual feasible, and the dual simplex goes on from
  // it to primal feasibility (or a proof that there is none).
  if (impl_->basis.size() == static_cast<size_t>(ncols + e.nrows)) {
    lp.copyinStatus(impl_->basis.data());
    lp.dual(0, /*startFinishOptions=*/0);
    ++warm_;
    if (lp.status() != 0 && lp.status() != 1) SolveFresh(lp, ncols);
  } else {
    SolveFresh(lp, ncols);
  }
  ++lps_;
  iterations_ += lp.numberIterations();
  if (lp.status() == 0 || lp.status() == 1)
    impl_->basis.assign(lp.statusArray(), lp.statusArray() + ncols + e.nrows);
  if (lp.status() == 1) {
    out.solved = true;
    return out;
  }
  if (lp.status() != 0) return out;
  StaticEquilibrium eq;
  if (ReadEquilibrium(lcp_k, e, lp.primalColumnSolution(), ncols, eq)) {
    eq.solved = eq.exists = true;
    eq.method = "dual simplex";
    last_ = std::move(eq);
    out.solved = out.exists = true;
    return out;
  }
  // The simplex said feasible within its tolerance but the forces do not
  // balance: the equilibrium LP decides afresh.
  StaticEquilibrium fresh = FindStaticEquilibrium(lcp_k);
  ++lps_;
  out.solved = fresh.solved;
  out.exists = fresh.exists;
  if (fresh.exists) last_ = std::move(fresh);
  return out;
}

}  // namespace cairn

#include "cairn/mechanics/static_equilibrium.h"

#include <Eigen/SparseCholesky>  // IWYU pragma: keep
#include <Eigen/SparseCore>      // IWYU pragma: keep
#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <vector>

#include "cairn/mechanics/lp_policy.h"
#include "mechanics/clp_solve.h"
#include "mechanics/equilibrium_lp.h"

namespace cairn {

namespace equilibrium_internal {

// The generators of every contact: D pyramid edges where the LCP has friction
// directions (and friction is wanted), else the normal alone.
std::vector<Generator> MakeGenerators(const ContactLcp& lcp, bool frictionless) {
  std::vector<Generator> out;
  const int nc = static_cast<int>(lcp.contacts.size());
  for (int c = 0; c < nc; ++c) {
    if (frictionless || lcp.friction_of[c] < 0) {
      out.push_back({c, -1});
      continue;
    }
    for (int k = 0; k < lcp.num_directions; ++k) out.push_back({c, k});
  }
  return out;
}

// The wrench (f, τ) at the centroid of side s's body of a unit generator force.
Vector6 GeneratorWrench(const ContactLcp& lcp, const Generator& g, int s) {
  Vector6 w = lcp.normal_rows[g.contact].g[s];
  if (g.direction >= 0) {
    const int f = lcp.friction_of[g.contact];
    w += lcp.contacts[g.contact].mu * lcp.direction_rows[lcp.num_directions * f + g.direction].g[s];
  }
  return w;
}

EquilibriumLp MakeEquilibriumLp(const ContactLcp& lcp, bool frictionless) {
  EquilibriumLp lp;
  const int nb = static_cast<int>(lcp.bodies.size());
  lp.generators = MakeGenerators(lcp, frictionless);
  lp.nrows = 6 * nb;
  for (int b = 0; b < nb; ++b) lp.P.push_back(lcp.bodies[b].FreeProjector());
  for (int j = 0; j < static_cast<int>(lp.generators.size()); ++j) {
    const JacobianRow& rn = lcp.normal_rows[lp.generators[j].contact];
    for (int s = 0; s < 2; ++s) {
      const int b = rn.body[s];
      if (b < 0) continue;
      const Vector6 w = lp.P[b] * GeneratorWrench(lcp, lp.generators[j], s);
      for (int k = 0; k < 6; ++k) lp.a.Add(6 * b + k, j, w[k]);
    }
  }
  lp.a.DropDust();
  lp.rhs.resize(lp.nrows);
  double largest = 0;
  for (int b = 0; b < nb; ++b)
    largest = std::max(largest, (lp.P[b] * lcp.bodies[b].F_ext).cwiseAbs().maxCoeff());
  if (largest > 0) lp.load_scale = largest;
  for (int b = 0; b < nb; ++b) {
    const Vector6 r = -(lp.P[b] * lcp.bodies[b].F_ext) / lp.load_scale;
    for (int k = 0; k < 6; ++k) lp.rhs[6 * b + k] = r[k];
  }
  return lp;
}

std::vector<Vector6> MotionOfDuals(const EquilibriumLp& e, const double* y) {
  std::vector<Vector6> nu(e.P.size());
  for (size_t b = 0; b < e.P.size(); ++b) nu[b] = -(e.P[b] * Eigen::Map<const Vector6>(y + 6 * b));
  return nu;
}

// The interior-point method's iteration budget on the equilibrium LP: a
// feasible one converges in 12–20 (Jenga, the vaults); an infeasible one
// wanders for hundreds (9 s on the cross vault at μ 0.3) before it says so,
// and the elastic LP decides it faster.
constexpr int kBarrierIterations = 60;

// Refinement of the LP's equilibrium (RefineEquilibrium): Newton steps, and
// the regularisation of A_S A_Sᵀ relative to its largest diagonal entry
// (dimensionless; a planar body's empty rows make it singular).
constexpr int kRefinementSteps = 2;
constexpr double kRefinementRegularisation = 1e-12;

// The largest equilibrium residual accepted, relative to the largest external
// wrench entry (dimensionless; the LP solvers' own feasibility tolerance is
// 1e-7 of the row scale).
constexpr double kEquilibriumResidual = 1e-7;

// The largest negative generator power a mechanism may show and still count
// as admissible, relative to the largest wrench entry for a unit-speed motion
// (dimensionless): Clp's primal feasibility tolerance is 1e-7 on each row.
constexpr double kMechanismSlack = 1e-6;

// A body of a mechanism whose motion is below this fraction of the fastest
// one's is at rest (dimensionless; interior-point duals leave ~1e-9 there).
constexpr double kMechanismRest = 1e-6;

// Loads the feasibility problem {A x = rhs, x ≥ 0} into a fresh Clp model.
void Load(const EquilibriumLp& e, ClpSimplex& lp) {
  const int ncols = static_cast<int>(e.generators.size());
  const std::vector<double> col_lo(ncols, 0.0), col_hi(ncols, COIN_DBL_MAX), cost(ncols, 0.0);
  lp.setLogLevel(0);  // the CLI's stdout may be a JSON document
  lp.loadProblem(e.a.Matrix(e.nrows, ncols), col_lo.data(), col_hi.data(), cost.data(),
                 e.rhs.data(), e.rhs.data());
}

// Refines the LP's generator amounts x (≥ 0) so that the equilibrium holds
// to roundoff rather than to the LP solver's feasibility tolerance (1e-7 of
// the rows): the LCP check of the forces at rest divides the unbalanced load
// by the masses, so light parts need it. Newton steps on A x = rhs over the
// loaded generators S (x_j > 0): δ = −A_Sᵀ (A_S A_Sᵀ + εI)⁻¹ r, the least
// change that removes the residual r, shortened to keep x ≥ 0.
void RefineEquilibrium(const EquilibriumLp& e, std::vector<double>& x) {
  const int ncols = static_cast<int>(x.size());
  std::vector<Eigen::Triplet<double>> t;
  for (size_t k = 0; k < e.a.values.size(); ++k)
    t.emplace_back(e.a.rows[k], e.a.cols[k], e.a.values[k]);
  SparseMatrixX A(e.nrows, ncols);
  A.setFromTriplets(t.begin(), t.end());
  for (int step = 0; step < kRefinementSteps; ++step) {
    VectorX xv = Eigen::Map<const VectorX>(x.data(), ncols);
    const VectorX r = A * xv - Eigen::Map<const VectorX>(e.rhs.data(), e.nrows);
    const double rnorm = r.lpNorm<Eigen::Infinity>();
    if (!(rnorm > 0)) return;
    // A_S: the columns of loaded generators.
    VectorX on = VectorX::Zero(ncols);
    for (int j = 0; j < ncols; ++j) on[j] = x[j] > 0 ? 1.0 : 0.0;
    const SparseMatrixX AS = A * on.asDiagonal();
    SparseMatrixX N = AS * AS.transpose();
    double diag = 0;
    for (int i = 0; i < N.rows(); ++i) diag = std::max(diag, N.coeff(i, i));
    SparseMatrixX reg(N.rows(), N.cols());
    reg.setIdentity();
    N += (kRefinementRegularisation * std::max(1.0, diag)) * reg;
    const Eigen::SimplicialLDLT<SparseMatrixX> ldlt(N);
    if (ldlt.info() != Eigen::Success) return;
    const VectorX delta = -(AS.transpose() * ldlt.solve(r));
    double step_length = 1.0;
    for (int j = 0; j < ncols; ++j)
      if (delta[j] < 0 && x[j] + delta[j] < 0)
        step_length = std::min(step_length, -x[j] / delta[j]);
    const VectorX next = xv + step_length * delta;
    if (!((A * next - Eigen::Map<const VectorX>(e.rhs.data(), e.nrows)).lpNorm<Eigen::Infinity>() <
          rnorm))
      return;
    for (int j = 0; j < ncols; ++j) x[j] = std::max(0.0, next[j]);
  }
}

// Reads the generator amounts into forces and the LCP's unknowns, and checks
// the equilibrium from them. False when the residual is too large.
bool ReadEquilibrium(const ContactLcp& lcp, const EquilibriumLp& e, const double* lp_x, int ncols,
                     StaticEquilibrium& out) {
  std::vector<double> x(lp_x, lp_x + ncols);
  for (double& v : x) v = std::max(0.0, v);
  RefineEquilibrium(e, x);
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const bool impulses = lcp.formulation == Formulation::kStewartTrinkle;
  const double scale_z = impulses ? lcp.dt : 1.0;
  out.normal_force = VectorX::Zero(nc);
  out.friction_force.assign(nc, Vector3::Zero());
  out.lcp_z = VectorX::Zero(lcp.size());
  std::vector<Vector6> net(nb);
  double scale = 0;
  for (int b = 0; b < nb; ++b) {
    net[b] = e.P[b] * lcp.bodies[b].F_ext;
    scale = std::max(scale, lcp.bodies[b].F_ext.cwiseAbs().maxCoeff());
  }
  for (int j = 0; j < static_cast<int>(e.generators.size()); ++j) {
    const double amount = std::max(0.0, x[j]) * e.load_scale;
    const Generator& g = e.generators[j];
    const int c = g.contact;
    out.normal_force[c] += amount;
    out.lcp_z[c] += amount * scale_z;
    if (g.direction >= 0) {
      const int f = lcp.friction_of[c];
      const double beta = lcp.contacts[c].mu * amount;
      out.friction_force[c] += beta * lcp.friction_directions[D * f + g.direction];
      out.lcp_z[nc + D * f + g.direction] += beta * scale_z;
    }
    const JacobianRow& rn = lcp.normal_rows[c];
    for (int s = 0; s < 2; ++s)
      if (rn.body[s] >= 0) net[rn.body[s]] += e.P[rn.body[s]] * GeneratorWrench(lcp, g, s) * amount;
  }
  out.residual = 0;
  for (int b = 0; b < nb; ++b) out.residual = std::max(out.residual, net[b].cwiseAbs().maxCoeff());
  // Relative to the loads (no absolute floor: a light part's forces are
  // small, and so must be their imbalance).
  return out.residual <= kEquilibriumResidual * scale;
}

}  // namespace equilibrium_internal

using equilibrium_internal::EquilibriumLp;
using equilibrium_internal::Generator;
using equilibrium_internal::GeneratorWrench;
using equilibrium_internal::kBarrierIterations;
using equilibrium_internal::kMechanismRest;
using equilibrium_internal::kMechanismSlack;
using equilibrium_internal::kSimplexPrimalTolerance;
using equilibrium_internal::Load;
using equilibrium_internal::MakeEquilibriumLp;
using equilibrium_internal::ReadEquilibrium;
using equilibrium_internal::Triplets;

StaticEquilibrium FindStaticEquilibrium(const ContactLcp& lcp, const EquilibriumOptions& options) {
  StaticEquilibrium out;
  const EquilibriumLp e = MakeEquilibriumLp(lcp, options.frictionless);
  const int ncols = static_cast<int>(e.generators.size());

  // 1. Large problems: the interior-point method, no crossover. Its answer is
  // accepted only when it passes the re-check; anything else goes on to the
  // simplex, which also proves infeasibility.
  const LpMethod first = FirstLpMethod(LpForm::kFeasibility, ncols);
  // An interior-point answer, taken when it is an optimum whose forces pass
  // the re-check.
  const auto balances = [&](const ClpSimplex& lp, const char* method) {
    if (clp::StatusOf(lp) != clp::Status::kOptimal ||
        !ReadEquilibrium(lcp, e, lp.primalColumnSolution(), ncols, out))
      return false;
    out.solved = out.exists = true;
    out.method = method;
    out.iterations = lp.numberIterations();
    return true;
  };
  if (first != LpMethod::kDualSimplex && options.max_iterations <= 0 && !options.vertex) {
    ClpSimplex lp;
    Load(e, lp);
    clp::SolveByBarrier(lp, first, kBarrierIterations);
    if (balances(lp, "barrier")) return out;
    // Not proven feasible. The dual simplex is slow to prove infeasibility
    // here (minutes on the cross vault at μ 0.3); the elastic LP, whose dual
    // is the mechanism, decides it in a barrier's time.
    if (!options.frictionless) {
      Mechanism m = FindMechanism(lcp);
      if (m.found) {
        out.solved = true;
        out.method = "barrier, mechanism";
        out.mechanism = std::move(m);
        return out;
      }
    }
    // Nor is there a mechanism: the feasible set may be nearly a point (a
    // friction factor at its critical value, where the dual simplex from
    // the slack basis took 9 s on the Armadillo vault). The interior-point
    // method run to its end and its crossover to a vertex, at the simplex's
    // primal tolerance: at Clp's default (1e-7) the vertex balanced only to
    // 5·10⁻⁸ of the loads there and failed the LCP check at rest; at this
    // one it balances to roundoff (3 s in all, `docs/margin.md`).
    ClpSimplex vertex;
    Load(e, vertex);
    vertex.setPrimalTolerance(kSimplexPrimalTolerance);
    clp::SolveByBarrier(vertex, LpMethod::kBarrierCrossover);
    if (balances(vertex, "barrier with crossover")) return out;
  }

  // 2. The dual simplex from the slack basis (dual feasible: no costs), which
  // searches for primal feasibility alone; on trouble, the primal simplex.
  ClpSimplex lp;
  Load(e, lp);
  lp.setPrimalTolerance(kSimplexPrimalTolerance);
  if (options.max_iterations > 0) lp.setMaximumIterations(options.max_iterations);
  out.method = clp::SolveBySimplex(lp);
  out.iterations = lp.numberIterations();
  switch (clp::StatusOf(lp)) {
    case clp::Status::kOptimal:
      break;
    case clp::Status::kPrimalInfeasible:
      out.solved = true;  // no equilibrium
      return out;
    case clp::Status::kStopped:
      out.message =
          "Clp: the iteration budget (" + std::to_string(options.max_iterations) + ") ran out";
      return out;
    default:
      out.message = clp::Failure("equilibrium LP", lp);
      return out;
  }
  if (!ReadEquilibrium(lcp, e, lp.primalColumnSolution(), ncols, out)) {
    out.message = "Clp's equilibrium fails the re-check: residual " + std::to_string(out.residual);
    return out;
  }
  out.solved = out.exists = true;
  return out;
}

namespace {

// A body's size for the mechanism's box: its radius of gyration about its
// stiffest axis (length), so that |v| and r|ω| compare.
double BodyRadius(const BodyDynamics& b) {
  if (b.mass <= 0) return 1.0;
  const double r = std::sqrt(b.inertia.diagonal().maxCoeff() / b.mass);
  return r > 0 ? r : 1.0;
}

// The elastic equilibrium LP: min Σ w_i (s⁺_i + s⁻_i) with A x + s⁺ − s⁻ = rhs,
// x, s ≥ 0; w = 1 on force rows, 1/r on torque rows. Its dual is the
// mechanism LP of the file comment: max F·ν with W_jᵀν ≥ 0 and |ν_i| ≤ w_i,
// where ν = −y (y the row duals). The optimum is the least unbalanced load.
// False (with `message`) when Clp fails.
bool SolveElasticLp(const EquilibriumLp& e, const std::vector<double>& radius, ClpSimplex& lp,
                    std::string* message) {
  const int ng = static_cast<int>(e.generators.size());
  Triplets a = e.a;
  const int ncols = ng + 2 * e.nrows;
  std::vector<double> cost(ncols, 0.0);
  for (int i = 0; i < e.nrows; ++i) {
    const double w = (i % 6) < 3 ? 1.0 : 1.0 / radius[i / 6];
    a.Add(i, ng + 2 * i, 1.0);
    a.Add(i, ng + 2 * i + 1, -1.0);
    cost[ng + 2 * i] = cost[ng + 2 * i + 1] = w;
  }
  const std::vector<double> col_lo(ncols, 0.0), col_hi(ncols, COIN_DBL_MAX);
  // In force units (the duals, the motion, are what this LP is for; their
  // accuracy was measured in these units: docs/benchmarks.md).
  std::vector<double> rhs = e.rhs;
  for (double& r : rhs) r *= e.load_scale;
  lp.setLogLevel(0);
  lp.loadProblem(a.Matrix(e.nrows, ncols), col_lo.data(), col_hi.data(), cost.data(), rhs.data(),
                 rhs.data());
  // Large: the interior-point method with crossover, a vertex of the dual,
  // so that bodies that need not move are exactly at rest.
  const LpMethod first = FirstLpMethod(LpForm::kElastic, ncols);
  if (first != LpMethod::kDualSimplex)
    clp::SolveByBarrier(lp, first);
  else
    clp::SolveBySimplex(lp);
  if (clp::StatusOf(lp) == clp::Status::kOptimal) return true;
  *message = clp::Failure("elastic equilibrium LP", lp);
  return false;
}

// Scales a virtual motion so that its fastest body moves by 1 (|v| + r|ω|);
// bodies below kMechanismRest of that are at rest (interior-point duals leave
// dust there). False when every body is at rest.
bool NormaliseMotion(const std::vector<double>& radius, std::vector<Vector6>* nu) {
  const auto size = [&](int b) {
    return (*nu)[b].head<3>().norm() + radius[b] * (*nu)[b].tail<3>().norm();
  };
  const int nb = static_cast<int>(radius.size());
  double largest = 0;
  for (int b = 0; b < nb; ++b) largest = std::max(largest, size(b));
  if (!(largest > 0) || !std::isfinite(largest)) return false;
  for (int b = 0; b < nb; ++b)
    if (size(b) <= kMechanismRest * largest) (*nu)[b].setZero();
  for (Vector6& n : *nu) n /= largest;
  return true;
}

// The virtual motion ν = −P y per body from the row duals, normalised.
bool MotionFromDuals(const EquilibriumLp& e, const std::vector<double>& radius, const double* y,
                     std::vector<Vector6>* nu) {
  *nu = equilibrium_internal::MotionOfDuals(e, y);
  return NormaliseMotion(radius, nu);
}

// The independent check of a mechanism, without Clp: gravity's power F·ν >
// 0 and every generator's power W_jᵀν ≥ 0 (no contact resists), both to
// kMechanismSlack of the wrenches' scale; the moving bodies.
void CheckMechanism(const ContactLcp& lcp, const EquilibriumLp& e,
                    const std::vector<double>& radius, Mechanism& out) {
  const int nb = static_cast<int>(lcp.bodies.size());
  double least = 0, wrench_scale = 0;
  for (const Generator& g : e.generators) {
    const JacobianRow& rn = lcp.normal_rows[g.contact];
    double pj = 0;
    for (int s = 0; s < 2; ++s) {
      const int b = rn.body[s];
      if (b < 0) continue;
      const Vector6 w = GeneratorWrench(lcp, g, s);
      pj += w.dot(out.nu[b]);
      wrench_scale = std::max(wrench_scale, w.cwiseAbs().maxCoeff());
    }
    least = std::min(least, pj);
  }
  out.power = 0;
  for (int b = 0; b < nb; ++b) {
    out.power += lcp.bodies[b].F_ext.dot(out.nu[b]);
    if (out.nu[b].head<3>().norm() + radius[b] * out.nu[b].tail<3>().norm() > 0)
      out.moving.push_back(b);
  }
  out.least_generator_power = least;
  // Gravity's power is a load (force units) times a motion of at most 1:
  // its slack scales with the loads, so that light parts' mechanisms count.
  // A generator's power may fall short of 0 by that fraction of the largest
  // of its wrench scale and gravity's power: a contact that resists the
  // motion by 1e-6 of the work gravity does along it does not hold it (the
  // interior-point duals of a 180-block vault leave 1e-6 there).
  const double power_slack = kMechanismSlack * e.load_scale;
  const double slack = kMechanismSlack * std::max({1.0, wrench_scale, out.power});
  out.found = out.power > power_slack && least >= -slack;
  if (!out.found)
    out.message = out.power <= power_slack
                      ? "no motion along which gravity does work is admissible"
                      : "the mechanism failed its check (power " + std::to_string(out.power) +
                            ", least generator power " + std::to_string(least) + ")";
}

}  // namespace

Mechanism VerifyMechanism(const ContactLcp& lcp, std::vector<Vector6> nu) {
  Mechanism out;
  const int nb = static_cast<int>(lcp.bodies.size());
  std::vector<double> radius(nb);
  for (int b = 0; b < nb; ++b) radius[b] = BodyRadius(lcp.bodies[b]);
  if (static_cast<int>(nu.size()) != nb) {
    out.message = "no motion given";
    return out;
  }
  for (int b = 0; b < nb; ++b) nu[b] = lcp.bodies[b].FreeProjector() * nu[b];
  if (!NormaliseMotion(radius, &nu)) {
    out.message = "every body is at rest";
    return out;
  }
  out.nu = std::move(nu);
  const EquilibriumLp e = MakeEquilibriumLp(lcp, /*frictionless=*/false);
  CheckMechanism(lcp, e, radius, out);
  return out;
}

Mechanism FindMechanism(const ContactLcp& lcp) {
  Mechanism out;
  const int nb = static_cast<int>(lcp.bodies.size());
  const EquilibriumLp e = MakeEquilibriumLp(lcp, /*frictionless=*/false);
  std::vector<double> radius(nb);
  for (int b = 0; b < nb; ++b) radius[b] = BodyRadius(lcp.bodies[b]);
  ClpSimplex lp;
  if (!SolveElasticLp(e, radius, lp, &out.message)) return out;
  if (!MotionFromDuals(e, radius, lp.dualRowSolution(), &out.nu)) {
    out.message = "no motion along which gravity does work is admissible";
    return out;
  }
  CheckMechanism(lcp, e, radius, out);
  return out;
}

}  // namespace cairn

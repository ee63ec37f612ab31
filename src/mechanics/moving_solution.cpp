#include "cairn/mechanics/moving_solution.h"

#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <utility>
#include <vector>

#include "mechanics/clp_solve.h"

namespace cairn {

const char* to_string(MovingSolution::Outcome o) {
  switch (o) {
    case MovingSolution::Outcome::kFound:
      return "found";
    case MovingSolution::Outcome::kNone:
      return "none";
    case MovingSolution::Outcome::kBudget:
      return "budget";
    case MovingSolution::Outcome::kNotRun:
      return "not run";
    case MovingSolution::Outcome::kFailed:
      return "failed";
  }
  return "?";
}

namespace {

// A pair (z_i, w_i) counts as complementary when the smaller side is below
// this, in the LP's scaled units (each z column over its unit, each w row
// over its largest coefficient: dimensionless, O(1) at the solution's scale).
constexpr double kComplementarityTolerance = 1e-9;
// Coefficients below this fraction of their row's largest are rounding dust
// (a moment arm along an axis) and dropped, as in the equilibrium LP.
constexpr double kDropRelative = 1e-13;
// A node's work beyond its simplex iterations (setting its bounds, the
// solve's start and the scan for a violated pair: O(rows) each), counted as
// this many iterations: without it a search on a small LP (the 48-variable
// stack of two cubes) ran 9 000 nodes, 1.5 s, on a budget meant for 0.3 s.
constexpr int kNodeOverhead = 10;
// Clp's primal feasibility tolerance on the scaled rows (its default is 1e-7):
// the polished solution must pass the LCP check.
constexpr double kPrimalTolerance = 1e-10;

// One sparse row being assembled: (column, value).
using SparseRow = std::vector<std::pair<int, double>>;

// The search's LP (file comment of the header), scaled: column j is
// x_j = (physical value) / col_unit[j]; row r is (Σ a x) / row_unit[r].
struct SearchLp {
  int n = 0;                  // LCP size: pairs
  int z0 = 0;                 // first z column (the ξ columns come first)
  int w0 = 0;                 // first w row (pair i ↔ z0 + i, w0 + i)
  std::vector<int> xi_first;  // (nb) first ξ column of body k, -1 if none
  std::vector<MatrixX> H;     // (nb) BᵀMB
  std::vector<Eigen::Matrix<double, 6, Eigen::Dynamic>> B;  // (nb)
  std::vector<double> col_unit;                             // (columns)
  std::vector<double> col_upper;                            // (columns) base upper bounds
  std::vector<double> row_lower;                            // (rows) base bounds
  std::vector<double> row_upper;
  double R = 0;            // Δt ‖F‖_{M⁻¹}
  double power_scale = 0;  // R² / Δt
};

// A row of J on the scaled ξ columns.
SparseRow JacobianOnXi(const SearchLp& s, const JacobianRow& row) {
  SparseRow out;
  for (int side = 0; side < 2; ++side) {
    const int k = row.body[side];
    if (k < 0 || s.xi_first[k] < 0) continue;
    const VectorX c = s.B[k].transpose() * row.g[side];
    for (int j = 0; j < c.size(); ++j)
      out.emplace_back(s.xi_first[k] + j, c(j) * s.col_unit[s.xi_first[k] + j]);
  }
  return out;
}

// Drops the dust of a row and divides it by its largest coefficient; returns
// that divisor (1 for an empty row).
double Equilibrate(SparseRow& row) {
  double largest = 0;
  for (const auto& [c, v] : row) largest = std::max(largest, std::abs(v));
  if (largest == 0) return 1.0;
  SparseRow kept;
  for (const auto& [c, v] : row)
    if (std::abs(v) > kDropRelative * largest) kept.emplace_back(c, v / largest);
  row = std::move(kept);
  return largest;
}

// Builds the LP of the root node into `lp`. False when the component has
// nothing to search (no load: every solution is at rest).
bool BuildSearchLp(const ContactLcp& lcp, SearchLp& s, ClpSimplex& lp) {
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const int nf = lcp.num_friction;
  const double dt = lcp.dt;
  s.n = lcp.size();
  s.xi_first.assign(nb, -1);
  s.H.resize(nb);
  s.B.resize(nb);

  // The bodies' free coordinates and the bound R = Δt ‖F‖_{M⁻¹}.
  double R2 = 0;
  int ncols = 0;
  std::vector<MatrixX> Hinv(nb);
  for (int k = 0; k < nb; ++k) {
    const BodyDynamics& b = lcp.bodies[k];
    s.B[k] = b.FreeBasis();
    if (s.B[k].cols() == 0) continue;
    Matrix6 M = Matrix6::Zero();
    M.topLeftCorner<3, 3>() = b.mass * Matrix3::Identity();
    M.bottomRightCorner<3, 3>() = b.inertia;
    s.H[k] = s.B[k].transpose() * M * s.B[k];
    Hinv[k] = s.H[k].inverse();
    const VectorX f = s.B[k].transpose() * b.F_ext;
    R2 += dt * dt * f.dot(Hinv[k] * f);
    s.xi_first[k] = ncols;
    ncols += static_cast<int>(s.B[k].cols());
  }
  s.R = std::sqrt(R2);
  if (!(s.R > 0)) return false;
  s.power_scale = R2 / dt;
  s.z0 = ncols;
  ncols += s.n;

  // Units: a velocity ξ_j in its bound, an impulse in the largest weight's
  // impulse over the step, λ (a speed) in the largest linear bound.
  s.col_unit.assign(ncols, 1.0);
  s.col_upper.assign(ncols, COIN_DBL_MAX);
  std::vector<double> col_lower(ncols, 0.0);
  double weight = 0, speed = 0;
  for (int k = 0; k < nb; ++k) {
    if (s.xi_first[k] < 0) continue;
    weight = std::max(weight, lcp.bodies[k].F_ext.head<3>().norm());
    for (int j = 0; j < s.B[k].cols(); ++j) {
      const double bound = s.R * std::sqrt(std::max(0.0, Hinv[k](j, j)));
      s.col_unit[s.xi_first[k] + j] = bound > 0 ? bound : 1.0;
      col_lower[s.xi_first[k] + j] = -1.0;
      s.col_upper[s.xi_first[k] + j] = 1.0;
      if (s.B[k].col(j).head<3>().norm() > 0.5) speed = std::max(speed, bound);
    }
  }
  const double impulse_unit = weight > 0 ? weight * dt : s.R;
  const double speed_unit = speed > 0 ? speed : 1.0;
  for (int i = 0; i < s.n; ++i) s.col_unit[s.z0 + i] = i < nc + D * nf ? impulse_unit : speed_unit;

  // Rows: the dynamics of each free coordinate, then w (pair order).
  std::vector<SparseRow> rows;
  std::vector<std::pair<double, double>> bounds;
  // Dynamics: H ξ − Bᵀ Jᵀ z = Bᵀ F Δt.
  std::vector<SparseRow> dyn(ncols - s.n);
  std::vector<double> rhs(ncols - s.n, 0.0);
  for (int k = 0; k < nb; ++k) {
    if (s.xi_first[k] < 0) continue;
    const VectorX f = s.B[k].transpose() * lcp.bodies[k].F_ext * dt;
    for (int j = 0; j < s.B[k].cols(); ++j) {
      for (int l = 0; l < s.B[k].cols(); ++l)
        dyn[s.xi_first[k] + j].emplace_back(s.xi_first[k] + l,
                                            s.H[k](j, l) * s.col_unit[s.xi_first[k] + l]);
      rhs[s.xi_first[k] + j] = f(j);
    }
  }
  const auto add_impulse = [&](const JacobianRow& row, int zcol) {
    for (int side = 0; side < 2; ++side) {
      const int k = row.body[side];
      if (k < 0 || s.xi_first[k] < 0) continue;
      const VectorX c = s.B[k].transpose() * row.g[side];
      for (int j = 0; j < c.size(); ++j)
        dyn[s.xi_first[k] + j].emplace_back(zcol, -c(j) * s.col_unit[zcol]);
    }
  };
  for (int c = 0; c < nc; ++c) add_impulse(lcp.normal_rows[c], s.z0 + c);
  for (int r = 0; r < D * nf; ++r) add_impulse(lcp.direction_rows[r], s.z0 + nc + r);
  for (size_t r = 0; r < dyn.size(); ++r) {
    const double unit = Equilibrate(dyn[r]);
    rows.push_back(std::move(dyn[r]));
    bounds.emplace_back(rhs[r] / unit, rhs[r] / unit);
  }
  s.w0 = static_cast<int>(rows.size());
  // w: normal rows J_n ν (+ d/Δt), friction rows J_d ν + λ, cone rows μ p_n − Σ p_f.
  std::vector<int> contact_of(nf, -1);
  for (int c = 0; c < nc; ++c)
    if (lcp.friction_of[c] >= 0) contact_of[lcp.friction_of[c]] = c;
  for (int i = 0; i < s.n; ++i) {
    SparseRow row;
    double constant = 0;
    if (i < nc) {
      row = JacobianOnXi(s, lcp.normal_rows[i]);
      constant = lcp.normal_offset.size() ? lcp.normal_offset(i) : 0.0;
    } else if (i < nc + D * nf) {
      row = JacobianOnXi(s, lcp.direction_rows[i - nc]);
      const int f = (i - nc) / D;
      row.emplace_back(s.z0 + nc + D * nf + f, s.col_unit[s.z0 + nc + D * nf + f]);
    } else {
      const int f = i - nc - D * nf;
      const int c = contact_of[f];
      row.emplace_back(s.z0 + c, lcp.contacts[c].mu * s.col_unit[s.z0 + c]);
      for (int k = 0; k < D; ++k) row.emplace_back(s.z0 + nc + D * f + k, -impulse_unit);
    }
    const double unit = Equilibrate(row);
    rows.push_back(std::move(row));
    bounds.emplace_back(-constant / unit, COIN_DBL_MAX);
  }

  // Load it (row-ordered), with the objective −Fᵀν (Clp minimises).
  std::vector<int> ri, ci;
  std::vector<double> vi;
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [c, v] : rows[r]) {
      ri.push_back(static_cast<int>(r));
      ci.push_back(c);
      vi.push_back(v);
    }
  CoinPackedMatrix m(/*colordered=*/false, ri.data(), ci.data(), vi.data(),
                     static_cast<CoinBigIndex>(vi.size()));
  m.setDimensions(static_cast<int>(rows.size()), ncols);
  std::vector<double> cost(ncols, 0.0);
  for (int k = 0; k < nb; ++k) {
    if (s.xi_first[k] < 0) continue;
    const VectorX f = s.B[k].transpose() * lcp.bodies[k].F_ext;
    for (int j = 0; j < f.size(); ++j) {
      const int col = s.xi_first[k] + j;
      cost[col] = -f(j) * s.col_unit[col] / s.power_scale;
    }
  }
  s.row_lower.clear();
  s.row_upper.clear();
  for (const auto& [lo, hi] : bounds) {
    s.row_lower.push_back(lo);
    s.row_upper.push_back(hi);
  }
  lp.setLogLevel(0);  // the CLI's stdout may be a JSON document
  lp.loadProblem(m, col_lower.data(), s.col_upper.data(), cost.data(), s.row_lower.data(),
                 s.row_upper.data());
  lp.setPrimalTolerance(kPrimalTolerance);
  lp.scaling(0);  // scaled above, in the problem's own units
  return true;
}

// One node: the pairs fixed on its way down, as (pair, side): side 0 fixes
// z_i = 0, side 1 fixes w_i = 0.
struct Node {
  std::vector<std::pair<int, char>> fixes;
};

void Apply(const SearchLp& s, const std::vector<std::pair<int, char>>& fixes, ClpSimplex& lp) {
  for (const auto& [i, side] : fixes) {
    if (side == 0)
      lp.setColumnUpper(s.z0 + i, 0.0);
    else
      lp.setRowUpper(s.w0 + i, s.row_lower[s.w0 + i]);
  }
}

void Undo(const SearchLp& s, const std::vector<std::pair<int, char>>& fixes, ClpSimplex& lp) {
  for (const auto& [i, side] : fixes) {
    if (side == 0)
      lp.setColumnUpper(s.z0 + i, s.col_upper[s.z0 + i]);
    else
      lp.setRowUpper(s.w0 + i, s.row_upper[s.w0 + i]);
  }
}

// Solves the node's LP; false on a numerical failure (the search is then
// not complete).
bool SolveNode(ClpSimplex& lp, MovingSolution& out) {
  const double rows = lp.numberRows();
  lp.dual();
  out.lp_iterations += lp.numberIterations();
  out.work += rows * (kNodeOverhead + lp.numberIterations());
  if (clp::StatusOf(lp) == clp::Status::kErrors || clp::StatusOf(lp) == clp::Status::kStopped) {
    ++out.restarts;
    lp.allSlackBasis(true);
    lp.primal();
    out.lp_iterations += lp.numberIterations();
    out.work += rows * (kNodeOverhead + lp.numberIterations());
  }
  const clp::Status st = clp::StatusOf(lp);
  return st == clp::Status::kOptimal || st == clp::Status::kPrimalInfeasible;
}

// The z of the LP point in the LCP's units.
VectorX PhysicalZ(const SearchLp& s, const double* x) {
  VectorX z(s.n);
  for (int i = 0; i < s.n; ++i) z(i) = std::max(0.0, x[s.z0 + i] * s.col_unit[s.z0 + i]);
  return z;
}

}  // namespace

MovingSolution SearchMovingSolution(const ContactLcp& lcp, const MovingSearchOptions& options) {
  MovingSolution out;
  // Only the rest state: nothing moving before the step, nothing driven.
  if (lcp.formulation != Formulation::kStewartTrinkle || lcp.num_friction == 0) {
    out.message = "not a frictional Stewart–Trinkle LCP (the frictionless certificate decides)";
    return out;
  }
  for (const BodyDynamics& b : lcp.bodies)
    if (!b.nu_prev.isZero() || !b.nu_prescribed.isZero() || b.motion == BodyMotion::kGuided) {
      out.message = "a body moves before the step or is driven: not a rest state";
      return out;
    }
  if (lcp.size() > options.max_variables) {
    out.message = "an LCP of " + std::to_string(lcp.size()) + " variables, beyond the search's " +
                  std::to_string(options.max_variables);
    return out;
  }
  SearchLp s;
  ClpSimplex lp;
  if (!BuildSearchLp(lcp, s, lp)) {
    out.outcome = MovingSolution::Outcome::kNone;
    out.message = "no load on any free body";
    return out;
  }
  out.power_scale = s.power_scale;
  out.max_work = options.max_work;
  const double least_power = options.power_fraction;  // in the objective's units

  std::vector<Node> stack(1);
  std::vector<std::pair<int, char>> applied;
  int rejected = 0;  // polished leaves that failed the LCP check
  while (!stack.empty()) {
    if (out.work >= out.max_work) {
      out.outcome = MovingSolution::Outcome::kBudget;
      out.open = static_cast<int>(stack.size());
      out.message = "its work budget ran out after " + std::to_string(out.nodes) + " nodes, " +
                    std::to_string(out.open) + " still open";
      return out;
    }
    Node node = std::move(stack.back());
    stack.pop_back();
    Undo(s, applied, lp);
    Apply(s, node.fixes, lp);
    applied = node.fixes;
    ++out.nodes;
    out.depth = std::max(out.depth, static_cast<int>(node.fixes.size()));

    const bool solved = SolveNode(lp, out);
    if (!solved) {
      out.outcome = MovingSolution::Outcome::kFailed;
      out.message = clp::Failure("moving-solution search, node " + std::to_string(out.nodes), lp);
      return out;
    }
    if (clp::StatusOf(lp) != clp::Status::kOptimal || -lp.objectiveValue() <= least_power)
      continue;  // no solution here moves

    // The most violated pair among those not fixed.
    const double* x = lp.primalColumnSolution();
    const double* act = lp.primalRowSolution();
    std::vector<char> fixed(s.n, 0);
    for (const auto& f : node.fixes) fixed[f.first] = 1;
    int worst = -1;
    double worst_violation = kComplementarityTolerance;
    for (int i = 0; i < s.n; ++i) {
      if (fixed[i]) continue;
      const double z = x[s.z0 + i];
      const double w = act[s.w0 + i] - s.row_lower[s.w0 + i];
      const double v = std::min(z, w);
      if (v > worst_violation) worst_violation = v, worst = i;
    }
    if (worst < 0) {
      // Complementary: polish (every pair fixed on its smaller side) and check.
      Node leaf = node;
      for (int i = 0; i < s.n; ++i) {
        if (fixed[i]) continue;
        const double w = act[s.w0 + i] - s.row_lower[s.w0 + i];
        leaf.fixes.emplace_back(i, x[s.z0 + i] <= w ? 0 : 1);
      }
      Undo(s, applied, lp);
      Apply(s, leaf.fixes, lp);
      applied = leaf.fixes;
      if (!SolveNode(lp, out)) continue;
      if (clp::StatusOf(lp) != clp::Status::kOptimal || -lp.objectiveValue() <= least_power)
        continue;
      const VectorX z = PhysicalZ(s, lp.primalColumnSolution());
      if (!IsContactLcpSolution(lcp, z, options.check_tolerance)) {
        ++rejected;  // complementary to the LP's tolerance, not to the LCP check's
        continue;
      }
      out.outcome = MovingSolution::Outcome::kFound;
      out.z = z;
      out.power = -lp.objectiveValue() * s.power_scale;
      out.message = "a moving solution after " + std::to_string(out.nodes) + " nodes";
      return out;
    }
    // Branch: the side nearer complementarity last on the stack (first out).
    const double zw = x[s.z0 + worst];
    const double ww = act[s.w0 + worst] - s.row_lower[s.w0 + worst];
    const char near = zw <= ww ? 0 : 1;
    Node far = node, first = std::move(node);
    far.fixes.emplace_back(worst, static_cast<char>(1 - near));
    first.fixes.emplace_back(worst, near);
    stack.push_back(std::move(far));
    stack.push_back(std::move(first));
  }
  if (rejected > 0) {
    out.outcome = MovingSolution::Outcome::kFailed;
    out.message = std::to_string(rejected) +
                  " moving LP points were complementary but failed the LCP check: the search is "
                  "not complete";
    return out;
  }
  out.outcome = MovingSolution::Outcome::kNone;
  out.message = "every branch pruned after " + std::to_string(out.nodes) + " nodes";
  return out;
}

}  // namespace cairn

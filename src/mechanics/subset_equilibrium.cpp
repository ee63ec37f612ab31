// The equilibrium LP of sub-assemblies, kept between solves
// (cairn/mechanics/subset_equilibrium.h).

#include "cairn/mechanics/subset_equilibrium.h"

#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <utility>

#include "cairn/core/check.h"
#include "mechanics/clp_solve.h"
#include "mechanics/equilibrium_lp.h"

namespace cairn {

using equilibrium_internal::EquilibriumLp;
using equilibrium_internal::kSimplexPrimalTolerance;
using equilibrium_internal::MakeEquilibriumLp;
using equilibrium_internal::MotionOfDuals;

namespace {

// A body moves along the infeasibility ray when its motion exceeds this
// fraction of the fastest body's (dimensionless): the ray's dust is not motion.
constexpr double kRayMotion = 1e-9;

// A ray y proves that no equilibrium exists (Farkas) when yᵀb > 0 while
// yᵀA_j ≤ 0 on every column that can carry force and y is 0 on every freed
// row: then yᵀA x = yᵀb > 0 for an equilibrium x ≥ 0, yet yᵀA x ≤ 0. The
// two inequalities are read to these fractions of |y|·|A_j| and |y|·|b|
// (dimensionless): gravity's power along the motion must exceed the
// contacts' by far more than rounding.
constexpr double kFarkasColumnSlack = 1e-9;
constexpr double kFarkasPower = 1e-7;

// An optimum is an equilibrium when every row balances, and every force is
// ≥ 0 (0 where the contact is off), to this fraction of the largest load a
// row balances (dimensionless; the simplex's own tolerance is 1e-10).
constexpr double kBalanceSlack = 1e-9;

}  // namespace

struct SubsetEquilibrium::Impl {
  EquilibriumLp e;
  std::vector<std::pair<int, int>> sides;  // per column: its contact's two bodies (-1: world)
  ClpSimplex lp;
};

SubsetEquilibrium::SubsetEquilibrium(const ContactLcp& lcp) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.e = MakeEquilibriumLp(lcp, /*frictionless=*/false);
  const int ng = static_cast<int>(m.e.generators.size());
  for (const equilibrium_internal::Generator& g : m.e.generators) {
    const JacobianRow& rn = lcp.normal_rows[g.contact];
    m.sides.emplace_back(rn.body[0], rn.body[1]);
  }
  const std::vector<double> col_lo(ng, 0.0), col_hi(ng, COIN_DBL_MAX), cost(ng, 0.0);
  m.lp.setLogLevel(0);
  m.lp.setPrimalTolerance(kSimplexPrimalTolerance);
  m.lp.loadProblem(m.e.a.Matrix(m.e.nrows, ng), col_lo.data(), col_hi.data(), cost.data(),
                   m.e.rhs.data(), m.e.rhs.data());
}

SubsetEquilibrium::~SubsetEquilibrium() = default;
SubsetEquilibrium::SubsetEquilibrium(SubsetEquilibrium&&) noexcept = default;
SubsetEquilibrium& SubsetEquilibrium::operator=(SubsetEquilibrium&&) noexcept = default;

int SubsetEquilibrium::num_bodies() const { return static_cast<int>(impl_->e.P.size()); }

bool SubsetEquilibrium::SolutionBalances() const {
  const ClpSimplex& lp = impl_->lp;
  const double* x = lp.primalColumnSolution();
  const double* row_lo = lp.getRowLower();
  const double* row_hi = lp.getRowUpper();
  const double* col_hi = lp.getColUpper();
  std::vector<double> ax(static_cast<size_t>(lp.numberRows()), 0.0);
  lp.matrix()->times(x, ax.data());
  double load = 0;  // the largest load a row balances
  for (int r = 0; r < lp.numberRows(); ++r)
    if (row_lo[r] == row_hi[r]) load = std::max(load, std::abs(row_lo[r]));
  const double slack = kBalanceSlack * load;
  for (int j = 0; j < lp.numberColumns(); ++j)
    if (x[j] < -slack || (col_hi[j] <= 0 && std::abs(x[j]) > slack)) return false;
  for (int r = 0; r < lp.numberRows(); ++r)
    if (row_lo[r] == row_hi[r] && std::abs(ax[r] - row_lo[r]) > slack) return false;
  return true;
}

bool SubsetEquilibrium::RayProvesInfeasible() const {
  const ClpSimplex& lp = impl_->lp;
  std::unique_ptr<double[]> ray(lp.infeasibilityRay());
  if (!ray) return false;
  const int nr = lp.numberRows();
  const double* row_lo = lp.getRowLower();
  const double* row_hi = lp.getRowUpper();
  double y_norm = 0, b_norm = 0, power = 0;
  for (int r = 0; r < nr; ++r)
    if (row_lo[r] == row_hi[r]) y_norm = std::max(y_norm, std::abs(ray[r]));
  if (!(y_norm > 0)) return false;
  for (int r = 0; r < nr; ++r) {
    if (row_lo[r] != row_hi[r]) continue;  // freed: the certificate is y with these at 0
    b_norm = std::max(b_norm, std::abs(row_lo[r]));
    power += ray[r] * row_lo[r];
  }
  // Clp's ray may point either way: the certificate is y or −y.
  const double sign = power > 0 ? 1.0 : -1.0;
  if (!(sign * power > kFarkasPower * y_norm * b_norm)) return false;
  const CoinPackedMatrix& a = *lp.matrix();
  const double* col_hi = lp.getColUpper();
  const int* start = a.getVectorStarts();
  const int* length = a.getVectorLengths();
  const int* index = a.getIndices();
  const double* value = a.getElements();
  for (int j = 0; j < lp.numberColumns(); ++j) {
    if (col_hi[j] <= 0) continue;  // a contact that is off
    double dot = 0, a_norm = 0;
    for (int k = start[j]; k < start[j] + length[j]; ++k) {
      const int r = index[k];
      if (row_lo[r] != row_hi[r]) continue;
      dot += ray[r] * value[k];
      a_norm = std::max(a_norm, std::abs(value[k]));
    }
    if (sign * dot > kFarkasColumnSlack * y_norm * a_norm) return false;
  }
  return true;
}

SubsetEquilibrium::Answer SubsetEquilibrium::Solve(const std::vector<bool>& present,
                                                   const std::vector<bool>& free) {
  Impl& m = *impl_;
  const int nb = num_bodies();
  CAIRN_CHECK(static_cast<int>(present.size()) == nb && static_cast<int>(free.size()) == nb);
  // Rows: a free body balances; an absent or held one is free of its rows.
  for (int b = 0; b < nb; ++b)
    for (int k = 0; k < 6; ++k) {
      const int r = 6 * b + k;
      if (present[b] && free[b])
        m.lp.setRowBounds(r, m.e.rhs[r], m.e.rhs[r]);
      else
        m.lp.setRowBounds(r, -COIN_DBL_MAX, COIN_DBL_MAX);
    }
  // Columns: a contact is on when both its sides are there and one is free.
  const auto there = [&](int b) { return b < 0 || present[b]; };
  const auto loose = [&](int b) { return b >= 0 && present[b] && free[b]; };
  for (size_t j = 0; j < m.sides.size(); ++j) {
    const auto [a, b] = m.sides[j];
    const bool on = there(a) && there(b) && (loose(a) || loose(b));
    m.lp.setColumnUpper(static_cast<int>(j), on ? COIN_DBL_MAX : 0.0);
  }
  clp::SolveBySimplex(m.lp);
  Answer out;
  out.iterations = m.lp.numberIterations();
  // A warm start's claim of infeasibility stands when its ray is a Farkas
  // certificate, and its optimum when its forces balance; otherwise it is
  // checked from the slack basis. After bounds that change from 0 to ∞ and
  // rows freed, Clp's dual simplex from the old basis has said "infeasible"
  // of a feasible LP (Fig. 4, all parts with the top one held, after the
  // other subsets), and "optimal" with forces of −10¹⁴ that balance to 3 %
  // (the cross vault, state 46 of a beam-1 search).
  const clp::Status warm = clp::StatusOf(m.lp);
  if ((warm == clp::Status::kPrimalInfeasible && !RayProvesInfeasible()) ||
      (warm == clp::Status::kOptimal && !SolutionBalances())) {
    m.lp.allSlackBasis(true);
    clp::SolveBySimplex(m.lp);
    out.iterations += m.lp.numberIterations();
    out.cold = true;
  }
  switch (clp::StatusOf(m.lp)) {
    case clp::Status::kOptimal:
      if (!SolutionBalances()) {  // not even from the slack basis: no verdict
        m.lp.allSlackBasis(true);
        return out;
      }
      out.solved = out.exists = true;
      return out;
    case clp::Status::kPrimalInfeasible:
      out.solved = true;
      break;
    default:
      m.lp.allSlackBasis(true);  // start afresh next time
      return out;
  }
  // The ray y (row duals' direction): the motion ν = −P y per body.
  std::unique_ptr<double[]> ray(m.lp.infeasibilityRay());
  if (!ray) return out;
  const std::vector<Vector6> nu = MotionOfDuals(m.e, ray.get());
  double fastest = 0;
  for (int b = 0; b < nb; ++b)
    if (present[b] && free[b]) fastest = std::max(fastest, nu[b].norm());
  if (!(fastest > 0)) return out;
  for (int b = 0; b < nb; ++b)
    if (present[b] && free[b] && nu[b].norm() > kRayMotion * fastest) out.unbalanced.push_back(b);
  return out;
}

}  // namespace cairn

// The equilibrium LP of sub-assemblies, kept between solves
// (cairn/mechanics/subset_equilibrium.h).

#include "cairn/mechanics/subset_equilibrium.h"

#include <algorithm>
#include <coin/ClpSimplex.hpp>
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
  // A warm start's claim of infeasibility is checked from the slack basis:
  // after bounds that change from 0 to ∞ and rows freed, Clp's dual simplex
  // from the old basis has said "infeasible" of a feasible LP (Fig. 4, all
  // parts with the top one held, after the other subsets).
  if (clp::StatusOf(m.lp) == clp::Status::kPrimalInfeasible) {
    m.lp.allSlackBasis(true);
    clp::SolveBySimplex(m.lp);
    out.iterations += m.lp.numberIterations();
    out.cold = true;
  }
  switch (clp::StatusOf(m.lp)) {
    case clp::Status::kOptimal:
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

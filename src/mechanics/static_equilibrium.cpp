#include "cairn/mechanics/static_equilibrium.h"

#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <vector>

namespace cairn {

StaticEquilibrium FindStaticEquilibrium(const ContactLcp& lcp) {
  StaticEquilibrium out;
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  out.normal_force = VectorX::Zero(nc);
  out.friction_force.assign(nc, Vector3::Zero());

  // The LCP's friction directions of every frictional contact (the Baraff
  // formulation has none: it is frictionless).
  std::vector<std::vector<JacobianRow>> dir_rows(nc);
  std::vector<std::vector<Vector3>> dirs(nc);
  for (int c = 0; c < nc; ++c) {
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    for (int k = 0; k < D; ++k) {
      dir_rows[c].push_back(lcp.direction_rows[D * f + k]);
      dirs[c].push_back(lcp.friction_directions[D * f + k]);
    }
  }

  // Columns (numbered from 1 here, from 0 for Clp): f_n of each contact, then the D friction
  // components β_k ≥ 0 of each contact with directions.
  std::vector<int> col_n(nc), col_d(nc, 0);
  int ncols = 0;
  for (int c = 0; c < nc; ++c) col_n[c] = ++ncols;
  for (int c = 0; c < nc; ++c)
    if (!dirs[c].empty()) col_d[c] = ncols + 1, ncols += static_cast<int>(dirs[c].size());

  // Rows: 6 equilibrium equations per body (projected on its free directions;
  // a planar body's other three are identically zero), then one friction row
  // per frictional contact.
  std::vector<Matrix6> P(nb);
  for (int b = 0; b < nb; ++b) P[b] = lcp.bodies[b].FreeProjector();
  // Sparse triplets (row, col, value), 1-based.
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  const auto add = [&](int row, int col, double v) {
    if (v == 0.0) return;
    ia.push_back(row);
    ja.push_back(col);
    ar.push_back(v);
  };
  // Rounding leaves coefficients of ~1e-17 where the geometry says 0 (a
  // rotated face's normal, a moment arm along an axis). Kept, they make the
  // simplex's bases near-singular (GLPK failed on them with GLP_EFAIL); they are
  // dropped below kDropRelative times the largest coefficient.
  constexpr double kDropRelative = 1e-13;
  // Body b's equation k is row 6 b + k + 1: Σ (P g) f = −P F_ext.
  for (int c = 0; c < nc; ++c) {
    const JacobianRow& rn = lcp.normal_rows[c];
    for (int s = 0; s < 2; ++s) {
      const int b = rn.body[s];
      if (b < 0) continue;
      const Vector6 gn = P[b] * rn.g[s];
      for (int k = 0; k < 6; ++k) add(6 * b + k + 1, col_n[c], gn[k]);
      for (size_t d = 0; d < dir_rows[c].size(); ++d) {
        const Vector6 gd = P[b] * dir_rows[c][d].g[s];
        for (int k = 0; k < 6; ++k) add(6 * b + k + 1, col_d[c] + static_cast<int>(d), gd[k]);
      }
    }
  }
  int nrows = 6 * nb;
  for (int c = 0; c < nc; ++c) {
    if (dirs[c].empty()) continue;
    ++nrows;
    add(nrows, col_n[c], lcp.contacts[c].mu);
    for (size_t d = 0; d < dirs[c].size(); ++d) add(nrows, col_d[c] + static_cast<int>(d), -1.0);
  }

  // Drop the dust (see kDropRelative), then hand the triplets to Clp (0-based).
  double largest = 0;
  for (size_t k = 1; k < ar.size(); ++k) largest = std::max(largest, std::abs(ar[k]));
  std::vector<int> rows, cols;
  std::vector<double> values;
  for (size_t k = 1; k < ar.size(); ++k) {
    if (std::abs(ar[k]) <= kDropRelative * largest) continue;
    rows.push_back(ia[k] - 1);
    cols.push_back(ja[k] - 1);
    values.push_back(ar[k]);
  }
  std::vector<double> row_lo(nrows, 0.0), row_hi(nrows, COIN_DBL_MAX);
  for (int b = 0; b < nb; ++b) {
    const Vector6 rhs = -(P[b] * lcp.bodies[b].F_ext);
    for (int k = 0; k < 6; ++k) row_lo[6 * b + k] = row_hi[6 * b + k] = rhs[k];
  }
  const std::vector<double> col_lo(ncols, 0.0), col_hi(ncols, COIN_DBL_MAX), cost(ncols, 0.0);
  const CoinPackedMatrix matrix(/*colordered=*/true, rows.data(), cols.data(), values.data(),
                                static_cast<CoinBigIndex>(values.size()));
  ClpSimplex lp;
  lp.setLogLevel(0);  // the CLI's stdout may be a JSON document
  // The matrix may have empty trailing rows or columns (a contact whose
  // coefficients were all dust): give the sizes explicitly.
  CoinPackedMatrix sized(matrix);
  sized.setDimensions(nrows, ncols);
  lp.loadProblem(sized, col_lo.data(), col_hi.data(), cost.data(), row_lo.data(), row_hi.data());
  // A feasibility problem (no costs): the slack basis is dual feasible and
  // the dual simplex searches for primal feasibility alone. Clp's dual
  // simplex perturbs the degenerate vertices such an LP is full of: 4 300
  // iterations, 1.7 s on the 184-block cross vault, against 7 000 and 4–12 s
  // for GLPK's and 95 s when Σ f_n was minimised (docs/benchmarks.md).
  lp.dual();
  if (lp.status() != 0 && lp.status() != 1) {
    // Trouble on the way (a near-singular basis): once more by the primal
    // simplex from the slack basis.
    lp.allSlackBasis(true);
    lp.primal();
  }
  if (lp.status() == 1) {
    out.solved = true;  // primal infeasible: no equilibrium
    return out;
  }
  if (lp.status() != 0) {
    out.message = "Clp simplex: status " + std::to_string(lp.status()) + ", secondary status " +
                  std::to_string(lp.secondaryStatus());
    return out;
  }
  const double* x = lp.primalColumnSolution();
  std::vector<std::vector<double>> beta(nc);
  for (int c = 0; c < nc; ++c) {
    out.normal_force[c] = std::max(0.0, x[col_n[c] - 1]);
    for (size_t d = 0; d < dirs[c].size(); ++d) {
      beta[c].push_back(std::max(0.0, x[col_d[c] + static_cast<int>(d) - 1]));
      out.friction_force[c] += dirs[c][d] * beta[c].back();
    }
  }
  // The LCP's unknowns (p_n, β by friction index, λ = 0).
  {
    const bool impulses = lcp.formulation == Formulation::kStewartTrinkle;
    const double scale = impulses ? lcp.dt : 1.0;
    out.lcp_z = VectorX::Zero(lcp.size());
    for (int c = 0; c < nc; ++c) {
      out.lcp_z[c] = out.normal_force[c] * scale;
      const int f = lcp.friction_of[c];
      for (int d = 0; f >= 0 && d < D; ++d) out.lcp_z[nc + D * f + d] = beta[c][d] * scale;
    }
  }
  // Re-check the equilibrium from the forces, independently of Clp.
  std::vector<Vector6> net(nb);
  double scale = 0;
  for (int b = 0; b < nb; ++b) {
    net[b] = P[b] * lcp.bodies[b].F_ext;
    scale = std::max(scale, lcp.bodies[b].F_ext.cwiseAbs().maxCoeff());
  }
  for (int c = 0; c < nc; ++c)
    for (int s = 0; s < 2; ++s) {
      const int b = lcp.normal_rows[c].body[s];
      if (b < 0) continue;
      Vector6 w = lcp.normal_rows[c].g[s] * out.normal_force[c];
      for (size_t d = 0; d < dirs[c].size(); ++d) w += dir_rows[c][d].g[s] * beta[c][d];
      net[b] += P[b] * w;
    }
  for (int b = 0; b < nb; ++b) out.residual = std::max(out.residual, net[b].cwiseAbs().maxCoeff());
  out.solved = true;
  out.exists = out.residual <= 1e-7 * std::max(1.0, scale);
  if (!out.exists) {
    out.solved = false;
    out.message = "Clp's equilibrium fails the re-check: residual " + std::to_string(out.residual);
  }
  return out;
}

}  // namespace cairn

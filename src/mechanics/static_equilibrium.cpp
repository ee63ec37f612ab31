#include "cairn/mechanics/static_equilibrium.h"

#include <glpk.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace cairn {

namespace {

// Owns a glp_prob.
struct GlpProblem {
  glp_prob* p = glp_create_prob();
  GlpProblem() = default;
  GlpProblem(const GlpProblem&) = delete;
  GlpProblem& operator=(const GlpProblem&) = delete;
  ~GlpProblem() { glp_delete_prob(p); }
};

}  // namespace

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

  // Columns (1-based in GLPK): f_n of each contact, then the D friction
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
  // simplex's bases near-singular (GLPK then fails with GLP_EFAIL); they are
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

  GlpProblem lp;
  glp_set_obj_dir(lp.p, GLP_MIN);
  if (nrows > 0) glp_add_rows(lp.p, nrows);
  if (ncols > 0) glp_add_cols(lp.p, ncols);
  for (int b = 0; b < nb; ++b) {
    const Vector6 rhs = -(P[b] * lcp.bodies[b].F_ext);
    for (int k = 0; k < 6; ++k) glp_set_row_bnds(lp.p, 6 * b + k + 1, GLP_FX, rhs[k], rhs[k]);
  }
  for (int r = 6 * nb + 1; r <= nrows; ++r) glp_set_row_bnds(lp.p, r, GLP_LO, 0.0, 0.0);
  for (int j = 1; j <= ncols; ++j) glp_set_col_bnds(lp.p, j, GLP_LO, 0.0, 0.0);
  for (int c = 0; c < nc; ++c) glp_set_obj_coef(lp.p, col_n[c], 1.0);
  {
    double largest = 0;
    for (size_t k = 1; k < ar.size(); ++k) largest = std::max(largest, std::abs(ar[k]));
    size_t kept = 1;
    for (size_t k = 1; k < ar.size(); ++k) {
      if (std::abs(ar[k]) <= kDropRelative * largest) continue;
      ia[kept] = ia[k], ja[kept] = ja[k], ar[kept] = ar[k];
      ++kept;
    }
    ia.resize(kept), ja.resize(kept), ar.resize(kept);
  }
  if (ia.size() > 1)
    glp_load_matrix(lp.p, static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());
  // glp_scale_prob reports to the terminal whatever msg_lev says: silence it
  // (the CLI's stdout is a JSON document).
  const int terminal = glp_term_out(GLP_OFF);
  glp_scale_prob(lp.p, GLP_SF_AUTO);

  glp_smcp params;
  glp_init_smcp(&params);
  params.msg_lev = GLP_MSG_OFF;
  params.presolve = GLP_ON;
  int err = glp_simplex(lp.p, &params);
  if (err == GLP_EFAIL) {
    // A near-singular basis on the way: start again from the standard basis
    // without presolve, and if that fails too, in exact rational arithmetic
    // (slow, but only ever reached on such ill-conditioned components).
    params.presolve = GLP_OFF;
    glp_std_basis(lp.p);
    err = glp_simplex(lp.p, &params);
    if (err == GLP_EFAIL) err = glp_exact(lp.p, &params);
  }
  glp_term_out(terminal);
  const int status = glp_get_status(lp.p);
  if (err == GLP_ENOPFS || err == GLP_ENODFS || status == GLP_NOFEAS) {
    out.solved = true;  // presolve or simplex proved infeasibility
    return out;
  }
  if (err != 0 || status != GLP_OPT) {
    out.message =
        "GLPK simplex: error " + std::to_string(err) + ", status " + std::to_string(status);
    return out;
  }
  std::vector<std::vector<double>> beta(nc);
  for (int c = 0; c < nc; ++c) {
    out.normal_force[c] = glp_get_col_prim(lp.p, col_n[c]);
    for (size_t d = 0; d < dirs[c].size(); ++d) {
      beta[c].push_back(glp_get_col_prim(lp.p, col_d[c] + static_cast<int>(d)));
      out.friction_force[c] += dirs[c][d] * beta[c].back();
    }
  }
  // Re-check the equilibrium from the forces, independently of GLPK.
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
    out.message = "GLPK's equilibrium fails the re-check: residual " + std::to_string(out.residual);
  }
  return out;
}

}  // namespace cairn

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
  out.normal_force = VectorX::Zero(nc);
  out.friction_force = VectorX::Zero(nc);

  // Columns (1-based in GLPK): f_n of each contact, then f_t+ and f_t− of
  // each contact with μ > 0.
  std::vector<int> col_n(nc), col_tp(nc, 0), col_tm(nc, 0);
  int ncols = 0;
  for (int c = 0; c < nc; ++c) col_n[c] = ++ncols;
  for (int c = 0; c < nc; ++c)
    if (lcp.contacts[c].mu > 0) col_tp[c] = ++ncols, col_tm[c] = ++ncols;

  // Rows: 3 equilibrium equations per body (projected on its free directions),
  // then one friction row per frictional contact.
  std::vector<Eigen::Matrix3d> P(nb);
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
  // Body b's equation k is row 3 b + k + 1: Σ (P g) f = −P F_ext.
  for (int c = 0; c < nc; ++c) {
    const JacobianRow& rn = lcp.normal_rows[c];
    const JacobianRow& rt = lcp.tangent_rows[c];
    for (int s = 0; s < 2; ++s) {
      const int b = rn.body[s];
      if (b < 0) continue;
      const Vector3 gn = P[b] * rn.g[s], gt = P[b] * rt.g[s];
      for (int k = 0; k < 3; ++k) {
        add(3 * b + k + 1, col_n[c], gn[k]);
        if (col_tp[c]) {
          add(3 * b + k + 1, col_tp[c], gt[k]);
          add(3 * b + k + 1, col_tm[c], -gt[k]);
        }
      }
    }
  }
  int nrows = 3 * nb;
  for (int c = 0; c < nc; ++c) {
    if (!col_tp[c]) continue;
    ++nrows;
    add(nrows, col_n[c], lcp.contacts[c].mu);
    add(nrows, col_tp[c], -1.0);
    add(nrows, col_tm[c], -1.0);
  }

  GlpProblem lp;
  glp_set_obj_dir(lp.p, GLP_MIN);
  if (nrows > 0) glp_add_rows(lp.p, nrows);
  if (ncols > 0) glp_add_cols(lp.p, ncols);
  for (int b = 0; b < nb; ++b) {
    const Vector3 rhs = -(P[b] * lcp.bodies[b].F_ext);
    for (int k = 0; k < 3; ++k) glp_set_row_bnds(lp.p, 3 * b + k + 1, GLP_FX, rhs[k], rhs[k]);
  }
  for (int r = 3 * nb + 1; r <= nrows; ++r) glp_set_row_bnds(lp.p, r, GLP_LO, 0.0, 0.0);
  for (int j = 1; j <= ncols; ++j) glp_set_col_bnds(lp.p, j, GLP_LO, 0.0, 0.0);
  for (int c = 0; c < nc; ++c) glp_set_obj_coef(lp.p, col_n[c], 1.0);
  if (ia.size() > 1)
    glp_load_matrix(lp.p, static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());

  glp_smcp params;
  glp_init_smcp(&params);
  params.msg_lev = GLP_MSG_OFF;
  params.presolve = GLP_ON;
  const int err = glp_simplex(lp.p, &params);
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
  for (int c = 0; c < nc; ++c) {
    out.normal_force[c] = glp_get_col_prim(lp.p, col_n[c]);
    if (col_tp[c])
      out.friction_force[c] = glp_get_col_prim(lp.p, col_tp[c]) - glp_get_col_prim(lp.p, col_tm[c]);
  }
  // Re-check the equilibrium from the forces, independently of GLPK.
  std::vector<Vector3> net(nb);
  double scale = 0;
  for (int b = 0; b < nb; ++b) {
    net[b] = P[b] * lcp.bodies[b].F_ext;
    scale = std::max(scale, lcp.bodies[b].F_ext.cwiseAbs().maxCoeff());
  }
  for (int c = 0; c < nc; ++c)
    for (int s = 0; s < 2; ++s) {
      const int b = lcp.normal_rows[c].body[s];
      if (b < 0) continue;
      net[b] += P[b] * (lcp.normal_rows[c].g[s] * out.normal_force[c] +
                        lcp.tangent_rows[c].g[s] * out.friction_force[c]);
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

#include "cairn/mechanics/rest_solution.h"

#include <glpk.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

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

// Orthonormal columns spanning the range of the projector P (the body's free
// directions): the eigenvectors of eigenvalue 1.
Eigen::Matrix<double, 6, Eigen::Dynamic> RangeOf(const Matrix6& P) {
  const Eigen::SelfAdjointEigenSolver<Matrix6> eig(P);
  int k = 0;
  for (int i = 0; i < 6; ++i) k += eig.eigenvalues()[i] > 0.5;
  Eigen::Matrix<double, 6, Eigen::Dynamic> B(6, k);
  for (int i = 0, c = 0; i < 6; ++i)
    if (eig.eigenvalues()[i] > 0.5) B.col(c++) = eig.eigenvectors().col(i);
  return B;
}

// The LP of the file comment for the body velocities `nu`. Bodies with
// `solved[b]` are not balanced here (their motion and the forces of their
// contacts come from elsewhere); the LCP unknowns with a finite `fixed[v]`
// (v < nc + D nf: p_n, β) are held at that value, and `fixed_lambda[f]`
// (finite) replaces the λ of frictional contact f.
RestSolution SolveRestLp(const ContactLcp& lcp, const std::vector<Vector6>& nu,
                         const std::vector<char>& solved, const std::vector<double>& fixed,
                         const std::vector<double>& fixed_lambda, RestLpBasis* warm) {
  RestSolution out;
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const int nf = lcp.num_friction;
  const int nr = nc + D * nf;  // p_n and β: the LP's unknowns
  const int n = lcp.size();
  double speed = 0;
  for (int b = 0; b < nb; ++b) speed = std::max(speed, nu[b].cwiseAbs().maxCoeff());
  // Relative velocities are exact zeros between bodies at rest and the
  // gripper's speed times a direction cosine otherwise: a relative threshold
  // only has to absorb the roundoff of those products.
  const double vtol = 1e-9 * speed;

  // Contact motions under the hypothesis: which forces may act.
  std::vector<char> normal_free(nc, 1), dir_free(D * nf, 1), sliding(nf, 0);
  std::vector<double> lambda(nf, 0.0);
  for (int c = 0; c < nc; ++c) {
    if (std::isfinite(fixed[c])) {  // decided elsewhere, with its friction and λ
      normal_free[c] = 0;
      const int f = lcp.friction_of[c];
      if (f < 0) continue;
      lambda[f] = fixed_lambda[f];
      for (int k = 0; k < D; ++k) dir_free[D * f + k] = 0;
      continue;
    }
    const double wn = lcp.normal_rows[c].Dot(nu) + lcp.normal_offset(c);
    if (wn < -vtol) {
      out.outcome = RestSolution::Outcome::kNone;
      out.message = "a driven part closes on contact " + std::to_string(c);
      return out;
    }
    if (wn > vtol) normal_free[c] = 0;  // opening: no force
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    double most = 0;  // λ: the largest −d_k · u
    for (int k = 0; k < D; ++k) most = std::max(most, -lcp.direction_rows[D * f + k].Dot(nu));
    if (most > vtol) {
      sliding[f] = 1;
      lambda[f] = most;
      for (int k = 0; k < D; ++k)
        dir_free[D * f + k] = lcp.direction_rows[D * f + k].Dot(nu) + most <= vtol;
    }
  }

  // Columns: the free p_n and β (1-based GLPK indices; 0 = fixed at zero).
  std::vector<int> col_of(nr, 0);
  int ncols = 0;
  for (int c = 0; c < nc; ++c)
    if (normal_free[c]) col_of[c] = ++ncols;
  for (int j = 0; j < D * nf; ++j)
    if (dir_free[j]) col_of[nc + j] = ++ncols;

  // Rows: the balance of each body in its free directions, then one cone row
  // per frictional contact.
  std::vector<Eigen::Matrix<double, 6, Eigen::Dynamic>> B(nb);
  std::vector<int> first_row(nb + 1, 0);
  for (int b = 0; b < nb; ++b) {
    B[b] = solved[b] ? Eigen::Matrix<double, 6, Eigen::Dynamic>(6, 0)
                     : RangeOf(lcp.bodies[b].FreeProjector());
    first_row[b + 1] = first_row[b] + static_cast<int>(B[b].cols());
  }
  const int nrows = first_row[nb] + nf;
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  const auto row_of = [&](int v) -> const JacobianRow& {
    return v < nc ? lcp.normal_rows[v] : lcp.direction_rows[v - nc];
  };
  for (int v = 0; v < nr; ++v) {
    if (!col_of[v]) continue;
    const JacobianRow& r = row_of(v);
    for (int s = 0; s < 2; ++s) {
      const int b = r.body[s];
      if (b < 0) continue;
      const VectorX coef = B[b].transpose() * r.g[s];
      for (int k = 0; k < coef.size(); ++k) {
        ia.push_back(first_row[b] + k + 1);
        ja.push_back(col_of[v]);
        ar.push_back(coef[k]);
      }
    }
  }
  for (int c = 0; c < nc; ++c) {
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    const int row = first_row[nb] + f + 1;
    if (col_of[c]) {
      ia.push_back(row), ja.push_back(col_of[c]), ar.push_back(lcp.contacts[c].mu);
    }
    for (int k = 0; k < D; ++k)
      if (col_of[nc + D * f + k])
        ia.push_back(row), ja.push_back(col_of[nc + D * f + k]), ar.push_back(-1.0);
  }
  // Rounding leaves coefficients of ~1e-17 where the geometry says 0 (a
  // moment arm along an axis); kept, they make the simplex's bases
  // near-singular. Dropped below 1e-13 of the largest (as in
  // static_equilibrium.cpp).
  {
    double largest = 0;
    for (size_t k = 1; k < ar.size(); ++k) largest = std::max(largest, std::abs(ar[k]));
    size_t kept = 1;
    for (size_t k = 1; k < ar.size(); ++k) {
      if (std::abs(ar[k]) <= 1e-13 * largest) continue;
      ia[kept] = ia[k], ja[kept] = ja[k], ar[kept] = ar[k];
      ++kept;
    }
    ia.resize(kept), ja.resize(kept), ar.resize(kept);
  }

  // The impulses of the held unknowns on each body: moved to the right-hand side.
  std::vector<Vector6> held(nb, Vector6::Zero());
  for (int v = 0; v < nr; ++v) {
    if (!std::isfinite(fixed[v]) || fixed[v] == 0.0) continue;
    const JacobianRow& r = row_of(v);
    for (int s = 0; s < 2; ++s)
      if (r.body[s] >= 0) held[r.body[s]] += r.g[s] * fixed[v];
  }

  GlpProblem lp;
  glp_set_obj_dir(lp.p, GLP_MIN);
  if (nrows > 0) glp_add_rows(lp.p, nrows);
  if (ncols > 0) glp_add_cols(lp.p, ncols);
  for (int b = 0; b < nb; ++b) {
    const BodyDynamics& body = lcp.bodies[b];
    Matrix6 M = Matrix6::Zero();
    M.topLeftCorner<3, 3>() = body.mass * Matrix3::Identity();
    M.bottomRightCorner<3, 3>() = body.inertia;
    const VectorX rhs = -(B[b].transpose() * (M * body.FreeProjector() * body.nu_prev +
                                              body.F_ext * lcp.dt + held[b]));
    for (int k = 0; k < rhs.size(); ++k)
      glp_set_row_bnds(lp.p, first_row[b] + k + 1, GLP_FX, rhs[k], rhs[k]);
  }
  std::vector<char> held_contact(nf, 0);
  for (int c = 0; c < nc; ++c)
    if (lcp.friction_of[c] >= 0 && std::isfinite(fixed[c])) held_contact[lcp.friction_of[c]] = 1;
  for (int f = 0; f < nf; ++f)
    glp_set_row_bnds(lp.p, first_row[nb] + f + 1,
                     held_contact[f] ? GLP_FR
                     : sliding[f]    ? GLP_FX
                                     : GLP_LO,
                     0.0, 0.0);
  for (int j = 1; j <= ncols; ++j) {
    glp_set_col_bnds(lp.p, j, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(lp.p, j, 1.0);
  }
  if (ia.size() > 1)
    glp_load_matrix(lp.p, static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());
  // GLPK reports to the terminal whatever msg_lev says; the CLI's stdout may
  // be a JSON document.
  const int terminal = glp_term_out(GLP_OFF);
  // Equilibration scaling only: GLP_SF_AUTO's geometric-mean passes took 11 %
  // of the Jenga pull (one LP a tick), for no change in the answers.
  glp_scale_prob(lp.p, GLP_SF_EQ);

  // A warm start from the last basis of this shape, else the slack basis
  // (dual feasible: every cost is ≥ 0 and every column at its bound 0).
  bool warmed = false;
  if (warm && static_cast<int>(warm->rows.size()) == nrows &&
      static_cast<int>(warm->cols.size()) == ncols) {
    for (int r = 1; r <= nrows; ++r) glp_set_row_stat(lp.p, r, warm->rows[r - 1]);
    for (int j = 1; j <= ncols; ++j) glp_set_col_stat(lp.p, j, warm->cols[j - 1]);
    // Only a dual feasible basis is worth keeping: the dual simplex goes on
    // from it, while from one that is not it needs a first phase that costs
    // more (~900 iterations on the Jenga tower) than starting afresh (~400).
    warmed = glp_warm_up(lp.p) == 0 && glp_get_dual_stat(lp.p) == GLP_FEAS;
  }
  if (!warmed) glp_std_basis(lp.p);
  glp_smcp params;
  glp_init_smcp(&params);
  params.msg_lev = GLP_MSG_OFF;
  params.meth = GLP_DUALP;
  // Bounds (the cone rows, z ≥ 0) to 1e-10 rather than GLPK's 1e-7: z must
  // pass the LCP check at 1e-8 of q.
  params.tol_bnd = 1e-10;
  int err = glp_simplex(lp.p, &params);
  out.iterations = glp_get_it_cnt(lp.p);
  if (err != 0 && err != GLP_ENOPFS && err != GLP_ENODFS) {
    // Trouble on the way (a near-singular basis): once more from the slack
    // basis with the primal simplex.
    glp_std_basis(lp.p);
    params.meth = GLP_PRIMAL;
    err = glp_simplex(lp.p, &params);
    out.iterations += glp_get_it_cnt(lp.p);
  }
  glp_term_out(terminal);
  const int status = glp_get_status(lp.p);
  if (err == GLP_ENOPFS || status == GLP_NOFEAS) {
    out.outcome = RestSolution::Outcome::kNone;
    out.message = "no forces hold the parts at rest";
    return out;
  }
  if (err != 0 || status != GLP_OPT) {
    out.outcome = RestSolution::Outcome::kSolverTrouble;
    out.message =
        "GLPK simplex: error " + std::to_string(err) + ", status " + std::to_string(status);
    return out;
  }
  if (warm) {
    warm->rows.resize(nrows);
    warm->cols.resize(ncols);
    for (int r = 1; r <= nrows; ++r) warm->rows[r - 1] = glp_get_row_stat(lp.p, r);
    for (int j = 1; j <= ncols; ++j) warm->cols[j - 1] = glp_get_col_stat(lp.p, j);
  }
  out.z = VectorX::Zero(n);
  for (int v = 0; v < nr; ++v) {
    if (col_of[v]) out.z[v] = std::max(0.0, glp_get_col_prim(lp.p, col_of[v]));
    if (std::isfinite(fixed[v])) out.z[v] = fixed[v];
  }
  for (int f = 0; f < nf; ++f) out.z[nr + f] = lambda[f];
  out.outcome = RestSolution::Outcome::kFound;
  return out;
}

}  // namespace

RestSolution FindRestSolution(const ContactLcp& lcp, RestLpBasis* warm, RestHypothesis hypothesis) {
  RestSolution out;
  if (lcp.formulation != Formulation::kStewartTrinkle) return out;
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const int nf = lcp.num_friction;
  const int nr = nc + D * nf;
  std::vector<Vector6> nu(nb);
  for (int b = 0; b < nb; ++b) nu[b] = lcp.bodies[b].nu_prescribed;
  std::vector<char> solved(nb, 0);
  std::vector<double> fixed(nr, NAN), fixed_lambda(nf, NAN);
  if (hypothesis == RestHypothesis::kEverythingButDriven)
    return SolveRestLp(lcp, nu, solved, fixed, fixed_lambda, warm);

  // kGuidedFree: the guided bodies against the rest held still, as a small
  // LCP of their own contacts (every other body prescribed at rest) ...
  std::vector<int> local(nb, -1);
  std::vector<BodyDynamics> bodies;
  for (int b = 0; b < nb; ++b)
    if (lcp.bodies[b].motion == BodyMotion::kGuided) solved[b] = 1;
  std::vector<int> sub_contacts;
  for (int c = 0; c < nc; ++c) {
    const JacobianRow& r = lcp.normal_rows[c];
    if ((r.body[0] >= 0 && solved[r.body[0]]) || (r.body[1] >= 0 && solved[r.body[1]]))
      sub_contacts.push_back(c);
  }
  if (sub_contacts.empty()) return out;  // no guided body, or one touching nothing
  std::vector<Contact> contacts;
  const auto add_body = [&](int b) {
    if (b < 0 || local[b] >= 0) return;
    local[b] = static_cast<int>(bodies.size());
    BodyDynamics body = lcp.bodies[b];
    if (!solved[b]) {
      body.motion = BodyMotion::kPrescribed;
      body.nu_prescribed = nu[b];
    }
    bodies.push_back(body);
  };
  for (int c : sub_contacts) {
    add_body(lcp.normal_rows[c].body[0]);
    add_body(lcp.normal_rows[c].body[1]);
    contacts.push_back(lcp.contacts[c]);
  }
  const int dimension = lcp.tangent2_rows.empty() ? 2 : 3;
  const bool gaps = lcp.normal_offset.size() > 0 && lcp.normal_offset.cwiseAbs().maxCoeff() > 0;
  const ContactLcp sub = BuildContactLcp(bodies, contacts, lcp.formulation, lcp.dt, gaps,
                                         LcpStorage::kAuto, dimension, D);
  const LcpResult r = SolveContactLcp(sub);
  if (r.status != LcpStatus::kSolved && r.status != LcpStatus::kTrivial) {
    out.outcome = RestSolution::Outcome::kSolverTrouble;
    out.message = "the guided parts' own LCP: " + std::string(to_string(r.status));
    return out;
  }
  // ... whose forces and motion are then held while the LP balances the rest.
  const ContactSolution motion = RecoverSolution(sub, r.z);
  for (int b = 0; b < nb; ++b)
    if (solved[b] && local[b] >= 0) nu[b] = motion.body_motion[local[b]];
  const int snc = static_cast<int>(sub_contacts.size());
  const int snr = snc + D * sub.num_friction;
  for (int s = 0; s < snc; ++s) {
    const int c = sub_contacts[s];
    fixed[c] = r.z[s];
    const int f = lcp.friction_of[c], sf = sub.friction_of[s];
    if (f < 0 || sf < 0) continue;
    for (int k = 0; k < D; ++k) fixed[nc + D * f + k] = r.z[snc + D * sf + k];
    fixed_lambda[f] = r.z[snr + sf];
  }
  return SolveRestLp(lcp, nu, solved, fixed, fixed_lambda, warm);
}

void ReleaseThreadSolverState() { glp_free_env(); }

}  // namespace cairn

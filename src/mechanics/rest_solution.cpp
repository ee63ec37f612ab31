#include "cairn/mechanics/rest_solution.h"

#include <glpk.h>

#include <Eigen/Eigenvalues>  // IWYU pragma: keep
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>

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

// Relative velocities are exact zeros between bodies at rest and the
// gripper's speed times a direction cosine otherwise: a relative threshold
// only has to absorb the roundoff of those products (dimensionless, times the
// largest body speed).
constexpr double kVelocityRoundoff = 1e-9;
// Rounding leaves coefficients of ~1e-17 where the geometry says 0 (a moment
// arm along an axis); kept, they make the simplex's bases near-singular.
// Dropped below this fraction of the largest (as in static_equilibrium.cpp).
constexpr double kDropRelative = 1e-13;
// Bounds (the cone rows, z ≥ 0) to this rather than GLPK's 1e-7 (relative,
// on the scaled problem): z must pass the LCP check at 1e-8 of q.
constexpr double kBoundTolerance = 1e-10;

// What the hypothesis allows each contact: which forces may act, which
// contacts slide and their λ.
struct ForceFreedom {
  std::vector<char> normal_free;  // (nc) p_n may be > 0
  std::vector<char> dir_free;     // (D nf) β_k may be > 0
  std::vector<char> sliding;      // (nf) the contact slides: its cone row is tight
  std::vector<double> lambda;     // (nf) λ of the contact
};

// Contact motions under the hypothesis: which forces may act. Empty when a
// driven part closes on a contact (the hypothesis is refuted; `why` says so).
std::optional<ForceFreedom> FreeForces(const ContactLcp& lcp, const std::vector<Vector6>& nu,
                                       const std::vector<double>& fixed,
                                       const std::vector<double>& fixed_lambda, std::string* why) {
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const int nf = lcp.num_friction;
  double speed = 0;
  for (const Vector6& v : nu) speed = std::max(speed, v.cwiseAbs().maxCoeff());
  const double vtol = kVelocityRoundoff * speed;
  ForceFreedom ff;
  ff.normal_free.assign(nc, 1);
  ff.dir_free.assign(D * nf, 1);
  ff.sliding.assign(nf, 0);
  ff.lambda.assign(nf, 0.0);
  for (int c = 0; c < nc; ++c) {
    if (std::isfinite(fixed[c])) {  // decided elsewhere, with its friction and λ
      ff.normal_free[c] = 0;
      const int f = lcp.friction_of[c];
      if (f < 0) continue;
      ff.lambda[f] = fixed_lambda[f];
      for (int k = 0; k < D; ++k) ff.dir_free[D * f + k] = 0;
      continue;
    }
    const double wn = lcp.normal_rows[c].Dot(nu) + lcp.normal_offset(c);
    if (wn < -vtol) {
      *why = "a driven part closes on contact " + std::to_string(c);
      return std::nullopt;
    }
    if (wn > vtol) ff.normal_free[c] = 0;  // opening: no force
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    double most = 0;  // λ: the largest −d_k · u
    for (int k = 0; k < D; ++k) most = std::max(most, -lcp.direction_rows[D * f + k].Dot(nu));
    if (most > vtol) {
      ff.sliding[f] = 1;
      ff.lambda[f] = most;
      for (int k = 0; k < D; ++k)
        ff.dir_free[D * f + k] = lcp.direction_rows[D * f + k].Dot(nu) + most <= vtol;
    }
  }
  return ff;
}

// The LP's matrix in GLPK's triplet form (1-based; entry 0 unused).
struct RestLpMatrix {
  std::vector<int> col_of;  // (nc + D nf) GLPK column of p_n / β, 0 = fixed at zero
  int ncols = 0;
  std::vector<Eigen::Matrix<double, 6, Eigen::Dynamic>> B;  // free directions per body
  std::vector<int> first_row;                               // (nb + 1) first balance row
  int nrows = 0;
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  std::vector<std::int64_t> row_keys, col_keys;  // RestLpBasis's keys (LpKeys)
  void Add(int row, int col, double value) {
    ia.push_back(row), ja.push_back(col), ar.push_back(value);
  }
};

void DropRoundoff(RestLpMatrix& m);
void LpKeys(const ContactLcp& lcp, const RestLpMatrix& m, std::vector<std::int64_t>* rows,
            std::vector<std::int64_t>* cols);

const JacobianRow& RowOf(const ContactLcp& lcp, int v) {
  const int nc = static_cast<int>(lcp.contacts.size());
  return v < nc ? lcp.normal_rows[v] : lcp.direction_rows[v - nc];
}

// Columns: the free p_n and β. Rows: the balance of each unsolved body in its
// free directions, then one cone row per frictional contact.
RestLpMatrix BuildRestLpMatrix(const ContactLcp& lcp, const ForceFreedom& ff,
                               const std::vector<char>& solved) {
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const int nf = lcp.num_friction;
  const int nr = nc + D * nf;
  RestLpMatrix m;
  m.col_of.assign(nr, 0);
  for (int c = 0; c < nc; ++c)
    if (ff.normal_free[c]) m.col_of[c] = ++m.ncols;
  for (int j = 0; j < D * nf; ++j)
    if (ff.dir_free[j]) m.col_of[nc + j] = ++m.ncols;
  m.B.resize(nb);
  m.first_row.assign(nb + 1, 0);
  for (int b = 0; b < nb; ++b) {
    m.B[b] = solved[b] ? Eigen::Matrix<double, 6, Eigen::Dynamic>(6, 0)
                       : RangeOf(lcp.bodies[b].FreeProjector());
    m.first_row[b + 1] = m.first_row[b] + static_cast<int>(m.B[b].cols());
  }
  m.nrows = m.first_row[nb] + nf;
  for (int v = 0; v < nr; ++v) {
    if (!m.col_of[v]) continue;
    const JacobianRow& r = RowOf(lcp, v);
    for (int s = 0; s < 2; ++s) {
      const int b = r.body[s];
      if (b < 0) continue;
      const VectorX coef = m.B[b].transpose() * r.g[s];
      for (int k = 0; k < coef.size(); ++k) m.Add(m.first_row[b] + k + 1, m.col_of[v], coef[k]);
    }
  }
  for (int c = 0; c < nc; ++c) {
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    const int row = m.first_row[nb] + f + 1;
    if (m.col_of[c]) m.Add(row, m.col_of[c], lcp.contacts[c].mu);
    for (int k = 0; k < D; ++k)
      if (m.col_of[nc + D * f + k]) m.Add(row, m.col_of[nc + D * f + k], -1.0);
  }
  DropRoundoff(m);
  LpKeys(lcp, m, &m.row_keys, &m.col_keys);
  return m;
}

void DropRoundoff(RestLpMatrix& m) {
  double largest = 0;
  for (size_t k = 1; k < m.ar.size(); ++k) largest = std::max(largest, std::abs(m.ar[k]));
  size_t kept = 1;
  for (size_t k = 1; k < m.ar.size(); ++k) {
    if (std::abs(m.ar[k]) <= kDropRelative * largest) continue;
    m.ia[kept] = m.ia[k], m.ja[kept] = m.ja[k], m.ar[kept] = m.ar[k];
    ++kept;
  }
  m.ia.resize(kept), m.ja.resize(kept), m.ar.resize(kept);
}

// The bounds of the rows: each balance row equals minus the momentum and
// the external and held impulses in the body's free directions; a cone row is
// free (its contact held), tight (sliding) or ≥ 0 (sticking). GLPK's type and
// value per row.
struct RowBounds {
  std::vector<int> type;
  std::vector<double> value;
};

RowBounds RestLpRowBounds(const ContactLcp& lcp, const RestLpMatrix& m, const ForceFreedom& ff,
                          const std::vector<double>& fixed) {
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int nf = lcp.num_friction;
  const int nr = nc + lcp.num_directions * nf;
  RowBounds rb;
  rb.type.assign(m.nrows, GLP_FX);
  rb.value.assign(m.nrows, 0.0);
  // The impulses of the held unknowns on each body: moved to the right-hand side.
  std::vector<Vector6> held(nb, Vector6::Zero());
  for (int v = 0; v < nr; ++v) {
    if (!std::isfinite(fixed[v]) || fixed[v] == 0.0) continue;
    const JacobianRow& r = RowOf(lcp, v);
    for (int s = 0; s < 2; ++s)
      if (r.body[s] >= 0) held[r.body[s]] += r.g[s] * fixed[v];
  }
  for (int b = 0; b < nb; ++b) {
    const BodyDynamics& body = lcp.bodies[b];
    Matrix6 M = Matrix6::Zero();
    M.topLeftCorner<3, 3>() = body.mass * Matrix3::Identity();
    M.bottomRightCorner<3, 3>() = body.inertia;
    const VectorX rhs = -(m.B[b].transpose() * (M * body.FreeProjector() * body.nu_prev +
                                                body.F_ext * lcp.dt + held[b]));
    for (int k = 0; k < rhs.size(); ++k) rb.value[m.first_row[b] + k] = rhs[k];
  }
  std::vector<char> held_contact(nf, 0);
  for (int c = 0; c < nc; ++c)
    if (lcp.friction_of[c] >= 0 && std::isfinite(fixed[c])) held_contact[lcp.friction_of[c]] = 1;
  for (int f = 0; f < nf; ++f)
    rb.type[m.first_row[nb] + f] = held_contact[f] ? GLP_FR : ff.sliding[f] ? GLP_FX : GLP_LO;
  return rb;
}

// The LP's matrix by columns (GLPK's 1-based row indices), to load a column
// or compare it with the last tick's.
struct ColumnMatrix {
  std::vector<int> start;  // (ncols + 1) into rows/values, 0-based
  std::vector<int> rows;
  std::vector<double> values;
};

ColumnMatrix ByColumns(const RestLpMatrix& m) {
  ColumnMatrix cm;
  cm.start.assign(m.ncols + 2, 0);
  for (size_t e = 1; e < m.ia.size(); ++e) ++cm.start[m.ja[e] + 1];
  for (int j = 1; j <= m.ncols + 1; ++j) cm.start[j] += cm.start[j - 1];
  cm.rows.resize(m.ia.size() - 1);
  cm.values.resize(m.ia.size() - 1);
  std::vector<int> next(cm.start.begin(), cm.start.end() - 1);
  for (size_t e = 1; e < m.ia.size(); ++e) {
    const int at = next[m.ja[e]]++;
    cm.rows[at] = m.ia[e];
    cm.values[at] = m.ar[e];
  }
  cm.start.erase(cm.start.begin());  // start[j - 1] .. start[j]: column j (1-based)
  return cm;
}

}  // namespace

// The GLPK problem of the last rest LP, kept (RestLpBasis::problem) so that
// the next tick's LP, when it has the same rows and columns (the same keys),
// is updated in place: only the columns whose coefficients changed (the
// moving part's contacts) and the right-hand sides are loaded again, instead
// of building, loading and scaling the whole LP (0.9 ms of a Jenga tick's
// 4 ms). The scale factors of the first load are kept.
struct RestLpProblem {
  GlpProblem lp;
  std::vector<std::int64_t> row_keys, col_keys;
  ColumnMatrix columns;
  RowBounds bounds;
};

namespace {

// A fresh problem: rows, columns (≥ 0, cost 1), matrix, equilibration scaling.
void LoadRestLp(const RestLpMatrix& m, const RowBounds& rb, glp_prob* lp) {
  glp_set_obj_dir(lp, GLP_MIN);
  if (m.nrows > 0) glp_add_rows(lp, m.nrows);
  if (m.ncols > 0) glp_add_cols(lp, m.ncols);
  for (int r = 1; r <= m.nrows; ++r)
    glp_set_row_bnds(lp, r, rb.type[r - 1], rb.value[r - 1], rb.value[r - 1]);
  for (int j = 1; j <= m.ncols; ++j) {
    glp_set_col_bnds(lp, j, GLP_LO, 0.0, 0.0);
    glp_set_obj_coef(lp, j, 1.0);
  }
  if (m.ia.size() > 1)
    glp_load_matrix(lp, static_cast<int>(m.ia.size()) - 1, m.ia.data(), m.ja.data(), m.ar.data());
  // Equilibration scaling only: GLP_SF_AUTO's geometric-mean passes took 11 %
  // of the Jenga pull (one LP a tick), for no change in the answers.
  glp_scale_prob(lp, GLP_SF_EQ);
}

// The kept problem brought to this LP (same keys): the columns and row
// bounds that differ, loaded again.
void UpdateRestLp(const ColumnMatrix& columns, const RowBounds& rb, RestLpProblem& kept) {
  glp_prob* lp = kept.lp.p;
  const int ncols = static_cast<int>(columns.start.size()) - 1;
  std::vector<int> ind{0};
  std::vector<double> val{0.0};
  for (int j = 1; j <= ncols; ++j) {
    const int b = columns.start[j - 1], e = columns.start[j];
    const int kb = kept.columns.start[j - 1], ke = kept.columns.start[j];
    if (e - b == ke - kb &&
        std::equal(columns.rows.begin() + b, columns.rows.begin() + e,
                   kept.columns.rows.begin() + kb) &&
        std::equal(columns.values.begin() + b, columns.values.begin() + e,
                   kept.columns.values.begin() + kb))
      continue;
    ind.assign(columns.rows.begin() + b, columns.rows.begin() + e);
    val.assign(columns.values.begin() + b, columns.values.begin() + e);
    ind.insert(ind.begin(), 0);
    val.insert(val.begin(), 0.0);
    glp_set_mat_col(lp, j, e - b, ind.data(), val.data());
  }
  for (size_t r = 0; r < rb.type.size(); ++r)
    if (rb.type[r] != kept.bounds.type[r] || rb.value[r] != kept.bounds.value[r])
      glp_set_row_bnds(lp, static_cast<int>(r) + 1, rb.type[r], rb.value[r], rb.value[r]);
}

// The problem this LP is solved in: the kept one, updated, when it has the
// same rows and columns and nothing else holds it (the guided LP works on a
// copy of the basis); else a fresh one, kept in `warm` for the next tick.
std::shared_ptr<RestLpProblem> LoadOrUpdate(const RestLpMatrix& m, RowBounds rb,
                                            RestLpBasis* warm) {
  ColumnMatrix columns = ByColumns(m);
  if (warm && warm->problem && warm->problem.use_count() == 1 &&
      warm->problem->row_keys == m.row_keys && warm->problem->col_keys == m.col_keys) {
    UpdateRestLp(columns, rb, *warm->problem);
    warm->problem->columns = std::move(columns);
    warm->problem->bounds = std::move(rb);
    return warm->problem;
  }
  auto kept = std::make_shared<RestLpProblem>();
  LoadRestLp(m, rb, kept->lp.p);
  kept->row_keys = m.row_keys;
  kept->col_keys = m.col_keys;
  kept->columns = std::move(columns);
  kept->bounds = std::move(rb);
  if (warm) warm->problem = kept;
  return kept;
}

// A contact's identity from one tick to the next: its parts and features,
// and its rank among the contacts of the component with the same ones (the
// corners of one face-face patch). Its index in the LCP is no identity: when
// a contact opens, every later one shifts, and a basis keyed by index would
// start the next LP from statuses of other contacts (the Jenga pull's tick
// 16, where 8 contacts open: 343 dual simplex iterations, 0 keyed so).
std::vector<std::uint64_t> ContactKeys(const ContactLcp& lcp) {
  const auto mix = [](std::uint64_t h, std::uint64_t v) {  // splitmix64 of h ^ v
    std::uint64_t z = (h ^ v) + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  std::vector<std::uint64_t> keys(lcp.contacts.size());
  std::unordered_map<std::uint64_t, std::uint64_t> seen;
  for (size_t c = 0; c < keys.size(); ++c) {
    const Contact& k = lcp.contacts[c];
    std::uint64_t h = mix(0, static_cast<std::uint64_t>(k.part_a + 2));
    h = mix(h, static_cast<std::uint64_t>(k.part_b + 2));
    h = mix(h, static_cast<std::uint64_t>(k.feature));
    h = mix(h, static_cast<std::uint64_t>(k.index_a + 2));
    h = mix(h, static_cast<std::uint64_t>(k.index_b + 2));
    keys[c] = mix(h, seen[h]++);
  }
  return keys;
}

// The keys of the LP's rows and columns (RestLpBasis): a balance row is its
// body and free direction, a cone row its frictional contact (after every
// body's), a column its contact and which of its unknowns (p_n, β_k) it is.
void LpKeys(const ContactLcp& lcp, const RestLpMatrix& m, std::vector<std::int64_t>* rows,
            std::vector<std::int64_t>* cols) {
  const int nb = static_cast<int>(m.B.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const std::vector<std::uint64_t> contact = ContactKeys(lcp);
  std::vector<int> contact_of_friction(lcp.num_friction, -1);
  for (int c = 0; c < nc; ++c)
    if (lcp.friction_of[c] >= 0) contact_of_friction[lcp.friction_of[c]] = c;
  // Balance rows: small nonnegative numbers; cone rows and columns: hashes
  // with the top bit set (a collision only costs iterations: a hint).
  const auto hashed = [](std::uint64_t h) {
    return static_cast<std::int64_t>(h | (std::uint64_t{1} << 63));
  };
  rows->assign(m.nrows, 0);
  for (int b = 0; b < nb; ++b)
    for (int k = m.first_row[b]; k < m.first_row[b + 1]; ++k)
      (*rows)[k] = 8 * std::int64_t{b} + (k - m.first_row[b]);
  for (int r = m.first_row[nb]; r < m.nrows; ++r)
    (*rows)[r] = hashed(contact[contact_of_friction[r - m.first_row[nb]]]);
  cols->assign(m.ncols, 0);
  for (size_t v = 0; v < m.col_of.size(); ++v) {
    if (!m.col_of[v]) continue;
    const int vi = static_cast<int>(v);
    const int c = vi < nc ? vi : contact_of_friction[(vi - nc) / D];
    const std::uint64_t which = vi < nc ? 0 : 1 + (vi - nc) % D;
    (*cols)[m.col_of[v] - 1] = hashed(contact[c] * 131 + which);
  }
}

// The statuses `warm` gives the rows and columns keyed `keys` (a row or
// column it does not know: basic for a row, at its bound 0 for a column).
std::vector<int> KeyedStatuses(const std::vector<int>& stat, const std::vector<std::int64_t>& from,
                               const std::vector<std::int64_t>& keys, int unknown) {
  if (from == keys) return stat;
  std::unordered_map<std::int64_t, int> by_key;
  by_key.reserve(from.size());
  for (size_t i = 0; i < from.size(); ++i) by_key.emplace(from[i], stat[i]);
  std::vector<int> out(keys.size(), unknown);
  for (size_t i = 0; i < keys.size(); ++i)
    if (const auto it = by_key.find(keys[i]); it != by_key.end()) out[i] = it->second;
  return out;
}

// How the simplex starts from the basis StartBasis set: the dual simplex
// from a dual feasible basis, the primal one from a primal feasible one; a
// basis feasible neither way (the contacts changed under it) is made dual
// feasible by shifting the costs of the columns whose reduced costs are
// negative, and the dual simplex then runs on the shifted costs; once it has
// a primal feasible basis, the costs are restored and the primal simplex
// finishes (cost shifting, as the dual simplex codes of CPLEX and HiGHS
// do). Feasibility does not depend on the costs, so an infeasibility proof
// on the shifted costs is one for the LP.
struct SimplexStart {
  int method = GLP_DUALP;
  std::vector<int> shifted;  // columns whose cost was raised (restored to 1 after)
};

// Reduced costs above this (relative to the unit costs) count as nonnegative.
constexpr double kDualFeasibility = 1e-9;

// Raises the cost of each column at its bound 0 whose reduced cost d_j is
// negative by 2|d_j| (so d_j becomes |d_j| > 0). False when a row's dual is
// of the wrong sign: rows have no cost to shift (the caller restarts).
bool ShiftCosts(glp_prob* lp, const RestLpMatrix& m, SimplexStart* start) {
  for (int r = 1; r <= m.nrows; ++r) {
    const int stat = glp_get_row_stat(lp, r);
    const double d = glp_get_row_dual(lp, r);
    if ((stat == GLP_NL && d < -kDualFeasibility) || (stat == GLP_NU && d > kDualFeasibility) ||
        (stat == GLP_NF && std::abs(d) > kDualFeasibility))
      return false;
  }
  for (int j = 1; j <= m.ncols; ++j) {
    if (glp_get_col_stat(lp, j) != GLP_NL) continue;
    const double d = glp_get_col_dual(lp, j);
    if (d >= -kDualFeasibility) continue;
    glp_set_obj_coef(lp, j, 1.0 - 2.0 * d);
    start->shifted.push_back(j);
  }
  return true;
}

// A warm start from the last basis, mapped by key onto this LP's rows and
// columns (exactly nrows basic: rows made basic, or columns made nonbasic,
// from the last, as needed), else the slack basis (dual feasible: every cost
// is ≥ 0 and every column at its bound 0). Returns the simplex to run from
// it (SimplexStart). On the Jenga pull a kept basis is dual feasible while
// the contacts do not change (0 iterations), primal feasible where the
// forces of the last tick still balance the parts but the cheapest set has
// changed (a few primal iterations, where the dual simplex afresh takes
// 350–430), and feasible neither way where contacts open or close.
SimplexStart StartBasis(const RestLpBasis* warm, const RestLpMatrix& m, glp_prob* lp) {
  SimplexStart start;
  if (warm && !warm->rows.empty() && warm->row_keys.size() == warm->rows.size() &&
      warm->col_keys.size() == warm->cols.size()) {
    std::vector<int> rows = KeyedStatuses(warm->rows, warm->row_keys, m.row_keys, GLP_BS);
    std::vector<int> cols = KeyedStatuses(warm->cols, warm->col_keys, m.col_keys, GLP_NL);
    // A row that no basic column touches (its columns opened, or its
    // forces are now held) makes the basis singular unless its own slack is
    // basic: those first, then other rows from the last, until nrows are
    // basic.
    std::vector<char> covered(m.nrows, 0);
    for (size_t e = 1; e < m.ia.size(); ++e)
      if (cols[m.ja[e] - 1] == GLP_BS) covered[m.ia[e] - 1] = 1;
    for (int r = 0; r < m.nrows; ++r)
      if (!covered[r]) rows[r] = GLP_BS;
    int basic = static_cast<int>(std::count(rows.begin(), rows.end(), GLP_BS) +
                                 std::count(cols.begin(), cols.end(), GLP_BS));
    for (int r = m.nrows - 1; r >= 0 && basic < m.nrows; --r)
      if (rows[r] != GLP_BS) rows[r] = GLP_BS, ++basic;
    for (int j = m.ncols - 1; j >= 0 && basic > m.nrows; --j)
      if (cols[j] == GLP_BS) cols[j] = GLP_NL, --basic;
    for (int r = 1; r <= m.nrows; ++r) glp_set_row_stat(lp, r, rows[r - 1]);
    for (int j = 1; j <= m.ncols; ++j) glp_set_col_stat(lp, j, cols[j - 1]);
    if (glp_warm_up(lp) == 0) {
      if (glp_get_dual_stat(lp) == GLP_FEAS) return start;
      start.method = GLP_PRIMAL;
      if (glp_get_prim_stat(lp) == GLP_FEAS) return start;
      start.method = GLP_DUALP;
      if (ShiftCosts(lp, m, &start)) return start;
      for (int j : start.shifted) glp_set_obj_coef(lp, j, 1.0);
      start.shifted.clear();
    }
  }
  glp_std_basis(lp);
  return start;
}

// The LP's final basis, with its keys, for the next StartBasis.
void KeepBasis(const RestLpMatrix& m, glp_prob* lp, RestLpBasis* warm) {
  warm->rows.resize(m.nrows);
  warm->cols.resize(m.ncols);
  for (int r = 1; r <= m.nrows; ++r) warm->rows[r - 1] = glp_get_row_stat(lp, r);
  for (int j = 1; j <= m.ncols; ++j) warm->cols[j - 1] = glp_get_col_stat(lp, j);
  warm->row_keys = m.row_keys;
  warm->col_keys = m.col_keys;
}

// The simplex StartBasis chose (on shifted costs: then, from the optimum of
// the shifted LP, the primal simplex on the true costs); on trouble on the
// way (a near-singular basis), once more from the slack basis with the primal
// simplex. GLPK's error code.
int RunSimplex(glp_prob* lp, const SimplexStart& start, int* iterations) {
  // GLPK counts iterations over the problem's life (it is kept between LPs).
  const int before = glp_get_it_cnt(lp);
  glp_smcp params;
  glp_init_smcp(&params);
  params.msg_lev = GLP_MSG_OFF;
  params.meth = start.method;
  params.tol_bnd = kBoundTolerance;
  int err = glp_simplex(lp, &params);
  if (!start.shifted.empty()) {
    for (int j : start.shifted) glp_set_obj_coef(lp, j, 1.0);
    if (err == 0 && glp_get_status(lp) == GLP_OPT) {
      params.meth = GLP_PRIMAL;
      err = glp_simplex(lp, &params);
    }
  }
  if (err != 0 && err != GLP_ENOPFS && err != GLP_ENODFS) {
    glp_std_basis(lp);
    params.meth = GLP_PRIMAL;
    err = glp_simplex(lp, &params);
  }
  *iterations = glp_get_it_cnt(lp) - before;
  return err;
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
  const std::optional<ForceFreedom> ff = FreeForces(lcp, nu, fixed, fixed_lambda, &out.message);
  if (!ff) {
    out.outcome = RestSolution::Outcome::kNone;
    return out;
  }
  const RestLpMatrix m = BuildRestLpMatrix(lcp, *ff, solved);
  // GLPK reports to the terminal whatever msg_lev says; the CLI's stdout may
  // be a JSON document.
  const int terminal = glp_term_out(GLP_OFF);
  const std::shared_ptr<RestLpProblem> problem =
      LoadOrUpdate(m, RestLpRowBounds(lcp, m, *ff, fixed), warm);
  glp_prob* lp = problem->lp.p;
  const SimplexStart method = StartBasis(warm, m, lp);
  const int err = RunSimplex(lp, method, &out.iterations);
  glp_term_out(terminal);
  const int status = glp_get_status(lp);
  // The final basis is dual feasible when the dual simplex ends, whether it
  // found the optimum or proved that no forces exist: either warm-starts.
  if (warm && err == 0 && (status == GLP_OPT || status == GLP_NOFEAS)) KeepBasis(m, lp, warm);
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
  // z = (p_n, β) from the LP (held values as given), λ from the hypothesis.
  const int nr = static_cast<int>(m.col_of.size());
  out.z = VectorX::Zero(lcp.size());
  for (int v = 0; v < nr; ++v) {
    if (m.col_of[v]) out.z[v] = std::max(0.0, glp_get_col_prim(lp, m.col_of[v]));
    if (std::isfinite(fixed[v])) out.z[v] = fixed[v];
  }
  for (int f = 0; f < lcp.num_friction; ++f) out.z[nr + f] = ff->lambda[f];
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
  LcpBuildOptions build = lcp.build;
  build.storage = LcpStorage::kAuto;
  const ContactLcp sub = BuildContactLcp(bodies, contacts, build);
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

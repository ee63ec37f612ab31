#include "cairn/mechanics/contact_model.h"

#include <Eigen/Cholesky>  // IWYU pragma: keep
#include <algorithm>
#include <cmath>

#include "cairn/core/check.h"

namespace cairn {

const char* to_string(Formulation f) {
  return f == Formulation::kBaraff ? "baraff" : "stewart-trinkle";
}

double JacobianRow::Dot(const std::vector<Vector6>& nu) const {
  double s = 0;
  for (int k = 0; k < 2; ++k)
    if (body[k] >= 0) s += g[k].dot(nu[body[k]]);
  return s;
}

namespace {

// The free velocity directions of a body, as orthonormal columns of B
// (6 x k): all six for a free 3-D body, (v_x, v_y, ω_z) for a planar one; a
// guided body loses the direction of its guide; a prescribed body has none.
Eigen::Matrix<double, 6, Eigen::Dynamic> FreeBasisOf(const BodyDynamics& b) {
  Eigen::Matrix<double, 6, Eigen::Dynamic> B(6, 0);
  if (b.motion == BodyMotion::kPrescribed) return B;
  // Linear directions: the plane's or all three, less the guide.
  std::vector<Vector3> linear;
  if (b.planar) {
    if (b.motion == BodyMotion::kGuided)
      linear.emplace_back(-b.guide.y(), b.guide.x(), 0);
    else
      linear = {Vector3::UnitX(), Vector3::UnitY()};
  } else if (b.motion == BodyMotion::kGuided) {
    const Vector3 g = b.guide.normalized();
    const Vector3 axis = std::abs(g.x()) < std::sqrt(0.5) ? Vector3::UnitX() : Vector3::UnitY();
    const Vector3 u = (axis - g * g.dot(axis)).normalized();
    linear = {u, g.cross(u)};
  } else {
    linear = {Vector3::UnitX(), Vector3::UnitY(), Vector3::UnitZ()};
  }
  const int nl = static_cast<int>(linear.size());
  const int na = b.planar ? 1 : 3;
  B.setZero(6, nl + na);
  for (int k = 0; k < nl; ++k) B.col(k).head<3>() = linear[k];
  if (b.planar)
    B(5, nl) = 1;
  else
    B.block<3, 3>(3, nl).setIdentity();
  return B;
}

}  // namespace

Matrix6 BodyDynamics::InverseMass() const {
  const auto B = FreeBasisOf(*this);
  if (B.cols() == 0) return Matrix6::Zero();
  Matrix6 M = Matrix6::Zero();
  M.topLeftCorner<3, 3>() = mass * Matrix3::Identity();
  M.bottomRightCorner<3, 3>() = inertia;
  const MatrixX reduced = B.transpose() * M * B;  // k x k, symmetric positive definite
  // Diagonal (axis-aligned inertia, planar bodies): invert exactly.
  if (reduced.isDiagonal(0.0)) {
    const VectorX inv = reduced.diagonal().cwiseInverse();
    return B * inv.asDiagonal() * B.transpose();
  }
  return B * reduced.llt().solve(B.transpose());
}

Eigen::Matrix<double, 6, Eigen::Dynamic> BodyDynamics::FreeBasis() const {
  return FreeBasisOf(*this);
}

Matrix6 BodyDynamics::FreeProjector() const {
  const auto B = FreeBasisOf(*this);
  return B.cols() ? Matrix6(B * B.transpose()) : Matrix6::Zero();
}

namespace {

// The body's motion without contact forces.
Vector6 FreeMotion(const BodyDynamics& b, const Matrix6& W, Formulation formulation, double dt) {
  if (formulation == Formulation::kBaraff) return W * b.F_ext;
  return b.nu_prescribed + b.FreeProjector() * b.nu_prev + W * b.F_ext * dt;
}

// The row of a contact along direction u (n, t or d_k): the relative velocity
// of a's material point over b's at p, along u.
JacobianRow MakeRow(const Contact& c, const Vector3& u, int body_a, int body_b,
                    const std::vector<BodyDynamics>& bodies) {
  JacobianRow row;
  row.body[0] = body_a;
  row.body[1] = body_b;
  if (body_a >= 0) {
    const Vector3 r = c.p_WC - bodies[body_a].p_WBcm;
    row.g[0] << u, r.cross(u);
  }
  if (body_b >= 0) {
    const Vector3 r = c.p_WC - bodies[body_b].p_WBcm;
    row.g[1] << -u, -r.cross(u);
  }
  return row;
}

// A = G M⁻¹ Gᵀ for the rows `rows`, formed body by body.
MatrixX Delassus(const std::vector<const JacobianRow*>& rows, const std::vector<Matrix6>& W_of) {
  const int n = static_cast<int>(rows.size());
  const int nb = static_cast<int>(W_of.size());
  // Rows touching each body, with their coefficient vectors.
  std::vector<std::vector<std::pair<int, Vector6>>> at_body(nb);
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < 2; ++k)
      if (rows[r]->body[k] >= 0) at_body[rows[r]->body[k]].emplace_back(r, rows[r]->g[k]);
  MatrixX A = MatrixX::Zero(n, n);
  for (int b = 0; b < nb; ++b) {
    const auto& list = at_body[b];
    const Matrix6& W = W_of[b];
    for (size_t i = 0; i < list.size(); ++i) {
      const Vector6 mg = W * list[i].second;
      for (size_t j = 0; j < list.size(); ++j)
        A(list[i].first, list[j].first) += mg.dot(list[j].second);
    }
  }
  return A;
}

bool WantDense(LcpStorage storage, int n) {
  return storage == LcpStorage::kDense || storage == LcpStorage::kBoth ||
         (storage == LcpStorage::kAuto && n <= kMaxDenseLcp);
}
bool WantFactored(LcpStorage storage, int n) {
  return storage == LcpStorage::kFactored || storage == LcpStorage::kBoth ||
         (storage == LcpStorage::kAuto && n > kMaxDenseLcp);
}

// The factored form G W Gᵀ + K of an LCP with `rows` (the first rows of G;
// the remaining n − rows.size() rows of G are zero) and K given as triplets.
// The columns of G are the body freedoms that move: (v_x, v_y, ω_z) of a
// planar body, all six of a 3-D one (so a 2-D LCP's factors are no larger
// than a planar model's).
FactoredLcpMatrix Factored(const std::vector<const JacobianRow*>& rows, int n,
                           const std::vector<BodyDynamics>& bodies,
                           const std::vector<Matrix6>& W_of,
                           const std::vector<Eigen::Triplet<double>>& k_entries) {
  const int nb = static_cast<int>(bodies.size());
  static constexpr int kPlanar[3] = {0, 1, 5};
  static constexpr int kSpatial[6] = {0, 1, 2, 3, 4, 5};
  std::vector<int> first(nb + 1, 0);
  for (int b = 0; b < nb; ++b) first[b + 1] = first[b] + (bodies[b].planar ? 3 : 6);
  const auto coords = [&](int b) -> std::pair<const int*, int> {
    return bodies[b].planar ? std::make_pair(kPlanar, 3) : std::make_pair(kSpatial, 6);
  };
  std::vector<Eigen::Triplet<double>> g;
  g.reserve(rows.size() * 12);
  for (size_t r = 0; r < rows.size(); ++r)
    for (int k = 0; k < 2; ++k) {
      const int b = rows[r]->body[k];
      if (b < 0) continue;
      const auto [idx, m] = coords(b);
      for (int a = 0; a < m; ++a)
        if (rows[r]->g[k][idx[a]] != 0.0)
          g.emplace_back(static_cast<int>(r), first[b] + a, rows[r]->g[k][idx[a]]);
    }
  std::vector<Eigen::Triplet<double>> w;
  w.reserve(36 * nb);
  for (int b = 0; b < nb; ++b) {
    const auto [idx, m] = coords(b);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        if (W_of[b](idx[i], idx[j]) != 0.0)
          w.emplace_back(first[b] + i, first[b] + j, W_of[b](idx[i], idx[j]));
  }
  SparseMatrixX G(n, first[nb]), W(first[nb], first[nb]), K(n, n);
  G.setFromTriplets(g.begin(), g.end());
  W.setFromTriplets(w.begin(), w.end());
  K.setFromTriplets(k_entries.begin(), k_entries.end());
  return FactoredLcpMatrix(G, W, K);
}

}  // namespace

namespace {

// Normal, tangent and friction-direction rows of every contact
// (lcp.bodies and lcp.contacts set).
void MakeContactRows(ContactLcp& lcp, int dimension) {
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  // Local body index of each part.
  std::vector<std::pair<int, int>> part_to_body;
  for (int k = 0; k < nb; ++k) part_to_body.emplace_back(lcp.bodies[k].part, k);
  std::sort(part_to_body.begin(), part_to_body.end());
  const auto local = [&](int part) {
    auto it = std::lower_bound(part_to_body.begin(), part_to_body.end(), std::make_pair(part, -1));
    return (it != part_to_body.end() && it->first == part) ? it->second : -1;
  };
  lcp.friction_of.assign(nc, -1);
  lcp.normal_offset = VectorX::Zero(nc);
  for (int c = 0; c < nc; ++c) {
    const Contact& ct = lcp.contacts[c];
    const int ba = local(ct.part_a);
    const int bb = ct.part_b >= 0 ? local(ct.part_b) : -1;
    CAIRN_CHECK(ba >= 0 || bb >= 0);
    lcp.normal_rows.push_back(MakeRow(ct, ct.n_W, ba, bb, lcp.bodies));
    if (dimension == 2) {
      lcp.tangent_rows.push_back(MakeRow(ct, ct.t_W(), ba, bb, lcp.bodies));
    } else {
      const auto [t1, t2] = TangentBasis(ct.n_W);
      lcp.tangent_rows.push_back(MakeRow(ct, t1, ba, bb, lcp.bodies));
      lcp.tangent2_rows.push_back(MakeRow(ct, t2, ba, bb, lcp.bodies));
    }
    if (lcp.formulation == Formulation::kStewartTrinkle && ct.mu > 0) {
      lcp.friction_of[c] = lcp.num_friction++;
      for (const Vector3& d : FrictionDirections(ct, dimension, D)) {
        lcp.direction_rows.push_back(MakeRow(ct, d, ba, bb, lcp.bodies));
        lcp.friction_directions.push_back(d);
      }
    }
  }
}

// Baraff's LCP (paper eq. 1): M = N W Nᵀ over the normal rows, q = N (W F).
void FillBaraff(ContactLcp& lcp, const std::vector<Matrix6>& W_of,
                const std::vector<Vector6>& free_motion, LcpStorage storage) {
  const int nc = static_cast<int>(lcp.contacts.size());
  std::vector<const JacobianRow*> rows;
  for (const auto& r : lcp.normal_rows) rows.push_back(&r);
  if (WantDense(storage, nc)) lcp.M = Delassus(rows, W_of);
  if (WantFactored(storage, nc)) lcp.factored = Factored(rows, nc, lcp.bodies, W_of, {});
  lcp.q.resize(nc);
  for (int c = 0; c < nc; ++c) lcp.q(c) = lcp.normal_rows[c].Dot(free_motion);
}

// The compliant contacts' entries of K (LcpBuildOptions): c_n on the normal
// rows' diagonal, c_t d_kᵀd_j in each contact's block of friction rows.
void AddCompliance(const ContactLcp& lcp, const LcpBuildOptions& options,
                   std::vector<Eigen::Triplet<double>>& k_entries) {
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  if (options.normal_compliance != 0.0)
    for (int c = 0; c < nc; ++c) k_entries.emplace_back(c, c, options.normal_compliance);
  if (options.tangential_compliance == 0.0) return;
  for (int f = 0; f < lcp.num_friction; ++f)
    for (int k = 0; k < D; ++k)
      for (int j = 0; j < D; ++j) {
        const double dd =
            lcp.friction_directions[D * f + k].dot(lcp.friction_directions[D * f + j]);
        if (dd != 0.0)
          k_entries.emplace_back(nc + D * f + k, nc + D * f + j,
                                 options.tangential_compliance * dd);
      }
}

// Stewart–Trinkle's LCP (paper eq. 5): rows are the normals, then D
// directions per frictional contact; then one λ per frictional contact, with
// the coupling K: λ enters every friction row of its contact (E);
// μ p_n − Eᵀ p_f ≥ 0. q adds the gaps over Δt when `use_gaps`.
void FillStewartTrinkle(ContactLcp& lcp, const std::vector<Matrix6>& W_of,
                        const std::vector<Vector6>& free_motion, const LcpBuildOptions& options) {
  const LcpStorage storage = options.storage;
  const bool use_gaps = options.use_gaps;
  const int nc = static_cast<int>(lcp.contacts.size());
  const int D = lcp.num_directions;
  const int nf = lcp.num_friction;
  std::vector<double> mu_of(nf);
  std::vector<int> contact_of(nf);
  for (int c = 0; c < nc; ++c) {
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    mu_of[f] = lcp.contacts[c].mu;
    contact_of[f] = c;
  }
  std::vector<const JacobianRow*> rows;
  for (const auto& r : lcp.normal_rows) rows.push_back(&r);
  for (const auto& r : lcp.direction_rows) rows.push_back(&r);
  const int nr = nc + D * nf;
  const int n = nr + nf;
  std::vector<Eigen::Triplet<double>> k_entries;
  for (int f = 0; f < nf; ++f) {
    const int lam = nr + f;
    for (int k = 0; k < D; ++k) {
      k_entries.emplace_back(nc + D * f + k, lam, 1.0);
      k_entries.emplace_back(lam, nc + D * f + k, -1.0);
    }
    k_entries.emplace_back(lam, contact_of[f], mu_of[f]);
  }
  AddCompliance(lcp, options, k_entries);
  if (WantDense(storage, n)) {
    lcp.M = MatrixX::Zero(n, n);
    lcp.M.topLeftCorner(nr, nr) = Delassus(rows, W_of);
    for (const auto& t : k_entries) lcp.M(t.row(), t.col()) += t.value();
  }
  if (WantFactored(storage, n)) lcp.factored = Factored(rows, n, lcp.bodies, W_of, k_entries);
  lcp.q = VectorX::Zero(n);
  for (int r = 0; r < nr; ++r) lcp.q(r) = rows[r]->Dot(free_motion);
  if (use_gaps)
    for (int c = 0; c < nc; ++c) lcp.normal_offset(c) = lcp.contacts[c].gap / lcp.dt;
  lcp.q.head(nc) += lcp.normal_offset;
}

}  // namespace

ContactLcp BuildContactLcp(std::vector<BodyDynamics> bodies, std::vector<Contact> contacts,
                           const LcpBuildOptions& options) {
  ContactLcp lcp;
  lcp.build = options;
  lcp.formulation = options.formulation;
  lcp.dt = options.dt;
  lcp.bodies = std::move(bodies);
  lcp.contacts = std::move(contacts);
  lcp.num_directions = options.dimension == 2 ? 2 : options.directions;
  CAIRN_CHECK(lcp.num_directions >= 2);
  for (const auto& b : lcp.bodies) CAIRN_CHECK(b.mass > 0 && b.inertia.diagonal().minCoeff() > 0);
  MakeContactRows(lcp, options.dimension);
  // Effective inverse masses, and the free motion W F (Baraff) or
  // ν_p + P ν⁻ + W F Δt (Stewart–Trinkle). (A prescribed velocity is a
  // Stewart–Trinkle notion: the Baraff LCP is at rest, where prescribed
  // bodies are simply fixed.)
  const int nb = static_cast<int>(lcp.bodies.size());
  std::vector<Matrix6> W_of(nb);
  std::vector<Vector6> free_motion(nb);
  for (int k = 0; k < nb; ++k) {
    W_of[k] = lcp.bodies[k].InverseMass();
    free_motion[k] = FreeMotion(lcp.bodies[k], W_of[k], lcp.formulation, lcp.dt);
  }
  if (lcp.formulation == Formulation::kBaraff)
    FillBaraff(lcp, W_of, free_motion, options.storage);
  else
    FillStewartTrinkle(lcp, W_of, free_motion, options);
  return lcp;
}

VectorX ContactLcp::Multiply(const VectorX& z) const {
  if (has_dense()) return M * z;
  VectorX out;
  factored.Multiply(z, &out);
  return out;
}

LcpResult SolveContactLcp(const ContactLcp& lcp, const LemkeParameters& params,
                          const LcpBasis* warm_start) {
  if (lcp.has_dense()) return SolveLemke(lcp.M, lcp.q, params, warm_start);
  return SolveLemkeFactored(lcp.factored, lcp.q, params, warm_start);
}

bool IsContactLcpSolution(const ContactLcp& lcp, const VectorX& z, double tol) {
  if (lcp.has_dense()) return IsLcpSolution(lcp.M, lcp.q, z, tol);
  return IsLcpSolution(lcp.factored, lcp.q, z, tol);
}

ContactSolution RecoverSolution(const ContactLcp& lcp, const VectorX& z) {
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  const int nf = lcp.num_friction;
  const int D = lcp.num_directions;
  const bool st = lcp.formulation == Formulation::kStewartTrinkle;
  CAIRN_CHECK(z.size() == lcp.q.size());
  ContactSolution s;
  s.normal_force = VectorX::Zero(nc);
  s.friction_force.assign(nc, Vector3::Zero());
  s.normal_motion = VectorX::Zero(nc);
  s.tangent_motion.assign(nc, Vector3::Zero());

  // Generalised contact wrench (Baraff: forces) or impulse (S–T) on each body.
  std::vector<Vector6> wrench(nb, Vector6::Zero());
  const auto add = [&](const JacobianRow& row, double value) {
    for (int k = 0; k < 2; ++k)
      if (row.body[k] >= 0) wrench[row.body[k]] += row.g[k] * value;
  };
  const double to_force = st ? 1.0 / lcp.dt : 1.0;
  for (int c = 0; c < nc; ++c) {
    add(lcp.normal_rows[c], z(c));
    s.normal_force(c) = z(c) * to_force;
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    for (int k = 0; k < D; ++k) {
      const double beta = z(nc + D * f + k);
      add(lcp.direction_rows[D * f + k], beta);
      s.friction_force[c] += lcp.friction_directions[D * f + k] * (beta * to_force);
    }
  }

  // Body motions: the free motion plus the contact wrench through W.
  s.body_motion.resize(nb);
  for (int k = 0; k < nb; ++k) {
    const BodyDynamics& b = lcp.bodies[k];
    const Matrix6 W = b.InverseMass();
    s.body_motion[k] = FreeMotion(b, W, lcp.formulation, lcp.dt) + W * wrench[k];
  }

  // Contact motions, and their agreement with the LCP's w: the normal rows
  // are G ν (+ d/Δt), the friction rows J_dk ν + λ.
  const VectorX w = lcp.Multiply(z) + lcp.q;
  double residual = 0;
  for (int c = 0; c < nc; ++c) {
    const Contact& ct = lcp.contacts[c];
    s.normal_motion(c) = lcp.normal_rows[c].Dot(s.body_motion);
    if (lcp.tangent2_rows.empty()) {
      s.tangent_motion[c] = ct.t_W() * lcp.tangent_rows[c].Dot(s.body_motion);
    } else {
      const auto [t1, t2] = TangentBasis(ct.n_W);
      s.tangent_motion[c] = t1 * lcp.tangent_rows[c].Dot(s.body_motion) +
                            t2 * lcp.tangent2_rows[c].Dot(s.body_motion);
    }
    residual = std::max(residual, std::abs(s.normal_motion(c) + lcp.normal_offset(c) - w(c)));
    const int f = lcp.friction_of[c];
    if (f >= 0) {
      const double lambda = z(nc + D * nf + f);
      for (int k = 0; k < D; ++k) {
        const double row = lcp.direction_rows[D * f + k].Dot(s.body_motion);
        residual = std::max(residual, std::abs(row + lambda - w(nc + D * f + k)));
      }
    }
  }
  s.consistency_residual = residual;
  return s;
}

}  // namespace cairn

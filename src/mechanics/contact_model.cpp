#include "cairn/mechanics/contact_model.h"

#include <algorithm>
#include <cmath>

#include "cairn/core/check.h"

namespace cairn {

const char* to_string(Formulation f) {
  return f == Formulation::kBaraff ? "baraff" : "stewart-trinkle";
}

double JacobianRow::Dot(const std::vector<Vector3>& nu) const {
  double s = 0;
  for (int k = 0; k < 2; ++k)
    if (body[k] >= 0) s += g[k].dot(nu[body[k]]);
  return s;
}

Eigen::Matrix3d BodyDynamics::InverseMass() const {
  Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
  switch (motion) {
    case BodyMotion::kFree:
      W.diagonal() << 1 / mass, 1 / mass, 1 / inertia;
      break;
    case BodyMotion::kGuided: {
      // Free directions: the normal of the guide in the plane, and rotation.
      const Vector2 perp(-guide.y(), guide.x());
      W.topLeftCorner<2, 2>() = perp * perp.transpose() / mass;
      W(2, 2) = 1 / inertia;
      break;
    }
    case BodyMotion::kPrescribed:
      break;
  }
  return W;
}

Eigen::Matrix3d BodyDynamics::FreeProjector() const {
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  switch (motion) {
    case BodyMotion::kFree:
      P.setIdentity();
      break;
    case BodyMotion::kGuided: {
      const Vector2 perp(-guide.y(), guide.x());
      P.topLeftCorner<2, 2>() = perp * perp.transpose();
      P(2, 2) = 1;
      break;
    }
    case BodyMotion::kPrescribed:
      break;
  }
  return P;
}

namespace {

// The body's motion without contact forces.
Vector3 FreeMotion(const BodyDynamics& b, Formulation formulation, double dt) {
  if (formulation == Formulation::kBaraff) return b.InverseMass() * b.F_ext;
  return b.nu_prescribed + b.FreeProjector() * b.nu_prev + b.InverseMass() * b.F_ext * dt;
}

// The row of a contact along direction u (n or t): the relative velocity of
// a's material point over b's at p, along u.
JacobianRow MakeRow(const Contact& c, const Vector2& u, int body_a, int body_b,
                    const std::vector<BodyDynamics>& bodies) {
  JacobianRow row;
  row.body[0] = body_a;
  row.body[1] = body_b;
  if (body_a >= 0) {
    const Vector2 r = c.p_WC - bodies[body_a].p_WBcm;
    row.g[0] = Vector3(u.x(), u.y(), Cross2(r, u));
  }
  if (body_b >= 0) {
    const Vector2 r = c.p_WC - bodies[body_b].p_WBcm;
    row.g[1] = -Vector3(u.x(), u.y(), Cross2(r, u));
  }
  return row;
}

// A = G M⁻¹ Gᵀ for the rows `rows`, formed body by body.
MatrixX Delassus(const std::vector<const JacobianRow*>& rows,
                 const std::vector<BodyDynamics>& bodies) {
  const int n = static_cast<int>(rows.size());
  const int nb = static_cast<int>(bodies.size());
  // Rows touching each body, with their coefficient vectors.
  std::vector<std::vector<std::pair<int, Vector3>>> at_body(nb);
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < 2; ++k)
      if (rows[r]->body[k] >= 0) at_body[rows[r]->body[k]].emplace_back(r, rows[r]->g[k]);
  MatrixX A = MatrixX::Zero(n, n);
  for (int b = 0; b < nb; ++b) {
    const auto& list = at_body[b];
    const Eigen::Matrix3d W = bodies[b].InverseMass();
    for (size_t i = 0; i < list.size(); ++i) {
      const Vector3 mg = W * list[i].second;
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
FactoredLcpMatrix Factored(const std::vector<const JacobianRow*>& rows, int n,
                           const std::vector<BodyDynamics>& bodies,
                           const std::vector<Eigen::Triplet<double>>& k_entries) {
  const int nb = static_cast<int>(bodies.size());
  std::vector<Eigen::Triplet<double>> g;
  g.reserve(rows.size() * 6);
  for (size_t r = 0; r < rows.size(); ++r)
    for (int k = 0; k < 2; ++k)
      if (rows[r]->body[k] >= 0)
        for (int a = 0; a < 3; ++a)
          if (rows[r]->g[k][a] != 0.0)
            g.emplace_back(static_cast<int>(r), 3 * rows[r]->body[k] + a, rows[r]->g[k][a]);
  std::vector<Eigen::Triplet<double>> w;
  w.reserve(9 * nb);
  for (int b = 0; b < nb; ++b) {
    const Eigen::Matrix3d Wb = bodies[b].InverseMass();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (Wb(i, j) != 0.0) w.emplace_back(3 * b + i, 3 * b + j, Wb(i, j));
  }
  SparseMatrixX G(n, 3 * nb), W(3 * nb, 3 * nb), K(n, n);
  G.setFromTriplets(g.begin(), g.end());
  W.setFromTriplets(w.begin(), w.end());
  K.setFromTriplets(k_entries.begin(), k_entries.end());
  return FactoredLcpMatrix(G, W, K);
}

}  // namespace

ContactLcp BuildContactLcp(std::vector<BodyDynamics> bodies, std::vector<Contact> contacts,
                           Formulation formulation, double dt, bool use_gaps, LcpStorage storage) {
  ContactLcp lcp;
  lcp.formulation = formulation;
  lcp.dt = dt;
  lcp.bodies = std::move(bodies);
  lcp.contacts = std::move(contacts);
  const int nb = static_cast<int>(lcp.bodies.size());
  const int nc = static_cast<int>(lcp.contacts.size());
  for (const auto& b : lcp.bodies) CAIRN_CHECK(b.mass > 0 && b.inertia > 0);
  // A prescribed velocity is a Stewart–Trinkle notion (the Baraff LCP is at
  // rest, where prescribed bodies are simply fixed).

  // Local body index of each part.
  std::vector<std::pair<int, int>> part_to_body;
  for (int k = 0; k < nb; ++k) part_to_body.emplace_back(lcp.bodies[k].part, k);
  std::sort(part_to_body.begin(), part_to_body.end());
  const auto local = [&](int part) {
    auto it = std::lower_bound(part_to_body.begin(), part_to_body.end(), std::make_pair(part, -1));
    return (it != part_to_body.end() && it->first == part) ? it->second : -1;
  };

  // Normal and tangent rows of every contact.
  lcp.friction_of.assign(nc, -1);
  lcp.normal_offset = VectorX::Zero(nc);
  for (int c = 0; c < nc; ++c) {
    const Contact& ct = lcp.contacts[c];
    const int ba = local(ct.part_a);
    const int bb = ct.part_b >= 0 ? local(ct.part_b) : -1;
    CAIRN_CHECK(ba >= 0 || bb >= 0);
    lcp.normal_rows.push_back(MakeRow(ct, ct.n_W, ba, bb, lcp.bodies));
    lcp.tangent_rows.push_back(MakeRow(ct, ct.t_W(), ba, bb, lcp.bodies));
    if (formulation == Formulation::kStewartTrinkle && ct.mu > 0)
      lcp.friction_of[c] = lcp.num_friction++;
  }

  // The free motion W F (Baraff) or ν_p + P ν⁻ + W F Δt (Stewart–Trinkle).
  std::vector<Vector3> free_motion(nb);
  for (int k = 0; k < nb; ++k) free_motion[k] = FreeMotion(lcp.bodies[k], formulation, dt);

  if (formulation == Formulation::kBaraff) {
    std::vector<const JacobianRow*> rows;
    for (const auto& r : lcp.normal_rows) rows.push_back(&r);
    if (WantDense(storage, nc)) lcp.M = Delassus(rows, lcp.bodies);
    if (WantFactored(storage, nc)) lcp.factored = Factored(rows, nc, lcp.bodies, {});
    lcp.q.resize(nc);
    for (int c = 0; c < nc; ++c) lcp.q(c) = lcp.normal_rows[c].Dot(free_motion);
    return lcp;
  }

  // Stewart–Trinkle: rows are the normals, then ±t for each frictional contact.
  const int nf = lcp.num_friction;
  std::vector<JacobianRow> friction_rows;
  friction_rows.reserve(2 * nf);
  std::vector<double> mu_of(nf);
  std::vector<int> contact_of(nf);
  for (int c = 0; c < nc; ++c) {
    const int f = lcp.friction_of[c];
    if (f < 0) continue;
    JacobianRow plus = lcp.tangent_rows[c], minus = lcp.tangent_rows[c];
    for (int k = 0; k < 2; ++k) minus.g[k] = -minus.g[k];
    friction_rows.push_back(plus);
    friction_rows.push_back(minus);
    mu_of[f] = lcp.contacts[c].mu;
    contact_of[f] = c;
  }
  std::vector<const JacobianRow*> rows;
  for (const auto& r : lcp.normal_rows) rows.push_back(&r);
  for (const auto& r : friction_rows) rows.push_back(&r);
  const int nr = nc + 2 * nf;
  const int n = nr + nf;
  // K: λ enters both friction rows (E); μ p_n − Eᵀ p_f ≥ 0.
  std::vector<Eigen::Triplet<double>> k_entries;
  for (int f = 0; f < nf; ++f) {
    const int lam = nr + f;
    k_entries.emplace_back(nc + 2 * f, lam, 1.0);
    k_entries.emplace_back(nc + 2 * f + 1, lam, 1.0);
    k_entries.emplace_back(lam, contact_of[f], mu_of[f]);
    k_entries.emplace_back(lam, nc + 2 * f, -1.0);
    k_entries.emplace_back(lam, nc + 2 * f + 1, -1.0);
  }
  if (WantDense(storage, n)) {
    lcp.M = MatrixX::Zero(n, n);
    lcp.M.topLeftCorner(nr, nr) = Delassus(rows, lcp.bodies);
    for (const auto& t : k_entries) lcp.M(t.row(), t.col()) = t.value();
  }
  if (WantFactored(storage, n)) lcp.factored = Factored(rows, n, lcp.bodies, k_entries);
  lcp.q = VectorX::Zero(n);
  for (int r = 0; r < nr; ++r) lcp.q(r) = rows[r]->Dot(free_motion);
  if (use_gaps)
    for (int c = 0; c < nc; ++c) lcp.normal_offset(c) = lcp.contacts[c].gap / dt;
  lcp.q.head(nc) += lcp.normal_offset;
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
  const bool st = lcp.formulation == Formulation::kStewartTrinkle;
  CAIRN_CHECK(z.size() == lcp.q.size());
  ContactSolution s;
  s.normal_force = VectorX::Zero(nc);
  s.friction_force = VectorX::Zero(nc);
  s.normal_motion = VectorX::Zero(nc);
  s.tangent_motion = VectorX::Zero(nc);

  // Generalised contact wrench (Baraff: forces) or impulse (S–T) on each body.
  std::vector<Vector3> wrench(nb, Vector3::Zero());
  const auto add = [&](const JacobianRow& row, double value) {
    for (int k = 0; k < 2; ++k)
      if (row.body[k] >= 0) wrench[row.body[k]] += row.g[k] * value;
  };
  const double to_force = st ? 1.0 / lcp.dt : 1.0;
  for (int c = 0; c < nc; ++c) {
    add(lcp.normal_rows[c], z(c));
    s.normal_force(c) = z(c) * to_force;
    const int f = lcp.friction_of[c];
    if (f >= 0) {
      const double net = z(nc + 2 * f) - z(nc + 2 * f + 1);
      add(lcp.tangent_rows[c], net);
      s.friction_force(c) = net * to_force;
    }
  }

  // Body motions: the free motion plus the contact wrench through W.
  s.body_motion.resize(nb);
  for (int k = 0; k < nb; ++k) {
    const BodyDynamics& b = lcp.bodies[k];
    s.body_motion[k] = FreeMotion(b, lcp.formulation, lcp.dt) + b.InverseMass() * wrench[k];
  }

  // Contact motions, and their agreement with the LCP's w: the normal rows
  // are G ν (+ d/Δt), the friction rows ±J_t ν + λ.
  const VectorX w = lcp.Multiply(z) + lcp.q;
  double residual = 0;
  for (int c = 0; c < nc; ++c) {
    s.normal_motion(c) = lcp.normal_rows[c].Dot(s.body_motion);
    s.tangent_motion(c) = lcp.tangent_rows[c].Dot(s.body_motion);
    residual = std::max(residual, std::abs(s.normal_motion(c) + lcp.normal_offset(c) - w(c)));
    const int f = lcp.friction_of[c];
    if (f >= 0) {
      const double lambda = z(nc + 2 * nf + f);
      residual = std::max(residual, std::abs(s.tangent_motion(c) + lambda - w(nc + 2 * f)));
      residual = std::max(residual, std::abs(-s.tangent_motion(c) + lambda - w(nc + 2 * f + 1)));
    }
  }
  s.consistency_residual = residual;
  return s;
}

}  // namespace cairn

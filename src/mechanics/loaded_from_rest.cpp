#include "cairn/mechanics/loaded_from_rest.h"

#include <algorithm>
#include <cmath>

namespace cairn {

const char* to_string(LoadedFromRest::Outcome o) {
  switch (o) {
    case LoadedFromRest::Outcome::kStands:
      return "stands";
    case LoadedFromRest::Outcome::kGivesWay:
      return "gives way";
    case LoadedFromRest::Outcome::kNotRun:
      return "not run";
    case LoadedFromRest::Outcome::kFailed:
      return "failed";
  }
  return "unknown";
}

namespace {

// The collapse step's inertia against the contacts' stiffness,
// m / Δt² = ρ k_n (dimensionless): small, so that a body the springs hold
// barely moves and one they cannot hold runs away.
constexpr double kInertiaRatio = 1e-6;
// The equilibrium's residual a solution may leave, as a fraction of the
// largest weight (dimensionless): round-off of the pivoting.
constexpr double kResidualTolerance = 1e-6;
// In the collapse step, a body moves when its displacement is above this
// share of the fastest body's (dimensionless): the rest is the springs' give.
constexpr double kCollapseShare = 1e-3;
// The collapse step's Lemke pivots, per LCP variable (dimensionless).
constexpr int kCollapsePivotsPerVariable = 10;
// The loading LCP's Lemke pivots, per LCP variable, when the caller sets no
// budget (dimensionless): paths that end take at most 5 on the cross vault's
// states (docs/benchmarks.md, "`bench/sequence_bench.sh`, fifth stop"); one
// that stalls gets twice that, not SolveLemke's default 50, which cost
// seconds for each of the few stalled ones (each form and its perturbed
// retry).
constexpr int kLoadPivotsPerVariable = 10;

// The unknowns of the loaded-from-rest LCP, in order: the free displacement
// coordinates ξ of every body, then per contact f_n, then per frictional
// contact its D friction components β, then its slip γ. ξ is free, written
// either as ξ⁺ − ξ⁻ (both ≥ 0, the equilibrium rows w = ∓Bᵀ(F + Jᵀ z) ≥ 0 as
// their partners: together equality), or `shifted`, as ξ' − s·1 (ξ' ≥ 0 and
// one shift s ≥ 0, partnered with w_i = −Bᵀ(F + Jᵀ z)_i ≥ 0 and their negated
// sum). The first is tried first; Lemke's method can stall on either (pairs
// of opposite columns, or the shift's dense row), rarely on both.
struct Layout {
  std::vector<int> body_offset;  // (nb + 1) into ξ
  int nxi = 0, nc = 0, nf = 0, D = 0;
  bool shifted = false;
  int first() const { return 0; }     // ξ⁺ or ξ'
  int second() const { return nxi; }  // ξ⁻ (nxi of them) or s (one)
  int forces() const { return shifted ? nxi + 1 : 2 * nxi; }
  int normal(int c) const { return forces() + c; }
  int beta(int f, int k) const { return forces() + nc + D * f + k; }
  int gamma(int f) const { return forces() + nc + D * nf + f; }
  int size() const { return forces() + nc + (D + 1) * nf; }
};

// Adds the row `row` (a linear form on the bodies' (v, ω)) written in the
// free coordinates ξ at LCP row r (on ξ', and −Σ on s); and its skew
// transpose in the equilibrium rows: column r of the ξ' rows gets −rowᵀ, of
// the s row +Σ rowᵀ.
void AddCoupling(const JacobianRow& row, const std::vector<Eigen::Matrix<double, 6, -1>>& B,
                 const Layout& L, int r, std::vector<Eigen::Triplet<double>>& M) {
  for (int s = 0; s < 2; ++s) {
    const int b = row.body[s];
    if (b < 0) continue;
    const VectorX g = B[b].transpose() * row.g[s];
    for (int i = 0; i < g.size(); ++i) {
      const int x = L.body_offset[b] + i;
      const int minus = L.shifted ? L.second() : L.second() + x;
      M.emplace_back(r, L.first() + x, g[i]);
      M.emplace_back(r, minus, -g[i]);
      M.emplace_back(L.first() + x, r, -g[i]);
      M.emplace_back(minus, r, g[i]);
    }
  }
}

// The contacts' reach about their bodies' centroids (length), for the
// stiffness's scale: the largest |p − c|, at least the smallest positive one
// the data allow.
double Reach(const ContactLcp& lcp) {
  double r = 0;
  for (const Contact& c : lcp.contacts)
    for (const BodyDynamics& b : lcp.bodies)
      if (b.part == c.part_a || b.part == c.part_b) r = std::max(r, (c.p_WC - b.p_WBcm).norm());
  return r > 0 ? r : 1.0;
}

// The LCP of the file comment, ξ shifted (Layout). M is sparse: the skew
// coupling of the free directions and the contacts' blocks.
void BuildStaticLcp(const ContactLcp& lcp, const std::vector<Eigen::Matrix<double, 6, -1>>& B,
                    const Layout& L, double kn, double kt, SparseMatrixX& sparse, VectorX& q) {
  const int nb = static_cast<int>(lcp.bodies.size());
  const int n = L.size();
  std::vector<Eigen::Triplet<double>> M;  // entries, summed where they repeat
  q = VectorX::Zero(n);
  // Equilibrium rows: w_ξ' = −Bᵀ(F + Jᵀ z) ≥ 0, w_s = Σ Bᵀ(F + Jᵀ z) ≥ 0.
  for (int b = 0; b < nb; ++b) {
    const VectorX f = B[b].transpose() * lcp.bodies[b].F_ext;
    for (int i = 0; i < f.size(); ++i) {
      q[L.first() + L.body_offset[b] + i] = -f[i];
      q[L.shifted ? L.second() : L.second() + L.body_offset[b] + i] += f[i];
    }
  }
  // Normal laws: w_n = J_n u + f_n / k_n.
  for (int c = 0; c < L.nc; ++c) {
    AddCoupling(lcp.normal_rows[c], B, L, L.normal(c), M);
    M.emplace_back(L.normal(c), L.normal(c), 1.0 / kn);
  }
  // Tangential laws: w_β = J_D u + GᵀG β / k_t + E γ, w_γ = μ f_n − Eᵀ β.
  for (int c = 0; c < L.nc; ++c) {
    const int f = L.nf > 0 ? lcp.friction_of[c] : -1;
    if (f < 0) continue;
    for (int k = 0; k < L.D; ++k) {
      const int r = L.beta(f, k);
      AddCoupling(lcp.direction_rows[L.D * f + k], B, L, r, M);
      const Vector3& dk = lcp.friction_directions[L.D * f + k];
      for (int j = 0; j < L.D; ++j)
        M.emplace_back(r, L.beta(f, j), dk.dot(lcp.friction_directions[L.D * f + j]) / kt);
      M.emplace_back(r, L.gamma(f), 1.0);
      M.emplace_back(L.gamma(f), r, -1.0);
    }
    M.emplace_back(L.gamma(f), L.normal(c), lcp.contacts[c].mu);
  }
  sparse.resize(n, n);
  sparse.setFromTriplets(M.begin(), M.end());
}

// Lemke's method on the loading LCP: dense up to kMaxDenseLcp variables,
// factored above. M is sparse (the skew coupling of the bodies' free
// directions and the contacts' blocks), so the factored solver's pivots
// cost O(k²) in the basic unknowns k rather than the dense tableau's O(n²),
// and its perturbed paths settle the degenerate ties (the many coplanar
// contacts of a joint) on which the dense lexicographic rule stalls to its
// pivot limit: on the Armadillo's states, 14 of 126 components stalled
// dense, and the factored paths all ended (docs/benchmarks.md,
// "`bench/sequence_bench.sh`, fifth stop"). Where both end they agree.
LcpResult SolveLoading(const SparseMatrixX& M, const VectorX& q, const LemkeParameters& lemke) {
  const Eigen::Index n = q.size();
  if (n <= kMaxDenseLcp) return SolveLemke(MatrixX(M), q, lemke);
  const FactoredLcpMatrix factored(SparseMatrixX(n, 0), SparseMatrixX(0, 0), M);
  return SolveLemkeFactored(factored, q, lemke);
}

// The forces, slips and displacements of a solution z, and the equilibrium's
// residual (force units).
void ReadState(const ContactLcp& lcp, const std::vector<Eigen::Matrix<double, 6, -1>>& B,
               const Layout& L, const VectorX& z, LoadedFromRest& out) {
  const int nb = static_cast<int>(lcp.bodies.size());
  out.normal_force = VectorX::Zero(L.nc);
  out.friction_force.assign(L.nc, Vector3::Zero());
  out.slipping.assign(L.nc, false);
  std::vector<Vector6> wrench(nb, Vector6::Zero());
  for (int b = 0; b < nb; ++b) wrench[b] = lcp.bodies[b].F_ext;
  const auto apply = [&](const JacobianRow& row, double x) {
    for (int s = 0; s < 2; ++s)
      if (row.body[s] >= 0) wrench[row.body[s]] += x * row.g[s];
  };
  for (int c = 0; c < L.nc; ++c) {
    out.normal_force[c] = std::max(0.0, z[L.normal(c)]);
    apply(lcp.normal_rows[c], out.normal_force[c]);
    const int f = L.nf > 0 ? lcp.friction_of[c] : -1;
    if (f < 0) continue;
    for (int k = 0; k < L.D; ++k) {
      const double beta = std::max(0.0, z[L.beta(f, k)]);
      out.friction_force[c] += beta * lcp.friction_directions[L.D * f + k];
      apply(lcp.direction_rows[L.D * f + k], beta);
    }
    out.slipping[c] = z[L.gamma(f)] > 0;
  }
  out.displacement.assign(nb, Vector6::Zero());
  out.unbalanced.assign(nb, 0.0);
  for (int b = 0; b < nb; ++b) {
    const int k = static_cast<int>(B[b].cols());
    const VectorX minus = L.shifted ? VectorX::Constant(k, z[L.second()])
                                    : VectorX(z.segment(L.second() + L.body_offset[b], k));
    out.displacement[b] = B[b] * (z.segment(L.first() + L.body_offset[b], k) - minus);
    const double w = std::max(lcp.bodies[b].F_ext.head<3>().norm(), 1e-300);
    out.unbalanced[b] = (B[b].transpose() * wrench[b]).lpNorm<Eigen::Infinity>() / w;
    out.equilibrium_residual = std::max(out.equilibrium_residual, out.unbalanced[b]);
  }
}

// How a component that gives way moves: one implicit Stewart–Trinkle step
// from rest with the compliant contacts and almost no inertia (m / Δt² =
// ρ k_n, Δt = 1): bodies the springs hold barely move, the others run away.
// Their displacements (ν⁺ Δt), or empty when Lemke's method fails on it.
std::vector<Vector6> CollapseStep(const ContactLcp& lcp, double kn, double kt,
                                  const LemkeParameters& lemke) {
  // The step: bodies whose inertia is kInertiaRatio of the contact stiffness
  // (m / Δt² = ρ k_n, Δt = 1 s), from rest.
  std::vector<BodyDynamics> bodies = lcp.bodies;
  for (BodyDynamics& b : bodies) {
    const double s = kInertiaRatio * kn / b.mass;
    b.mass *= s;
    b.inertia *= s;
    b.nu_prev.setZero();
  }
  LcpBuildOptions build = lcp.build;
  build.formulation = Formulation::kStewartTrinkle;
  build.dt = 1.0;
  build.use_gaps = false;
  // The contact laws' compliance: p_n / k_n in the normal rows, Gᵀ G β / k_t
  // in the friction rows. The matrix is J W Jᵀ plus sparse terms: stored
  // factored above kMaxDenseLcp, where a pivot costs O(k² + nnz(J)) with k
  // at most the bodies' degrees of freedom, against the dense O(n²).
  build.normal_compliance = 1.0 / kn;
  build.tangential_compliance = 1.0 / kt;
  build.storage = LcpStorage::kAuto;
  // The unscaled F_ext stays: the bodies' weights.
  std::vector<Contact> contacts = lcp.contacts;
  const ContactLcp step = BuildContactLcp(std::move(bodies), std::move(contacts), build);
  // A budget of kCollapsePivotsPerVariable pivots a variable: the step only
  // says how it moves, and the caller has other ways to say it.
  LemkeParameters budget = lemke;
  const int most = kCollapsePivotsPerVariable * (step.size() + 1);
  if (budget.max_pivots <= 0 || budget.max_pivots > most) budget.max_pivots = most;
  const LcpResult r = SolveContactLcp(step, budget);
  if (r.status != LcpStatus::kSolved && r.status != LcpStatus::kTrivial) return {};
  return RecoverSolution(step, r.z).body_motion;
}

}  // namespace

LoadedFromRest LoadFromRest(const ContactLcp& lcp, const LoadFromRestOptions& options) {
  LoadedFromRest out;
  out.tolerance = kResidualTolerance;
  const int nb = static_cast<int>(lcp.bodies.size());
  Layout L;
  L.nc = static_cast<int>(lcp.contacts.size());
  L.nf = lcp.formulation == Formulation::kStewartTrinkle ? lcp.num_friction : 0;
  L.D = lcp.num_directions;
  std::vector<Eigen::Matrix<double, 6, -1>> B(nb);
  L.body_offset.assign(nb + 1, 0);
  double weight = 0;
  for (int b = 0; b < nb; ++b) {
    B[b] = lcp.bodies[b].FreeBasis();
    L.body_offset[b + 1] = L.body_offset[b] + static_cast<int>(B[b].cols());
    weight = std::max(weight, lcp.bodies[b].F_ext.head<3>().norm());
  }
  L.nxi = L.body_offset[nb];
  const int n = L.size();  // the first form's: the larger
  out.variables = n;
  if (n > options.max_variables) {
    out.message = "the loaded-from-rest LCP has " + std::to_string(n) +
                  " variables, beyond its budget of " + std::to_string(options.max_variables);
    return out;
  }
  // Stiffness: any value gives the same answer (homogeneity); this one makes
  // displacements of the order of the parts' size, for conditioning.
  const double kn = options.stiffness_scale * std::max(weight, 1e-300) / Reach(lcp);
  const double kt = options.stiffness_ratio * kn;
  out.stiffness = kn;

  LemkeParameters lemke = options.lemke;
  if (lemke.max_pivots <= 0) lemke.max_pivots = kLoadPivotsPerVariable * (n + 1);
  SparseMatrixX M;
  VectorX q;
  BuildStaticLcp(lcp, B, L, kn, kt, M, q);
  LcpResult r = SolveLoading(M, q, lemke);
  out.pivots = r.pivots;
  if (r.status == LcpStatus::kPivotLimit || r.status == LcpStatus::kNumericalFailure) {
    L.shifted = true;  // the other form of the free displacements (Layout)
    BuildStaticLcp(lcp, B, L, kn, kt, M, q);
    r = SolveLoading(M, q, lemke);
    out.pivots += r.pivots;
  }
  if (r.status == LcpStatus::kRayTermination) {
    // No state of the springs holds full gravity: it gives way. How: the
    // collapse step's displacements.
    out.outcome = LoadedFromRest::Outcome::kGivesWay;
    out.message = "no state of the compliant contacts holds full gravity (Lemke's ray)";
    if (!options.explain) return out;
    LemkeParameters step = options.lemke;
    step.retry_after_ray = true;  // how it gives way: every path the solver has
    out.displacement = CollapseStep(lcp, kn, kt, step);
    out.unbalanced.assign(nb, 0.0);
    if (!out.displacement.empty()) {
      double fastest = 0;
      for (const Vector6& u : out.displacement) fastest = std::max(fastest, u.norm());
      for (int b = 0; b < nb; ++b)
        out.unbalanced[b] = fastest > 0 ? out.displacement[b].norm() / fastest : 0.0;
    }
    out.tolerance = kCollapseShare;
    return out;
  }
  if (r.status != LcpStatus::kSolved && r.status != LcpStatus::kTrivial) {
    out.outcome = LoadedFromRest::Outcome::kFailed;
    out.message = std::string("Lemke's method: ") + to_string(r.status) +
                  (r.message.empty() ? "" : ": " + r.message);
    return out;
  }
  ReadState(lcp, B, L, r.z, out);
  if (out.equilibrium_residual > kResidualTolerance) {
    out.outcome = LoadedFromRest::Outcome::kFailed;
    out.message = "the compliant solution does not balance the parts (residual " +
                  std::to_string(out.equilibrium_residual) + " of a weight)";
    return out;
  }
  out.outcome = LoadedFromRest::Outcome::kStands;
  return out;
}

}  // namespace cairn

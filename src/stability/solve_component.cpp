#include "cairn/stability/solve_component.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace cairn {

const char* to_string(DecidedBy d) {
  switch (d) {
    case DecidedBy::kLemke:
      return "lemke";
    case DecidedBy::kEquilibrium:
      return "equilibrium";
    case DecidedBy::kRestHypothesis:
      return "rest hypothesis";
    case DecidedBy::kMechanism:
      return "mechanism";
    case DecidedBy::kDrag:
      return "drag";
    case DecidedBy::kJammed:
      return "jammed";
    case DecidedBy::kLoadedFromRest:
      return "loaded from rest";
    case DecidedBy::kUndecided:
      return "undecided";
  }
  return "unknown";
}

const char* to_string(VerdictRule r) {
  return r == VerdictRule::kEquilibrium ? "equilibrium" : "loaded-from-rest";
}

const char* to_string(StabilityProof s) {
  switch (s) {
    case StabilityProof::kNone:
      return "none";
    case StabilityProof::kStrong:
      return "strong";
    case StabilityProof::kWeak:
      return "weak";
    case StabilityProof::kNotCertified:
      return "not certified";
  }
  return "unknown";
}

namespace {

// Work budgets (dimensionless operation counts), so that a certificate or a
// probe costs about as much on every machine and its answer never depends on
// the clock. r is the rank bound of the LCP matrix, six times the free bodies
// (W M⁻¹ Wᵀ has the rank of the bodies).
//  - The Lemke probe: a pivot of the factored solver costs O(r²); at most
//    kProbeWork / r² pivots (Jenga, r = 324: 1 900 pivots, it needs 375; the
//    399-block Armadillo vault, r = 2 196: 41, about 0.1 s).
//  - The strong-stability certificate: a dual simplex iteration costs O(rows);
//    at most kCertificateWork / rows iterations (Jenga: 617, it needs 164;
//    Armadillo: 91, where proving infeasibility takes 3 935, 4 s).
constexpr double kProbeWork = 2e8;
constexpr double kCertificateWork = 2e5;
constexpr int kLeastProbePivots = 100;
constexpr int kDenseProbePivotsPerVariable = 10;
constexpr int kLeastCertificateIterations = 50;

// r: the rank bound of the LCP matrix, the free motions of the bodies.
int RankBound(const ContactLcp& lcp) {
  int free = 0;
  for (const BodyDynamics& b : lcp.bodies) free += static_cast<int>(b.FreeBasis().cols());
  return std::max(1, std::min(lcp.size(), free));
}

// The Lemke probe's pivot budget: kProbeWork / r² (dense LCPs: ten pivots a
// variable). −1: not worth starting, because Lemke's
// method brings one basic variable in per pivot and a component whose loads
// span r directions needs about r of them: a budget below r cannot finish.
int ProbePivots(const ContactLcp& lcp) {
  // A dense probe's pivot costs O(n²): at most kDenseProbePivotsPerVariable
  // per variable (a solution takes about one per variable; the shelf's
  // 456-variable LCP ran to the default 50 per variable before ending on a
  // ray: 24 000 pivots).
  if (lcp.has_dense())
    return std::max(kLeastProbePivots, kDenseProbePivotsPerVariable * (lcp.size() + 1));
  const double r = RankBound(lcp);
  const int budget = std::max(kLeastProbePivots, static_cast<int>(kProbeWork / (r * r)));
  return budget < r ? -1 : budget;
}

double CheckTolerance(const ContactLcp& lcp, const LemkeParameters& p) {
  return p.solution_tolerance * std::max(1.0, lcp.q.lpNorm<Eigen::Infinity>());
}

double NaturalResidual(const ContactLcp& lcp, const VectorX& z) {
  return NaturalMapResidual(z, lcp.Multiply(z) + lcp.q);
}

bool Solved(const LcpResult& r) {
  return r.status == LcpStatus::kSolved || r.status == LcpStatus::kTrivial;
}

// Accepts z as the component's answer when it passes the independent check.
bool Accept(const ContactLcp& lcp, const VectorX& z, const LemkeParameters& p, DecidedBy by,
            ComponentSolution& out) {
  if (!IsContactLcpSolution(lcp, z, CheckTolerance(lcp, p))) return false;
  out.decided_by = by;
  out.has_solution = true;
  out.z = z;
  out.residual = NaturalResidual(lcp, z);
  return true;
}

// Lemke's method on the component; its answer only counts once re-checked.
void RunLemke(const ContactLcp& lcp, const SolveContext& ctx, int max_pivots,
              ComponentSolution& out) {
  if (max_pivots < 0) {
    out.notes.push_back("Lemke's method not run: its work budget (" +
                        std::to_string(static_cast<long long>(kProbeWork)) +
                        " / r², r the rank bound " + std::to_string(RankBound(lcp)) +
                        ") is fewer pivots than the basis needs");
    return;
  }
  LemkeParameters p = ctx.lemke;
  if (max_pivots > 0 && (p.max_pivots <= 0 || max_pivots < p.max_pivots)) {
    p.max_pivots = max_pivots;
    out.lemke_budgeted = true;
  }
  out.lemke = SolveContactLcp(lcp, p, ctx.warm_start);
  out.lemke_tried = true;
  if (Solved(out.lemke) && !IsContactLcpSolution(lcp, out.lemke.z, CheckTolerance(lcp, p))) {
    out.lemke.status = LcpStatus::kNumericalFailure;
    out.lemke.message = "the solver's answer failed the independent LCP check";
  }
  if (!Solved(out.lemke))
    out.notes.push_back(
        std::string("Lemke's method failed (") + to_string(out.lemke.status) +
        (out.lemke.message.empty() ? "" : ": " + out.lemke.message) +
        (out.lemke_budgeted ? "; probe budget " + std::to_string(p.max_pivots) + " pivots" : "") +
        ")");
}

// The equilibrium's forces as the LCP's solution with every part at rest.
bool AcceptEquilibrium(const ContactLcp& lcp, const SolveContext& ctx, ComponentSolution& out) {
  if (!out.equilibrium) out.equilibrium = FindStaticEquilibrium(lcp);
  const StaticEquilibrium& eq = *out.equilibrium;
  if (!eq.solved || !eq.exists) return false;
  const auto accept = [&](const StaticEquilibrium& e) {
    if (!Accept(lcp, e.lcp_z, ctx.lemke, DecidedBy::kEquilibrium, out)) return false;
    out.notes.push_back(std::string("the static equilibrium (") + e.method +
                        ") solves the LCP with every part at rest");
    return true;
  };
  if (accept(eq)) return true;
  // An interior point's forces balance to its tolerance relative to the
  // largest load: a light part's imbalance, over its mass, can still fail
  // the check at rest (a cross vault state of 110 blocks: w −4·10⁻⁷ against
  // a tolerance of 10⁻⁷). The simplex's vertex balances to roundoff.
  if (std::string(eq.method).rfind("barrier", 0) == 0) {
    EquilibriumOptions vertex;
    vertex.vertex = true;
    StaticEquilibrium v = FindStaticEquilibrium(lcp, vertex);
    if (v.solved && v.exists && accept(v)) {
      out.equilibrium = std::move(v);
      return true;
    }
  }
  const VectorX w = lcp.Multiply(eq.lcp_z) + lcp.q;
  std::ostringstream why;
  why.precision(3);
  why << "the equilibrium's forces fail the LCP check at rest (equilibrium residual " << eq.residual
      << ", least w " << w.minCoeff() << ", tolerance " << CheckTolerance(lcp, ctx.lemke) << ")";
  out.notes.push_back(why.str());
  return false;
}

// The strong-stability certificate: a frictionless equilibrium (proof in
// static_equilibrium.h), within its work budget.
bool StrongCertificate(const ContactLcp& lcp, const StaticEquilibrium& eq) {
  if (lcp.formulation == Formulation::kBaraff || lcp.num_friction == 0) return eq.exists;
  EquilibriumOptions o;
  o.frictionless = true;
  const double rows = 6.0 * static_cast<double>(lcp.bodies.size());
  o.max_iterations =
      std::max(kLeastCertificateIterations, static_cast<int>(kCertificateWork / rows));
  const StaticEquilibrium fl = FindStaticEquilibrium(lcp, o);
  return fl.solved && fl.exists;
}

// The component's bodies with every free body outside `free` held at rest
// (prescribed zero velocity); `held` gets their local indices.
std::vector<BodyDynamics> HoldAllBut(const ContactLcp& lcp, const std::vector<char>& free,
                                     std::vector<int>* held = nullptr) {
  std::vector<BodyDynamics> bodies = lcp.bodies;
  for (size_t b = 0; b < bodies.size(); ++b) {
    if (free[b] || bodies[b].motion != BodyMotion::kFree) continue;
    bodies[b].motion = BodyMotion::kPrescribed;
    bodies[b].nu_prescribed.setZero();
    if (held) held->push_back(static_cast<int>(b));
  }
  return bodies;
}

// Solves the component's LCP with every free body outside `free` held at
// rest (prescribed zero velocity): how the bodies of `free` move when nothing
// else gives way. A verified solution of that LCP, or a note.
void SolveWithOthersHeld(const ContactLcp& lcp, const SolveContext& ctx,
                         const std::vector<char>& free, ComponentSolution& out) {
  out.held.clear();
  std::vector<BodyDynamics> bodies = HoldAllBut(lcp, free, &out.held);
  if (out.held.empty()) return;  // nothing to hold: the component's own LCP failed
  LcpBuildOptions build = lcp.build;
  build.use_gaps = false;
  build.storage = LcpStorage::kAuto;
  ContactLcp held = BuildContactLcp(std::move(bodies), lcp.contacts, build);
  LemkeParameters p = ctx.lemke;
  const int budget = ProbePivots(held);
  if (budget < 0) {
    out.notes.push_back("the LCP with the other parts held is beyond Lemke's work budget");
    return;
  }
  if (budget > 0) p.max_pivots = budget;
  const LcpResult r = SolveContactLcp(held, p);
  if (Solved(r) && IsContactLcpSolution(held, r.z, CheckTolerance(held, ctx.lemke))) {
    out.has_solution = true;
    out.z = r.z;
    out.residual = NaturalResidual(held, r.z);
    out.held_lcp = std::move(held);
  } else {
    out.notes.push_back(std::string("the LCP with the other parts held: ") + to_string(r.status));
  }
}

// No equilibrium, no LCP solution: the mechanism names the parts that must
// move; the LCP with every other part held at rest says how they move.
void ExplainByMechanism(const ContactLcp& lcp, const SolveContext& ctx, ComponentSolution& out) {
  out.mechanism = out.equilibrium && out.equilibrium->mechanism ? *out.equilibrium->mechanism
                                                                : FindMechanism(lcp);
  if (!out.mechanism->found) {
    out.notes.push_back("mechanism LP: " + out.mechanism->message);
    return;
  }
  out.decided_by = DecidedBy::kMechanism;
  std::vector<char> moving(lcp.bodies.size(), 0);
  for (int b : out.mechanism->moving) moving[b] = 1;
  SolveWithOthersHeld(lcp, ctx, moving, out);
}

// Along a path where the judged parts cannot rest (the rest hypothesis) and
// gravity alone moves none of them (no mechanism): the driven parts drag or
// push their neighbours. The LCP of those neighbours, with every other part
// held at rest, says how they move.
void ExplainByDrag(const ContactLcp& lcp, const SolveContext& ctx, ComponentSolution& out) {
  std::vector<char> driven(lcp.bodies.size(), 0), neighbour(lcp.bodies.size(), 0);
  for (size_t b = 0; b < lcp.bodies.size(); ++b)
    driven[b] = lcp.bodies[b].motion != BodyMotion::kFree;
  for (const JacobianRow& row : lcp.normal_rows) {
    const int a = row.body[0], b = row.body[1];
    if (a >= 0 && b >= 0 && driven[a] && !driven[b]) neighbour[b] = 1;
    if (a >= 0 && b >= 0 && driven[b] && !driven[a]) neighbour[a] = 1;
  }
  SolveWithOthersHeld(lcp, ctx, neighbour, out);
  if (out.has_solution) out.decided_by = DecidedBy::kDrag;
}

// The collapse motion of a component that gives way when loaded from rest:
// the loading step's displacements, scaled so that the fastest body moves by
// 1; bodies far slower than it (the springs' elastic give, below
// kCollapseFraction of it) at rest.
constexpr double kCollapseFraction = 1e-3;

std::vector<Vector6> CollapseMotion(const ContactLcp& lcp, const LoadedFromRest& loaded) {
  std::vector<Vector6> nu = loaded.displacement;
  double fastest = 0;
  std::vector<double> speed(nu.size(), 0.0);
  for (size_t b = 0; b < nu.size(); ++b) {
    const double r = std::sqrt(lcp.bodies[b].inertia.trace() / (2.0 * lcp.bodies[b].mass));
    speed[b] = nu[b].head<3>().norm() + r * nu[b].tail<3>().norm();
    fastest = std::max(fastest, speed[b]);
  }
  for (size_t b = 0; b < nu.size(); ++b)
    nu[b] = fastest > 0 && speed[b] > kCollapseFraction * fastest ? Vector6(nu[b] / fastest)
                                                                  : Vector6::Zero();
  return nu;
}

// The bodies of `lcp` that give way when loaded from rest with every other
// body held where it is (local indices).
std::vector<int> PartsThatGiveWayAlone(const ContactLcp& lcp) {
  std::vector<int> out;
  for (size_t k = 0; k < lcp.bodies.size(); ++k) {
    if (lcp.bodies[k].motion != BodyMotion::kFree) continue;
    std::vector<char> free(lcp.bodies.size(), 0);
    free[k] = 1;
    std::vector<BodyDynamics> bodies = HoldAllBut(lcp, free);
    LcpBuildOptions build = lcp.build;
    build.use_gaps = false;
    build.storage = LcpStorage::kDense;
    const ContactLcp alone = BuildContactLcp(std::move(bodies), lcp.contacts, build);
    if (LoadFromRest(alone).outcome == LoadedFromRest::Outcome::kGivesWay)
      out.push_back(static_cast<int>(k));
  }
  return out;
}

// It gives way, and neither the rigid probe nor the collapse step says how:
// the parts that give way even with every other part held, and how they
// move with the others held (a verified solution of that LCP).
void ExplainByPartsThatGiveWay(const ContactLcp& lcp, const SolveContext& ctx,
                               ComponentSolution& out) {
  const std::vector<int> alone = PartsThatGiveWayAlone(lcp);
  if (alone.empty()) {
    out.notes.push_back(
        "no part gives way alone, and the collapse step failed: how it moves "
        "is not known");
    return;
  }
  std::vector<char> free(lcp.bodies.size(), 0);
  for (int b : alone) free[b] = 1;
  SolveWithOthersHeld(lcp, ctx, free, out);
  if (out.has_solution) {
    out.decided_by = DecidedBy::kLoadedFromRest;
    out.notes.push_back("the parts that give way even with the others held, with the others held");
  }
}

// Loading from rest as the context asks: a conservative verdict takes the
// loading LCP's first secondary ray as its answer and does not seek how
// the component gives way.
LoadFromRestOptions LoadingOptions(const SolveContext& ctx) {
  LoadFromRestOptions o;
  o.lemke.retry_after_ray = !ctx.conservative;
  o.explain = !ctx.conservative;
  return o;
}

// An equilibrium exists and strong stability is not proved: the rule decides
// (VerdictRule). `rest`: a verified LCP solution at rest (Lemke's), or null;
// `moving`: a verified LCP solution in which a part moves, or null.
void DecideOpenCase(const ContactLcp& lcp, const SolveContext& ctx, const VectorX* rest,
                    const VectorX* moving, ComponentSolution& out) {
  // A rigid solution at rest for the report: Lemke's, else the equilibrium's.
  const auto stand = [&](DecidedBy by) {
    if ((rest && Accept(lcp, *rest, ctx.lemke, by, out)) || AcceptEquilibrium(lcp, ctx, out))
      out.decided_by = by;
  };
  if (ctx.rule == VerdictRule::kEquilibrium) {
    out.notes.push_back("an equilibrium exists: it stands by the equilibrium rule");
    stand(rest ? DecidedBy::kLemke : DecidedBy::kEquilibrium);
    return;
  }
  if (!out.loaded) out.loaded = LoadFromRest(lcp, LoadingOptions(ctx));  // (or DecideWeakOrStrong)
  const LoadedFromRest& loaded = *out.loaded;
  switch (loaded.outcome) {
    case LoadedFromRest::Outcome::kStands:
      out.notes.push_back("it stands when loaded from rest on compliant contacts");
      stand(DecidedBy::kLoadedFromRest);
      return;
    case LoadedFromRest::Outcome::kGivesWay:
      out.notes.push_back("it gives way when loaded from rest on compliant contacts");
      if (moving && Accept(lcp, *moving, ctx.lemke, DecidedBy::kLoadedFromRest, out)) return;
      if (!loaded.displacement.empty() || ctx.conservative) {
        out.decided_by = DecidedBy::kLoadedFromRest;
        if (loaded.displacement.empty()) {
          out.gives_way_unexplained = true;
          out.notes.push_back("how it moves was not sought (a conservative verdict)");
        } else {
          out.collapse = CollapseMotion(lcp, loaded);
        }
        return;
      }
      ExplainByPartsThatGiveWay(lcp, ctx, out);
      return;
    case LoadedFromRest::Outcome::kNotRun:
    case LoadedFromRest::Outcome::kFailed:
      out.notes.push_back("loaded from rest: " + std::string(to_string(loaded.outcome)) + " (" +
                          loaded.message + "); the equilibrium decides");
      stand(rest ? DecidedBy::kLemke : DecidedBy::kEquilibrium);
      return;
  }
}

// The bodies a moving LCP solution moves (local indices): those faster than
// kCollapseFraction of the fastest.
std::vector<int> MovingBodies(const ContactLcp& lcp, const VectorX& z) {
  const ContactSolution s = RecoverSolution(lcp, z);
  double fastest = 0;
  for (const Vector6& nu : s.body_motion) fastest = std::max(fastest, nu.norm());
  std::vector<int> out;
  for (size_t b = 0; b < lcp.bodies.size(); ++b)
    if (s.body_motion[b].norm() > kCollapseFraction * fastest) out.push_back(static_cast<int>(b));
  return out;
}

// Rest is possible and the certificate did not prove it guaranteed: is there
// an LCP solution that moves? Lemke's probe may have found one (`lemke`,
// `moves`); else the complete search (mechanics/moving_solution.h), within
// its budget, finds one or proves there is none.
void DecideWeakOrStrong(const ContactLcp& lcp, const SolveContext& ctx, bool lemke, bool moves,
                        ComponentSolution& out) {
  const VectorX* rest = lemke && !moves ? &out.lemke.z : nullptr;
  if (moves) {
    out.stability = StabilityProof::kWeak;
    out.rigid_motion = MovingBodies(lcp, out.lemke.z);
    DecideOpenCase(lcp, ctx, rest, &out.lemke.z, out);
    return;
  }
  // Only the verdict wanted: the search can change it only where the rule
  // would let it fall (loading from rest gives way: a proof of strong
  // stability makes it stand), so elsewhere the rule decides at once.
  if (!ctx.prove_strong) {
    bool stands = ctx.rule == VerdictRule::kEquilibrium;
    if (!stands) {
      out.loaded = LoadFromRest(lcp, LoadingOptions(ctx));
      stands = out.loaded->outcome != LoadedFromRest::Outcome::kGivesWay;
    }
    if (stands) {
      out.stability = StabilityProof::kNotCertified;
      out.notes.push_back("strong stability not sought (only the verdict)");
      DecideOpenCase(lcp, ctx, rest, nullptr, out);
      return;
    }
    if (ctx.conservative) {  // no proof of strong stability sought: it falls
      out.stability = StabilityProof::kNotCertified;
      out.notes.push_back("strong stability not sought (a conservative verdict)");
      DecideOpenCase(lcp, ctx, rest, nullptr, out);
      return;
    }
  }
  MovingSearchOptions o;
  o.check_tolerance = CheckTolerance(lcp, ctx.lemke);
  out.search = SearchMovingSolution(lcp, o);
  const MovingSolution& search = *out.search;
  if (search.outcome == MovingSolution::Outcome::kFound && ctx.moves && ctx.moves(lcp, search.z)) {
    out.stability = StabilityProof::kWeak;
    out.rigid_motion = MovingBodies(lcp, search.z);
    DecideOpenCase(lcp, ctx, rest, &search.z, out);
    return;
  }
  if (search.outcome == MovingSolution::Outcome::kNone) {
    out.stability = StabilityProof::kStrong;
    out.notes.push_back("the complete search proved that no LCP solution moves (" + search.message +
                        "): rest is guaranteed");
    if ((rest && Accept(lcp, *rest, ctx.lemke, DecidedBy::kLemke, out)) ||
        AcceptEquilibrium(lcp, ctx, out))
      return;
  }
  out.stability = StabilityProof::kNotCertified;
  out.notes.push_back(std::string("the search for a moving solution: ") +
                      to_string(search.outcome) + " (" + search.message + ")");
  DecideOpenCase(lcp, ctx, rest, nullptr, out);
}

// The static policy (file comment of the header, "From rest").
void SolveFromRest(const ContactLcp& lcp, const SolveContext& ctx, ComponentSolution& out) {
  // 1. Can the parts stand at all?
  out.equilibrium = FindStaticEquilibrium(lcp);
  const StaticEquilibrium& eq = *out.equilibrium;
  if (!eq.solved) out.notes.push_back("equilibrium LP: " + eq.message);

  if (eq.solved && eq.exists) {
    // 2. Rest is possible. Guaranteed? Then probe for a moving solution.
    const bool strong = StrongCertificate(lcp, eq);
    out.frictionless_equilibrium = strong;
    // With the certificate there is no moving solution to find; Lemke's
    // method still gives the forces of small components (its pivots are
    // cheap there), the equilibrium those of large ones.
    if (strong && !lcp.has_dense()) {
      out.notes.push_back("rest is guaranteed (frictionless equilibrium): no probe needed");
      if (AcceptEquilibrium(lcp, ctx, out)) {
        out.stability = StabilityProof::kStrong;
        return;
      }
    }
    // Only the verdict wanted and no certificate: the probe's answer cannot
    // change it (a motion it finds or not, the rule decides, and the search
    // runs where the rule lets it fall: DecideWeakOrStrong), so it is not
    // run (a large jammed component's probe can take its whole budget).
    if (strong || ctx.prove_strong) RunLemke(lcp, ctx, ProbePivots(lcp), out);
    const bool lemke = Solved(out.lemke);
    const bool moves = lemke && ctx.moves && ctx.moves(lcp, out.lemke.z);
    if (strong) {
      if (lemke && moves)
        out.notes.push_back(
            "Lemke's method found motion below the certificate's resolution; rest is guaranteed");
      if ((lemke && !moves && Accept(lcp, out.lemke.z, ctx.lemke, DecidedBy::kLemke, out)) ||
          AcceptEquilibrium(lcp, ctx, out))
        out.stability = StabilityProof::kStrong;
      return;
    }
    // Rigid bodies leave it open: rest is possible, not guaranteed?
    DecideWeakOrStrong(lcp, ctx, lemke, moves, out);
    return;
  }

  // 3. Something must move (or the LP could not tell): Lemke's method says
  // how, within the same budget (the mechanism below always answers);
  // failing that, the mechanism.
  RunLemke(lcp, ctx, ProbePivots(lcp), out);
  if (Solved(out.lemke) && Accept(lcp, out.lemke.z, ctx.lemke, DecidedBy::kLemke, out)) return;
  if (eq.solved) ExplainByMechanism(lcp, ctx, out);
}

// Along a path (file comment of the header, "With a drive").
void SolveDriven(const ContactLcp& lcp, const SolveContext& ctx, ComponentSolution& out) {
  if (ctx.rest_first) {
    RestSolution r = FindRestSolution(lcp, ctx.rest_warm);
    out.lp_iterations = r.iterations;
    // No rest for all: perhaps for all but a guided part (which then leaves
    // its path: unsupported, with the assembly at rest).
    if (r.outcome == RestSolution::Outcome::kNone) {
      out.rest_none = true;
      if (ctx.has_guided) {
        // From the basis that proved the first LP infeasible: the same LP
        // but for the guided parts' rows and forces (a copy, so that the
        // next tick starts from this tick's first LP).
        RestLpBasis guided;
        if (ctx.rest_warm) guided = *ctx.rest_warm;
        r = FindRestSolution(lcp, &guided, RestHypothesis::kGuidedFree);
        out.lp_iterations += r.iterations;
      }
    }
    if (r.outcome == RestSolution::Outcome::kFound &&
        Accept(lcp, r.z, ctx.lemke, DecidedBy::kRestHypothesis, out))
      return;
  }
  if (out.rest_none) {
    if (AcceptEquilibrium(lcp, ctx, out)) return;
    ExplainByMechanism(lcp, ctx, out);
    if (out.decided_by == DecidedBy::kMechanism) return;
    ExplainByDrag(lcp, ctx, out);
    if (out.decided_by == DecidedBy::kDrag) return;
  }
  RunLemke(lcp, ctx, ProbePivots(lcp), out);
  if (Solved(out.lemke) && Accept(lcp, out.lemke.z, ctx.lemke, DecidedBy::kLemke, out)) return;
  if (!out.rest_none && AcceptEquilibrium(lcp, ctx, out)) return;
  // A driven part whose prescribed motion no contact forces allow.
  if (ctx.has_driven && out.lemke.status == LcpStatus::kRayTermination) {
    out.decided_by = DecidedBy::kJammed;
    return;
  }
  if (!out.rest_none) ExplainByMechanism(lcp, ctx, out);
}

}  // namespace

ComponentSolution SolveComponent(const ContactLcp& lcp, const SolveContext& context) {
  ComponentSolution out;
  if (context.static_check)
    SolveFromRest(lcp, context, out);
  else
    SolveDriven(lcp, context, out);
  return out;
}

}  // namespace cairn

#pragma once
/// @file
/// The solve policy of one contact-graph component: which solvers run, in
/// which order, and what each proves. AnalyzeConfiguration calls it once per
/// component; its answer is always a verified LCP solution (of the component,
/// or of the component with some parts held), or a verified mechanism, never
/// "the solver failed" alone.
///
/// From rest (the static check, no driven parts):
///  1. The static-equilibrium LP (mechanics/static_equilibrium.h). Can the
///     parts stand at all?
///  2. If an equilibrium exists: the strong-stability certificate (a
///     frictionless equilibrium: every LCP solution is then at rest; the proof
///     is in static_equilibrium.h), under a work budget; then Lemke's method as
///     a probe for a moving solution, under a work budget, and where it finds
///     none the complete search (mechanics/moving_solution.h), under its own:
///     a motion, `stability` "weak" (rest possible, not guaranteed: Pang and
///     Trinkle's weak stability); every branch pruned, "strong"; the budget
///     spent, "not certified". With the certificate or the search's proof the
///     component stands. Otherwise rigid bodies leave the answer open, and the
///     rule decides
///     (VerdictRule): the component loaded from rest on compliant contacts
///     (mechanics/loaded_from_rest.h) stands, and the forces reported are a
///     rigid solution at rest (Lemke's, or the equilibrium's); or it gives
///     way, and the motion reported is the probe's, or else the loading's
///     collapse motion. Beyond that analysis's budget, and with the
///     equilibrium rule, the equilibrium decides: it stands.
///  3. If no equilibrium exists, some part must move: Lemke's method gives how.
///     If it fails, the mechanism LP names the parts that must move (a virtual
///     motion along which gravity does work and no contact resists, checked);
///     the component's LCP is then solved again with every other part held at
///     rest, which gives their motion (a verified solution of that LCP). If
///     even that fails, the mechanism itself is the motion reported.
///
/// With a drive (a step of a motion path): in 3-D with friction the rest
/// hypothesis LP first (mechanics/rest_solution.h). Where it proves that the
/// judged parts cannot all stay at rest, the cheap verified explanations come
/// next, before Lemke's method on the whole component (whose probe is the
/// costly step: 0.55 s of the Jenga pull's failing tick, to its pivot limit):
/// a static equilibrium with every part at rest as an LCP solution; the
/// mechanism as above (with the driven parts stopped); the LCP of the driven
/// parts' neighbours with every other part held (they are dragged or pushed:
/// "drag"); only then Lemke's method. Otherwise (no rest hypothesis, or it
/// held but failed its check) Lemke's method, then the equilibrium. A Lemke
/// ray with a driven part is a jam; failing all that, the mechanism.
///
/// The work budgets are deterministic (pivots and simplex iterations scaled by
/// the component's size), so the answers do not depend on the machine.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cairn/lcp/lemke.h"
#include "cairn/mechanics/contact_model.h"
#include "cairn/mechanics/loaded_from_rest.h"
#include "cairn/mechanics/moving_solution.h"
#include "cairn/mechanics/rest_solution.h"
#include "cairn/mechanics/static_equilibrium.h"

namespace cairn {

/// What decided a component.
enum class DecidedBy {
  kLemke,           ///< Lemke's method's solution of the component's LCP
  kEquilibrium,     ///< the static equilibrium, as an LCP solution with every part at rest
  kRestHypothesis,  ///< the rest-hypothesis LP (along paths: judged parts at rest, driven ones
                    ///< on their path)
  kMechanism,       ///< the mechanism LP (parts named), refined by an LCP with the others held
  kDrag,            ///< along a path, no rest and no mechanism: the driven parts' neighbours
                    ///< move (their LCP with every other part held at rest)
  kJammed,          ///< the driven motion is blocked: no contact forces allow it (Lemke's ray)
  kLoadedFromRest,  ///< rigid bodies left it open (an equilibrium and no proof that every
                    ///< solution rests): the component loaded from rest on compliant contacts
                    ///< (mechanics/loaded_from_rest.h) decided
  kUndecided,       ///< nothing above could decide (a defect: reported with its reasons)
};

/// "lemke", "equilibrium", "rest hypothesis", "mechanism", "drag", "jammed",
/// "loaded from rest", "undecided".
const char* to_string(DecidedBy d);

/// What is proved about rest.
enum class StabilityProof {
  kNone,          ///< no rest possible (no equilibrium), or not examined (along paths)
  kStrong,        ///< every solution of the LCP is at rest (certificate)
  kWeak,          ///< rest is possible (an equilibrium) but a moving solution exists (found)
  kNotCertified,  ///< rest is possible; no moving solution found, none ruled out
};

/// "none", "strong", "weak", "not certified".
const char* to_string(StabilityProof s);

/// Which question a static check answers where rigid bodies leave it open
/// (an equilibrium exists, strong stability is not proved).
enum class VerdictRule {
  /// Stands iff it stands when loaded from rest on compliant contacts
  /// (mechanics/loaded_from_rest.h); where that analysis is beyond its budget,
  /// the equilibrium decides (and the report says so).
  kLoadedFromRest,
  /// Stands iff a static equilibrium exists: the rigid-block-equilibrium
  /// answer of RBE tools and rigid-block planners.
  kEquilibrium,
};

/// "loaded-from-rest", "equilibrium" (the CLI's --rule values).
const char* to_string(VerdictRule r);

/// What the caller knows of the component's bodies.
struct SolveContext {
  LemkeParameters lemke;
  /// From rest, nothing driven: the static policy (equilibrium first).
  bool static_check = true;
  /// The static policy's rule where rigid bodies leave the answer open.
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  /// Whether `stability` must be decided as far as the search's budget allows
  /// (check, --require strong). When not (the margins' bisections), the
  /// complete search runs only where its proof could change the verdict:
  /// where loading from rest gives way. The verdict is the same either way.
  bool prove_strong = true;
  /// With prove_strong off: the verdict may say "falls" where the full one
  /// says "stands", never the reverse, for less work where loading from
  /// rest gives way (the rejections of a search, each costing several times
  /// an acceptance): the loading LCP's first secondary ray is its answer
  /// (no retry along the perturbed paths, which can find a solution the
  /// first path missed), and no search for a proof of strong stability
  /// follows (which would make the component stand).
  bool conservative = false;
  /// Along paths: try the rest hypothesis LP first (3-D, friction, a driven
  /// part, no carried one).
  bool rest_first = false;
  /// Along paths: whether a body is guided (pushed along its path only), and
  /// whether any is driven (guided or prescribed).
  bool has_guided = false;
  bool has_driven = false;
  /// Whether an LCP solution moves a part that must stay put (judged), by the
  /// caller's own test (point motions over the tolerance).
  std::function<bool(const ContactLcp&, const VectorX&)> moves;
  /// Warm starts (may be null).
  const LcpBasis* warm_start = nullptr;
  RestLpBasis* rest_warm = nullptr;
};

/// The answer for one component.
struct ComponentSolution {
  DecidedBy decided_by = DecidedBy::kUndecided;
  StabilityProof stability = StabilityProof::kNone;
  /// The LCP whose solution `z` is: the component's, or (mechanism) the same
  /// with the bodies outside the mechanism held at rest. Absent when the
  /// mechanism alone is reported (or undecided).
  std::optional<ContactLcp> held_lcp;  ///< set when the LCP solved is not the component's own
  bool has_solution = false;           ///< z solves the LCP (verified)
  VectorX z;
  double residual = 0;  ///< natural-map residual of z
  /// Lemke's method on the component (status, pivots, message; z not used
  /// unless decided_by is kLemke).
  LcpResult lemke;
  bool lemke_tried = false;
  bool lemke_budgeted = false;  ///< run as a probe with a work budget
  std::optional<StaticEquilibrium> equilibrium;
  std::optional<bool> frictionless_equilibrium;  ///< the certificate, when tried and decided
  std::optional<Mechanism> mechanism;
  /// The static check where an equilibrium exists and strong stability is not
  /// proved: the component loaded from rest (with the loaded-from-rest rule).
  std::optional<LoadedFromRest> loaded;
  /// The complete search for a moving solution, when an equilibrium exists,
  /// the certificate did not prove strong stability and the probe found none.
  std::optional<MovingSolution> search;
  /// When it gives way and the rigid analysis found no motion: the bodies'
  /// collapse motion from the loading step (its displacements, scaled so the
  /// fastest body moves by 1: a direction), decided_by kLoadedFromRest.
  std::vector<Vector6> collapse;
  /// A conservative verdict (SolveContext::conservative): it gives way when
  /// loaded from rest, and how was not sought: every body counts as moving.
  bool gives_way_unexplained = false;
  /// The rigid LCP's probe found a solution in which a part moves (weak
  /// stability's evidence), even where the verdict is that it stands; the
  /// local indices of the bodies it moves.
  std::vector<int> rigid_motion;
  std::vector<int> held;   ///< local body indices held at rest (mechanism refinement)
  int lp_iterations = 0;   ///< rest-hypothesis LP iterations
  bool rest_none = false;  ///< the rest hypothesis proved no rest exists
  /// Human-readable notes in order (what was tried, what failed), for the
  /// report's message; the structured fields above are the contract.
  std::vector<std::string> notes;
};

/// Runs the policy of the file comment on one component's LCP.
ComponentSolution SolveComponent(const ContactLcp& lcp, const SolveContext& context);

}  // namespace cairn

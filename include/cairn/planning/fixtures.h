#pragma once
/// @file
/// Fixel suggestions (paper Section IV-B, Figs. 4-5): when a step of a plan
/// is unstable, point fixtures with the fixed world on the free faces of the
/// parts that moved, opposing their motion; the fewest that make the plan
/// stable, verified by re-running it, with the greatest force each must carry
/// along the path. docs/fixtures.md describes the method and the reports.
///
/// The search, for each failing step in the order the plan runs:
///   1. Candidates. For each part that moved (MotionFailure::parts; judged
///      parts, so at their assembled pose), the points of its free boundary
///      at the failing tick: 2-D, the two ends and the midpoint of every edge
///      that carries no contact with another part (a contact lies on the edge
///      with a normal parallel to the edge's); 3-D, the centroid of every free
///      face and its corners pulled 10% towards the centroid (a corner itself
///      has no single inward direction). The normal is the inward face
///      normal. A candidate is kept when the point's velocity at the failure,
///      v + ω × (p − c), has a component along the outward normal (the fixel
///      opposes the motion), and when the scene accepts it (Assembly::Create:
///      on the boundary, pushing into the part); candidates are ranked by that
///      component, largest first (near-ties: midpoints and centroids first,
///      then part, face and point order), and the first max_candidates kept.
///   2. Subsets of the candidates by increasing size (1, 2, ... up to the
///      fixels still allowed), in lexicographic order of their ranks; each is
///      verified by re-running the whole plan on the scene with every fixel
///      so far plus the subset. The first whose run gets past the failing
///      step (stable, or failing only at a later step) wins.
///   3. The next failure of that run, if any, is treated the same way.
/// Failures fixels cannot prevent end the search: an infeasible step (the
/// gripped parts are blocked), an unsupported one (the gripper must carry
/// its part), a solver failure.
///
/// Parts removed by the plan (in any step) get no fixels: a fixel is fixed
/// to the world, while Cairn's fixtures move with their part, so one on a
/// part that leaves would travel with it (or block it). When only such parts
/// move, the search says so and finds nothing. The planner's one-step plans
/// (a subassembly S leaving T) never meet this: the parts that move stay.
///
/// Deterministic: the same inputs give the same fixels, in the same order.
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/plan.h"
#include "cairn/motion/simulate.h"

namespace cairn {

/// A point of a part's free boundary where a fixel can push: SuggestFixtures'
/// candidates before they are ranked, and `cairn sequence`'s props.
struct FacePoint {
  int part = -1;            ///< index into Assembly::parts()
  Vector3 point{0, 0, 0};   ///< world frame, assembled pose
  Vector3 normal{0, 0, 0};  ///< unit, into the part (the inward face normal)
  int face = -1;            ///< edge (2-D) or face (3-D) index of the part
  bool centre = false;      ///< an edge midpoint or a face centroid
  std::string face_name;    ///< in words: "edge 1 (7, 0)-(7, 3)", "face 4"
};

/// The points of `part`'s boundary, at its assembled pose, on the faces that
/// carry no contact of `contacts` with another part (a contact on the face,
/// within `tol` (length), its normal parallel to the face's): 2-D, the ends
/// and the midpoint of each such edge; 3-D, each such face's centroid and its
/// corners pulled 10% towards it. In the part's face order.
std::vector<FacePoint> FreeFacePoints(const Assembly& a, int part,
                                      const std::vector<Contact>& contacts, double tol);

/// One suggested fixel and what it carries.
struct SuggestedFixel {
  FixtureDef fixture;    ///< part (name), point on its free face, normal into the part
  int part = -1;         ///< index into Assembly::parts()
  int step = -1;         ///< the plan step whose failure it was added for (Plan::steps index)
  double max_force = 0;  ///< the greatest normal force it carries along the plan (force units)
  std::string face;      ///< the face it sits on, in words ("edge 1 (7, 0)-(7, 3)", "face 4")
};

/// Options of SuggestFixtures.
struct FixtureSearchOptions {
  /// The most fixels added in all; the search fails beyond.
  int max_fixels = 3;
  /// The most candidate points considered per failure (the best-opposing ones).
  int max_candidates = 16;
  /// The most plan simulations in all (the budget of the subset search: with
  /// 16 candidates, sizes 1 to 3 are 696 subsets); the search fails beyond.
  int max_simulations = 1000;
  /// The simulation used to find failures and to verify; the search sets
  /// continue_after_failure (off: a run stops at its first failure) and
  /// record_timeline (on: the contacts at a failure, the fixels' forces).
  SimulationOptions simulation;
};

/// What SuggestFixtures found.
struct FixtureSuggestion {
  /// The plan is stable with `fixels` added to the scene (verified by
  /// re-running it; also true with no fixels when `failed` was stable);
  /// false: no set of at most max_fixels was found within the budget, or a
  /// failure is not one fixels can prevent (`stopped_at`, `stop_reason`).
  bool found = false;
  /// Found: the fewest, in the order added (by step; within a step in rank
  /// order). Not found: those that got the plan past its earlier failing
  /// steps, if any (the verification shows where it fails then).
  std::vector<SuggestedFixel> fixels;
  /// The plan re-run on the scene with `fixels` added (after the scene's own
  /// fixtures: fixture index = def.fixtures.size() + index in `fixels`), with
  /// its timeline; when no fixel was added, `failed` itself.
  SimulationResult verification;
  int candidates = 0;   ///< candidate points kept (ranked, accepted) over all failures
  int simulations = 0;  ///< plan simulations run (the verification included)
  /// Not found: the failure where the search stopped, and why, in the
  /// search's own words as they read after "step N (<the failure>)": " is
  /// infeasible: fixels cannot free a blocked motion", ": the budget of 1000
  /// simulations ran out", ... The whole line for people is the report's
  /// (FixtureMessage in cairn/report/words.h).
  std::optional<MotionFailure> stopped_at;
  std::string stop_reason;
};

/// Suggests fixels for `plan` on the scene `def` (which `assembly` was built
/// from: the suggestion adds FixtureDefs and rebuilds it). `failed` is the
/// plan's simulation without them. Steps fail in order; each failure gets
/// the fewest fixels (tried by increasing count) that make the plan stable up
/// to and including that step. Fixels carry no friction (FixtureDef).
/// @throws std::invalid_argument when options.max_fixels, max_candidates or
/// max_simulations < 1.
FixtureSuggestion SuggestFixtures(const AssemblyDef& def, const Assembly& assembly,
                                  const Plan& plan, const SimulationResult& failed,
                                  const FixtureSearchOptions& options = {});

}  // namespace cairn

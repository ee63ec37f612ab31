#pragma once
/// @file
/// Fixel suggestions (paper Section IV-B, Figs. 4-5): when a step of a plan
/// is unstable, point fixtures with the fixed world on the free faces of the
/// parts that moved, opposing their motion; the fewest that make the plan
/// stable, verified by re-running it, with the greatest force each must carry
/// along the path.

#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/motion/plan.h"
#include "cairn/motion/simulate.h"

namespace cairn {

/// One suggested fixel and what it carries.
struct SuggestedFixel {
  FixtureDef fixture;      ///< part (name), point on its free face, normal into the part
  int part = -1;           ///< index into Assembly::parts()
  int step = -1;           ///< the plan step whose failure it was added for (Plan::steps index)
  double max_force = 0;    ///< the greatest normal force it carries along the plan (force units)
  std::string face;        ///< the face it sits on, in words ("edge 1 (7, 0)-(7, 3)", "face 4")
};

/// Options of SuggestFixtures.
struct FixtureSearchOptions {
  /// The most fixels added in all; the search fails beyond.
  int max_fixels = 3;
  /// The most candidate points considered per failure (the best-opposing ones).
  int max_candidates = 16;
  /// The simulation used to find failures and to verify (continue_after_failure
  /// and record_timeline are set by the search).
  SimulationOptions simulation;
};

/// What SuggestFixtures found.
struct FixtureSuggestion {
  /// The plan is stable with `fixels` added to the scene (verified by
  /// re-running it); false: no set of at most max_fixels was found (the
  /// reason in `message`), or the failure is not one fixels can prevent (an
  /// infeasible step).
  bool found = false;
  std::vector<SuggestedFixel> fixels;  ///< the fewest found, in the order added
  SimulationResult verification;       ///< the plan re-run with every fixel of `fixels`
  int candidates = 0;                  ///< candidate points considered in all
  int simulations = 0;                 ///< plan simulations run (the verification included)
  std::string message;                 ///< why nothing was found, when so
};

/// Suggests fixels for `plan` on the scene `def` (which `assembly` was built
/// from: the suggestion adds FixtureDefs and rebuilds it). `failed` is the
/// plan's simulation without them. Steps fail in order; each failure gets
/// the fewest fixels (tried by increasing count) that make the plan stable up
/// to and including that step.
FixtureSuggestion SuggestFixtures(const AssemblyDef& def, const Assembly& assembly,
                                  const Plan& plan, const SimulationResult& failed,
                                  const FixtureSearchOptions& options = {});

}  // namespace cairn

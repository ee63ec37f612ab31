#pragma once
/// @file
/// `cairn simulate ... --margin friction`: the least friction factor k* for
/// which every tick of a plan is stable, and the tick that decides it
/// (docs/margin.md, "Along a plan").
///
/// Method: a bisection over whole simulations (SimulatePlan with every μ
/// multiplied by k), not per-tick static margins. Along a path the verdict of
/// a tick is not the static equilibrium LP's: the gripped parts move, the
/// contacts they slide on carry friction on the sliding cone's boundary
/// (μ N against the motion), parts are pushed, and while every tick is stable
/// the poses do not depend on μ, but the verdict at each does in ways no
/// one parametric LP describes. So each probe is the real simulation, and
/// both ends of the final bracket are verified by one: the plan is stable at
/// `critical` and fails at `failing_at`, whose first failure (step, tick,
/// parts) is the deciding tick. The bisection finds *a* boundary; it is the
/// least stable factor when stability along the plan is monotone in k (more
/// friction never makes a tick fail), which holds for the static ticks but is
/// not guaranteed where driven parts drag others by friction.

#include <optional>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/plan.h"
#include "cairn/motion/simulate.h"

namespace cairn {

/// What PlanFrictionMargin found.
struct PlanMargin {
  /// k* (or μ* when the scene has no friction pairs: `factor` false); empty:
  /// no factor up to the largest allowed makes the plan stable.
  std::optional<double> critical;
  bool factor = false;
  double nominal = 0;  ///< the scene's own μ, or 1 (factor)
  /// The factor just below k* at which the plan fails, and its first failure
  /// (the deciding tick); empty when the plan is stable at k = 0.
  std::optional<double> failing_at;
  std::optional<MotionFailure> failure;
  double tolerance = 0;  ///< the final bracket's width (k's unit)
  int simulations = 0;
};

/// The friction margin of `plan` on the model `def` (see the file comment).
PlanMargin PlanFrictionMargin(const AssemblyDef& def, const Plan& plan,
                              const SimulationOptions& options = {});

}  // namespace cairn

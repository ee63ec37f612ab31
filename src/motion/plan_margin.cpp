#include "cairn/motion/plan_margin.h"

#include <algorithm>

#include "cairn/stability/margin.h"

namespace cairn {

namespace {

// The bisection stops when its bracket is narrower than this fraction of its
// upper end (dimensionless): about 14 simulations from [0, μ].
constexpr double kPlanTolerance = 1e-4;
constexpr int kMaxSimulations = 60;

}  // namespace

PlanMargin PlanFrictionMargin(const AssemblyDef& def, const Plan& plan,
                              const SimulationOptions& options) {
  PlanMargin out;
  const FrictionScaling scaling = FrictionScalingOf(def);
  out.factor = scaling.factor;
  out.nominal = scaling.nominal;
  const Assembly scene = Assembly::Create(def);
  const double k_max = scaling.k_max;
  SimulationOptions sim = options;
  sim.continue_after_failure = false;  // the first failure is the answer
  sim.record_timeline = false;
  // One probe: the whole plan at factor k (its first failure, if any).
  const auto run = [&](double k) {
    ++out.simulations;
    return SimulatePlan(scaling.At(scene, k), plan, sim);
  };
  // 1. A stable upper end: the nominal factor, doubled until the plan holds.
  double hi = out.nominal > 0 ? out.nominal : 1.0, lo = 0;
  std::optional<SimulationResult> failing;
  for (SimulationResult r = run(hi); !r.stable(); r = run(hi)) {
    lo = hi;
    failing = std::move(r);
    if (hi >= k_max || out.simulations >= kMaxSimulations) {
      out.failing_at = lo;
      out.failure = failing->failure;
      return out;
    }
    hi = std::min(2 * hi, k_max);
  }
  // 2. Does it need friction at all?
  if (!failing) {
    SimulationResult r = run(0.0);
    if (r.stable()) {
      out.critical = 0.0;
      return out;
    }
    failing = std::move(r);
  }
  // 3. Bisection: stable at hi, failing at lo (both simulated).
  while (hi - lo > kPlanTolerance * hi && out.simulations < kMaxSimulations) {
    const double mid = 0.5 * (lo + hi);
    SimulationResult r = run(mid);
    if (r.stable()) {
      hi = mid;
    } else {
      lo = mid;
      failing = std::move(r);
    }
  }
  out.critical = hi;
  out.failing_at = lo;
  out.failure = failing->failure;
  out.tolerance = hi - lo;
  return out;
}

}  // namespace cairn

#pragma once
// One policy for every linear program Cairn solves with Clp: which method goes
// first, by the form of the LP and its number of columns. The solves
// themselves (mechanics/clp_solve.h, private) follow it; callers that weigh a
// method's cost before asking (the margins ask the equilibrium LP first where
// the interior-point method would be slow to find an empty set) read it here.
//
// The forms:
//   feasibility   A x = b, x ≥ 0, no objective: the equilibrium LP
//                 (static_equilibrium.h). The dual simplex from the slack
//                 basis is dual feasible at once and searches for primal
//                 feasibility alone; it also proves infeasibility.
//   elastic       min wᵀ(s⁺ + s⁻), A x + s⁺ − s⁻ = b: the least unbalanced
//                 load, whose duals are the mechanism. Its answer must be a
//                 vertex of the dual (bodies that need not move exactly at
//                 rest), so the interior-point method crosses over.
//   parametric    max or min s, A x + s F₁ = b: the margins (margin_lp.h).
//   deficit       min Σ slack of the friction cones: the friction margin's
//                 deficit φ(k) (margin_lp.h), very degenerate (a warm-started
//                 simplex took 2000–16000 pivots per step on the Armadillo
//                 vault).
//
// The thresholds were measured on these machines (docs/benchmarks.md, "The
// equilibrium LP" and "Margins"): below them the dual simplex is as fast and
// its answer exact (a vertex); above, the interior-point method without
// crossover is 2–4 times faster, and its answer is accepted only after the
// same re-check as the simplex's (a failed one goes on to the simplex).

namespace cairn {

enum class LpForm { kFeasibility, kElastic, kParametric, kDeficit };

enum class LpMethod {
  kDualSimplex,       ///< Clp's dual simplex (the primal simplex on its trouble)
  kBarrier,           ///< interior point, no crossover: an interior optimum
  kBarrierCrossover,  ///< interior point, then crossover to a vertex
};

/// From this many columns on, the equilibrium LP (and the elastic and deficit
/// LPs, which have its columns and a few more) go to the interior-point
/// method first (measured: 2000 generators is where the barrier's 12–20
/// iterations overtake the dual simplex's pivots on Jenga and the vaults).
inline constexpr int kFeasibilityBarrierColumns = 2000;

/// From this many columns on, a parametric (margin) LP goes to the
/// interior-point method first: the tilt LP of the 100-brick wall (1141
/// columns) takes 16 ms so, 30 ms by the dual simplex; Jenga's (2497 columns)
/// 15 ms against 44–64 ms.
inline constexpr int kParametricBarrierColumns = 1000;

/// The method an LP of `form` with `columns` columns is solved by first.
LpMethod FirstLpMethod(LpForm form, int columns);

/// The method's name in reports ("dual simplex", "barrier", ...).
const char* to_string(LpMethod method);

}  // namespace cairn

#pragma once
/// @file
/// Weak or strong stability, decided completely: does the rest-state contact
/// LCP of a component (Stewart–Trinkle, every contact closed, every body at
/// rest before the step) have a solution in which something moves?
///
/// Pang and Trinkle call a configuration *strongly stable* when every
/// solution of that LCP is at rest, *weakly stable* when one is (an
/// equilibrium) and another moves. Lemke's method finds one solution, which
/// one depends on the order of the unknowns; this search looks at all of
/// them.
///
/// **The energy of a solution.** With ν⁻ = 0 the step's equations are
/// M ν = Δt F + Jᵀ z (z = (p_n, p_f, λ), J the LCP's rows), so
///
///     νᵀ M ν = Δt Fᵀ ν + (J ν)ᵀ p = Δt Fᵀ ν + zᵀ w − Σ_c μ_c λ_c p_n,c,
///
/// and complementarity (zᵀ w = 0) leaves νᵀ M ν = Δt Fᵀ ν − (friction's
/// dissipation) ≤ Δt Fᵀ ν. A solution moves iff gravity's power Fᵀ ν on it is
/// positive, and every solution has ‖ν‖_M ≤ R = Δt ‖F‖_{M⁻¹}: the velocities
/// are bounded, |ξ_j| ≤ R √((BᵀMB)⁻¹)_jj in each body's free coordinates.
///
/// **The search.** Branch and bound over the complementarity pairs
/// (z_i, w_i), each node a linear program in the bodies' velocities and the
/// impulses (Clp's dual simplex, warm-started from the last node):
///
///     maximise  Fᵀ ν
///     subject to  BᵀMB ξ − Bᵀ Jᵀ z = Bᵀ F Δt          (the step's dynamics)
///                 w = J ν (+ λ E, μ p_n − Eᵀ p_f) ≥ 0,  z ≥ 0
///                 |ξ_j| ≤ R √((BᵀMB)⁻¹)_jj            (the energy bound)
///                 z_i = 0 or w_i = 0 for the pairs fixed on the way down.
///
/// Every solution of the LCP lies in the LP of some leaf, so a node whose LP
/// cannot reach a power of kMotionPowerFraction · R²/Δt holds no solution
/// moving faster than that resolution, and is pruned. A node whose LP point
/// is complementary (each pair to kComplementarityTolerance) is polished:
/// each pair fixed on its smaller side, solved again, and the result
/// re-checked as an LCP solution (IsContactLcpSolution) before it is
/// returned. Depth first, the side nearer complementarity first; the pair
/// branched on is the most violated. (Tangent cuts of νᵀMν ≤ Δt Fᵀν were
/// tried as well: they moved the LP points off the vertices the dive
/// follows, and the snake's moving solution, found in 307 nodes without
/// them, was not found in 3 000 with them.)
///
/// **Budget.** A work count, not a clock: the simplex iterations of every
/// node, plus a fixed overhead per node, times the LP's rows (about the
/// arithmetic a dual simplex iteration does). When it runs out the answer is
/// kBudget with how far the search got: the nodes solved and the nodes still
/// open.

#include <string>

#include "cairn/core/types.h"
#include "cairn/mechanics/contact_model.h"

namespace cairn {

/// The power resolution of the search (dimensionless): a solution is "at
/// rest" when gravity's power on it is below this fraction of the largest
/// power any solution can have, R²/Δt (for one body, speeds below about
/// √(10⁻⁶) = 10⁻³ of its free-fall speed over the step).
inline constexpr double kMotionPowerFraction = 1e-6;

/// The default largest LCP the search takes on (variables): each node is an
/// LP of about that many rows and columns.
inline constexpr int kMovingSearchMaxVariables = 1500;

/// The default work budget of the search: simplex iterations times LP rows
/// (dimensionless; about 0.3 s on the machine of docs/benchmarks.md).
inline constexpr double kMovingSearchWork = 4e6;

/// Options of SearchMovingSolution.
struct MovingSearchOptions {
  /// The work budget (file comment): simplex iterations times LP rows.
  double max_work = kMovingSearchWork;
  /// Gravity's power below which a solution counts as rest (fraction of R²/Δt).
  double power_fraction = kMotionPowerFraction;
  /// The tolerance of the returned z's LCP check (absolute, on the LCP's
  /// units): as the component's other solutions are checked.
  double check_tolerance = 1e-8;
  /// The largest LCP searched (variables); above it the answer is kNotRun.
  int max_variables = kMovingSearchMaxVariables;
};

/// What the search found.
struct MovingSolution {
  enum class Outcome {
    kFound,   ///< a verified LCP solution in which something moves (weak, if rest is possible)
    kNone,    ///< proved: no solution moves (strongly stable, if rest is possible)
    kBudget,  ///< the work budget ran out first (how far: nodes, open)
    kNotRun,  ///< not a rest-state Stewart–Trinkle LCP (moving bodies, or frictionless)
    kFailed,  ///< an LP failed numerically: the search is not complete (message)
  };
  Outcome outcome = Outcome::kNotRun;
  VectorX z;               ///< kFound: the solution, in the LCP's order
  double power = 0;        ///< kFound: gravity's power on it, Fᵀ ν (force · length / s)
  double power_scale = 0;  ///< R²/Δt, the largest power of any solution
  int nodes = 0;           ///< LPs solved (branch-and-bound nodes)
  int open = 0;            ///< kBudget: nodes left unexplored
  int depth = 0;           ///< the deepest node (pairs fixed)
  int lp_iterations = 0;   ///< Clp's simplex iterations, over every node
  double work = 0;         ///< the work spent (file comment)
  double max_work = 0;     ///< the budget it ran under
  int restarts = 0;        ///< nodes whose dual simplex failed and were solved from the slack basis
  std::string message;     ///< kNotRun, kFailed, kBudget: why, in words
};

/// "found", "none", "budget", "not run", "failed".
const char* to_string(MovingSolution::Outcome o);

/// Searches the rest-state LCP of `lcp` (file comment) for a solution in
/// which something moves.
MovingSolution SearchMovingSolution(const ContactLcp& lcp, const MovingSearchOptions& options = {});

}  // namespace cairn

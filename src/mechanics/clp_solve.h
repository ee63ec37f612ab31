#pragma once
// Clp, as every LP of the mechanics stage calls it (private to the stage): its
// statuses by name, and the two ways of solving that the LP policy chooses
// between (cairn/mechanics/lp_policy.h).

#include <coin/ClpSimplex.hpp>
#include <string>

#include "cairn/mechanics/lp_policy.h"

namespace cairn::clp {

/// ClpSimplex::status(), named (Clp's ClpModel.hpp documents the integers).
enum class Status {
  kOptimal = 0,
  kPrimalInfeasible = 1,  ///< no feasible point: for the equilibrium LP, no equilibrium
  kDualInfeasible = 2,    ///< unbounded (where a feasible point exists)
  kStopped = 3,           ///< the iteration or time budget ran out
  kErrors = 4,            ///< stopped on numerical trouble
  kEvent = 5,             ///< stopped by an event handler
};

/// The status of the last solve (kErrors for an integer Clp does not document).
Status StatusOf(const ClpSimplex& lp);

/// "optimal", "primal infeasible", ...
const char* to_string(Status s);

/// A failure message naming the LP, the status and Clp's secondary status:
/// "Clp (friction deficit LP): stopped on numerical errors (status 4,
/// secondary 0)".
std::string Failure(const std::string& what, const ClpSimplex& lp);

/// The interior-point method from scratch, presolve off (the setting every
/// timing in docs/benchmarks.md was taken with: the answer is read by column
/// and row, and re-checked); `max_iterations` > 0 bounds it. The caller reads
/// the status and re-checks an optimum.
void SolveByBarrier(ClpSimplex& lp, LpMethod method, int max_iterations = 0);

/// The dual simplex, and the primal simplex from the slack basis when the dual
/// stops on trouble (neither an answer nor a spent budget). Returns the method
/// that gave the final status: "dual simplex" or "primal simplex".
const char* SolveBySimplex(ClpSimplex& lp);

}  // namespace cairn::clp

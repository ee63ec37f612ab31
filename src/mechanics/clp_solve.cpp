#include "mechanics/clp_solve.h"

#include <coin/ClpSolve.hpp>

namespace cairn {

LpMethod FirstLpMethod(LpForm form, int columns) {
  switch (form) {
    case LpForm::kFeasibility:
    case LpForm::kDeficit:
      return columns >= kFeasibilityBarrierColumns ? LpMethod::kBarrier : LpMethod::kDualSimplex;
    case LpForm::kElastic:
      return columns >= kFeasibilityBarrierColumns ? LpMethod::kBarrierCrossover
                                                   : LpMethod::kDualSimplex;
    case LpForm::kParametric:
      return columns >= kParametricBarrierColumns ? LpMethod::kBarrier : LpMethod::kDualSimplex;
  }
  return LpMethod::kDualSimplex;
}

const char* to_string(LpMethod method) {
  switch (method) {
    case LpMethod::kDualSimplex:
      return "dual simplex";
    case LpMethod::kBarrier:
      return "barrier";
    case LpMethod::kBarrierCrossover:
      return "barrier with crossover";
  }
  return "?";
}

namespace clp {

Status StatusOf(const ClpSimplex& lp) {
  const int s = lp.status();
  return s >= 0 && s <= 5 ? static_cast<Status>(s) : Status::kErrors;
}

const char* to_string(Status s) {
  switch (s) {
    case Status::kOptimal:
      return "optimal";
    case Status::kPrimalInfeasible:
      return "primal infeasible";
    case Status::kDualInfeasible:
      return "dual infeasible (unbounded)";
    case Status::kStopped:
      return "stopped by its iteration budget";
    case Status::kErrors:
      return "stopped on numerical errors";
    case Status::kEvent:
      return "stopped by an event";
  }
  return "?";
}

std::string Failure(const std::string& what, const ClpSimplex& lp) {
  return "Clp (" + what + "): " + to_string(StatusOf(lp)) + " (status " +
         std::to_string(lp.status()) + ", secondary " + std::to_string(lp.secondaryStatus()) + ")";
}

void SolveByBarrier(ClpSimplex& lp, LpMethod method, int max_iterations) {
  ClpSolve how;
  how.setSolveType(method == LpMethod::kBarrierCrossover ? ClpSolve::useBarrier
                                                         : ClpSolve::useBarrierNoCross);
  how.setPresolveType(ClpSolve::presolveOff);
  if (max_iterations > 0) lp.setMaximumIterations(max_iterations);
  lp.initialSolve(how);
}

const char* SolveBySimplex(ClpSimplex& lp) {
  lp.dual();
  switch (StatusOf(lp)) {
    case Status::kOptimal:
    case Status::kPrimalInfeasible:
    case Status::kDualInfeasible:
    case Status::kStopped:
      return "dual simplex";
    case Status::kErrors:
    case Status::kEvent:
      break;
  }
  lp.allSlackBasis(true);
  lp.primal();
  return "primal simplex";
}

}  // namespace clp
}  // namespace cairn

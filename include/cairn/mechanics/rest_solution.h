#pragma once
/// @file
/// The rest hypothesis: a solution of a component's Stewart–Trinkle LCP in
/// which every body moves exactly as the gripper moves it and is otherwise at
/// rest, found by a linear program instead of Lemke's method.
///
/// Why. With friction, the contact LCP of a statically indeterminate assembly
/// has many solutions, and in 3-D whole families of them: a face contact is
/// four corner points, so how a block's weight is shared among the blocks
/// under it is not fixed by rigid-body mechanics, and neither is the friction
/// those shares allow. Pulling the middle block out of a Jenga layer, one
/// solution keeps the tower above at rest (the two side blocks carry enough
/// of it), another lets the pulled block drag it along, a third lets the
/// pulled block yaw (its corner loads unequal, so are the friction forces on
/// them). Lemke's method returns one of them, chosen by its pivoting rules
/// rather than by the physics; on a large component (the 54-block tower, 3744
/// LCP variables) its path wanders through thousands of near-singular bases
/// and ends on a secondary ray or a singular basis (docs/benchmarks.md,
/// "3-D: Jenga tower").
///
/// Whether the parts *can* stay put while the gripper moves one of them is a
/// linear program. Hypothesis: every body moves with its prescribed velocity
/// (along the path, for a guided body; the gripper's, for a prescribed one)
/// and is at rest in each of its free directions. Then every contact's
/// relative velocity is known, and with it every complementarity condition of
/// the Stewart–Trinkle LCP (contact_model.h) but the forces':
///
///  - a contact opening (normal velocity > 0) carries no force; one closing
///    (< 0) refutes the hypothesis: a driven part runs into something that
///    would have to move;
///  - a contact at rest (zero relative velocity: both bodies at rest) sticks:
///    λ = 0, its friction anywhere in the pyramid, Σ_k β_k ≤ μ p_n;
///  - a sliding contact (a driven body against one at rest) has λ = the
///    largest −d_k · u of the friction directions against its slip u, and
///    only those directions may carry friction, at the edge of the pyramid:
///    Σ_k β_k = μ p_n (kinetic friction against the slip);
///
/// and the body velocities equal the hypothesis exactly when the impulses
/// balance every body in its free directions:
///     Bᵀ (Gᵀ z + F Δt) = −Bᵀ M P ν⁻   (B: the free directions, P = B Bᵀ).
/// A nonnegative (p_n, β) meeting these is an LP solution; with λ as above,
/// z = (p_n, β, λ) solves the LCP (every w_i ≥ 0 and z_i w_i = 0 by
/// construction). The LP minimises Σ p_n + Σ β: the least force that holds
/// the parts (and, with all costs ≥ 0, the slack basis is dual feasible, so
/// GLPK's dual simplex starts from it at once: ~300 iterations, ~20 ms, on
/// the Jenga tower against seconds for Lemke).
///
/// The caller re-checks z against the LCP (IsContactLcpSolution) before
/// using it. When no such z exists, something other than the gripper's
/// parts must move, and Lemke's method finds how.
///
/// The answer is Pang and Trinkle's weak stability along the path: the parts
/// stay put if some solution of the contact problem keeps them put (the
/// question `cairn check` answers at rest with FindStaticEquilibrium).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cairn/mechanics/contact_model.h"

namespace cairn {

/// The simplex basis (GLPK row and column statuses) of the last rest LP, to
/// warm-start the next one (a hint only: any basis, even a wrong one, gives
/// the same verdict, only the iterations differ). Rows and columns are keyed
/// by what they are in the LCP (a body's free direction, a contact's cone, an
/// LCP unknown), so that an LP of another shape (contacts that opened or
/// started to slide, a guided part's rows taken out) starts from the statuses
/// of the rows and columns the two share.
struct RestLpProblem;  // rest_solution.cpp: the solver's problem, kept between LPs
struct RestLpBasis {
  std::vector<int> rows, cols;
  std::vector<std::int64_t> row_keys, col_keys;
  /// The last LP itself, updated in place when the next has the same rows
  /// and columns (only the moving part's columns and the right-hand sides
  /// change along a path). Shared by copies; a copy that solves another LP
  /// replaces its own pointer, never the problem behind it.
  std::shared_ptr<RestLpProblem> problem;
};

/// The outcome of FindRestSolution.
struct RestSolution {
  enum class Outcome {
    kFound,          ///< z holds an LCP solution under the hypothesis
    kNone,           ///< no such solution: something the gripper does not move must move
    kNotApplicable,  ///< not a Stewart–Trinkle LCP
    kSolverTrouble,  ///< the LP solver failed (see message): decide by other means
  };
  Outcome outcome = Outcome::kNotApplicable;
  VectorX z;           ///< (n) kFound: the LCP unknowns (p_n, β, λ)
  int iterations = 0;  ///< simplex iterations
  std::string message;
};

/// Which bodies the hypothesis holds still.
enum class RestHypothesis {
  /// Every body at exactly its prescribed velocity (BodyDynamics::nu_prescribed;
  /// zero for a free body).
  kEverythingButDriven,
  /// The same, except the guided bodies (support "none"), whose motion is
  /// solved first: their own contacts as a small LCP (Lemke's method) with
  /// every other body held at its prescribed velocity; then the LP balances
  /// the other bodies with the guided bodies' contact forces as loads. When it
  /// succeeds, the assembly can stay put while the guided part does what it
  /// does (e.g. tips off the assembly: unsupported).
  kGuidedFree,
};

/// Looks for an LCP solution of `lcp` (Stewart–Trinkle) under `hypothesis`
/// (see the file comment). `warm` (optional) is read as a warm start and
/// overwritten with this LP's final basis.
RestSolution FindRestSolution(const ContactLcp& lcp, RestLpBasis* warm = nullptr,
                              RestHypothesis hypothesis = RestHypothesis::kEverythingButDriven);

/// Frees the LP solver's state of the calling thread (GLPK keeps one
/// environment per thread). Worker threads that may have solved LPs call it
/// before they end; harmless when they have not.
void ReleaseThreadSolverState();

}  // namespace cairn

#pragma once
/// @file
/// The stability of one configuration: does every movable part stay put?
///
/// AnalyzeConfiguration is the driver; it reads as the pipeline:
///   DetectContacts → SplitComponents → BuildContactLcp → SolveComponent
///   (the equilibrium LP first, Lemke's method where it decides: one solve
///   policy, solve_component.h) → RecoverSolution → ClassifyMotion.
/// Movable parts that share no contact are solved apart (contact-graph
/// components), so a large scene costs the sum of its pieces.
///
/// The verdict is about body motion, not only contact normals: a frictionless
/// block on a slope keeps every normal acceleration at zero and still slides.
/// A part moves when some point of it accelerates (Baraff) or moves within one
/// step (Stewart–Trinkle) faster than the scene's tolerance
/// (Tolerances::acceleration, Tolerances::velocity).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/core/tolerances.h"
#include "cairn/geometry/assembly.h"
#include "cairn/lcp/lemke.h"
#include "cairn/mechanics/contact_model.h"
#include "cairn/mechanics/rest_solution.h"
#include "cairn/stability/solve_component.h"

namespace cairn {

/// How a moving part moves.
enum class MotionKind {
  kAtRest,  ///< does not move
  kSlides,  ///< translates (keeps some contact)
  kTips,    ///< rotates about a point near its contacts
  kFalls,   ///< loses every contact (free fall, or lifts off all supports)
};

/// "at rest", "slides", "tips", "falls".
const char* to_string(MotionKind kind);

/// How a part moving by (linear, angular) about its centroid moves (the one
/// classification of the check, the simulation and the margins' mechanisms):
/// falls when it keeps no closed contact; tips when its instantaneous axis
/// (Chasles: its point nearest the centroid is ω × v / |ω|²) passes within
/// the larger of twice the part's radius `size` and half the scene's size
/// `scene_size` (lengths); else slides (a far-away axis is a translation
/// with a little spin). `pivot`, when given and the part tips, receives that
/// point relative to the centroid. A part at rest is the caller's to say.
MotionKind ClassifyRigidMotion(const Vector3& linear, const Vector3& angular, bool keeps_contact,
                               double size, double scene_size, Vector3* pivot = nullptr);

/// What a part is doing in a configuration.
enum class PartRole {
  kJudged,      ///< should stay put: any motion makes the configuration unstable
  kCarried,     ///< leaving with the gripped parts but not gripped: free, not judged
  kGuided,      ///< gripped, pushed along the path only (support "none"): its other motion makes it
                ///< unsupported
  kPrescribed,  ///< gripped rigidly (support "full") or a tool: moves with the gripper
};

/// "judged", "carried", "guided", "prescribed".
const char* to_string(PartRole role);

/// Moved by the gripper (guided or prescribed): its motion is an input.
inline bool IsDriven(PartRole role) {
  return role == PartRole::kGuided || role == PartRole::kPrescribed;
}

/// The motion of one movable part.
struct PartMotion {
  int part = -1;
  PartRole role = PartRole::kJudged;
  int component = -1;  ///< index into StabilityResult::components
  bool moving = false;
  MotionKind kind = MotionKind::kAtRest;
  /// Centroid acceleration (length/s², Baraff) or velocity after Δt
  /// (length/s, S–T), world frame (z = 0 in 2-D).
  Vector3 linear{0, 0, 0};
  /// Angular acceleration (rad/s²) or velocity (rad/s), world axes; 2-D:
  /// (0, 0, ω), counter-clockwise positive.
  Vector3 angular{0, 0, 0};
  /// For kTips: the point of the instantaneous axis nearest the centroid (2-D:
  /// the point of zero acceleration/velocity), world frame.
  std::optional<Vector3> pivot;
  double point_motion = 0;  ///< largest |acceleration| or |velocity| over the part's vertices
};

/// One contact with its force and motion.
struct ContactReport {
  Contact contact;
  int component = -1;
  double normal_force = 0;  ///< force units, ≥ 0, on a along n_W
  /// Force units, on a, world frame, in the tangent plane (2-D: along ±t_W).
  Vector3 friction_force{0, 0, 0};
  double normal_motion =
      0;  ///< relative normal acceleration (Baraff) or velocity (S–T); > 0 separates
  /// Relative tangential acceleration or velocity of a over b, world frame.
  Vector3 tangent_motion{0, 0, 0};
  bool breaking = false;  ///< normal_motion above the tolerance: the contact opens
  bool sliding = false;   ///< |tangent_motion| above the tolerance while closed
};

/// One contact-graph component and its solve.
struct ComponentReport {
  std::vector<int> parts;  ///< movable parts (indices into Assembly::parts())
  int num_contacts = 0;
  int lcp_size = 0;
  /// What decided the component (stability/solve_component.h).
  DecidedBy decided_by = DecidedBy::kLemke;
  /// What is proved about rest (static checks; kNone along paths).
  StabilityProof stability = StabilityProof::kNone;
  /// Lemke's method's status (kSolved when another solver decided).
  LcpStatus status = LcpStatus::kTrivial;
  int pivots = 0;
  double residual = 0;              ///< natural-map residual of the LCP solution
  double consistency_residual = 0;  ///< LCP w against the recovered body motions
  bool warm_start_used = false;
  /// Solved by the rest hypothesis (mechanics/rest_solution.h: every judged
  /// part at rest, an LP) rather than by Lemke's method; `pivots` is then 0.
  bool rest_solution = false;
  int lp_iterations = 0;  ///< simplex iterations of the rest hypothesis, when tried
  std::string message;    ///< diagnostics when the solve failed
  /// With StabilityOptions::check_equilibrium: whether the component could
  /// stand in static equilibrium (mechanics/static_equilibrium.h); empty when
  /// not asked for or when the LP solver failed.
  std::optional<bool> static_equilibrium;
  /// The strong-stability certificate (a frictionless equilibrium), when tried
  /// and decided within its budget.
  std::optional<bool> frictionless_equilibrium;
  std::string equilibrium_method;  ///< the LP method that decided the equilibrium
  /// Parts held at rest to find how the mechanism's parts move (decided_by
  /// kMechanism), part indices.
  std::vector<int> held;
  /// The mechanism (decided_by kMechanism): the parts it moves and gravity's
  /// power along it (force · length/s for a unit-speed motion).
  std::vector<int> mechanism_parts;
  double mechanism_power = 0;
  /// The component loaded from rest on compliant contacts, when rigid bodies
  /// left its answer open (static checks with the loaded-from-rest rule).
  std::optional<LoadedFromRest::Outcome> loaded_from_rest;
  /// Its forces' imbalance: the largest over the parts of the force the
  /// contacts leave unbalanced, as a fraction of the part's weight; and the
  /// parts above the tolerance (those that give way), part indices.
  double loaded_unbalanced = 0;
  std::vector<int> loaded_gives_way;
  /// The parts a rigid solution of the LCP moves although the verdict may be
  /// that they stand (weak stability's evidence), part indices.
  std::vector<int> rigid_motion_parts;
  /// The complete search for a moving solution (mechanics/moving_solution.h),
  /// when it ran: its outcome, the nodes it solved, and those left open when
  /// its work budget ran out.
  std::optional<MovingSolution::Outcome> search;
  int search_nodes = 0, search_open = 0;
};

/// The overall answer.
enum class Verdict {
  kStable,         ///< no movable part moves
  kUnstable,       ///< some movable part moves
  kSolverFailure,  ///< no solver, equilibrium or mechanism decided a component (a defect;
                   ///< see diagnostics)
};

/// "stable", "unstable", "solver failure".
const char* to_string(Verdict v);

/// Wall-clock seconds spent in each stage of AnalyzeConfiguration.
struct StageProfile {
  double detect = 0, build = 0, solve = 0, classify = 0;
};

/// Everything AnalyzeConfiguration found.
struct StabilityResult {
  Verdict verdict = Verdict::kStable;
  bool stable() const { return verdict == Verdict::kStable; }
  Formulation formulation = Formulation::kBaraff;
  double dt = 1.0;                      ///< s (Stewart–Trinkle step)
  Tolerances tolerances;                ///< the tolerances used
  std::vector<PartMotion> parts;        ///< every present movable part, by part index
  std::vector<ContactReport> contacts;  ///< every contact
  std::vector<ComponentReport> components;
  std::vector<int> moving;       ///< judged parts that move
  std::vector<int> unsupported;  ///< guided parts that move off their path (fall or tip)
  std::vector<int> jammed;       ///< driven parts whose prescribed motion no contact forces allow
  StageProfile profile;
  std::string diagnostics;  ///< what went wrong numerically, if anything
  /// With StabilityOptions::check_equilibrium: every component could stand in
  /// static equilibrium (empty: not asked for, or an LP failed).
  std::optional<bool> static_equilibrium;
  /// Some part moves (the LCP from rest finds motion) although a static
  /// equilibrium exists: the configuration can only be held by forces nothing
  /// produces, such as a squeeze between faces (jamming; Pang and Trinkle's
  /// weak stability).
  bool weakly_stable = false;
  /// Static checks: what is proved about rest (SolveComponent): kStrong, every
  /// LCP solution is at rest; kWeak, an equilibrium exists but the parts move
  /// (weakly_stable); kNotCertified, stable, rest possible and no motion found
  /// but not proved impossible; kNone, unstable with no equilibrium (or along
  /// paths, where it is not examined).
  StabilityProof stability = StabilityProof::kNone;
  /// The rule of the static check (StabilityOptions::rule).
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  /// Static checks: whether loading from rest decided (kStands, kGivesWay) a
  /// component, or was beyond its budget or failed (kNotRun, kFailed: the
  /// equilibrium decided); the least favourable over the components (gives
  /// way, then failed, not run, stands). Empty: no component needed it.
  std::optional<LoadedFromRest::Outcome> loaded_from_rest;
};

/// How the gripper drives the parts of one configuration (motion stage). Every
/// vector is indexed by part, and empty means "nothing driven, all at rest".
struct DriveInputs {
  std::vector<PartRole> role;  ///< (num_parts) default kJudged
  /// (num_parts) gripper velocity of kGuided/kPrescribed parts (length/s, world)
  std::vector<Vector3> velocity;
  /// (num_parts) kGuided: unit direction of the path the gripper holds the
  /// part along (its speed, |velocity|, may be 0 at the end of the path)
  std::vector<Vector3> guide;
  std::vector<Vector6> nu_prev;  ///< (num_parts) each part's (v, ω) before this step
};

/// Warm starts kept between calls, e.g. along a motion path: the last basis of
/// each component structure (the same bodies, the same contact features in the
/// same order, the same LCP size). A basis is only ever offered to a component
/// of exactly its structure.
class StabilityWorkspace {
 public:
  StabilityWorkspace();
  ~StabilityWorkspace();
  StabilityWorkspace(StabilityWorkspace&&) noexcept;
  StabilityWorkspace& operator=(StabilityWorkspace&&) noexcept;
  StabilityWorkspace(const StabilityWorkspace&) = delete;
  StabilityWorkspace& operator=(const StabilityWorkspace&) = delete;

  /// Solves answered by a warm start since the last TakeWarmStarts.
  int warm_starts() const;
  /// warm_starts(), and the count starts again from 0.
  int TakeWarmStarts();
  /// Component structures with a stored basis.
  int num_structures() const;

  /// Reuse mode, for static checks of scenes that differ only in which
  /// parts are present, fixed or held (the states of a build order), all
  /// with the same options: no warm start is offered (every solve is the
  /// cold one a fresh check makes), and each component's solution is kept
  /// by the component's whole data (its bodies, contacts and the verdict's
  /// options, compared exactly), so that a component met again is not
  /// solved again. The answers are those of fresh checks.
  void set_reuse_solutions(bool on);
  /// Components answered from the kept solutions (reuse mode).
  int reused() const;

  /// The stored bases and LP hints (defined in analyze.cpp only).
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// A force on a movable part, besides gravity: `force` (force units, world
/// frame) acting at `point` (world frame, in the configuration checked).
struct PartLoad {
  int part = -1;
  Vector3 force{0, 0, 0};
  Vector3 point{0, 0, 0};
};

/// Options of AnalyzeConfiguration.
struct StabilityOptions {
  double dt = 1.0;  ///< Stewart–Trinkle step (s); the verdict does not depend on it from rest
  std::optional<Formulation> formulation;  ///< default: Baraff when the scene is frictionless
  std::optional<Tolerances> tolerances;    ///< default: Assembly::MakeTolerances(dt)
  LemkeParameters lemke;
  /// Dense or factored LCP matrices (kAuto: dense up to kMaxDenseLcp
  /// variables); the solver follows the storage. kBoth solves densely.
  LcpStorage lcp_storage = LcpStorage::kAuto;
  /// Also decide, by a linear program over the contact forces, whether a
  /// static equilibrium exists (StabilityResult::static_equilibrium,
  /// weakly_stable). One LP per component; off along motion paths.
  bool check_equilibrium = false;
  /// With a drive, in 3-D with friction: first look for a solution of a
  /// component's LCP that keeps every judged part at rest and the driven ones
  /// on their prescribed motion (mechanics/rest_solution.h, a linear
  /// program), and use Lemke's method only when there is none (or the
  /// component carries a part, whose motion is not known beforehand). In 3-D
  /// the frictional LCP of stacked blocks has whole families of solutions, of
  /// which Lemke's method picks one by its pivoting rules (and on large
  /// components fails); this asks whether the parts can stay put (weak
  /// stability). Off: Lemke's method only, as in 2-D.
  bool rest_first = true;
  /// Static checks: the rule where rigid bodies leave the answer open
  /// (stability/solve_component.h).
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  /// Forces on parts besides gravity (the load margin's verdict).
  std::vector<PartLoad> loads;
  /// Static checks: decide `stability` as far as the search's budget allows
  /// (SolveContext::prove_strong); off, only the verdict is sought.
  bool prove_strong = true;
  /// Static checks with prove_strong off: a cheaper verdict that may say a
  /// component falls where the full one says it stands, never the reverse
  /// (SolveContext::conservative). For searches that confirm their answer
  /// with the full verdict (cairn sequence's beam).
  bool conservative = false;
};

/// The contact LCP of every contact-graph component of `config`: the first
/// stages of AnalyzeConfiguration (DetectContacts → SplitComponents →
/// BuildContactLcp), for benchmarks and diagnostics. With `drive`, the LCPs
/// are those AnalyzeConfiguration solves with that drive (same formulation).
std::vector<ContactLcp> BuildComponentLcps(const Assembly& assembly, const Configuration& config,
                                           const StabilityOptions& options = {},
                                           const DriveInputs* drive = nullptr);

/// Decides whether the movable parts of `config` stay put under gravity.
/// With `drive`, gripped parts move with their gripper and the Stewart–Trinkle
/// step is always used (velocity level: a part pushed by a moving one moves
/// even without friction). `workspace` (optional) carries warm starts.
StabilityResult AnalyzeConfiguration(const Assembly& assembly, const Configuration& config,
                                     const StabilityOptions& options = {},
                                     const DriveInputs* drive = nullptr,
                                     StabilityWorkspace* workspace = nullptr);

}  // namespace cairn

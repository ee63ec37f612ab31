#pragma once
/// @file
/// The stability of one configuration: does every movable part stay put?
///
/// AnalyzeConfiguration is the driver; it reads as the pipeline:
///   DetectContacts → SplitComponents → BuildContactLcp → SolveLemke →
///   RecoverSolution → ClassifyMotion.
/// Movable parts that share no contact are solved apart (contact-graph
/// components), so a large scene costs the sum of its pieces.
///
/// The verdict is about body motion, not only contact normals: a frictionless
/// block on a slope keeps every normal acceleration at zero and still slides.
/// A part moves when some point of it accelerates (Baraff) or moves within one
/// step (Stewart–Trinkle) faster than the scene's tolerance
/// (Tolerances::acceleration, Tolerances::velocity).

#include <optional>
#include <string>
#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/core/tolerances.h"
#include "cairn/geometry/assembly.h"
#include "cairn/lcp/lemke.h"
#include "cairn/mechanics/contact_model.h"

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

/// The motion of one movable part.
struct PartMotion {
  int part = -1;
  int component = -1;  ///< index into StabilityResult::components
  bool moving = false;
  MotionKind kind = MotionKind::kAtRest;
  Vector2 linear{
      0, 0};  ///< centroid acceleration (length/s², Baraff) or velocity after Δt (length/s, S–T)
  double angular = 0;  ///< angular acceleration (rad/s²) or velocity (rad/s), counter-clockwise
  std::optional<Vector2>
      pivot;                ///< for kTips: the point of zero acceleration/velocity (world frame)
  double point_motion = 0;  ///< largest |acceleration| or |velocity| over the part's vertices
};

/// One contact with its force and motion.
struct ContactReport {
  Contact contact;
  int component = -1;
  double normal_force = 0;    ///< force units, ≥ 0, on a along n_W
  double friction_force = 0;  ///< force units, on a along t_W
  double normal_motion =
      0;  ///< relative normal acceleration (Baraff) or velocity (S–T); > 0 separates
  double tangent_motion = 0;  ///< relative tangential acceleration or velocity along t_W
  bool breaking = false;      ///< normal_motion above the tolerance: the contact opens
  bool sliding = false;       ///< |tangent_motion| above the tolerance while closed
};

/// One contact-graph component and its solve.
struct ComponentReport {
  std::vector<int> parts;  ///< movable parts (indices into Assembly::parts())
  int num_contacts = 0;
  int lcp_size = 0;
  LcpStatus status = LcpStatus::kTrivial;
  int pivots = 0;
  double residual = 0;              ///< natural-map residual of the LCP solution
  double consistency_residual = 0;  ///< LCP w against the recovered body motions
  bool warm_start_used = false;
  std::string message;  ///< diagnostics when the solve failed
};

/// The overall answer.
enum class Verdict {
  kStable,         ///< no movable part moves
  kUnstable,       ///< some movable part moves
  kSolverFailure,  ///< a component's LCP could not be solved reliably (see diagnostics)
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
  std::vector<int> moving;  ///< indices of the parts that move
  StageProfile profile;
  std::string diagnostics;  ///< what went wrong numerically, if anything
};

/// Options of AnalyzeConfiguration.
struct StabilityOptions {
  double dt = 1.0;  ///< Stewart–Trinkle step (s); the verdict does not depend on it from rest
  std::optional<Formulation> formulation;  ///< default: Baraff when the scene is frictionless
  std::optional<Tolerances> tolerances;    ///< default: Assembly::MakeTolerances(dt)
  LemkeParameters lemke;
};

/// The contact LCP of every contact-graph component of `config`: the first
/// stages of AnalyzeConfiguration (DetectContacts → SplitComponents →
/// BuildContactLcp), for benchmarks and diagnostics.
std::vector<ContactLcp> BuildComponentLcps(const Assembly& assembly, const Configuration& config,
                                           const StabilityOptions& options = {});

/// Decides whether the movable parts of `config` stay put under gravity.
StabilityResult AnalyzeConfiguration(const Assembly& assembly, const Configuration& config,
                                     const StabilityOptions& options = {});

}  // namespace cairn

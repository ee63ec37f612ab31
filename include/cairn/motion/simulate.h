#pragma once
/// @file
/// Disassembly and assembly along motion paths: the paper's Algorithm 1.
///
/// For each plan step, the gripped parts travel their path in ticks of length
/// speed · dt; the last tick ends exactly at the end of the path. At every tick
/// (the start included) all contacts are recomputed from the current poses (a
/// moving part breaks old contacts and makes new ones as it slides across
/// others) and one Stewart–Trinkle step is solved for the contact impulses and
/// the velocity of every free part, each part starting from its velocity of the
/// previous tick (the paper's eq. 5). The velocity level is used with and
/// without friction: it sees a part pushed by a moving one, which an
/// acceleration-level LCP at rest cannot.
///
/// Roles: the gripped parts follow the path (support "full": rigidly, carrying
/// their weight; "none": only along the path, every other freedom free); the
/// other parts of `remove` are carried (free, pushed along, not judged); tools
/// move rigidly with the gripper; every other present movable part must stay
/// put.
///
/// Outcome of a tick, in order of precedence:
/// - `infeasible`: the gripped parts run into something that cannot give way:
///   a gripped part penetrates a fixed part (or one held after an earlier
///   failure) beyond the tolerance, or the contact LCP finds no forces that
///   let the prescribed motion happen (`jammed`: e.g. a free part pinned
///   between the gripped part and a fixed one);
/// - `unstable`: a part that should stay put moves: by itself (it falls, tips
///   or slides), or pushed by the moving parts (MotionFailure::pushed). A
///   push is seen from the first instant: tick 0 judges the node at rest,
///   then solves again with the gripper moving, and every judged part that
///   this driven motion pushes (a closed, loaded contact whose point the
///   gripper's velocity drives into the part, directly or through carried or
///   other pushed parts) fails the step at t = its start (paper Fig. 1 with
///   B lifted before C: C and D ride up on B). Parts that start to move for
///   another reason (a support or counterweight leaves, a guided part's
///   weight tips them) and a jam of that solve are judged at the next tick,
///   as before. At later ticks the pushed ones among the moving parts are
///   named the same way. A free part that
///   a gripped part reaches later along its path is pushed from the moment
///   they touch (found by bisection between ticks): the time reported, with
///   the pusher's velocity as its motion;
/// - `unsupported`: with support "none", a gripped part would fall or tip off
///   its path;
/// - `stable`.
/// A step's outcome is its first failing tick's, a plan's its first failing
/// step's. With `continue_after_failure`, the simulation goes on as if each
/// failure had been prevented (parts that should stay put, pushed ones
/// included, are held in place), so every step gets a verdict.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/plan.h"
#include "cairn/stability/analyze.h"

namespace cairn {

/// The outcome of a tick, a step or a plan.
enum class MotionVerdict { kStable, kUnstable, kUnsupported, kInfeasible };

/// "stable", "unstable", "unsupported", "infeasible".
const char* to_string(MotionVerdict v);

/// Where and why a step failed.
struct MotionFailure {
  MotionVerdict verdict = MotionVerdict::kStable;
  int step = -1;  ///< index into Plan::steps (file order)
  int tick = -1;  ///< tick within the step (0 = its start)
  /// Assembling: at the step's end, when its parts were let go where they
  /// arrived (`tick` is the last).
  bool released = false;
  double time = 0;         ///< s, from the start of the plan
  std::vector<int> parts;  ///< unstable: the parts that move; unsupported: the gripped parts;
                           ///< infeasible: the moving part, then the part it runs into (if any)
  /// unstable: those of `parts` that move because the moving parts push them
  /// (not by themselves); `time` is when the push starts. Empty: none.
  std::vector<int> pushed;
  std::vector<int> pushers;             ///< with `pushed`: the driven parts that push them
  std::vector<PartMotion> motions;      ///< how the parts in `parts` move
  std::vector<ContactReport> contacts;  ///< contacts that break or slide at the failure
  /// Unstable because the contact LCP could not be solved (never taken for
  /// stability): the solver's diagnostics. Empty otherwise. The failure in
  /// words is the report's (DescribeFailure in cairn/report/words.h).
  std::string solver_note;
};

/// One step of the plan, as simulated.
struct MotionStepReport {
  int step = -1;  ///< index into Plan::steps
  MotionVerdict verdict = MotionVerdict::kStable;
  int ticks = 0;                        ///< configurations analysed (the start included)
  double start_time = 0, end_time = 0;  ///< s
  int pivots = 0;                       ///< LCP pivots over all ticks
  int warm_starts = 0;                  ///< component solves answered by the previous tick's basis
  std::optional<MotionFailure> failure;
};

/// One row of the timeline: one contact at one tick.
struct TimelineRow {
  double time = 0;  ///< s
  int step = -1;
  int tick = 0;
  ContactReport contact;
};

/// Everything a simulation found.
struct SimulationResult {
  MotionVerdict verdict = MotionVerdict::kStable;
  bool stable() const { return verdict == MotionVerdict::kStable; }
  std::vector<MotionStepReport> steps;   ///< in the order simulated
  std::optional<MotionFailure> failure;  ///< the first failure
  std::vector<TimelineRow> timeline;     ///< when asked for
  std::string diagnostics;               ///< solver trouble, if any
  /// Every configuration checked from rest (each step's tick 0) is proved
  /// strongly stable: no component left "weak" or "not certified"
  /// (`--require strong`).
  bool rest_strong = true;
};

/// One analysis SimulatePlan is about to make (for benchmarks that replay a
/// path, and diagnostics): its inputs, exactly as AnalyzeConfiguration gets
/// them. Valid only during the call.
struct AnalysisInputs {
  int step = -1;    ///< index into Plan::steps
  int tick = 0;     ///< tick within the step
  double time = 0;  ///< s, from the start of the plan
  /// false: tick 0's second solve (gripper moving): it judges the pushes of
  /// the first instant and moves the carried parts; its pivots are not
  /// counted in MotionStepReport::pivots.
  bool judged = true;
  const Configuration* config = nullptr;
  const DriveInputs* drive = nullptr;
  const StabilityOptions* options = nullptr;
};

/// Options of SimulatePlan.
struct SimulationOptions {
  bool continue_after_failure = false;
  bool record_timeline = false;
  /// With support "none": when a guided part would fall or tip off its path,
  /// the gripper takes its weight (support "full") for the rest of the step
  /// instead of the step failing as `unsupported` ("the weight of the moving
  /// part is not supported by the gripper unless the part itself becomes
  /// unstable", paper Section V-A). The planner's paths use it.
  bool carry_when_unsupported = false;
  /// Parts (indices) taken away before the plan starts: the plan runs on that
  /// subassembly (a node of the planner's AND/OR graph). Default: none.
  std::vector<int> absent;
  LemkeParameters lemke;
  /// The static checks' rule where rigid bodies leave the answer open
  /// (stability/solve_component.h).
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  /// Called before every AnalyzeConfiguration, in order (may be empty).
  std::function<void(const AnalysisInputs&)> on_analysis;
};

/// Runs `plan` on `assembly` (disassembly, or assembly when plan.mode says so).
SimulationResult SimulatePlan(const Assembly& assembly, const Plan& plan,
                              const SimulationOptions& options = {});

}  // namespace cairn

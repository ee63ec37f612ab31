#pragma once
/// @file
/// A disassembly (or assembly) plan: a sequence of removals, each with the
/// path its gripped parts follow (docs/plan-format.md; a public contract);
/// and the candidate paths the planner tries (`cairn plan --paths`). Data
/// about the model's parts and their motions, validated against the
/// Assembly, which the readers (io) build and the algorithms (motion,
/// planning) use: it lives with the Assembly, below both.

#include <string>
#include <vector>

#include "cairn/core/types.h"
#include "cairn/geometry/assembly.h"

namespace cairn {

/// How the gripper holds the gripped parts.
enum class SupportMode {
  kFull,  ///< rigidly, carrying their weight (the paper's default): they act on the rest only
          ///< through contacts
  kNone,  ///< only along the path: their motion along it is prescribed, every other freedom is free
};

/// "full", "none".
const char* to_string(SupportMode mode);

/// Which way the plan reads.
enum class PlanMode {
  kDisassemble,  ///< steps in order, each taking its parts out along its path
  kAssemble,     ///< steps in reverse order, each bringing its parts in along its path backwards
};

/// "disassemble", "assemble".
const char* to_string(PlanMode mode);

/// One step as the user writes it (`steps[i]`).
struct PlanStepDef {
  std::vector<std::string> remove;  ///< parts leaving the assembly in this step
  std::vector<std::string> grip;    ///< parts the gripper holds; empty: all of `remove`
  std::vector<Vector3> path;        ///< displacements from the start pose; `path` form (2-D: z = 0)
  bool has_path = false;            ///< the step used `path`
  Vector3 direction{0, 0, 0};       ///< `direction` + `distance` form
  double distance = 0;
  bool has_direction = false;  ///< the step used `direction` and `distance`
  SupportMode support = SupportMode::kFull;
  /// Parts held in place (all freedoms fixed, pulling as well as pushing, as
  /// a robot or a crane holds a block) while this step's parts move.
  std::vector<std::string> hold;
  /// Parts held while this step's parts rest in their assembled pose, let
  /// go: before they leave (disassembling), after they arrive (assembling).
  /// Absent (has_hold_at_rest false): `hold`.
  std::vector<std::string> hold_at_rest;
  bool has_hold_at_rest = false;
  /// Props (fixels from the ground: a scene's `fixtures`, docs/scene-format.md)
  /// in place while this step's parts move, and while they rest in place
  /// (absent, has_props_at_rest false: `props`).
  std::vector<FixtureDef> props;
  std::vector<FixtureDef> props_at_rest;
  bool has_props_at_rest = false;
};

/// A whole plan as the user writes it. Vector indices equal JSON indices.
struct PlanDef {
  PlanMode mode = PlanMode::kDisassemble;
  double dt = 1.0;     ///< seconds per time step
  double speed = 1.0;  ///< length per second along the path
  std::vector<PlanStepDef> steps;
};

/// One validated step.
struct PlanStep {
  std::vector<int> remove;    ///< part indices, in the order given
  std::vector<int> grip;      ///< part indices (tools included); never empty
  std::vector<Vector3> path;  ///< piecewise-linear displacements, path[0] = 0, ≥ 2 points
  SupportMode support = SupportMode::kFull;
  std::vector<int> hold;                  ///< held while the step's parts move (part indices)
  std::vector<int> hold_at_rest;          ///< held while they rest in place, let go
  std::vector<FixtureDef> props;          ///< props while the step's parts move (validated)
  std::vector<FixtureDef> props_at_rest;  ///< props while they rest in place
  double Length() const;                  ///< total path length
  /// The displacement after travelling arc length s along the path (clamped).
  Vector3 At(double s) const;
};

/// A validated plan, tied to the Assembly it was checked against.
struct Plan {
  PlanMode mode = PlanMode::kDisassemble;
  double dt = 1.0;
  double speed = 1.0;
  std::vector<PlanStep> steps;

  /// Validates `def` against `assembly`. @throws InputError naming `file`, the
  /// JSON path and the fault: unknown parts, a part removed twice, a fixed part
  /// removed, a `grip` part outside `remove` that is not a tool, a tool in
  /// `remove`, an empty path or zero-length path, both or neither path forms,
  /// a zero direction, a negative distance, dt or speed ≤ 0, non-finite numbers.
  /// Also refused (docs/plan-format.md, "Validated ranges"): dt above
  /// kMaxDt, a speed outside kMinSpeed..kMaxSpeed scene sizes per second,
  /// path points beyond limits::kMaxCoordinate, and a step of more than
  /// `max_ticks` time steps (its path length over speed · dt).
  static Plan Create(const PlanDef& def, const Assembly& assembly, const std::string& file = "",
                     long long max_ticks = kDefaultMaxTicks);

  /// The time steps of one step a plan may take unless the caller allows more
  /// (`cairn simulate --max-ticks`): a path of a million steps takes minutes.
  static constexpr long long kDefaultMaxTicks = 1'000'000;
  /// The longest time step (s).
  static constexpr double kMaxDt = 1e6;
  /// The gripper's speed in scene sizes per second: slower, a step moves
  /// less than roundoff; faster, the velocities leave the LCP's range.
  static constexpr double kMinSpeed = 1e-12, kMaxSpeed = 1e12;
};

/// A candidate path for a part or subassembly.
struct CandidatePath {
  std::vector<Vector3> path;  ///< displacements from the assembled pose, path[0] = 0, ≥ 2 points
  SupportMode support = SupportMode::kFull;
  std::vector<int> grip;  ///< extra gripped parts besides the removed ones (tools), may be empty
  std::string label;      ///< for people: "up", "(−1, 0)", "given path 2 of C"
  bool straight = false;  ///< a straight removal along an NDBG cell direction
  Vector3 direction{0, 0, 0};  ///< straight: the unit direction
};

}  // namespace cairn

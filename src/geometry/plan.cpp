#include "cairn/geometry/plan.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/core/tolerances.h"

namespace cairn {
namespace {

std::string Indexed(const std::string& path, size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

// A point as the user wrote it: (x, y) in 2-D, (x, y, z) in 3-D.
std::string Point(const Vector3& p, int dimension) {
  return "(" + FormatNumber(p.x()) + ", " + FormatNumber(p.y()) +
         (dimension == 3 ? ", " + FormatNumber(p.z()) : "") + ")";
}

// Throws the InputError of one fault of a plan; all validation goes through it.
class PlanValidator {
 public:
  PlanValidator(const std::string& file, const Assembly& assembly)
      : file_(file), assembly_(assembly) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& message) const {
    throw InputError(file_, path, message);
  }
  void Positive(double x, const std::string& path) const {
    if (!std::isfinite(x)) Fail(path, "must be a finite number (got " + FormatNumber(x) + ")");
    if (x <= 0) Fail(path, "must be positive (got " + FormatNumber(x) + ")");
  }
  void FinitePoint(const Vector3& v, const std::string& path) const {
    if (!v.allFinite()) {
      Fail(path, "must have finite coordinates (got " + Point(v, assembly_.dimension()) + ")");
    }
  }
  // The index of the part `name`, which must exist and not be fixed.
  int MovablePart(const std::string& name, const std::string& path) const {
    const int i = assembly_.FindPart(name);
    if (i < 0) Fail(path, "no part named '" + EscapedName(name) + "'");
    if (assembly_.part(i).fixed)
      Fail(path, "part '" + EscapedName(name) + "' is fixed: fixed parts never move");
    return i;
  }

 private:
  const std::string& file_;
  const Assembly& assembly_;
};

// The step's path as given: the polyline, or the straight segment of
// `direction` and `distance`.
std::vector<Vector3> RawPath(const PlanStepDef& def, const std::string& path,
                             const PlanValidator& check) {
  if (def.has_path && def.has_direction) {
    check.Fail(path, "has both path and direction with distance: give one of them");
  }
  if (!def.has_path && !def.has_direction) {
    check.Fail(path, "has no path: give path, or direction and distance");
  }
  if (def.has_path) {
    const std::string path_path = path + ".path";
    if (def.path.empty()) check.Fail(path_path, "must have at least one point");
    for (size_t k = 0; k < def.path.size(); ++k) {
      check.FinitePoint(def.path[k], Indexed(path_path, k));
    }
    return def.path;
  }
  check.FinitePoint(def.direction, path + ".direction");
  // Scaled by its largest entry first: the norm of [1e308, 0] overflows.
  const double largest = def.direction.cwiseAbs().maxCoeff();
  if (largest == 0) check.Fail(path + ".direction", "must not be zero");
  const Vector3 unit = (def.direction / largest).normalized();
  check.Positive(def.distance, path + ".distance");
  return {Vector3(0, 0, 0), def.distance * unit};
}

}  // namespace

const char* to_string(SupportMode mode) {
  switch (mode) {
    case SupportMode::kFull:
      return "full";
    case SupportMode::kNone:
      return "none";
  }
  return "unknown";
}

const char* to_string(PlanMode mode) {
  switch (mode) {
    case PlanMode::kDisassemble:
      return "disassemble";
    case PlanMode::kAssemble:
      return "assemble";
  }
  return "unknown";
}

double PlanStep::Length() const {
  double length = 0;
  for (size_t k = 1; k < path.size(); ++k) length += (path[k] - path[k - 1]).norm();
  return length;
}

Vector3 PlanStep::At(double s) const {
  if (path.empty()) return Vector3(0, 0, 0);
  // Walk the segments until the one holding arc length s; before the start
  // (or NaN) is the start, past the end is the end.
  if (!(s > 0)) return path.front();
  double remaining = s;
  for (size_t k = 1; k < path.size(); ++k) {
    const Vector3 segment = path[k] - path[k - 1];
    const double length = segment.norm();
    if (remaining <= length) return path[k - 1] + (remaining / length) * segment;
    remaining -= length;
  }
  return path.back();
}

namespace {

// Where each part was removed: its step and the JSON path of its entry.
using RemovedAt = std::unordered_map<int, std::pair<size_t, std::string>>;

// The parts leaving in step i: movable, no tools, each once in the whole plan.
std::vector<int> RemovedParts(const PlanStepDef& sd, size_t i, const std::string& bare,
                              const Assembly& assembly, const PlanValidator& check,
                              RemovedAt& removed_at) {
  std::vector<int> remove;
  const std::string remove_path = bare + ".remove";
  if (sd.remove.empty()) check.Fail(remove_path, "must name at least one part");
  for (size_t k = 0; k < sd.remove.size(); ++k) {
    const std::string entry = Indexed(remove_path, k);
    const int part = check.MovablePart(sd.remove[k], entry);
    if (assembly.part(part).tool) {
      check.Fail(entry, "part '" + EscapedName(sd.remove[k]) +
                            "' is a tool, not part of the assembly: grip it, do not remove it");
    }
    const auto [it, inserted] = removed_at.emplace(part, std::make_pair(i, entry));
    if (!inserted) {
      const auto& [step_index, earlier] = it->second;
      check.Fail(entry,
                 step_index == i
                     ? "names part '" + EscapedName(sd.remove[k]) + "' twice (also " + earlier + ")"
                     : "part '" + EscapedName(sd.remove[k]) + "' is already removed by " + earlier);
    }
    remove.push_back(part);
  }
  return remove;
}

// The gripped parts: by default all of remove; beyond remove, only tools.
std::vector<int> GrippedParts(const PlanStepDef& sd, const std::vector<int>& remove,
                              const std::string& bare, const std::string& path,
                              const Assembly& assembly, const PlanValidator& check) {
  if (sd.grip.empty()) return remove;
  std::vector<int> grip;
  const std::string grip_path = path + ".grip";
  for (size_t k = 0; k < sd.grip.size(); ++k) {
    const std::string entry = Indexed(grip_path, k);
    const int part = check.MovablePart(sd.grip[k], entry);
    const auto earlier = std::find(grip.begin(), grip.end(), part);
    if (earlier != grip.end()) {
      check.Fail(entry, "names part '" + EscapedName(sd.grip[k]) + "' twice (also " +
                            Indexed(bare + ".grip", earlier - grip.begin()) + ")");
    }
    const bool removed = std::find(remove.begin(), remove.end(), part) != remove.end();
    if (!removed && !assembly.part(part).tool) {
      check.Fail(entry, "part '" + EscapedName(sd.grip[k]) +
                            "' is neither in this step's remove nor a tool (\"tool\": true in "
                            "the scene)");
    }
    grip.push_back(part);
  }
  return grip;
}

// Held parts (`key` "hold" or "hold_at_rest"): movable parts of the
// assembly, each once, present at step i (not removed by an earlier step;
// of this step's own parts only at rest: the gripper keeps them).
std::vector<int> HeldParts(const std::vector<std::string>& names, const char* key,
                           const std::vector<int>& remove, size_t i, const std::string& path,
                           const Assembly& assembly, const PlanValidator& check,
                           const RemovedAt& removed_at) {
  std::vector<int> held;
  const std::string list = path + "." + key;
  const bool at_rest = std::string(key) == "hold_at_rest";
  for (size_t k = 0; k < names.size(); ++k) {
    const std::string entry = Indexed(list, k);
    const int part = check.MovablePart(names[k], entry);
    const std::string quoted = "part '" + EscapedName(names[k]) + "'";
    if (assembly.part(part).tool)
      check.Fail(entry,
                 quoted + " is a tool, not part of the assembly: it cannot be held in place");
    if (std::find(held.begin(), held.end(), part) != held.end())
      check.Fail(entry, "names " + quoted + " twice");
    const auto it = removed_at.find(part);
    if (it != removed_at.end() && it->second.first < i)
      check.Fail(entry, quoted + " is not there to hold: it is removed by " + it->second.second);
    if (!at_rest && std::find(remove.begin(), remove.end(), part) != remove.end())
      check.Fail(entry, quoted +
                            " moves in this step: it cannot be held in place while it moves "
                            "(hold_at_rest keeps it in the gripper at rest)");
    held.push_back(part);
  }
  return held;
}

// Props (`key` "props" or "props_at_rest"): fixels the scene would accept
// (Assembly::FixtureFault), under movable parts present at step i (as
// HeldParts), not under a part moving in this step but at rest.
std::vector<FixtureDef> StepProps(const std::vector<FixtureDef>& props, const char* key,
                                  const std::vector<int>& remove, size_t i, const std::string& path,
                                  const Assembly& assembly, const PlanValidator& check,
                                  const RemovedAt& removed_at) {
  const std::string list = path + "." + key;
  for (size_t k = 0; k < props.size(); ++k) {
    const std::string entry = Indexed(list, k);
    const int part = check.MovablePart(props[k].part, entry + ".part");
    const std::string quoted = "part '" + EscapedName(props[k].part) + "'";
    if (assembly.part(part).tool)
      check.Fail(entry + ".part",
                 quoted + " is a tool, not part of the assembly: it cannot be propped");
    const auto it = removed_at.find(part);
    if (it != removed_at.end() && it->second.first < i)
      check.Fail(entry + ".part",
                 quoted + " is not there to prop: it is removed by " + it->second.second);
    if (std::string(key) == "props" &&
        std::find(remove.begin(), remove.end(), part) != remove.end())
      check.Fail(entry + ".part", quoted +
                                      " moves in this step: it cannot be propped while it "
                                      "moves (props_at_rest props it at rest)");
    if (const auto fault = assembly.FixtureFault(props[k])) check.Fail(entry, *fault);
  }
  return props;
}

// The path: from the origin, without repeated points, of nonzero length.
std::vector<Vector3> StepPath(const PlanStepDef& sd, const std::string& path,
                              const Assembly& assembly, const PlanValidator& check) {
  std::vector<Vector3> out;
  const std::vector<Vector3> raw = RawPath(sd, path, check);
  for (size_t k = 0; k < raw.size(); ++k)
    if (raw[k].cwiseAbs().maxCoeff() > limits::kMaxCoordinate)
      check.Fail(sd.has_path ? Indexed(path + ".path", k) : path + ".distance",
                 "goes out of range (a displacement of " +
                     FormatNumber(raw[k].cwiseAbs().maxCoeff()) + "; |x| ≤ " +
                     FormatNumber(limits::kMaxCoordinate) + " length units)");
  if (raw.front() != Vector3(0, 0, 0)) out.push_back(Vector3(0, 0, 0));
  for (const Vector3& p : raw) {
    if (out.empty() || p != out.back()) out.push_back(p);
  }
  if (out.size() < 2) {
    check.Fail(path + ".path", assembly.is_3d()
                                   ? "has zero length: every point is the start (0, 0, 0)"
                                   : "has zero length: every point is the start (0, 0)");
  }
  return out;
}

// The step's time steps, its path length over speed · dt, at most
// `max_ticks` (a step of 2³¹ would overflow the tick counter; long before
// that it runs for hours without a word).
void StepTicks(const PlanStep& step, const Plan& plan, long long max_ticks, const std::string& path,
               const PlanValidator& check) {
  const double ticks = std::ceil(step.Length() / (plan.speed * plan.dt));
  if (ticks <= static_cast<double>(max_ticks)) return;
  check.Fail(path, "takes " + FormatNumber(ticks) + " time steps (path length " +
                       FormatNumber(step.Length()) + " at speed " + FormatNumber(plan.speed) +
                       " and dt " + FormatNumber(plan.dt) + "), more than " +
                       std::to_string(max_ticks) +
                       ": give a larger dt or speed, or allow more with --max-ticks");
}

}  // namespace

Plan Plan::Create(const PlanDef& def, const Assembly& assembly, const std::string& file,
                  long long max_ticks) {
  const PlanValidator check(file, assembly);
  Plan plan;
  plan.mode = def.mode;
  check.Positive(def.dt, "dt");
  check.Positive(def.speed, "speed");
  if (def.dt > kMaxDt)
    check.Fail("dt", "is out of range (got " + FormatNumber(def.dt) + " s; at most " +
                         FormatNumber(kMaxDt) + " s)");
  const double size = std::max(assembly.scene_size(), std::numeric_limits<double>::min());
  if (def.speed < kMinSpeed * size || def.speed > kMaxSpeed * size)
    check.Fail("speed", "is out of range (got " + FormatNumber(def.speed) + "; between " +
                            FormatNumber(kMinSpeed) + " and " + FormatNumber(kMaxSpeed) +
                            " times the scene's size " + FormatNumber(size) + " per second)");
  plan.dt = def.dt;
  plan.speed = def.speed;
  if (def.steps.empty()) check.Fail("steps", "must list at least one step");
  RemovedAt removed_at;
  for (size_t i = 0; i < def.steps.size(); ++i) {
    const PlanStepDef& sd = def.steps[i];
    // Faults of `remove` are reported at `steps[i].remove`; every other at
    // the step's path named by the parts it removes: `steps[i] ("B")`.
    const std::string bare = Indexed("steps", i);
    const std::string path = NamedPath(bare, sd.remove);
    PlanStep step;
    step.remove = RemovedParts(sd, i, bare, assembly, check, removed_at);
    step.grip = GrippedParts(sd, step.remove, bare, path, assembly, check);
    step.path = StepPath(sd, path, assembly, check);
    StepTicks(step, plan, max_ticks, path, check);
    step.support = sd.support;
    step.hold = HeldParts(sd.hold, "hold", step.remove, i, path, assembly, check, removed_at);
    step.hold_at_rest = sd.has_hold_at_rest
                            ? HeldParts(sd.hold_at_rest, "hold_at_rest", step.remove, i, path,
                                        assembly, check, removed_at)
                            : step.hold;
    step.props = StepProps(sd.props, "props", step.remove, i, path, assembly, check, removed_at);
    step.props_at_rest = sd.has_props_at_rest
                             ? StepProps(sd.props_at_rest, "props_at_rest", step.remove, i, path,
                                         assembly, check, removed_at)
                             : step.props;
    plan.steps.push_back(std::move(step));
  }
  return plan;
}

}  // namespace cairn

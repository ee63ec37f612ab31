#include "cairn/io/plan_reader.h"

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/json_checks.h"

namespace cairn {
namespace {

using io_internal::Child;
using io_internal::Index;
using nlohmann::json;

// The keys of each level of plan format version 1.
constexpr std::initializer_list<const char*> kPlanKeys = {"cairn_plan", "mode", "dt", "speed",
                                                          "steps"};
constexpr std::initializer_list<const char*> kStepKeys = {
    "remove",  "grip", "path",         "direction", "distance",
    "support", "hold", "hold_at_rest", "props",     "props_at_rest"};

// Converts a parsed document to a PlanDef, checking structure and types on
// the way; the first fault throws an InputError with its JSON path. Values
// (positive dt, known part names, path forms) are Plan::Create's to check.
class PlanParser : private io_internal::JsonChecker {
 public:
  PlanParser(const std::string& file, int dimension) : JsonChecker(file), dim_(dimension) {}

  PlanDef Parse(const json& doc) const {
    if (!doc.is_object()) Fail("", "a plan must be a JSON object, not " + Article(doc));
    CheckVersion(doc, "cairn_plan", "plan");
    CheckKeys(doc, "", kPlanKeys);

    PlanDef def;
    if (doc.contains("mode")) {
      const std::string mode = String(doc["mode"], "mode");
      if (mode == "disassemble") {
        def.mode = PlanMode::kDisassemble;
      } else if (mode == "assemble") {
        def.mode = PlanMode::kAssemble;
      } else {
        Fail("mode", "must be \"disassemble\" or \"assemble\", not \"" + mode + "\"");
      }
    }
    if (doc.contains("dt")) def.dt = Number(doc["dt"], "dt");
    if (doc.contains("speed")) def.speed = Number(doc["speed"], "speed");
    const json& steps = Array(Require(doc, "steps", ""), "steps");
    if (steps.empty()) Fail("steps", "must list at least one step");
    for (size_t i = 0; i < steps.size(); ++i) {
      def.steps.push_back(ParseStep(steps[i], Index("steps", i)));
    }
    return def;
  }

 private:
  // The names a step's `remove` lists, when it is an array of strings: the
  // step is named by them (`steps[0] ("B")`). Empty otherwise.
  static std::vector<std::string> RemovedNames(const json& step) {
    std::vector<std::string> names;
    if (!step.contains("remove") || !step["remove"].is_array()) return names;
    for (const json& name : step["remove"]) {
      if (!name.is_string()) return {};
      names.push_back(name.get<std::string>());
    }
    return names;
  }

  // steps[i]. Faults of `remove` are reported at `steps[i].remove`; every
  // other at the step's path named by the parts it removes (NamedPath).
  PlanStepDef ParseStep(const json& j, const std::string& bare) const {
    Object(j, bare);
    const std::string path = NamedPath(bare, RemovedNames(j));
    CheckKeys(j, path, kStepKeys);
    PlanStepDef step;
    step.remove = Strings(Require(j, "remove", bare), Child(bare, "remove"));
    if (j.contains("grip")) {
      // An empty PlanStepDef::grip means "all of remove"; an empty array in
      // the file is a mistake, not that default.
      step.grip = Strings(j["grip"], Child(path, "grip"));
      if (step.grip.empty()) {
        Fail(Child(path, "grip"),
             "must name at least one part (leave it out to grip all of remove)");
      }
    }

    // The path: a polyline, or a direction and a distance (Plan::Create
    // rejects both and neither).
    if (j.contains("path")) {
      const std::string path_path = Child(path, "path");
      const json& points = Array(j["path"], path_path);
      step.has_path = true;
      for (size_t k = 0; k < points.size(); ++k) {
        step.path.push_back(VecN(points[k], Index(path_path, k), dim_));
      }
    }
    if (j.contains("direction") || j.contains("distance")) {
      step.has_direction = true;
      const char* missing = j.contains("direction") ? "distance" : "direction";
      if (!j.contains(missing)) {
        Fail(Child(path, missing),
             "required key is missing (a straight path needs both direction and distance)");
      }
      step.direction = VecN(j["direction"], Child(path, "direction"), dim_);
      step.distance = Number(j["distance"], Child(path, "distance"));
    }

    if (j.contains("support")) {
      const std::string support = String(j["support"], Child(path, "support"));
      if (support == "full") {
        step.support = SupportMode::kFull;
      } else if (support == "none") {
        step.support = SupportMode::kNone;
      } else {
        Fail(Child(path, "support"), "must be \"full\" or \"none\", not \"" + support + "\"");
      }
    }
    // Held parts (an empty list is allowed: hold_at_rest [] lets go of all).
    if (j.contains("hold")) step.hold = Strings(j["hold"], Child(path, "hold"));
    if (j.contains("hold_at_rest")) {
      step.hold_at_rest = Strings(j["hold_at_rest"], Child(path, "hold_at_rest"));
      step.has_hold_at_rest = true;
    }
    if (j.contains("props")) step.props = Props(j["props"], Child(path, "props"));
    if (j.contains("props_at_rest")) {
      step.props_at_rest = Props(j["props_at_rest"], Child(path, "props_at_rest"));
      step.has_props_at_rest = true;
    }
    return step;
  }

  // A list of props: fixels {"part", "point", "normal"}.
  std::vector<FixtureDef> Props(const json& j, const std::string& path) const {
    std::vector<FixtureDef> out;
    const json& list = Array(j, path);
    for (size_t k = 0; k < list.size(); ++k) out.push_back(Fixture(list[k], Index(path, k), dim_));
    return out;
  }

  int dim_;  // the scene's dimension: path points and directions have this many numbers
};

}  // namespace

PlanDef ParsePlanJson(const nlohmann::json& doc, const std::string& file, int dimension) {
  return PlanParser(file, dimension).Parse(doc);
}

Plan ReadPlan(const std::string& path, const Assembly& assembly, long long max_ticks,
              std::uint64_t max_input_size) {
  return Plan::Create(
      ParsePlanJson(io_internal::ReadJsonFile(path, max_input_size), path, assembly.dimension()),
      assembly, path, max_ticks);
}

}  // namespace cairn

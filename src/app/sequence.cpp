#include "cairn/app/sequence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "cairn/app/blocking.h"
#include "cairn/core/error.h"
#include "cairn/geometry/plan.h"
#include "cairn/planning/sequence.h"
#include "cairn/report/html_report.h"
#include "cairn/report/plan_report.h"
#include "cairn/report/sequence_report.h"

namespace cairn::app {

namespace {

// The removal directions the query asks for (a part arrives along the
// reverse of the first that is free past the parts placed).
std::vector<Vector3> DirectionsOf(const Model& model, const SequenceQuery& query) {
  const Assembly& assembly = model.assembly;
  if (!query.direction.empty())
    return {BlockingDirection(query.direction, assembly, "--direction")};
  const Vector3& g = assembly.gravity();
  const Vector3 up = g.norm() > 0 ? Vector3(-g / g.norm())
                                  : (assembly.is_3d() ? Vector3(0, 0, 1) : Vector3(0, 1, 0));
  if (query.directions == "up") return {up};
  if (query.directions == "ndbg") return {};  // SequenceOptions::ndbg
  if (query.directions != "axes")
    throw InputError(model.file, "--directions",
                     "must be up, axes or ndbg, not " + query.directions);
  // Up first, then the other axis directions in a fixed order.
  std::vector<Vector3> out = {up};
  const int dim = assembly.dimension();
  for (int axis = 0; axis < dim; ++axis)
    for (const double sign : {1.0, -1.0}) {
      Vector3 d = Vector3::Zero();
      d[axis] = sign;
      if ((d - up).norm() > 1e-12) out.push_back(d);
    }
  return out;
}

// The order as an assembly plan (docs/plan-format.md, assemble mode): the
// file lists the parts in the order they come out, so that assembling runs
// the build order. Part p_i comes in along its arrival direction from a scene
// size away (clear of every part: a part moved by the bounding box's
// diagonal lies outside it), in two time steps (its way is free of every
// placed part: a blocking graph to infinity), held by the gripper. While it
// moves, the supports in place before it and those put in for it on other
// parts are in place (`hold`, `props`); when it is let go, the supports of
// the state after it (`hold_at_rest`, `props_at_rest`).
PlanDef SequencePlan(const Assembly& assembly, const BuildSequence& sequence) {
  PlanDef plan;
  plan.mode = PlanMode::kAssemble;
  plan.speed = assembly.scene_size();  // a scene size a second
  plan.dt = 0.5;
  const auto fill = [&](const std::vector<TemporarySupport>& supports,
                        std::vector<std::string>& hold, std::vector<FixtureDef>& props) {
    for (const TemporarySupport& t : supports) {
      const std::string& name = assembly.part(t.part).name;
      if (t.kind == TemporaryKind::kHold)
        hold.push_back(name);
      else
        props.push_back({name, t.point, t.normal});
    }
  };
  std::vector<TemporarySupport> before;  // the supports in place before the step
  for (const SequenceStep& s : sequence.steps) {
    PlanStepDef step;
    step.remove = {assembly.part(s.part).name};
    step.has_direction = true;
    step.direction = -s.direction;
    step.distance = assembly.scene_size();
    std::vector<TemporarySupport> moving = before, after = before;
    for (const TemporarySupport& t : s.added) {
      if (t.part != s.part) moving.push_back(t);
      after.push_back(t);
    }
    for (const TemporarySupport& t : s.removed)
      after.erase(std::find(after.begin(), after.end(), t));
    fill(moving, step.hold, step.props);
    fill(after, step.hold_at_rest, step.props_at_rest);
    step.has_hold_at_rest = step.has_props_at_rest = true;
    plan.steps.insert(plan.steps.begin(), std::move(step));
    before = after;
  }
  return plan;
}

}  // namespace

CommandResult SequenceDocument(const Model& model, const SequenceQuery& query,
                               const Monitor& monitor) {
  if (query.temporary != "hold" && query.temporary != "prop" && query.temporary != "both")
    throw InputError(model.file, "--temporary",
                     "must be hold, prop or both, not " + query.temporary);
  SequenceOptions options;
  options.holds = query.temporary != "prop";
  options.props = query.temporary != "hold";
  options.max_temporary = query.max_temporary;
  options.directions = DirectionsOf(model, query);
  options.ndbg = query.direction.empty() && query.directions == "ndbg";
  options.beam_width = query.beam_width;
  if (query.threads < 0)
    throw InputError(model.file, "--threads",
                     "must be 0 (every core) or more, not " + std::to_string(query.threads));
  options.threads = query.threads;
  if (!(query.time_limit >= 0) || !std::isfinite(query.time_limit))
    throw InputError(model.file, "--time-limit", "must be a finite number of seconds, at least 0");
  options.time_limit = query.time_limit;
  options.stop = query.stop;
  options.stability.rule = query.rule;
  options.stability.prove_strong = query.require_strong;
  options.require_strong = query.require_strong;
  options.checkpoint = monitor.checkpoint;
  options.record_contacts = query.page;
  options.status = monitor.status;
  const auto start = std::chrono::steady_clock::now();
  const BuildSequence sequence = FindBuildSequence(model.assembly, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ReportOptions report;
  report.scene_file = model.file;
  CommandResult out;
  out.document = SequenceToJson(model.assembly, sequence, seconds, report);
  out.exit = sequence.complete ? kExitStable : kExitUnstable;
  out.text = SequenceToText(model.assembly, sequence, report);
  if (query.page) out.page = SequencePage(model.assembly, sequence, out.document, report);
  if (query.emit_plans && !sequence.complete) {
    // A plan lists the parts it moves; the others are there from the start.
    const std::string why =
        "--emit-plans: no plan written: the order is not complete (a plan of part of it would "
        "have the parts not placed there from the start)";
    out.text += "  " + why + "\n";
    std::string message = out.document.value("message", std::string());
    out.document["message"] = message.empty() ? why : message + "; " + why;
  } else if (query.emit_plans) {
    out.plans = {
        {"sequence.assemble.plan.json",
         PlanDefToJson(SequencePlan(model.assembly, sequence), model.assembly.dimension()).dump(2) +
             "\n"}};
  }
  return out;
}

}  // namespace cairn::app

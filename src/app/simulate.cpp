#include "cairn/app/simulate.h"

#include <cmath>
#include <optional>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/io/plan_reader.h"
#include "cairn/motion/plan_margin.h"
#include "cairn/motion/simulate.h"
#include "cairn/planning/fixtures.h"
#include "cairn/report/fixture_report.h"
#include "cairn/report/html_report.h"
#include "cairn/report/margin_report.h"
#include "cairn/report/simulation_report.h"

namespace cairn::app {
namespace {

// What a plan step does with each part, as the page colours it: the gripped
// parts (tools included) move with the gripper, the rest of `remove` is
// carried, every other part is judged.
std::vector<PartRole> PlanRoles(const Assembly& assembly, const PlanStep& step) {
  std::vector<PartRole> roles(assembly.num_parts(), PartRole::kJudged);
  for (int p : step.remove) roles[p] = PartRole::kCarried;
  for (int p : step.grip) roles[p] = PartRole::kPrescribed;
  return roles;
}

int ExitOf(const SimulationResult& result) {
  switch (result.verdict) {
    case MotionVerdict::kStable:
      return kExitStable;
    case MotionVerdict::kInfeasible:
      return kExitInfeasible;
    default:
      return kExitUnstable;
  }
}

Plan ReadQueryPlan(const Assembly& assembly, const SimulateQuery& query) {
  if (!query.plan_data)
    return ReadPlan(query.plan_file, assembly, query.max_ticks, query.max_input_size);
  return Plan::Create(ParsePlanJson(*query.plan_data, query.plan_file, assembly.dimension()),
                      assembly, query.plan_file, query.max_ticks);
}

// "step 2/5, time step 40/120": the steps' lengths in time steps, at the
// plan's speed and time step.
std::string Status(const Plan& plan, const AnalysisInputs& in) {
  const PlanStep& step = plan.steps[in.step];
  const auto ticks = static_cast<long long>(std::ceil(step.Length() / (plan.speed * plan.dt)));
  return "step " + std::to_string(in.step + 1) + "/" + std::to_string(plan.steps.size()) +
         ", time step " + std::to_string(in.tick) + "/" + std::to_string(ticks);
}

}  // namespace

CommandResult SimulateDocument(const Model& model, const SimulateQuery& query,
                               const Monitor& monitor) {
  const Assembly& assembly = model.assembly;
  RefuseGivenInterfaces(assembly, model.file,
                        "parts cannot be moved along a plan (check it, with --without for "
                        "subassemblies, or let Cairn find the contacts from the shapes)");
  if (!query.margin.empty() && query.margin != "friction")
    throw InputError("", "--margin", "must be friction, not \"" + query.margin + "\"");
  const Plan plan = ReadQueryPlan(assembly, query);
  ReportOptions report;
  report.scene_file = model.file;
  report.normalize_part = ResolveNormalize(assembly, query.normalize, model.file);
  const auto on_analysis = [&](const AnalysisInputs& in) {
    monitor.Poll();
    if (monitor.status) monitor.status(Status(plan, in));
  };

  // The run. The page draws every tick: its poses and roles (recorded here)
  // and its contacts (the timeline).
  SimulationOptions options;
  options.continue_after_failure = query.continue_after_failure;
  options.rule = query.rule;
  options.record_timeline = query.timeline || query.page;
  std::vector<SimulationFrame> frames;
  options.on_analysis = [&](const AnalysisInputs& in) {
    if (query.page && in.judged)
      frames.push_back({in.step, in.tick, in.time, in.config->present, in.config->poses,
                        PlanRoles(assembly, plan.steps[in.step])});
    on_analysis(in);
  };
  const SimulationResult result = SimulatePlan(assembly, plan, options);

  // --suggest-fixtures: when the plan fails, the fewest fixels that make it
  // stable (docs/fixtures.md). The exit code stays the plan's own verdict.
  std::optional<FixtureSuggestion> suggestion;
  FixtureSearchOptions search;
  search.max_fixels = query.max_fixels;
  search.simulation.on_analysis = on_analysis;
  if (query.suggest_fixtures && !result.stable())
    suggestion = SuggestFixtures(model.def, assembly, plan, result, search);
  search.simulation.on_analysis = nullptr;

  // --margin friction: the least friction factor for which the plan is
  // stable, by bisection over simulations (motion/plan_margin.h); those runs
  // record no frames.
  std::optional<PlanMargin> margin;
  if (query.margin == "friction") {
    SimulationOptions bisection = options;
    bisection.record_timeline = false;
    bisection.on_analysis = on_analysis;
    margin = PlanFrictionMargin(model.def, plan, bisection);
  }

  // The answer: the document (null fixtures: asked for, but the plan is
  // stable without fixels), the words, the files asked for.
  CommandResult out;
  out.document = SimulationToJson(assembly, plan, result, report);
  if (query.suggest_fixtures)
    out.document["fixtures"] = suggestion
                                   ? FixtureSuggestionToJson(assembly, *suggestion, search, report)
                                   : nlohmann::json(nullptr);
  if (margin) out.document["margin"] = PlanMarginToJson(assembly, *margin);
  out.exit = ExitOf(result);
  if (out.exit == kExitStable && query.require_strong && !result.rest_strong)
    out.exit = kExitNotStrong;
  out.text = SimulationToText(assembly, plan, result, report);
  if (suggestion) out.text += FixtureSuggestionToText(assembly, *suggestion, search, report);
  if (margin) out.text += PlanMarginToText(assembly, *margin);
  if (query.timeline) out.timeline = TimelineToCsv(assembly, result, report);
  if (query.page)
    out.page = SimulationPage(assembly, result, frames, out.document,
                              margin ? PlanMarginToText(assembly, *margin) : std::string(), report);
  return out;
}

}  // namespace cairn::app

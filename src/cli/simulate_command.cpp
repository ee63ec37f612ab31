
#include "cli/simulate_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "cairn/core/error.h"
#include "cairn/io/compas_reader.h"
#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/plan_margin.h"
#include "cairn/motion/simulate.h"
#include "cairn/planning/fixtures.h"
#include "cairn/report/fixture_report.h"
#include "cairn/report/html_report.h"
#include "cairn/report/margin_report.h"
#include "cairn/report/simulation_report.h"
#include "cairn/stability/analyze.h"
#include "cli/command.h"
#include "cli/model.h"
#include "cli/output_files.h"
#include "cli/progress.h"
#include "cli/scene_writer.h"

namespace cairn::cli {

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

// The plan simulated (and, with --suggest-fixtures, the fixels found), for
// the document, the summary, the timeline and the page.
struct Simulated {
  Model model;
  Plan plan;
  ReportOptions report;
  SimulationResult result;
  FixtureSearchOptions search;
  std::optional<FixtureSuggestion> suggestion;
  std::vector<SimulationFrame> frames;  ///< with --html: every analysed tick of the plan's run
  std::optional<PlanMargin> margin;     ///< with --margin friction
  int exit() const {
    switch (result.verdict) {
      case MotionVerdict::kStable:
        return kExitStable;
      case MotionVerdict::kInfeasible:
        return kExitInfeasible;
      default:
        return kExitUnstable;
    }
  }
};

// `on_tick` is called at every time step, with the plan (the progress line,
// a deadline).
using OnTick = std::function<void(const Plan&, const AnalysisInputs&)>;
Simulated Simulate(const SimulateArgs& args, const OnTick& on_tick, std::ostream* notes = nullptr) {
  // The definition too: a fixel suggestion adds fixtures to it.
  Model model = LoadModel(args.scene, args.model, notes);
  const Assembly& assembly = model.assembly;
  RefuseGivenInterfaces(assembly, args.scene,
                        "parts cannot be moved along a plan (check it, with --without for "
                        "subassemblies, or let Cairn find the contacts from the shapes)");
  Plan plan = ReadPlan(args.plan, assembly, args.max_ticks, args.model.max_input_size);
  ReportOptions report;
  report.scene_file = args.scene;
  report.normalize_part = ResolveNormalize(assembly, args.normalize, args.scene);
  const auto on_analysis = [&](const AnalysisInputs& in) { on_tick(plan, in); };
  SimulationOptions options;
  options.continue_after_failure = args.continue_after_failure;
  // The page draws every tick: its poses and roles (recorded here) and its
  // contacts (the timeline).
  options.record_timeline = !args.timeline.empty() || !args.html.empty();
  std::vector<SimulationFrame> frames;
  options.on_analysis = [&](const AnalysisInputs& in) {
    if (!args.html.empty() && in.judged)
      frames.push_back({in.step, in.tick, in.time, in.config->present, in.config->poses,
                        PlanRoles(assembly, plan.steps[in.step])});
    on_analysis(in);
  };
  SimulationResult result = SimulatePlan(assembly, plan, options);
  // --suggest-fixtures: when the plan fails, the fewest fixels that make it
  // stable (docs/fixtures.md). The exit code stays the plan's own verdict.
  std::optional<FixtureSuggestion> suggestion;
  FixtureSearchOptions search;
  search.max_fixels = args.max_fixels;
  search.simulation.on_analysis = on_analysis;
  if (args.suggest_fixtures && !result.stable())
    suggestion = SuggestFixtures(model.def, assembly, plan, result, search);
  search.simulation.on_analysis = nullptr;
  // --margin friction: the least friction factor for which the plan is
  // stable, by bisection over simulations (motion/plan_margin.h); those runs
  // record no frames.
  std::optional<PlanMargin> margin;
  if (args.margin == "friction") {
    SimulationOptions bisection = options;
    bisection.record_timeline = false;
    bisection.on_analysis = on_analysis;
    margin = PlanFrictionMargin(model.def, plan, bisection);
  }
  return {std::move(model),  std::move(plan),       std::move(report), std::move(result),
          std::move(search), std::move(suggestion), std::move(frames), std::move(margin)};
}

nlohmann::json SimulationDocumentJson(const Simulated& s, const SimulateArgs& args) {
  nlohmann::json doc = SimulationToJson(s.model.assembly, s.plan, s.result, s.report);
  // null: asked for, but the plan is stable without fixels.
  if (args.suggest_fixtures)
    doc["fixtures"] =
        s.suggestion ? FixtureSuggestionToJson(s.model.assembly, *s.suggestion, s.search, s.report)
                     : nlohmann::json(nullptr);
  if (s.margin) doc["margin"] = PlanMarginToJson(s.model.assembly, *s.margin);
  return doc;
}

}  // namespace

CommandDocument SimulateDocument(const SimulateArgs& args, const Checkpoint& checkpoint) {
  const Simulated s = Simulate(args, [&](const Plan&, const AnalysisInputs&) {
    if (checkpoint) checkpoint();
  });
  return {SimulationDocumentJson(s, args), s.exit()};
}

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The outputs are checked first (never over an input), written last.
    std::vector<NamedFile> inputs = ModelInputs(args.scene, args.model, "the model file");
    inputs.push_back({args.plan, "the plan file"});
    CheckOutputs({{args.timeline, "--timeline"}, {args.html, "--html"}}, inputs);
    // A long plan says where it is, on a terminal (the steps' lengths in
    // time steps computed at the first tick).
    Progress progress("cairn simulate");
    std::vector<long long> ticks;
    const Simulated s = Simulate(
        args,
        [&](const Plan& plan, const AnalysisInputs& in) {
          if (ticks.empty())
            for (const PlanStep& step : plan.steps)
              ticks.push_back(
                  static_cast<long long>(std::ceil(step.Length() / (plan.speed * plan.dt))));
          progress.Show("step " + std::to_string(in.step + 1) + "/" +
                        std::to_string(plan.steps.size()) + ", time step " +
                        std::to_string(in.tick) + "/" + std::to_string(ticks[in.step]));
        },
        &err);
    progress.Done();
    // Everything is computed before anything is written.
    const nlohmann::json doc = SimulationDocumentJson(s, args);
    std::string text;
    if (args.json) {
      text = doc.dump(2) + "\n";
    } else {
      text = SimulationToText(s.model.assembly, s.plan, s.result, s.report);
      if (s.suggestion)
        text += FixtureSuggestionToText(s.model.assembly, *s.suggestion, s.search, s.report);
      if (s.margin) text += PlanMarginToText(s.model.assembly, *s.margin);
    }
    // Every file, or none (OutputFiles).
    OutputFiles files(inputs);
    if (!args.timeline.empty())
      files.Add(args.timeline, TimelineToCsv(s.model.assembly, s.result, s.report), "--timeline");
    if (!args.html.empty())
      files.Add(args.html, SimulationPage(s.model.assembly, s.result, s.frames, doc, s.report),
                "--html");
    files.Commit();
    out << text;
    return s.exit();
  });
}

}  // namespace cairn::cli

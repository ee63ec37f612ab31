
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
#include "cairn/motion/plan_margin.h"  // --margin (issue 20)
#include "cairn/motion/simulate.h"
#include "cairn/planning/fixtures.h"
#include "cairn/report/fixture_report.h"
#include "cairn/report/html_report.h"
#include "cairn/report/margin_report.h"  // --margin (issue 20)
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

}  // namespace

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The definition too: a fixel suggestion adds fixtures to it.
    const Model model = LoadModel(args.scene, args.model);
    const Assembly& assembly = model.assembly;
    RefuseGivenInterfaces(assembly, args.scene,
                          "parts cannot be moved along a plan (check it, with --without for "
                          "subassemblies, or let Cairn find the contacts from the shapes)");
    const Plan plan = ReadPlan(args.plan, assembly, args.max_ticks);
    ReportOptions report;
    report.scene_file = args.scene;
    report.normalize_part = ResolveNormalize(assembly, args.normalize, args.scene);
    SimulationOptions options;
    options.continue_after_failure = args.continue_after_failure;
    // The page draws every tick: its poses and roles (recorded here) and its
    // contacts (the timeline).
    options.record_timeline = !args.timeline.empty() || !args.html.empty();
    std::vector<SimulationFrame> frames;
    // A long plan says where it is, on a terminal.
    Progress progress("cairn simulate");
    std::vector<long long> ticks;
    for (const PlanStep& s : plan.steps)
      ticks.push_back(static_cast<long long>(std::ceil(s.Length() / (plan.speed * plan.dt))));
    options.on_analysis = [&](const AnalysisInputs& in) {
      if (!args.html.empty() && in.judged)
        frames.push_back({in.step, in.tick, in.time, in.config->present, in.config->poses,
                          PlanRoles(assembly, plan.steps[in.step])});
      progress.Show("step " + std::to_string(in.step + 1) + "/" +
                    std::to_string(plan.steps.size()) + ", time step " + std::to_string(in.tick) +
                    "/" + std::to_string(ticks[in.step]));
    };
    const SimulationResult result = SimulatePlan(assembly, plan, options);
    progress.Done();
    // --suggest-fixtures: when the plan fails, the fewest fixels that make it
    // stable (docs/fixtures.md). The exit code stays the plan's own verdict.
    std::optional<FixtureSuggestion> suggestion;
    FixtureSearchOptions search;
    search.max_fixels = args.max_fixels;
    if (args.suggest_fixtures && !result.stable())
      suggestion = SuggestFixtures(model.def, assembly, plan, result, search);
    // Everything is computed before anything is written.
    nlohmann::json doc = SimulationToJson(assembly, plan, result, report);
    // null: asked for, but the plan is stable without fixels.
    if (args.suggest_fixtures)
      doc["fixtures"] = suggestion ? FixtureSuggestionToJson(assembly, *suggestion, search, report)
                                   : nlohmann::json(nullptr);
    // --margin friction (issue 20): the least friction factor for which the
    // plan is stable, by bisection over simulations.
    std::optional<PlanMargin> margin;
    if (args.margin == "friction") {
      margin = PlanFrictionMargin(model.def, plan, options);
      doc["margin"] = PlanMarginToJson(assembly, *margin);
    }
    std::string text;
    if (args.json) {
      text = doc.dump(2) + "\n";
    } else {
      text = SimulationToText(assembly, plan, result, report);
      if (suggestion) text += FixtureSuggestionToText(assembly, *suggestion, search, report);
      if (margin) text += PlanMarginToText(assembly, *margin);  // issue 20
    }
    // Every file, or none (OutputFiles).
    OutputFiles files;
    if (!args.timeline.empty())
      files.Add(args.timeline, TimelineToCsv(assembly, result, report), "--timeline");
    if (!args.html.empty())
      files.Add(args.html, SimulationPage(assembly, result, frames, doc, report), "--html");
    files.Commit();
    out << text;
    switch (result.verdict) {
      case MotionVerdict::kStable:
        return kExitStable;
      case MotionVerdict::kInfeasible:
        return kExitInfeasible;
      default:
        return kExitUnstable;
    }
  });
}

}  // namespace cairn::cli

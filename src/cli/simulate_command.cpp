
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
#include "cairn/motion/simulate.h"
#include "cairn/planning/fixtures.h"
#include "cairn/report/fixture_report.h"
#include "cairn/report/simulation_report.h"
#include "cairn/stability/analyze.h"
#include "cli/command.h"
#include "cli/model.h"
#include "cli/progress.h"
#include "cli/scene_writer.h"

namespace cairn::cli {

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The definition too: a fixel suggestion adds fixtures to it.
    const Model model = LoadModel(args.scene, args.model, &err);
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
    options.record_timeline = !args.timeline.empty();
    // A long plan says where it is, on a terminal.
    Progress progress("cairn simulate");
    std::vector<long long> ticks;
    for (const PlanStep& s : plan.steps)
      ticks.push_back(static_cast<long long>(std::ceil(s.Length() / (plan.speed * plan.dt))));
    options.on_analysis = [&](const AnalysisInputs& in) {
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
    std::string text;
    if (args.json) {
      nlohmann::json doc = SimulationToJson(assembly, plan, result, report);
      // null: asked for, but the plan is stable without fixels.
      if (args.suggest_fixtures)
        doc["fixtures"] = suggestion
                              ? FixtureSuggestionToJson(assembly, *suggestion, search, report)
                              : nlohmann::json(nullptr);
      text = doc.dump(2) + "\n";
    } else {
      text = SimulationToText(assembly, plan, result, report);
      if (suggestion) text += FixtureSuggestionToText(assembly, *suggestion, search, report);
    }
    if (!args.timeline.empty())
      WriteAtomically(args.timeline, TimelineToCsv(assembly, result, report), "--timeline");
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

#include "cli/commands.h"

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
#include "cairn/report/report.h"
#include "cairn/stability/analyze.h"
#include "cli/model.h"
#include "cli/scene_writer.h"

namespace cairn::cli {

int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const Assembly assembly = LoadModel(args.scene, args.model).assembly;
    ReportOptions report;
    report.scene_file = args.scene;
    report.normalize_part = ResolveNormalize(assembly, args.normalize, args.scene);
    const Configuration config = WithoutParts(assembly, args.without, args.scene, report.without);
    StabilityOptions analysis;
    analysis.check_equilibrium = true;  // report jamming (weak stability) too
    const StabilityResult result = AnalyzeConfiguration(assembly, config, analysis);
    if (args.json)
      out << StabilityToJson(assembly, config, result, report).dump(2) << '\n';
    else
      out << StabilityToText(assembly, config, result, report);
    return result.stable() ? kExitStable : kExitUnstable;
  } catch (const InputError& e) {
    err << "cairn: error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  try {
    // The definition too: a fixel suggestion adds fixtures to it.
    const Model model = LoadModel(args.scene, args.model);
    const Assembly& assembly = model.assembly;
    RefuseGivenInterfaces(assembly, args.scene,
                          "parts cannot be moved along a plan (check it, with --without for "
                          "subassemblies, or let Cairn find the contacts from the shapes)");
    const Plan plan = ReadPlan(args.plan, assembly);
    ReportOptions report;
    report.scene_file = args.scene;
    report.normalize_part = ResolveNormalize(assembly, args.normalize, args.scene);
    SimulationOptions options;
    options.continue_after_failure = args.continue_after_failure;
    options.record_timeline = !args.timeline.empty();
    const SimulationResult result = SimulatePlan(assembly, plan, options);
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
  } catch (const InputError& e) {
    err << "cairn: error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

int RunConvert(const ConvertArgs& args, std::ostream& out, std::ostream& err) {
  try {
    // The model is validated (Assembly::Create) before anything is written,
    // so a scene that convert writes is one `cairn check` reads.
    const Model m = LoadModel(args.input, args.model);
    const std::string text = WriteSceneJson(m.def);
    WriteAtomically(args.output, text, "");
    int fixed = 0;
    for (const Part& p : m.assembly.parts()) fixed += p.fixed ? 1 : 0;
    out << "cairn: wrote " << args.output << ": " << m.assembly.num_parts() << " parts (" << fixed
        << " fixed), " << m.assembly.dimension() << "-D, friction " << Num(m.def.friction) << '\n';
    return kExitStable;
  } catch (const InputError& e) {
    err << "cairn: error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace cairn::cli

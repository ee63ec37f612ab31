#include "cli/commands.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cairn/core/error.h"
#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "cairn/report/report.h"
#include "cairn/stability/analyze.h"

namespace cairn::cli {

int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const Assembly assembly = ReadScene(args.scene);
    ReportOptions report;
    report.scene_file = args.scene;
    // Resolve part names given on the command line.
    const auto resolve = [&](const std::string& name, const std::string& flag) {
      const int i = assembly.FindPart(name);
      if (i < 0) throw InputError("", flag, "no part named '" + name + "' in " + args.scene);
      return i;
    };
    if (!args.normalize.empty()) {
      report.normalize_part = resolve(args.normalize, "--normalize");
      if (assembly.part(*report.normalize_part).mass <= 0)
        throw InputError("", "--normalize", "part '" + args.normalize + "' has no weight");
    }
    Configuration config = Configuration::Assembled(assembly);
    for (const std::string& name : args.without) {
      const int i = resolve(name, "--without");
      config.present[i] = false;
      report.without.push_back(i);
    }
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

namespace {

// Writes `text` to `path` whole or not at all: a temporary file beside it,
// renamed over it once complete. @throws InputError naming the flag.
void WriteAtomically(const std::string& path, const std::string& text, const std::string& flag) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    if (!(f << text) || !f.flush()) {
      std::remove(tmp.c_str());
      throw InputError("", flag, "cannot write '" + path + "'");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    throw InputError("", flag, "cannot write '" + path + "': " + ec.message());
  }
}

}  // namespace

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  try {
    const Assembly assembly = ReadScene(args.scene);
    const Plan plan = ReadPlan(args.plan, assembly);
    ReportOptions report;
    report.scene_file = args.scene;
    if (!args.normalize.empty()) {
      const int i = assembly.FindPart(args.normalize);
      if (i < 0)
        throw InputError("", "--normalize",
                         "no part named '" + args.normalize + "' in " + args.scene);
      report.normalize_part = i;
    }
    SimulationOptions options;
    options.continue_after_failure = args.continue_after_failure;
    options.record_timeline = !args.timeline.empty();
    const SimulationResult result = SimulatePlan(assembly, plan, options);
    // Everything is computed before anything is written.
    const std::string text = args.json
                                 ? SimulationToJson(assembly, plan, result, report).dump(2) + "\n"
                                 : SimulationToText(assembly, plan, result, report);
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

}  // namespace cairn::cli

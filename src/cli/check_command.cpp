
#include "cli/check_command.h"

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
#include "cairn/report/check_report.h"
#include "cairn/report/fixture_report.h"
#include "cairn/stability/analyze.h"
#include "cli/command.h"
#include "cli/model.h"
#include "cli/scene_writer.h"

namespace cairn::cli {

int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    const Assembly assembly = LoadModel(args.scene, args.model, &err).assembly;
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
  });
}

}  // namespace cairn::cli

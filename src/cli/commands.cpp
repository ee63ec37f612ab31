#include "cli/commands.h"

#include <algorithm>
#include <iostream>

#include "cairn/core/error.h"
#include "cairn/io/scene_reader.h"
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
    const StabilityResult result = AnalyzeConfiguration(assembly, config);
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

}  // namespace cairn::cli

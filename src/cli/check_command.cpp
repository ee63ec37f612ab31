
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
#include "cairn/report/html_report.h"
#include "cairn/stability/analyze.h"
#include "cli/command.h"
#include "cli/model.h"
#include "cli/output_files.h"
#include "cli/scene_writer.h"

namespace cairn::cli {
namespace {

// The check itself, for the document and for the summary.
struct Checked {
  Assembly assembly;
  ReportOptions report;
  Configuration config;
  StabilityResult result;
  int exit() const { return result.stable() ? kExitStable : kExitUnstable; }
};

Checked Check(const CheckArgs& args, const Checkpoint& checkpoint, std::ostream* notes = nullptr) {
  Assembly assembly = LoadModel(args.scene, args.model, notes).assembly;
  ReportOptions report;
  report.scene_file = args.scene;
  report.normalize_part = ResolveNormalize(assembly, args.normalize, args.scene);
  report.contacts = args.contacts == "all"    ? ContactListing::kAll
                    : args.contacts == "none" ? ContactListing::kNone
                                              : ContactListing::kSummary;
  Configuration config = WithoutParts(assembly, args.without, args.scene, report.without);
  if (checkpoint) checkpoint();
  StabilityOptions analysis;
  analysis.check_equilibrium = true;  // report jamming (weak stability) too
  StabilityResult result = AnalyzeConfiguration(assembly, config, analysis);
  return {std::move(assembly), std::move(report), std::move(config), std::move(result)};
}

nlohmann::json CheckJson(const Checked& c) {
  return StabilityToJson(c.assembly, c.config, c.result, c.report);
}

}  // namespace

CommandDocument CheckDocument(const CheckArgs& args, const Checkpoint& checkpoint) {
  const Checked c = Check(args, checkpoint);
  return {CheckJson(c), c.exit()};
}

int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The output is checked first (never over the input), written last.
    const std::vector<NamedFile> inputs = ModelInputs(args.scene, args.model, "the model file");
    CheckOutputs({{args.html, "--html"}}, inputs);
    const Checked c = Check(args, {}, &err);
    // Everything is computed before anything is written.
    const nlohmann::json doc = CheckJson(c);
    OutputFiles files(inputs);
    if (!args.html.empty()) files.Add(args.html, CheckPage(c.assembly, doc, c.report), "--html");
    files.Commit();
    if (args.json)
      out << doc.dump(2) << '\n';
    else
      out << StabilityToText(c.assembly, c.config, c.result, c.report);
    return c.exit();
  });
}

}  // namespace cairn::cli

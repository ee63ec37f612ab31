#include "cairn/app/plan.h"

#include <cstdio>
#include <utility>

#include "cairn/core/error.h"
#include "cairn/io/paths_reader.h"
#include "cairn/io/scene_writer.h"
#include "cairn/report/html_report.h"
#include "cairn/report/plan_report.h"

namespace cairn::app {
namespace {

std::string Numbered(const std::string& stem, size_t k, const std::string& suffix) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%03zu", k + 1);
  return stem + buf + suffix;
}

PlannerOptions OptionsOf(const Model& model, const PlanQuery& query, const Monitor& monitor) {
  const Assembly& assembly = model.assembly;
  PlannerOptions options;
  options.rule = query.rule;
  options.require_strong = query.require_strong;
  options.max_sequences = query.max;
  options.threads = query.threads;
  options.subassemblies = !query.single_parts;
  options.dt = query.dt;
  options.speed = query.speed;
  options.allow_fixtures = query.allow_fixtures;
  if (query.directions != "ndbg" && query.directions != "axes")
    throw InputError("", "--directions", "must be ndbg or axes, not \"" + query.directions + "\"");
  if (query.directions == "axes") {
    // The classic six (four in 2-D) instead of the NDBG's cells.
    for (int k = 0; k < assembly.dimension(); ++k)
      for (const double sign : {1.0, -1.0}) options.directions.push_back(sign * Vector3::Unit(k));
  }
  if (query.support != "full" && query.support != "none" && query.support != "both")
    throw InputError("", "--support", "must be full, none or both, not \"" + query.support + "\"");
  options.support = query.support == "none"   ? SupportChoice::kNone
                    : query.support == "both" ? SupportChoice::kBoth
                                              : SupportChoice::kFull;
  for (const std::string& name : query.keep)
    options.keep.push_back(ResolvePart(assembly, name, "--keep", model.file));
  if (!query.paths.empty())
    options.given_paths = ReadCandidatePaths(query.paths, assembly, query.max_input_size);
  options.on_progress = [&monitor](const PlannerStats& s) {
    monitor.Poll();
    if (monitor.status)
      monitor.status(std::to_string(s.node_checks) + " nodes checked, " +
                     std::to_string(s.path_simulations) + " paths simulated");
  };
  options.checkpoint = monitor.checkpoint;
  options.executor = query.executor;
  return options;
}

// --emit-plans: per sequence its disassembly plan and, when it was checked
// the other way too, its assembly plan; a sequence that needs fixels gets
// its scene with them instead (the assembly direction was not checked with
// fixels); then the plans that only assemble.
std::vector<std::pair<std::string, std::string>> EmittedPlans(const Model& model,
                                                              const PlannerResult& result) {
  std::vector<std::pair<std::string, std::string>> files;
  const int dim = model.assembly.dimension();
  const auto plan_text = [&](const PlannedSequence& s, PlanMode mode) {
    return PlanDefToJson(SequenceToPlanDef(s, result, mode), dim).dump(2) + "\n";
  };
  for (size_t k = 0; k < result.sequences.size(); ++k) {
    const PlannedSequence& s = result.sequences[k];
    files.emplace_back(Numbered("sequence_", k, ".plan.json"),
                       plan_text(s, PlanMode::kDisassemble));
    if (!s.fixels.empty()) {
      AssemblyDef def = model.def;
      def.fixtures.insert(def.fixtures.end(), s.fixels.begin(), s.fixels.end());
      files.emplace_back(Numbered("sequence_", k, ".scene.json"), WriteSceneJson(def));
      continue;
    }
    files.emplace_back(Numbered("sequence_", k, ".assemble.plan.json"),
                       plan_text(s, PlanMode::kAssemble));
  }
  for (size_t k = 0; k < result.assembly_only.size(); ++k)
    files.emplace_back(Numbered("assembly_only_", k, ".plan.json"),
                       plan_text(result.assembly_only[k], PlanMode::kAssemble));
  return files;
}

}  // namespace

CommandResult PlanDocument(const Model& model, const PlanQuery& query, const Monitor& monitor) {
  const Assembly& assembly = model.assembly;
  RefuseGivenInterfaces(assembly, model.file,
                        "parts cannot be moved, so no removal can be planned");
  const PlannerResult result =
      PlanDisassembly(model.def, assembly, OptionsOf(model, query, monitor));
  CommandResult out;
  out.document = PlannerToJson(assembly, result, model.file);
  out.exit = result.sequences.empty() ? kExitUnstable : kExitStable;
  out.text = PlannerToText(assembly, result, model.file);
  if (query.emit_plans) out.plans = EmittedPlans(model, result);
  if (query.dot) out.dot = PlannerToDot(assembly, result);
  if (query.page) {
    ReportOptions report;
    report.scene_file = model.file;
    out.page = PlanPage(assembly, result, out.document, report);
  }
  return out;
}

}  // namespace cairn::app

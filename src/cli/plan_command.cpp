// `cairn plan`: stable disassembly sequences of a scene (docs/planning.md).

#include "cli/plan_command.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <sstream>

#include "cairn/core/error.h"
#include "cairn/io/paths_reader.h"
#include "cairn/planning/planner.h"
#include "cairn/report/html_report.h"
#include "cairn/report/plan_report.h"
#include "cli/command.h"
#include "cli/model.h"
#include "cli/mpi.h"
#include "cli/output_files.h"
#include "cli/progress.h"
#include "cli/scene_writer.h"

namespace cairn::cli {
namespace {

using nlohmann::json;

std::string Numbered(const std::string& stem, size_t k, const std::string& suffix) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%03zu", k + 1);
  return stem + buf + suffix;
}

}  // namespace

namespace {

// The search, for the document, the summary and the files.
struct Planned {
  Model model;
  PlannerResult result;
  int exit() const { return result.sequences.empty() ? kExitUnstable : kExitStable; }
};

Planned Search(const PlanArgs& args, const Checkpoint& checkpoint, PlanExecutor* executor,
               const std::function<void(const PlannerStats&)>& on_progress,
               std::ostream* notes = nullptr) {
  Model model = LoadModel(args.scene, args.model, notes);
  const Assembly& assembly = model.assembly;
  RefuseGivenInterfaces(assembly, args.scene,
                        "parts cannot be moved, so no removal can be planned");
  PlannerOptions options;
  options.max_sequences = args.max;
  options.threads = args.threads;
  options.subassemblies = !args.no_subassemblies;
  options.dt = args.dt;
  options.speed = args.speed;
  options.allow_fixtures = args.allow_fixtures;
  if (args.directions == "axes") {
    // The classic six (four in 2-D) instead of the NDBG's cells.
    for (int k = 0; k < assembly.dimension(); ++k)
      for (const double sign : {1.0, -1.0}) options.directions.push_back(sign * Vector3::Unit(k));
  }
  options.support = args.support == "none"   ? SupportChoice::kNone
                    : args.support == "both" ? SupportChoice::kBoth
                                             : SupportChoice::kFull;
  for (const std::string& name : args.keep)
    options.keep.push_back(ResolvePart(assembly, name, "--keep", args.scene));
  if (!args.paths.empty())
    options.given_paths = ReadCandidatePaths(args.paths, assembly, args.model.max_input_size);
  options.on_progress = on_progress;
  options.checkpoint = checkpoint;
  options.executor = executor;
  PlannerResult result = PlanDisassembly(model.def, assembly, options);
  return {std::move(model), std::move(result)};
}

}  // namespace

CommandDocument PlanDocument(const PlanArgs& args, const Checkpoint& checkpoint,
                             PlanExecutor* executor) {
  const Planned p = Search(args, checkpoint, executor, [&](const PlannerStats&) {
    if (checkpoint) checkpoint();
  });
  return {PlannerToJson(p.model.assembly, p.result, args.scene), p.exit()};
}

int RunPlan(const PlanArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The outputs are checked first (never over an input), written last.
    std::vector<NamedFile> inputs = ModelInputs(args.scene, args.model, "the model file");
    if (!args.paths.empty()) inputs.push_back({args.paths, "--paths"});
    CheckOutputs({{args.dot, "--dot"}, {args.html, "--html"}}, inputs);
    if (!args.emit_plans.empty()) OutputFiles(inputs).AddFolder(args.emit_plans, "--emit-plans");
    // A long search says where it is, on a terminal (rank 0's: the others'
    // standard error is quiet under mpirun).
    Progress progress("cairn plan");
    const Planned planned = Search(
        args, {}, MpiPlanExecutor(),
        [&](const PlannerStats& s) {
          if (MpiRank() == 0)
            progress.Show(std::to_string(s.node_checks) + " nodes checked, " +
                          std::to_string(s.path_simulations) + " paths simulated");
        },
        MpiRank() == 0 ? &err : nullptr);
    progress.Done();
    const Model& model = planned.model;
    const Assembly& assembly = model.assembly;
    const PlannerResult& result = planned.result;
    // Under mpirun, every rank has the same result; rank 0 alone writes it.
    if (MpiRank() != 0) return planned.exit();

    // Everything is computed before anything is written.
    const nlohmann::json doc = PlannerToJson(assembly, result, args.scene);
    const std::string text =
        args.json ? doc.dump(2) + "\n" : PlannerToText(assembly, result, args.scene);
    // Every file, or none (OutputFiles); the --emit-plans folder is made at
    // the commit, and taken away again (when the commit made it) if the
    // files fail or a signal ends the run.
    OutputFiles files(inputs);
    if (!args.emit_plans.empty()) {
      files.AddFolder(args.emit_plans, "--emit-plans");
      const std::filesystem::path dir(args.emit_plans);
      const int dim = assembly.dimension();
      for (size_t k = 0; k < result.sequences.size(); ++k) {
        const PlannedSequence& s = result.sequences[k];
        files.Add(
            (dir / Numbered("sequence_", k, ".plan.json")).string(),
            PlanDefToJson(SequenceToPlanDef(s, result, PlanMode::kDisassemble), dim).dump(2) + "\n",
            "--emit-plans");
        if (!s.fixels.empty()) {
          // The plan needs its fixels: the scene with them, beside the plan.
          AssemblyDef def = model.def;
          def.fixtures.insert(def.fixtures.end(), s.fixels.begin(), s.fixels.end());
          files.Add((dir / Numbered("sequence_", k, ".scene.json")).string(), WriteSceneJson(def),
                    "--emit-plans");
          continue;  // the assembly direction was not checked with fixels
        }
        files.Add(
            (dir / Numbered("sequence_", k, ".assemble.plan.json")).string(),
            PlanDefToJson(SequenceToPlanDef(s, result, PlanMode::kAssemble), dim).dump(2) + "\n",
            "--emit-plans");
      }
      for (size_t k = 0; k < result.assembly_only.size(); ++k)
        files.Add((dir / Numbered("assembly_only_", k, ".plan.json")).string(),
                  PlanDefToJson(
                      SequenceToPlanDef(result.assembly_only[k], result, PlanMode::kAssemble), dim)
                          .dump(2) +
                      "\n",
                  "--emit-plans");
    }
    if (!args.dot.empty()) files.Add(args.dot, PlannerToDot(assembly, result), "--dot");
    if (!args.html.empty()) {
      ReportOptions report;
      report.scene_file = args.scene;
      files.Add(args.html, PlanPage(assembly, result, doc, report), "--html");
    }
    files.Commit();
    out << text;
    return planned.exit();
  });
}

}  // namespace cairn::cli

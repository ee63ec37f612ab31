// `cairn plan`: stable disassembly sequences of a scene (docs/planning.md).

#include "cli/plan_command.h"

#include <filesystem>
#include <ostream>

#include "cairn/app/plan.h"
#include "cli/command.h"
#include "cli/mpi.h"
#include "cli/output_files.h"
#include "cli/progress.h"

namespace cairn::cli {
namespace {

app::PlanQuery QueryOf(const PlanArgs& args) {
  app::PlanQuery q;
  q.rule = RuleOf(args.rule);
  q.require_strong = args.require == "strong";
  q.max = args.max;
  q.threads = args.threads;
  q.paths = args.paths;
  q.keep = args.keep;
  q.support = args.support;
  q.single_parts = args.no_subassemblies;
  q.dt = args.dt;
  q.speed = args.speed;
  q.allow_fixtures = args.allow_fixtures;
  q.directions = args.directions;
  q.dot = !args.dot.empty();
  q.emit_plans = !args.emit_plans.empty();
  q.page = !args.html.empty();
  q.max_input_size = args.model.max_input_size;
  return q;
}

}  // namespace

CommandDocument PlanDocument(const PlanArgs& args, const Checkpoint& checkpoint,
                             PlanExecutor* executor) {
  app::PlanQuery q = QueryOf(args);
  q.dot = q.emit_plans = q.page = false;  // batch writes no files
  q.executor = executor;
  const app::CommandResult r =
      app::PlanDocument(LoadModel(args.scene, args.model), q, {checkpoint, {}});
  return {r.document, r.exit};
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
    const bool rank0 = MpiRank() == 0;
    app::PlanQuery q = QueryOf(args);
    q.executor = MpiPlanExecutor();
    const app::CommandResult r =
        app::PlanDocument(LoadModel(args.scene, args.model, rank0 ? &err : nullptr), q,
                          {{}, [&](const std::string& status) {
                             if (rank0) progress.Show(status);
                           }});
    progress.Done();
    // Under mpirun, every rank has the same result; rank 0 alone writes it.
    if (!rank0) return r.exit;
    // Every file, or none (OutputFiles); the --emit-plans folder is made at
    // the commit, and taken away again (when the commit made it) if the
    // files fail or a signal ends the run.
    OutputFiles files(inputs);
    if (!args.emit_plans.empty()) {
      files.AddFolder(args.emit_plans, "--emit-plans");
      const std::filesystem::path dir(args.emit_plans);
      for (const auto& [name, text] : r.plans)
        files.Add((dir / name).string(), text, "--emit-plans");
    }
    if (!args.dot.empty()) files.Add(args.dot, r.dot, "--dot");
    if (!args.html.empty()) files.Add(args.html, r.page, "--html");
    files.Commit();
    out << (args.json ? r.document.dump(2) + "\n" : r.text);
    return r.exit;
  });
}

}  // namespace cairn::cli

#include "cli/simulate_command.h"

#include <ostream>

#include "cairn/app/simulate.h"
#include "cli/command.h"
#include "cli/output_files.h"
#include "cli/progress.h"

namespace cairn::cli {
namespace {

app::SimulateQuery QueryOf(const SimulateArgs& args) {
  app::SimulateQuery q;
  q.rule = RuleOf(args.rule);
  q.require_strong = args.require == "strong";
  q.plan_file = args.plan;
  q.normalize = args.normalize;
  q.continue_after_failure = args.continue_after_failure;
  q.suggest_fixtures = args.suggest_fixtures;
  q.max_fixels = args.max_fixels;
  q.max_ticks = args.max_ticks;
  q.margin = args.margin;
  q.timeline = !args.timeline.empty();
  q.page = !args.html.empty();
  q.max_input_size = args.model.max_input_size;
  return q;
}

}  // namespace

CommandDocument SimulateDocument(const SimulateArgs& args, const Checkpoint& checkpoint) {
  app::SimulateQuery q = QueryOf(args);
  q.timeline = q.page = false;  // batch writes no files
  const app::CommandResult r =
      app::SimulateDocument(LoadModel(args.scene, args.model), q, {checkpoint, {}});
  return {r.document, r.exit};
}

int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The outputs are checked first (never over an input), written last.
    std::vector<NamedFile> inputs = ModelInputs(args.scene, args.model, "the model file");
    inputs.push_back({args.plan, "the plan file"});
    CheckOutputs({{args.timeline, "--timeline"}, {args.html, "--html"}}, inputs);
    // A long plan says where it is, on a terminal.
    Progress progress("cairn simulate");
    const app::CommandResult r =
        app::SimulateDocument(LoadModel(args.scene, args.model, &err), QueryOf(args),
                              {{}, [&](const std::string& status) { progress.Show(status); }});
    progress.Done();
    // Every file, or none (OutputFiles).
    OutputFiles files(inputs);
    if (!args.timeline.empty()) files.Add(args.timeline, r.timeline, "--timeline");
    if (!args.html.empty()) files.Add(args.html, r.page, "--html");
    files.Commit();
    out << (args.json ? r.document.dump(2) + "\n" : r.text);
    return r.exit;
  });
}

}  // namespace cairn::cli

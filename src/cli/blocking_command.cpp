// `cairn blocking`: the NDBG of a scene (planning/blocking.h) and, per cell,
// the parts that can be taken out along its directions.
#include "cli/blocking_command.h"

#include <ostream>

#include "cairn/app/blocking.h"
#include "cli/command.h"
#include "cli/output_files.h"

namespace cairn::cli {

CommandDocument BlockingDocument(const BlockingArgs& args, const Checkpoint& checkpoint) {
  const app::CommandResult r = app::BlockingDocument(
      LoadModel(args.scene, args.model), {args.without, args.direction}, {checkpoint, {}});
  return {r.document, r.exit};
}

int RunBlocking(const BlockingArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The output is checked first (never over the input), written last.
    const std::vector<NamedFile> inputs = ModelInputs(args.scene, args.model, "the model file");
    CheckOutputs({{args.html, "--html"}}, inputs);
    app::BlockingQuery query{args.without, args.direction};
    query.page = !args.html.empty();
    const app::CommandResult r =
        app::BlockingDocument(LoadModel(args.scene, args.model, &err), query);
    OutputFiles files(inputs);
    if (!args.html.empty()) files.Add(args.html, r.page, "--html");
    files.Commit();
    out << (args.json ? r.document.dump(2) + "\n" : r.text);
    return r.exit;
  });
}

}  // namespace cairn::cli

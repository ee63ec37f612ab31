#include "cli/check_command.h"

#include <ostream>

#include "cairn/app/check.h"
#include "cli/command.h"
#include "cli/output_files.h"

namespace cairn::cli {
namespace {

app::CheckQuery QueryOf(const CheckArgs& args) {
  app::CheckQuery q;
  q.without = args.without;
  q.normalize = args.normalize;
  q.contacts = args.contacts == "all"    ? ContactListing::kAll
               : args.contacts == "none" ? ContactListing::kNone
                                         : ContactListing::kSummary;
  q.page = !args.html.empty();
  q.rule = RuleOf(args.rule);
  q.require_strong = args.require == "strong";
  return q;
}

}  // namespace

CommandDocument CheckDocument(const CheckArgs& args, const Checkpoint& checkpoint) {
  const app::CommandResult r =
      app::CheckDocument(LoadModel(args.scene, args.model), QueryOf(args), {checkpoint, {}});
  return {r.document, r.exit};
}

int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The output is checked first (never over the input), written last.
    const std::vector<NamedFile> inputs = ModelInputs(args.scene, args.model, "the model file");
    CheckOutputs({{args.html, "--html"}}, inputs);
    const app::CommandResult r =
        app::CheckDocument(LoadModel(args.scene, args.model, &err), QueryOf(args));
    OutputFiles files(inputs);
    if (!args.html.empty()) files.Add(args.html, r.page, "--html");
    files.Commit();
    out << (args.json ? r.document.dump(2) + "\n" : r.text);
    return r.exit;
  });
}

}  // namespace cairn::cli

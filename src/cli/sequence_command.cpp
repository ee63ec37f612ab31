// `cairn sequence`: a build order with the fewest temporary supports
// (docs/sequence.md).

#include "cli/sequence_command.h"

#include <ostream>

#include "cairn/app/sequence.h"
#include "cli/command.h"
#include "cli/output_files.h"
#include "cli/progress.h"

namespace cairn::cli {
namespace {

app::SequenceQuery QueryOf(const SequenceArgs& args) {
  app::SequenceQuery q;
  q.temporary = args.temporary;
  q.max_temporary = args.max_temporary;
  q.direction = args.direction;
  q.directions = args.directions;
  q.beam_width = args.beam;
  q.rule = args.rule == "equilibrium" ? VerdictRule::kEquilibrium : VerdictRule::kLoadedFromRest;
  q.require_strong = args.require == "strong";
  return q;
}

}  // namespace

CommandDocument SequenceDocument(const SequenceArgs& args, const Checkpoint& checkpoint) {
  const app::CommandResult r =
      app::SequenceDocument(LoadModel(args.scene, args.model), QueryOf(args), {checkpoint, {}});
  return {r.document, r.exit};
}

int RunSequence(const SequenceArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    Progress progress("cairn sequence");
    const app::CommandResult r =
        app::SequenceDocument(LoadModel(args.scene, args.model, &err), QueryOf(args),
                              {{}, [&](const std::string& status) { progress.Show(status); }});
    progress.Done();
    out << (args.json ? r.document.dump(2) + "\n" : r.text);
    return r.exit;
  });
}

}  // namespace cairn::cli

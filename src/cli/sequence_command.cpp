// `cairn sequence`: a build order with the fewest temporary supports
// (docs/sequence.md).

#include "cli/sequence_command.h"

#include <csignal>
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
  q.time_limit = args.time_limit;
  q.rule = RuleOf(args.rule);
  q.require_strong = args.require == "strong";
  return q;
}

}  // namespace

CommandDocument SequenceDocument(const SequenceArgs& args, const Checkpoint& checkpoint) {
  const app::CommandResult r =
      app::SequenceDocument(LoadModel(args.scene, args.model), QueryOf(args), {checkpoint, {}});
  return {r.document, r.exit};
}

namespace {

// SIGINT during the search: it ends with the best order so far, which is
// printed as a finished run's is (a second SIGINT ends the process).
volatile std::sig_atomic_t interrupted = 0;

void OnInterrupt(int) {
  interrupted = 1;
  std::signal(SIGINT, SIG_DFL);
}

// OnInterrupt handles SIGINT while it lives; the previous handler after.
class InterruptScope {
 public:
  InterruptScope() : previous_(std::signal(SIGINT, OnInterrupt)) { interrupted = 0; }
  ~InterruptScope() { std::signal(SIGINT, previous_); }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  void (*previous_)(int);
};

}  // namespace

int RunSequence(const SequenceArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    Progress progress("cairn sequence");
    app::SequenceQuery q = QueryOf(args);
    q.stop = [] { return interrupted != 0; };
    app::CommandResult r;
    {
      // From before the model is read: a Ctrl-C while a large model loads
      // (seconds under the sanitizers) still ends with a document.
      const InterruptScope scope;
      const app::Model model = LoadModel(args.scene, args.model, &err);
      r = app::SequenceDocument(model, q,
                                {{}, [&](const std::string& status) { progress.Show(status); }});
    }
    progress.Done();
    out << (args.json ? r.document.dump(2) + "\n" : r.text);
    return r.exit;
  });
}

}  // namespace cairn::cli

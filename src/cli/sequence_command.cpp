// `cairn sequence`: a build order with the fewest temporary supports
// (docs/sequence.md).

#include "cli/sequence_command.h"

#include <csignal>
#include <ctime>
#include <filesystem>
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
  q.threads = args.threads;
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
// printed as a finished run's is. A second SIGINT ends the process, unless it
// comes within kSameInterrupt of the first: `timeout -s INT` sends the signal
// to the process and then to its group, and those two are one request.
volatile std::sig_atomic_t interrupted = 0;
volatile std::sig_atomic_t first_interrupt_ms = 0;  // CLOCK_MONOTONIC, ms (mod 2^31)
constexpr long kSameInterrupt = 500;                // ms

long MonotonicMs() {  // async-signal-safe (clock_gettime is)
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<long>((t.tv_sec * 1000 + t.tv_nsec / 1000000) & 0x7fffffff);
}

void OnInterrupt(int sig) {
  const long now = MonotonicMs();
  if (interrupted == 0) {
    first_interrupt_ms = static_cast<std::sig_atomic_t>(now);
    interrupted = 1;
    return;
  }
  const long since = (now - first_interrupt_ms) & 0x7fffffff;
  if (since < kSameInterrupt) return;
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// OnInterrupt handles SIGINT while it lives; the previous handler after,
// unless an interrupt came (then OnInterrupt stays, so that its twin, a
// moment late, does not end the process after the document is written).
class InterruptScope {
 public:
  InterruptScope() : previous_(std::signal(SIGINT, OnInterrupt)) { interrupted = 0; }
  ~InterruptScope() {
    if (interrupted == 0) std::signal(SIGINT, previous_);
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  void (*previous_)(int);
};

}  // namespace

int RunSequence(const SequenceArgs& args, std::ostream& out, std::ostream& err) {
  return RunGuarded(err, [&]() -> int {
    // The outputs are checked first (never over an input), written last.
    const std::vector<NamedFile> inputs = ModelInputs(args.scene, args.model, "the model file");
    CheckOutputs({{args.html, "--html"}}, inputs);
    if (!args.emit_plans.empty()) OutputFiles(inputs).AddFolder(args.emit_plans, "--emit-plans");
    Progress progress("cairn sequence");
    app::SequenceQuery q = QueryOf(args);
    q.emit_plans = !args.emit_plans.empty();
    q.page = !args.html.empty();
    q.stop = [] { return interrupted != 0; };
    app::CommandResult r;
    {
      // From before the model is read: a Ctrl-C while a large model loads
      // (seconds under the sanitizers) still ends with a document.
      const InterruptScope scope;
      const app::Model model = LoadModel(args.scene, args.model, &err);
      r = app::SequenceDocument(model, q,
                                {{}, [&](const std::string& status) { progress.Show(status); }});
      progress.Done();
      // Every file, or none (OutputFiles).
      OutputFiles files(inputs);
      if (!args.emit_plans.empty()) {
        files.AddFolder(args.emit_plans, "--emit-plans");
        for (const auto& [name, text] : r.plans)
          files.Add((std::filesystem::path(args.emit_plans) / name).string(), text, "--emit-plans");
      }
      if (!args.html.empty()) files.Add(args.html, r.page, "--html");
      files.Commit();
      out << (args.json ? r.document.dump(2) + "\n" : r.text) << std::flush;
    }
    return r.exit;
  });
}

}  // namespace cairn::cli

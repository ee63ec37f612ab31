#pragma once
/// @file
/// The front door of every command (docs/architecture.md, "app"): one
/// function per command takes a loaded model (app/model.h) and the
/// command's query, and returns what the command answers — its JSON
/// document, its exit code, its report in words and, when asked, its page
/// and files. The CLI (src/cli), `cairn batch` and the Python module call
/// the same functions, so their answers cannot drift apart; each of them only
/// converts arguments in and writes results out.

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace cairn::app {

/// Exit codes (a public contract, docs/cli.md).
inline constexpr int kExitStable = 0;
inline constexpr int kExitUnstable = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInfeasible = 3;
/// `--require strong`: it stands, but strong stability is not proved (the same
/// code as `simulate`'s infeasible step: a requirement the answer does not meet).
inline constexpr int kExitNotStrong = 3;
/// A defect of Cairn's (an exception that is not bad input, a solver that
/// failed): reported as an internal error, never a crash.
inline constexpr int kExitInternalError = 4;

/// What a command reports while it works. `checkpoint` is called often
/// (before each node check, at every time step) and may throw to abandon
/// the work (`cairn batch --job-timeout`: a cooperative deadline);
/// `status` gets a line saying where the work is (a progress line). Either
/// may be empty.
struct Monitor {
  std::function<void()> checkpoint;
  std::function<void(const std::string&)> status;

  void Poll() const {
    if (checkpoint) checkpoint();
  }
};

/// A command's answer.
struct CommandResult {
  nlohmann::json document;  ///< what `--json` prints
  int exit = kExitStable;
  std::string text;     ///< the report in words (what the command prints without --json)
  std::string failure;  ///< exit kExitInternalError: what failed
  std::string page;     ///< the result page (HTML), when the query asked for it
  /// Files beside the report, when the query asked for them: simulate's
  /// timeline (CSV), plan's graph (Graphviz) and plans (a name in the
  /// folder, and the text).
  std::string timeline;
  std::string dot;
  std::vector<std::pair<std::string, std::string>> plans;
};

}  // namespace cairn::app

#pragma once
// What every command shares: the exit codes (a public contract,
// docs/cli.md) and the one place a command's errors become an exit code.

#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>

namespace cairn::cli {

/// Exit codes (a public contract).
inline constexpr int kExitStable = 0;
inline constexpr int kExitUnstable = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInfeasible = 3;
/// A defect of Cairn's (an exception that is not bad input): reported as an
/// internal error, never a crash.
inline constexpr int kExitInternalError = 4;

/// Runs a command's `body` and returns its exit code; bad input
/// (InputError) is written to `err` as "cairn: error: ..." with exit
/// kExitBadInput, any other exception as "cairn: internal error: ..." with
/// kExitInternalError.
int RunGuarded(std::ostream& err, const std::function<int()>& body);

/// A command's JSON document (what it prints with `--json`) and its exit
/// code: what each command's `...Document` function returns, for the CLI and
/// for `cairn batch`, which calls them in-process.
struct CommandDocument {
  nlohmann::json json;
  int exit = kExitStable;
};

/// Called often while a command works (before each node check, at every
/// time step of a simulation); it may throw to abandon the work (`cairn
/// batch --job-timeout`: a cooperative deadline). Empty: never called.
using Checkpoint = std::function<void()>;

}  // namespace cairn::cli

#pragma once
// What every command shares: the exit codes (a public contract,
// docs/cli.md) and the one place a command's errors become an exit code.

#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>

#include "cairn/app/command.h"
#include "cairn/app/model.h"
#include "cairn/stability/solve_component.h"

namespace cairn::cli {

/// Exit codes (a public contract): app's.
using app::kExitBadInput;
using app::kExitInfeasible;
using app::kExitInternalError;
using app::kExitStable;
using app::kExitUnstable;

/// The model options and the model, as app reads them.
using app::LoadModel;
using app::Model;
using app::ModelArgs;

/// Runs a command's `body` and returns its exit code; bad input
/// (InputError) is written to `err` as "cairn: error: ..." with exit
/// kExitBadInput, any other exception as "cairn: internal error: ..." with
/// kExitInternalError.
int RunGuarded(std::ostream& err, const std::function<int()>& body);

/// A command's JSON document (what it prints with `--json`) and its exit
/// code, for `cairn batch`, which runs the commands in-process.
struct CommandDocument {
  nlohmann::json json;
  int exit = kExitStable;
};

/// Called often while a command works (before each node check, at every
/// time step of a simulation); it may throw to abandon the work (`cairn
/// batch --job-timeout`: a cooperative deadline). Empty: never called.
using Checkpoint = std::function<void()>;

/// `--rule`'s value (CLI11 has checked it is one of the two) as the rule.
inline VerdictRule RuleOf(const std::string& rule) {
  return rule == "equilibrium" ? VerdictRule::kEquilibrium : VerdictRule::kLoadedFromRest;
}

}  // namespace cairn::cli

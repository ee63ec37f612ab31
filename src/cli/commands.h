#pragma once
// The CLI's commands, callable from main and from tests. Each returns the
// process exit code (docs/cli.md).

#include <iosfwd>
#include <string>
#include <vector>

namespace cairn::cli {

/// Exit codes (a public contract).
inline constexpr int kExitStable = 0;
inline constexpr int kExitUnstable = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInfeasible = 3;

struct CheckArgs {
  std::string scene;
  bool json = false;
  std::string normalize;             // part name, or empty
  std::vector<std::string> without;  // part names
};

/// `cairn check`: writes the report to `out`, errors to `err`.
int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err);

struct SimulateArgs {
  std::string scene;
  std::string plan;
  bool json = false;
  std::string timeline;   // CSV file, or empty
  std::string normalize;  // part name, or empty
  bool continue_after_failure = false;
};

/// `cairn simulate`: exit 0 stable, 1 unstable or unsupported, 3 infeasible,
/// 2 bad input.
int RunSimulate(const SimulateArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

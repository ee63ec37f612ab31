#pragma once
// The CLI's commands, callable from main and from tests. Each returns the
// process exit code: 0 stable, 1 not stable (or undecided), 2 bad input.

#include <iosfwd>
#include <string>
#include <vector>

namespace cairn::cli {

/// Exit codes (a public contract).
inline constexpr int kExitStable = 0;
inline constexpr int kExitUnstable = 1;
inline constexpr int kExitBadInput = 2;

struct CheckArgs {
  std::string scene;
  bool json = false;
  std::string normalize;             // part name, or empty
  std::vector<std::string> without;  // part names
};

/// `cairn check`: writes the report to `out`, errors to `err`.
int RunCheck(const CheckArgs& args, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

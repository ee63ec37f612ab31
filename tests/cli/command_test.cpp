// RunGuarded (src/cli/command.h): every exception a command lets escape
// becomes an exit code and one line on stderr, never a crash.
#include "cli/command.h"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "cairn/core/error.h"

namespace cairn::cli {
namespace {

TEST(RunGuarded, ReturnsTheCommandsOwnExitCode) {
  std::ostringstream err;
  EXPECT_EQ(RunGuarded(err, [] { return kExitInfeasible; }), kExitInfeasible);
  EXPECT_EQ(err.str(), "");
}

TEST(RunGuarded, BadInputIsExitTwoWithTheMessage) {
  std::ostringstream err;
  EXPECT_EQ(RunGuarded(err, []() -> int { throw InputError("scene.json", "parts[0]", "bad"); }),
            kExitBadInput);
  EXPECT_EQ(err.str(), "cairn: error: scene.json: parts[0]: bad\n");
}

TEST(RunGuarded, AnyOtherExceptionIsAnInternalErrorWithExitFour) {
  std::ostringstream err;
  EXPECT_EQ(RunGuarded(err, []() -> int { throw std::logic_error("an invariant"); }),
            kExitInternalError);
  EXPECT_EQ(err.str(), "cairn: internal error: an invariant\n");
  std::ostringstream err2;
  EXPECT_EQ(RunGuarded(err2, []() -> int { throw 42; }), kExitInternalError);
  EXPECT_EQ(err2.str(), "cairn: internal error: an unknown exception\n");
  EXPECT_EQ(kExitInternalError, 4);  // a public contract (docs/cli.md)
}

}  // namespace
}  // namespace cairn::cli

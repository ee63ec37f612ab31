// RunGuarded (src/cli/command.h): every exception a command lets escape
// becomes an exit code and one line on stderr, never a crash. And the
// command line's own errors (src/cli/main.cpp), through the real binary:
// an unknown command or option named, with the nearest one; an option
// without its value; a list option that never takes the file after it.
#include "cli/command.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cairn/core/error.h"
#include "cli/cli_run.h"
#include "test_paths.h"

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

using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;

// A usage error: exit 2, nothing on stdout, one line on stderr that holds
// `words`.
void ExpectUsageError(const std::string& args, const std::string& words) {
  const CliRun r = Cairn(args);
  EXPECT_EQ(r.exit_code, kExitBadInput) << args << "\n" << r.err;
  EXPECT_TRUE(r.out.empty()) << args << ": " << r.out;
  EXPECT_EQ(r.err.rfind("cairn: error: ", 0), 0u) << args << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << args << ": " << r.err;
}

TEST(UsageErrors, AnUnknownCommandIsNamedWithTheNearestOne) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  ExpectUsageError("chek " + fig1, "unknown command 'chek' (did you mean check?)");
  ExpectUsageError("simualte " + fig1, "unknown command 'simualte' (did you mean simulate?)");
  ExpectUsageError("frobnicate " + fig1, "unknown command 'frobnicate' (the commands: check, ");
  ExpectUsageError("", "say which command: check, simulate, ");
}

TEST(UsageErrors, AnUnknownOptionIsNamedWithTheNearestOne) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  ExpectUsageError("check " + fig1 + " --withot C",
                   "unknown option --withot (did you mean --without?)");
  ExpectUsageError("check --withot C " + fig1, "unknown option --withot (did you mean --without?)");
  ExpectUsageError("margin " + fig1 + " --tlit 0,0,1",
                   "unknown option --tlit (did you mean --tilt?)");
  ExpectUsageError("check " + fig1 + " --jsno", "unknown option --jsno (did you mean --json?)");
  ExpectUsageError("check " + fig1 + " --nothing-like-it",
                   "unknown option --nothing-like-it for check; see cairn check --help");
}

// simulate has no --without (a plan starts from the whole assembly): the
// message says so and which commands take it, not CLI11's "not expected:
// 7,8,9 --without".
TEST(UsageErrors, AnOptionOfAnotherCommandSaysWhichTakeIt) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  const std::string plan = ExamplePath("plans/paper_fig1_dcba.plan.json");
  ExpectUsageError("simulate " + fig1 + " " + plan + " --without 7,8,9",
                   "unknown option --without for simulate (check, blocking, margin take it)");
}

TEST(UsageErrors, AnOptionWithoutItsValueSaysSo) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  ExpectUsageError("check " + fig1 + " --friction", "--friction needs a value");
  ExpectUsageError("check " + fig1 + " --normalize --json", "--normalize needs a value");
  ExpectUsageError("check " + fig1 + " --without", "--without needs a value");
  ExpectUsageError("blocking " + fig1 + " --direction", "--direction needs a value");
}

// margin's --friction takes a value or none: the file after it is taken as
// its value, and the message says so.
TEST(UsageErrors, AnOptionalValueThatTookTheFileSaysSo) {
  const std::string incline = ExamplePath("incline.json");
  ExpectUsageError("margin --friction " + incline, "a file is missing: --friction took '" +
                                                       incline +
                                                       "' as its value: write the file "
                                                       "before --friction, or "
                                                       "--friction=VALUE");
  const CliRun r = Cairn("margin " + incline + " --friction");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const CliRun mu = Cairn("margin --friction 0.5 " + incline);
  EXPECT_EQ(mu.exit_code, 0) << mu.err;
}

TEST(UsageErrors, AnArgumentTooManyIsNamed) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  ExpectUsageError("check " + fig1 + " --without D C",
                   "unexpected argument 'C': check takes 1 file");
}

// Every comma-list option takes one argument: the file after it stays the
// file (not "Could not convert", not a part named after the file).
TEST(UsageErrors, AListOptionNeverTakesTheFileAfterIt) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  struct Case {
    std::string args;
    int exit_code;
  };
  for (const Case& c :
       {Case{"margin --tilt 0,0,1 " + fig1, 0},
        Case{"margin --load A --point 0,4 --direction 1,0 " + fig1, 0},
        Case{"check --without D " + fig1, 0}, Case{"check --supports A " + fig1, 0},
        Case{"check --fixed A " + fig1, 0}, Case{"check --gravity 0,-9.81 " + fig1, 0},
        Case{"blocking --direction 0,1 " + fig1, 0}, Case{"plan --max 1 --keep A " + fig1, 0}}) {
    const CliRun r = Cairn(c.args + " --json");
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.err.empty()) << c.args << ": " << r.err;
    EXPECT_TRUE(nlohmann::json::accept(r.out)) << c.args << ": " << r.out;
  }
}

TEST(UsageErrors, AListsEmptyPartIsRefused) {
  const std::string fig1 = ExamplePath("paper_fig1.json");
  ExpectUsageError("check " + fig1 + " --without C,,D",
                   "--without: an empty part name (between two commas)");
  ExpectUsageError("check " + fig1 + " --without C,",
                   "--without: an empty part name (a comma at an end)");
  ExpectUsageError("check " + fig1 + " --without=", "--without needs a value (nothing after '=')");
  ExpectUsageError("check " + fig1 + " --fixed ,A",
                   "--supports: an empty part name (a comma at an end)");
  ExpectUsageError("margin " + fig1 + " --tilt 0,,1",
                   "--tilt: an empty number (between two commas)");
  ExpectUsageError("margin " + fig1 + " --tilt 0,x,1", "--tilt: \"x\" is not a number");
  ExpectUsageError("margin " + fig1 + " --tilt 0,0,1 --tilt 0,0,1", "--tilt: given 2 times");
}

// A list option given twice: the lists are joined.
TEST(UsageErrors, AListOptionGivenTwiceJoinsTheLists) {
  const CliRun r =
      Cairn("check " + ExamplePath("paper_fig1.json") + " --without D --without C --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["without"], nlohmann::json::parse(R"(["D", "C"])"));
}

}  // namespace
}  // namespace cairn::cli

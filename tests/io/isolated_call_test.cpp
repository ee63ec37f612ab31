// io/isolated_call.h: work that may crash or never return runs in a child
// process; what it returns comes back whole, and a crash, an exit without a
// result or a hang comes back as a status, the parent untouched.
#include "io/isolated_call.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <string>

namespace cairn::io_internal {
namespace {

IsolationLimits Seconds(double s) {
  IsolationLimits limits;
  limits.time_limit = s;
  return limits;
}

// A result larger than a pipe's buffer (64 KiB), with zero bytes in it.
TEST(RunIsolated, TheResultComesBackWhole) {
  std::string big(1 << 20, 'x');
  for (size_t k = 0; k < big.size(); k += 4097) big[k] = '\0';
  const IsolatedResult r = RunIsolated([&] { return big; }, Seconds(60));
  ASSERT_EQ(r.status, IsolatedResult::Status::kDone);
  EXPECT_EQ(r.output, big);
  EXPECT_EQ(RunIsolated([] { return std::string(); }, Seconds(60)).output, "");
}

TEST(RunIsolated, ACrashIsAStatusWithItsSignal) {
  const IsolatedResult r = RunIsolated(
      []() -> std::string {
        std::abort();  // SIGABRT (the sanitizers leave it alone)
      },
      Seconds(60));
  EXPECT_EQ(r.status, IsolatedResult::Status::kCrashed);
  EXPECT_EQ(r.signal, SIGABRT);
  EXPECT_EQ(SignalName(r.signal), "SIGABRT");
}

TEST(RunIsolated, AnExitWithoutAResultIsACrashWithItsCode) {
  const IsolatedResult r = RunIsolated([]() -> std::string { _exit(3); }, Seconds(60));
  EXPECT_EQ(r.status, IsolatedResult::Status::kCrashed);
  EXPECT_EQ(r.signal, 0);
  EXPECT_EQ(r.exit_code, 3);
}

TEST(RunIsolated, WorkThatNeverReturnsIsKilledAtTheTimeLimit) {
  const IsolatedResult r = RunIsolated(
      []() -> std::string {
        for (;;) pause();
      },
      Seconds(0.2));
  EXPECT_EQ(r.status, IsolatedResult::Status::kTimedOut);
}

TEST(RunIsolated, TheMemoryLimitStopsAnAllocationThatWouldExceedIt) {
  if (UnderAddressSanitizer())
    GTEST_SKIP() << "under AddressSanitizer RLIMIT_AS cannot be applied (its shadow memory "
                    "takes terabytes of address space); the Release build runs this test";
  IsolationLimits limits = Seconds(60);
  limits.memory_limit = 256u << 20;
  const IsolatedResult r = RunIsolated(
      [] {
        std::string s(1u << 30, 'y');  // 1 GiB: bad_alloc, which escapes `work`: a crash
        return s.substr(0, 1);
      },
      limits);
  EXPECT_EQ(r.status, IsolatedResult::Status::kCrashed);
}

TEST(SignalName, NamedOrNumbered) {
  EXPECT_EQ(SignalName(SIGSEGV), "SIGSEGV");
  EXPECT_EQ(SignalName(SIGKILL), "SIGKILL");
  EXPECT_EQ(SignalName(200), "signal 200");
}

}  // namespace
}  // namespace cairn::io_internal

#pragma once
// Private to the io stage: running work that may crash or never return (a
// third-party reader on untrusted input: OpenCASCADE on a STEP file) in a
// child process with a wall-time limit and a memory limit, its result passed
// back as bytes over a pipe.
//
// The child is forked from the calling thread, does only `work` (no other
// thread of the parent exists in it) and leaves with _exit, so nothing of the
// parent's state (atexit handlers, buffered output, the sanitizers' end-of-
// process checks) runs twice. Its standard output and error go to /dev/null:
// what it has to say is its result.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace cairn::io_internal {

/// The limits of one isolated call.
struct IsolationLimits {
  double time_limit = 0;           ///< s of wall time; the child is killed after it
  std::uint64_t memory_limit = 0;  ///< bytes of address space (RLIMIT_AS); 0: none
};

/// How an isolated call ended.
struct IsolatedResult {
  enum class Status {
    kDone,      ///< `work` returned: `output` is what it returned
    kCrashed,   ///< the child died (a signal, or an exit without its result)
    kTimedOut,  ///< killed after IsolationLimits::time_limit
    kNoFork,    ///< no child could be started (`output`: why)
  };
  Status status = Status::kCrashed;
  std::string output;
  int signal = 0;     ///< kCrashed: the signal that ended the child, or 0
  int exit_code = 0;  ///< kCrashed without a signal: its exit status
};

/// Runs `work` in a child process under `limits`. `work` must not throw
/// (an exception escaping it is a crash).
IsolatedResult RunIsolated(const std::function<std::string()>& work, const IsolationLimits& limits);

/// Runs the program `argv[0]` (a path) with `argv` in a child process under
/// `limits`, `input` as its standard input. The program writes its answer as
/// RunIsolated's child does (its length, 8 bytes in native order, then the
/// bytes) on standard output and exits 0; anything else is kCrashed (exit
/// code 127: it could not be started).
IsolatedResult RunIsolatedProgram(const std::vector<std::string>& argv, const std::string& input,
                                  const IsolationLimits& limits);

/// Writes all of `data` to the file descriptor `fd` (through EINTR and short
/// writes); false when it cannot (a broken pipe).
bool WriteAll(int fd, const char* data, size_t size);

/// "SIGSEGV", "SIGKILL", ...; "signal N" for one without a name.
std::string SignalName(int signal);

/// Whether this process runs under AddressSanitizer, whose shadow memory
/// takes terabytes of address space: RLIMIT_AS cannot be applied.
bool UnderAddressSanitizer();

}  // namespace cairn::io_internal

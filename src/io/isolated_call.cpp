// RunIsolated (isolated_call.h): fork, limits, a pipe read against the
// deadline, waitpid.

#include "io/isolated_call.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <vector>

namespace cairn::io_internal {

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif
#else
constexpr bool kAsan = false;
#endif

// What every child does first: die with the parent (also if it died before
// this line), leave the parent's signal handlers (temporary files to remove on
// SIGTERM are not the child's), write nothing to the parent's standard output
// or error, and take the memory limit.
void EnterChild(const IsolationLimits& limits, pid_t parent) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(3);
  for (const int s : {SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGPIPE}) std::signal(s, SIG_DFL);
  const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
  }
  if (limits.memory_limit > 0 && !kAsan) {
    const rlimit limit{limits.memory_limit, limits.memory_limit};
    ::setrlimit(RLIMIT_AS, &limit);
  }
}

// The child of RunIsolated: the work, its result (length first) on `fd`.
[[noreturn]] void Child(int fd, const std::function<std::string()>& work) {
  const std::string output = work();
  const std::uint64_t size = output.size();
  char header[sizeof size];
  std::memcpy(header, &size, sizeof size);
  const bool ok = WriteAll(fd, header, sizeof header) && WriteAll(fd, output.data(), output.size());
  ::_exit(ok ? 0 : 3);
}

}  // namespace

bool UnderAddressSanitizer() { return kAsan; }

bool WriteAll(int fd, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<size_t>(n);
  }
  return true;
}

std::string SignalName(int signal) {
  const char* abbrev = ::sigabbrev_np(signal);
  return abbrev ? std::string("SIG") + abbrev : "signal " + std::to_string(signal);
}

namespace {

// Starts a child that runs `child` (which never returns) with its answer's
// end of a pipe, and reads the answer against the deadline.
IsolatedResult Run(const std::function<void(int)>& child, const IsolationLimits& limits) {
  IsolatedResult result;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    result.status = IsolatedResult::Status::kNoFork;
    result.output = std::string("cannot make a pipe: ") + std::strerror(errno);
    return result;
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int error = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    result.status = IsolatedResult::Status::kNoFork;
    result.output = std::string("cannot start a process: ") + std::strerror(error);
    return result;
  }
  if (pid == 0) {
    ::close(fds[0]);
    EnterChild(limits, parent);
    child(fds[1]);
    ::_exit(3);
  }
  ::close(fds[1]);

  // Read until the child closes its end, or the deadline.
  using Clock = std::chrono::steady_clock;
  const auto deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(std::max(limits.time_limit, 0.0)));
  std::string bytes;
  bool timed_out = false;
  char buffer[1 << 16];
  while (true) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) break;
    if (ready == 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) break;  // end of file: the child is done (or dead)
    bytes.append(buffer, static_cast<size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) {
    result.status = IsolatedResult::Status::kTimedOut;
    return result;
  }
  std::uint64_t size = 0;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && bytes.size() >= sizeof size) {
    std::memcpy(&size, bytes.data(), sizeof size);
    if (bytes.size() - sizeof size == size) {
      result.status = IsolatedResult::Status::kDone;
      result.output = bytes.substr(sizeof size);
      return result;
    }
  }
  result.status = IsolatedResult::Status::kCrashed;
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  return result;
}

}  // namespace

IsolatedResult RunIsolated(const std::function<std::string()>& work,
                           const IsolationLimits& limits) {
  return Run([&](int fd) { Child(fd, work); }, limits);
}

IsolatedResult RunIsolatedProgram(const std::vector<std::string>& argv, const std::string& input,
                                  const IsolationLimits& limits) {
  // The input in memory, as the program's standard input: written whole
  // before it starts (no pipe to fill, no SIGPIPE if it dies early).
  const int in = ::memfd_create("cairn-input", MFD_CLOEXEC);
  if (in < 0 || !WriteAll(in, input.data(), input.size()) || ::lseek(in, 0, SEEK_SET) != 0) {
    const int error = errno;
    if (in >= 0) ::close(in);
    IsolatedResult result;
    result.status = IsolatedResult::Status::kNoFork;
    result.output = std::string("cannot pass the input: ") + std::strerror(error);
    return result;
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  IsolatedResult result = Run(
      [&](int fd) {
        ::dup2(in, STDIN_FILENO);
        ::dup2(fd, STDOUT_FILENO);
        ::execv(args[0], args.data());
        ::_exit(127);  // not started: a crash with this code
      },
      limits);
  ::close(in);
  return result;
}

}  // namespace cairn::io_internal

// Opening user-given files safely (include/cairn/io/input_file.h): one open
// with O_NONBLOCK (a FIFO without a writer does not block it), fstat on the
// open descriptor (what is read is what was checked), a bounded read.

#include "cairn/io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <limits>
#include <utility>

#include "cairn/core/error.h"

namespace cairn {

namespace {

// The open descriptor of one file, closed on scope exit.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(Descriptor&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  Descriptor& operator=(Descriptor&&) = delete;
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

// What an errno of open(), fstat() or read() means for the user.
std::string Reason(int error) {
  switch (error) {
    case ENOENT:
      return "no such file";
    case ENOTDIR:
      return "no such file (a folder of its path is not a folder)";
    case ELOOP:
      return "a loop of symbolic links (too many levels of links to follow)";
    case ENAMETOOLONG:
      return "the file name is too long";
    case EACCES:
    case EPERM:
      return "permission denied";
    case EISDIR:
      return "is a directory, not a file";
    case ENXIO:
      return "a socket or a device without a reader, not a regular file";
    case ENOMEM:
      return "out of memory";
    default: {
      std::string s = std::strerror(error);
      if (!s.empty()) s[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(s[0])));
      return s;
    }
  }
}

// What a file that is not a regular file is.
std::string NotRegular(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory, not a file";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe), not a regular file";
  if (S_ISCHR(mode)) return "is a character device, not a regular file";
  if (S_ISBLK(mode)) return "is a block device, not a regular file";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file";
  return "is not a regular file";
}

[[noreturn]] void TooLarge(const std::string& path, const std::string& what,
                           const std::string& size, std::uint64_t max_size) {
  throw InputError(path, "",
                   "the " + what + " is " + size + ", more than the maximum input size " +
                       DescribeByteSize(max_size) + " (--max-input-size raises it)");
}

// Opens `path` for reading without blocking and checks it: a regular file of
// at most `max_size` bytes, whose size `size` gets.
Descriptor OpenChecked(const std::string& path, std::uint64_t max_size, const std::string& what,
                       std::uint64_t& size) {
  if (path.empty()) throw InputError(path, "", "the " + what + " name is empty");
  int fd = -1;
  do {
    fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  } while (fd < 0 && errno == EINTR);
  if (fd < 0) {
    const int error = errno;
    // A socket cannot be opened (ENXIO): say what it is.
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
      throw InputError(path, "", NotRegular(st.st_mode));
    throw InputError(path, "", "cannot open the " + what + ": " + Reason(error));
  }
  Descriptor file(fd);
  struct stat st {};
  if (::fstat(fd, &st) != 0)
    throw InputError(path, "", "cannot examine the " + what + ": " + Reason(errno));
  if (!S_ISREG(st.st_mode)) throw InputError(path, "", NotRegular(st.st_mode));
  size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_size) TooLarge(path, what, DescribeByteSize(size), max_size);
  // Reads of a regular file never wait; blocking mode all the same.
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return file;
}

}  // namespace

std::uint64_t CheckInputFile(const std::string& path, std::uint64_t max_size,
                             const std::string& what) {
  std::uint64_t size = 0;
  OpenChecked(path, max_size, what, size);
  return size;
}

std::string ReadInputFile(const std::string& path, std::uint64_t max_size,
                          const std::string& what) {
  std::uint64_t size = 0;
  const Descriptor file = OpenChecked(path, max_size, what, size);
  std::string text;
  text.reserve(static_cast<size_t>(size));
  // Up to one byte past the limit: a file that grew past it is refused.
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(file.get(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(path, "", "cannot read the " + what + ": " + Reason(errno));
    if (n == 0) break;
    text.append(buffer, static_cast<size_t>(n));
    if (text.size() > max_size) TooLarge(path, what, "larger than that", max_size);
  }
  return text;
}

bool IsDirectory(const std::string& path) noexcept {
  struct stat st {};
  return !path.empty() && ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::optional<std::uint64_t> ParseByteSize(const std::string& text) {
  size_t k = 0;
  std::uint64_t value = 0;
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) {
    const std::uint64_t digit = static_cast<std::uint64_t>(text[k] - '0');
    if (value > (kMax - digit) / 10) return std::nullopt;
    value = value * 10 + digit;
    ++k;
  }
  if (k == 0) return std::nullopt;
  std::string suffix;
  for (; k < text.size(); ++k)
    suffix += static_cast<char>(std::toupper(static_cast<unsigned char>(text[k])));
  int shift = 0;
  if (suffix == "K" || suffix == "KIB") {
    shift = 10;
  } else if (suffix == "M" || suffix == "MIB") {
    shift = 20;
  } else if (suffix == "G" || suffix == "GIB") {
    shift = 30;
  } else if (!suffix.empty() && suffix != "B") {
    return std::nullopt;
  }
  if (value > (kMax >> shift)) return std::nullopt;
  value <<= shift;
  if (value == 0) return std::nullopt;
  return value;
}

std::string DescribeByteSize(std::uint64_t bytes) {
  std::string out = std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  const char* units[] = {"GiB", "MiB", "KiB"};
  const int shifts[] = {30, 20, 10};
  for (int u = 0; u < 3; ++u) {
    const std::uint64_t unit = std::uint64_t{1} << shifts[u];
    if (bytes >= unit && bytes % unit == 0) {
      out += " (" + std::to_string(bytes / unit) + " " + units[u] + ")";
      break;
    }
  }
  return out;
}

}  // namespace cairn

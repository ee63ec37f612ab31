#include "cairn/core/error.h"

#include <cstdio>
#include <cstdlib>

#include "cairn/core/check.h"

namespace cairn {
namespace {
std::string Compose(const std::string& file, const std::string& path, const std::string& msg) {
  std::string out;
  if (!file.empty()) out += file + ": ";
  if (!path.empty()) out += path + ": ";
  return out + msg;
}
}  // namespace

InputError::InputError(std::string file, std::string json_path, std::string message)
    : std::runtime_error(Compose(file, json_path, message)),
      file_(std::move(file)),
      json_path_(std::move(json_path)),
      message_(std::move(message)) {}

namespace internal {
void AbortWithMessage(const char* kind, const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s failed: %s at %s:%d\n", kind, condition, file, line);
  std::abort();
}
}  // namespace internal
}  // namespace cairn

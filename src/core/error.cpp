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

std::string EscapedName(const std::string& name) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\b':
        out += "\\b";
        break;
      case '\f':
        out += "\\f";
        break;
      default:
        if (u < 0x20 || u == 0x7f) {
          out += "\\u00";
          out += kHex[u >> 4];
          out += kHex[u & 0xf];
        } else {
          out += c;  // UTF-8 bytes pass through, as JSON allows
        }
    }
  }
  return out;
}

std::string JsonQuoted(const std::string& name) { return "\"" + EscapedName(name) + "\""; }

std::string NamedPath(const std::string& path, const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) {
    if (name.empty()) continue;
    list += (list.empty() ? "" : ", ") + JsonQuoted(name);
  }
  return list.empty() ? path : path + " (" + list + ")";
}

namespace internal {
void AbortWithMessage(const char* kind, const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s failed: %s at %s:%d\n", kind, condition, file, line);
  std::abort();
}
}  // namespace internal
}  // namespace cairn

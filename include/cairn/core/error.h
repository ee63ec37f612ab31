#pragma once
/// @file
/// The error type for bad user input (scene and plan files, CLI arguments).
/// It always says where (file, JSON path) and what is wrong, so the CLI can
/// print one precise line and exit with code 2.

#include <stdexcept>
#include <string>
#include <vector>

#include "cairn/core/format.h"  // FormatNumber, FormatPoint: numbers in messages

namespace cairn {

/// Bad input from a user: a scene or plan file, or a command-line argument.
/// `file` is the file it came from (may be empty), `json_path` the location
/// inside it in the form `parts[2].polygon[3]` (may be empty), `message` what
/// is wrong. what() is "FILE: JSON_PATH: MESSAGE".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string json_path, std::string message);

  const std::string& file() const { return file_; }
  const std::string& json_path() const { return json_path_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  std::string json_path_;
  std::string message_;
};

/// A name as a JSON string: in double quotes, with `"`, `\` and control
/// characters escaped as JSON escapes them (`\"`, `\\`, `\n`, `\u0001`), so
/// that no name can break a one-line message. `"A"` for A.
std::string JsonQuoted(const std::string& name);

/// The name's characters as JsonQuoted escapes them, without the quotes: for
/// names inside a message's own quotes (`part 'A'`) or a JSON path key.
std::string EscapedName(const std::string& name);

/// The JSON path of something that has a name (a part, a COMPAS block, a plan
/// step by the parts it removes), with the name after it: `parts[1] ("A")`,
/// `steps[0] ("B", "C")`. The rest of the path follows: `parts[1] ("A").polygon`.
/// Empty names are left out; with no names left the path is returned as is
/// (a part whose name is missing or is itself the fault is not named).
std::string NamedPath(const std::string& path, const std::vector<std::string>& names);
inline std::string NamedPath(const std::string& path, const std::string& name) {
  return NamedPath(path, std::vector<std::string>{name});
}

}  // namespace cairn

#pragma once
/// @file
/// The error type for bad user input (scene and plan files, CLI arguments).
/// It always says where (file, JSON path) and what is wrong, so the CLI can
/// print one precise line and exit with code 2.

#include <stdexcept>
#include <string>

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

}  // namespace cairn

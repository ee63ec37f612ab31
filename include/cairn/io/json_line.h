#pragma once
/// @file
/// One line of JSON (a JSON-lines file: `cairn batch`'s jobs and results)
/// parsed with the readers' checks: nested at most as deep as the readers
/// allow (a line nested deeper would overflow the stack of whatever walks
/// it), no key given twice in one object (JSON would silently keep the
/// last), no NUL byte.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace cairn {

struct JsonLine {
  std::optional<nlohmann::json> value;  ///< empty: not JSON, or refused
  std::string why;                      ///< then: what is wrong, with its JSON path or column
  bool cut_short = false;               ///< then: valid JSON text up to its end, but incomplete
};

/// The line parsed, or why it is not a JSON text Cairn reads.
JsonLine ParseJsonLine(const std::string& line);

}  // namespace cairn

#include "cairn/io/json_line.h"

#include "io/json_checks.h"

namespace cairn {

JsonLine ParseJsonLine(const std::string& line) {
  using nlohmann::json;
  JsonLine out;
  io_internal::SyntaxChecker checker;
  if (line.find('\0') == std::string::npos && json::sax_parse(line, &checker)) {
    out.value = json::parse(line);
    return out;
  }
  if (checker.duplicate_path()) {
    out.why = *checker.duplicate_path() + ": duplicate key in one object";
  } else if (checker.too_deep_path()) {
    out.why = *checker.too_deep_path() + ": nested more than " +
              std::to_string(io_internal::kMaxJsonDepth) + " arrays or objects deep";
  } else if (line.find('\0') != std::string::npos) {
    out.why = "a NUL byte (a JSON text has none; is this a binary file?)";
  } else {
    out.why = io_internal::DescribeJsonError(line, checker.error_position(),
                                             checker.error().value_or(""));
    // One line: its column says where ("at line 1, column C" says no more).
    if (const size_t at = out.why.find("at line 1, column"); at != std::string::npos)
      out.why.replace(at, 17, "at column");
    out.cut_short = checker.error_position() >= line.size();
  }
  return out;
}

}  // namespace cairn

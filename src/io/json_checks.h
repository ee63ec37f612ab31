#pragma once
// Private to the io stage: the checks shared by the scene and plan readers.
// JSON paths are written `parts[2].polygon[3]`, and a part's path carries its
// name (NamedPath in cairn/core/error.h): `parts[2] ("B").polygon[3]`; every
// fault is an InputError naming the file, the JSON path and one short
// lowercase clause.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/core/tolerances.h"
#include "cairn/core/types.h"
#include "cairn/geometry/assembly.h"
#include "cairn/io/input_file.h"

namespace cairn::io_internal {

using nlohmann::json;

// `path.key`, or `key` at the top level. The key is escaped as in JSON
// (EscapedName): a key of the file with a quote or a newline cannot break the
// one-line message.
// An empty key is written `""`, so that the message still names it.
inline std::string Child(const std::string& path, const std::string& key) {
  const std::string name = key.empty() ? "\"\"" : EscapedName(key);
  return path.empty() ? name : path + "." + name;
}

// `path[i]`.
inline std::string Index(const std::string& path, size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

inline std::string Num(double x) { return FormatNumber(x); }

inline std::string Point(const Vector2& p) { return "(" + Num(p.x()) + ", " + Num(p.y()) + ")"; }
inline std::string Point(const Vector3& p) {
  return "(" + Num(p.x()) + ", " + Num(p.y()) + ", " + Num(p.z()) + ")";
}

inline std::string JoinKeys(std::initializer_list<const char*> keys) {
  std::string out;
  for (const char* k : keys) out += (out.empty() ? "" : ", ") + std::string(k);
  return out;
}

// The typed accessors of one document: each returns the value or throws the
// InputError of `file` at the JSON path given.
class JsonChecker {
 public:
  explicit JsonChecker(const std::string& file) : file_(file) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& message) const {
    throw InputError(file_, path, message);
  }

  // "a string", "an array", ...
  static std::string Article(const json& j) {
    const std::string t = j.type_name();
    return (t == "array" || t == "object" ? "an " : "a ") + t;
  }

  // The format version comes first: a later version may mean other keys.
  // `key` is the version key ("cairn", "cairn_plan"), `what` the format
  // ("scene", "plan").
  void CheckVersion(const json& doc, const char* key, const std::string& what) const {
    if (!doc.contains(key)) {
      Fail(key, "required key is missing (the " + what + " format version: 1)");
    }
    const json& v = doc[key];
    if (!v.is_number()) Fail(key, "must be the format version number 1, not " + Article(v));
    if (v.get<double>() != 1.0) {
      Fail(key, "unsupported format version " + v.dump() + " (this version reads version 1)");
    }
  }

  void CheckKeys(const json& obj, const std::string& path,
                 std::initializer_list<const char*> known) const {
    for (const auto& item : obj.items()) {
      const std::string& key = item.key();
      if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) {
        Fail(Child(path, key), "unknown key (expected one of: " + JoinKeys(known) + ")");
      }
    }
  }

  const json& Require(const json& obj, const char* key, const std::string& path) const {
    if (!obj.contains(key)) Fail(Child(path, key), "required key is missing");
    return obj[key];
  }

  const json& Object(const json& j, const std::string& path) const {
    if (!j.is_object()) Fail(path, "must be an object, not " + Article(j));
    return j;
  }

  const json& Array(const json& j, const std::string& path) const {
    if (!j.is_array()) Fail(path, "must be an array, not " + Article(j));
    return j;
  }

  double Number(const json& j, const std::string& path) const {
    if (!j.is_number()) Fail(path, "must be a number, not " + Article(j));
    const double x = j.get<double>();
    if (!std::isfinite(x)) Fail(path, "must be a finite number (got " + Num(x) + ")");
    return x;
  }

  // A coordinate (length units): finite and within limits::kMaxCoordinate.
  double Coordinate(const json& j, const std::string& path) const {
    const double x = Number(j, path);
    if (std::abs(x) > limits::kMaxCoordinate)
      Fail(path, "coordinate out of range (got " + Num(x) + "; |x| ≤ " +
                     Num(limits::kMaxCoordinate) + " length units)");
    return x;
  }

  std::string String(const json& j, const std::string& path) const {
    if (!j.is_string()) Fail(path, "must be a string, not " + Article(j));
    return j.get<std::string>();
  }

  bool Bool(const json& j, const std::string& path) const {
    if (!j.is_boolean()) Fail(path, "must be true or false, not " + Article(j));
    return j.get<bool>();
  }

  // A 2-D point or vector: an array of exactly two numbers [x, y].
  Vector2 Vec2(const json& j, const std::string& path) const {
    if (!j.is_array()) Fail(path, "must be an array of 2 numbers [x, y], not " + Article(j));
    if (j.size() != 2) {
      Fail(path, "must have 2 numbers [x, y] in a 2-D scene, not " + std::to_string(j.size()));
    }
    return Vector2(Number(j[0], Index(path, 0)), Number(j[1], Index(path, 1)));
  }

  // A point or vector of a `dim`-D scene (2 or 3): [x, y] or [x, y, z]; a 2-D
  // one has z = 0.
  Vector3 VecN(const json& j, const std::string& path, int dim) const {
    if (dim == 2) return Embed(Vec2(j, path));
    if (!j.is_array()) Fail(path, "must be an array of 3 numbers [x, y, z], not " + Article(j));
    if (j.size() != 3) {
      Fail(path, "must have 3 numbers [x, y, z] in a 3-D scene, not " + std::to_string(j.size()));
    }
    return Vector3(Number(j[0], Index(path, 0)), Number(j[1], Index(path, 1)),
                   Number(j[2], Index(path, 2)));
  }

  // A fixel, {"part", "point", "normal"} (a scene's `fixtures[i]`, a plan
  // step's `props[i]`), in a `dim`-D scene.
  FixtureDef Fixture(const json& j, const std::string& path, int dim) const {
    Object(j, path);
    CheckKeys(j, path, {"part", "point", "normal"});
    FixtureDef fixture;
    fixture.part = String(Require(j, "part", path), Child(path, "part"));
    fixture.point = VecN(Require(j, "point", path), Child(path, "point"), dim);
    fixture.normal = VecN(Require(j, "normal", path), Child(path, "normal"), dim);
    return fixture;
  }

  // An array of strings (part names).
  std::vector<std::string> Strings(const json& j, const std::string& path) const {
    Array(j, path);
    std::vector<std::string> out;
    for (size_t i = 0; i < j.size(); ++i) out.push_back(String(j[i], Index(path, i)));
    return out;
  }

 private:
  const std::string& file_;
};

// How deeply arrays and objects may nest. The deepest of Cairn's formats
// (a COMPAS file: data.graph.data.node.<key>.block.data.face.<key>[i]) nests
// about 10; nothing legitimate comes near this, and a document nested
// millions deep (which a recursive reader would overflow the stack on) is
// refused by the SAX pass below, which keeps its own stack.
inline constexpr std::size_t kMaxJsonDepth = 256;

// A SAX pass over the text that builds nothing: it finds syntax errors and
// number overflows (with their position), nesting deeper than kMaxJsonDepth
// and keys repeated within one object (nlohmann::json would silently keep the
// last), with their JSON path.
class SyntaxChecker : public nlohmann::json_sax<json> {
 public:
  bool null() override { return Value(); }
  bool boolean(bool) override { return Value(); }
  bool number_integer(number_integer_t) override { return Value(); }
  bool number_unsigned(number_unsigned_t) override { return Value(); }
  bool number_float(number_float_t, const string_t&) override { return Value(); }
  bool string(string_t&) override { return Value(); }
  bool binary(binary_t&) override { return Value(); }
  bool start_object(std::size_t) override {
    Value();
    frames_.emplace_back().array = false;
    return Depth();
  }
  bool key(string_t& k) override {
    Frame& top = frames_.back();
    top.key = k;
    if (!top.keys.insert(k).second) {
      duplicate_path_ = Path();
      return false;
    }
    return true;
  }
  bool end_object() override {
    frames_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override {
    Value();
    frames_.emplace_back().array = true;
    return Depth();
  }
  bool end_array() override {
    frames_.pop_back();
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const json::exception& ex) override {
    error_position_ = position;
    error_ = ex.what();
    return false;
  }

  const std::optional<std::string>& duplicate_path() const { return duplicate_path_; }
  const std::optional<std::string>& too_deep_path() const { return too_deep_path_; }
  const std::optional<std::string>& error() const { return error_; }
  std::size_t error_position() const { return error_position_; }

 private:
  struct Frame {
    bool array = false;
    size_t count = 0;  // elements seen (arrays)
    std::string key;   // current key (objects)
    std::set<std::string> keys;
  };

  bool Depth() {
    if (frames_.size() <= kMaxJsonDepth) return true;
    too_deep_path_ = Path(8) + "...";  // the first levels say where
    return false;
  }

  // Counts an element of the enclosing array.
  bool Value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
    return true;
  }

  // The JSON path of the current value, at most `levels` deep.
  std::string Path(size_t levels = kMaxJsonDepth + 1) const {
    std::string path;
    for (size_t i = 0; i < frames_.size() && i < levels; ++i) {
      const Frame& f = frames_[i];
      path = f.array ? Index(path, f.count - 1) : Child(path, f.key);
    }
    return path;
  }

  std::vector<Frame> frames_;
  std::optional<std::string> duplicate_path_;
  std::optional<std::string> too_deep_path_;
  std::optional<std::string> error_;
  std::size_t error_position_ = 0;
};

// "invalid JSON at line L, column C: what" from a SAX error of nlohmann::json.
inline std::string DescribeJsonError(const std::string& text, std::size_t position,
                                     const std::string& what) {
  // Drop the "[json.exception.parse_error.101] " tag.
  const size_t tag_end = what.find("] ");
  std::string message = tag_end == std::string::npos ? what : what.substr(tag_end + 2);
  const std::string prefix = "parse error at ";
  if (message.rfind(prefix, 0) == 0) return "invalid JSON at " + message.substr(prefix.size());
  // Other errors (a number too large for a double) carry only a byte offset.
  const size_t end = std::min(position, text.size());
  const size_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
  const size_t line_start = text.rfind('\n', end == 0 ? 0 : end - 1);
  const size_t column = line_start == std::string::npos || end == 0 ? end : end - line_start - 1;
  if (message.find("overflow") != std::string::npos) message += " (numbers must be finite)";
  return "invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
         ": " + message;
}

// Line and column (1-based) of byte `offset` of `text`.
inline std::string LineColumn(const std::string& text, std::size_t offset) {
  const size_t end = std::min(offset, text.size());
  const size_t line = 1 + std::count(text.begin(), text.begin() + end, '\n');
  const size_t line_start = end == 0 ? std::string::npos : text.rfind('\n', end - 1);
  const size_t column = line_start == std::string::npos ? end + 1 : end - line_start;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// Parses the JSON text of `file`: syntax first (with line and column; a NUL
// byte, which nlohmann::json would take for the end of the text and so
// accept a valid document followed by junk, is an error), then nesting depth
// and repeated keys (with their JSON path).
inline json ParseJsonText(const std::string& text, const std::string& file) {
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    throw InputError(file, "",
                     "invalid JSON at " + LineColumn(text, nul) +
                         ": a NUL byte (a JSON text has none; is this a binary file?)");
  SyntaxChecker checker;
  if (!json::sax_parse(text, &checker)) {
    if (checker.duplicate_path()) {
      throw InputError(file, *checker.duplicate_path(), "duplicate key in one object");
    }
    if (checker.too_deep_path()) {
      throw InputError(
          file, *checker.too_deep_path(),
          "nested more than " + std::to_string(kMaxJsonDepth) + " arrays or objects deep");
    }
    throw InputError(
        file, "", DescribeJsonError(text, checker.error_position(), checker.error().value_or("")));
  }
  return json::parse(text);
}

// Reads the file at `path` (ReadInputFile: a regular file of at most
// `max_size` bytes) and parses it (ParseJsonText).
inline json ReadJsonFile(const std::string& path, std::uint64_t max_size) {
  return ParseJsonText(ReadInputFile(path, max_size), path);
}

}  // namespace cairn::io_internal

#include "cairn/io/scene_reader.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "cairn/core/error.h"

namespace cairn {
namespace {

using nlohmann::json;

std::string Child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string Index(const std::string& path, size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

std::string Num(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

std::string Point(const Vector2& p) { return "(" + Num(p.x()) + ", " + Num(p.y()) + ")"; }

std::string JoinKeys(std::initializer_list<const char*> keys) {
  std::string out;
  for (const char* k : keys) out += (out.empty() ? "" : ", ") + std::string(k);
  return out;
}

// The keys of each level of format version 1.
constexpr std::initializer_list<const char*> kSceneKeys = {
    "cairn", "name", "gravity", "friction", "friction_pairs", "tolerance", "parts", "fixtures"};
constexpr std::initializer_list<const char*> kPartKeys = {"name",    "fixed", "density",    "mass",
                                                          "polygon", "box",   "polyhedron", "mesh"};
constexpr std::initializer_list<const char*> kBoxKeys = {"min", "max"};
constexpr std::initializer_list<const char*> kPairKeys = {"parts", "mu"};
constexpr std::initializer_list<const char*> kFixtureKeys = {"part", "point", "normal"};

// The shape keys of a part, and the dimension each makes.
constexpr std::initializer_list<const char*> kShapeKeys = {"polygon", "box", "polyhedron", "mesh"};

// Converts a parsed document to an AssemblyDef, checking structure and types
// on the way; the first fault throws an InputError with its JSON path.
class SceneParser {
 public:
  explicit SceneParser(const std::string& file) : file_(file) {}

  AssemblyDef Parse(const json& doc) const {
    if (!doc.is_object()) Fail("", "a scene must be a JSON object, not " + Article(doc));
    CheckVersion(doc);
    CheckKeys(doc, "", kSceneKeys);
    CheckDimension(doc);

    AssemblyDef def;
    if (doc.contains("name")) def.name = String(doc["name"], "name");
    if (doc.contains("gravity")) def.gravity = Vec2(doc["gravity"], "gravity");
    if (doc.contains("friction")) def.friction = Number(doc["friction"], "friction");
    if (doc.contains("tolerance")) {
      def.tolerance = Number(doc["tolerance"], "tolerance");
      if (def.tolerance <= 0)
        Fail("tolerance", "must be positive (got " + Num(def.tolerance) + ")");
    }
    const json& parts = Array(Require(doc, "parts", ""), "parts");
    if (parts.empty()) Fail("parts", "must list at least one part");
    for (size_t i = 0; i < parts.size(); ++i) {
      def.parts.push_back(ParsePart(parts[i], Index("parts", i)));
    }
    if (doc.contains("friction_pairs")) {
      const json& pairs = Array(doc["friction_pairs"], "friction_pairs");
      for (size_t i = 0; i < pairs.size(); ++i) {
        def.friction_pairs.push_back(ParsePair(pairs[i], Index("friction_pairs", i)));
      }
    }
    if (doc.contains("fixtures")) {
      const json& fixtures = Array(doc["fixtures"], "fixtures");
      for (size_t i = 0; i < fixtures.size(); ++i) {
        def.fixtures.push_back(ParseFixture(fixtures[i], Index("fixtures", i)));
      }
    }
    return def;
  }

 private:
  [[noreturn]] void Fail(const std::string& path, const std::string& message) const {
    throw InputError(file_, path, message);
  }

  static std::string Article(const json& j) {
    const std::string t = j.type_name();
    return (t == "array" || t == "object" ? "an " : "a ") + t;
  }

  // The format version comes first: a later version may mean other keys.
  void CheckVersion(const json& doc) const {
    if (!doc.contains("cairn")) {
      Fail("cairn", "required key is missing (the scene format version: 1)");
    }
    const json& v = doc["cairn"];
    if (!v.is_number()) Fail("cairn", "must be the format version number 1, not " + Article(v));
    if (v.get<double>() != 1.0) {
      Fail("cairn", "unsupported format version " + v.dump() + " (this version reads version 1)");
    }
  }

  void CheckKeys(const json& obj, const std::string& path,
                 std::initializer_list<const char*> known) const {
    for (const auto& [key, value] : obj.items()) {
      if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) {
        Fail(Child(path, key), "unknown key (expected one of: " + JoinKeys(known) + ")");
      }
    }
  }

  // The dimension of a part's shape (2 or 3) and its key, when it can be told.
  static std::optional<std::pair<int, std::string>> ShapeDimension(const json& part) {
    if (!part.is_object()) return std::nullopt;
    int count = 0;
    std::optional<std::pair<int, std::string>> found;
    for (const char* key : kShapeKeys) {
      if (!part.contains(key)) continue;
      ++count;
      const std::string k = key;
      if (k == "polygon") {
        found = {2, k};
      } else if (k == "box") {
        const json& box = part[key];
        if (box.is_object() && box.contains("min") && box["min"].is_array() &&
            (box["min"].size() == 2 || box["min"].size() == 3)) {
          found = {static_cast<int>(box["min"].size()), k};
        }
      } else {
        found = {3, k};
      }
    }
    return count == 1 ? found : std::nullopt;
  }

  // A scene is 2-D or 3-D as its shapes are; 3-D is for a later version.
  void CheckDimension(const json& doc) const {
    if (!doc.contains("parts") || !doc["parts"].is_array()) return;
    const json& parts = doc["parts"];
    std::optional<size_t> first;
    int dim = 0;
    for (size_t i = 0; i < parts.size(); ++i) {
      const auto shape = ShapeDimension(parts[i]);
      if (!shape) continue;
      if (!first) {
        first = i;
        dim = shape->first;
      } else if (shape->first != dim) {
        Fail(Child(Index("parts", i), shape->second),
             "mixes 2-D and 3-D shapes (this part is " + std::to_string(shape->first) + "-D, " +
                 Index("parts", *first) + " is " + std::to_string(dim) + "-D)");
      }
    }
    if (first && dim == 3) {
      const std::string key = ShapeDimension(parts[*first])->second;
      Fail(Child(Index("parts", *first), key),
           "3-D scenes are not supported by this version of Cairn yet (2-D polygons and boxes "
           "only)");
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

  PartDef ParsePart(const json& j, const std::string& path) const {
    Object(j, path);
    CheckKeys(j, path, kPartKeys);
    PartDef part;
    part.name = String(Require(j, "name", path), Child(path, "name"));
    if (j.contains("fixed")) part.fixed = Bool(j["fixed"], Child(path, "fixed"));
    if (j.contains("density")) part.density = Number(j["density"], Child(path, "density"));
    if (j.contains("mass")) part.mass = Number(j["mass"], Child(path, "mass"));

    // Exactly one shape.
    std::vector<std::string> shapes;
    for (const char* key : kShapeKeys) {
      if (j.contains(key)) shapes.push_back(key);
    }
    if (shapes.empty()) Fail(path, "missing a shape: give one of polygon, box");
    if (shapes.size() > 1) {
      Fail(Child(path, shapes[1]),
           "a part has exactly one shape, but this one also has " + shapes[0]);
    }
    if (shapes[0] == "polygon") {
      const std::string poly_path = Child(path, "polygon");
      const json& poly = Array(j["polygon"], poly_path);
      for (size_t k = 0; k < poly.size(); ++k) {
        part.polygon.push_back(Vec2(poly[k], Index(poly_path, k)));
      }
    } else {
      // A box (2-D here: CheckDimension has rejected 3-D shapes).
      const std::string box_path = Child(path, "box");
      const json& box = Object(j["box"], box_path);
      CheckKeys(box, box_path, kBoxKeys);
      const Vector2 lo = Vec2(Require(box, "min", box_path), Child(box_path, "min"));
      const Vector2 hi = Vec2(Require(box, "max", box_path), Child(box_path, "max"));
      if (!(lo.x() < hi.x() && lo.y() < hi.y())) {
        Fail(box_path,
             "min " + Point(lo) + " must be less than max " + Point(hi) + " in both coordinates");
      }
      part.polygon = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
    }
    return part;
  }

  FrictionPairDef ParsePair(const json& j, const std::string& path) const {
    Object(j, path);
    CheckKeys(j, path, kPairKeys);
    const std::string parts_path = Child(path, "parts");
    const json& names = Array(Require(j, "parts", path), parts_path);
    if (names.size() != 2) {
      Fail(parts_path, "must name exactly 2 parts, not " + std::to_string(names.size()));
    }
    FrictionPairDef pair;
    pair.part_a = String(names[0], Index(parts_path, 0));
    pair.part_b = String(names[1], Index(parts_path, 1));
    pair.mu = Number(Require(j, "mu", path), Child(path, "mu"));
    return pair;
  }

  FixtureDef ParseFixture(const json& j, const std::string& path) const {
    Object(j, path);
    CheckKeys(j, path, kFixtureKeys);
    FixtureDef fixture;
    fixture.part = String(Require(j, "part", path), Child(path, "part"));
    fixture.point = Vec2(Require(j, "point", path), Child(path, "point"));
    fixture.normal = Vec2(Require(j, "normal", path), Child(path, "normal"));
    return fixture;
  }

  const std::string& file_;
};

// A SAX pass over the text that builds nothing: it finds syntax errors and
// number overflows (with their position) and keys repeated within one object
// (nlohmann::json would silently keep the last), with their JSON path.
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
    return true;
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
    return true;
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
  const std::optional<std::string>& error() const { return error_; }
  std::size_t error_position() const { return error_position_; }

 private:
  struct Frame {
    bool array = false;
    size_t count = 0;  // elements seen (arrays)
    std::string key;   // current key (objects)
    std::set<std::string> keys;
  };

  // Counts an element of the enclosing array.
  bool Value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().count;
    return true;
  }

  std::string Path() const {
    std::string path;
    for (const Frame& f : frames_) {
      path = f.array ? Index(path, f.count - 1) : Child(path, f.key);
    }
    return path;
  }

  std::vector<Frame> frames_;
  std::optional<std::string> duplicate_path_;
  std::optional<std::string> error_;
  std::size_t error_position_ = 0;
};

// "invalid JSON at line L, column C: what" from a SAX error of nlohmann::json.
std::string DescribeJsonError(const std::string& text, std::size_t position,
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

}  // namespace

AssemblyDef ParseSceneJson(const nlohmann::json& doc, const std::string& file) {
  return SceneParser(file).Parse(doc);
}

AssemblyDef ReadSceneDef(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the file for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();

  // Syntax first, then the document.
  SyntaxChecker checker;
  if (!json::sax_parse(text, &checker)) {
    if (checker.duplicate_path()) {
      throw InputError(path, *checker.duplicate_path(), "duplicate key in one object");
    }
    throw InputError(
        path, "", DescribeJsonError(text, checker.error_position(), checker.error().value_or("")));
  }
  return ParseSceneJson(json::parse(text), path);
}

Assembly ReadScene(const std::string& path) { return Assembly::Create(ReadSceneDef(path), path); }

}  // namespace cairn

#include "cairn/io/scene_reader.h"

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/json_checks.h"

namespace cairn {
namespace {

using io_internal::Child;
using io_internal::Index;
using io_internal::Num;
using io_internal::Point;
using nlohmann::json;

// The keys of each level of format version 1.
constexpr std::initializer_list<const char*> kSceneKeys = {
    "cairn", "name", "gravity", "friction", "friction_pairs", "tolerance", "parts", "fixtures"};
constexpr std::initializer_list<const char*> kPartKeys = {
    "name", "fixed", "tool", "density", "mass", "polygon", "box", "polyhedron", "mesh"};
constexpr std::initializer_list<const char*> kBoxKeys = {"min", "max"};
constexpr std::initializer_list<const char*> kPairKeys = {"parts", "mu"};
constexpr std::initializer_list<const char*> kFixtureKeys = {"part", "point", "normal"};

// The shape keys of a part, and the dimension each makes.
constexpr std::initializer_list<const char*> kShapeKeys = {"polygon", "box", "polyhedron", "mesh"};

// Converts a parsed document to an AssemblyDef, checking structure and types
// on the way; the first fault throws an InputError with its JSON path.
class SceneParser : private io_internal::JsonChecker {
 public:
  explicit SceneParser(const std::string& file) : JsonChecker(file) {}

  AssemblyDef Parse(const json& doc) const {
    if (!doc.is_object()) Fail("", "a scene must be a JSON object, not " + Article(doc));
    CheckVersion(doc, "cairn", "scene");
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

  PartDef ParsePart(const json& j, const std::string& path) const {
    Object(j, path);
    CheckKeys(j, path, kPartKeys);
    PartDef part;
    part.name = String(Require(j, "name", path), Child(path, "name"));
    if (j.contains("fixed")) part.fixed = Bool(j["fixed"], Child(path, "fixed"));
    if (j.contains("tool")) part.tool = Bool(j["tool"], Child(path, "tool"));
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
};

}  // namespace

AssemblyDef ParseSceneJson(const nlohmann::json& doc, const std::string& file) {
  return SceneParser(file).Parse(doc);
}

AssemblyDef ReadSceneDef(const std::string& path) {
  return ParseSceneJson(io_internal::ReadJsonFile(path), path);
}

Assembly ReadScene(const std::string& path) { return Assembly::Create(ReadSceneDef(path), path); }

}  // namespace cairn

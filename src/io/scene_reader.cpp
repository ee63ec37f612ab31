#include "cairn/io/scene_reader.h"

#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/io/mesh_reader.h"
#include "io/json_checks.h"

namespace cairn {
namespace {

using io_internal::Child;
using io_internal::Index;
using io_internal::Num;
using io_internal::Point;
using nlohmann::json;

// The keys of each level of format version 1.
constexpr std::initializer_list<const char*> kSceneKeys = {"cairn",
                                                           "name",
                                                           "gravity",
                                                           "friction",
                                                           "friction_pairs",
                                                           "tolerance",
                                                           "parts",
                                                           "fixtures",
                                                           "friction_directions",
                                                           "interfaces",
                                                           "overlap_allowance",
                                                           "overlap_depth"};
constexpr std::initializer_list<const char*> kPolyhedronKeys = {"vertices", "faces"};
constexpr std::initializer_list<const char*> kPartKeys = {
    "name", "fixed", "tool", "density", "mass", "polygon", "box", "polyhedron", "mesh"};
constexpr std::initializer_list<const char*> kBoxKeys = {"min", "max"};
constexpr std::initializer_list<const char*> kPairKeys = {"parts", "mu"};
constexpr std::initializer_list<const char*> kInterfaceKeys = {"parts", "normal", "points"};

// The shape keys of a part, and the dimension each makes.
constexpr std::initializer_list<const char*> kShapeKeys = {"polygon", "box", "polyhedron", "mesh"};

// Converts a parsed document to an AssemblyDef, checking structure and types
// on the way; the first fault throws an InputError with its JSON path.
class SceneParser : private io_internal::JsonChecker {
 public:
  SceneParser(const std::string& file, std::uint64_t max_input_size)
      : JsonChecker(file), file_(file), max_input_size_(max_input_size) {}

  AssemblyDef Parse(const json& doc) {
    if (!doc.is_object()) Fail("", "a scene must be a JSON object, not " + Article(doc));
    CheckVersion(doc, "cairn", "scene");
    CheckKeys(doc, "", kSceneKeys);
    dim_ = CheckDimension(doc);

    AssemblyDef def;
    if (doc.contains("name")) def.name = String(doc["name"], "name");
    if (doc.contains("gravity")) def.gravity = VecN(doc["gravity"], "gravity", dim_);
    if (doc.contains("friction")) def.friction = Number(doc["friction"], "friction");
    if (doc.contains("friction_directions")) {
      const json& d = doc["friction_directions"];
      if (!d.is_number_integer())
        Fail("friction_directions", "must be a whole number, not " + Article(d));
      if (dim_ != 3)
        Fail("friction_directions",
             "applies to 3-D scenes only (2-D friction has the two directions ±t)");
      const auto D = d.get<long long>();
      if (D < 3 || D > 64)
        Fail("friction_directions", "must be from 3 to 64 (got " + std::to_string(D) + ")");
      def.friction_directions = static_cast<int>(D);
    }
    if (doc.contains("tolerance")) {
      def.tolerance = Number(doc["tolerance"], "tolerance");
      if (def.tolerance <= 0)
        Fail("tolerance", "must be positive (got " + Num(def.tolerance) + ")");
    }
    if (doc.contains("overlap_allowance")) {
      def.overlap_allowance = Number(doc["overlap_allowance"], "overlap_allowance");
      if (def.overlap_allowance < 0)
        Fail("overlap_allowance", "must not be negative (got " + Num(def.overlap_allowance) + ")");
    }
    if (doc.contains("overlap_depth")) {
      def.overlap_depth = Number(doc["overlap_depth"], "overlap_depth");
      if (def.overlap_depth < 0)
        Fail("overlap_depth", "must not be negative (got " + Num(def.overlap_depth) + ")");
    }
    const json& parts = Array(Require(doc, "parts", ""), "parts");
    if (parts.empty()) Fail("parts", "must list at least one part");
    for (size_t i = 0; i < parts.size(); ++i) {
      def.parts.push_back(ParsePart(parts[i], i));
    }
    def.notes = notes_;
    if (doc.contains("friction_pairs")) {
      const json& pairs = Array(doc["friction_pairs"], "friction_pairs");
      for (size_t i = 0; i < pairs.size(); ++i) {
        def.friction_pairs.push_back(ParsePair(pairs[i], Index("friction_pairs", i)));
      }
    }
    if (doc.contains("fixtures")) {
      const json& fixtures = Array(doc["fixtures"], "fixtures");
      for (size_t i = 0; i < fixtures.size(); ++i) {
        def.fixtures.push_back(Fixture(fixtures[i], Index("fixtures", i), dim_));
      }
    }
    if (doc.contains("interfaces")) {
      if (dim_ != 3) Fail("interfaces", "interfaces are given in 3-D scenes only");
      const json& interfaces = Array(doc["interfaces"], "interfaces");
      for (size_t i = 0; i < interfaces.size(); ++i) {
        def.interfaces.push_back(ParseInterface(interfaces[i], Index("interfaces", i)));
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

  // The JSON path of parts[i] with its name when it has a readable one
  // (NamedPath): `parts[1] ("A")`.
  static std::string PartPath(const json& part, size_t i) {
    const bool named = part.is_object() && part.contains("name") && part["name"].is_string();
    return NamedPath(Index("parts", i), named ? part["name"].get<std::string>() : "");
  }

  // A scene is 2-D or 3-D as its shapes are (2 when none can be told yet).
  int CheckDimension(const json& doc) const {
    if (!doc.contains("parts") || !doc["parts"].is_array()) return 2;
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
        Fail(Child(PartPath(parts[i], i), shape->second),
             "mixes 2-D and 3-D shapes (this part is " + std::to_string(shape->first) + "-D, " +
                 PartPath(parts[*first], *first) + " is " + std::to_string(dim) + "-D)");
      }
    }
    return first ? dim : 2;
  }

  // parts[i]. Faults of the name are reported at `parts[i].name`; every
  // other at the part's named path `parts[i] ("A")`.
  PartDef ParsePart(const json& j, size_t i) const {
    const std::string bare = Index("parts", i);
    Object(j, bare);
    const std::string path = PartPath(j, i);
    CheckKeys(j, path, kPartKeys);
    PartDef part;
    part.name = String(Require(j, "name", bare), Child(bare, "name"));
    if (j.contains("fixed")) part.fixed = Bool(j["fixed"], Child(path, "fixed"));
    if (j.contains("tool")) part.tool = Bool(j["tool"], Child(path, "tool"));
    if (j.contains("density")) part.density = Number(j["density"], Child(path, "density"));
    if (j.contains("mass")) part.mass = Number(j["mass"], Child(path, "mass"));

    // Exactly one shape.
    std::vector<std::string> shapes;
    for (const char* key : kShapeKeys) {
      if (j.contains(key)) shapes.push_back(key);
    }
    if (shapes.empty()) Fail(path, "missing a shape: give one of polygon, box, polyhedron, mesh");
    if (shapes.size() > 1) {
      Fail(Child(path, shapes[1]),
           "a part has exactly one shape, but this one also has " + shapes[0]);
    }
    part.shape_key = shapes[0];
    if (dim_ == 3) {
      part.polyhedron = Parse3dShape(j, path, shapes[0]);
    } else if (shapes[0] == "polygon") {
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

  InterfaceDef ParseInterface(const json& j, const std::string& path) const {
    Object(j, path);
    CheckKeys(j, path, kInterfaceKeys);
    const std::string parts_path = Child(path, "parts");
    const json& names = Array(Require(j, "parts", path), parts_path);
    if (names.size() != 2) {
      Fail(parts_path, "must name exactly 2 parts, not " + std::to_string(names.size()));
    }
    InterfaceDef in;
    in.part_a = String(names[0], Index(parts_path, 0));
    in.part_b = String(names[1], Index(parts_path, 1));
    in.normal = VecN(Require(j, "normal", path), Child(path, "normal"), 3);
    const std::string points_path = Child(path, "points");
    const json& points = Array(Require(j, "points", path), points_path);
    for (size_t i = 0; i < points.size(); ++i)
      in.points.push_back(VecN(points[i], Index(points_path, i), 3));
    return in;
  }

  // A 3-D part's shape as vertices and faces: a `box` with 3-D corners, a
  // `polyhedron`, or a `mesh` file (relative to the scene file).
  PolyhedronDef Parse3dShape(const json& j, const std::string& path, const std::string& key) const {
    const std::string shape_path = Child(path, key);
    PolyhedronDef def;
    if (key == "box") {
      const json& box = Object(j["box"], shape_path);
      CheckKeys(box, shape_path, kBoxKeys);
      const Vector3 lo = VecN(Require(box, "min", shape_path), Child(shape_path, "min"), 3);
      const Vector3 hi = VecN(Require(box, "max", shape_path), Child(shape_path, "max"), 3);
      if (!(lo.array() < hi.array()).all()) {
        Fail(shape_path,
             "min " + Point(lo) + " must be less than max " + Point(hi) + " in every coordinate");
      }
      for (int k = 0; k < 8; ++k)
        def.vertices.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                                  k & 4 ? hi.z() : lo.z());
      // Outward (counter-clockwise seen from outside): -z, +z, -y, +y, -x, +x.
      def.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      return def;
    }
    if (key == "polygon") {
      Fail(shape_path, "a polygon is a 2-D shape; in a 3-D scene give box, polyhedron or mesh");
    }
    if (key == "polyhedron") {
      const json& poly = Object(j["polyhedron"], shape_path);
      CheckKeys(poly, shape_path, kPolyhedronKeys);
      const std::string v_path = Child(shape_path, "vertices");
      const json& vertices = Array(Require(poly, "vertices", shape_path), v_path);
      for (size_t k = 0; k < vertices.size(); ++k)
        def.vertices.push_back(VecN(vertices[k], Index(v_path, k), 3));
      if (def.vertices.size() < 4)
        Fail(v_path,
             "a polyhedron needs at least 4 vertices, not " + std::to_string(def.vertices.size()));
      const std::string f_path = Child(shape_path, "faces");
      const json& faces = Array(Require(poly, "faces", shape_path), f_path);
      for (size_t f = 0; f < faces.size(); ++f) {
        const std::string face_path = Index(f_path, f);
        const json& face = Array(faces[f], face_path);
        if (face.size() < 3)
          Fail(face_path, "a face needs at least 3 vertices, not " + std::to_string(face.size()));
        std::vector<int> ids;
        for (size_t k = 0; k < face.size(); ++k) {
          const json& id = face[k];
          if (!id.is_number_integer() || id.get<long long>() < 0 ||
              id.get<long long>() >= static_cast<long long>(def.vertices.size()))
            Fail(Index(face_path, k), "must be a vertex index from 0 to " +
                                          std::to_string(def.vertices.size() - 1) + ", not " +
                                          id.dump());
          ids.push_back(static_cast<int>(id.get<long long>()));
        }
        def.faces.push_back(std::move(ids));
      }
      return def;
    }
    // A mesh file, relative to the scene file's folder.
    const std::string name = String(j["mesh"], shape_path);
    const std::filesystem::path base = std::filesystem::path(file_).parent_path();
    const std::string mesh_file = (base / name).lexically_normal().string();
    try {
      MeshReadOptions options;
      options.max_input_size = max_input_size_;
      MeshMergeStats stats;
      PolyhedronDef mesh = ReadMesh(mesh_file, options, &stats);
      const std::string part =
          j.contains("name") && j["name"].is_string() ? j["name"].get<std::string>() : "";
      if (std::string note = MeshRepairNote(part, mesh_file, stats); !note.empty())
        notes_.push_back(std::move(note));
      return mesh;
    } catch (const InputError& e) {
      Fail(shape_path, "cannot read mesh '" + mesh_file + "': " + e.message());
    }
  }

  const std::string& file_;
  std::uint64_t max_input_size_;
  mutable std::vector<std::string> notes_;  // AssemblyDef::notes, as the meshes are read
  int dim_ = 2;
};

}  // namespace

AssemblyDef ParseSceneJson(const nlohmann::json& doc, const std::string& file,
                           std::uint64_t max_input_size) {
  return SceneParser(file, max_input_size).Parse(doc);
}

AssemblyDef ReadSceneDef(const std::string& path, std::uint64_t max_input_size) {
  return ParseSceneJson(io_internal::ReadJsonFile(path, max_input_size), path, max_input_size);
}

Assembly ReadScene(const std::string& path, std::uint64_t max_input_size) {
  return Assembly::Create(ReadSceneDef(path, max_input_size), path);
}

}  // namespace cairn

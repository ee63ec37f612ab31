#include "cairn/io/compas_reader.h"

#include <algorithm>
#include <cstddef>
#include <map>
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
using nlohmann::json;

// The value of a key made only of decimal digits (at most 18), else nullopt.
std::optional<long long> NumericKey(const std::string& key) {
  if (key.empty() || key.size() > 18) return std::nullopt;
  if (!std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  return std::stoll(key);
}

// COMPAS keys are strings of integers; nlohmann::json keeps object keys in
// text order ("10" < "9"). This is the order Cairn uses instead: numeric keys
// by value, then the others as text.
bool KeyLess(const std::string& a, const std::string& b) {
  const std::optional<long long> na = NumericKey(a);
  const std::optional<long long> nb = NumericKey(b);
  if (na && nb) return *na != *nb ? *na < *nb : a < b;  // "01" and "1" differ
  if (na || nb) return na.has_value();
  return a < b;
}

// The keys of `obj` in KeyLess order.
std::vector<std::string> SortedKeys(const json& obj) {
  std::vector<std::string> keys;
  keys.reserve(obj.size());
  for (const auto& item : obj.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end(), KeyLess);
  return keys;
}

// True when `dtype` ("compas_cra.datastructures/CRA_Assembly") names an
// assembly class: its class name ends in "Assembly".
bool IsAssemblyType(const std::string& dtype) {
  const std::string cls = dtype.substr(dtype.rfind('/') + 1);
  const std::string suffix = "Assembly";
  return cls.size() >= suffix.size() &&
         cls.compare(cls.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Converts a parsed COMPAS document to its blocks; the first fault throws an
// InputError with its JSON path.
class CompasParser : private io_internal::JsonChecker {
 public:
  explicit CompasParser(const std::string& file) : JsonChecker(file) {}

  CompasAssembly Parse(const json& doc) const {
    if (!doc.is_object()) {
      Fail("", "a COMPAS assembly must be a JSON object, not " + Article(doc));
    }
    if (doc.contains("dtype")) {
      const std::string dtype = String(doc["dtype"], "dtype");
      if (!IsAssemblyType(dtype)) {
        Fail("dtype", "\"" + dtype + "\" is not a COMPAS assembly (expected a type such as " +
                          "compas_assembly.datastructures/Assembly)");
      }
    } else if (!doc.contains("graph") && !doc.contains("node")) {
      Fail("",
           "not a COMPAS assembly: expected a \"dtype\" naming an Assembly, or assembly data "
           "with a \"graph\" or \"node\" key");
    }
    std::string path;
    const json& data = Unwrap(doc, &path);

    CompasAssembly out;
    if (data.contains("attributes") && data["attributes"].is_object()) {
      const json& attributes = data["attributes"];
      if (attributes.contains("name") && attributes["name"].is_string()) {
        out.name = attributes["name"].get<std::string>();
      }
    }

    // COMPAS 2 assemblies hold their graph under "graph"; a COMPAS 1
    // assembly is itself the graph (a Network).
    const json* graph = &data;
    std::string graph_path = path;
    if (data.contains("graph")) {
      graph_path = Child(path, "graph");
      graph = &Unwrap(Object(data["graph"], graph_path), &graph_path);
    }
    const std::string nodes_path = Child(graph_path, "node");
    const json& nodes = Object(Require(*graph, "node", graph_path), nodes_path);
    if (nodes.empty()) Fail(nodes_path, "the assembly has no blocks");

    // Default node attributes: "default_node_attributes" (COMPAS 2) or
    // "dna" (COMPAS 1) apply to nodes that lack the key.
    const json* defaults = nullptr;
    std::string defaults_path;
    for (const char* key : {"default_node_attributes", "dna"}) {
      if (graph->contains(key) && !(*graph)[key].is_null()) {
        defaults_path = Child(graph_path, key);
        defaults = &Object((*graph)[key], defaults_path);
        break;
      }
    }

    for (const std::string& key : SortedKeys(nodes)) {
      out.blocks.push_back(
          ParseNode(nodes[key], key, Child(nodes_path, key), defaults, defaults_path));
    }
    return out;
  }

 private:
  // The payload of a serialized COMPAS object: `data` (COMPAS 2) or `value`
  // (COMPAS 1) of an object with a "dtype"; the object itself otherwise.
  // `path` is the object's path on entry and the payload's on return.
  const json& Unwrap(const json& obj, std::string* path) const {
    if (!obj.contains("dtype")) return obj;
    for (const char* key : {"data", "value"}) {
      if (obj.contains(key)) {
        *path = Child(*path, key);
        return Object(obj[key], *path);
      }
    }
    Fail(Child(*path, "data"), "required key is missing (the data of the \"dtype\" object)");
  }

  // An attribute of a node, or its default, or nullptr when neither is set
  // (null counts as unset); `where` receives the JSON path of the value used.
  static const json* Attribute(const json& node, const std::string& node_path, const json* defaults,
                               const std::string& defaults_path, const char* key,
                               std::string* where) {
    if (node.contains(key) && !node[key].is_null()) {
      *where = Child(node_path, key);
      return &node[key];
    }
    if (defaults != nullptr && defaults->contains(key) && !(*defaults)[key].is_null()) {
      *where = Child(defaults_path, key);
      return &(*defaults)[key];
    }
    return nullptr;
  }

  CompasBlock ParseNode(const json& node, const std::string& key, const std::string& path,
                        const json* defaults, const std::string& defaults_path) const {
    Object(node, path);
    CompasBlock block;
    block.name = key;

    std::string where;
    if (const json* support =
            Attribute(node, path, defaults, defaults_path, "is_support", &where)) {
      block.is_support = Bool(*support, where);
    }
    if (const json* density = Attribute(node, path, defaults, defaults_path, "density", &where)) {
      const double rho = Number(*density, where);
      if (rho <= 0) Fail(where, "must be positive (got " + Num(rho) + ")");
      block.density = rho;
    }

    std::string mesh_path = Child(path, "block");
    const json& mesh_json = Require(node, "block", path);
    if (mesh_json.is_null()) Fail(mesh_path, "the node has no block (null)");
    const json& mesh = Unwrap(Object(mesh_json, mesh_path), &mesh_path);
    block.shape = ParseMesh(mesh, mesh_path);
    return block;
  }

  // A COMPAS mesh: "vertex" {key: {"x", "y", "z"}} and "face" {key: [vertex
  // keys]}. Vertices are renumbered 0..n−1 in KeyLess order of their keys.
  PolyhedronDef ParseMesh(const json& mesh, const std::string& path) const {
    const std::string vertex_path = Child(path, "vertex");
    const std::string face_path = Child(path, "face");
    const json& vertices = Object(Require(mesh, "vertex", path), vertex_path);
    const json& faces = Object(Require(mesh, "face", path), face_path);
    if (vertices.size() < 4) {
      Fail(vertex_path,
           "a block needs at least 4 vertices, not " + std::to_string(vertices.size()));
    }
    if (faces.size() < 4) {
      Fail(face_path, "a block needs at least 4 faces, not " + std::to_string(faces.size()));
    }

    PolyhedronDef def;
    std::map<std::string, int> index;  // vertex key -> 0..n−1
    for (const std::string& key : SortedKeys(vertices)) {
      const std::string v_path = Child(vertex_path, key);
      const json& v = Object(vertices[key], v_path);
      const double x = Number(Require(v, "x", v_path), Child(v_path, "x"));
      const double y = Number(Require(v, "y", v_path), Child(v_path, "y"));
      const double z = Number(Require(v, "z", v_path), Child(v_path, "z"));
      index.emplace(key, static_cast<int>(def.vertices.size()));
      def.vertices.emplace_back(x, y, z);
    }

    for (const std::string& key : SortedKeys(faces)) {
      const std::string f_path = Child(face_path, key);
      const json& face = faces[key];
      if (!face.is_array()) {
        Fail(f_path, "must be an array of vertex keys, not " + Article(face));
      }
      if (face.size() < 3) {
        Fail(f_path, "a face needs at least 3 vertices, not " + std::to_string(face.size()));
      }
      std::vector<int> polygon;
      polygon.reserve(face.size());
      for (size_t i = 0; i < face.size(); ++i) {
        const std::string i_path = Index(f_path, i);
        const json& ref = face[i];
        std::string vkey;
        if (ref.is_number_unsigned()) {
          vkey = std::to_string(ref.get<unsigned long long>());
        } else if (ref.is_number_integer()) {
          vkey = std::to_string(ref.get<long long>());
        } else if (ref.is_string()) {
          vkey = ref.get<std::string>();
        } else {
          Fail(i_path, "must be a vertex key (an integer), not " + Article(ref) +
                           (ref.is_number() ? " with a fraction" : ""));
        }
        const auto it = index.find(vkey);
        if (it == index.end()) {
          Fail(i_path,
               "vertex " + vkey + " does not exist (it is not a key of " + vertex_path + ")");
        }
        polygon.push_back(it->second);
      }
      def.faces.push_back(std::move(polygon));
    }
    return def;
  }
};

}  // namespace

CompasAssembly ParseCompasAssembly(const json& doc, const std::string& file) {
  return CompasParser(file).Parse(doc);
}

CompasAssembly ReadCompasAssembly(const std::string& path) {
  return ParseCompasAssembly(io_internal::ReadJsonFile(path), path);
}

}  // namespace cairn

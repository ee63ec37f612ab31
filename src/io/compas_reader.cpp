#include "cairn/io/compas_reader.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/core/tolerances.h"
#include "io/json_checks.h"

namespace cairn {
namespace {

using io_internal::Child;
using io_internal::Index;
using io_internal::Num;
using io_internal::Point;
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
    out.interfaces = ParseEdges(*graph, graph_path, nodes, nodes_path);
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

  // The node `key` at `node_path`. Faults inside it are reported at its path
  // named by its key, the block's name: `data.graph.data.node.3 ("3").block`.
  CompasBlock ParseNode(const json& node, const std::string& key, const std::string& node_path,
                        const json* defaults, const std::string& defaults_path) const {
    const std::string path = NamedPath(node_path, key);
    Object(node, path);
    CompasBlock block;
    block.name = key;
    block.path = node_path;

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
    block.mesh_path = node_path + mesh_path.substr(path.size());  // the bare JSON path
    block.shape = ParseMesh(mesh, mesh_path, &block.face_keys);
    return block;
  }

  // ---- Stored interfaces -------------------------------------------------

  // The interfaces stored on the edges of the graph ("edge": {u: {v: attrs}}),
  // u then v in KeyLess order. An edge's attributes hold them as
  // "interfaces": [Interface, ...] (compas_assembly 0.6 and later, compas_cra)
  // or as "interface_points" and "interface_uvw" (compas_assembly's COMPAS 1
  // Network); an edge with neither (absent, null or []) is skipped.
  std::vector<CompasInterface> ParseEdges(const json& graph, const std::string& graph_path,
                                          const json& nodes, const std::string& nodes_path) const {
    std::vector<CompasInterface> out;
    if (!graph.contains("edge") || graph["edge"].is_null()) return out;
    const std::string edges_path = Child(graph_path, "edge");
    const json& edges = Object(graph["edge"], edges_path);
    for (const std::string& u : SortedKeys(edges)) {
      const std::string u_path = Child(edges_path, u);
      if (edges[u].is_null()) continue;
      const json& row = Object(edges[u], u_path);
      for (const std::string& v : SortedKeys(row)) {
        const std::string e_path = Child(u_path, v);
        if (row[v].is_null()) continue;
        const json& attr = Object(row[v], e_path);
        const json* listed = nullptr;
        if (attr.contains("interfaces") && !attr["interfaces"].is_null()) {
          listed = &Array(attr["interfaces"], Child(e_path, "interfaces"));
          if (listed->empty()) listed = nullptr;
        }
        const bool legacy =
            attr.contains("interface_points") && !attr["interface_points"].is_null();
        if (listed == nullptr && !legacy) continue;

        for (const std::string& key : {u, v}) {
          if (!nodes.contains(key)) {
            Fail(e_path, "block " + EscapedName(key) + " does not exist (it is not a key of " +
                             nodes_path + ")");
          }
        }
        if (u == v) Fail(e_path, "an interface between block " + EscapedName(u) + " and itself");

        if (listed != nullptr) {
          const std::string list_path = Child(e_path, "interfaces");
          for (size_t i = 0; i < listed->size(); ++i) {
            out.push_back(ParseInterface((*listed)[i], Index(list_path, i), u, v));
          }
        }
        if (legacy) out.push_back(ParseLegacyInterface(attr, e_path, u, v));
      }
    }
    return out;
  }

  // A point or vector: [x, y, z], or a serialized COMPAS Point or Vector
  // ({"dtype": "compas.geometry/Point", "data" (COMPAS 1: "value"): [x, y, z]}).
  Vector3 Xyz(const json& j, const std::string& path) const {
    std::string p = path;
    const json* value = &j;
    if (j.is_object() && j.contains("dtype")) {
      const char* key = j.contains("data") ? "data" : j.contains("value") ? "value" : nullptr;
      if (key == nullptr) {
        Fail(Child(path, "data"), "required key is missing (the data of the \"dtype\" object)");
      }
      p = Child(path, key);
      value = &j[key];
    }
    if (!value->is_array()) {
      Fail(p, "must be an array of 3 numbers [x, y, z], not " + Article(*value));
    }
    if (value->size() != 3) {
      Fail(p, "must have 3 numbers [x, y, z], not " + std::to_string(value->size()));
    }
    return Vector3(Coordinate((*value)[0], Index(p, 0)), Coordinate((*value)[1], Index(p, 1)),
                   Coordinate((*value)[2], Index(p, 2)));
  }

  // The polygon of an interface: an array of at least 3 points.
  std::vector<Vector3> InterfacePoints(const json& j, const std::string& path) const {
    if (!j.is_array()) Fail(path, "must be an array of points [x, y, z], not " + Article(j));
    if (j.size() < 3) {
      Fail(path, "an interface needs at least 3 points, not " + std::to_string(j.size()));
    }
    std::vector<Vector3> points;
    points.reserve(j.size());
    for (size_t i = 0; i < j.size(); ++i) points.push_back(Xyz(j[i], Index(path, i)));
    return points;
  }

  // An Interface object ({"dtype": ".../Interface", "data": {...}}, COMPAS 1
  // "value", or its bare data): "points" and "frame" {"point", "xaxis",
  // "yaxis"} (itself a serialized Frame or its bare data), normal xaxis ×
  // yaxis. Other keys ("size", "forces", "mesh", "type") are ignored.
  CompasInterface ParseInterface(const json& j, const std::string& where, const std::string& u,
                                 const std::string& v) const {
    std::string path = where;
    const json& data = Unwrap(Object(j, path), &path);
    const std::string points_path = Child(path, "points");
    std::vector<Vector3> points = InterfacePoints(Require(data, "points", path), points_path);
    std::string frame_path = Child(path, "frame");
    const json& frame = Unwrap(Object(Require(data, "frame", path), frame_path), &frame_path);
    const Vector3 x = Xyz(Require(frame, "xaxis", frame_path), Child(frame_path, "xaxis"));
    const Vector3 y = Xyz(Require(frame, "yaxis", frame_path), Child(frame_path, "yaxis"));
    return Finish(u, v, std::move(points), x.cross(y), frame_path,
                  "the cross product of the frame's xaxis and yaxis", points_path, where);
  }

  // compas_assembly's COMPAS 1 edge attributes: "interface_points" and
  // "interface_uvw" [u, v, w], w the normal ("interface_origin", "_type",
  // "_size", "_forces" are ignored).
  CompasInterface ParseLegacyInterface(const json& attr, const std::string& e_path,
                                       const std::string& u, const std::string& v) const {
    const std::string points_path = Child(e_path, "interface_points");
    std::vector<Vector3> points = InterfacePoints(attr["interface_points"], points_path);
    const std::string uvw_path = Child(e_path, "interface_uvw");
    const json& uvw = Require(attr, "interface_uvw", e_path);
    if (!uvw.is_array()) {
      Fail(uvw_path, "must be the interface frame [u, v, w] (3 vectors), not " + Article(uvw));
    }
    if (uvw.size() != 3) {
      Fail(uvw_path,
           "must be the interface frame [u, v, w] (3 vectors), not " + std::to_string(uvw.size()));
    }
    const std::string w_path = Index(uvw_path, 2);
    return Finish(u, v, std::move(points), Xyz(uvw[2], w_path), w_path, "interface_uvw[2]",
                  points_path, e_path);
  }

  // Validates the normal and the planarity and turns the file's normal (from
  // u into v) into Cairn's (from b = v into a = u).
  CompasInterface Finish(const std::string& u, const std::string& v, std::vector<Vector3> points,
                         const Vector3& file_normal, const std::string& normal_path,
                         const std::string& normal_what, const std::string& points_path,
                         const std::string& where) const {
    // Scale first: a cross product of large finite axes may overflow.
    if (!file_normal.allFinite()) {
      Fail(normal_path, "the interface normal (" + normal_what + ") is not finite");
    }
    const double scale = file_normal.cwiseAbs().maxCoeff();
    if (scale == 0) {
      Fail(normal_path, "the interface normal (" + normal_what + ") is zero");
    }
    const Vector3 n = (file_normal / scale).normalized();

    Vector3 lo = points[0], hi = points[0], center = Vector3::Zero();
    for (const Vector3& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
      center += p;
    }
    center /= static_cast<double>(points.size());
    const double size = (hi - lo).norm();
    if (!(size > 0)) Fail(points_path, "the points of the interface all coincide");
    size_t worst = 0;
    double off = -1;
    for (size_t i = 0; i < points.size(); ++i) {
      const double d = std::abs(n.dot(points[i] - center));
      if (d > off) off = d, worst = i;
    }
    if (off > kCompasInterfacePlanarity * size) {
      Fail(Index(points_path, worst),
           "the point is " + Num(off) + " off the plane of the interface (through the points' " +
               "centroid, normal " + Point(n) + " = " + normal_what + "), more than " +
               Num(kCompasInterfacePlanarity) + " of its size " + Num(size));
    }

    CompasInterface out;
    out.a = u;
    out.b = v;
    out.points = std::move(points);
    out.normal = -n;
    out.where = where;
    return out;
  }

  // A COMPAS mesh: "vertex" {key: {"x", "y", "z"}} and "face" {key: [vertex
  // keys]}. Vertices are renumbered 0..n−1 in KeyLess order of their keys;
  // faces are listed in KeyLess order of theirs, which go to `face_keys`.
  PolyhedronDef ParseMesh(const json& mesh, const std::string& path,
                          std::vector<std::string>* face_keys) const {
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
      const double x = Coordinate(Require(v, "x", v_path), Child(v_path, "x"));
      const double y = Coordinate(Require(v, "y", v_path), Child(v_path, "y"));
      const double z = Coordinate(Require(v, "z", v_path), Child(v_path, "z"));
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
          Fail(i_path, "vertex " + EscapedName(vkey) + " does not exist (it is not a key of " +
                           vertex_path + ")");
        }
        polygon.push_back(it->second);
      }
      def.faces.push_back(std::move(polygon));
      face_keys->push_back(key);
    }
    return def;
  }
};

// ---- The model: the planarity policy and validation of each block ----------

// The mean plane of a face: its centroid and Newell's unit normal (zero when
// the face has no area), computed as Polyhedron::Check computes them so that
// "planar" means the same here and there.
struct FacePlane {
  Vector3 center{0, 0, 0};
  Vector3 normal{0, 0, 0};
  double off = 0;  // the largest distance of a vertex from the plane (length)
};

FacePlane MeanPlane(const std::vector<Vector3>& x, const std::vector<int>& face) {
  FacePlane plane;
  for (int v : face) plane.center += x[v];
  plane.center /= static_cast<double>(face.size());
  Vector3 n = Vector3::Zero();
  const size_t m = face.size();
  for (size_t i = 0; i < m; ++i) {
    const Vector3 p = x[face[i]] - plane.center;
    const Vector3 q = x[face[(i + 1) % m]] - plane.center;
    n.x() += (p.y() - q.y()) * (p.z() + q.z());
    n.y() += (p.z() - q.z()) * (p.x() + q.x());
    n.z() += (p.x() - q.x()) * (p.y() + q.y());
  }
  if (n.norm() == 0) return plane;  // degenerate: left to Polyhedron::Check
  plane.normal = n.normalized();
  for (int v : face)
    plane.off = std::max(plane.off, std::abs(plane.normal.dot(x[v] - plane.center)));
  return plane;
}

// Lexicographic order of points: a tie-break that depends on the geometry
// only, not on how a face is numbered or oriented.
bool PointLess(const Vector3& a, const Vector3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

// Splits a non-planar face into triangles: ear clipping of its projection on
// the mean plane, each time cutting off the ear whose new diagonal is the
// shortest in 3-D (ties broken by the diagonal's end points). A face and its
// twin on the neighbouring block (the same points, the other way round) have
// the same ears, so they are split along the same diagonals and still match.
// The triangles keep the face's orientation. Empty when the projection is not
// a simple polygon (no ear can be cut).
std::vector<std::array<int, 3>> SplitFace(const std::vector<Vector3>& x,
                                          const std::vector<int>& face, const FacePlane& plane) {
  // (u, w, n) right-handed: the projection runs counter-clockwise.
  const Vector3 u = plane.normal.unitOrthogonal();
  const Vector3 w = plane.normal.cross(u);
  std::vector<Vector2> p;
  double scale = 0;
  for (int v : face) {
    const Vector3 d = x[v] - plane.center;
    p.emplace_back(u.dot(d), w.dot(d));
    scale = std::max(scale, d.norm());
  }
  // Purely numerical decisions (a straight angle, a point on a diagonal):
  // 1e-12 of the face's size.
  const double eps = numeric::kRoundoff * scale * scale;
  const auto cross = [&](int a, int b, int c) {
    return (p[b] - p[a]).x() * (p[c] - p[a]).y() - (p[b] - p[a]).y() * (p[c] - p[a]).x();
  };
  std::vector<int> idx(face.size());
  for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<int>(i);
  std::vector<std::array<int, 3>> out;
  while (idx.size() > 3) {
    const size_t m = idx.size();
    std::optional<size_t> best;
    double best_len = 0;
    std::array<Vector3, 2> best_ends;
    for (size_t k = 0; k < m; ++k) {
      const int a = idx[(k + m - 1) % m], b = idx[k], c = idx[(k + 1) % m];
      if (cross(a, b, c) <= eps) continue;  // not strictly convex
      bool empty = true;                    // no other vertex inside or on the ear
      for (int o : idx) {
        if (o == a || o == b || o == c) continue;
        if (cross(a, b, o) >= -eps && cross(b, c, o) >= -eps && cross(c, a, o) >= -eps) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      const double len = (x[face[c]] - x[face[a]]).norm();
      std::array<Vector3, 2> ends = {x[face[a]], x[face[c]]};
      if (PointLess(ends[1], ends[0])) std::swap(ends[0], ends[1]);
      const bool better = !best || len < best_len ||
                          (len == best_len &&
                           std::lexicographical_compare(
                               ends.begin(), ends.end(), best_ends.begin(), best_ends.end(),
                               [](const Vector3& l, const Vector3& r) { return PointLess(l, r); }));
      if (better) {
        best = k;
        best_len = len;
        best_ends = ends;
      }
    }
    if (!best) return {};
    const size_t k = *best;
    out.push_back({face[idx[(k + m - 1) % m]], face[idx[k]], face[idx[(k + 1) % m]]});
    idx.erase(idx.begin() + static_cast<std::ptrdiff_t>(k));
  }
  out.push_back({face[idx[0]], face[idx[1]], face[idx[2]]});
  return out;
}

// The JSON path of a block's node named by its key: `data.graph.data.node.3 ("3")`.
std::string BlockPath(const CompasBlock& block) { return NamedPath(block.path, block.name); }

// The JSON path of a block's face f, from its named node: `...node.3 ("3").block.data.face.2`.
std::string FacePath(const CompasBlock& block, size_t f) {
  const std::string mesh = BlockPath(block) + block.mesh_path.substr(block.path.size());
  return Child(Child(mesh, "face"), block.face_keys.at(f));
}

// The diagonal of the bounding box of all blocks: the scene size.
double BoxDiagonal(const CompasAssembly& assembly) {
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const CompasBlock& b : assembly.blocks) {
    for (const Vector3& v : b.shape.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  }
  return (hi - lo).norm();
}

// Replaces every "parts[i]" in `text` by the JSON path of block i.
std::string RenameParts(const std::string& text, const std::vector<std::string>& block_paths) {
  std::string out;
  size_t pos = 0;
  while (true) {
    const size_t at = text.find("parts[", pos);
    if (at == std::string::npos) break;
    const size_t close = text.find(']', at);
    const std::string digits =
        close == std::string::npos ? "" : text.substr(at + 6, close - at - 6);
    const std::optional<long long> i = NumericKey(digits);
    if (!i || *i >= static_cast<long long>(block_paths.size())) {
      out += text.substr(pos, at + 6 - pos);
      pos = at + 6;
      continue;
    }
    out += text.substr(pos, at - pos) + block_paths[static_cast<size_t>(*i)];
    pos = close + 1;
  }
  return out + text.substr(pos);
}

// A block's shape as a polyhedron: the planarity policy, then validation
// with the fault named by the block's path in the COMPAS file and the key of
// its face. `split_faces` counts the faces split into triangles.
PolyhedronDef BlockShape(const CompasBlock& block, double tol, const std::string& file,
                         int& split_faces) {
  // The planarity policy: faces within half the tolerance of their mean
  // plane are kept (the margin keeps roundoff from deciding differently
  // here and in Polyhedron::Check); the others are split into triangles.
  PolyhedronDef shape;
  shape.vertices = block.shape.vertices;
  std::vector<size_t> origin;  // the file's face of each face of `shape`
  for (size_t f = 0; f < block.shape.faces.size(); ++f) {
    const std::vector<int>& face = block.shape.faces[f];
    const FacePlane plane = MeanPlane(shape.vertices, face);
    if (face.size() == 3 || plane.off <= tol / 2 || plane.normal.isZero()) {
      shape.faces.push_back(face);
      origin.push_back(f);
      continue;
    }
    const std::vector<std::array<int, 3>> triangles = SplitFace(shape.vertices, face, plane);
    if (triangles.empty()) {
      throw InputError(file, FacePath(block, f),
                       "block '" + EscapedName(block.name) +
                           "': the face is not planar (a vertex is " + Num(plane.off) +
                           " off its mean plane) and cannot be split into triangles: seen "
                           "along its normal it is not a simple polygon");
    }
    for (const auto& t : triangles) {
      shape.faces.push_back({t[0], t[1], t[2]});
      origin.push_back(f);
    }
    ++split_faces;
  }
  // Validate here, where a fault can still be named by the block's path in
  // the COMPAS file and the key of its face.
  if (const auto fault = Polyhedron::Check(shape, tol)) {
    const std::string where = fault->face >= 0
                                  ? FacePath(block, origin.at(static_cast<size_t>(fault->face)))
                                  : BlockPath(block) + block.mesh_path.substr(block.path.size());
    throw InputError(
        file, where,
        "block '" + EscapedName(block.name) + "' is not a valid solid: " + fault->message);
  }
  return shape;
}

}  // namespace

CompasModel CompasToModel(const CompasAssembly& assembly, const CompasOptions& options,
                          const std::string& file) {
  const double friction = options.friction;
  if (!std::isfinite(friction)) {
    throw InputError(file, "friction", "must be a finite number (got " + Num(friction) + ")");
  }
  if (friction < 0) {
    throw InputError(file, "friction", "must not be negative (got " + Num(friction) + ")");
  }
  CompasModel model;
  model.def.name =
      assembly.name.empty() ? std::filesystem::path(file).stem().string() : assembly.name;
  model.def.friction = friction;
  if (!std::isfinite(options.tolerance)) {
    throw InputError(file, "tolerance",
                     "must be a finite number (got " + Num(options.tolerance) + ")");
  }
  model.def.tolerance =
      options.tolerance > 0
          ? options.tolerance
          : (options.stored_interfaces ? kCompasInterfaceToleranceFactor : kCompasToleranceFactor) *
                BoxDiagonal(assembly);
  if (options.stored_interfaces) {
    if (assembly.interfaces.empty())
      throw InputError(file, "data.graph.data.edge",
                       "stores no interfaces (give the contacts up to Cairn: leave out "
                       "--interfaces stored)");
    for (const CompasInterface& in : assembly.interfaces) {
      InterfaceDef def;
      def.part_a = in.a;
      def.part_b = in.b;
      def.points = in.points;
      def.normal = in.normal;
      model.def.interfaces.push_back(std::move(def));
      model.interface_paths.push_back(in.where);
    }
  }
  const double tol = model.def.tolerance;
  for (const CompasBlock& block : assembly.blocks) {
    PolyhedronDef shape = BlockShape(block, tol, file, model.split_faces);
    PartDef part;
    part.name = block.name;
    part.fixed = block.is_support;
    part.density = block.density.value_or(1.0);
    part.polyhedron = std::move(shape);
    part.shape_key = "polyhedron";
    model.def.parts.push_back(std::move(part));
    model.block_paths.push_back(block.path);
  }
  return model;
}

Assembly CreateCompasAssembly(const CompasModel& model, const std::string& file) {
  try {
    return Assembly::Create(model.def, file);
  } catch (const InputError& e) {
    // The model's paths (`parts[3] ("7").polyhedron`) mean nothing in a
    // COMPAS file: name the block's node instead (named by its key, the
    // part's name), keeping any scene-level path.
    std::string path = e.json_path();
    if (path.rfind("parts[", 0) == 0) {
      const size_t close = path.find(']');
      const size_t i = std::stoul(path.substr(6, close - 6));
      path = i < model.block_paths.size()
                 ? NamedPath(model.block_paths[i], model.def.parts.at(i).name)
                 : path.substr(0, close + 1);
    } else if (path.rfind("interfaces[", 0) == 0) {
      const size_t close = path.find(']');
      const size_t k = std::stoul(path.substr(11, close - 11));
      if (k < model.interface_paths.size())
        path = model.interface_paths[k] + (path.find(".points", close) != std::string::npos
                                               ? ".data.points" + path.substr(close + 8)
                                               : std::string());
    }
    std::string message = RenameParts(e.message(), model.block_paths);
    if (const auto* overlap = dynamic_cast<const OverlapError*>(&e))
      throw OverlapError(e.file(), path, std::move(message), overlap->overlaps(),
                         overlap->tolerance());
    throw InputError(e.file(), path, std::move(message));
  }
}

Assembly ReadCompasScene(const std::string& path, const CompasOptions& options,
                         std::uint64_t max_input_size) {
  return CreateCompasAssembly(
      CompasToModel(ReadCompasAssembly(path, max_input_size), options, path), path);
}

CompasAssembly ParseCompasAssembly(const json& doc, const std::string& file) {
  return CompasParser(file).Parse(doc);
}

CompasAssembly ReadCompasAssembly(const std::string& path, std::uint64_t max_input_size) {
  return ParseCompasAssembly(io_internal::ReadJsonFile(path, max_input_size), path);
}

}  // namespace cairn

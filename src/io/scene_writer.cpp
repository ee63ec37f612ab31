#include "cairn/io/scene_writer.h"

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace cairn {
namespace {

using nlohmann::ordered_json;

// A point or vector with the scene's number of coordinates.
ordered_json Vec(const Vector3& v, int dim) {
  ordered_json a = ordered_json::array();
  for (int d = 0; d < dim; ++d) a.push_back(v(d));
  return a;
}

// Pretty-printing with a twist: an array of scalars stays on one line.
// nlohmann's dump of a scalar is exact (shortest round-trip form).
void Print(const ordered_json& j, int indent, std::ostringstream& os) {
  const std::string pad(static_cast<size_t>(indent) + 2, ' ');
  if (j.is_object()) {
    if (j.empty()) {
      os << "{}";
      return;
    }
    os << "{\n";
    bool first = true;
    for (const auto& item : j.items()) {
      if (!first) os << ",\n";
      first = false;
      os << pad << ordered_json(item.key()).dump() << ": ";
      Print(item.value(), indent + 2, os);
    }
    os << '\n' << std::string(static_cast<size_t>(indent), ' ') << '}';
    return;
  }
  if (j.is_array()) {
    bool scalars = true;
    for (const auto& e : j) scalars = scalars && !e.is_structured();
    if (scalars) {
      os << '[';
      for (size_t i = 0; i < j.size(); ++i) os << (i ? ", " : "") << j[i].dump();
      os << ']';
      return;
    }
    os << "[\n";
    for (size_t i = 0; i < j.size(); ++i) {
      os << pad;
      Print(j[i], indent + 2, os);
      os << (i + 1 < j.size() ? ",\n" : "\n");
    }
    os << std::string(static_cast<size_t>(indent), ' ') << ']';
    return;
  }
  os << j.dump();
}

}  // namespace

std::string WriteSceneJson(const AssemblyDef& def) {
  const int dim = !def.parts.empty() && def.parts[0].polyhedron ? 3 : 2;
  ordered_json doc;
  doc["cairn"] = 1;
  doc["name"] = def.name;
  if (def.gravity) doc["gravity"] = Vec(*def.gravity, dim);
  doc["friction"] = def.friction;
  if (def.friction_directions != 0) doc["friction_directions"] = def.friction_directions;
  if (!def.friction_pairs.empty()) {
    ordered_json pairs = ordered_json::array();
    for (const FrictionPairDef& p : def.friction_pairs) {
      pairs.push_back({{"parts", {p.part_a, p.part_b}}, {"mu", p.mu}});
    }
    doc["friction_pairs"] = pairs;
  }
  if (def.tolerance > 0) doc["tolerance"] = def.tolerance;
  if (def.overlap_allowance > 0) doc["overlap_allowance"] = def.overlap_allowance;
  if (def.overlap_depth > 0) doc["overlap_depth"] = def.overlap_depth;
  ordered_json parts = ordered_json::array();
  for (const PartDef& p : def.parts) {
    ordered_json part;
    part["name"] = p.name;
    if (p.fixed) part["fixed"] = true;
    if (p.tool) part["tool"] = true;
    if (p.density) part["density"] = *p.density;
    if (p.mass) part["mass"] = *p.mass;
    if (p.polyhedron) {
      ordered_json vertices = ordered_json::array();
      for (const Vector3& v : p.polyhedron->vertices) vertices.push_back(Vec(v, 3));
      part["polyhedron"] = {{"vertices", vertices}, {"faces", p.polyhedron->faces}};
    } else {
      ordered_json polygon = ordered_json::array();
      for (const Vector2& v : p.polygon) polygon.push_back({v.x(), v.y()});
      part["polygon"] = polygon;
    }
    parts.push_back(part);
  }
  doc["parts"] = parts;
  if (!def.fixtures.empty()) {
    ordered_json fixtures = ordered_json::array();
    for (const FixtureDef& f : def.fixtures) {
      fixtures.push_back(
          {{"part", f.part}, {"point", Vec(f.point, dim)}, {"normal", Vec(f.normal, dim)}});
    }
    doc["fixtures"] = fixtures;
  }
  if (!def.interfaces.empty()) {
    ordered_json interfaces = ordered_json::array();
    for (const InterfaceDef& in : def.interfaces) {
      ordered_json points = ordered_json::array();
      for (const Vector3& p : in.points) points.push_back(Vec(p, 3));
      interfaces.push_back(
          {{"parts", {in.part_a, in.part_b}}, {"normal", Vec(in.normal, 3)}, {"points", points}});
    }
    doc["interfaces"] = interfaces;
  }
  std::ostringstream os;
  Print(doc, 0, os);
  os << '\n';
  return os.str();
}

}  // namespace cairn

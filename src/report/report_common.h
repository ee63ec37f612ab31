#pragma once
// Helpers shared by the report writers: vectors written as [x, y] in 2-D and
// [x, y, z] in 3-D, with floating-point dust cleaned away.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/core/tolerances.h"
#include "cairn/core/types.h"
#include "cairn/geometry/assembly.h"
#include "cairn/stability/analyze.h"

namespace cairn::report_internal {

// Rounds away floating-point dust so that reports are stable across
// platforms: values below 1e-12 of the scale print as 0.
// The scale below whose roundoff a reported force is 0: the scene's largest
// weight in the reported unit (a milligram part's forces are not dust).
inline double ForceRoundoffScale(const Assembly& assembly, double force_scale) {
  return (assembly.max_weight() > 0 ? assembly.max_weight() : 1.0) / force_scale;
}

inline double Clean(double x, double scale = 1.0) {
  return std::abs(x) < numeric::kRoundoff * scale ? 0.0 : x;
}

// A point or vector: 2 numbers in a 2-D scene, 3 in a 3-D one.
inline nlohmann::json Vec(const Vector3& v, int dim, double scale = 1.0) {
  nlohmann::json out = nlohmann::json::array({Clean(v.x(), scale), Clean(v.y(), scale)});
  if (dim == 3) out.push_back(Clean(v.z(), scale));
  return out;
}

// An angular rate: the scalar ω_z (counter-clockwise) in 2-D, a vector in 3-D.
inline nlohmann::json Angular(const Vector3& w, int dim, double scale = 1.0) {
  return dim == 2 ? nlohmann::json(Clean(w.z(), scale)) : Vec(w, 3, scale);
}

// A tangential quantity of a contact: signed along t_W in 2-D, a vector in 3-D.
inline nlohmann::json Tangential(const Vector3& v, const Contact& c, int dim, double scale = 1.0) {
  return dim == 2 ? nlohmann::json(Clean(v.dot(c.t_W()), scale)) : Vec(v, 3, scale);
}

// A number for text and CSV: `digits` significant digits, dust cleaned.
inline std::string Num(double x, int digits = 6) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, Clean(x));
  return buf;
}

// Part names, in the order given.
inline nlohmann::json Names(const Assembly& a, const std::vector<int>& parts) {
  nlohmann::json out = nlohmann::json::array();
  for (int p : parts) out.push_back(a.part(p).name);
  return out;
}

// The name of part i of a contact, or `world` (JSON, CSV) / `fixture` (text)
// for the world side (i < 0).
inline std::string PartName(const Assembly& a, int i, const char* world) {
  return i >= 0 ? a.part(i).name : world;
}

// A contact as every document writes it (`check --json`'s `contacts`,
// `simulate --json`'s failure, the result page's frames and plan nodes): the
// parts ("world" for a fixel), point, normal (into the first part), the
// normal and friction forces on the first part divided by `force_scale` (the
// report's force unit; `forces` is ForceRoundoffScale), whether it breaks or
// slides, and in 3-D its patch. Each document adds its own keys (the motions,
// the feature, the component).
inline nlohmann::json ContactRecord(const Assembly& a, const ContactReport& c, double force_scale,
                                    double forces) {
  const int dim = a.dimension();
  nlohmann::json out = {
      {"parts", {PartName(a, c.contact.part_a, "world"), PartName(a, c.contact.part_b, "world")}},
      {"point", Vec(c.contact.p_WC, dim)},
      {"normal", Vec(c.contact.n_W, dim)},
      {"normal_force", Clean(c.normal_force / force_scale, forces)},
      {"friction_force", Tangential(c.friction_force / force_scale, c.contact, dim, forces)},
      {"breaks", c.breaking},
      {"slides", c.sliding}};
  if (dim == 3) out["patch"] = c.contact.patch;
  return out;
}

// A fixel as a scene file's `fixtures` entry: part, point, normal.
inline nlohmann::json FixtureToJson(const FixtureDef& f, int dim) {
  return {{"part", f.part}, {"point", Vec(f.point, dim)}, {"normal", Vec(f.normal, dim)}};
}

}  // namespace cairn::report_internal

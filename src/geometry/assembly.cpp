#include "cairn/geometry/assembly.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <variant>

#include "cairn/core/check.h"
#include "cairn/core/error.h"
#include "cairn/core/tolerances.h"

namespace cairn {
namespace {

using Box = std::pair<Vector2, Vector2>;

std::string Indexed(const std::string& key, int i) { return key + "[" + std::to_string(i) + "]"; }

std::string Point(const Vector2& p) {
  return "(" + FormatNumber(p.x()) + ", " + FormatNumber(p.y()) + ")";
}

std::string Point(const Vector3& p) {
  return "(" + FormatNumber(p.x()) + ", " + FormatNumber(p.y()) + ", " + FormatNumber(p.z()) + ")";
}

bool Finite(const Vector2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }
bool Finite(const Vector3& v) { return v.allFinite(); }

// Throws the InputError of one fault; all validation goes through it.
class Validator {
 public:
  explicit Validator(const std::string& file) : file_(file) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& message) const {
    throw InputError(file_, path, message);
  }
  [[noreturn]] void FailOverlaps(const std::string& path, const std::string& message,
                                 std::vector<PartOverlap> overlaps, double tol) const {
    throw OverlapError(file_, path, message, std::move(overlaps), tol);
  }
  void FiniteNumber(double x, const std::string& path) const {
    if (!std::isfinite(x)) Fail(path, "must be a finite number (got " + FormatNumber(x) + ")");
  }
  void FinitePoint(const Vector2& v, const std::string& path) const {
    if (!Finite(v)) Fail(path, "must have finite coordinates (got " + Point(v) + ")");
  }
  void FinitePoint(const Vector3& v, const std::string& path) const {
    if (!Finite(v)) Fail(path, "must have finite coordinates (got " + Point(v) + ")");
  }
  void Positive(double x, const std::string& path) const {
    FiniteNumber(x, path);
    if (x <= 0) Fail(path, "must be positive (got " + FormatNumber(x) + ")");
  }
  void NonNegative(double x, const std::string& path) const {
    FiniteNumber(x, path);
    if (x < 0) Fail(path, "must not be negative (got " + FormatNumber(x) + ")");
  }
  // A friction coefficient: 0 to limits::kMaxFriction.
  void Friction(double mu, const std::string& path) const {
    NonNegative(mu, path);
    if (mu > limits::kMaxFriction)
      Fail(path, "is out of range (got " + FormatNumber(mu) + "; at most " +
                     FormatNumber(limits::kMaxFriction) + ")");
  }
  // A point within the coordinate range (limits::kMaxCoordinate).
  template <typename V>
  void Coordinates(const V& v, const std::string& path) const {
    FinitePoint(v, path);
    if (v.cwiseAbs().maxCoeff() > limits::kMaxCoordinate)
      Fail(path, "coordinate out of range (got " + Point(v) + "; |x| ≤ " +
                     FormatNumber(limits::kMaxCoordinate) + " length units)");
  }
  // The fault of a value the command line may have set (`option`, e.g.
  // "--tolerance"), reported against the option when it did, else against
  // the file's `path`.
  [[noreturn]] void FailValue(const std::string& option, const std::string& path,
                              const std::string& message) const {
    if (!option.empty()) throw InputError("", option, message);
    Fail(path, message);
  }

 private:
  const std::string& file_;
};

// True when every vertex lies within tol of the line through vertex 0 and the
// vertex farthest from it (a polygon with no interior).
bool Collinear(const Polygon& poly, double tol) {
  const Vector2& o = poly[0];
  const auto far = std::max_element(poly.begin(), poly.end(), [&](const auto& a, const auto& b) {
    return (a - o).squaredNorm() < (b - o).squaredNorm();
  });
  if ((*far - o).norm() <= tol) return true;
  return std::all_of(poly.begin(), poly.end(),
                     [&](const Vector2& v) { return std::abs(LineSide(o, *far, v)) <= tol; });
}

// True when the normal n, applied at p on the counter-clockwise polygon's
// boundary, points into the part. On an edge, n must point against the
// outward normal. At a convex vertex n must lie in the (closed) wedge of the
// material; at a reflex vertex it must point into the material of at least
// one of its two edges.
bool PointsInto(const Polygon& poly, const Vector2& p, const Vector2& n, double tol,
                double angle_tol) {
  const int m = static_cast<int>(poly.size());
  int vertex = -1;
  double vertex_dist = tol;
  int edge = 0;
  double edge_dist = std::numeric_limits<double>::infinity();
  for (int k = 0; k < m; ++k) {
    const double dv = (poly[k] - p).norm();
    if (dv <= vertex_dist) {
      vertex = k;
      vertex_dist = dv;
    }
    const double de = DistanceToSegment(p, poly[k], poly[(k + 1) % m]);
    if (de < edge_dist) {
      edge = k;
      edge_dist = de;
    }
  }
  if (vertex < 0) return n.dot(EdgeNormal(poly, edge)) < -angle_tol;
  const int prev = (vertex + m - 1) % m;
  const double d1 = n.dot(EdgeNormal(poly, prev));
  const double d2 = n.dot(EdgeNormal(poly, vertex));
  const bool convex = Cross2(poly[vertex] - poly[prev], poly[(vertex + 1) % m] - poly[vertex]) >= 0;
  if (convex) return std::max(d1, d2) <= angle_tol && std::min(d1, d2) < -angle_tol;
  return std::min(d1, d2) < -angle_tol;
}

// The message of a self-intersection found by FindSelfIntersection.
std::string DescribeSelfIntersection(const Polygon& poly, const SelfIntersection& s) {
  const int n = static_cast<int>(poly.size());
  const int a = s.edge_a, b = s.edge_b;
  if (b == a + 1 || (a == 0 && b == n - 1)) {
    return "self-intersecting: edges " + std::to_string(a) + " and " + std::to_string(b) +
           " fold back onto each other";
  }
  const bool crosses =
      SegmentsCrossProperly(poly[a], poly[(a + 1) % n], poly[b], poly[(b + 1) % n], 0.0);
  return "self-intersecting: edge " + std::to_string(a) + (crosses ? " crosses" : " touches") +
         " edge " + std::to_string(b);
}

}  // namespace

namespace {

// The JSON path of a part with its name: `parts[1] ("A")` (NamedPath).
std::string PartPath(const PartDef& p, int i) { return NamedPath(Indexed("parts", i), p.name); }

// The JSON path of a part's shape: `parts[1] ("A").polygon`.
std::string ShapePath(const PartDef& p, int i) {
  const std::string key = !p.shape_key.empty() ? p.shape_key
                          : p.polyhedron       ? "polyhedron"
                                               : "polygon";
  return PartPath(p, i) + "." + key;
}

// A 2-D part's validated polygon and mass properties.
// The first vertex k (in order) within tol of an earlier vertex l: (k, l).
// A sweep over the vertices sorted by x, comparing each with those within
// tol in x: O(n log n) for any polygon whose vertices do not crowd into one
// tol-wide column.
std::optional<std::pair<int, int>> RepeatedVertex(const Polygon& poly, double tol) {
  const int n = static_cast<int>(poly.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return poly[a].x() < poly[b].x() || (poly[a].x() == poly[b].x() && a < b);
  });
  std::optional<std::pair<int, int>> first;
  for (int s = 0; s < n; ++s) {
    for (int t = s + 1; t < n && poly[order[t]].x() - poly[order[s]].x() <= tol; ++t) {
      if ((poly[order[t]] - poly[order[s]]).norm() > tol) continue;
      const int k = std::max(order[s], order[t]), l = std::min(order[s], order[t]);
      if (!first || std::make_pair(k, l) < *first) first = std::make_pair(k, l);
    }
  }
  return first;
}

Part Make2dPart(const PartDef& p, const std::string& path, double tol, const Validator& check) {
  if (const auto r = RepeatedVertex(p.polygon, tol))
    check.Fail(path + Indexed("", r->first), "self-intersecting: vertex " +
                                                 std::to_string(r->first) + " repeats vertex " +
                                                 std::to_string(r->second));
  const auto box = BoundingBox(p.polygon);
  const double size = (box.second - box.first).norm();
  if (Collinear(p.polygon, tol)) check.Fail(path, "has zero area: its vertices are collinear");
  if (const auto s = FindSelfIntersection(p.polygon, tol)) {
    check.Fail(path, DescribeSelfIntersection(p.polygon, *s));
  }
  const double area = std::abs(SignedArea(p.polygon));
  if (area <= tol * size) {
    check.Fail(path, "has zero area (" + FormatNumber(area) +
                         ", at most the tolerance times its size, " + FormatNumber(tol * size) +
                         ")");
  }
  Part part;
  part.polygon = p.polygon;
  MakeCounterClockwise(part.polygon);
  for (const Vector2& v : part.polygon) part.vertices.push_back(Embed(v));
  const PolygonMass pm = ComputePolygonMass(part.polygon);
  part.area = pm.area;
  part.centroid = Embed(pm.centroid);
  // An explicit mass wins over a density.
  part.mass = p.mass ? *p.mass : p.density.value_or(1.0) * pm.area;
  part.inertia = Matrix3::Identity() * (part.mass * pm.polar_moment / pm.area);
  return part;
}

// A 3-D part's validated polyhedron and mass properties.
Part Make3dPart(const PartDef& p, const std::string& path, double tol, const Validator& check) {
  auto made = Polyhedron::CheckAndCreate(*p.polyhedron, tol);
  if (const auto* fault = std::get_if<PolyhedronFault>(&made)) check.Fail(path, fault->message);
  Part part;
  part.polyhedron = std::make_shared<const Polyhedron>(std::get<Polyhedron>(std::move(made)));
  part.vertices = part.polyhedron->vertices();
  const PolyhedronMass& pm = part.polyhedron->mass();
  part.area = pm.volume;
  part.centroid = pm.centroid;
  part.mass = p.mass ? *p.mass : p.density.value_or(1.0) * pm.volume;
  part.inertia = pm.inertia * (part.mass / pm.volume);
  return part;
}

// True when the normal n at the point p on the boundary of a 3-D part points
// into the part: a short step along n from p goes inside.
bool PointsInto3d(const Polyhedron& poly, const Vector3& p, const Vector3& n, double tol) {
  const double step = 100 * tol;
  return SignedDistance(poly, Eigen::Isometry3d::Identity(), p + step * n) < -0.5 * step;
}

}  // namespace

namespace {

// The dimension: that of the parts' shapes, which must agree.
int SceneDimension(const AssemblyDef& def, const Validator& check) {
  int dimension = 2;
  for (int i = 0; i < static_cast<int>(def.parts.size()); ++i) {
    const int dim = def.parts[i].polyhedron ? 3 : 2;
    if (i == 0) dimension = dim;
    if (dim != dimension) {
      check.Fail(ShapePath(def.parts[i], i), "mixes 2-D and 3-D shapes (this part is " +
                                                 std::to_string(dim) + "-D, parts[0] is " +
                                                 std::to_string(dimension) + "-D)");
    }
  }
  return dimension;
}

// Scene-wide numbers: gravity, friction, the tolerance override and the
// friction directions of a 3-D scene.
struct SceneNumbers {
  Vector3 gravity;
  double friction = 0;
  double tolerance_override = 0;
  int friction_directions = 2;
};

SceneNumbers ReadSceneNumbers(const AssemblyDef& def, bool is3, const Validator& check) {
  SceneNumbers out;
  out.gravity = def.gravity.value_or(is3 ? Vector3(0, 0, -9.81) : Vector3(0, -9.81, 0));
  if (!Finite(out.gravity))
    check.FailValue(def.gravity_option, "gravity",
                    "must have finite components (got " + Point(out.gravity) + ")");
  const double g = out.gravity.cwiseAbs().maxCoeff();
  if (g != 0 && (g < limits::kMinGravity || g > limits::kMaxGravity))
    check.FailValue(def.gravity_option, "gravity",
                    "out of range (got " + Point(out.gravity) + "; |g| is 0 or between " +
                        FormatNumber(limits::kMinGravity) + " and " +
                        FormatNumber(limits::kMaxGravity) + " length/s²)");
  if (!is3 && out.gravity.z() != 0) check.Fail("gravity", "must have z = 0 in a 2-D scene");
  check.Friction(def.friction, "friction");
  if (!std::isfinite(def.tolerance))
    check.FailValue(def.tolerance_option, "tolerance",
                    "must be a finite number (got " + FormatNumber(def.tolerance) + ")");
  out.friction = def.friction;
  out.tolerance_override = def.tolerance > 0 ? def.tolerance : 0.0;
  if (def.friction_directions != 0) {
    if (!is3) {
      check.Fail("friction_directions",
                 "applies to 3-D scenes only (2-D friction has the two directions ±t)");
    }
    if (def.friction_directions < 3) {
      check.Fail("friction_directions",
                 "must be at least 3 (got " + std::to_string(def.friction_directions) + ")");
    }
  }
  out.friction_directions = is3 ? (def.friction_directions ? def.friction_directions : 4) : 2;
  return out;
}

// Names, mass numbers and vertex counts of every part; the index of each
// name. A fault of the name is reported at the bare path; every other at the
// named one.
std::unordered_map<std::string, int> CheckPartNumbers(const AssemblyDef& def, bool is3,
                                                      const Validator& check) {
  std::unordered_map<std::string, int> index;
  for (int i = 0; i < static_cast<int>(def.parts.size()); ++i) {
    const PartDef& p = def.parts[i];
    if (p.name.empty()) check.Fail(Indexed("parts", i) + ".name", "must not be empty");
    const auto [it, inserted] = index.emplace(p.name, i);
    if (!inserted) {
      check.Fail(Indexed("parts", i) + ".name", "duplicate part name '" + EscapedName(p.name) +
                                                    "' (also " + Indexed("parts", it->second) +
                                                    ")");
    }
    const std::string path = PartPath(p, i);
    // A tool travels with the gripper, which a fixed part never does.
    if (p.fixed && p.tool) {
      check.Fail(path + ".tool",
                 "part '" + EscapedName(p.name) + "' cannot be both fixed and a tool");
    }
    if (p.density) check.Positive(*p.density, path + ".density");
    if (p.mass) check.Positive(*p.mass, path + ".mass");
    if (is3) {
      for (size_t k = 0; k < p.polyhedron->vertices.size(); ++k)
        check.Coordinates(p.polyhedron->vertices[k],
                          ShapePath(p, i) + ".vertices" + Indexed("", static_cast<int>(k)));
      continue;
    }
    const int nv = static_cast<int>(p.polygon.size());
    if (nv < 3) {
      check.Fail(path + ".polygon",
                 "has " + std::to_string(nv) + " vertices; a polygon needs at least 3");
    }
    for (int k = 0; k < nv; ++k) {
      check.Coordinates(p.polygon[k], path + ".polygon" + Indexed("", k));
    }
  }
  return index;
}

// The bounding box of a part's vertices (as given).
std::pair<Vector3, Vector3> PartBox(const PartDef& p, bool is3) {
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  if (is3)
    for (const Vector3& v : p.polyhedron->vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  else
    for (const Vector2& v : p.polygon) lo = lo.cwiseMin(Embed(v)), hi = hi.cwiseMax(Embed(v));
  return {lo, hi};
}

// The diagonal of the box around every vertex of the scene (its size).
double SceneSize(const AssemblyDef& def, bool is3) {
  Vector3 lo = Vector3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const PartDef& p : def.parts) {
    const auto [plo, phi] = PartBox(p, is3);
    lo = lo.cwiseMin(plo), hi = hi.cwiseMax(phi);
  }
  return def.parts.empty() ? 0.0 : (hi - lo).norm();
}

// Every part at least limits::kMinPartSizeInTolerances length tolerances
// across: otherwise its shape is below the tolerance (a coarse --tolerance,
// or a scene spanning too many orders of magnitude: one part far from the
// others makes the scaled tolerance coarse for all), and checking its shape
// would blame it for what the scale did.
void CheckScale(const AssemblyDef& def, bool is3, double scene_size, double tol,
                const Validator& check) {
  const int n = static_cast<int>(def.parts.size());
  std::vector<Vector3> centre(n);
  int smallest = -1;
  double smallest_size = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    const auto [lo, hi] = PartBox(def.parts[i], is3);
    centre[i] = 0.5 * (lo + hi);
    if ((hi - lo).norm() < smallest_size) smallest_size = (hi - lo).norm(), smallest = i;
  }
  if (smallest < 0 || smallest_size >= limits::kMinPartSizeInTolerances * tol) return;
  const std::string size = "its size " + FormatNumber(smallest_size) + " is less than " +
                           FormatNumber(limits::kMinPartSizeInTolerances) +
                           " times the length tolerance " + FormatNumber(tol);
  const PartDef& p = def.parts[smallest];
  if (def.tolerance > 0) {
    check.FailValue(def.tolerance_option, def.tolerance_option.empty() ? "tolerance" : "",
                    "too coarse for part '" + EscapedName(p.name) + "' (" + PartPath(p, smallest) +
                        "): " + size + "; give a tolerance below " +
                        FormatNumber(smallest_size / limits::kMinPartSizeInTolerances));
  }
  // The part farthest from the smallest one spans the scene.
  int far = smallest;
  for (int i = 0; i < n; ++i)
    if ((centre[i] - centre[smallest]).norm() > (centre[far] - centre[smallest]).norm()) far = i;
  check.Fail(PartPath(p, smallest),
             size + " (1e-6 of the scene's size " + FormatNumber(scene_size) +
                 "): the scene spans too many orders of magnitude (part '" +
                 EscapedName(def.parts[far].name) + "', " + PartPath(def.parts[far], far) +
                 ", lies " + FormatNumber((centre[far] - centre[smallest]).norm()) +
                 " away); bring the parts together, or set a tolerance");
}

// Each part's mass within limits::kMinMass..kMaxMass, and the movable
// parts' masses within limits::kMaxMassRatio of each other. Reported at the
// mass, the density, or the part, whichever set it.
void CheckMasses(const AssemblyDef& def, const std::vector<Part>& parts, const Validator& check) {
  const auto where = [&](int i) {
    const PartDef& p = def.parts[i];
    return PartPath(p, i) + (p.mass ? ".mass" : p.density ? ".density" : "");
  };
  int lightest = -1, heaviest = -1;
  for (int i = 0; i < static_cast<int>(parts.size()); ++i) {
    const double m = parts[i].mass;
    if (!(m >= limits::kMinMass && m <= limits::kMaxMass))
      check.Fail(where(i), "the part's mass " + FormatNumber(m) + " is out of range (" +
                               FormatNumber(limits::kMinMass) + " to " +
                               FormatNumber(limits::kMaxMass) + " mass units)");
    if (parts[i].fixed) continue;
    if (lightest < 0 || m < parts[lightest].mass) lightest = i;
    if (heaviest < 0 || m > parts[heaviest].mass) heaviest = i;
  }
  if (lightest < 0 || parts[heaviest].mass <= limits::kMaxMassRatio * parts[lightest].mass) return;
  check.Fail(where(lightest), "the part's mass " + FormatNumber(parts[lightest].mass) +
                                  " is less than 1/" + FormatNumber(limits::kMaxMassRatio) +
                                  " of the heaviest movable part's, '" +
                                  EscapedName(parts[heaviest].name) + "' (" +
                                  FormatNumber(parts[heaviest].mass) + ")");
}

// Every pair of parts that overlap by more than `tol`, skipping pairs whose
// bounding boxes are apart (a sweep over boxes sorted by their low x), in
// order of (later, earlier) index, each with a point of both parts (a
// witness) and, in 3-D, how deep that point lies inside the part it is not
// on the surface of.
std::vector<PartOverlap> FindPartOverlaps(const std::vector<Part>& parts, int dimension,
                                          double tol) {
  const int num_parts = static_cast<int>(parts.size());
  const bool is3 = dimension == 3;
  std::vector<std::pair<Vector3, Vector3>> boxes(num_parts);
  for (int i = 0; i < num_parts; ++i) {
    boxes[i] = {parts[i].vertices[0], parts[i].vertices[0]};
    for (const Vector3& v : parts[i].vertices)
      boxes[i] = {boxes[i].first.cwiseMin(v), boxes[i].second.cwiseMax(v)};
  }
  std::vector<int> order(num_parts);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return boxes[a].first.x() < boxes[b].first.x(); });
  std::map<std::pair<int, int>, Vector3> overlaps;  // (later, earlier) index → witness
  for (int oi = 0; oi < num_parts; ++oi) {
    const int i = order[oi];
    for (int oj = oi + 1; oj < num_parts; ++oj) {
      const int j = order[oj];
      if (boxes[j].first.x() >= boxes[i].second.x() - tol) break;
      bool apart = false;
      for (int d = 1; d < dimension; ++d)
        apart = apart || boxes[j].first(d) >= boxes[i].second(d) - tol ||
                boxes[i].first(d) >= boxes[j].second(d) - tol;
      if (apart) continue;
      const std::pair<int, int> key{std::max(i, j), std::min(i, j)};
      if (is3) {
        const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
        if (const auto w =
                FindPolyhedronOverlap(*parts[i].polyhedron, I, *parts[j].polyhedron, I, tol))
          overlaps[key] = *w;
      } else if (const auto w = FindOverlap(parts[i].polygon, parts[j].polygon, tol)) {
        overlaps[key] = Embed(*w);
      }
    }
  }
  std::vector<PartOverlap> found;
  for (const auto& [key, witness] : overlaps) {
    PartOverlap o;
    o.later = key.first;
    o.earlier = key.second;
    o.witness = witness;
    if (is3) {
      // The witness lies on or inside each part: its depth is in the other.
      const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
      o.depth = std::max(-SignedDistance(*parts[o.later].polyhedron, I, witness),
                         -SignedDistance(*parts[o.earlier].polyhedron, I, witness));
    }
    found.push_back(o);
  }
  return found;
}

// Refuses the overlapping pairs `found` (FindPartOverlaps; not empty): every
// one is reported, the one with the lowest indices first (its later part's
// path is the error's).
[[noreturn]] void FailOverlaps(const AssemblyDef& def, const std::vector<Part>& parts, bool is3,
                               std::vector<PartOverlap> found, double tol, const Validator& check) {
  // "at (x, y, z), d deep"
  const auto where = [&](const PartOverlap& o) {
    return is3 ? Point(o.witness) + ", " + FormatNumber(o.depth) + " deep"
               : Point(Vector2(o.witness.head<2>()));
  };
  const PartOverlap& first = found.front();
  std::string message = "part '" + EscapedName(parts[first.later].name) + "' overlaps part '" +
                        EscapedName(parts[first.earlier].name) + "' (" +
                        Indexed("parts", first.earlier) + ") by more than the tolerance " +
                        FormatNumber(tol) + ", e.g. at " + where(first);
  if (found.size() > 1) {
    message += "; " + std::to_string(found.size() - 1) + " more overlapping pair" +
               (found.size() == 2 ? "" : "s") + ":";
    for (size_t k = 1; k < found.size(); ++k) {
      const PartOverlap& o = found[k];
      message += " '" + EscapedName(parts[o.later].name) + "' and '" +
                 EscapedName(parts[o.earlier].name) + "' (" + Indexed("parts", o.later) + ", " +
                 Indexed("parts", o.earlier) + ") at " + where(o) +
                 (k + 1 == found.size() ? "" : ";");
    }
  }
  const std::string path = PartPath(def.parts[first.later], first.later);
  check.FailOverlaps(path, message, std::move(found), tol);
}

// The overlap test: no two parts interpenetrate by more than `tol`.
void CheckOverlaps(const AssemblyDef& def, const std::vector<Part>& parts, int dimension,
                   double tol, const Validator& check) {
  std::vector<PartOverlap> found = FindPartOverlaps(parts, dimension, tol);
  if (!found.empty()) FailOverlaps(def, parts, dimension == 3, std::move(found), tol, check);
}

// The overlap test with an overlap depth (AssemblyDef::overlap_depth, 3-D):
// the pairs that overlap by more than `tol` but no deeper than tol + depth,
// each with its deepest point and depth (PolyhedronOverlapDepth), are read
// as touching and returned; deeper ones are refused, every one with its
// depth.
std::vector<PartOverlap> TouchingOverlaps(const AssemblyDef& def, const std::vector<Part>& parts,
                                          double tol, double depth, const Validator& check) {
  std::vector<PartOverlap> touching, too_deep;
  for (PartOverlap& o : FindPartOverlaps(parts, 3, tol)) {
    const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
    Vector3 deepest{0, 0, 0};
    const double d = PolyhedronOverlapDepth(*parts[o.later].polyhedron, I,
                                            *parts[o.earlier].polyhedron, I, tol, &deepest);
    // The samples may all miss an overlap that an edge crossing found: the
    // witness's depth stands then.
    if (d > o.depth) o.depth = d, o.witness = deepest;
    (o.depth > tol + depth ? too_deep : touching).push_back(o);
  }
  if (!too_deep.empty()) FailOverlaps(def, parts, true, std::move(too_deep), tol + depth, check);
  return touching;
}

// The overlap depth: finite, ≥ 0, 3-D only, and at most
// kMaxOverlapDepthFactor of the smallest part's size.
double CheckOverlapDepth(const AssemblyDef& def, bool is3, double smallest_part_size,
                         const Validator& check) {
  const double depth = def.overlap_depth;
  if (!std::isfinite(depth) || depth < 0)
    check.FailValue(def.overlap_depth_option, "overlap_depth",
                    "must be a finite number ≥ 0 (got " + FormatNumber(depth) + ")");
  if (depth == 0) return 0;
  if (!is3)
    check.FailValue(def.overlap_depth_option, "overlap_depth",
                    "applies to 3-D models only (2-D parts that overlap are refused)");
  const double largest = limits::kMaxOverlapDepthFactor * smallest_part_size;
  if (depth > largest)
    check.FailValue(def.overlap_depth_option, "overlap_depth",
                    "too large: " + FormatNumber(depth) + " is more than " +
                        FormatNumber(limits::kMaxOverlapDepthFactor) +
                        " of the smallest part's size (" + FormatNumber(smallest_part_size) +
                        "): give at most " + FormatNumber(largest) +
                        "; parts that overlap deeper share material (--fastened joins a "
                        "STEP model's pairs)");
  return depth;
}

using PartFinder = std::function<int(const std::string&)>;

// Friction pairs: two named parts each, once, with μ ≥ 0; sorted by index pair.
std::vector<std::pair<std::pair<int, int>, double>> MakeFrictionPairs(const AssemblyDef& def,
                                                                      const PartFinder& find,
                                                                      const Validator& check) {
  std::vector<std::pair<std::pair<int, int>, double>> pair_mu;
  for (int k = 0; k < static_cast<int>(def.friction_pairs.size()); ++k) {
    const FrictionPairDef& fp = def.friction_pairs[k];
    const std::string path = Indexed("friction_pairs", k);
    const int a = find(fp.part_a), b = find(fp.part_b);
    if (a < 0) check.Fail(path + ".parts[0]", "no part named '" + EscapedName(fp.part_a) + "'");
    if (b < 0) check.Fail(path + ".parts[1]", "no part named '" + EscapedName(fp.part_b) + "'");
    if (a == b) check.Fail(path + ".parts[1]", "names part '" + EscapedName(fp.part_a) + "' twice");
    check.Friction(fp.mu, path + ".mu");
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    for (int l = 0; l < k; ++l) {
      if (pair_mu[l].first == key) {
        check.Fail(path, "repeats the pair '" + EscapedName(fp.part_a) + "', '" +
                             EscapedName(fp.part_b) + "' of " + Indexed("friction_pairs", l));
      }
    }
    pair_mu.push_back({key, fp.mu});
  }
  std::sort(pair_mu.begin(), pair_mu.end());
  return pair_mu;
}

// Where a fixel of `part` fails to touch it or to push into it: (".point" or
// ".normal", what is wrong); n is its unit normal. Empty when it is valid.
std::optional<std::pair<std::string, std::string>> FixtureContactFault(const Part& part, bool is3,
                                                                       const FixtureDef& fd,
                                                                       const Vector3& n, double tol,
                                                                       double angle_tol) {
  const auto show = [&](const Vector3& v) { return is3 ? Point(v) : Point(Vector2(v.head<2>())); };
  double dist = 0;
  bool into = false;
  if (is3) {
    const Polyhedron& poly = *part.polyhedron;
    dist = std::abs(SignedDistance(poly, Eigen::Isometry3d::Identity(), fd.point));
    into = dist <= tol && PointsInto3d(poly, fd.point, n, tol);
  } else {
    const Polygon& poly = part.polygon;
    dist = DistanceToBoundary(poly, fd.point.head<2>());
    into = dist <= tol && PointsInto(poly, fd.point.head<2>(), n.head<2>(), tol, angle_tol);
  }
  if (dist > tol) {
    return std::make_pair(std::string(".point"),
                          show(fd.point) + " is not on the boundary of part '" +
                              EscapedName(fd.part) + "' (distance " + FormatNumber(dist) +
                              " > tolerance " + FormatNumber(tol) + ")");
  }
  if (!into) {
    return std::make_pair(std::string(".normal"),
                          show(fd.normal) + " points out of part '" + EscapedName(fd.part) +
                              "' (a fixel pushes: its normal must point into the part)");
  }
  return std::nullopt;
}

// Fixtures: on their part's boundary, pushing into it.
std::vector<Fixture> MakeFixtures(const AssemblyDef& def, const std::vector<Part>& parts, bool is3,
                                  const PartFinder& find, double tol, double angle_tol,
                                  const Validator& check) {
  std::vector<Fixture> fixtures;
  for (int f = 0; f < static_cast<int>(def.fixtures.size()); ++f) {
    const FixtureDef& fd = def.fixtures[f];
    const std::string path = Indexed("fixtures", f);
    const int part = find(fd.part);
    if (part < 0) check.Fail(path + ".part", "no part named '" + EscapedName(fd.part) + "'");
    check.FinitePoint(fd.point, path + ".point");
    check.FinitePoint(fd.normal, path + ".normal");
    const double len = fd.normal.norm();
    if (len == 0) check.Fail(path + ".normal", "must not be zero");
    const Vector3 n = fd.normal / len;
    if (const auto fault = FixtureContactFault(parts[part], is3, fd, n, tol, angle_tol))
      check.Fail(path + fault->first, fault->second);
    fixtures.push_back(Fixture{part, fd.point, n});
  }

  return fixtures;
}

// Interfaces: 3-D, between two named parts, a planar polygon.
std::vector<Interface> MakeInterfaces(const AssemblyDef& def, bool is3, const PartFinder& find,
                                      double tol, const Validator& check) {
  std::vector<Interface> interfaces;
  for (int k = 0; k < static_cast<int>(def.interfaces.size()); ++k) {
    const InterfaceDef& id = def.interfaces[k];
    const std::string path = Indexed("interfaces", k);
    if (!is3) {
      check.Fail(path, "interfaces are given in 3-D scenes only (a 2-D scene finds its contacts)");
      continue;
    }
    Interface in;
    in.part_a = find(id.part_a);
    in.part_b = find(id.part_b);
    if (in.part_a < 0)
      check.Fail(path + ".parts[0]", "no part named '" + EscapedName(id.part_a) + "'");
    if (in.part_b < 0)
      check.Fail(path + ".parts[1]", "no part named '" + EscapedName(id.part_b) + "'");
    if (in.part_a == in.part_b)
      check.Fail(path + ".parts[1]", "names part '" + EscapedName(id.part_a) + "' twice");
    if (id.points.size() < 3)
      check.Fail(path + ".points",
                 "needs at least 3 points (got " + std::to_string(id.points.size()) + ")");
    for (size_t i = 0; i < id.points.size(); ++i)
      check.FinitePoint(id.points[i], path + Indexed(".points", static_cast<int>(i)));
    check.FinitePoint(id.normal, path + ".normal");
    const double len = id.normal.norm();
    if (len == 0) check.Fail(path + ".normal", "must not be zero");
    in.normal = id.normal / len;
    // Planar: every point within the tolerance of the plane through the
    // first with that normal.
    for (size_t i = 1; i < id.points.size(); ++i) {
      const double off = std::abs(in.normal.dot(id.points[i] - id.points[0]));
      if (off > tol)
        check.Fail(path + Indexed(".points", static_cast<int>(i)),
                   Point(id.points[i]) + " is " + FormatNumber(off) +
                       " off the interface's plane (more than the tolerance " + FormatNumber(tol) +
                       ")");
    }
    in.points = id.points;
    interfaces.push_back(std::move(in));
  }

  return interfaces;
}

}  // namespace

Assembly Assembly::Create(const AssemblyDef& def, const std::string& source_file) {
  const Validator check(source_file);
  Assembly out;
  out.name_ = def.name;
  out.dimension_ = SceneDimension(def, check);
  const bool is3 = out.dimension_ == 3;
  const SceneNumbers numbers = ReadSceneNumbers(def, is3, check);
  out.gravity_ = numbers.gravity;
  out.default_friction_ = numbers.friction;
  out.tolerance_override_ = numbers.tolerance_override;
  out.overlap_allowance_ =
      std::isfinite(def.overlap_allowance) ? std::max(def.overlap_allowance, 0.0) : 0.0;
  out.friction_directions_ = numbers.friction_directions;
  const std::unordered_map<std::string, int> index = CheckPartNumbers(def, is3, check);

  // The scene's size and its length tolerance.
  out.scene_size_ = SceneSize(def, is3);
  const double tol =
      Tolerances::Scaled(out.scene_size_, 1.0, 1.0, 1.0, out.tolerance_override_).length;
  const double angle_tol = Tolerances{}.angle;
  CheckScale(def, is3, out.scene_size_, tol, check);

  // Each part's shape, then its mass properties.
  for (int i = 0; i < static_cast<int>(def.parts.size()); ++i) {
    const PartDef& p = def.parts[i];
    Part part = is3 ? Make3dPart(p, ShapePath(p, i), tol, check)
                    : Make2dPart(p, PartPath(p, i) + ".polygon", tol, check);
    part.name = p.name;
    part.fixed = p.fixed;
    part.tool = p.tool;
    out.parts_.push_back(std::move(part));
  }
  CheckMasses(def, out.parts_, check);
  for (const Part& p : out.parts_) {
    Vector3 lo = p.vertices[0], hi = lo;
    for (const Vector3& v : p.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double size = (hi - lo).norm();
    if (out.smallest_part_size_ == 0 || size < out.smallest_part_size_)
      out.smallest_part_size_ = size;
  }
  // Given interfaces say how the parts touch; their shapes may interpenetrate
  // (InterfaceDef): no overlap test then.
  out.overlap_depth_ = CheckOverlapDepth(def, is3, out.smallest_part_size_, check);
  if (def.interfaces.empty() && out.overlap_depth_ > 0)
    out.touching_overlaps_ =
        TouchingOverlaps(def, out.parts_, tol + out.overlap_allowance_, out.overlap_depth_, check);
  else if (def.interfaces.empty())
    CheckOverlaps(def, out.parts_, out.dimension_, tol + out.overlap_allowance_, check);

  const PartFinder find = [&](const std::string& name) {
    const auto it = index.find(name);
    return it == index.end() ? -1 : it->second;
  };
  out.pair_mu_ = MakeFrictionPairs(def, find, check);
  out.fixtures_ = MakeFixtures(def, out.parts_, is3, find, tol, angle_tol, check);
  out.interfaces_ = MakeInterfaces(def, is3, find, tol, check);

  // Tolerances scaled to the scene and its heaviest movable part.
  for (const Part& p : out.parts_) {
    if (!p.fixed) out.max_weight_ = std::max(out.max_weight_, p.mass * out.gravity_.norm());
  }
  out.tolerances_ = out.MakeTolerances(1.0);
  return out;
}

std::string Assembly::NameList(const std::vector<int>& parts) const {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + part(parts[i]).name;
  return out;
}

int Assembly::FindPart(const std::string& name) const {
  for (int i = 0; i < num_parts(); ++i) {
    if (parts_[i].name == name) return i;
  }
  return -1;
}

double Assembly::Friction(int i, int j) const {
  // Fixtures (the world) are frictionless.
  if (i < 0 || j < 0) return 0.0;
  const std::pair<int, int> key{std::min(i, j), std::max(i, j)};
  const auto it = std::lower_bound(
      pair_mu_.begin(), pair_mu_.end(), key,
      [](const auto& entry, const std::pair<int, int>& k) { return entry.first < k; });
  if (it != pair_mu_.end() && it->first == key) return it->second;
  return default_friction_;
}

bool Assembly::IsFrictionless() const {
  return default_friction_ == 0 &&
         std::all_of(pair_mu_.begin(), pair_mu_.end(), [](const auto& e) { return e.second == 0; });
}

Assembly Assembly::WithFriction(double default_mu, double pair_factor) const {
  CAIRN_CHECK(std::isfinite(default_mu) && default_mu >= 0 && std::isfinite(pair_factor) &&
              pair_factor >= 0);
  Assembly out = *this;
  out.default_friction_ = default_mu;
  for (auto& entry : out.pair_mu_) entry.second *= pair_factor;
  return out;
}

Assembly Assembly::WithGravity(const Vector3& g) const {
  CAIRN_CHECK(g.allFinite());
  Assembly out = *this;
  out.gravity_ = g;
  out.max_weight_ = 0;
  for (const Part& p : out.parts_)
    if (!p.fixed) out.max_weight_ = std::max(out.max_weight_, p.mass * g.norm());
  return out;
}

Assembly Assembly::WithHeld(const std::vector<int>& held) const {
  Assembly out = *this;
  for (const int p : held) {
    CAIRN_CHECK(p >= 0 && p < num_parts());
    out.parts_[p].fixed = true;
  }
  return out;
}

Assembly Assembly::WithFixtures(const std::vector<FixtureDef>& added) const {
  Assembly out = *this;
  for (const FixtureDef& f : added) {
    if (const auto fault = FixtureFault(f))
      throw std::invalid_argument("a fixel on '" + EscapedName(f.part) + "': " + *fault);
    out.fixtures_.push_back(Fixture{FindPart(f.part), f.point, f.normal.normalized()});
  }
  return out;
}

std::optional<std::string> Assembly::FixtureFault(const FixtureDef& f) const {
  const int part = FindPart(f.part);
  if (part < 0) return "no part named '" + EscapedName(f.part) + "'";
  if (!f.point.allFinite() || !f.normal.allFinite()) return "a coordinate is not finite";
  const double len = f.normal.norm();
  if (len == 0) return "the normal is zero";
  // The tolerances Create checks fixtures with.
  const double tol = Tolerances::Scaled(scene_size_, 1.0, 1.0, 1.0, tolerance_override_).length;
  if (const auto fault =
          FixtureContactFault(parts_[part], is_3d(), f, f.normal / len, tol, Tolerances{}.angle))
    return fault->second;
  return std::nullopt;
}

Tolerances Assembly::MakeTolerances(double dt) const {
  Tolerances t =
      Tolerances::Scaled(scene_size_, gravity_.norm(), dt, max_weight_, tolerance_override_);
  t.penetration = t.length + overlap_allowance_ + overlap_depth_;
  // Facets within the allowance of a curved surface have normals within
  // about allowance / size of it on a part of that size: the angle
  // tolerance of a tessellated model (kMaxApproximatedAngle at most).
  if (overlap_allowance_ > 0 && smallest_part_size_ > 0)
    t.angle = std::max(
        t.angle, std::min(overlap_allowance_ / smallest_part_size_, limits::kMaxApproximatedAngle));
  return t;
}

Pose Pose::Planar(const Vector2& translation, double angle) {
  Pose pose;
  pose.translation = Embed(translation);
  pose.rotation = Eigen::AngleAxisd(angle, Vector3::UnitZ()).toRotationMatrix();
  return pose;
}

Pose Pose::Translation(const Vector3& translation) {
  Pose pose;
  pose.translation = translation;
  return pose;
}

Vector3 Pose::Apply(const Vector3& p_assembled, const Vector3& centroid_assembled) const {
  return centroid_assembled + rotation * (p_assembled - centroid_assembled) + translation;
}

double Pose::angle() const { return std::atan2(rotation(1, 0), rotation(0, 0)); }

void Pose::Rotate(const Vector3& rotation_vector) {
  const double angle = rotation_vector.norm();
  if (angle == 0) return;
  rotation = Eigen::AngleAxisd(angle, rotation_vector / angle).toRotationMatrix() * rotation;
}

Configuration Configuration::Assembled(const Assembly& assembly) {
  Configuration config;
  // Tools are no part of the assembly: absent until a plan step grips them.
  config.present.resize(assembly.num_parts());
  for (int i = 0; i < assembly.num_parts(); ++i) config.present[i] = !assembly.part(i).tool;
  config.poses.assign(assembly.num_parts(), Pose{});
  return config;
}

Polygon Configuration::WorldPolygon(const Assembly& assembly, int i) const {
  const Part& part = assembly.part(i);
  const Pose& pose = poses.at(i);
  const Eigen::Matrix2d R = pose.rotation.topLeftCorner<2, 2>();
  const Vector2 c = part.centroid.head<2>(), t = pose.translation.head<2>();
  Polygon out;
  out.reserve(part.polygon.size());
  // A rotation keeps the counter-clockwise order.
  for (const Vector2& v : part.polygon) out.push_back(c + R * (v - c) + t);
  return out;
}

std::vector<Vector3> Configuration::WorldVertices(const Assembly& assembly, int i) const {
  const Part& part = assembly.part(i);
  std::vector<Vector3> out;
  out.reserve(part.vertices.size());
  for (const Vector3& v : part.vertices) out.push_back(poses.at(i).Apply(v, part.centroid));
  return out;
}

Eigen::Isometry3d Configuration::WorldTransform(const Assembly& assembly, int i) const {
  const Pose& pose = poses.at(i);
  const Vector3& c = assembly.part(i).centroid;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = pose.rotation;
  X.translation() = c + pose.translation - pose.rotation * c;
  return X;
}

Vector3 Configuration::WorldCentroid(const Assembly& assembly, int i) const {
  return assembly.part(i).centroid + poses.at(i).translation;
}

Matrix3 Configuration::WorldInertia(const Assembly& assembly, int i) const {
  const Matrix3& R = poses.at(i).rotation;
  return R * assembly.part(i).inertia * R.transpose();
}

}  // namespace cairn

#include "cairn/geometry/assembly.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "cairn/core/check.h"
#include "cairn/core/error.h"

namespace cairn {
namespace {

using Box = std::pair<Vector2, Vector2>;

std::string Indexed(const std::string& key, int i) { return key + "[" + std::to_string(i) + "]"; }

std::string Num(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

std::string Point(const Vector2& p) { return "(" + Num(p.x()) + ", " + Num(p.y()) + ")"; }

bool Finite(const Vector2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// Throws the InputError of one fault; all validation goes through it.
class Validator {
 public:
  explicit Validator(const std::string& file) : file_(file) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& message) const {
    throw InputError(file_, path, message);
  }
  void FiniteNumber(double x, const std::string& path) const {
    if (!std::isfinite(x)) Fail(path, "must be a finite number (got " + Num(x) + ")");
  }
  void FinitePoint(const Vector2& v, const std::string& path) const {
    if (!Finite(v)) Fail(path, "must have finite coordinates (got " + Point(v) + ")");
  }
  void Positive(double x, const std::string& path) const {
    FiniteNumber(x, path);
    if (x <= 0) Fail(path, "must be positive (got " + Num(x) + ")");
  }
  void NonNegative(double x, const std::string& path) const {
    FiniteNumber(x, path);
    if (x < 0) Fail(path, "must not be negative (got " + Num(x) + ")");
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

Assembly Assembly::Create(const AssemblyDef& def, const std::string& source_file) {
  const Validator check(source_file);
  Assembly out;
  out.name_ = def.name;

  // Scene-wide numbers.
  check.FinitePoint(def.gravity, "gravity");
  check.NonNegative(def.friction, "friction");
  check.FiniteNumber(def.tolerance, "tolerance");
  out.gravity_ = def.gravity;
  out.default_friction_ = def.friction;
  out.tolerance_override_ = def.tolerance > 0 ? def.tolerance : 0.0;

  // Names, mass numbers and vertex counts of every part.
  const int num_parts = static_cast<int>(def.parts.size());
  std::unordered_map<std::string, int> index;
  for (int i = 0; i < num_parts; ++i) {
    const PartDef& p = def.parts[i];
    const std::string path = Indexed("parts", i);
    if (p.name.empty()) check.Fail(path + ".name", "must not be empty");
    const auto [it, inserted] = index.emplace(p.name, i);
    if (!inserted) {
      check.Fail(path + ".name", "duplicate part name '" + p.name + "' (also " +
                                     Indexed("parts", it->second) + ")");
    }
    // A tool travels with the gripper, which a fixed part never does.
    if (p.fixed && p.tool) {
      check.Fail(path + ".tool", "part '" + p.name + "' cannot be both fixed and a tool");
    }
    if (p.density) check.Positive(*p.density, path + ".density");
    if (p.mass) check.Positive(*p.mass, path + ".mass");
    const int nv = static_cast<int>(p.polygon.size());
    if (nv < 3) {
      check.Fail(path + ".polygon",
                 "has " + std::to_string(nv) + " vertices; a polygon needs at least 3");
    }
    for (int k = 0; k < nv; ++k) {
      check.FinitePoint(p.polygon[k], path + ".polygon" + Indexed("", k));
    }
  }

  // The scene's size and its length tolerance.
  Box scene_box{Vector2(0, 0), Vector2(0, 0)};
  for (int i = 0; i < num_parts; ++i) {
    const Box b = BoundingBox(def.parts[i].polygon);
    scene_box =
        i == 0 ? b : Box{scene_box.first.cwiseMin(b.first), scene_box.second.cwiseMax(b.second)};
  }
  out.scene_size_ = (scene_box.second - scene_box.first).norm();
  const double tol =
      Tolerances::Scaled(out.scene_size_, 1.0, 1.0, 1.0, out.tolerance_override_).length;
  const double angle_tol = Tolerances{}.angle;

  // Each part's shape, then its mass properties.
  for (int i = 0; i < num_parts; ++i) {
    const PartDef& p = def.parts[i];
    const std::string path = Indexed("parts", i) + ".polygon";
    const int nv = static_cast<int>(p.polygon.size());
    for (int k = 1; k < nv; ++k) {
      for (int l = 0; l < k; ++l) {
        if ((p.polygon[k] - p.polygon[l]).norm() <= tol) {
          check.Fail(path + Indexed("", k), "self-intersecting: vertex " + std::to_string(k) +
                                                " repeats vertex " + std::to_string(l));
        }
      }
    }
    const Box box = BoundingBox(p.polygon);
    const double size = (box.second - box.first).norm();
    if (Collinear(p.polygon, tol)) check.Fail(path, "has zero area: its vertices are collinear");
    if (const auto s = FindSelfIntersection(p.polygon, tol)) {
      check.Fail(path, DescribeSelfIntersection(p.polygon, *s));
    }
    const double area = std::abs(SignedArea(p.polygon));
    if (area <= tol * size) {
      check.Fail(path, "has zero area (" + Num(area) + ", at most the tolerance times its size, " +
                           Num(tol * size) + ")");
    }

    Part part;
    part.name = p.name;
    part.fixed = p.fixed;
    part.tool = p.tool;
    part.polygon = p.polygon;
    MakeCounterClockwise(part.polygon);
    const PolygonMass pm = ComputePolygonMass(part.polygon);
    part.area = pm.area;
    part.centroid = pm.centroid;
    // An explicit mass wins over a density.
    part.mass = p.mass ? *p.mass : p.density.value_or(1.0) * pm.area;
    part.inertia = part.mass * pm.polar_moment / pm.area;
    out.parts_.push_back(std::move(part));
  }

  // Overlap between every pair of parts, skipping pairs whose bounding boxes
  // are apart (a sweep over boxes sorted by their left side). Of all the
  // overlapping pairs the one with the lowest indices is reported.
  std::vector<Box> boxes(num_parts);
  for (int i = 0; i < num_parts; ++i) boxes[i] = BoundingBox(out.parts_[i].polygon);
  std::vector<int> order(num_parts);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return boxes[a].first.x() < boxes[b].first.x(); });
  std::optional<std::pair<int, int>> worst;  // (later, earlier) index
  Vector2 witness(0, 0);
  for (int oi = 0; oi < num_parts; ++oi) {
    const int i = order[oi];
    for (int oj = oi + 1; oj < num_parts; ++oj) {
      const int j = order[oj];
      if (boxes[j].first.x() >= boxes[i].second.x() - tol) break;
      if (boxes[j].first.y() >= boxes[i].second.y() - tol ||
          boxes[i].first.y() >= boxes[j].second.y() - tol) {
        continue;
      }
      const std::pair<int, int> key{std::max(i, j), std::min(i, j)};
      if (worst && *worst <= key) continue;
      if (const auto w = FindOverlap(out.parts_[i].polygon, out.parts_[j].polygon, tol)) {
        worst = key;
        witness = *w;
      }
    }
  }
  if (worst) {
    const auto [later, earlier] = *worst;
    check.Fail(Indexed("parts", later),
               "part '" + out.parts_[later].name + "' overlaps part '" + out.parts_[earlier].name +
                   "' (" + Indexed("parts", earlier) + ") by more than the tolerance " + Num(tol) +
                   ", e.g. at " + Point(witness));
  }

  // Friction pairs.
  const auto find = [&](const std::string& name) {
    const auto it = index.find(name);
    return it == index.end() ? -1 : it->second;
  };
  for (int k = 0; k < static_cast<int>(def.friction_pairs.size()); ++k) {
    const FrictionPairDef& fp = def.friction_pairs[k];
    const std::string path = Indexed("friction_pairs", k);
    const int a = find(fp.part_a), b = find(fp.part_b);
    if (a < 0) check.Fail(path + ".parts[0]", "no part named '" + fp.part_a + "'");
    if (b < 0) check.Fail(path + ".parts[1]", "no part named '" + fp.part_b + "'");
    if (a == b) check.Fail(path + ".parts[1]", "names part '" + fp.part_a + "' twice");
    check.NonNegative(fp.mu, path + ".mu");
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    for (int l = 0; l < k; ++l) {
      if (out.pair_mu_[l].first == key) {
        check.Fail(path, "repeats the pair '" + fp.part_a + "', '" + fp.part_b + "' of " +
                             Indexed("friction_pairs", l));
      }
    }
    out.pair_mu_.push_back({key, fp.mu});
  }
  std::sort(out.pair_mu_.begin(), out.pair_mu_.end());

  // Fixtures: on their part's boundary, pushing into it.
  for (int f = 0; f < static_cast<int>(def.fixtures.size()); ++f) {
    const FixtureDef& fd = def.fixtures[f];
    const std::string path = Indexed("fixtures", f);
    const int part = find(fd.part);
    if (part < 0) check.Fail(path + ".part", "no part named '" + fd.part + "'");
    check.FinitePoint(fd.point, path + ".point");
    check.FinitePoint(fd.normal, path + ".normal");
    const double len = std::hypot(fd.normal.x(), fd.normal.y());
    if (len == 0) check.Fail(path + ".normal", "must not be zero");
    const Polygon& poly = out.parts_[part].polygon;
    const double dist = DistanceToBoundary(poly, fd.point);
    if (dist > tol) {
      check.Fail(path + ".point", Point(fd.point) + " is not on the boundary of part '" + fd.part +
                                      "' (distance " + Num(dist) + " > tolerance " + Num(tol) +
                                      ")");
    }
    const Vector2 n = fd.normal / len;
    if (!PointsInto(poly, fd.point, n, tol, angle_tol)) {
      check.Fail(path + ".normal", Point(fd.normal) + " points out of part '" + fd.part +
                                       "' (a fixel pushes: its normal must point into the part)");
    }
    out.fixtures_.push_back(Fixture{part, fd.point, n});
  }

  // Tolerances scaled to the scene and its heaviest movable part.
  for (const Part& p : out.parts_) {
    if (!p.fixed) out.max_weight_ = std::max(out.max_weight_, p.mass * out.gravity_.norm());
  }
  out.tolerances_ = out.MakeTolerances(1.0);
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

Tolerances Assembly::MakeTolerances(double dt) const {
  return Tolerances::Scaled(scene_size_, gravity_.norm(), dt, max_weight_, tolerance_override_);
}

Vector2 Pose2::Apply(const Vector2& p_assembled, const Vector2& centroid_assembled) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const Vector2 r = p_assembled - centroid_assembled;
  return centroid_assembled + Vector2(c * r.x() - s * r.y(), s * r.x() + c * r.y()) + translation;
}

Configuration Configuration::Assembled(const Assembly& assembly) {
  Configuration config;
  // Tools are no part of the assembly: absent until a plan step grips them.
  config.present.resize(assembly.num_parts());
  for (int i = 0; i < assembly.num_parts(); ++i) config.present[i] = !assembly.part(i).tool;
  config.poses.assign(assembly.num_parts(), Pose2{});
  return config;
}

Polygon Configuration::WorldPolygon(const Assembly& assembly, int i) const {
  const Part& part = assembly.part(i);
  const Pose2& pose = poses.at(i);
  Polygon out;
  out.reserve(part.polygon.size());
  // A rotation keeps the counter-clockwise order.
  for (const Vector2& v : part.polygon) out.push_back(pose.Apply(v, part.centroid));
  return out;
}

Vector2 Configuration::WorldCentroid(const Assembly& assembly, int i) const {
  return assembly.part(i).centroid + poses.at(i).translation;
}

}  // namespace cairn

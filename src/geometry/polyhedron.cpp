#include "cairn/geometry/polyhedron.h"

#include <Eigen/Geometry>  // IWYU pragma: keep
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <queue>
#include <stdexcept>
#include <utility>

#include "cairn/core/check.h"
#include "cairn/core/error.h"  // IWYU pragma: keep
#include "cairn/geometry/box_grid.h"
#include "cairn/geometry/polygon.h"

namespace cairn {
namespace {

using Triangle = std::array<int, 3>;

// Relative precision for the purely numerical decisions (a straight angle, a
// point on a diagonal) that are not the user's tolerance: 1e-12 of the size.
constexpr double kRelEps = 1e-12;

int Size(const std::vector<int>& v) { return static_cast<int>(v.size()); }

PolyhedronFault Fault(int face, const std::string& message) { return {face, message}; }

std::string FaceName(int f) { return "face " + std::to_string(f); }

std::string VertexPair(int a, int b) {
  return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

std::string EdgeName(int a, int b) { return "edge " + VertexPair(a, b); }

// Newell's normal of the polygon through `face`: its length is twice the area
// and it points to where the vertices run counter-clockwise. Computed about
// `center` for precision far from the origin.
Vector3 NewellNormal(const std::vector<Vector3>& vertices, const std::vector<int>& face,
                     const Vector3& center) {
  Vector3 n = Vector3::Zero();
  const int m = Size(face);
  for (int i = 0; i < m; ++i) {
    const Vector3 p = vertices[face[i]] - center;
    const Vector3 q = vertices[face[(i + 1) % m]] - center;
    n.x() += (p.y() - q.y()) * (p.z() + q.z());
    n.y() += (p.z() - q.z()) * (p.x() + q.x());
    n.z() += (p.x() - q.x()) * (p.y() + q.y());
  }
  return n;
}

Vector3 Centroid(const std::vector<Vector3>& vertices, const std::vector<int>& face) {
  Vector3 c = Vector3::Zero();
  for (int v : face) c += vertices[v];
  return c / static_cast<double>(face.size());
}

// Ear clipping of a simple counter-clockwise polygon; returns triangles of
// local indices, counter-clockwise. An ear's tip must be strictly convex and no
// other vertex may lie inside or on its triangle, so straight-angle vertices
// never end up on a diagonal and every triangle has positive area. A tip
// within `tol` (length) of the line through its neighbours is straight: mesh
// files print coordinates to 7–9 digits, so a vertex splitting an edge is off
// its line by far more than roundoff, and clipping it would leave the
// diagonal through (almost) a vertex of the face. O(n³), fine for faces of
// tens of vertices.
std::vector<Triangle> EarClip(const std::vector<Vector2>& p, double tol) {
  std::vector<int> idx(p.size());
  std::iota(idx.begin(), idx.end(), 0);
  double scale = 0;
  for (const Vector2& q : p) scale = std::max(scale, (q - p[0]).norm());
  // A vertex within tol of an ear's triangle blocks it, as one inside does.
  const double eps_len = std::max(kRelEps * scale, tol);
  const double eps_area = kRelEps * scale * scale;
  std::vector<Triangle> out;
  while (idx.size() > 3) {
    const int m = Size(idx);
    int chosen = -1;
    int most_convex = 0;
    double best_cross = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < m && chosen < 0; ++k) {
      const int prev = (k + m - 1) % m, next = (k + 1) % m;
      const Vector2& a = p[idx[prev]];
      const Vector2& b = p[idx[k]];
      const Vector2& c = p[idx[next]];
      const double cross = Cross2(b - a, c - b);
      if (cross > best_cross) {
        best_cross = cross;
        most_convex = k;
      }
      if (cross <= std::max(eps_area, tol * (c - a).norm())) continue;
      bool blocked = false;
      for (int j = 0; j < m && !blocked; ++j) {
        if (j == k || j == prev || j == next) continue;
        const Vector2& q = p[idx[j]];
        blocked = LineSide(a, b, q) >= -eps_len && LineSide(b, c, q) >= -eps_len &&
                  LineSide(c, a, q) >= -eps_len;
      }
      if (!blocked) chosen = k;
    }
    // Only roundoff on a nearly degenerate face leaves no ear: clip the most
    // convex vertex so the loop ends; the triangles still cover the face.
    if (chosen < 0) chosen = most_convex;
    out.push_back({idx[(chosen + m - 1) % m], idx[chosen], idx[(chosen + 1) % m]});
    idx.erase(idx.begin() + chosen);
  }
  out.push_back({idx[0], idx[1], idx[2]});
  return out;
}

// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection,
// 5.1.5).
Vector3 ClosestPointOnTriangle(const Vector3& p, const Vector3& a, const Vector3& b,
                               const Vector3& c) {
  const Vector3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vector3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Distance between segments [p1, q1] and [p2, q2] (Ericson 5.1.9).
double SegmentSegmentDistance(const Vector3& p1, const Vector3& q1, const Vector3& p2,
                              const Vector3& q2) {
  const Vector3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a == 0 && e == 0) return r.norm();
  if (a == 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e == 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p1 + d1 * s) - (p2 + d2 * t)).norm();
}

struct Tri3 {
  Vector3 a, b, c;
};

// Distance from segment [p, q] to a triangle of nonzero area: 0 when the
// segment pierces it, else the least of its endpoints' distances and its
// distances to the triangle's edges.
double SegmentTriangleDistance(const Vector3& p, const Vector3& q, const Tri3& t) {
  const Vector3 n = (t.b - t.a).cross(t.c - t.a).normalized();
  const double dp = n.dot(p - t.a), dq = n.dot(q - t.a);
  double d = std::min((p - ClosestPointOnTriangle(p, t.a, t.b, t.c)).norm(),
                      (q - ClosestPointOnTriangle(q, t.a, t.b, t.c)).norm());
  if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
    const Vector3 x = p + (q - p) * (dp / (dp - dq));
    d = std::min(d, (x - ClosestPointOnTriangle(x, t.a, t.b, t.c)).norm());
  }
  d = std::min(d, SegmentSegmentDistance(p, q, t.a, t.b));
  d = std::min(d, SegmentSegmentDistance(p, q, t.b, t.c));
  d = std::min(d, SegmentSegmentDistance(p, q, t.c, t.a));
  return d;
}

// Distance between two triangles of nonzero area. Two triangles that meet
// have an edge of one meeting the other, and two apart are closest at a
// vertex–face or an edge–edge pair, so six segment–triangle distances decide.
double TriangleDistance(const Tri3& s, const Tri3& t) {
  return std::min({SegmentTriangleDistance(s.a, s.b, t), SegmentTriangleDistance(s.b, s.c, t),
                   SegmentTriangleDistance(s.c, s.a, t), SegmentTriangleDistance(t.a, t.b, s),
                   SegmentTriangleDistance(t.b, t.c, s), SegmentTriangleDistance(t.c, t.a, s)});
}

// One triangle of a face, for the face–face intersection test.
struct FaceTriangle {
  int face;
  Triangle v;
  Vector3 lo, hi;  // bounding box
};

// True when triangles s and t (of different faces) meet anywhere but at the
// vertices and edge they share, within tol.
bool TrianglesIntersect(const std::vector<Vector3>& x, const FaceTriangle& s, const FaceTriangle& t,
                        double tol) {
  int shared_s[3], shared_t[3], n_shared = 0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (s.v[i] == t.v[j]) {
        shared_s[n_shared] = i;
        shared_t[n_shared] = j;
        ++n_shared;
      }
    }
  }
  const Tri3 ts{x[s.v[0]], x[s.v[1]], x[s.v[2]]};
  const Tri3 tt{x[t.v[0]], x[t.v[1]], x[t.v[2]]};
  if (n_shared == 0) return TriangleDistance(ts, tt) <= tol;
  if (n_shared == 1) {
    // Meeting beyond the shared vertex v, the two meet along a segment from v
    // that leaves one of them through the edge opposite v.
    const int i = shared_s[0], j = shared_t[0];
    return SegmentTriangleDistance(x[s.v[(i + 1) % 3]], x[s.v[(i + 2) % 3]], tt) <= tol ||
           SegmentTriangleDistance(x[t.v[(j + 1) % 3]], x[t.v[(j + 2) % 3]], ts) <= tol;
  }
  if (n_shared == 2) {
    // Sharing edge uv, they overlap only when folded flat onto each other:
    // s's third vertex within tol of the half-plane of t beyond uv.
    const Vector3& u = x[s.v[shared_s[0]]];
    const Vector3 e = (x[s.v[shared_s[1]]] - u).normalized();
    const Vector3 a = x[s.v[3 - shared_s[0] - shared_s[1]]] - u;
    const Vector3 b = x[t.v[3 - shared_t[0] - shared_t[1]]] - u;
    const Vector3 pa = a - e * e.dot(a), pb = b - e * e.dot(b);
    if (pa.dot(pb) <= 0) return false;
    const Vector3 hb = pb.normalized();
    return (pa - hb * hb.dot(pa)).norm() <= tol;
  }
  return false;  // the same triangle twice: caught as zero volume
}

}  // namespace

PolyhedronMass ComputePolyhedronMass(const std::vector<Vector3>& vertices,
                                     const std::vector<Triangle>& triangles) {
  PolyhedronMass mass;
  if (triangles.empty()) return mass;
  // Reference point: the mean of the triangles' corners, so that the sums stay
  // well conditioned for meshes far from the origin.
  Vector3 ref = Vector3::Zero();
  for (const Triangle& t : triangles) {
    for (int v : t) ref += vertices[v];
  }
  ref /= 3.0 * static_cast<double>(triangles.size());
  // Each outward triangle abc with the reference point spans a tetrahedron of
  // signed volume det(a, b, c)/6; over a closed surface the signed
  // tetrahedra sum to the solid (divergence theorem). For a tetrahedron with
  // one corner at the origin: ∫ r dV = V (a + b + c)/4 and
  // ∫ r rᵀ dV = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ), s = a + b + c.
  double volume = 0;
  Vector3 first = Vector3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const Triangle& t : triangles) {
    const Vector3 a = vertices[t[0]] - ref, b = vertices[t[1]] - ref, c = vertices[t[2]] - ref;
    const double v = a.dot(b.cross(c)) / 6;
    const Vector3 s = a + b + c;
    volume += v;
    first += v * s / 4;
    second +=
        v / 20 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  mass.volume = volume;
  if (volume == 0) {
    // No solid: no centroid. Report the moments about the reference point.
    mass.centroid = ref;
    mass.inertia = second.trace() * Eigen::Matrix3d::Identity() - second;
    return mass;
  }
  const Vector3 c = first / volume;
  const Eigen::Matrix3d central = second - volume * c * c.transpose();
  mass.centroid = ref + c;
  mass.inertia = central.trace() * Eigen::Matrix3d::Identity() - central;
  mass.inertia = (0.5 * (mass.inertia + mass.inertia.transpose())).eval();
  return mass;
}

namespace {

// Everything Check finds out, for Create to keep.
struct Checked {
  std::vector<std::vector<int>> faces;
  std::vector<Vector3> normals;
  std::vector<std::vector<Triangle>> triangles;
  PolyhedronMass mass;
};

// One face on its own: indices, area, planarity, simplicity; its normal and
// triangles into `out`.
std::optional<PolyhedronFault> CheckFace(const PolyhedronDef& def, int f, double tol,
                                         Checked& out) {
  const std::vector<Vector3>& x = def.vertices;
  const int num_vertices = static_cast<int>(x.size());
  const std::vector<int>& face = def.faces[f];
  const int m = Size(face);
  const std::string name = FaceName(f);
  if (m < 3) {
    return Fault(f, name + " has " + std::to_string(m) + " vertices (at least 3 needed)");
  }
  for (int i = 0; i < m; ++i) {
    if (face[i] < 0 || face[i] >= num_vertices) {
      return Fault(f, name + ": vertex index " + std::to_string(face[i]) +
                          " is out of range (there are " + std::to_string(num_vertices) +
                          " vertices)");
    }
  }
  for (int i = 0; i < m; ++i) {
    for (int j = i + 1; j < m; ++j) {
      if (face[i] == face[j]) {
        return Fault(f, name + " lists vertex " + std::to_string(face[i]) + " twice");
      }
    }
  }
  const Vector3 center = Centroid(x, face);
  const Vector3 newell = NewellNormal(x, face, center);
  const double area = newell.norm() / 2;
  double perimeter = 0;
  for (int i = 0; i < m; ++i) perimeter += (x[face[(i + 1) % m]] - x[face[i]]).norm();
  // A face of width w and perimeter P has area about w P / 2: zero area or
  // collinear vertices (within tol) make it degenerate.
  if (area <= std::max(tol * perimeter / 2, kRelEps * perimeter * perimeter)) {
    return Fault(f, name + " is degenerate: zero area or collinear vertices (area " +
                        FormatNumber(area) + ")");
  }
  const Vector3 n = newell / (2 * area);
  for (int v : face) {
    const double off = std::abs(n.dot(x[v] - center));
    if (off > tol) {
      return Fault(f, name + " is not planar: vertex " + std::to_string(v) + " is " +
                          FormatNumber(off) + " off its plane (tolerance " + FormatNumber(tol) +
                          ")");
    }
  }
  // Project onto the plane; (u, w, n) is right-handed, so the projection runs
  // counter-clockwise.
  const Vector3 u = n.unitOrthogonal();
  const Vector3 w = n.cross(u);
  Polygon poly;
  poly.reserve(m);
  for (int v : face) poly.push_back(Vector2(u.dot(x[v] - center), w.dot(x[v] - center)));
  if (const auto hit = FindSelfIntersection(poly, tol)) {
    const int a = hit->edge_a, b = hit->edge_b;
    return Fault(f, name + " is self-intersecting: its edges " +
                        VertexPair(face[a], face[(a + 1) % m]) + " and " +
                        VertexPair(face[b], face[(b + 1) % m]) + " cross or touch");
  }
  out.normals[f] = n;
  for (const Triangle& t : EarClip(poly, tol)) {
    out.triangles[f].push_back({face[t[0]], face[t[1]], face[t[2]]});
  }
  return std::nullopt;
}

using EdgeUsers = std::map<std::pair<int, int>, std::vector<std::pair<int, int>>>;

// The faces using each edge: key (low, high) → (face, direction: +1 low →
// high).
EdgeUsers EdgesOf(const PolyhedronDef& def) {
  const int num_faces = static_cast<int>(def.faces.size());
  EdgeUsers edges;
  for (int f = 0; f < num_faces; ++f) {
    const std::vector<int>& face = def.faces[f];
    const int m = Size(face);
    for (int i = 0; i < m; ++i) {
      const int a = face[i], b = face[(i + 1) % m];
      edges[{std::min(a, b), std::max(a, b)}].push_back({f, a < b ? 1 : -1});
    }
  }
  return edges;
}

// Each edge must be used by exactly two faces: else the surface is open or
// non-manifold.
std::optional<PolyhedronFault> CheckEdges(const PolyhedronDef& def, const EdgeUsers& edges) {
  const int num_faces = static_cast<int>(def.faces.size());
  for (int f = 0; f < num_faces; ++f) {
    const std::vector<int>& face = def.faces[f];
    const int m = Size(face);
    for (int i = 0; i < m; ++i) {
      const int a = face[i], b = face[(i + 1) % m];
      const auto& users = edges.at({std::min(a, b), std::max(a, b)});
      if (users.size() == 1) {
        return Fault(f, "the surface is open: " + EdgeName(a, b) + " of " + FaceName(f) +
                            " belongs to no other face");
      }
      if (users.size() > 2) {
        std::string list;
        for (const auto& [g, dir] : users) list += (list.empty() ? "" : ", ") + std::to_string(g);
        return Fault(users[2].first, "the surface is non-manifold: " + EdgeName(a, b) +
                                         " is shared by " + std::to_string(users.size()) +
                                         " faces (" + list + "), not 2");
      }
    }
  }
  return std::nullopt;
}

// Orientation: breadth-first over the faces, flipping a face when it runs a
// shared edge the same way as its (already oriented) neighbour; one shell.
std::optional<PolyhedronFault> Orient(const PolyhedronDef& def, const EdgeUsers& edges,
                                      Checked& out) {
  const int num_faces = static_cast<int>(def.faces.size());
  std::vector<std::vector<std::pair<int, int>>> neighbours(num_faces);  // (face, same way?)
  for (const auto& [key, users] : edges) {
    const bool same = users[0].second == users[1].second;
    neighbours[users[0].first].push_back({users[1].first, same ? 1 : 0});
    neighbours[users[1].first].push_back({users[0].first, same ? 1 : 0});
  }
  std::vector<int> flip(num_faces, -1);
  int shells = 0;
  int second_shell_face = -1;
  for (int start = 0; start < num_faces; ++start) {
    if (flip[start] >= 0) continue;
    ++shells;
    if (shells == 2) second_shell_face = start;
    flip[start] = 0;
    std::queue<int> queue;
    queue.push(start);
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop();
      for (const auto& [g, same] : neighbours[f]) {
        const int want = flip[f] ^ same;
        if (flip[g] < 0) {
          flip[g] = want;
          queue.push(g);
        } else if (flip[g] != want) {
          return Fault(g, FaceName(g) +
                              " cannot be oriented consistently with its neighbours: the "
                              "surface is not orientable");
        }
      }
    }
  }
  if (shells > 1) {
    return Fault(second_shell_face, "the faces form " + std::to_string(shells) +
                                        " separate shells (" + FaceName(second_shell_face) +
                                        " is not connected to face 0); one part must be one solid");
  }
  for (int f = 0; f < num_faces; ++f) {
    if (!flip[f]) continue;
    std::reverse(out.faces[f].begin(), out.faces[f].end());
    out.normals[f] = -out.normals[f];
    for (Triangle& t : out.triangles[f]) std::swap(t[1], t[2]);
  }
  return std::nullopt;
}

// Outward: positive volume (and not a zero one); the mass properties.
std::optional<PolyhedronFault> OrientOutward(const PolyhedronDef& def, double tol, Checked& out) {
  const std::vector<Vector3>& x = def.vertices;
  const int num_faces = static_cast<int>(def.faces.size());
  std::vector<Triangle> all;
  double surface = 0;
  for (int f = 0; f < num_faces; ++f) {
    for (const Triangle& t : out.triangles[f]) {
      all.push_back(t);
      surface += (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm() / 2;
    }
  }
  out.mass = ComputePolyhedronMass(x, all);
  // A solid thinner than tol everywhere has volume at most about tol × area / 2.
  if (std::abs(out.mass.volume) <=
      std::max(tol * surface / 2, kRelEps * surface * std::sqrt(surface))) {
    return Fault(-1, "the solid has zero volume (" + FormatNumber(out.mass.volume) + ")");
  }
  if (out.mass.volume < 0) {
    for (int f = 0; f < num_faces; ++f) {
      std::reverse(out.faces[f].begin(), out.faces[f].end());
      out.normals[f] = -out.normals[f];
      for (Triangle& t : out.triangles[f]) std::swap(t[1], t[2]);
    }
    for (Triangle& t : all) std::swap(t[1], t[2]);
    out.mass = ComputePolyhedronMass(x, all);
  }
  return std::nullopt;
}

// Faces intersecting each other. Every pair of triangles of different faces
// is tested: O(T²), acceptable for parts of tens to hundreds of faces; a
// bounding-volume hierarchy would be the next step. Bounding boxes apart by
// more than tol skip the exact test.
// Up to this many triangles every pair is tested (the first fault in index
// order reported); above, a sweep.
constexpr size_t kBruteForceTriangles = 128;

std::optional<PolyhedronFault> CheckFacesApart(const PolyhedronDef& def, double tol,
                                               const Checked& out) {
  const std::vector<Vector3>& x = def.vertices;
  const int num_faces = static_cast<int>(def.faces.size());
  std::vector<FaceTriangle> tris;
  for (int f = 0; f < num_faces; ++f) {
    for (const Triangle& t : out.triangles[f]) {
      FaceTriangle ft{f, t, x[t[0]], x[t[0]]};
      for (int v : t) {
        ft.lo = ft.lo.cwiseMin(x[v]);
        ft.hi = ft.hi.cwiseMax(x[v]);
      }
      tris.push_back(ft);
    }
  }
  // Triangles i < j of different faces whose boxes overlap (within tol) and
  // that intersect.
  const auto fault = [&](size_t i, size_t j) -> std::optional<PolyhedronFault> {
    const FaceTriangle& s = tris[std::min(i, j)];
    const FaceTriangle& t = tris[std::max(i, j)];
    if (s.face == t.face) return std::nullopt;
    if (((s.lo - t.hi).array() > tol).any() || ((t.lo - s.hi).array() > tol).any())
      return std::nullopt;
    if (!TrianglesIntersect(x, s, t, tol)) return std::nullopt;
    return Fault(s.face, FaceName(s.face) + " intersects " + FaceName(t.face) +
                             " (the surface is self-intersecting)");
  };
  // Small solids: every pair, the first in index order reported. Larger: a
  // sweep over the triangles' boxes sorted by their low x, each tested
  // against the active ones whose boxes reach it (O(T log T) plus the
  // overlapping pairs, against T² for every pair: a 60 000-triangle mesh).
  if (tris.size() <= kBruteForceTriangles) {
    for (size_t i = 0; i < tris.size(); ++i)
      for (size_t j = i + 1; j < tris.size(); ++j)
        if (auto f = fault(i, j)) return f;
    return std::nullopt;
  }
  std::vector<size_t> order(tris.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return tris[a].lo.x() < tris[b].lo.x() || (tris[a].lo.x() == tris[b].lo.x() && a < b);
  });
  std::vector<size_t> active;
  for (const size_t e : order) {
    size_t kept = 0;
    for (const size_t a : active) {
      if (tris[a].hi.x() + tol < tris[e].lo.x()) continue;  // left behind for good
      active[kept++] = a;
      if (auto f = fault(a, e)) return f;
    }
    active.resize(kept);
    active.push_back(e);
  }
  return std::nullopt;
}

std::optional<PolyhedronFault> Validate(const PolyhedronDef& def, double tol, Checked& out) {
  CAIRN_THROW_UNLESS(std::isfinite(tol) && tol >= 0,
                     "the polyhedron tolerance must be finite and >= 0 (got " << tol << ")");
  const int num_vertices = static_cast<int>(def.vertices.size());
  const int num_faces = static_cast<int>(def.faces.size());
  for (int v = 0; v < num_vertices; ++v) {
    if (!def.vertices[v].allFinite())
      return Fault(-1, "vertex " + std::to_string(v) + " is not finite");
  }
  if (num_faces < 4) {
    return Fault(-1, "a polyhedron needs at least 4 faces (got " + std::to_string(num_faces) + ")");
  }
  out.faces = def.faces;
  out.normals.assign(num_faces, Vector3::Zero());
  out.triangles.assign(num_faces, {});
  for (int f = 0; f < num_faces; ++f)
    if (auto fault = CheckFace(def, f, tol, out)) return fault;
  const EdgeUsers edges = EdgesOf(def);
  if (auto fault = CheckEdges(def, edges)) return fault;
  if (auto fault = Orient(def, edges, out)) return fault;
  if (auto fault = OrientOutward(def, tol, out)) return fault;
  return CheckFacesApart(def, tol, out);
}

}  // namespace

std::optional<PolyhedronFault> Polyhedron::Check(const PolyhedronDef& def, double tol) {
  Checked checked;
  return Validate(def, tol, checked);
}

Polyhedron Polyhedron::Create(const PolyhedronDef& def, double tol) {
  auto made = CheckAndCreate(def, tol);
  if (auto* fault = std::get_if<PolyhedronFault>(&made))
    throw std::invalid_argument(fault->message);
  return std::get<Polyhedron>(std::move(made));
}

std::variant<Polyhedron, PolyhedronFault> Polyhedron::CheckAndCreate(const PolyhedronDef& def,
                                                                     double tol) {
  Checked checked;
  if (auto fault = Validate(def, tol, checked)) return std::move(*fault);
  Polyhedron p;
  p.vertices_ = def.vertices;
  p.faces_ = std::move(checked.faces);
  p.normals_ = std::move(checked.normals);
  p.triangles_ = std::move(checked.triangles);
  p.mass_ = checked.mass;
  p.centroid_depth_ = -SignedDistance(p, Eigen::Isometry3d::Identity(), p.mass_.centroid);
  return p;
}

namespace {

// The solid angle of triangle abc seen from the origin (Van Oosterom and
// Strackee 1983), signed positive for a counter-clockwise triangle seen from
// outside when the origin is inside.
double SolidAngle(const Vector3& a, const Vector3& b, const Vector3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double num = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2 * std::atan2(num, den);
}

}  // namespace

double SignedDistance(const Polyhedron& poly, const Eigen::Isometry3d& X_WB, const Vector3& p_W) {
  // In the polyhedron's own frame.
  const Vector3 p = X_WB.inverse() * p_W;
  const auto& x = poly.vertices();
  double dist = std::numeric_limits<double>::infinity();
  double winding = 0;
  for (const auto& face : poly.face_triangles()) {
    for (const auto& t : face) {
      const Vector3& a = x[t[0]];
      const Vector3& b = x[t[1]];
      const Vector3& c = x[t[2]];
      dist = std::min(dist, (ClosestPointOnTriangle(p, a, b, c) - p).norm());
      winding += SolidAngle(a - p, b - p, c - p);
    }
  }
  // The winding number is 1 inside and 0 outside (4π steradians per turn).
  const bool inside = winding > 2 * M_PI;
  return inside ? -dist : dist;
}

namespace {

// A polyhedron's triangles in its own frame, with a grid over their boxes
// (BoxGrid) to find the ones near a point.
struct Triangles {
  std::vector<std::array<Vector3, 3>> corners;
  Vector3 lo{0, 0, 0}, hi{0, 0, 0};  // the polyhedron's box
  BoxGrid grid;

  static Triangles Of(const Polyhedron& poly, double tol) {
    std::vector<std::array<Vector3, 3>> corners;
    std::vector<Vector3> lo, hi;
    const auto& x = poly.vertices();
    for (const auto& face : poly.face_triangles())
      for (const auto& t : face) {
        corners.push_back({x[t[0]], x[t[1]], x[t[2]]});
        lo.push_back(x[t[0]].cwiseMin(x[t[1]]).cwiseMin(x[t[2]]));
        hi.push_back(x[t[0]].cwiseMax(x[t[1]]).cwiseMax(x[t[2]]));
      }
    Vector3 box_lo = x[0], box_hi = x[0];
    for (const Vector3& v : x) box_lo = box_lo.cwiseMin(v), box_hi = box_hi.cwiseMax(v);
    return {std::move(corners), box_lo, box_hi, BoxGrid(lo, hi, tol)};
  }
};

// The parity of the crossings of the ray from p along +axis (z = 2, x = 0,
// y = 1) with the closed surface `tris`: odd inside, even outside. Only the
// triangles the grid puts in the ray's column can cross it. With (a, b) the
// two other coordinates (cyclic after the axis), a crossing is counted where
// (p.a, p.b) lies strictly inside the triangle's projection on their plane
// (the signed areas w0, w1, w2 of its sub-triangles all of the sign of the
// whole, d) and the hit, (w0 a.k + w1 b.k + w2 c.k) / d along the axis, is
// beyond p. Where the ray grazes an edge or a vertex, or a triangle parallel
// to it (|w| within kGraze of the triangle's area scale), parity is not
// defined: nullopt, and the caller tries another axis.
std::optional<bool> RayParityInside(const Triangles& tris, const Vector3& p, int axis) {
  // Relative to the triangle's squared size: a signed area this small is a
  // graze (dimensionless).
  constexpr double kGraze = 1e-10;
  const int ia = (axis + 1) % 3, ib = (axis + 2) % 3;
  Vector3 end = p;
  end[axis] = std::max(p[axis], tris.hi[axis]);
  bool inside = false;
  for (const int k : tris.grid.QueryUnordered(p.cwiseMin(end), p.cwiseMax(end))) {
    const auto& c = tris.corners[k];
    const auto orient = [&](const Vector3& u, const Vector3& v, const Vector3& q) {
      return (v[ia] - u[ia]) * (q[ib] - u[ib]) - (v[ib] - u[ib]) * (q[ia] - u[ia]);
    };
    const double w0 = orient(c[1], c[2], p), w1 = orient(c[2], c[0], p), w2 = orient(c[0], c[1], p);
    const double scale = std::max(
        {(c[1] - c[0]).squaredNorm(), (c[2] - c[1]).squaredNorm(), (c[0] - c[2]).squaredNorm()});
    const double eps = kGraze * scale;
    const bool pos = w0 > eps && w1 > eps && w2 > eps;
    const bool neg = w0 < -eps && w1 < -eps && w2 < -eps;
    if (!pos && !neg) {
      // Outside the projection unless every |w| is small or all lean one way.
      const bool out = (w0 < -eps || w1 < -eps || w2 < -eps) && (w0 > eps || w1 > eps || w2 > eps);
      if (out) continue;
      return std::nullopt;  // on an edge or a vertex of the projection
    }
    const double d = w0 + w1 + w2;
    const double hit = (w0 * c[0][axis] + w1 * c[1][axis] + w2 * c[2][axis]) / d;
    if (hit > p[axis]) inside = !inside;
  }
  return inside;
}

// Whether p (own frame) is inside the closed surface `tris`: by a ray's
// parity, along +z, then +x, then +y (an axis-aligned model's vertical ray
// through p often grazes an edge, a horizontal one rarely at the same time);
// where all three graze, by the winding number, which needs every triangle.
bool Inside(const Triangles& tris, const Vector3& p) {
  for (const int axis : {2, 0, 1})
    if (const std::optional<bool> parity = RayParityInside(tris, p, axis)) return *parity;
  double winding = 0;
  for (const auto& c : tris.corners) winding += SolidAngle(c[0] - p, c[1] - p, c[2] - p);
  return winding > 2 * M_PI;
}

// SignedDistance(poly, p) < −tol for a point p in poly's own frame, cheapest
// test first: outside the bounding box grown by tol it cannot be; within tol
// of a triangle (only those the grid puts near p can be) it is not; only
// then inside at all? (Inside).
bool DeeperInside(const Triangles& tris, const Vector3& p, double tol) {
  if ((p.array() < tris.lo.array() - tol).any() || (p.array() > tris.hi.array() + tol).any())
    return false;
  for (const int k : tris.grid.QueryUnordered(p, p)) {
    const auto& c = tris.corners[k];
    if ((ClosestPointOnTriangle(p, c[0], c[1], c[2]) - p).norm() <= tol) return false;
  }
  return Inside(tris, p);
}

// A point of `a` deeper than tol inside `b`, among a's sample points.
// The points of `a` (own frame) tested against another solid: its vertices,
// the centroid and edge midpoints of its face triangles, and its centroid,
// which catches a solid wholly inside the other, but only if it is inside its
// own solid: a non-convex one's (a U, an arch) may lie in the gap, where
// another part may rightly be.
std::vector<Vector3> OverlapSamples(const Polyhedron& a, double tol) {
  const auto& x = a.vertices();
  std::vector<Vector3> samples;
  if (a.centroid_depth() > tol) samples.push_back(a.mass().centroid);
  for (const Vector3& v : x) samples.push_back(v);
  for (const auto& face : a.face_triangles())
    for (const auto& t : face) {
      samples.push_back((x[t[0]] + x[t[1]] + x[t[2]]) / 3);
      for (int k = 0; k < 3; ++k) samples.push_back((x[t[k]] + x[t[(k + 1) % 3]]) / 2);
    }
  return samples;
}

// The first half-width of NearestTriangleDistance's box for a point of no
// known depth, as a fraction of the solid's box diagonal (dimensionless).
constexpr double kNearestStart = 1e-3;

// The distance from p to the nearest of `tris` (own frame): the triangles in
// a box about p that doubles until one lies within its half-width (any
// triangle nearer than that meets the box).
double NearestTriangleDistance(const Triangles& tris, const Vector3& p, double start) {
  const double reach = (tris.hi - tris.lo).norm() + (p - tris.lo).norm();
  for (double r = start;; r *= 2) {
    double best = std::numeric_limits<double>::infinity();
    for (const int k :
         tris.grid.QueryUnordered(p - Vector3::Constant(r), p + Vector3::Constant(r))) {
      const auto& c = tris.corners[k];
      best = std::min(best, (ClosestPointOnTriangle(p, c[0], c[1], c[2]) - p).norm());
    }
    if (best <= r || r > reach) return best;
  }
}

}  // namespace

// A prepared solid's grids (own frame): its triangles (inside tests), its
// sample points, and its faces for the edge crossings of EdgeThroughFace:
// normals, plane offsets and boxes grown by tol, the solid's box and a grid
// over the face boxes.
struct PreparedSolid::Grids {
  Triangles tris;
  std::vector<Vector3> samples;
  std::vector<Vector3> normal, face_lo, face_hi;
  std::vector<double> offset;
  Vector3 lo{0, 0, 0}, hi{0, 0, 0};
  BoxGrid faces;
};

namespace {

PreparedSolid::Grids MakeGrids(const Polyhedron& b, double tol) {
  const auto& xb = b.vertices();
  const int nf = static_cast<int>(b.faces().size());
  std::vector<Vector3> normal(nf), face_lo(nf), face_hi(nf);
  std::vector<double> offset(nf);
  Vector3 lo = xb[0], hi = xb[0];
  for (int f = 0; f < nf; ++f) {
    normal[f] = b.face_normals()[f];
    offset[f] = normal[f].dot(xb[b.faces()[f][0]]);
    face_lo[f] = face_hi[f] = xb[b.faces()[f][0]];
    for (const int v : b.faces()[f]) {
      face_lo[f] = face_lo[f].cwiseMin(xb[v]);
      face_hi[f] = face_hi[f].cwiseMax(xb[v]);
    }
    face_lo[f].array() -= tol;
    face_hi[f].array() += tol;
    lo = lo.cwiseMin(face_lo[f]);
    hi = hi.cwiseMax(face_hi[f]);
  }
  BoxGrid faces(face_lo, face_hi, 0);  // the boxes are grown by tol already
  return {Triangles::Of(b, tol),
          OverlapSamples(b, tol),
          std::move(normal),
          std::move(face_lo),
          std::move(face_hi),
          std::move(offset),
          lo,
          hi,
          std::move(faces)};
}

// A sample point of `a` deeper than tol inside `b` (world), if any.
std::optional<Vector3> SampleInside(const PreparedSolid& a, const Eigen::Isometry3d& X_WA,
                                    const PreparedSolid& b, const Eigen::Isometry3d& X_WB) {
  const Eigen::Isometry3d X_BA = X_WB.inverse() * X_WA;
  for (const Vector3& s : a.grids().samples)
    if (DeeperInside(b.grids().tris, X_BA * s, b.tol())) return X_WA * s;
  return std::nullopt;
}

// The deepest of a's samples inside b (deeper than tol): its depth, and the
// point (world) in *deepest.
double DeepestSampleInside(const PreparedSolid& a, const Eigen::Isometry3d& X_WA,
                           const PreparedSolid& b, const Eigen::Isometry3d& X_WB,
                           Vector3* deepest) {
  const Triangles& tris = b.grids().tris;
  const double tol = b.tol();
  const Eigen::Isometry3d X_BA = X_WB.inverse() * X_WA;
  double depth = 0;
  for (const Vector3& s : a.grids().samples) {
    const Vector3 p = X_BA * s;
    if (!DeeperInside(tris, p, tol)) continue;
    const double d = NearestTriangleDistance(tris, p, std::max(tol, depth));
    if (d > depth) depth = d, *deepest = X_WA * s;
  }
  return depth;
}

// An edge of `a` crossing a face of `b` properly (both ends more than tol off
// the face's plane, the crossing more than tol inside the face polygon) and
// deeper than tol inside b somewhere between two of its crossings of b's
// surface (tested at the middle of each stretch between them). A crossing
// alone does not show depth: a pin's long edge, on its true cylinder, passes
// through the slightly tilted facets of its hole's wall, which cut into the
// hole by up to the chordal tolerance, and stays within that of them
// (the shear mold's rod 14_001 in bush 13_001; docs/step-format.md).
// Computed in b's frame, where its faces were prepared; the point returned
// is in the world.
std::optional<Vector3> EdgeThroughFace(const PreparedSolid& pa, const Eigen::Isometry3d& X_WA,
                                       const PreparedSolid& pb, const Eigen::Isometry3d& X_WB) {
  const Polyhedron &a = pa.polyhedron(), &b = pb.polyhedron();
  const PreparedSolid::Grids& g = pb.grids();
  const double tol = pb.tol();
  const Eigen::Isometry3d X_BA = X_WB.inverse() * X_WA;
  std::vector<Vector3> xa;
  xa.reserve(a.vertices().size());
  for (const Vector3& v : a.vertices()) xa.push_back(X_BA * v);
  const auto& xb = b.vertices();
  // The crossing point lies on the face, so an edge whose box misses a face's
  // box does not cross it, and one that misses b's box crosses none.
  const auto boxes_apart = [](const Vector3& lo1, const Vector3& hi1, const Vector3& lo2,
                              const Vector3& hi2) {
    return (lo1.array() > hi2.array()).any() || (lo2.array() > hi1.array()).any();
  };
  // Whether the point `hit` of face f's plane is in one of its triangles.
  const auto in_face = [&](int f, const Vector3& hit) {
    for (const auto& t : b.face_triangles()[f]) {
      const Vector3 &ta = xb[t[0]], &tb = xb[t[1]], &tc = xb[t[2]];
      const Vector3& n = g.normal[f];
      if (n.dot((tb - ta).cross(hit - ta)) >= 0 && n.dot((tc - tb).cross(hit - tb)) >= 0 &&
          n.dot((ta - tc).cross(hit - tc)) >= 0)
        return true;
    }
    return false;
  };
  // The distance from such a point to the face polygon's edges.
  const auto edge_distance = [&](int f, const Vector3& hit) {
    const auto& fb = b.faces()[f];
    const int k = static_cast<int>(fb.size());
    double edge_dist = std::numeric_limits<double>::infinity();
    for (int e = 0; e < k; ++e) {
      const Vector3 &u = xb[fb[e]], &w = xb[fb[(e + 1) % k]];
      const double s = std::clamp((hit - u).dot(w - u) / (w - u).squaredNorm(), 0.0, 1.0);
      edge_dist = std::min(edge_dist, (u + s * (w - u) - hit).norm());
    }
    return edge_dist;
  };
  std::vector<double> crossings;
  for (const auto& face : a.faces()) {
    const int m = static_cast<int>(face.size());
    for (int i = 0; i < m; ++i) {
      const Vector3& p = xa[face[i]];
      const Vector3& q = xa[face[(i + 1) % m]];
      if (face[i] > face[(i + 1) % m]) continue;  // each edge once
      const Vector3 e_lo = p.cwiseMin(q), e_hi = p.cwiseMax(q);
      if (boxes_apart(e_lo, e_hi, g.lo, g.hi)) continue;
      bool proper = false;
      crossings.assign({0.0, 1.0});
      for (const int f : g.faces.QueryUnordered(e_lo, e_hi)) {  // crossings sorted below
        if (boxes_apart(e_lo, e_hi, g.face_lo[f], g.face_hi[f])) continue;
        const double dp = g.normal[f].dot(p) - g.offset[f], dq = g.normal[f].dot(q) - g.offset[f];
        if ((dp > 0) == (dq > 0) || dp == dq) continue;
        const double t = dp / (dp - dq);
        const Vector3 hit = p + (q - p) * t;
        if (!in_face(f, hit)) continue;
        crossings.push_back(t);
        proper = proper || (((dp > tol && dq < -tol) || (dp < -tol && dq > tol)) &&
                            edge_distance(f, hit) > tol);
      }
      if (!proper) continue;
      std::sort(crossings.begin(), crossings.end());
      for (size_t k = 0; k + 1 < crossings.size(); ++k) {
        const Vector3 mid = p + (q - p) * (0.5 * (crossings[k] + crossings[k + 1]));
        if (DeeperInside(g.tris, mid, tol)) return X_WB * mid;
      }
    }
  }
  return std::nullopt;
}

}  // namespace

PreparedSolid::PreparedSolid(const Polyhedron& poly, double tol)
    : poly_(&poly), tol_(tol), grids_(std::make_unique<Grids>(MakeGrids(poly, tol))) {}
PreparedSolid::~PreparedSolid() = default;
PreparedSolid::PreparedSolid(PreparedSolid&&) noexcept = default;
PreparedSolid& PreparedSolid::operator=(PreparedSolid&&) noexcept = default;

double PolyhedronOverlapDepth(const Polyhedron& a, const Eigen::Isometry3d& X_WA,
                              const Polyhedron& b, const Eigen::Isometry3d& X_WB, double tol,
                              Vector3* deepest) {
  Vector3 in_b{0, 0, 0}, in_a{0, 0, 0};
  const PreparedSolid pa(a, tol), pb(b, tol);
  const double depth_in_b = DeepestSampleInside(pa, X_WA, pb, X_WB, &in_b);
  const double depth_in_a = DeepestSampleInside(pb, X_WB, pa, X_WA, &in_a);
  if (deepest) *deepest = depth_in_b >= depth_in_a ? in_b : in_a;
  return std::max(depth_in_b, depth_in_a);
}

std::optional<Vector3> FindPolyhedronOverlap(const Polyhedron& a, const Eigen::Isometry3d& X_WA,
                                             const Polyhedron& b, const Eigen::Isometry3d& X_WB,
                                             double tol) {
  return FindPolyhedronOverlap(PreparedSolid(a, tol), X_WA, PreparedSolid(b, tol), X_WB);
}

double SignedDistance(const PreparedSolid& b, const Eigen::Isometry3d& X_WB, const Vector3& p_W) {
  const PreparedSolid::Grids& g = b.grids();
  const Vector3 p = X_WB.inverse() * p_W;
  const double start = std::max(b.tol(), kNearestStart * (g.tris.hi - g.tris.lo).norm());
  const double dist = NearestTriangleDistance(g.tris, p, start);
  return Inside(g.tris, p) ? -dist : dist;
}

std::optional<Vector3> FindPolyhedronOverlap(const PreparedSolid& a, const Eigen::Isometry3d& X_WA,
                                             const PreparedSolid& b,
                                             const Eigen::Isometry3d& X_WB) {
  CAIRN_THROW_UNLESS(a.tol() == b.tol(),
                     "FindPolyhedronOverlap: the two solids were prepared at different tolerances");
  if (auto p = SampleInside(a, X_WA, b, X_WB)) return p;
  if (auto p = SampleInside(b, X_WB, a, X_WA)) return p;
  if (auto p = EdgeThroughFace(a, X_WA, b, X_WB)) return p;
  if (auto p = EdgeThroughFace(b, X_WB, a, X_WA)) return p;
  return std::nullopt;
}

}  // namespace cairn

#include "cairn/geometry/polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cairn/core/check.h"

namespace cairn {
namespace {

int Size(const Polygon& poly) { return static_cast<int>(poly.size()); }

// Distance between the segments [a0, a1] and [b0, b1]: 0 when they cross,
// else the least of the four endpoint-to-segment distances.
double SegmentDistance(const Vector2& a0, const Vector2& a1, const Vector2& b0, const Vector2& b1) {
  const double s0 = Cross2(a1 - a0, b0 - a0), s1 = Cross2(a1 - a0, b1 - a0);
  const double t0 = Cross2(b1 - b0, a0 - b0), t1 = Cross2(b1 - b0, a1 - b0);
  if (((s0 < 0 && s1 > 0) || (s0 > 0 && s1 < 0)) && ((t0 < 0 && t1 > 0) || (t0 > 0 && t1 < 0))) {
    return 0.0;
  }
  return std::min({DistanceToSegment(b0, a0, a1), DistanceToSegment(b1, a0, a1),
                   DistanceToSegment(a0, b0, b1), DistanceToSegment(a1, b0, b1)});
}

}  // namespace

double SignedArea(const Polygon& poly) {
  const int n = Size(poly);
  if (n < 3) return 0.0;
  // Shoelace about the first vertex (less cancellation far from the origin).
  const Vector2& o = poly[0];
  double twice = 0;
  for (int i = 1; i + 1 < n; ++i) twice += Cross2(poly[i] - o, poly[i + 1] - o);
  return 0.5 * twice;
}

void MakeCounterClockwise(Polygon& poly) {
  // Keep vertex 0 first so that vertex 0 still names the same point.
  if (SignedArea(poly) < 0) std::reverse(poly.begin() + 1, poly.end());
}

// Green's theorem over the edges (p_i, p_{i+1}) with c_i = p_i × p_{i+1}, in
// coordinates relative to a reference point o (the first vertex):
//   A      = ½ Σ c_i
//   A x̄    = ⅙ Σ c_i (p_i + p_{i+1})
//   J_o    = ¹⁄₁₂ Σ c_i (|p_i|² + p_i·p_{i+1} + |p_{i+1}|²)
// and the parallel-axis theorem moves J_o to the centroid: J = J_o − A |x̄|².
// All three are signed by the orientation, so dividing by A and flipping the
// sign of a clockwise polygon gives the same result for either orientation.
PolygonMass ComputePolygonMass(const Polygon& poly) {
  PolygonMass m;
  const int n = Size(poly);
  if (n < 3) return m;
  const Vector2& o = poly[0];
  double twice_area = 0, j_o = 0;
  Vector2 first_moment(0, 0);  // 6 · ∫ r dA (relative to o)
  for (int i = 0; i < n; ++i) {
    const Vector2 p = poly[i] - o;
    const Vector2 q = poly[(i + 1) % n] - o;
    const double c = Cross2(p, q);
    twice_area += c;
    first_moment += c * (p + q);
    j_o += c * (p.squaredNorm() + p.dot(q) + q.squaredNorm());
  }
  const double area = 0.5 * twice_area;
  if (area == 0) {
    m.centroid = o;
    return m;
  }
  const Vector2 centroid_rel = first_moment / (6.0 * area);
  j_o /= 12.0;
  const double sign = area < 0 ? -1.0 : 1.0;
  m.area = sign * area;
  m.centroid = o + centroid_rel;
  m.polar_moment = sign * (j_o - area * centroid_rel.squaredNorm());
  return m;
}

namespace {

// Whether edges i < j of the polygon touch (within tol): adjacent ones when
// they fold back onto each other (either far end on the other edge), others
// when they come within tol anywhere.
bool EdgesTouch(const Polygon& poly, int i, int j, double tol) {
  const int n = Size(poly);
  const Vector2& a0 = poly[i];
  const Vector2& a1 = poly[(i + 1) % n];
  const Vector2& b0 = poly[j];
  const Vector2& b1 = poly[(j + 1) % n];
  if (j == i + 1)  // sharing a1 == b0
    return DistanceToSegment(b1, a0, a1) <= tol || DistanceToSegment(a0, b0, b1) <= tol;
  if (i == 0 && j == n - 1)  // sharing a0 == b1, across the closing vertex
    return DistanceToSegment(b0, a0, a1) <= tol || DistanceToSegment(a1, b0, b1) <= tol;
  return SegmentDistance(a0, a1, b0, b1) <= tol;
}

// Up to this many vertices every pair of edges is tested, and the first
// touching pair in (i, j) order is reported; above it, a sweep.
constexpr int kBruteForceVertices = 64;

// A sweep over the edges' boxes (grown by tol) sorted by their low x: an
// edge is tested only against the edges whose boxes overlap its own. For a
// simple polygon that is O(n log n) plus the overlapping pairs (a 60 000-gon
// circle: ~10⁵ tests, against 1.8·10⁹ for every pair). The first touching
// pair in sweep order is reported (deterministic: ties in x by index).
std::optional<SelfIntersection> SweepSelfIntersection(const Polygon& poly, double tol) {
  const int n = Size(poly);
  struct Box {
    double x0, x1, y0, y1;
  };
  std::vector<Box> box(n);
  for (int i = 0; i < n; ++i) {
    const Vector2& a = poly[i];
    const Vector2& b = poly[(i + 1) % n];
    box[i] = {std::min(a.x(), b.x()) - tol, std::max(a.x(), b.x()) + tol,
              std::min(a.y(), b.y()) - tol, std::max(a.y(), b.y()) + tol};
  }
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return box[a].x0 < box[b].x0 || (box[a].x0 == box[b].x0 && a < b);
  });
  std::vector<int> active;
  for (int e : order) {
    size_t kept = 0;
    for (const int a : active) {
      if (box[a].x1 < box[e].x0) continue;  // left behind for good
      active[kept++] = a;
      if (box[a].y1 < box[e].y0 || box[e].y1 < box[a].y0) continue;
      const int i = std::min(a, e), j = std::max(a, e);
      if (EdgesTouch(poly, i, j, tol)) return SelfIntersection{i, j};
    }
    active.resize(kept);
    active.push_back(e);
  }
  return std::nullopt;
}

}  // namespace

std::optional<SelfIntersection> FindSelfIntersection(const Polygon& poly, double tol) {
  const int n = Size(poly);
  if (n < 3) return std::nullopt;
  // A zero-length edge i (a vertex repeated next to itself): its neighbours
  // i−1 and i+1 meet at the repeated point.
  for (int i = 0; i < n; ++i) {
    if ((poly[(i + 1) % n] - poly[i]).norm() <= tol) {
      const int prev = (i + n - 1) % n, next = (i + 1) % n;
      return SelfIntersection{std::min(prev, next), std::max(prev, next)};
    }
  }
  if (n > kBruteForceVertices) return SweepSelfIntersection(poly, tol);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (EdgesTouch(poly, i, j, tol)) return SelfIntersection{i, j};
  return std::nullopt;
}

double DistanceToSegment(const Vector2& p, const Vector2& a, const Vector2& b) {
  const Vector2 d = b - a;
  const double len2 = d.squaredNorm();
  if (len2 == 0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(d) / len2, 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

double DistanceToBoundary(const Polygon& poly, const Vector2& p) {
  const int n = Size(poly);
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    best = std::min(best, DistanceToSegment(p, poly[i], poly[(i + 1) % n]));
  }
  return best;
}

bool ContainsPoint(const Polygon& poly, const Vector2& p) {
  // Crossing number: count the edges that cross the horizontal ray to the
  // right of p (half-open in y, so a vertex on the ray counts once).
  const int n = Size(poly);
  bool inside = false;
  for (int i = 0, j = n - 1; i < n; j = i++) {
    const Vector2& a = poly[i];
    const Vector2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) inside = !inside;
    }
  }
  return inside;
}

double SignedDepth(const Polygon& poly, const Vector2& p) {
  const double d = DistanceToBoundary(poly, p);
  return ContainsPoint(poly, p) ? d : -d;
}

std::pair<Vector2, Vector2> BoundingBox(const Polygon& poly) {
  if (poly.empty()) return {Vector2(0, 0), Vector2(0, 0)};
  Vector2 lo = poly[0], hi = poly[0];
  for (const Vector2& v : poly) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return {lo, hi};
}

// Ear clipping over a doubly linked ring of the remaining vertices. A vertex
// is an ear when it turns left by more than tol and no remaining reflex
// vertex lies in its triangle (boundary included); only reflex vertices can
// lie in an ear's triangle, and a reflex vertex only turns convex as its
// neighbours are clipped, so they are the ones tested.
std::vector<std::array<int, 3>> Triangulate(const Polygon& ccw_poly, double tol) {
  const int n = Size(ccw_poly);
  std::vector<std::array<int, 3>> out;
  if (n < 3) return out;
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  std::vector<char> removed(n, 0);
  const auto turn = [&](int i) {
    return LineSide(ccw_poly[prev[i]], ccw_poly[i], ccw_poly[next[i]]);
  };
  const auto unlink = [&](int i) {
    removed[i] = 1;
    next[prev[i]] = next[i];
    prev[next[i]] = prev[i];
  };
  // Vertices on a straight line first, so that no ear takes one of them.
  int remaining = n;
  for (int i = 0, seen = 0; remaining >= 3 && seen < remaining;) {
    const int after = next[i];
    if (std::abs(turn(i)) <= tol) {
      unlink(i);
      --remaining;
      seen = 0;
    } else {
      ++seen;
    }
    i = after;
  }
  std::vector<int> reflex;
  for (int i = 0; i < n; ++i)
    if (!removed[i] && turn(i) < -tol) reflex.push_back(i);
  const auto in_triangle = [&](int a, int b, int c, int r) {
    const Vector2 &pa = ccw_poly[a], &pb = ccw_poly[b], &pc = ccw_poly[c], &p = ccw_poly[r];
    return LineSide(pa, pb, p) >= 0 && LineSide(pb, pc, p) >= 0 && LineSide(pc, pa, p) >= 0;
  };
  const auto is_ear = [&](int i) {
    const int a = prev[i], c = next[i];
    for (const int r : reflex)
      if (!removed[r] && r != a && r != c && r != i && turn(r) < -tol && in_triangle(a, i, c, r))
        return false;
    return true;
  };
  int i = 0;
  while (removed[i]) ++i;
  int since_progress = 0;
  while (remaining >= 3) {
    if (since_progress > remaining) return {};  // no ear: not a simple polygon
    const double t = turn(i);
    if (std::abs(t) <= tol) {  // on a straight line: no triangle
      const int after = next[i];
      unlink(i);
      --remaining;
      i = after;
      since_progress = 0;
    } else if (t > tol && is_ear(i)) {
      out.push_back({prev[i], i, next[i]});
      const int after = next[i];
      unlink(i);
      --remaining;
      i = after;
      since_progress = 0;
    } else {
      i = next[i];
      ++since_progress;
    }
  }
  return out;
}

Vector2 EdgeNormal(const Polygon& ccw_poly, int i) {
  const int n = Size(ccw_poly);
  CAIRN_ASSERT(n >= 2 && i >= 0 && i < n);
  const Vector2 d = ccw_poly[(i + 1) % n] - ccw_poly[i];
  const double len = d.norm();
  if (len == 0) return Vector2(0, 0);
  // Right of the edge direction: outward for a counter-clockwise polygon.
  return Vector2(d.y(), -d.x()) / len;
}

// Signed distance of p from the line through a, b (positive on the left).
double LineSide(const Vector2& a, const Vector2& b, const Vector2& p) {
  const Vector2 d = b - a;
  const double len = d.norm();
  return len > 0 ? Cross2(d, p - a) / len : 0.0;
}

// True when the segments cross properly with margin: each one's endpoints lie
// on opposite sides of the other's line, farther than tol from it.
bool SegmentsCrossProperly(const Vector2& a0, const Vector2& a1, const Vector2& b0,
                           const Vector2& b1, double tol) {
  const auto opposite = [tol](double s, double t) {
    return (s > tol && t < -tol) || (s < -tol && t > tol);
  };
  return opposite(LineSide(b0, b1, a0), LineSide(b0, b1, a1)) &&
         opposite(LineSide(a0, a1, b0), LineSide(a0, a1, b1));
}

// A point inside both counter-clockwise polygons at depth more than tol, if
// there is one: (a) a vertex of one deep inside the other; (b) two edges
// crossing properly; (c) for coincident shapes, a point just inside an edge
// midpoint of one lying deep inside the other.
std::optional<Vector2> FindOverlap(const Polygon& a, const Polygon& b, double tol) {
  for (const Vector2& v : a) {
    if (SignedDepth(b, v) > tol) return v;
  }
  for (const Vector2& v : b) {
    if (SignedDepth(a, v) > tol) return v;
  }
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  for (int i = 0; i < na; ++i) {
    const Vector2 &a0 = a[i], &a1 = a[(i + 1) % na];
    for (int j = 0; j < nb; ++j) {
      const Vector2 &b0 = b[j], &b1 = b[(j + 1) % nb];
      if (SegmentsCrossProperly(a0, a1, b0, b1, tol)) {
        // The crossing point, as the witness.
        const double s0 = LineSide(b0, b1, a0), s1 = LineSide(b0, b1, a1);
        return Vector2(a0 + (s0 / (s0 - s1)) * (a1 - a0));
      }
    }
  }
  const auto midpoints_inside = [tol](const Polygon& p,
                                      const Polygon& q) -> std::optional<Vector2> {
    const int n = static_cast<int>(p.size());
    for (int i = 0; i < n; ++i) {
      const Vector2 m = 0.5 * (p[i] + p[(i + 1) % n]) - 2.0 * tol * EdgeNormal(p, i);
      if (SignedDepth(q, m) > tol) return m;
    }
    return std::nullopt;
  };
  if (auto m = midpoints_inside(a, b)) return m;
  return midpoints_inside(b, a);
}

}  // namespace cairn

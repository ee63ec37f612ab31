// Directional blocking graphs and the NDBG (Wilson and Latombe 1994).
//
// The method, in the order ComputeNdbg runs it:
//
// 1. Scene. The present parts in the world frame (polygons, or polyhedra with
//    their vertices, edges and face triangles), their bounding boxes, and
//    whether each is convex; the contacts (DetectContacts) grouped by part
//    pair, each contact's normal written as ± one of the distinct normals
//    (Ndbg::normals, deduplicated up to sign within the angle tolerance, each
//    turned so that its largest component is positive).
//
// 2. The infinitesimal relation of a pair (i, j) at d: with n the contact
//    normal from j into i, i → j when d · n < −tol_angle, j → i when
//    d · n > +tol_angle. It only depends on the signs of d · n_k, so on a cell
//    of the arrangement of the great circles d · n_k = 0 (3-D) or between the
//    perpendiculars of the n_k (2-D) it is exact.
//
// 3. The relation to infinity, i → j at d: the ray {t d : t > 0} meets the
//    interior of the Minkowski difference j ⊖ i (deeper than tol_length).
//    Decided per pair in three steps, cheapest first:
//      a. the ray against the Minkowski difference of the bounding boxes
//         (slab test; exact for axis-aligned boxes, which most blocks are);
//      b. both parts convex: the separating-axis theorem over time. On each
//         axis a (face normals of both; in 3-D also the cross products of
//         their edge directions) the projections overlap by more than tol
//         for t in an open interval (two linear inequalities in t); the parts
//         overlap deeper than tol exactly where every axis does, so i → j
//         iff the intersection of those intervals with t > 0 is not empty
//         (for convex polytopes the penetration depth is the smallest
//         projected overlap over exactly these axes). The inequalities'
//         constants depend on the pair alone: found once per pair, a test
//         at one direction costs one product per axis;
//      c. otherwise (non-convex parts) events: the overlap of i + t d and j
//         can only start or stop when a vertex of one crosses an edge (2-D)
//         or face (3-D) of the other, or (3-D) an edge of one crosses an
//         edge of the other. Those times are collected and sorted; the
//         overlap is constant between two of them, so it is tested once per
//         interval, at its middle, with FindOverlap / FindPolyhedronOverlap.
//         In 3-D a "yes" leaves a cone of directions proved blocked too
//         (ConeOfOverlap), which the pair's next directions try first;
//         likely times are tried before the events (EventSweptOverlap3);
//         both solids are prepared for overlap tests once (PreparedSolid);
//         and each test is kept, for j along d is i along −d.
//    The result is united with the infinitesimal relation (an overlap that
//    grows from a contact at a grazing angle is shallower than tol_length for
//    a long way).
//
// 4. Cells, 2-D. The relation of a pair changes only at directions of
//    differences v_j − v_i of its vertices (the vertices and edges of the
//    Minkowski difference seen from the origin) and at the perpendiculars of
//    its contact normals. Cut into convex pieces (a convex part is one; a
//    non-convex one its triangles), the parts run into each other exactly
//    when two of their pieces do, and two convex pieces do so on one open
//    arc, between the tangents from the origin to their difference's hull:
//    two candidates per pair of pieces instead of one per pair of vertices
//    (a 20 000-gon beside a block: 4 instead of 160 000). All those
//    candidate angles of all pairs are
//    clustered (within tol_angle) into canonical directions; a cluster that
//    holds a world axis direction is that axis exactly. Each pair is then
//    evaluated at each of its candidates and at the middle of each arc
//    between two of them, and keeps only the candidates where a bit changes.
//    The union of the kept candidates cuts the circle; walking the cells
//    and each pair's list side by side gives every cell's graphs without
//    re-evaluating anything. A convex pair's relation to infinity holds on
//    one open arc of directions (the cone of the eroded Minkowski
//    difference), so among its candidates and arc middles it holds on one
//    run: a point inside it, one outside and two bisections find the run
//    with O(log n) swept tests instead of n (a free n-gon beside a block has
//    thousands of candidates). At a critical direction the infinitesimal
//    relation treats d · n_k as 0 when the direction is a perpendicular of
//    n_k (the cluster it fell into), so a slot's direction is free exactly.
//
// 5. Cells, 3-D. The arrangement of the great circles of the distinct
//    normals: vertices ±(n_k × n_l) normalised, arcs between consecutive
//    vertices on each circle, faces found by pushing each arc's middle off its
//    circle (by less than its distance to any other circle) to both sides;
//    each cell is identified by its sign vector (unique in a central
//    arrangement). The infinitesimal graph comes from the sign vector
//    (exact); the graph to infinity from step 3 at the cell's representative.
//
// Everything is sequential and visits pairs in (i, j) order: deterministic.
#include "cairn/planning/blocking.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

#include "cairn/contact/contact.h"
#include "cairn/contact/detect_contacts.h"
#include "cairn/core/check.h"
#include "cairn/core/tolerances.h"
#include "cairn/core/unit_vector.h"
#include "cairn/geometry/box_grid.h"

namespace cairn {

const char* to_string(BlockingKind kind) {
  switch (kind) {
    case BlockingKind::kInfinitesimal:
      return "infinitesimal";
    case BlockingKind::kInfinity:
      return "infinity";
  }
  return "unknown";
}

BlockingGraph Reversed(const BlockingGraph& graph) {
  BlockingGraph out;
  out.direction = -graph.direction;
  out.kind = graph.kind;
  out.fixed = graph.fixed;
  out.blockers.resize(graph.blockers.size());
  // i in ascending order: every list stays ascending.
  for (size_t i = 0; i < graph.blockers.size(); ++i)
    for (const int j : graph.blockers[i]) out.blockers[j].push_back(static_cast<int>(i));
  return out;
}

std::vector<BlockingGraph> InfinityGraphsUpFirst(std::vector<NdbgCell> cells, const Vector3& up) {
  std::stable_sort(cells.begin(), cells.end(), [&](const NdbgCell& a, const NdbgCell& b) {
    return a.direction.dot(up) > b.direction.dot(up) + numeric::kRoundoff;
  });
  std::vector<BlockingGraph> graphs;
  for (NdbgCell& c : cells) {
    bool duplicate = false;
    for (const BlockingGraph& g : graphs)
      duplicate = duplicate || (g.direction - c.direction).norm() < numeric::kRoundoff;
    if (!duplicate) graphs.push_back(std::move(c.infinity));
  }
  return graphs;
}

bool BlockingGraph::Blocks(int i, int j) const {
  if (i < 0 || i >= static_cast<int>(blockers.size())) return false;
  const std::vector<int>& b = blockers[i];
  return std::binary_search(b.begin(), b.end(), j);
}

namespace {

using Checkpoint = std::function<void()>;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The bits of a pair (i, j), i < j, at one direction.
enum : std::uint8_t {
  kInfIJ = 1,  // infinitesimal: i → j
  kInfJI = 2,  // infinitesimal: j → i
  kFarIJ = 4,  // to infinity (contains the infinitesimal one): i → j
  kFarJI = 8,  // to infinity: j → i
};

// One present part in the world frame of the configuration.
struct Shape {
  bool present = false;
  bool fixed = false;
  bool tool = false;
  bool convex = false;
  Vector3 lo{0, 0, 0}, hi{0, 0, 0};  // bounding box (length)
  std::vector<Vector3> verts;        // every vertex, world (2-D: z = 0)
  std::vector<Vector3> axes;         // convex: face (2-D: edge) normals, one per ± pair
  std::vector<Vector3> edge_dirs;    // convex 3-D: edge directions, one per ± pair
  Polygon poly;                      // 2-D: counter-clockwise, world
  // 2-D: convex pieces whose union is the polygon (itself when convex, else
  // its triangles; none when it could not be cut: every vertex is a candidate)
  std::vector<std::vector<Vector3>> pieces;
  // 3-D
  const Polyhedron* solid = nullptr;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  std::vector<std::array<int, 3>> triangles;  // indices into verts
  std::vector<std::array<int, 2>> edges;      // indices into verts
};

// A contact of a pair, as seen by the pair's first part i: the normal from j
// into i is sign · normals[normal].
struct PairContact {
  int normal = 0;
  int sign = 1;
};

struct PartPair {
  int i = 0, j = 0;  // i < j
  std::vector<PairContact> contacts;
  bool given_interface = false;  // the contacts are a given interface (shapes may overlap)
};

struct Scene {
  int dim = 2;
  double tol_length = 0;
  double tol_angle = 0;
  std::vector<Shape> shapes;     // (num_parts)
  std::vector<Vector3> normals;  // distinct contact normals, one of each ± pair
  std::vector<PartPair> pairs;   // present pairs, not both fixed, in (i, j) order
  std::vector<Vector3> axes;     // world axis directions, preferred first
  Checkpoint checkpoint;         // polled all through; may throw

  void Poll() const {
    if (checkpoint) checkpoint();
  }
};

// +1, 0 or −1: the side of the plane ⟂ n that d is on, within tol.
int SignOf(double x, double tol) { return x > tol ? 1 : (x < -tol ? -1 : 0); }

// The world axis directions, the one closest to "up" (−gravity) first, then
// in the order +x, −x, +y, −y (+z, −z): a stable sort by descending dot with up.
std::vector<Vector3> PreferredAxes(const Assembly& assembly) {
  const int dim = assembly.dimension();
  std::vector<Vector3> axes;
  for (int a = 0; a < dim; ++a) {
    axes.push_back(Vector3::Unit(a));
    axes.push_back(-Vector3::Unit(a));
  }
  const Vector3& g = assembly.gravity();
  const Vector3 up = -UnitVector(g).value_or(Vector3::Zero());
  std::stable_sort(axes.begin(), axes.end(), [&](const Vector3& a, const Vector3& b) {
    return a.dot(up) > b.dot(up) + numeric::kRoundoff;
  });
  return axes;
}

// Unit vectors `v` not parallel (within tol, up to sign) to any already in `out`.
void AddUnique(std::vector<Vector3>& out, const Vector3& v, double tol) {
  for (const Vector3& u : out)
    if (u.cross(v).norm() <= tol) return;
  out.push_back(v);
}

// AddUnique of each of `vs` in turn, for vectors in the plane (a polygon's
// edge normals, thousands of them on a fine polygon): the same vectors kept,
// found by comparing each only with the kept ones whose angle modulo π is
// within the tolerance (|u × v| ≤ tol means |sin(θ_u − θ_v)| ≤ tol), not
// with all of them.
std::vector<Vector3> UniqueAxes2d(const std::vector<Vector3>& vs, double tol, const Scene& sc) {
  // Wider than asin(tol) by far more than atan2's roundoff.
  constexpr double kWindowSlack = 1e-9;  // radians
  const double window = std::asin(std::min(tol, 1.0)) + kWindowSlack;
  std::vector<Vector3> out;
  std::multimap<double, int> by_angle;  // angle modulo π in [0, π) → index in out
  const auto near_one = [&](double lo, double hi, const Vector3& v) {
    for (auto it = by_angle.lower_bound(lo); it != by_angle.end() && it->first <= hi; ++it)
      if (out[it->second].cross(v).norm() <= tol) return true;
    return false;
  };
  for (const Vector3& v : vs) {
    sc.Poll();
    // A zero vector is parallel to everything: dropped after the first kept
    // one; kept first, it drops everything after it.
    if (!out.empty() && out[0].norm() == 0) break;
    if (v.norm() == 0) {
      if (out.empty()) out.push_back(v);
      continue;
    }
    double a = std::atan2(v.y(), v.x());
    a = std::fmod(a + std::numbers::pi, std::numbers::pi);  // [0, π)
    if (near_one(a - window, a + window, v) ||
        near_one(a - window + std::numbers::pi, a + window + std::numbers::pi, v) ||
        near_one(a - window - std::numbers::pi, a + window - std::numbers::pi, v))
      continue;
    by_angle.emplace(a, static_cast<int>(out.size()));
    out.push_back(v);
  }
  return out;
}

// Step 1: the shapes, the distinct normals and the pairs with their contacts.
// A 2-D part's world polygon; when convex (a simple counter-clockwise
// polygon that never turns right), its edge normals as separating axes.
void PlaceShape2d(const Assembly& assembly, const Configuration& config, int i,
                  const Tolerances& tol, const Scene& sc, Shape& s) {
  s.poly = config.WorldPolygon(assembly, i);
  s.verts.clear();
  for (const Vector2& v : s.poly) s.verts.push_back(Embed(v));
  // A simple counter-clockwise polygon is convex when it never turns right.
  const int m = static_cast<int>(s.poly.size());
  s.convex = true;
  for (int k = 0; k < m && s.convex; ++k) {
    const Vector2 &a = s.poly[k], &b = s.poly[(k + 1) % m], &c = s.poly[(k + 2) % m];
    s.convex = LineSide(a, b, c) >= -tol.length;
  }
  if (s.convex) {
    std::vector<Vector3> normals;
    for (int k = 0; k < m; ++k) normals.push_back(Embed(EdgeNormal(s.poly, k)));
    s.axes = UniqueAxes2d(normals, tol.angle, sc);
    s.pieces = {s.verts};
    return;
  }
  s.pieces.clear();
  for (const auto& tri : Triangulate(s.poly, tol.length))
    s.pieces.push_back({s.verts[tri[0]], s.verts[tri[1]], s.verts[tri[2]]});
}

// A 3-D part's world transform, triangles and edges; when convex (every
// vertex behind every face's plane), its face normals as separating axes and
// its edge directions.
void PlaceShape3d(const Assembly& assembly, const Configuration& config, int i,
                  const Tolerances& tol, Shape& s) {
  const Part& part = assembly.part(i);
  s.solid = part.polyhedron.get();
  s.solid = part.polyhedron.get();
  s.X_WB = config.WorldTransform(assembly, i);
  const Matrix3 R = s.X_WB.linear();
  const auto& faces = s.solid->faces();
  const auto& face_normals = s.solid->face_normals();
  for (const auto& face : s.solid->face_triangles())
    for (const auto& t : face) s.triangles.push_back(t);
  for (const auto& face : faces) {
    const int m = static_cast<int>(face.size());
    for (int k = 0; k < m; ++k) {
      const int a = face[k], b = face[(k + 1) % m];
      if (a < b) s.edges.push_back({a, b});  // each edge once (the other face has b → a)
    }
  }
  // Convex when every vertex lies behind every face's plane.
  s.convex = true;
  for (size_t f = 0; f < faces.size() && s.convex; ++f) {
    const Vector3 nf = R * face_normals[f];
    const Vector3& p = s.verts[faces[f][0]];
    for (const Vector3& v : s.verts)
      if (nf.dot(v - p) > tol.length) {
        s.convex = false;
        break;
      }
  }
  if (s.convex) {
    for (size_t f = 0; f < faces.size(); ++f) AddUnique(s.axes, R * face_normals[f], tol.angle);
    for (const auto& e : s.edges)
      AddUnique(s.edge_dirs, (s.verts[e[1]] - s.verts[e[0]]).normalized(), tol.angle);
  }
}

// The pairs, in (i, j) order: every present pair, not both fixed; then the
// contacts, their normals deduplicated up to sign (first appearance).
void AddPairsAndNormals(const Assembly& assembly, const Configuration& config,
                        const Tolerances& tol, Scene& sc) {
  const int n = assembly.num_parts();
  std::vector<int> pair_of(static_cast<size_t>(n) * n, -1);
  for (int i = 0; i < n; ++i) {
    if (!sc.shapes[i].present) continue;
    for (int j = i + 1; j < n; ++j) {
      if (!sc.shapes[j].present || (sc.shapes[i].fixed && sc.shapes[j].fixed)) continue;
      pair_of[static_cast<size_t>(i) * n + j] = static_cast<int>(sc.pairs.size());
      sc.pairs.push_back({i, j, {}, false});
    }
  }
  // The contacts, their normals deduplicated up to sign (first appearance).
  for (const Contact& c : DetectContacts(assembly, config, tol.length, tol.angle)) {
    if (c.part_b == kWorld) continue;  // fixels block nothing (blocking.h)
    const int i = std::min(c.part_a, c.part_b), j = std::max(c.part_a, c.part_b);
    const int p = pair_of[static_cast<size_t>(i) * n + j];
    if (p < 0) continue;
    // The normal from j into i.
    const Vector3 n_ji = c.part_a == i ? c.n_W : Vector3(-c.n_W);
    int k = 0;
    while (k < static_cast<int>(sc.normals.size()) && sc.normals[k].cross(n_ji).norm() > tol.angle)
      ++k;
    if (k == static_cast<int>(sc.normals.size())) {
      // Of the ± pair, the one whose largest component is positive.
      Vector3 nk = n_ji.normalized();
      int big = 0;
      nk.cwiseAbs().maxCoeff(&big);
      if (nk[big] < 0) nk = -nk;
      sc.normals.push_back(nk);
    }
    const int sign = sc.normals[k].dot(n_ji) > 0 ? 1 : -1;
    std::vector<PairContact>& list = sc.pairs[p].contacts;
    const bool known = std::any_of(list.begin(), list.end(), [&](const PairContact& pc) {
      return pc.normal == k && pc.sign == sign;
    });
    if (!known) list.push_back({k, sign});
    if (c.feature == ContactFeature::kInterface) sc.pairs[p].given_interface = true;
  }
}

Scene BuildScene(const Assembly& assembly, const Configuration& config,
                 const Checkpoint& checkpoint) {
  const int n = assembly.num_parts();
  CAIRN_THROW_UNLESS(
      static_cast<int>(config.present.size()) == n && static_cast<int>(config.poses.size()) == n,
      "blocking: the configuration has " + std::to_string(config.present.size()) +
          " presence flags and " + std::to_string(config.poses.size()) + " poses for " +
          std::to_string(n) + " parts");
  const Tolerances tol = assembly.MakeTolerances();
  Scene sc;
  sc.checkpoint = checkpoint;
  sc.dim = assembly.dimension();
  // The relation to infinity: an overlap deeper than the penetration
  // tolerance (the length tolerance, plus a tessellation's chordal error).
  sc.tol_length = tol.penetration;
  sc.tol_angle = tol.angle;
  sc.axes = PreferredAxes(assembly);
  sc.shapes.resize(n);
  for (int i = 0; i < n; ++i) {
    sc.Poll();
    Shape& s = sc.shapes[i];
    const Part& part = assembly.part(i);
    s.present = config.present[i];
    s.fixed = part.fixed;
    s.tool = part.tool;
    if (!s.present) continue;
    s.verts = config.WorldVertices(assembly, i);
    s.lo = s.hi = s.verts[0];
    for (const Vector3& v : s.verts) {
      s.lo = s.lo.cwiseMin(v);
      s.hi = s.hi.cwiseMax(v);
    }
    if (sc.dim == 2)
      PlaceShape2d(assembly, config, i, tol, sc, s);
    else
      PlaceShape3d(assembly, config, i, tol, s);
  }
  sc.Poll();
  AddPairsAndNormals(assembly, config, tol, sc);
  sc.Poll();
  return sc;
}

// Step 2: the infinitesimal bits of a pair from the signs of d · n_k.
template <class SignFn>
std::uint8_t InfinitesimalBits(const PartPair& pair, const SignFn& sign_of_normal) {
  std::uint8_t bits = 0;
  for (const PairContact& c : pair.contacts) {
    const int s = c.sign * sign_of_normal(c.normal);
    if (s < 0) bits |= kInfIJ;
    if (s > 0) bits |= kInfJI;
  }
  return bits;
}

// Step 3a: does the ray {t d : t > 0} meet the open box (lo, hi) shrunk by tol?
bool RayMeetsBox(const Vector3& lo, const Vector3& hi, const Vector3& d, double tol, int dim) {
  double t0 = 0, t1 = kInf;
  for (int c = 0; c < dim; ++c) {
    const double a = lo[c] + tol, b = hi[c] - tol;
    if (!(a < b)) return false;
    if (d[c] == 0) {
      if (!(a < 0 && 0 < b)) return false;
      continue;
    }
    double ta = a / d[c], tb = b / d[c];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (!(t0 < t1)) return false;
  }
  return t0 < t1;
}

// Narrows the open interval (t0, t1) to where c0 + t s > 0.
void Narrow(double c0, double s, double& t0, double& t1) {
  if (s == 0) {
    if (!(c0 > 0)) t1 = -kInf;
  } else if (s > 0) {
    t0 = std::max(t0, -c0 / s);
  } else {
    t1 = std::min(t1, -c0 / s);
  }
}

// Step 3b: convex a moving along d, convex b still: do they ever overlap by
// more than tol (separating-axis theorem over time)? On an axis u, with a's
// projection [amin, amax] and b's [bmin, bmax], the projections of a + t d
// and b overlap deeper than tol where amax − bmin − tol + t (u · d) > 0 and
// bmax − amin − tol − t (u · d) > 0. Those two constants depend on the pair
// alone: a Slab each, found once per pair (SweptCache), in the order the
// axes are tried (a's, b's, then in 3-D the cross products of their edges).
struct Slab {
  Vector3 u;
  double ab = 0;  // amax − bmin − tol
  double ba = 0;  // bmax − amin − tol
};

// Does a + t d overlap b deeper than tol for some t > 0, given their slabs?
bool SlabsOverlap(const std::vector<Slab>& slabs, const Vector3& d) {
  double t0 = 0, t1 = kInf;
  for (const Slab& slab : slabs) {
    const double s = slab.u.dot(d);
    Narrow(slab.ab, s, t0, t1);
    Narrow(slab.ba, -s, t0, t1);
    if (!(t0 < t1)) return false;
  }
  return t0 < t1;
}

// [min, max] of u · v over the vertices.
std::array<double, 2> Extent(const std::vector<Vector3>& verts, const Vector3& u) {
  double lo = kInf, hi = -kInf;
  for (const Vector3& v : verts) {
    const double x = u.dot(v);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return {lo, hi};
}

// A cone of directions along which a part certainly runs into another: every
// unit d' with d' · axis ≥ cos_angle (Step 3c's certificates).
struct BlockedCone {
  Vector3 axis;
  double cos_angle;
};

// What the swept tests of one computation keep, found on first use: each
// convex shape's extents on its own axes, and each ordered convex pair's
// slabs (the same numbers a direct computation gives, computed once); and,
// 3-D, each non-convex solid prepared for overlap tests, and each non-convex
// pair's (i < j) tests done and cones of directions proved blocked.
class SweptCache {
 public:
  explicit SweptCache(const Scene& sc) : sc_(sc), own_(sc.shapes.size()) {}

  // The slabs of part ia moving into part ib (both convex).
  const std::vector<Slab>& Slabs(int ia, int ib) {
    auto it = slabs_.find({ia, ib});
    if (it != slabs_.end()) return it->second;
    const Shape &a = sc_.shapes[ia], &b = sc_.shapes[ib];
    const double tol = sc_.tol_length;
    std::vector<Slab> slabs;
    const auto add = [&](const Vector3& u, const std::array<double, 2>& pa,
                         const std::array<double, 2>& pb) {
      slabs.push_back({u, pa[1] - pb[0] - tol, pb[1] - pa[0] - tol});
    };
    const std::vector<std::array<double, 2>>& own_a = Own(ia);
    for (size_t k = 0; k < a.axes.size(); ++k) add(a.axes[k], own_a[k], Extent(b.verts, a.axes[k]));
    const std::vector<std::array<double, 2>>& own_b = Own(ib);
    for (size_t k = 0; k < b.axes.size(); ++k) add(b.axes[k], Extent(a.verts, b.axes[k]), own_b[k]);
    if (sc_.dim == 3)
      for (const Vector3& e : a.edge_dirs)
        for (const Vector3& f : b.edge_dirs) {
          const Vector3 u = e.cross(f);
          const double len = u.norm();
          if (len < numeric::kParameterSlack)
            continue;  // parallel edges: their axis is a face normal's
          const Vector3 unit = u / len;
          add(unit, Extent(a.verts, unit), Extent(b.verts, unit));
        }
    return slabs_.emplace(std::make_pair(ia, ib), std::move(slabs)).first->second;
  }

  // The cones of directions along which part i is known to run into part
  // j > i (3-D, either non-convex: ConeOfOverlap), gathered as the
  // directions are tested.
  std::vector<BlockedCone>& Cones(int i, int j) { return cones_[{i, j}]; }

  // A swept test of a non-convex pair (i < j, i moving along d) done before.
  using FarKey = std::tuple<int, int, double, double, double>;
  std::optional<bool> Known(const FarKey& key) const {
    const auto it = far_.find(key);
    return it == far_.end() ? std::nullopt : std::optional<bool>(it->second);
  }
  bool Remember(const FarKey& key, bool blocked) {
    far_.emplace(key, blocked);
    return blocked;
  }

  // Part i's solid prepared for overlap tests at the scene's tolerance (3-D).
  const PreparedSolid& Prepared(int i) {
    auto it = prepared_.find(i);
    if (it == prepared_.end())
      it = prepared_.emplace(i, PreparedSolid(*sc_.shapes[i].solid, sc_.tol_length)).first;
    return it->second;
  }

 private:
  const std::vector<std::array<double, 2>>& Own(int i) {
    std::vector<std::array<double, 2>>& own = own_[i];
    const Shape& s = sc_.shapes[i];
    if (own.size() != s.axes.size()) {
      own.clear();
      for (const Vector3& u : s.axes) {
        sc_.Poll();
        own.push_back(Extent(s.verts, u));
      }
    }
    return own;
  }

  const Scene& sc_;
  std::vector<std::vector<std::array<double, 2>>> own_;  // (num_parts) per axis
  std::map<std::pair<int, int>, std::vector<Slab>> slabs_;
  std::map<std::pair<int, int>, std::vector<BlockedCone>> cones_;
  std::map<int, PreparedSolid> prepared_;
  std::map<FarKey, bool> far_;
};

// Sorts event times, merges those within tol, and tests the middle of each
// interval between 0 and the last with `overlaps(t)`. The overlap is the same
// all along an interval, so an interval whose middle is outside the window
// [t_lo, t_hi] (where the moving bounding box meets the other's) has none.
template <class OverlapFn>
bool AnyIntervalOverlaps(std::vector<double>& events, double tol, const OverlapFn& overlaps,
                         double t_lo = -std::numeric_limits<double>::infinity(),
                         double t_hi = std::numeric_limits<double>::infinity()) {
  std::sort(events.begin(), events.end());
  double prev = 0;
  for (const double t : events) {
    if (t - prev <= tol) continue;
    const double mid = 0.5 * (prev + t);
    if (mid >= t_lo && mid <= t_hi && overlaps(mid)) return true;
    prev = t;
  }
  return false;
}

// The times t at which the bounding box of a + t d meets b's (grown by tol,
// for roundoff), as [t_lo, t_hi] (empty: t_lo > t_hi). Every overlap
// FindPolyhedronOverlap reports is at a point of both solids (a sample point
// of one inside the other, or an edge of one through a face of the other),
// so in both boxes: outside the window there is none.
std::pair<double, double> BoxWindow(const Shape& a, const Shape& b, const Vector3& d, double tol) {
  double t_lo = -std::numeric_limits<double>::infinity();
  double t_hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    // a.lo + t d ≤ b.hi + tol and a.hi + t d ≥ b.lo − tol.
    const double upper = b.hi[k] + tol - a.lo[k], lower = b.lo[k] - tol - a.hi[k];
    if (d[k] == 0) {
      if (!(upper >= 0 && lower <= 0)) return {1, 0};
      continue;
    }
    double t0 = lower / d[k], t1 = upper / d[k];
    if (t0 > t1) std::swap(t0, t1);
    t_lo = std::max(t_lo, t0);
    t_hi = std::min(t_hi, t1);
  }
  return {t_lo, t_hi};
}

// Times t > tol at which vertex p moving along d crosses the segment [q0, q1].
void VertexEdgeEvents(const Vector2& p, const Vector2& d, const Vector2& q0, const Vector2& q1,
                      double tol, std::vector<double>& out) {
  const Vector2 e = q1 - q0, w = q0 - p;
  const double den = Cross2(d, e);
  if (std::abs(den) <= numeric::kRoundoff * e.norm()) {
    // Parallel: when p slides along the edge's line it meets its ends.
    if (std::abs(Cross2(w, d)) <= tol) {
      out.push_back(w.dot(d));
      out.push_back((q1 - p).dot(d));
    }
    return;
  }
  const double t = Cross2(w, e) / den, s = Cross2(w, d) / den;
  if (t > tol && s >= -numeric::kParameterSlack && s <= 1 + numeric::kParameterSlack)
    out.push_back(t);
}

// VertexEdgeEvents of every vertex of `ps` moving along d and every edge of
// `q`, the same times, skipping the pairs that cannot give one. With
// c(x) = d × x, a vertex p crosses the line of edge (q0, q1) at the edge's
// parameter s = (c(p) − c(q0)) / (c(q1) − c(q0)), so only vertices whose c
// lies between c(q0) and c(q1) (widened by the parameter slack, and by far
// more than roundoff) can; edges parallel to d are tested with every vertex.
void PolygonEvents(const Polygon& ps, const Vector2& d, const Polygon& q, double tol,
                   std::vector<double>& out) {
  // Relative to the coordinates: far above the roundoff of c and s.
  constexpr double kCSlack = 1e-9;
  const int np = static_cast<int>(ps.size()), nq = static_cast<int>(q.size());
  std::vector<double> c(np);
  double scale = 1;
  for (int i = 0; i < np; ++i) {
    c[i] = Cross2(d, ps[i]);
    scale = std::max(scale, ps[i].cwiseAbs().maxCoeff());
  }
  for (const Vector2& v : q) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  for (int k = 0; k < nq; ++k) {
    const Vector2 &q0 = q[k], &q1 = q[(k + 1) % nq];
    const Vector2 e = q1 - q0;
    const double den = Cross2(d, e);
    if (std::abs(den) <= numeric::kRoundoff * e.norm()) {  // parallel (VertexEdgeEvents' test)
      for (const Vector2& p : ps) VertexEdgeEvents(p, d, q0, q1, tol, out);
      continue;
    }
    const double c0 = Cross2(d, q0), c1 = Cross2(d, q1);
    const double widen = numeric::kParameterSlack * std::abs(den) + kCSlack * scale;
    const double lo = std::min(c0, c1) - widen, hi = std::max(c0, c1) + widen;
    for (int i = 0; i < np; ++i)
      if (c[i] >= lo && c[i] <= hi) VertexEdgeEvents(ps[i], d, q0, q1, tol, out);
  }
}

// FindOverlap(a, b, tol).has_value(), by the same tests, skipping those that
// bounding boxes show cannot pass: a point deeper than tol inside a polygon
// lies inside its box by more than tol (skipped: closer than tol / 2 to the
// box's sides, far beyond roundoff), and two edges that cross properly cross
// at a point of both boxes. FindOverlap tests every vertex and every pair of
// edges (O(n_a · n_b)); the swept test of a many-sided part calls it once or
// more per direction, and its vertices and edges are mostly nowhere near the
// other part.
bool Overlaps2(const Polygon& a, const Polygon& b, double tol) {
  const auto [a_lo, a_hi] = BoundingBox(a);
  const auto [b_lo, b_hi] = BoundingBox(b);
  const double margin = 0.5 * tol;
  const auto deep_in_box = [margin](const Vector2& p, const Vector2& lo, const Vector2& hi) {
    return p.x() > lo.x() + margin && p.x() < hi.x() - margin && p.y() > lo.y() + margin &&
           p.y() < hi.y() - margin;
  };
  // SignedDepth(poly, p) > tol: inside (the cheap test first), then deep.
  const auto deeper = [tol](const Polygon& poly, const Vector2& p) {
    return ContainsPoint(poly, p) && DistanceToBoundary(poly, p) > tol;
  };
  // (a) a vertex of one deep inside the other.
  for (const Vector2& v : a)
    if (deep_in_box(v, b_lo, b_hi) && deeper(b, v)) return true;
  for (const Vector2& v : b)
    if (deep_in_box(v, a_lo, a_hi) && deeper(a, v)) return true;
  // (b) two edges crossing properly: each edge's box meets the other polygon's.
  const auto edge_box = [](const Polygon& p, int i) {
    const Vector2 &p0 = p[i], &p1 = p[(i + 1) % static_cast<int>(p.size())];
    return std::pair<Vector2, Vector2>(p0.cwiseMin(p1), p0.cwiseMax(p1));
  };
  const auto boxes_meet = [tol](const std::pair<Vector2, Vector2>& x, const Vector2& lo,
                                const Vector2& hi) {
    return x.first.x() <= hi.x() + tol && x.second.x() >= lo.x() - tol &&
           x.first.y() <= hi.y() + tol && x.second.y() >= lo.y() - tol;
  };
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  std::vector<int> near_b, near_a;  // a's edges near b's box, b's edges near a's box
  for (int i = 0; i < na; ++i)
    if (boxes_meet(edge_box(a, i), b_lo, b_hi)) near_b.push_back(i);
  for (int j = 0; j < nb; ++j)
    if (boxes_meet(edge_box(b, j), a_lo, a_hi)) near_a.push_back(j);
  for (const int i : near_b) {
    const auto box_i = edge_box(a, i);
    for (const int j : near_a)
      if (boxes_meet(edge_box(b, j), box_i.first, box_i.second) &&
          SegmentsCrossProperly(a[i], a[(i + 1) % na], b[j], b[(j + 1) % nb], tol))
        return true;
  }
  // (c) coincident shapes: a point just inside an edge's midpoint of one deep
  // inside the other. That point is 2 tol from the midpoint, so a midpoint
  // outside the box grown by 2 tol cannot give one.
  const auto midpoint_inside = [&](const Polygon& p, const Polygon& q, const Vector2& lo,
                                   const Vector2& hi) {
    const int n = static_cast<int>(p.size());
    const Vector2 grow = Vector2::Constant(2.0 * tol + margin);
    for (int i = 0; i < n; ++i) {
      const Vector2 mid = 0.5 * (p[i] + p[(i + 1) % n]);
      if (!deep_in_box(mid, lo - grow, hi + grow)) continue;
      const Vector2 m = mid - 2.0 * tol * EdgeNormal(p, i);
      if (deep_in_box(m, lo, hi) && deeper(q, m)) return true;
    }
    return false;
  };
  return midpoint_inside(a, b, b_lo, b_hi) || midpoint_inside(b, a, a_lo, a_hi);
}

// Step 3c, 2-D: a moving along d, b still, either non-convex.
bool EventSweptOverlap2(const Shape& a, const Shape& b, const Vector3& d3, double tol) {
  const Vector2 d = d3.head<2>();
  std::vector<double> events;
  const int na = static_cast<int>(a.poly.size());
  PolygonEvents(a.poly, d, b.poly, tol, events);
  PolygonEvents(b.poly, -d, a.poly, tol, events);
  Polygon moved = a.poly;
  return AnyIntervalOverlaps(events, tol, [&](double t) {
    for (int k = 0; k < na; ++k) moved[k] = a.poly[k] + t * d;
    return Overlaps2(moved, b.poly, tol);
  });
}

// Times t > tol at which point p moving along d crosses triangle (q0, q1, q2).
void VertexTriangleEvent(const Vector3& p, const Vector3& d, const Vector3& q0, const Vector3& q1,
                         const Vector3& q2, double tol, std::vector<double>& out) {
  // Möller–Trumbore.
  const Vector3 e1 = q1 - q0, e2 = q2 - q0;
  const Vector3 h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) <= numeric::kRoundoff * e1.norm() * e2.norm())
    return;  // d parallel to the triangle
  const Vector3 s = p - q0;
  const double u = s.dot(h) / det;
  if (u < -numeric::kParameterSlack || u > 1 + numeric::kParameterSlack) return;
  const Vector3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < -numeric::kParameterSlack || u + v > 1 + numeric::kParameterSlack) return;
  const double t = e2.dot(q) / det;
  if (t > tol) out.push_back(t);
}

// A shape's features seen along d: each point's coordinates (x·u, x·w, 0)
// in the plane ⟂ d. A point moving along d can only cross a triangle, and
// an edge can only cross an edge, whose projections meet.
struct AlongD {
  Vector3 u, w;
  Vector3 operator()(const Vector3& x) const { return {x.dot(u), x.dot(w), 0}; }
};

// The grid of a shape's triangles (or edges) projected along d, each box
// grown by tol.
template <size_t N>
BoxGrid ProjectedGrid(const Shape& s, const std::vector<std::array<int, N>>& features,
                      const AlongD& along, double tol) {
  std::vector<Vector3> lo, hi;
  lo.reserve(features.size());
  hi.reserve(features.size());
  for (const auto& f : features) {
    Vector3 l = along(s.verts[f[0]]), h = l;
    for (size_t k = 1; k < N; ++k) {
      const Vector3 x = along(s.verts[f[k]]);
      l = l.cwiseMin(x);
      h = h.cwiseMax(x);
    }
    lo.push_back(l);
    hi.push_back(h);
  }
  return BoxGrid(lo, hi, tol);
}

// The times t > tol at which a vertex of `p` moving along d crosses a
// triangle of `q` (q's triangles looked up by their projection along d).
void VertexTriangleEvents(const Shape& p, const Shape& q, const Vector3& d, const AlongD& along,
                          double tol, std::vector<double>& events) {
  const BoxGrid triangles = ProjectedGrid(q, q.triangles, along, tol);
  for (const Vector3& x : p.verts) {
    const Vector3 at = along(x);
    for (const int k : triangles.Query(at, at)) {
      const auto& tr = q.triangles[k];
      VertexTriangleEvent(x, d, q.verts[tr[0]], q.verts[tr[1]], q.verts[tr[2]], tol, events);
    }
  }
}

// Step 3c's certificate of a "yes": a moving along the unit d overlaps b at
// time t > 0, at `witness`, a sample point of one lying deeper than tol
// inside the other (FindPolyhedronOverlap). That sample point is at c(τ) at
// time τ (seen from b's frame, or from a's at rest when it is b's); where
// c(τ) lies D deep, every point of the ball of radius ρ = (D − tol) / 2
// about it lies deeper than tol, so the sample point, moving along any d'
// whose ray passes through the ball, is as deep there too, and the overlap
// test finds it: a runs into b along every d' within asin(ρ / τ) of d. The
// widest of the cones at τ = t · 2^k, k = −6 … 2, is kept (the witness
// itself lies barely deeper than tol; a little later its point is deep
// inside). Pin and plate of the shear mold: a few such cones cover the
// hundreds of cells of the NDBG where the pin is blocked, each of which
// otherwise costs a full event sweep.
std::optional<BlockedCone> ConeOfOverlap(const Shape& a, const PreparedSolid& pa, const Shape& b,
                                         const PreparedSolid& pb, const Vector3& d, double t,
                                         const Vector3& witness, double tol) {
  Eigen::Isometry3d X = a.X_WB;
  X.pretranslate(t * d);
  // Which part the witness is deep in: b (a's sample moving) or a.
  const bool in_b = -SignedDistance(pb, b.X_WB, witness) >= -SignedDistance(pa, X, witness);
  std::optional<BlockedCone> best;
  for (int k = -6; k <= 2; ++k) {
    const double tau = t * std::ldexp(1.0, k);
    const double depth = in_b ? -SignedDistance(pb, b.X_WB, witness + (tau - t) * d)
                              : -SignedDistance(pa, a.X_WB, witness - tau * d);
    const double rho = 0.5 * (depth - tol);
    if (!(rho > 0)) continue;
    const double cos_angle = std::cos(std::asin(std::min(1.0, rho / tau)));
    if (!best || cos_angle < best->cos_angle) best = BlockedCone{d, cos_angle};
  }
  return best;
}

// Step 3c, 3-D: a moving along d, b still, either non-convex. A "yes" adds
// its certificate to `cones` (ConeOfOverlap). Any overlap found at any
// t > tol proves a "yes", so two likely times are tried before the events
// are gathered: where the centroids pass each other along d, and the middle
// of the window where the boxes overlap. A part that runs into another
// overlaps it there nearly always; the events and their intervals are then
// needed only for a "no" (the shear mold's full NDBG: 7 times faster, and
// the overlaps the probes find include some that the intervals' middles
// missed: bench/blocking_oracle.py confirms them).
bool EventSweptOverlap3(const Shape& a, const PreparedSolid& pa, const Shape& b,
                        const PreparedSolid& pb, const Vector3& d, double tol,
                        std::vector<BlockedCone>& cones) {
  const auto [t_lo, t_hi] = BoxWindow(a, b, d, tol);
  const auto overlaps_at = [&](double t) {
    Eigen::Isometry3d X = a.X_WB;
    X.pretranslate(t * d);
    const std::optional<Vector3> w = FindPolyhedronOverlap(pa, X, pb, b.X_WB);
    if (w)
      if (const auto cone = ConeOfOverlap(a, pa, b, pb, d, t, *w, tol)) cones.push_back(*cone);
    return w.has_value();
  };
  const double t_c = d.dot(b.X_WB * b.solid->mass().centroid - a.X_WB * a.solid->mass().centroid);
  for (const double t : {t_c, 0.5 * (t_lo + t_hi)})
    if (t > tol && t >= t_lo && t <= t_hi && overlaps_at(t)) return true;
  std::vector<double> events;
  AlongD along;
  along.u = d.unitOrthogonal();
  along.w = d.cross(along.u);
  VertexTriangleEvents(a, b, d, along, tol, events);
  VertexTriangleEvents(b, a, -d, along, tol, events);
  // Edge p0 + u e of a moving along d meets edge q0 + v f of b:
  // t d + u e − v f = q0 − p0.
  const BoxGrid edges_b = ProjectedGrid(b, b.edges, along, tol);
  for (const auto& ea : a.edges) {
    const Vector3 &p0 = a.verts[ea[0]], e = a.verts[ea[1]] - p0;
    const Vector3 x0 = along(p0), x1 = along(a.verts[ea[1]]);
    for (const int k : edges_b.Query(x0.cwiseMin(x1), x0.cwiseMax(x1))) {
      const auto& eb = b.edges[k];
      const Vector3 &q0 = b.verts[eb[0]], f = b.verts[eb[1]] - q0;
      Matrix3 M;
      M << d, e, -f;
      const double det = M.determinant();
      if (std::abs(det) <= numeric::kRoundoff * e.norm() * f.norm()) continue;
      const Vector3 x = M.inverse() * (q0 - p0);
      if (x[0] > tol && x[1] >= -numeric::kParameterSlack && x[1] <= 1 + numeric::kParameterSlack &&
          x[2] >= -numeric::kParameterSlack && x[2] <= 1 + numeric::kParameterSlack)
        events.push_back(x[0]);
    }
  }
  return AnyIntervalOverlaps(events, tol, overlaps_at, t_lo, t_hi);
}

// Step 3: does part a, translated along the unit d to infinity, run into b?
bool SweptOverlap(const Scene& sc, SweptCache& cache, int ia, int ib, const Vector3& d) {
  const Shape &a = sc.shapes[ia], &b = sc.shapes[ib];
  if (!RayMeetsBox(b.lo - a.hi, b.hi - a.lo, d, sc.tol_length, sc.dim)) return false;
  if (a.convex && b.convex) return SlabsOverlap(cache.Slabs(ia, ib), d);
  if (sc.dim == 2) return EventSweptOverlap2(a, b, d, sc.tol_length);
  // j running into i along d is i running into j along −d: tests, results
  // and cones are kept for i < j only, and the NDBG's cells come in exactly
  // antipodal pairs (Arrangement), so each test serves both.
  const bool swap = ia > ib;
  const int i = swap ? ib : ia, j = swap ? ia : ib;
  const Vector3 dd = swap ? Vector3(-d) : d;
  const SweptCache::FarKey key{i, j, dd.x(), dd.y(), dd.z()};
  if (const std::optional<bool> known = cache.Known(key)) return *known;
  std::vector<BlockedCone>& cones = cache.Cones(i, j);
  for (const BlockedCone& c : cones)
    if (dd.dot(c.axis) >= c.cos_angle) return cache.Remember(key, true);
  return cache.Remember(key, EventSweptOverlap3(sc.shapes[i], cache.Prepared(i), sc.shapes[j],
                                                cache.Prepared(j), dd, sc.tol_length, cones));
}

// Both relations of a pair at d, given its infinitesimal bits there.
std::uint8_t PairBits(const Scene& sc, SweptCache& cache, const PartPair& pair, const Vector3& d,
                      std::uint8_t inf) {
  std::uint8_t bits = inf;
  if (inf & kInfIJ) bits |= kFarIJ;
  if (inf & kInfJI) bits |= kFarJI;
  // Given interfaces: the shapes of the two parts may interpenetrate (that is
  // why the interfaces are given), so the contacts alone decide.
  if (pair.given_interface) return bits;
  if (!(bits & kFarIJ) && SweptOverlap(sc, cache, pair.i, pair.j, d)) bits |= kFarIJ;
  if (!(bits & kFarJI) && SweptOverlap(sc, cache, pair.j, pair.i, d)) bits |= kFarJI;
  return bits;
}

// An empty graph over the scene's parts.
BlockingGraph EmptyGraph(const Scene& sc, const Vector3& d, BlockingKind kind) {
  BlockingGraph g;
  g.direction = d;
  g.kind = kind;
  g.blockers.resize(sc.shapes.size());
  g.fixed.resize(sc.shapes.size());
  for (size_t i = 0; i < sc.shapes.size(); ++i) g.fixed[i] = sc.shapes[i].fixed;
  return g;
}

// Adds the arcs of `bits` for a pair; pairs must come in (i, j) order so that
// every blockers list stays ascending.
void AddArcs(const PartPair& pair, std::uint8_t bits, std::uint8_t ij, std::uint8_t ji,
             BlockingGraph& g) {
  if (bits & ij) g.blockers[pair.i].push_back(pair.j);
  if (bits & ji) g.blockers[pair.j].push_back(pair.i);
}

// Finishes a cell: the movable present parts with no arc to infinity.
void FinishCell(const Scene& sc, NdbgCell& cell) {
  cell.removable.clear();
  for (size_t i = 0; i < sc.shapes.size(); ++i) {
    const Shape& s = sc.shapes[i];
    if (s.present && !s.fixed && !s.tool && cell.infinity.blockers[i].empty())
      cell.removable.push_back(static_cast<int>(i));
  }
}

// ---------------------------------------------------------------------------
// 2-D cells (step 4).

double NormalizeAngle(double a) {
  a = std::fmod(a, kTwoPi);
  if (a < 0) a += kTwoPi;
  if (a >= kTwoPi) a = 0;
  return a;
}

double AngleOf(const Vector3& d) { return NormalizeAngle(std::atan2(d.y(), d.x())); }

// Canonical directions: clusters of candidate angles.
struct Cluster {
  double lo = 0, hi = 0;  // the smallest and largest member angle
  double angle = 0;       // canonical angle, [0, 2π)
  Vector3 dir{1, 0, 0};   // canonical unit direction
};

struct Clusters {
  std::vector<Cluster> list;  // ascending by angle
  int wrap_alias = -1;        // a last cluster merged into cluster 0 across 2π, or -1

  // The cluster of an angle that was one of the members.
  int Find(double a) const {
    auto it = std::upper_bound(list.begin(), list.end(), a,
                               [](double x, const Cluster& c) { return x < c.lo; });
    int c = static_cast<int>(it - list.begin()) - 1;
    if (c < 0) c = 0;
    return c == wrap_alias ? 0 : c;
  }
};

// Where "p moved along d runs into q" can begin or end, for convex pieces p,
// q of two parts (angles). It holds on the open arc of directions towards
// the convex hull of the differences w − v (w of q, v of p) as seen from the
// origin: the two tangents from the origin, which are the extreme angles of
// the differences about a direction into the hull (the difference of the
// vertex means); their opposites are where q moved along −d runs into p.
// When the origin is inside the hull (the pieces overlap where they stand,
// within the tolerance) the relation is no single arc, and every difference
// is a candidate.
void PieceCandidates(const std::vector<Vector3>& p, const std::vector<Vector3>& q, double tol,
                     std::vector<double>& out) {
  Vector3 r = Vector3::Zero();
  for (const Vector3& w : q) r += w / static_cast<double>(q.size());
  for (const Vector3& v : p) r -= v / static_cast<double>(p.size());
  double lo = kInf, hi = -kInf;
  Vector3 e_lo = Vector3::Zero(), e_hi = Vector3::Zero();
  const bool outside = r.norm() > tol;
  if (outside)
    for (const Vector3& v : p)
      for (const Vector3& w : q) {
        const Vector3 e = w - v;
        if (e.norm() <= tol) continue;
        const double a = std::atan2(r.x() * e.y() - r.y() * e.x(), r.dot(e));
        if (a < lo) std::tie(lo, e_lo) = std::pair(a, e);
        if (a > hi) std::tie(hi, e_hi) = std::pair(a, e);
      }
  const auto both = [&](const Vector3& e) {
    const double a = AngleOf(e);
    out.push_back(a);
    out.push_back(NormalizeAngle(a + std::numbers::pi));
  };
  // Within a half-turn: the origin is outside the hull or on its boundary
  // (inside, the differences surround it and span more than a half-turn).
  if (outside && lo <= hi && hi - lo <= std::numbers::pi) {
    both(e_lo);
    both(e_hi);
    return;
  }
  for (const Vector3& v : p)
    for (const Vector3& w : q)
      if ((w - v).norm() > tol) both(w - v);
}

// The candidate angles of a pair: where the swept relation of a convex
// piece of one part and a convex piece of the other can change (the union
// of the parts' relations changes only where one of the pieces' does), and
// the perpendiculars of its contact normals. A part that could not be cut
// into convex pieces counts as one piece, every difference a candidate.
void PairCandidates(const Scene& sc, const PartPair& pair,
                    const std::vector<std::array<double, 2>>& perps, std::vector<double>& out) {
  const Shape &a = sc.shapes[pair.i], &b = sc.shapes[pair.j];
  if (a.pieces.empty() || b.pieces.empty()) {
    for (const Vector3& v : a.verts)
      for (const Vector3& w : b.verts) {
        const Vector3 e = w - v;
        if (e.norm() <= sc.tol_length) continue;
        const double angle = AngleOf(e);
        out.push_back(angle);
        out.push_back(NormalizeAngle(angle + std::numbers::pi));
      }
  } else {
    for (const auto& p : a.pieces)
      for (const auto& q : b.pieces) PieceCandidates(p, q, sc.tol_length, out);
  }
  for (const PairContact& c : pair.contacts) {
    out.push_back(perps[c.normal][0]);
    out.push_back(perps[c.normal][1]);
  }
}

Clusters MakeClusters(std::vector<double> angles, const std::vector<Vector3>& axes, double tol) {
  Clusters cl;
  std::sort(angles.begin(), angles.end());
  for (const double a : angles) {
    if (cl.list.empty() || a - cl.list.back().lo > tol)
      cl.list.push_back({a, a, a, Vector3::Zero()});
    cl.list.back().hi = a;
  }
  if (cl.list.size() > 1 && cl.list[0].lo + kTwoPi - cl.list.back().hi <= tol)
    cl.wrap_alias = static_cast<int>(cl.list.size()) - 1;
  // A cluster that holds a world axis direction (within tol) is that axis,
  // exactly; each axis snaps one cluster only (the first), so no two
  // canonical directions coincide.
  std::vector<bool> used(axes.size(), false);
  for (int c = 0; c < static_cast<int>(cl.list.size()); ++c) {
    Cluster& k = cl.list[c];
    k.angle = k.lo;
    k.dir = Vector3(std::cos(k.lo), std::sin(k.lo), 0);
    if (c == cl.wrap_alias) continue;
    const auto near = [&](double x) {
      const Cluster& alias = cl.list.back();
      return (x >= k.lo - tol && x <= k.hi + tol) ||
             (c == 0 && cl.wrap_alias >= 0 && x >= alias.lo - tol && x <= alias.hi + tol);
    };
    for (size_t a = 0; a < axes.size(); ++a) {
      const double aa = AngleOf(axes[a]);
      if (used[a] || !(near(aa) || near(aa + kTwoPi) || near(aa - kTwoPi))) continue;
      used[a] = true;
      k.angle = aa;
      k.dir = axes[a];
      break;
    }
  }
  return cl;
}

// A pair's relation as a function of the direction: its critical clusters,
// the bits at each and on the arc after each (constant when none).
struct PairFunction {
  std::vector<int> critical;
  std::vector<std::uint8_t> at, after;
  std::uint8_t constant = 0;
};

// The middle of the arc from angle a counter-clockwise to angle b (b == a:
// the whole circle).
double ArcMiddle(double a, double b) {
  double span = b - a;
  if (span <= 0) span += kTwoPi;
  return NormalizeAngle(a + 0.5 * span);
}

Vector3 DirectionAt(double angle) { return {std::cos(angle), std::sin(angle), 0}; }

// The swept relation of a moving into b at directions given in
// counter-clockwise order around the circle (`angle` each), both convex: 1
// where it holds. For convex parts it holds on one open arc of directions
// (those of the open convex cone spanned by the points t d where a + t d
// overlaps b deeper than tol: the tol-eroded Minkowski difference b ⊖ a,
// seen from the origin; empty, or less than a half-turn, unless they overlap
// where they stand), so among the directions it holds on one run: found
// from a direction inside the arc (towards the difference of the vertex
// means, a point of b ⊖ a), one outside (opposite) and two bisections, in
// O(log n) tests instead of n. Empty when one of those premises is not met
// (the caller then tests every direction).
std::optional<std::vector<char>> ConvexSweptRun(const Scene& sc, SweptCache& cache, int ia, int ib,
                                                const std::vector<Vector3>& dir,
                                                const std::vector<double>& angle) {
  const int n = static_cast<int>(dir.size());
  const Shape &a = sc.shapes[ia], &b = sc.shapes[ib];
  if (n < 2 || !a.convex || !b.convex) return std::nullopt;
  int descents = 0;  // the angles must go once around, in order
  for (int s = 0; s < n; ++s) descents += angle[(s + 1) % n] < angle[s] ? 1 : 0;
  if (descents != 1) return std::nullopt;
  Vector3 mean_a = Vector3::Zero(), mean_b = Vector3::Zero();
  for (const Vector3& v : a.verts) mean_a += v / static_cast<double>(a.verts.size());
  for (const Vector3& v : b.verts) mean_b += v / static_cast<double>(b.verts.size());
  const Vector3 c = mean_b - mean_a;
  if (!(c.norm() > sc.tol_length)) return std::nullopt;
  const auto test = [&](const Vector3& d) {
    sc.Poll();
    return SweptOverlap(sc, cache, ia, ib, d);
  };
  if (!test(c.normalized())) return std::nullopt;
  // The directions just after and just before an angle.
  const auto after = [&](double theta) {
    int best = 0;
    double best_off = kInf;
    for (int s = 0; s < n; ++s) {
      const double off = NormalizeAngle(angle[s] - theta);
      if (off < best_off) {
        best_off = off;
        best = s;
      }
    }
    return best;
  };
  std::vector<signed char> known(n, -1);  // -1: not tested yet
  const auto holds = [&](int s) {
    if (known[s] < 0) known[s] = test(dir[s]) ? 1 : 0;
    return known[s] == 1;
  };
  const int in_after = after(AngleOf(c)), in_before = (in_after + n - 1) % n;
  std::vector<char> out(n, 0);
  int t = -1;
  if (holds(in_after))
    t = in_after;
  else if (holds(in_before))
    t = in_before;
  if (t < 0) return out;  // the arc holds no direction
  const int out_after = after(AngleOf(-c)), out_before = (out_after + n - 1) % n;
  int f = -1;
  if (!holds(out_after))
    f = out_after;
  else if (!holds(out_before))
    f = out_before;
  if (f < 0) return std::nullopt;
  // From t (holds) forward to f (does not): the last that holds.
  int lo = 0, hi = (f - t + n) % n;
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (holds((t + mid) % n) ? lo : hi) = mid;
  }
  const int last = (t + lo) % n;
  // From f forward to t: the first that holds.
  lo = 0;
  hi = (t - f + n) % n;
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (holds((f + mid) % n) ? hi : lo) = mid;
  }
  const int first = (f + hi) % n;
  for (int s = first;; s = (s + 1) % n) {
    out[s] = 1;
    if (s == last) break;
  }
  return out;
}

// A pair's relation as a function of the direction (step 4): its bits at
// each of its candidate clusters and at the middle of each arc between two,
// of which it keeps the clusters where a bit changes.
PairFunction EvaluatePair2(const Scene& sc, SweptCache& cache, const PartPair& pair,
                           const Clusters& cl, const std::vector<std::array<int, 2>>& perp_cluster,
                           const std::vector<std::array<double, 2>>& perps) {
  std::vector<double> raw;
  PairCandidates(sc, pair, perps, raw);
  std::vector<int> ids;
  for (const double a : raw) ids.push_back(cl.Find(a));
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const int m = static_cast<int>(ids.size());
  // Signs of d · n_k at a direction; at a cluster, exactly 0 on its normals.
  const auto inf_at = [&](const Vector3& d, int cluster) {
    return InfinitesimalBits(pair, [&](int k) {
      if (cluster >= 0 && (perp_cluster[k][0] == cluster || perp_cluster[k][1] == cluster))
        return 0;
      return SignOf(d.dot(sc.normals[k]), sc.tol_angle);
    });
  };
  PairFunction f;
  if (m == 0) {
    f.constant = PairBits(sc, cache, pair, Vector3(1, 0, 0), inf_at(Vector3(1, 0, 0), -1));
    return f;
  }
  // The 2m sample directions in counter-clockwise order: each cluster, then
  // the middle of the arc after it; their bits as PairBits gives them.
  const int n = 2 * m;
  std::vector<Vector3> dir(n);
  std::vector<double> angle(n);
  std::vector<std::uint8_t> bits(n);
  for (int q = 0; q < m; ++q) {
    const Cluster& c = cl.list[ids[q]];
    const double next = cl.list[ids[(q + 1) % m]].angle;
    dir[2 * q] = c.dir;
    angle[2 * q] = c.angle;
    bits[2 * q] = inf_at(c.dir, ids[q]);
    angle[2 * q + 1] = ArcMiddle(c.angle, next);
    dir[2 * q + 1] = DirectionAt(angle[2 * q + 1]);
    bits[2 * q + 1] = inf_at(dir[2 * q + 1], -1);
  }
  for (std::uint8_t& b : bits) {
    if (b & kInfIJ) b |= kFarIJ;
    if (b & kInfJI) b |= kFarJI;
  }
  // Given interfaces: the contacts alone decide (PairBits).
  if (!pair.given_interface)
    for (const auto& [ia, ib, far] :
         {std::tuple(pair.i, pair.j, kFarIJ), std::tuple(pair.j, pair.i, kFarJI)}) {
      if (const auto run = ConvexSweptRun(sc, cache, ia, ib, dir, angle)) {
        for (int s = 0; s < n; ++s)
          if ((*run)[s]) bits[s] |= far;
        continue;
      }
      for (int s = 0; s < n; ++s) {
        if (bits[s] & far) continue;
        sc.Poll();
        if (SweptOverlap(sc, cache, ia, ib, dir[s])) bits[s] |= far;
      }
    }
  std::vector<std::uint8_t> at(m), arc(m);
  for (int q = 0; q < m; ++q) {
    at[q] = bits[2 * q];
    arc[q] = bits[2 * q + 1];
  }
  for (int q = 0; q < m; ++q) {
    const std::uint8_t before = arc[(q + m - 1) % m];
    if (at[q] != before || at[q] != arc[q]) {
      f.critical.push_back(ids[q]);
      f.at.push_back(at[q]);
      f.after.push_back(arc[q]);
    }
  }
  f.constant = arc[0];
  return f;
}

// The cells of the circle of directions: each critical direction (a
// cluster), then the arc after it; one whole circle when there is none.
void MakeCells2(const Scene& sc, const Clusters& cl, const std::vector<int>& critical, Ndbg& out) {
  const int r_count = static_cast<int>(critical.size());
  const auto arc_direction = [&](double from, double to) {
    double span = to - from;
    if (span <= 0) span += kTwoPi;
    for (const Vector3& ax : sc.axes) {
      double off = AngleOf(ax) - from;
      if (off < 0) off += kTwoPi;
      if (off > sc.tol_angle && off < span - sc.tol_angle) return ax;
    }
    return DirectionAt(ArcMiddle(from, to));
  };
  const auto new_cell = [&](int dimension, double from, double to, const Vector3& d) {
    NdbgCell cell;
    cell.cell_dimension = dimension;
    cell.direction = d;
    cell.angle_from = from;
    cell.angle_to = to;
    cell.infinitesimal = EmptyGraph(sc, d, BlockingKind::kInfinitesimal);
    cell.infinity = EmptyGraph(sc, d, BlockingKind::kInfinity);
    out.cells.push_back(std::move(cell));
  };
  if (r_count == 0) {
    new_cell(1, 0, kTwoPi, arc_direction(0, 0));
  } else {
    for (int r = 0; r < r_count; ++r) {
      const Cluster& c = cl.list[critical[r]];
      const double next = cl.list[critical[(r + 1) % r_count]].angle;
      new_cell(0, c.angle, c.angle, c.dir);
      new_cell(1, c.angle, next, arc_direction(c.angle, next));
    }
  }
}

// Each pair's arcs in each cell: its critical list walked beside the cells'.
void FillCells2(const Scene& sc, const std::vector<PairFunction>& fns,
                const std::vector<int>& critical, Ndbg& out) {
  const int r_count = static_cast<int>(critical.size());
  for (size_t p = 0; p < sc.pairs.size(); ++p) {
    const PartPair& pair = sc.pairs[p];
    const PairFunction& f = fns[p];
    const int m = static_cast<int>(f.critical.size());
    const auto add = [&](NdbgCell& cell, std::uint8_t bits) {
      AddArcs(pair, bits, kInfIJ, kInfJI, cell.infinitesimal);
      AddArcs(pair, bits, kFarIJ, kFarJI, cell.infinity);
    };
    if (r_count == 0 || m == 0) {
      for (NdbgCell& cell : out.cells) add(cell, f.constant);
      continue;
    }
    int q = 0;  // f.critical[0, q) are before the current critical direction
    for (int r = 0; r < r_count; ++r) {
      while (q < m && f.critical[q] < critical[r]) ++q;
      std::uint8_t at, after;
      if (q < m && f.critical[q] == critical[r]) {
        at = f.at[q];
        after = f.after[q];
      } else {
        at = after = f.after[(q + m - 1) % m];
      }
      add(out.cells[2 * r], at);
      add(out.cells[2 * r + 1], after);
    }
  }
}

Ndbg ComputeNdbg2(const Scene& sc) {
  Ndbg out;
  out.dimension = 2;
  out.normals = sc.normals;
  // The perpendiculars of the normals, and every pair's candidates: clusters.
  std::vector<std::array<double, 2>> perps;
  for (const Vector3& nk : sc.normals) {
    const double a = AngleOf(Vector3(-nk.y(), nk.x(), 0));
    perps.push_back({a, NormalizeAngle(a + std::numbers::pi)});
  }
  std::vector<double> all;
  for (const PartPair& pair : sc.pairs) {
    sc.Poll();
    PairCandidates(sc, pair, perps, all);
  }
  const Clusters cl = MakeClusters(std::move(all), sc.axes, sc.tol_angle);
  std::vector<std::array<int, 2>> perp_cluster;
  for (const auto& p : perps) {
    if (cl.list.empty())
      perp_cluster.push_back({-1, -1});
    else
      perp_cluster.push_back({cl.Find(p[0]), cl.Find(p[1])});
  }

  // Each pair's function, and the critical clusters of all.
  std::vector<PairFunction> fns;
  fns.reserve(sc.pairs.size());
  std::vector<int> critical;
  SweptCache cache(sc);
  for (const PartPair& pair : sc.pairs) {
    fns.push_back(EvaluatePair2(sc, cache, pair, cl, perp_cluster, perps));
    critical.insert(critical.end(), fns.back().critical.begin(), fns.back().critical.end());
  }
  std::sort(critical.begin(), critical.end());
  critical.erase(std::unique(critical.begin(), critical.end()), critical.end());

  MakeCells2(sc, cl, critical, out);
  FillCells2(sc, fns, critical, out);
  for (NdbgCell& cell : out.cells) FinishCell(sc, cell);
  return out;
}

// ---------------------------------------------------------------------------
// 3-D cells (step 5).

std::vector<int> SignsOf(const Vector3& d, const std::vector<Vector3>& normals, double tol) {
  std::vector<int> s(normals.size());
  for (size_t k = 0; k < normals.size(); ++k) s[k] = SignOf(d.dot(normals[k]), tol);
  return s;
}

struct ArrangementCell {
  int dimension = 0;
  Vector3 direction{0, 0, 1};
  std::vector<int> signs;
};

using ArrangementVertices = std::map<std::pair<std::vector<int>, int>, Vector3>;
using ArrangementArcs = std::map<std::vector<int>, Vector3>;
using ArrangementFaces = std::map<std::vector<int>, std::pair<Vector3, Vector3>>;

// Vertices: ±(n_k × n_l), identified by their sign vectors. When all the
// normals lie in one plane (every circle through the same two antipodal
// points) both vertices have the sign vector 0…0: then the sign of the
// vertex's largest component tells them apart.
ArrangementVertices VerticesOf(const std::vector<Vector3>& normals, double tol) {
  const int nn = static_cast<int>(normals.size());
  ArrangementVertices vertices;
  for (int k = 0; k < nn; ++k)
    for (int l = k + 1; l < nn; ++l) {
      const Vector3 v = normals[k].cross(normals[l]).normalized();
      for (const Vector3& w : {v, Vector3(-v)}) {
        std::vector<int> s = SignsOf(w, normals, tol);
        s[k] = s[l] = 0;
        int tie = 0;
        if (std::all_of(s.begin(), s.end(), [](int x) { return x == 0; })) {
          int big = 0;
          w.cwiseAbs().maxCoeff(&big);
          tie = w[big] > 0 ? 1 : -1;
        }
        vertices.emplace(std::make_pair(s, tie), w);
      }
    }
  return vertices;
}

// Arcs: between consecutive vertices on each circle. Faces: each arc's
// middle pushed off its circle to both sides; their representative the
// normalised sum of the middles of the arcs around them (faces: sum of
// middles, pushed point).
void ArcsAndFaces(const std::vector<Vector3>& normals, const ArrangementVertices& vertices,
                  double tol, ArrangementArcs& arcs, ArrangementFaces& faces) {
  const int nn = static_cast<int>(normals.size());
  for (int k = 0; k < nn; ++k) {
    const auto [u, w] = TangentBasis(normals[k]);
    std::vector<double> phi;
    for (const auto& [key, v] : vertices)
      if (key.first[k] == 0) phi.push_back(std::atan2(v.dot(w), v.dot(u)));
    std::sort(phi.begin(), phi.end());
    const int m = static_cast<int>(phi.size());
    for (int q = 0; q < m; ++q) {
      const double a = phi[q], b = q + 1 < m ? phi[q + 1] : phi[0] + kTwoPi;
      if (b - a <= tol) continue;
      const double mid = 0.5 * (a + b);
      const Vector3 mpt = std::cos(mid) * u + std::sin(mid) * w;
      std::vector<int> s = SignsOf(mpt, normals, tol);
      s[k] = 0;
      if (std::count(s.begin(), s.end(), 0) != 1) continue;  // degenerate (vertices too close)
      arcs.emplace(s, mpt);
      double eps = 0.5;
      for (int l = 0; l < nn; ++l)
        if (l != k) eps = std::min(eps, 0.5 * std::abs(mpt.dot(normals[l])));
      for (const int side : {-1, 1}) {
        const Vector3 pushed = (mpt + side * eps * normals[k]).normalized();
        std::vector<int> fs = s;
        fs[k] = side;
        auto [it, fresh] = faces.emplace(fs, std::make_pair(Vector3::Zero().eval(), pushed));
        it->second.first += mpt;
        (void)fresh;
      }
    }
  }
}

// The cells of the arrangement of the great circles d · n_k = 0.
std::vector<ArrangementCell> Arrangement(const std::vector<Vector3>& normals,
                                         const std::vector<Vector3>& axes, double tol) {
  const int nn = static_cast<int>(normals.size());
  std::vector<ArrangementCell> cells;
  // A representative: a world axis direction with the cell's signs, if any.
  const auto prefer_axis = [&](ArrangementCell& c) {
    for (const Vector3& ax : axes)
      if (SignsOf(ax, normals, tol) == c.signs) {
        c.direction = ax;
        return;
      }
  };
  if (nn == 0) {
    ArrangementCell whole{2, axes[0], {}};
    cells.push_back(whole);
    return cells;
  }
  if (nn == 1) {
    ArrangementCell circle{1, TangentBasis(normals[0]).first, {0}};
    prefer_axis(circle);
    cells.push_back(circle);
    for (const int s : {-1, 1}) {
      ArrangementCell half{2, Vector3(s * normals[0]), {s}};
      prefer_axis(half);
      cells.push_back(half);
    }
    return cells;
  }
  const ArrangementVertices vertices = VerticesOf(normals, tol);
  ArrangementArcs arcs;
  ArrangementFaces faces;
  ArcsAndFaces(normals, vertices, tol, arcs, faces);
  for (const auto& [key, v] : vertices) {
    ArrangementCell c{0, v, key.first};
    for (const Vector3& ax : axes)  // a vertex on a world axis is that axis, exactly
      if ((ax - v).norm() <= tol) c.direction = ax;
    cells.push_back(c);
  }
  for (const auto& [s, v] : arcs) {
    ArrangementCell c{1, v, s};
    prefer_axis(c);
    cells.push_back(c);
  }
  for (const auto& [s, sums] : faces) {
    ArrangementCell c{2, sums.second, s};
    if (sums.first.norm() > numeric::kParameterSlack) {
      const Vector3 inside = sums.first.normalized();
      if (SignsOf(inside, normals, tol) == s) c.direction = inside;
    }
    prefer_axis(c);
    cells.push_back(c);
  }
  // The arrangement is centrally symmetric: the cell of −s takes exactly −(the
  // representative of s), so that the swept tests of opposite cells are the
  // same tests (SweptOverlap) and their graphs exact reverses. (The two
  // vertices of coplanar normals share the sign vector 0…0: the second
  // becomes the first's antipode, which it is.)
  std::map<std::vector<int>, size_t> seen;
  for (size_t c = 0; c < cells.size(); ++c) {
    std::vector<int> opposite = cells[c].signs;
    for (int& x : opposite) x = -x;
    if (const auto it = seen.find(opposite); it != seen.end())
      cells[c].direction = -cells[it->second].direction;
    else
      seen.emplace(cells[c].signs, c);
  }
  return cells;
}

Ndbg ComputeNdbg3(const Scene& sc) {
  Ndbg out;
  out.dimension = 3;
  out.normals = sc.normals;
  SweptCache cache(sc);
  for (const ArrangementCell& a : Arrangement(sc.normals, sc.axes, sc.tol_angle)) {
    NdbgCell cell;
    cell.cell_dimension = a.dimension;
    cell.direction = a.direction;
    cell.signs = a.signs;
    cell.infinitesimal = EmptyGraph(sc, a.direction, BlockingKind::kInfinitesimal);
    cell.infinity = EmptyGraph(sc, a.direction, BlockingKind::kInfinity);
    for (const PartPair& pair : sc.pairs) {
      sc.Poll();
      const std::uint8_t inf = InfinitesimalBits(pair, [&](int k) { return a.signs[k]; });
      const std::uint8_t bits = PairBits(sc, cache, pair, a.direction, inf);
      AddArcs(pair, bits, kInfIJ, kInfJI, cell.infinitesimal);
      AddArcs(pair, bits, kFarIJ, kFarJI, cell.infinity);
    }
    FinishCell(sc, cell);
    out.cells.push_back(std::move(cell));
  }
  return out;
}

}  // namespace

BlockingGraph ComputeBlockingGraph(const Assembly& assembly, const Configuration& config,
                                   const Vector3& direction, BlockingKind kind) {
  Vector3 d = direction;
  if (!assembly.is_3d()) d.z() = 0;
  std::ostringstream given;
  given << "(" << direction.x() << ", " << direction.y() << ", " << direction.z() << ")";
  const std::optional<Vector3> unit = UnitVector(d);
  CAIRN_THROW_UNLESS(
      unit.has_value(),
      "ComputeBlockingGraph: the direction must be finite and nonzero, got " + given.str());
  d = *unit;
  const Scene sc = BuildScene(assembly, config, {});
  SweptCache cache(sc);
  BlockingGraph g = EmptyGraph(sc, d, kind);
  for (const PartPair& pair : sc.pairs) {
    const std::uint8_t inf =
        InfinitesimalBits(pair, [&](int k) { return SignOf(d.dot(sc.normals[k]), sc.tol_angle); });
    if (kind == BlockingKind::kInfinitesimal)
      AddArcs(pair, inf, kInfIJ, kInfJI, g);
    else
      AddArcs(pair, PairBits(sc, cache, pair, d, inf), kFarIJ, kFarJI, g);
  }
  return g;
}

Ndbg ComputeBlockingAt(const Assembly& assembly, const Configuration& config,
                       const Vector3& direction, const std::function<void()>& checkpoint) {
  Vector3 d = direction;
  if (!assembly.is_3d()) d.z() = 0;
  const std::optional<Vector3> unit = UnitVector(d);
  CAIRN_THROW_UNLESS(unit.has_value(),
                     "ComputeBlockingAt: the direction must be finite and nonzero");
  d = *unit;
  const Scene sc = BuildScene(assembly, config, checkpoint);
  SweptCache cache(sc);
  Ndbg out;
  out.dimension = sc.dim;
  out.normals = sc.normals;
  // The cell of the arrangement that holds d: its signs s_k = sign(d · n_k);
  // on no great circle a face, on one an arc, on two or more a vertex. In
  // 2-D the cell is the direction itself, [θ, θ].
  std::vector<int> signs;
  int zeros = 0;
  for (const Vector3& n : sc.normals) {
    signs.push_back(SignOf(d.dot(n), sc.tol_angle));
    zeros += signs.back() == 0 ? 1 : 0;
  }
  NdbgCell cell;
  cell.direction = d;
  if (sc.dim == 3) {
    cell.signs = signs;
    cell.cell_dimension = zeros == 0 ? 2 : (zeros == 1 ? 1 : 0);
  } else {
    cell.cell_dimension = 0;
    cell.angle_from = cell.angle_to = AngleOf(d);
  }
  cell.infinitesimal = EmptyGraph(sc, d, BlockingKind::kInfinitesimal);
  cell.infinity = EmptyGraph(sc, d, BlockingKind::kInfinity);
  for (const PartPair& pair : sc.pairs) {
    sc.Poll();
    const std::uint8_t inf = InfinitesimalBits(pair, [&](int k) { return signs[k]; });
    const std::uint8_t bits = PairBits(sc, cache, pair, d, inf);
    AddArcs(pair, bits, kInfIJ, kInfJI, cell.infinitesimal);
    AddArcs(pair, bits, kFarIJ, kFarJI, cell.infinity);
  }
  FinishCell(sc, cell);
  out.cells.push_back(std::move(cell));
  return out;
}

Ndbg ComputeNdbg(const Assembly& assembly, const Configuration& config,
                 const std::function<void()>& checkpoint) {
  const Scene sc = BuildScene(assembly, config, checkpoint);
  return sc.dim == 2 ? ComputeNdbg2(sc) : ComputeNdbg3(sc);
}

bool CanLeave(const BlockingGraph& graph, const std::vector<bool>& in_s,
              const std::vector<bool>& present) {
  const size_t n = graph.blockers.size();
  CAIRN_THROW_UNLESS(in_s.size() == n && present.size() == n,
                     "CanLeave: " + std::to_string(in_s.size()) + " set flags and " +
                         std::to_string(present.size()) + " presence flags for a graph of " +
                         std::to_string(n) + " parts");
  for (size_t i = 0; i < n; ++i) {
    if (!in_s[i] || !present[i]) continue;
    if (i < graph.fixed.size() && graph.fixed[i]) return false;
    for (const int j : graph.blockers[i])
      if (present[j] && !in_s[j]) return false;
  }
  return true;
}

std::vector<int> BlockingClosure(const BlockingGraph& graph, int part,
                                 const std::vector<bool>& present) {
  const int n = static_cast<int>(graph.blockers.size());
  CAIRN_THROW_UNLESS(part >= 0 && part < n && static_cast<int>(present.size()) == n,
                     "BlockingClosure: part " + std::to_string(part) + " of a graph of " +
                         std::to_string(n) + " parts, " + std::to_string(present.size()) +
                         " presence flags");
  std::vector<bool> seen(n, false);
  std::vector<int> stack{part}, out;
  seen[part] = true;
  while (!stack.empty()) {
    const int i = stack.back();
    stack.pop_back();
    out.push_back(i);
    for (const int j : graph.blockers[i])
      if (present[j] && !seen[j]) {
        seen[j] = true;
        stack.push_back(j);
      }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::vector<int>> StronglyConnectedComponents(const BlockingGraph& graph,
                                                          const std::vector<bool>& present) {
  // Tarjan's algorithm, iterative (no recursion depth limit on big scenes).
  const int n = static_cast<int>(graph.blockers.size());
  CAIRN_THROW_UNLESS(static_cast<int>(present.size()) == n,
                     "StronglyConnectedComponents: " + std::to_string(present.size()) +
                         " presence flags for a graph of " + std::to_string(n) + " parts");
  std::vector<int> index(n, -1), low(n, 0), stack;
  std::vector<bool> on_stack(n, false);
  std::vector<std::vector<int>> components;
  int counter = 0;
  for (int root = 0; root < n; ++root) {
    if (!present[root] || index[root] >= 0) continue;
    std::vector<std::pair<int, size_t>> calls{{root, 0}};  // (node, next arc)
    index[root] = low[root] = counter++;
    stack.push_back(root);
    on_stack[root] = true;
    while (!calls.empty()) {
      auto& [v, next] = calls.back();
      if (next < graph.blockers[v].size()) {
        const int w = graph.blockers[v][next++];
        if (!present[w]) continue;
        if (index[w] < 0) {
          index[w] = low[w] = counter++;
          stack.push_back(w);
          on_stack[w] = true;
          calls.emplace_back(w, 0);
        } else if (on_stack[w]) {
          low[v] = std::min(low[v], index[w]);
        }
        continue;
      }
      const int done = v;
      calls.pop_back();
      if (!calls.empty()) low[calls.back().first] = std::min(low[calls.back().first], low[done]);
      if (low[done] == index[done]) {
        std::vector<int> comp;
        int w = -1;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = false;
          comp.push_back(w);
        } while (w != done);
        std::sort(comp.begin(), comp.end());
        components.push_back(std::move(comp));
      }
    }
  }
  std::sort(components.begin(), components.end(),
            [](const std::vector<int>& a, const std::vector<int>& b) { return a[0] < b[0]; });
  return components;
}

}  // namespace cairn

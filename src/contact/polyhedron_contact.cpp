#include "cairn/contact/polyhedron_contact.h"

// Boost.Geometry's default "robustness" rescales coordinates to an integer
// grid before clipping, which moves the intersection points by ~1e-8 of the
// face size: contact points must lie exactly on both faces' edges. Cairn's
// faces are validated simple polygons, so plain floating point suffices.
#define BOOST_GEOMETRY_NO_ROBUSTNESS

#include <algorithm>
#include <array>
#include <boost/geometry.hpp>  // IWYU pragma: keep
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "cairn/geometry/box_grid.h"
#include "cairn/geometry/polygon.h"

namespace cairn {

const char* to_string(ContactKind3 kind) {
  switch (kind) {
    case ContactKind3::kFaceFace:
      return "face-face";
    case ContactKind3::kVertexFace:
      return "vertex-face";
    case ContactKind3::kFaceVertex:
      return "face-vertex";
    case ContactKind3::kEdgeFace:
      return "edge-face";
    case ContactKind3::kFaceEdge:
      return "face-edge";
    case ContactKind3::kEdgeEdge:
      return "edge-edge";
  }
  return "unknown";
}

std::vector<std::array<int, 2>> PolyhedronEdges(const Polyhedron& p) {
  std::vector<std::array<int, 2>> edges;
  for (const auto& f : p.faces())
    for (size_t i = 0; i < f.size(); ++i) {
      const int a = f[i], b = f[(i + 1) % f.size()];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

namespace {

namespace bg = boost::geometry;
using Point2 = bg::model::d2::point_xy<double>;
using Polygon2 = bg::model::polygon<Point2>;
using MultiPolygon2 = bg::model::multi_polygon<Polygon2>;
using Line2 = bg::model::linestring<Point2>;
using MultiLine2 = bg::model::multi_linestring<Line2>;

// A face's corner whose turn, |a × b| / (|a| |b|) = sin of its exterior
// angle, is below this is flat (a vertex inside a straight edge) rather than
// convex (dimensionless: the roundoff of unit vectors' cross products).
constexpr double kCornerFlat = 1e-9;

// A polyhedron placed in the world, with the adjacency the tests need.
struct Placed {
  std::vector<Vector3> v;       // vertices, world
  std::vector<Vector3> n;       // face normals, world
  std::vector<double> offset;   // n · x on each face's plane
  std::vector<Vector3> lo, hi;  // face bounding boxes
  // vertex → its corners: (previous vertex, next vertex, face), one per face
  // around it, in the face's outward (counter-clockwise) order.
  std::vector<std::vector<std::array<int, 3>>> corners;
  std::vector<std::array<int, 2>> edges;       // PolyhedronEdges order
  std::vector<std::array<int, 2>> edge_faces;  // edge → its two faces
  const Polyhedron* shape = nullptr;

  Placed(const Polyhedron& p, const Eigen::Isometry3d& X) : shape(&p) {
    for (const Vector3& x : p.vertices()) v.push_back(X * x);
    const int nf = static_cast<int>(p.faces().size());
    for (int f = 0; f < nf; ++f) {
      n.push_back(X.linear() * p.face_normals()[f]);
      offset.push_back(n[f].dot(v[p.faces()[f][0]]));
      Vector3 l = v[p.faces()[f][0]], h = l;
      for (int i : p.faces()[f]) l = l.cwiseMin(v[i]), h = h.cwiseMax(v[i]);
      lo.push_back(l);
      hi.push_back(h);
    }
    corners.resize(v.size());
    edges = PolyhedronEdges(p);
    edge_faces.assign(edges.size(), {-1, -1});
    for (int f = 0; f < nf; ++f) {
      const auto& face = p.faces()[f];
      for (size_t i = 0; i < face.size(); ++i) {
        const int a = face[i], b = face[(i + 1) % face.size()];
        corners[b].push_back({a, face[(i + 2) % face.size()], f});
        const std::array<int, 2> key{std::min(a, b), std::max(a, b)};
        const auto e = std::lower_bound(edges.begin(), edges.end(), key) - edges.begin();
        (edge_faces[e][0] < 0 ? edge_faces[e][0] : edge_faces[e][1]) = f;
      }
    }
  }
};

// An orthonormal basis (u, w) of the plane with normal n; fixed by n alone.
void PlaneBasis(const Vector3& n, Vector3* u, Vector3* w) {
  const Vector3 seed = std::abs(n.x()) < 0.9 ? Vector3::UnitX() : Vector3::UnitY();
  *u = n.cross(seed).normalized();
  *w = n.cross(*u);
}

Polygon2 FacePolygon(const Placed& P, int f, const Vector3& o, const Vector3& u, const Vector3& w) {
  Polygon2 poly;
  for (int i : P.shape->faces()[f]) {
    const Vector3 d = P.v[i] - o;
    bg::append(poly.outer(), Point2(d.dot(u), d.dot(w)));
  }
  bg::correct(poly);
  return poly;
}

bool BoxesApart(const Vector3& lo1, const Vector3& hi1, const Vector3& lo2, const Vector3& hi2,
                double tol) {
  return (lo1.array() > hi2.array() + tol).any() || (lo2.array() > hi1.array() + tol).any();
}

// The grid of a placed part's edges.
BoxGrid EdgeGrid(const Placed& P, double tol) {
  std::vector<Vector3> lo, hi;
  for (const auto& e : P.edges) {
    lo.push_back(P.v[e[0]].cwiseMin(P.v[e[1]]));
    hi.push_back(P.v[e[0]].cwiseMax(P.v[e[1]]));
  }
  return BoxGrid(lo, hi, tol);
}

// Whether P's material near vertex i lies on the +n side of the plane
// n · x = c (within tol): every corner of a face at i does. A corner is the
// sector of its face between the edges a = p − v and b = q − v (p, q the
// face's vertices before and after i). A convex corner (angle < π) lies on
// that side when a and b do. A flat corner (i inside a straight edge of the
// face: a and b opposite) is a half-plane, which also needs its inward
// direction m = a × n_f on that side; a reflex one (angle > π) holds −a and
// −b as well, so a and b must lie in the plane. Testing only the vertices
// next to i missed both: the middle vertex of a cube's split vertical edge,
// whose neighbours are on that edge, passed as "above" the face of a wall
// beside the cube, and a contact whose normal was that face's held the cube
// up by a squeeze (issue 31).
bool MaterialAbove(const Placed& P, int i, const Vector3& n, double c, double tol) {
  const Vector3& v = P.v[i];
  const auto below = [&](const Vector3& d) { return n.dot(v + d) - c < -tol; };
  for (const auto& [p, q, f] : P.corners[i]) {
    const Vector3 a = P.v[p] - v, b = P.v[q] - v;
    if (below(a) || below(b)) return false;
    // Convex when turning from the edge into i to the edge out of it is a
    // left turn about the outward normal (by more than roundoff).
    const Vector3& nf = P.n[f];
    const double turn = (-a).cross(b).dot(nf);
    if (turn > kCornerFlat * a.norm() * b.norm()) continue;
    if (below(a.cross(nf)) || below(-a) || below(-b)) return false;
  }
  return true;
}

// Whether P's material next to edge e lies on the +n side of a plane through
// the edge (n ⟂ the edge), to within the angle whose sine is sin_tol. That
// material is the wedge between the edge's two faces. Each face leaves the
// edge along `into` = n_f × (the edge in the face's counter-clockwise
// order), so both must point to +n. A convex wedge is spanned by those two;
// a flat or reflex one (the faces turn by π or more) also holds the
// half-space behind each face, so each face's outward normal must point to
// −n as well, which for a reflex edge no plane through it satisfies.
bool EdgeMaterialAbove(const Placed& P, int e, const Vector3& n, double sin_tol) {
  const auto [i, j] = P.edges[e];
  const Vector3 d = (P.v[j] - P.v[i]).normalized();
  std::array<Vector3, 2> into;
  for (int s = 0; s < 2; ++s) {
    const int f = P.edge_faces[e][s];
    const auto& face = P.shape->faces()[f];
    const size_t k = std::find(face.begin(), face.end(), i) - face.begin();
    const bool i_to_j = face[(k + 1) % face.size()] == j;
    into[s] = P.n[f].cross(i_to_j ? d : Vector3(-d));
    if (n.dot(into[s]) < -sin_tol) return false;
  }
  const auto [f1, f2] = P.edge_faces[e];
  const bool convex = into[0].dot(P.n[f2]) < -kCornerFlat;
  return convex || (n.dot(P.n[f1]) <= sin_tol && n.dot(P.n[f2]) <= sin_tol);
}

// Whether P's material next to its vertex i, touching face `face` (2-D, in
// the face's plane basis u, w about o; outward normal n) at or near the
// face's boundary, lies over the face: some direction of P's surface
// leaving i (each corner's two edges, and the middle of a convex corner),
// projected on the plane, runs into the face polygon. A vertex beside the
// face, at its corner or on its edge with its material across the face's
// boundary in the plane, touches nothing that the faces there do not
// already give: a wheel arch's corner at the end of a bumper's inside step
// (the toy truck, issue 31) gave a contact normal to the step, and so an
// arc along it, where the two parts only meet at that corner. A vertex
// inside the face by more than tol needs no test; where the face is too
// small to step into, the answer is yes (keep the contact).
bool OverFace(const Placed& P, int i, const Vector3& n, const Polygon2& face, const Vector3& o,
              const Vector3& u, const Vector3& w, double tol, double sin_tol) {
  const Vector3& x = P.v[i];
  const Point2 at((x - o).dot(u), (x - o).dot(w));
  const auto& ring = face.outer();
  double boundary = std::numeric_limits<double>::infinity(), shortest = boundary;
  for (size_t k = 0; k + 1 < ring.size(); ++k) {  // the ring repeats its first point
    const Vector2 a(ring[k].x(), ring[k].y()), b(ring[k + 1].x(), ring[k + 1].y());
    boundary = std::min(boundary, DistanceToSegment(Vector2(at.x(), at.y()), a, b));
    shortest = std::min(shortest, (b - a).norm());
  }
  if (boundary > tol) return true;
  for (const auto& [p, q, f] : P.corners[i]) {
    const Vector3 a = P.v[p] - x, b = P.v[q] - x;
    std::array<Vector3, 3> dirs{a, b, Vector3::Zero()};
    if ((-a).cross(b).dot(P.n[f]) > kCornerFlat * a.norm() * b.norm())
      dirs[2] = a.normalized() + b.normalized();
    for (const Vector3& d : dirs) {
      const Vector3 t = d - n.dot(d) * n;
      if (t.norm() <= sin_tol * d.norm()) continue;  // along the normal (or none)
      const double step = 0.5 * std::min(shortest, t.norm());
      if (step <= 4 * tol) return true;  // too small to tell
      const Vector3 r = x + step * t.normalized() - o;
      if (bg::distance(Point2(r.dot(u), r.dot(w)), face) <= tol) return true;
    }
  }
  return false;
}

// The face–face patches found so far on each face of b (in b-face 2-D
// coordinates), to skip vertex and edge points inside them.
struct Patch {
  int face_b;
  MultiPolygon2 area;
};

}  // namespace

namespace {

// The contacts between two placed polyhedra, found kind by kind; the
// face–face patches found first are remembered, so that the vertex and edge
// points inside them are not found again.
class PairContacts {
 public:
  PairContacts(const Polyhedron& shape_a, const Eigen::Isometry3d& X_WA, const Polyhedron& shape_b,
               const Eigen::Isometry3d& X_WB, double length, double angle, double depth)
      : a(shape_a),
        b(shape_b),
        A(shape_a, X_WA),
        B(shape_b, X_WB),
        length_tol(length),
        depth_tol(std::max(length, depth)),
        cos_tol(std::cos(angle)),
        sin_tol(std::sin(angle)),
        area_tol(length * length),
        faces_a(A.lo, A.hi, depth_tol),
        faces_b(B.lo, B.hi, depth_tol),
        edges_b(EdgeGrid(B, depth_tol)) {}

  // Vertex–face and edge–face contacts, both ways (a's features on b's faces,
  // then b's on a's).
  void VertexFaces() {
    VertexFace(A, B, true);
    VertexFace(B, A, false);
  }
  void EdgeFaces() {
    EdgeFace(A, B, true);
    EdgeFace(B, A, false);
  }

  // Face–face: a face of a pressed onto a face of b (opposite normals, every
  // vertex on b's plane, or behind it by up to the depth): their
  // intersection, one patch per piece, on a's face, or where a's face lies
  // deeper than the length tolerance behind b's, midway between the two
  // (Height).
  void FaceFace() {
    for (int fb = 0; fb < static_cast<int>(B.n.size()); ++fb) {
      Vector3 u, w;
      PlaneBasis(B.n[fb], &u, &w);
      const Vector3 o = B.v[b.faces()[fb][0]];
      Polygon2 poly_b;
      bool have_b = false;
      for (const int fa : faces_a.Query(B.lo[fb], B.hi[fb])) {
        if (A.n[fa].dot(B.n[fb]) > -cos_tol) continue;
        if (BoxesApart(A.lo[fa], A.hi[fa], B.lo[fb], B.hi[fb], depth_tol)) continue;
        bool on_plane = true;
        double gap = 0;
        for (int i : a.faces()[fa]) {
          const double d = B.n[fb].dot(A.v[i]) - B.offset[fb];
          on_plane = on_plane && Touches(d);
          gap += d;
        }
        if (!on_plane) continue;
        gap /= static_cast<double>(a.faces()[fa].size());
        if (!have_b) poly_b = FacePolygon(B, fb, o, u, w), have_b = true;
        MultiPolygon2 pieces;
        bg::intersection(FacePolygon(A, fa, o, u, w), poly_b, pieces);
        MultiPolygon2 kept;
        for (const Polygon2& piece : pieces) {
          if (bg::area(piece) <= area_tol) continue;
          kept.push_back(piece);
          const auto& ring = piece.outer();
          for (size_t k = 0; k + 1 < ring.size(); ++k) {  // the ring repeats its first point
            PolyhedronContactPoint c;
            c.p_W = o + ring[k].x() * u + ring[k].y() * w + Height(gap) * B.n[fb];
            c.n_W = B.n[fb];
            c.gap = gap;
            c.kind = ContactKind3::kFaceFace;
            c.patch = next_patch;
            c.feature_a = fa;
            c.feature_b = fb;
            out.push_back(c);
          }
          ++next_patch;
        }
        if (!kept.empty()) {
          patches.push_back({fb, kept});
          face_pairs.emplace_back(fa, fb);
        }
      }
    }
  }

  // Is the point p (on face f of `faces_of`'s side) inside a face–face patch?
  bool InPatch(const Vector3& p, int face, bool face_is_b) const {
    for (size_t k = 0; k < patches.size(); ++k) {
      const int f = face_is_b ? patches[k].face_b : face_pairs[k].first;
      if (f != face) continue;
      const int fb = patches[k].face_b;
      Vector3 u, w;
      PlaneBasis(B.n[fb], &u, &w);
      const Vector3 d = p - B.v[b.faces()[fb][0]];
      if (bg::distance(Point2(d.dot(u), d.dot(w)), patches[k].area) <= length_tol) return true;
    }
    return false;
  }

  // Vertex–face, both ways: a vertex of P on a face of Q (or behind it by up
  // to the depth: the point is then midway between the vertex and the face,
  // Height).
  void VertexFace(const Placed& P, const Placed& Q, bool p_is_a) {
    for (int i = 0; i < static_cast<int>(P.v.size()); ++i) {
      for (const int f : FacesOf(Q).Query(P.v[i], P.v[i])) {
        const double d = Q.n[f].dot(P.v[i]) - Q.offset[f];
        if (!Touches(d)) continue;
        if (BoxesApart(P.v[i], P.v[i], Q.lo[f], Q.hi[f], depth_tol)) continue;
        if (!MaterialAbove(P, i, Q.n[f], Level(Q, f, d), length_tol)) continue;
        Vector3 u, w;
        PlaneBasis(Q.n[f], &u, &w);
        const Vector3 o = Q.v[Q.shape->faces()[f][0]];
        const Vector3 r = P.v[i] - o;
        const Polygon2 face = FacePolygon(Q, f, o, u, w);
        if (bg::distance(Point2(r.dot(u), r.dot(w)), face) > length_tol) continue;
        if (!OverFace(P, i, Q.n[f], face, o, u, w, length_tol, sin_tol)) continue;
        // Inside a face–face patch of this face: already a contact.
        if (p_is_a ? InPatch(P.v[i], f, true) : InPatch(P.v[i], f, false)) continue;
        PolyhedronContactPoint c;
        c.p_W = P.v[i] + (Height(d) - d) * Q.n[f];
        c.n_W = p_is_a ? Q.n[f] : Vector3(-Q.n[f]);
        c.gap = d;
        c.kind = p_is_a ? ContactKind3::kVertexFace : ContactKind3::kFaceVertex;
        c.patch = next_patch++;
        c.feature_a = p_is_a ? i : f;
        c.feature_b = p_is_a ? f : i;
        out.push_back(c);
      }
    }
  }

  // Edge–face, both ways: an edge of P lying on a face of Q, clipped to it
  // (its ends inside the face are vertex–face points already; the clip points
  // on the face's boundary are new).
  void EdgeFace(const Placed& P, const Placed& Q, bool p_is_a) {
    for (int e = 0; e < static_cast<int>(P.edges.size()); ++e) {
      const int i = P.edges[e][0], j = P.edges[e][1];
      for (const int f : FacesOf(Q).Query(P.v[i].cwiseMin(P.v[j]), P.v[i].cwiseMax(P.v[j]))) {
        const double di = Q.n[f].dot(P.v[i]) - Q.offset[f];
        const double dj = Q.n[f].dot(P.v[j]) - Q.offset[f];
        if (!Touches(di) || !Touches(dj)) continue;
        if (BoxesApart(P.v[i].cwiseMin(P.v[j]), P.v[i].cwiseMax(P.v[j]), Q.lo[f], Q.hi[f],
                       depth_tol))
          continue;
        // An edge of a face already pressed onto this face: inside that patch.
        bool in_face_pair = false;
        for (const auto& [fa, fb] : face_pairs)
          for (int s = 0; s < 2; ++s) {
            const int pf = P.edge_faces[e][s];
            in_face_pair = in_face_pair || (p_is_a ? (pf == fa && f == fb) : (pf == fb && f == fa));
          }
        if (in_face_pair) continue;
        if (!MaterialAbove(P, i, Q.n[f], Level(Q, f, di), length_tol) ||
            !MaterialAbove(P, j, Q.n[f], Level(Q, f, dj), length_tol))
          continue;
        Vector3 u, w;
        PlaneBasis(Q.n[f], &u, &w);
        const Vector3 o = Q.v[Q.shape->faces()[f][0]];
        Line2 seg;
        for (int k : {i, j}) {
          const Vector3 r = P.v[k] - o;
          bg::append(seg, Point2(r.dot(u), r.dot(w)));
        }
        MultiLine2 clipped;
        bg::intersection(seg, FacePolygon(Q, f, o, u, w), clipped);
        for (const Line2& piece : clipped) {
          if (piece.size() < 2) continue;
          for (const Point2& q : {piece.front(), piece.back()}) {
            PolyhedronContactPoint c;
            c.p_W = o + q.x() * u + q.y() * w + Height(0.5 * (di + dj)) * Q.n[f];
            c.n_W = p_is_a ? Q.n[f] : Vector3(-Q.n[f]);
            c.gap = 0.5 * (di + dj);
            c.kind = p_is_a ? ContactKind3::kEdgeFace : ContactKind3::kFaceEdge;
            c.patch = next_patch;
            c.feature_a = p_is_a ? e : f;
            c.feature_b = p_is_a ? f : e;
            out.push_back(c);
          }
          ++next_patch;
        }
      }
    }
  }

  // Edge–edge crossings.
  void EdgeEdge() {
    for (int ea = 0; ea < static_cast<int>(A.edges.size()); ++ea) {
      const Vector3 p0 = A.v[A.edges[ea][0]], p1 = A.v[A.edges[ea][1]];
      for (const int eb : edges_b.Query(p0.cwiseMin(p1), p0.cwiseMax(p1))) {
        const Vector3 q0 = B.v[B.edges[eb][0]], q1 = B.v[B.edges[eb][1]];
        if (BoxesApart(p0.cwiseMin(p1), p0.cwiseMax(p1), q0.cwiseMin(q1), q0.cwiseMax(q1),
                       depth_tol))
          continue;
        const Vector3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
        const Vector3 cr = d1.cross(d2);
        if (cr.norm() <= sin_tol * d1.norm() * d2.norm()) continue;  // parallel
        // Closest points p0 + s d1, q0 + t d2.
        const double a11 = d1.dot(d1), a12 = d1.dot(d2), a22 = d2.dot(d2);
        const double det = a11 * a22 - a12 * a12;
        const double s = (a12 * d2.dot(r) - a22 * d1.dot(r)) / det;
        const double t = (a11 * d2.dot(r) - a12 * d1.dot(r)) / det;
        const double margin1 = length_tol / std::sqrt(a11), margin2 = length_tol / std::sqrt(a22);
        if (s <= margin1 || s >= 1 - margin1 || t <= margin2 || t >= 1 - margin2) continue;
        const Vector3 pa = p0 + s * d1, pb = q0 + t * d2;
        if ((pa - pb).norm() > depth_tol) continue;
        // The normal, into a's material: the plane of the two edges must
        // separate the wedges of material along them, a's on the side n
        // points to and b's on the other. Where neither side does, the
        // crossing constrains nothing the faces there do not: an edge of a
        // face flush with a face beside it (a rod's end in the plane of the
        // plate it passes through), or edges along the same smooth surface.
        Vector3 n = cr.normalized();
        const auto separates = [&](const Vector3& m) {
          return EdgeMaterialAbove(A, ea, m, sin_tol) && EdgeMaterialAbove(B, eb, -m, sin_tol);
        };
        if (!separates(n)) {
          if (!separates(-n)) continue;
          n = -n;
        }
        // Apart by more than the length tolerance, or a's edge deeper than
        // the depth behind b's.
        if (!Touches(n.dot(pa - pb))) continue;
        PolyhedronContactPoint c;
        c.p_W = 0.5 * (pa + pb);
        c.n_W = n;
        c.gap = n.dot(pa - pb);
        c.kind = ContactKind3::kEdgeEdge;
        c.patch = next_patch++;
        c.feature_a = ea;
        c.feature_b = eb;
        out.push_back(c);
      }
    }
  }

  // Merge points closer than length_tol with the same normal (an edge end on
  // a face that is also a vertex–face point, ...): the first one stays.
  std::vector<PolyhedronContactPoint> Merged() const {
    std::vector<PolyhedronContactPoint> merged;
    for (const PolyhedronContactPoint& c : out) {
      bool dup = false;
      for (const PolyhedronContactPoint& m : merged)
        dup = dup || ((m.p_W - c.p_W).norm() <= length_tol && m.n_W.dot(c.n_W) >= cos_tol);
      if (!dup) merged.push_back(c);
    }
    return merged;
  }

 private:
  const Polyhedron& a;
  const Polyhedron& b;
  const Placed A, B;
  // length_tol: how far apart features still touch; depth_tol (≥ it): how
  // deep one may lie behind the other's face and still touch (an overlap
  // depth, AssemblyDef::overlap_depth, read as contact).
  const double length_tol, depth_tol, cos_tol, sin_tol, area_tol;
  std::vector<PolyhedronContactPoint> out;
  std::vector<Patch> patches;  // by face of b (face–face, a's faces pressed onto b's)
  std::vector<std::pair<int, int>> face_pairs;  // (face a, face b) of each patch
  int next_patch = 0;
  // Which faces and edges are near which (BoxGrid).
  const BoxGrid faces_a, faces_b, edges_b;
  const BoxGrid& FacesOf(const Placed& Q) const { return &Q == &A ? faces_a : faces_b; }

  // Whether a feature at signed distance d (length; < 0: behind, inside the
  // other part) from a face touches it.
  bool Touches(double d) const { return d >= -depth_tol && d <= length_tol; }
  // The level of face f's plane that MaterialAbove tests a feature at
  // signed distance d against: the plane itself, or for a feature deeper
  // than the length tolerance behind it, that plane moved down to the
  // feature's depth (less the tolerance), so that a corner pressed into the
  // face is tested as one resting on it.
  double Level(const Placed& Q, int f, double d) const {
    return Q.offset[f] + std::min(0.0, d + length_tol);
  }
  // Where a contact point lies along a face's normal, above its plane, for a
  // feature at signed distance d from it: on the feature (d) where they
  // touch within the length tolerance, as always; midway (d / 2, the
  // overlap's mid-surface) where the feature lies deeper behind the face.
  double Height(double d) const { return d < -length_tol ? 0.5 * d : d; }
};

}  // namespace

std::vector<PolyhedronContactPoint> FindPolyhedronContacts(
    const Polyhedron& a, const Eigen::Isometry3d& X_WA, const Polyhedron& b,
    const Eigen::Isometry3d& X_WB, double length_tol, double angle_tol, double depth_tol) {
  PairContacts pair(a, X_WA, b, X_WB, length_tol, angle_tol, depth_tol);
  pair.FaceFace();
  pair.VertexFaces();
  pair.EdgeFaces();
  pair.EdgeEdge();
  return pair.Merged();
}

}  // namespace cairn

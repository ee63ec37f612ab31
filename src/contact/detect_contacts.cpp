#include "cairn/contact/detect_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "cairn/contact/polyhedron_contact.h"
#include "cairn/core/tolerances.h"
#include "corner_touches.h"

namespace cairn {

namespace {
// The roundoff of a dot product of two unit normals (dimensionless, ≈ 4.5 ε):
// normals the angle tolerance calls equal must compare so despite it.
constexpr double kCosineRoundoff = 1e-15;
}  // namespace

Contact FlippedContact(Contact c) {
  std::swap(c.part_a, c.part_b);
  std::swap(c.index_a, c.index_b);
  c.n_W = -c.n_W;
  switch (c.feature) {
    case ContactFeature::kVertexOfAOnEdgeOfB:
      c.feature = ContactFeature::kVertexOfBOnEdgeOfA;
      break;
    case ContactFeature::kVertexOfBOnEdgeOfA:
      c.feature = ContactFeature::kVertexOfAOnEdgeOfB;
      break;
    case ContactFeature::kVertexFace:
      c.feature = ContactFeature::kFaceVertex;
      break;
    case ContactFeature::kFaceVertex:
      c.feature = ContactFeature::kVertexFace;
      break;
    case ContactFeature::kEdgeFace:
      c.feature = ContactFeature::kFaceEdge;
      break;
    case ContactFeature::kFaceEdge:
      c.feature = ContactFeature::kEdgeFace;
      break;
    default:
      break;
  }
  return c;
}

const char* to_string(ContactFeature feature) {
  switch (feature) {
    case ContactFeature::kVertexOfAOnEdgeOfB:
      return "vertex-edge";
    case ContactFeature::kVertexOfBOnEdgeOfA:
      return "edge-vertex";
    case ContactFeature::kFixture:
      return "fixture";
    case ContactFeature::kFaceFace:
      return "face-face";
    case ContactFeature::kVertexFace:
      return "vertex-face";
    case ContactFeature::kFaceVertex:
      return "face-vertex";
    case ContactFeature::kEdgeFace:
      return "edge-face";
    case ContactFeature::kFaceEdge:
      return "face-edge";
    case ContactFeature::kEdgeEdge:
      return "edge-edge";
    case ContactFeature::kInterface:
      return "interface";
  }
  return "unknown";
}

std::pair<Vector3, Vector3> TangentBasis(const Vector3& n) {
  // Project the world x axis onto the tangent plane, or the y axis when n is
  // within 45° of x (the projection would be short).
  const Vector3 axis = std::abs(n.x()) < std::sqrt(0.5) ? Vector3::UnitX() : Vector3::UnitY();
  const Vector3 t1 = (axis - n * n.dot(axis)).normalized();
  return {t1, n.cross(t1)};
}

std::vector<Vector3> FrictionDirections(const Contact& c, int dimension, int D) {
  if (dimension == 2) return {c.t_W(), -c.t_W()};
  const auto [t1, t2] = TangentBasis(c.n_W);
  std::vector<Vector3> out(D);
  for (int k = 0; k < D; ++k) {
    const double angle = 2 * M_PI * k / D;
    out[k] = std::cos(angle) * t1 + std::sin(angle) * t2;
  }
  return out;
}

namespace {

// True when the polygon's material at vertex k lies on the outer side of a
// line with outward normal n (so that vertex can rest on that line): k is a
// convex (or straight) vertex and both its edges leave it at an angle no more
// than `angle_tol` into the inner side, plus the distance allowance `tol`.
bool WedgeOutside(const Polygon& poly, int k, const Vector2& n, double tol, double angle_tol) {
  const int m = static_cast<int>(poly.size());
  const Vector2& v = poly[k];
  const Vector2 to_prev = poly[(k + m - 1) % m] - v;
  const Vector2 to_next = poly[(k + 1) % m] - v;
  // A reflex vertex's material spans more than a half-plane: it cannot rest
  // on a line without penetrating it.
  const double turn = Cross2(-to_prev, to_next);
  if (turn < -angle_tol * to_prev.norm() * to_next.norm()) return false;
  const auto outside = [&](const Vector2& d) { return d.dot(n) >= -(angle_tol * d.norm() + tol); };
  return outside(to_prev) && outside(to_next);
}

// Appends the contacts of every vertex of `vp` touching an edge of `ep`.
// `n_sign` = +1 when vp is part a (the edge normal of ep points from b into
// a), −1 when vp is part b.
void VertexEdgeContacts(const Polygon& vp, const Polygon& ep, int a, int b, double mu, double tol,
                        double angle_tol, bool vertex_of_a, std::vector<Contact>& out) {
  const int nv = static_cast<int>(vp.size());
  const int ne = static_cast<int>(ep.size());
  for (int e = 0; e < ne; ++e) {
    const Vector2& q0 = ep[e];
    const Vector2 d = ep[(e + 1) % ne] - q0;
    const double len = d.norm();
    if (len <= 0) continue;
    const Vector2 dir = d / len;
    const Vector2 n_e(dir.y(), -dir.x());  // outward normal of a ccw polygon
    for (int k = 0; k < nv; ++k) {
      const Vector2 r = vp[k] - q0;
      const double s = r.dot(n_e);
      if (s > tol || s < -tol) continue;
      const double u = r.dot(dir);
      if (u < -tol || u > len + tol) continue;
      if (!WedgeOutside(vp, k, n_e, tol, angle_tol)) continue;
      Contact c;
      c.part_a = a;
      c.part_b = b;
      c.p_WC = Embed(vp[k]);
      c.n_W = Embed(vertex_of_a ? n_e : Vector2(-n_e));
      c.gap = s;
      c.mu = mu;
      c.feature =
          vertex_of_a ? ContactFeature::kVertexOfAOnEdgeOfB : ContactFeature::kVertexOfBOnEdgeOfA;
      c.index_a = vertex_of_a ? k : e;
      c.index_b = vertex_of_a ? e : k;
      out.push_back(c);
    }
  }
}

}  // namespace

void DetectPairContacts(const Polygon& poly_i, const Polygon& poly_j, int i, int j, double mu,
                        double tol, double angle_tol, std::vector<Contact>& out) {
  const size_t first = out.size();
  VertexEdgeContacts(poly_i, poly_j, i, j, mu, tol, angle_tol, /*vertex_of_a=*/true, out);
  VertexEdgeContacts(poly_j, poly_i, i, j, mu, tol, angle_tol, /*vertex_of_a=*/false, out);
  // Merge duplicates: the same point (within tol) with the same normal (within
  // the angle tolerance). The end of an edge–edge overlap where two vertices
  // coincide is found from both sides.
  size_t kept = first;
  for (size_t c = first; c < out.size(); ++c) {
    bool duplicate = false;
    for (size_t k = first; k < kept; ++k) {
      if ((out[k].p_WC - out[c].p_WC).norm() <= tol &&
          out[k].n_W.dot(out[c].n_W) >= std::cos(angle_tol) - kCosineRoundoff) {
        duplicate = true;
        break;
      }
    }
    if (!duplicate) out[kept++] = out[c];
  }
  out.resize(kept);
}

namespace {

ContactFeature FeatureOf(ContactKind3 kind) {
  switch (kind) {
    case ContactKind3::kFaceFace:
      return ContactFeature::kFaceFace;
    case ContactKind3::kVertexFace:
      return ContactFeature::kVertexFace;
    case ContactKind3::kFaceVertex:
      return ContactFeature::kFaceVertex;
    case ContactKind3::kEdgeFace:
      return ContactFeature::kEdgeFace;
    case ContactKind3::kFaceEdge:
      return ContactFeature::kFaceEdge;
    case ContactKind3::kEdgeEdge:
      return ContactFeature::kEdgeEdge;
  }
  return ContactFeature::kFaceFace;
}

using Box3 = std::pair<Vector3, Vector3>;

// 2-D: whether an edge of the (ccw) polygon with outward normal m contains p.
bool PolygonHasEdge(const Polygon& poly, const Vector2& p, const Vector2& m, double tol,
                    double cos_tol) {
  const int ne = static_cast<int>(poly.size());
  for (int e = 0; e < ne; ++e) {
    const Vector2 d = poly[(e + 1) % ne] - poly[e];
    const double len = d.norm();
    if (len <= 0) continue;
    const Vector2 dir = d / len;
    if (Vector2(dir.y(), -dir.x()).dot(m) < cos_tol) continue;
    const double u = std::clamp((p - poly[e]).dot(dir), 0.0, len);
    if ((poly[e] + u * dir - p).norm() <= tol) return true;
  }
  return false;
}

// 2-D: whether the polygon's material near p lies on the side m·(x − p) ≥ 0:
// every edge through p has both ends on that side, and p is no reflex vertex.
bool PolygonOnSide(const Polygon& poly, const Vector2& p, const Vector2& m, double tol,
                   double angle_tol) {
  const int ne = static_cast<int>(poly.size());
  for (int e = 0; e < ne; ++e) {
    const Vector2& q0 = poly[e];
    const Vector2& q1 = poly[(e + 1) % ne];
    const Vector2 d = q1 - q0;
    const double len = d.norm();
    if (len <= 0) continue;
    const double u = std::clamp((p - q0).dot(d) / len, 0.0, len);
    if ((q0 + u * d / len - p).norm() > tol) continue;
    for (const Vector2& q : {q0, q1})
      if (m.dot(q - p) < -(tol + angle_tol * (q - p).norm())) return false;
  }
  for (int k = 0; k < ne; ++k) {
    if ((poly[k] - p).norm() > tol) continue;
    const Vector2 to_prev = poly[(k + ne - 1) % ne] - poly[k];
    const Vector2 to_next = poly[(k + 1) % ne] - poly[k];
    if (Cross2(-to_prev, to_next) < -angle_tol * to_prev.norm() * to_next.norm()) return false;
  }
  return true;
}

// 3-D, in the polyhedron's own frame (X maps it to the world; a rigid map
// keeps every distance, so the tolerances are the same): whether face f
// contains p_B, on its plane within tol and inside its polygon or within
// tol of it (crossing number in the face's plane).
bool FaceContains(const Polyhedron& poly, size_t f, const Vector3& p_B, double tol) {
  const Vector3& n = poly.face_normals()[f];
  const auto& face = poly.faces()[f];
  const Vector3& v0 = poly.vertices()[face[0]];
  if (std::abs(n.dot(p_B - v0)) > tol) return false;
  const auto [u, w] = TangentBasis(n);
  const Vector2 q((p_B - v0).dot(u), (p_B - v0).dot(w));
  bool inside = false;
  for (size_t i = 0, j = face.size() - 1; i < face.size(); j = i++) {
    const Vector3 &vj = poly.vertices()[face[j]], &vi = poly.vertices()[face[i]];
    const Vector2 a((vj - v0).dot(u), (vj - v0).dot(w));
    const Vector2 b((vi - v0).dot(u), (vi - v0).dot(w));
    const Vector2 d = b - a;
    const double s =
        d.squaredNorm() > 0 ? std::clamp((q - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    if ((a + s * d - q).norm() <= tol) return true;
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < a.x() + (q.y() - a.y()) * d.x() / d.y())
      inside = !inside;
  }
  return inside;
}

// 3-D: whether the polyhedron's material near p lies on the side
// m·(x − p) ≥ 0: every face through p has all its vertices on that side. A
// face counts as through p when a face of (nearly) its normal contains p:
// the faces that contain p are found once, in the body's frame.
bool PolyhedronOnSide(const Polyhedron& poly, const Eigen::Isometry3d& X, const Vector3& p,
                      const Vector3& m, double tol, double angle_tol) {
  const Vector3 p_B = X.inverse() * p, m_B = X.linear().transpose() * m;
  std::vector<Vector3> through;  // the normals of the faces that contain p
  for (size_t f = 0; f < poly.faces().size(); ++f)
    if (FaceContains(poly, f, p_B, tol)) through.push_back(poly.face_normals()[f]);
  const double same = 1.0 - numeric::kRoundoff;
  for (size_t f = 0; f < poly.faces().size(); ++f) {
    const Vector3& n = poly.face_normals()[f];
    if (std::none_of(through.begin(), through.end(),
                     [&](const Vector3& t) { return t.dot(n) >= same; }))
      continue;
    for (int i : poly.faces()[f]) {
      const Vector3 v = poly.vertices()[i] - p_B;
      if (m_B.dot(v) < -(tol + angle_tol * v.norm())) return false;
    }
  }
  return true;
}

// 3-D: whether a face of the polyhedron placed by X, with outward normal
// within cos_tol of m, contains p (FaceContains, in the body's frame).
bool PolyhedronHasFace(const Polyhedron& poly, const Eigen::Isometry3d& X, const Vector3& p,
                       const Vector3& m, double tol, double cos_tol) {
  const Vector3 p_B = X.inverse() * p, m_B = X.linear().transpose() * m;
  for (size_t f = 0; f < poly.faces().size(); ++f)
    if (poly.face_normals()[f].dot(m_B) >= cos_tol && FaceContains(poly, f, p_B, tol)) return true;
  return false;
}

bool BoxesTouch3(const Box3& x, const Box3& y, double tol) {
  return ((x.first.array() <= y.second.array() + tol) &&
          (y.first.array() <= x.second.array() + tol))
      .all();
}

}  // namespace

// One pair's contacts at its placements (patches numbered from 0 within the
// pair), keyed by (a, b).
struct PairContactCache::Impl {
  struct Entry {
    Eigen::Isometry3d X_a, X_b;
    std::vector<PolyhedronContactPoint> points;
  };
  const Assembly* assembly = nullptr;  // the pairs are this assembly's parts
  double tol = 0, angle_tol = 0;
  std::unordered_map<std::uint64_t, Entry> pairs;
  int hits = 0;
};

PairContactCache::PairContactCache() : impl_(std::make_unique<Impl>()) {}
PairContactCache::~PairContactCache() = default;
PairContactCache::PairContactCache(PairContactCache&&) noexcept = default;
PairContactCache& PairContactCache::operator=(PairContactCache&&) noexcept = default;
int PairContactCache::hits() const { return impl_->hits; }

namespace {

// The configuration's shapes placed in the world: 2-D polygons or 3-D
// transforms, and every present part's bounding box.
struct PlacedParts {
  std::vector<Polygon> polys;
  std::vector<Eigen::Isometry3d> X;
  std::vector<Box3> boxes;
};

PlacedParts PlaceParts(const Assembly& assembly, const Configuration& config) {
  const int n = assembly.num_parts();
  PlacedParts out;
  out.polys.resize(n);
  out.X.resize(n);
  out.boxes.resize(n);
  for (int i = 0; i < n; ++i) {
    if (!config.present[i]) continue;
    if (assembly.is_3d()) {
      out.X[i] = config.WorldTransform(assembly, i);
    } else {
      out.polys[i] = config.WorldPolygon(assembly, i);
    }
    const std::vector<Vector3> v = config.WorldVertices(assembly, i);
    out.boxes[i] = {v[0], v[0]};
    for (const Vector3& p : v)
      out.boxes[i] = {out.boxes[i].first.cwiseMin(p), out.boxes[i].second.cwiseMax(p)};
  }
  return out;
}

// Given interfaces (Assembly::interfaces()) are the contacts of the assembled
// configuration: each point of each one between two present parts, not both
// fixed. They do not move with the parts: a configuration that moves a part
// is refused by the motion stage (SimulatePlan).
void InterfaceContacts(const Assembly& assembly, const Configuration& config,
                       std::vector<Contact>& contacts, int& patches, ContactStats& stats) {
  const auto& interfaces = assembly.interfaces();
  for (int k = 0; k < static_cast<int>(interfaces.size()); ++k) {
    const Interface& in = interfaces[k];
    if (!config.present[in.part_a] || !config.present[in.part_b]) continue;
    if (assembly.part(in.part_a).fixed && assembly.part(in.part_b).fixed) continue;
    ++stats.pairs_tested;
    ++stats.pairs_touching;
    // The movable part is a, as for found contacts.
    const bool swap = assembly.part(in.part_a).fixed;
    for (int v = 0; v < static_cast<int>(in.points.size()); ++v) {
      Contact c;
      c.part_a = swap ? in.part_b : in.part_a;
      c.part_b = swap ? in.part_a : in.part_b;
      c.p_WC = in.points[v];
      c.n_W = swap ? Vector3(-in.normal) : in.normal;
      c.mu = assembly.Friction(in.part_a, in.part_b);
      c.feature = ContactFeature::kInterface;
      c.index_a = k;
      c.index_b = v;
      c.patch = patches;
      contacts.push_back(c);
    }
    ++patches;
  }
}

// Part pairs whose boxes touch, pruned by a sweep over the boxes sorted by
// their low x; sorted by (i, j), so that they are visited in that order
// whatever the sweep: deterministic. Pairs of two fixed parts are left out.
std::vector<std::pair<int, int>> CandidatePairs(const Assembly& assembly,
                                                const Configuration& config,
                                                const std::vector<Box3>& boxes, double tol) {
  std::vector<int> order;
  for (int i = 0; i < assembly.num_parts(); ++i)
    if (config.present[i]) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    return boxes[x].first.x() < boxes[y].first.x() ||
           (boxes[x].first.x() == boxes[y].first.x() && x < y);
  });
  std::vector<std::pair<int, int>> pairs;
  for (size_t oi = 0; oi < order.size(); ++oi) {
    const int i = order[oi];
    for (size_t oj = oi + 1; oj < order.size(); ++oj) {
      const int j = order[oj];
      if (boxes[j].first.x() > boxes[i].second.x() + tol) break;
      if (assembly.part(i).fixed && assembly.part(j).fixed) continue;
      if (!BoxesTouch3(boxes[i], boxes[j], tol)) continue;
      pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// The contacts of one pair (i, j). The movable part of a movable–fixed pair
// is made part a, so that "the force on a" is the force on the part that
// might move.
// The polyhedron contacts of parts a and b, from the cache when neither has
// moved since it last computed them.
const std::vector<PolyhedronContactPoint>& PolyhedronPair(const Assembly& assembly,
                                                          const PlacedParts& placed, int a, int b,
                                                          double tol, double angle_tol,
                                                          PairContactCache::Impl& cache) {
  const std::uint64_t key = (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
  auto [it, added] = cache.pairs.try_emplace(key);
  PairContactCache::Impl::Entry& e = it->second;
  const auto same = [](const Eigen::Isometry3d& x, const Eigen::Isometry3d& y) {
    return std::equal(x.data(), x.data() + 16, y.data());
  };
  if (!added && same(e.X_a, placed.X[a]) && same(e.X_b, placed.X[b])) {
    ++cache.hits;
    return e.points;
  }
  e.X_a = placed.X[a];
  e.X_b = placed.X[b];
  e.points = FindPolyhedronContacts(*assembly.part(a).polyhedron, placed.X[a],
                                    *assembly.part(b).polyhedron, placed.X[b], tol, angle_tol,
                                    tol + assembly.overlap_depth());
  return e.points;
}

void PairContacts(const Assembly& assembly, const PlacedParts& placed, int i, int j, double tol,
                  double angle_tol, std::vector<Contact>& contacts, int& patches,
                  PairContactCache::Impl* cache) {
  const double mu = assembly.Friction(i, j);
  // The movable part of a movable–fixed pair is a, else the lower index. The
  // points of two movable parts are computed from the side of the one whose
  // box's low corner comes first (x, then y, then z), and turned back: the
  // same points to the last bit however the parts are numbered (a permuted
  // file), in the usual orientation.
  const auto first = [&](int x, int y) {
    const Vector3& p = placed.boxes[x].first;
    const Vector3& q = placed.boxes[y].first;
    return std::make_tuple(p.x(), p.y(), p.z(), x) < std::make_tuple(q.x(), q.y(), q.z(), y);
  };
  const bool swap = assembly.part(i).fixed;
  const bool turn = !swap && !assembly.part(j).fixed && first(j, i);
  const int a = swap || turn ? j : i, b = swap || turn ? i : j;
  const size_t first_new = contacts.size();
  // Turned back to a = i (the lower index) where computed from j's side.
  const auto orient = [&] {
    if (turn)
      for (size_t k = first_new; k < contacts.size(); ++k)
        contacts[k] = FlippedContact(contacts[k]);
  };
  if (!assembly.is_3d()) {
    DetectPairContacts(placed.polys[a], placed.polys[b], a, b, mu, tol, angle_tol, contacts);
    orient();
    return;
  }
  const size_t before = contacts.size();
  std::vector<PolyhedronContactPoint> computed;
  if (!cache)
    computed = FindPolyhedronContacts(*assembly.part(a).polyhedron, placed.X[a],
                                      *assembly.part(b).polyhedron, placed.X[b], tol, angle_tol,
                                      tol + assembly.overlap_depth());
  for (const PolyhedronContactPoint& p :
       cache ? PolyhedronPair(assembly, placed, a, b, tol, angle_tol, *cache) : computed) {
    Contact c;
    c.part_a = a;
    c.part_b = b;
    c.p_WC = p.p_W;
    c.n_W = p.n_W;
    c.gap = p.gap;
    c.mu = mu;
    c.feature = FeatureOf(p.kind);
    c.index_a = p.feature_a;
    c.index_b = p.feature_b;
    c.patch = patches + p.patch;
    contacts.push_back(c);
  }
  orient();
  int most = -1;
  for (size_t k = before; k < contacts.size(); ++k) most = std::max(most, contacts[k].patch);
  if (most >= 0) patches = most + 1;
}

// Corner touches and flush joints (docs/contacts.md): one normal, or the
// flush ones the configuration supports, where a corner touches a corner.
void CornerRule(const Assembly& assembly, const PlacedParts& placed, double tol, double angle_tol,
                std::vector<Contact>& contacts) {
  const double cos_tol = std::cos(angle_tol);
  const bool is3 = assembly.is_3d();
  CornerQueries queries;
  queries.has_face = [&](int part, const Vector3& p_W, const Vector3& m_W) {
    if (is3)
      return PolyhedronHasFace(*assembly.part(part).polyhedron, placed.X[part], p_W, m_W, tol,
                               cos_tol);
    return PolygonHasEdge(placed.polys[part], p_W.head<2>(), m_W.head<2>(), tol, cos_tol);
  };
  queries.on_side = [&](int part, const Vector3& p_W, const Vector3& m_W) {
    if (is3)
      return PolyhedronOnSide(*assembly.part(part).polyhedron, placed.X[part], p_W, m_W, tol,
                              angle_tol);
    return PolygonOnSide(placed.polys[part], p_W.head<2>(), m_W.head<2>(), tol, angle_tol);
  };
  ApplyCornerRule(contacts, queries, assembly.gravity(), tol, angle_tol);
}

// Fixtures: frictionless contacts with the fixed world, moving with their part.
void FixtureContacts(const Assembly& assembly, const Configuration& config,
                     std::vector<Contact>& contacts, int& patches) {
  const auto& fixtures = assembly.fixtures();
  for (int f = 0; f < static_cast<int>(fixtures.size()); ++f) {
    const Fixture& fx = fixtures[f];
    if (!config.present[fx.part] || assembly.part(fx.part).fixed) continue;
    const Pose& pose = config.poses[fx.part];
    Contact c;
    c.part_a = fx.part;
    c.part_b = kWorld;
    c.p_WC = pose.Apply(fx.point, assembly.part(fx.part).centroid);
    c.n_W = pose.rotation * fx.normal;
    c.mu = 0;
    c.feature = ContactFeature::kFixture;
    c.index_a = f;
    if (assembly.is_3d()) c.patch = patches++;
    contacts.push_back(c);
  }
}

}  // namespace

std::vector<Contact> DetectContacts(const Assembly& assembly, const Configuration& config,
                                    double tol, double angle_tol, ContactStats* stats,
                                    PairContactCache* cache) {
  const PlacedParts placed = PlaceParts(assembly, config);
  PairContactCache::Impl* pair_cache = cache ? &cache->impl() : nullptr;
  if (pair_cache && (pair_cache->assembly != &assembly || pair_cache->tol != tol ||
                     pair_cache->angle_tol != angle_tol)) {
    pair_cache->pairs.clear();
    pair_cache->assembly = &assembly;
    pair_cache->tol = tol;
    pair_cache->angle_tol = angle_tol;
  }
  ContactStats local;
  std::vector<Contact> contacts;
  int patches = 0;
  if (assembly.has_interfaces()) {
    InterfaceContacts(assembly, config, contacts, patches, local);
  } else {
    for (const auto& [i, j] : CandidatePairs(assembly, config, placed.boxes, tol)) {
      ++local.pairs_tested;
      const size_t before = contacts.size();
      PairContacts(assembly, placed, i, j, tol, angle_tol, contacts, patches, pair_cache);
      if (contacts.size() > before) ++local.pairs_touching;
    }
  }
  CornerRule(assembly, placed, tol, angle_tol, contacts);
  FixtureContacts(assembly, config, contacts, patches);
  if (stats) *stats = local;
  return contacts;
}

}  // namespace cairn

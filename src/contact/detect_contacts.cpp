#include "cairn/contact/detect_contacts.h"

#include <algorithm>
#include <cmath>

namespace cairn {

const char* to_string(ContactFeature feature) {
  switch (feature) {
    case ContactFeature::kVertexOfAOnEdgeOfB:
      return "vertex-edge";
    case ContactFeature::kVertexOfBOnEdgeOfA:
      return "edge-vertex";
    case ContactFeature::kFixture:
      return "fixture";
  }
  return "unknown";
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
      c.p_WC = vp[k];
      c.n_W = vertex_of_a ? n_e : Vector2(-n_e);
      c.gap = s;
      c.mu = mu;
      c.feature =
          vertex_of_a ? ContactFeature::kVertexOfAOnEdgeOfB : ContactFeature::kVertexOfBOnEdgeOfA;
      c.vertex = k;
      c.edge = e;
      out.push_back(c);
    }
  }
}

bool BoxesTouch(const std::pair<Vector2, Vector2>& x, const std::pair<Vector2, Vector2>& y,
                double tol) {
  return x.first.x() <= y.second.x() + tol && y.first.x() <= x.second.x() + tol &&
         x.first.y() <= y.second.y() + tol && y.first.y() <= x.second.y() + tol;
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
          out[k].n_W.dot(out[c].n_W) >= std::cos(angle_tol) - 1e-15) {
        duplicate = true;
        break;
      }
    }
    if (!duplicate) out[kept++] = out[c];
  }
  out.resize(kept);
}

std::vector<Contact> DetectContacts(const Assembly& assembly, const Configuration& config,
                                    double tol, double angle_tol, ContactStats* stats) {
  const int n = assembly.num_parts();
  std::vector<Polygon> polys(n);
  std::vector<std::pair<Vector2, Vector2>> boxes(n);
  for (int i = 0; i < n; ++i) {
    if (!config.present[i]) continue;
    polys[i] = config.WorldPolygon(assembly, i);
    boxes[i] = BoundingBox(polys[i]);
  }
  ContactStats local;
  std::vector<Contact> contacts;
  // Part pairs. The movable part of a movable–fixed pair is made part a, so
  // that "the force on a" is the force on the part that might move.
  for (int i = 0; i < n; ++i) {
    if (!config.present[i]) continue;
    for (int j = i + 1; j < n; ++j) {
      if (!config.present[j]) continue;
      const bool fi = assembly.part(i).fixed, fj = assembly.part(j).fixed;
      if (fi && fj) continue;
      if (!BoxesTouch(boxes[i], boxes[j], tol)) continue;
      ++local.pairs_tested;
      const size_t before = contacts.size();
      const double mu = assembly.Friction(i, j);
      if (fi) {
        DetectPairContacts(polys[j], polys[i], j, i, mu, tol, angle_tol, contacts);
      } else {
        DetectPairContacts(polys[i], polys[j], i, j, mu, tol, angle_tol, contacts);
      }
      if (contacts.size() > before) ++local.pairs_touching;
    }
  }
  // Fixtures: frictionless contacts with the fixed world, moving with their part.
  const auto& fixtures = assembly.fixtures();
  for (int f = 0; f < static_cast<int>(fixtures.size()); ++f) {
    const Fixture& fx = fixtures[f];
    if (!config.present[fx.part] || assembly.part(fx.part).fixed) continue;
    const Pose2& pose = config.poses[fx.part];
    Contact c;
    c.part_a = fx.part;
    c.part_b = kWorld;
    c.p_WC = pose.Apply(fx.point, assembly.part(fx.part).centroid);
    const double cs = std::cos(pose.rotation), sn = std::sin(pose.rotation);
    c.n_W =
        Vector2(cs * fx.normal.x() - sn * fx.normal.y(), sn * fx.normal.x() + cs * fx.normal.y());
    c.mu = 0;
    c.feature = ContactFeature::kFixture;
    c.vertex = f;
    contacts.push_back(c);
  }
  if (stats) *stats = local;
  return contacts;
}

}  // namespace cairn

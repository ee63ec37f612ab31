// HullContactSubset: planar patches reduced to their hull vertices (the
// argument for exactness is in include/cairn/contact/contact_reduction.h).

#include "cairn/contact/contact_reduction.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "cairn/core/check.h"

namespace cairn {

namespace {

// One patch being collected: its first point's plane, μ and gap, and members.
struct Patch {
  Vector3 n_W;
  Vector3 p_W;  // a point of the plane
  double mu;
  double gap;
  std::vector<int> members;
};

// z-component of (a − o) × (b − o) in the patch plane (length²).
double Cross(const Vector2& o, const Vector2& a, const Vector2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// The hull vertices of one patch (Andrew's monotone chain in the plane spanned
// by TangentBasis(n)): turns of at most `eps` (length²) are not vertices, so
// points on hull edges and repeated points are dropped. Appends to `keep`.
void HullVertices(const std::vector<Contact>& contacts, const Patch& patch,
                  std::vector<int>* keep) {
  const auto [t1, t2] = TangentBasis(patch.n_W);
  struct Point {
    Vector2 uv;
    int index;
  };
  std::vector<Point> pts;
  pts.reserve(patch.members.size());
  Vector2 lo = Vector2::Constant(1e300), hi = Vector2::Constant(-1e300);
  for (int i : patch.members) {
    const Vector3 r = contacts[i].p_WC - patch.p_W;
    const Vector2 uv(r.dot(t1), r.dot(t2));
    lo = lo.cwiseMin(uv), hi = hi.cwiseMax(uv);
    pts.push_back({uv, i});
  }
  const double diameter = (hi - lo).norm();
  if (!(diameter > 0)) {  // one point, repeated: keep the first
    keep->push_back(patch.members.front());
    return;
  }
  const double eps = kHullRoundoff * diameter * diameter;
  std::sort(pts.begin(), pts.end(), [](const Point& a, const Point& b) {
    if (a.uv.x() != b.uv.x()) return a.uv.x() < b.uv.x();
    if (a.uv.y() != b.uv.y()) return a.uv.y() < b.uv.y();
    return a.index < b.index;
  });
  // Lower then upper chain; a point that does not turn left by more than eps
  // is popped.
  std::vector<Point> hull;
  hull.reserve(2 * pts.size());
  for (int pass = 0; pass < 2; ++pass) {
    const size_t base = hull.size();
    for (size_t s = 0; s < pts.size(); ++s) {
      const Point& p = pass == 0 ? pts[s] : pts[pts.size() - 1 - s];
      while (hull.size() >= base + 2 &&
             Cross(hull[hull.size() - 2].uv, hull.back().uv, p.uv) <= eps)
        hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();  // the last point starts the other chain
  }
  // All points collinear (or equal): the chains are the two extremes.
  for (const Point& p : hull) keep->push_back(p.index);
}

}  // namespace

std::vector<int> HullContactSubset(const std::vector<Contact>& contacts,
                                   const ContactReductionTolerances& tolerances) {
  CAIRN_THROW_UNLESS(tolerances.angle >= 0 && tolerances.length >= 0 && tolerances.gap >= 0,
                     "HullContactSubset: tolerances must be ≥ 0 (angle "
                         << tolerances.angle << " rad, length " << tolerances.length << ", gap "
                         << tolerances.gap << ")");
  const double cos_angle = std::cos(tolerances.angle);

  // Group the contacts into patches, in order: each joins the first patch of
  // its part pair whose plane, μ and gap it matches.
  std::vector<Patch> patches;
  std::map<std::pair<int, int>, std::vector<int>> of_pair;  // (a, b) → patch ids
  for (int i = 0; i < static_cast<int>(contacts.size()); ++i) {
    const Contact& c = contacts[i];
    std::vector<int>& ids = of_pair[{c.part_a, c.part_b}];
    int found = -1;
    for (int id : ids) {
      const Patch& p = patches[id];
      if (c.mu == p.mu && c.n_W.dot(p.n_W) >= cos_angle &&
          std::abs(p.n_W.dot(c.p_WC - p.p_W)) <= tolerances.length &&
          std::abs(c.gap - p.gap) <= tolerances.gap) {
        found = id;
        break;
      }
    }
    if (found < 0) {
      found = static_cast<int>(patches.size());
      patches.push_back({c.n_W, c.p_WC, c.mu, c.gap, {}});
      ids.push_back(found);
    }
    patches[found].members.push_back(i);
  }

  // Keep the hull vertices of every patch of three points or more.
  std::vector<int> keep;
  keep.reserve(contacts.size());
  for (const Patch& p : patches) {
    if (p.members.size() <= 2) {
      keep.insert(keep.end(), p.members.begin(), p.members.end());
    } else {
      HullVertices(contacts, p, &keep);
    }
  }
  std::sort(keep.begin(), keep.end());
  return keep;
}

}  // namespace cairn

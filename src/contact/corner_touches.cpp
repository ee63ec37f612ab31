// The corner rule (docs/contacts.md, "Corner touches and flush joints").
//
// Two parts that touch at a point with one normal n (a vertex on the inside
// of a face, or a face patch) forbid exactly the relative velocities v with
// n·v < 0 there. Where a corner of one touches a corner (or an edge) of the
// other, the touch has a *set* N of normals: the unit vectors n such that
// the plane through the point normal to n separates the two parts' local
// cones (the candidate normals the detectors find are the face normals in
// N). The exact first-order non-penetration condition is a disjunction,
//
//     v is admissible  ⇔  n·v ≥ 0 for SOME n ∈ N,
//
// so the forbidden set F = {v : n·v < 0 for every n ∈ N} is a convex cone
// narrower than a half-space. One LCP row n·v ≥ 0 forbids a whole half-space
// (containing F); keeping every candidate normal forbids the union of their
// half-spaces, so a part can slide along neither face at the corner. The rule
// picks rows as follows, for each touch (one pair, one point) with two or
// more distinct normals:
//
//  0. Inner corners: if some candidate normal does not separate the two parts
//     locally (a block in the inner corner of a non-convex part: the floor's
//     normal does not separate the block from the wall above the corner), N
//     is empty or smaller than the candidates, and the candidates are
//     constraints that hold together: every one is kept.
//  1. Flush normals: n is flush at p when both parts have a face through p in
//     the plane normal to n (a's with outward normal −n, b's with +n): a
//     face–face (2-D: edge–edge) contact of zero or positive extent. Sliding
//     along a flush plane keeps each part on its own side of it, so a touch
//     with flush normals keeps only those; the normals of faces that merely
//     meet the flush plane at the corner are dropped (a drawer, a brick or a
//     Jenga block slides over a flush joint).
//  2. No flush normal (a wedge's apex on a block's corner): every candidate is
//     kept (conservative; the touch can still carry a load in each).
//  3. Two or more flush normals (a corner against a complementary corner:
//     two box corners meeting edge to edge or tip to tip): the geometry of
//     the pair is symmetric, and the configuration decides. A flush normal n
//     is *continued* when the plane through p normal to n carries another
//     contact of a or of b with the same orientation (into a along n, or into
//     b along −n) elsewhere in the configuration: the flush surface goes on
//     past the joint (the support and the ledge of a slide across a joint,
//     the second block under a load resting on a vertex shared by three
//     parts). When exactly one is continued, it is kept.
//  4. Otherwise the candidates are the continued flush normals (two or more:
//     the touch is where continued surfaces meet, each carrying the load on
//     its own) or, if none is continued, all the flush normals. When the
//     weight of a pushes it into their forbidden cone (g·n < 0 for every
//     candidate n: a tip standing on a tip), the one(s) most opposed to
//     gravity are kept, so the load rests on the touch; otherwise none is
//     kept: the touch carries no load, and a may leave the corner along
//     either face (the motion into F is the only one given up, and it
//     overlaps at once, which the next configuration's detection sees).
//     Without gravity, every candidate is kept.

#include "corner_touches.h"

#include <algorithm>
#include <cmath>

namespace cairn {

namespace {

// The contacts the rule applies to: found between two parts (not fixtures,
// not given interfaces).
bool Found(const Contact& c) {
  return c.feature != ContactFeature::kFixture && c.feature != ContactFeature::kInterface &&
         c.part_b >= 0;
}

// One touch: the contacts of one pair at one point, and its distinct normals.
struct Touch {
  int a = -1, b = -1;
  Vector3 p_W{0, 0, 0};
  std::vector<Vector3> normals;  // distinct normals (from b into a)
  std::vector<bool> flush;       // by normal
  std::vector<bool> keep;        // by normal
};

}  // namespace

namespace {

// The corner rule over one set of contacts: the touches they form, then the
// rules in order (docs/contacts.md).
class CornerRule {
 public:
  CornerRule(std::vector<Contact>& contacts, const CornerQueries& queries, double tol,
             double angle_tol)
      : contacts_(contacts),
        queries_(queries),
        tol_(tol),
        angle_tol_(angle_tol),
        cos_tol_(std::cos(angle_tol)) {}

  bool Same(const Vector3& x, const Vector3& y) const { return x.dot(y) >= cos_tol_; }

  // Group the found contacts into touches: same pair, points within tol.
  void GroupTouches() {
    std::vector<Contact>& contacts = contacts_;
    const double tol = tol_;
    const auto same = [this](const Vector3& x, const Vector3& y) { return Same(x, y); };
    std::vector<Touch>& touches = touches_;
    std::vector<int>& touch_of = touch_of_;
    touch_of.assign(contacts.size(), -1);
    // Group the found contacts into touches: same pair, points within tol.
    for (int k = 0; k < static_cast<int>(contacts.size()); ++k) {
      const Contact& c = contacts[k];
      if (!Found(c)) continue;
      // A pair's contacts are contiguous: look back over its touches only.
      int t = -1;
      for (int j = static_cast<int>(touches.size()) - 1; j >= 0 && t < 0; --j) {
        if (touches[j].a != c.part_a || touches[j].b != c.part_b) break;
        if ((touches[j].p_W - c.p_WC).norm() <= tol) t = j;
      }
      if (t < 0) {
        touches.push_back({});
        t = static_cast<int>(touches.size()) - 1;
        touches[t].a = c.part_a;
        touches[t].b = c.part_b;
        touches[t].p_W = c.p_WC;
      }
      touch_of[k] = t;
      Touch& touch = touches[t];
      const bool known = std::any_of(touch.normals.begin(), touch.normals.end(),
                                     [&](const Vector3& n) { return same(n, c.n_W); });
      if (!known) touch.normals.push_back(c.n_W);
    }
  }

  // Rules 0-2, per touch: every normal when one of them does not separate
  // the parts (an inner corner); else flush normals only, or every normal
  // when none is flush. The touches left with two flush normals or more are
  // ambiguous.
  void FlushNormals() {
    const CornerQueries& queries = queries_;
    std::vector<Touch>& touches = touches_;
    std::vector<int>& ambiguous = ambiguous_;
    for (int t = 0; t < static_cast<int>(touches.size()); ++t) {
      Touch& touch = touches[t];
      const int m = static_cast<int>(touch.normals.size());
      touch.keep.assign(m, true);
      touch.flush.assign(m, false);
      if (m < 2) continue;
      bool separating = true;
      for (int i = 0; i < m && separating; ++i) {
        const Vector3& n = touch.normals[i];
        separating =
            queries.on_side(touch.a, touch.p_W, n) && queries.on_side(touch.b, touch.p_W, -n);
      }
      if (!separating) continue;
      int flush = 0;
      for (int i = 0; i < m; ++i) {
        const Vector3& n = touch.normals[i];
        touch.flush[i] =
            queries.has_face(touch.a, touch.p_W, -n) && queries.has_face(touch.b, touch.p_W, n);
        flush += touch.flush[i];
      }
      if (flush == 0) continue;
      touch.keep = touch.flush;
      if (flush >= 2) ambiguous.push_back(t);
    }
  }

  // Rule 3: a flush normal is continued when its plane carries another
  // contact of a or b with the same orientation. Every candidate counts (two
  // ambiguous touches of different pairs under one load support each other),
  // except the touch itself and the other ambiguous touches of the same pair
  // (the two ends of one edge-to-edge touch in 3-D do not support each other).
  bool Continues(const Touch& touch, const Vector3& n) const {
    for (int k = 0; k < static_cast<int>(contacts_.size()); ++k) {
      const Contact& c = contacts_[k];
      const int t = touch_of_[k];
      if (t >= 0 && (&touches_[t] == &touch ||
                     (is_ambiguous_[t] && touches_[t].a == touch.a && touches_[t].b == touch.b)))
        continue;
      if (std::abs(n.dot(c.p_WC - touch.p_W)) > tol_) continue;
      const bool into_a =
          (c.part_a == touch.a && Same(c.n_W, n)) || (c.part_b == touch.a && Same(c.n_W, -n));
      const bool into_b =
          (c.part_a == touch.b && Same(c.n_W, -n)) || (c.part_b == touch.b && Same(c.n_W, n));
      if (into_a || into_b) return true;
    }
    return false;
  }

  // Rules 3 and 4 for every ambiguous touch: the continued flush normals (or
  // all flush ones if none is); among several, the one(s) most opposed to
  // gravity if the weight pushes a into them, none otherwise.
  void ResolveAmbiguous(const Vector3& gravity) {
    is_ambiguous_.assign(touches_.size(), false);
    for (int t : ambiguous_) is_ambiguous_[t] = true;
    const Vector3 g_hat = gravity.norm() > 0 ? Vector3(gravity.normalized()) : Vector3::Zero();
    const double sin_tol = std::sin(angle_tol_);
    std::vector<std::vector<bool>> resolved(touches_.size());
    for (int t : ambiguous_) {
      const Touch& touch = touches_[t];
      const int m = static_cast<int>(touch.normals.size());
      std::vector<bool> cand(m, false);
      int continued = 0;
      for (int i = 0; i < m; ++i)
        if (touch.flush[i] && Continues(touch, touch.normals[i])) cand[i] = true, ++continued;
      if (continued == 0) cand = touch.flush;
      std::vector<bool> keep = cand;
      if ((continued == 0 || continued >= 2) && g_hat.norm() > 0) {
        bool into = true;
        double lowest = 1;
        for (int i = 0; i < m; ++i)
          if (cand[i]) {
            const double gn = g_hat.dot(touch.normals[i]);
            into = into && gn < -sin_tol;
            lowest = std::min(lowest, gn);
          }
        for (int i = 0; i < m; ++i)
          keep[i] = into && cand[i] && g_hat.dot(touch.normals[i]) <= lowest + sin_tol;
      }
      resolved[t] = keep;
    }
    for (int t : ambiguous_) touches_[t].keep = resolved[t];
  }

  // Drop the contacts whose normal is not kept; how many were.
  int DropUnkept() {
    std::vector<Contact>& contacts = contacts_;
    const auto same = [this](const Vector3& x, const Vector3& y) { return Same(x, y); };
    const std::vector<Touch>& touches = touches_;
    const std::vector<int>& touch_of = touch_of_;
    size_t kept = 0;
    for (size_t k = 0; k < contacts.size(); ++k) {
      bool stay = true;
      if (touch_of[k] >= 0) {
        const Touch& touch = touches[touch_of[k]];
        for (size_t i = 0; i < touch.normals.size(); ++i)
          if (same(touch.normals[i], contacts[k].n_W)) {
            stay = touch.keep[i];
            break;
          }
      }
      if (stay) contacts[kept++] = contacts[k];
    }
    const int removed = static_cast<int>(contacts.size() - kept);
    contacts.resize(kept);
    return removed;
  }

 private:
  std::vector<Contact>& contacts_;
  const CornerQueries& queries_;
  const double tol_, angle_tol_, cos_tol_;
  std::vector<Touch> touches_;
  std::vector<int> touch_of_;  // by contact: its touch, or −1
  std::vector<int> ambiguous_;
  std::vector<bool> is_ambiguous_;
};

}  // namespace

int ApplyCornerRule(std::vector<Contact>& contacts, const CornerQueries& queries,
                    const Vector3& gravity, double tol, double angle_tol) {
  CornerRule rule(contacts, queries, tol, angle_tol);
  rule.GroupTouches();
  rule.FlushNormals();
  rule.ResolveAmbiguous(gravity);
  return rule.DropUnkept();
}

}  // namespace cairn

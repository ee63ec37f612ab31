#pragma once
/// @file
/// Contact detection between the parts of one configuration (2-D).
///
/// Two polygons touch where a vertex of one lies on an edge of the other. Every
/// touching pair of features is found by testing each vertex of a against each
/// edge of b and each vertex of b against each edge of a:
///  - a vertex v touches edge e when its distance to e is ≤ tol, it projects
///    onto e (within tol of its extent), v is a convex vertex of its polygon,
///    and both edges at v leave v on the outer side of e (within the angle
///    tolerance): the polygon's material at v lies outside e, so the contact
///    can push;
///  - two edges that touch along a segment (anti-parallel within tolerance,
///    overlapping extents) are found as the two ends of their overlap, each of
///    which is a vertex of one edge lying on the other: so an edge–edge contact
///    gives its two end points, with the edge's normal, as Baraff's and the
///    paper's models want;
///  - duplicates (the same point with the same normal, e.g. where two vertices
///    coincide) are merged.
/// A vertex touching a vertex gives one candidate contact per edge it lies on
/// (DetectPairContacts returns them all). DetectContacts then applies the
/// *corner rule* (docs/contacts.md) to every touch with several normals,
/// because the exact condition there (the motion is admissible if SOME
/// line/plane through the point separates the two parts) is a disjunction
/// one LCP row cannot express, and keeping every normal forbids sliding along
/// either face:
///  0. if some candidate does not separate the two parts locally (a block in
///     an inner corner), the candidates hold together: all are kept;
///  1. a *flush* normal (both parts have a face through the point in the
///     plane normal to it: a face–face contact of zero or positive length) is
///     kept, and the other normals of the touch are dropped: a part slides
///     over a flush joint;
///  2. with no flush normal every candidate is kept (a wedge's apex on a
///     corner);
///  3. with several flush normals (complementary corners), the one whose plane
///     carries another contact of either part with the same orientation (the
///     flush surface continues: a block slid from its support onto a ledge
///     flush with it; a load on a vertex shared by three parts) is kept;
///  4. otherwise, among the continued ones or else all flush ones, those most
///     opposed to gravity are kept if the weight pushes into the forbidden
///     cone (a tip on a tip), none if it does not (a lone corner-to-corner
///     touch: the part may slide off along either face), all without gravity.
/// The same rule applies to 3-D contacts (faces for edges). "The same point"
/// and "on the plane" use `tol`, "the same normal" `angle_tol`.
/// Contacts between two fixed parts, and with absent parts, are not made.
/// Fixtures become contacts with the fixed world (frictionless), and are
/// never changed by the corner rule, nor are given interfaces.

#include <memory>
#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/geometry/assembly.h"

namespace cairn {

/// Statistics of one detection pass.
struct ContactStats {
  int pairs_tested = 0;    ///< part pairs whose bounding boxes overlapped
  int pairs_touching = 0;  ///< part pairs with at least one contact
};

/// The contacts of each 3-D part pair at the placements they were last found
/// at, kept between calls of DetectContacts on one assembly with the same
/// tolerances: along a path, where one part moves, only the pairs with a
/// moved part are computed again (the Jenga pull: 3 of ~150 pairs a tick).
/// A pair is reused only when both placements are bitwise those of the last
/// time, so the contacts are exactly those computing them again would give;
/// another assembly or other tolerances empty the cache.
/// Not thread-safe: one cache per sequence of configurations (a workspace).
class PairContactCache {
 public:
  PairContactCache();
  ~PairContactCache();
  PairContactCache(PairContactCache&&) noexcept;
  PairContactCache& operator=(PairContactCache&&) noexcept;
  /// Pairs answered from the cache, over its life.
  int hits() const;
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// All contacts of `config`, after the corner rule, in a deterministic order
/// (part pairs in (i, j) order, then fixtures).
/// `tol` is the contact distance tolerance (length), `angle_tol` the angle
/// tolerance (rad). Parts that overlap by up to the assembly's overlap depth
/// more (Assembly::overlap_depth) touch on the overlap's mid-surface
/// (FindPolyhedronContacts). `cache` (optional): see PairContactCache; the
/// answer is the same with or without it.
std::vector<Contact> DetectContacts(const Assembly& assembly, const Configuration& config,
                                    double tol, double angle_tol, ContactStats* stats = nullptr,
                                    PairContactCache* cache = nullptr);

/// The candidate contacts between the polygons of parts i and j (both present,
/// not both fixed), appended to `out`. Part i is `a`, part j is `b`. The
/// corner rule is not applied (it needs the whole configuration).
void DetectPairContacts(const Polygon& poly_i, const Polygon& poly_j, int i, int j, double mu,
                        double tol, double angle_tol, std::vector<Contact>& out);

}  // namespace cairn

#pragma once
/// @file
/// Contact points between parts, in 2-D and 3-D.
///
/// Convention (docs/notation.md): a contact joins part `a` and part `b`
/// (b = kWorld for a fixture). Its unit normal n_W points from b into a: a
/// compressive contact force f ≥ 0 acts on a as +f n_W and on b as −f n_W at
/// the point p_WC. 2-D contacts lie in the plane z = 0 with n_W.z() = 0; their
/// tangent is t_W = ẑ × n_W = (−n_y, n_x, 0), and a positive friction force
/// acts on a along +t_W. In 3-D the tangent plane is spanned by
/// TangentBasis(n_W).

#include <string>
#include <utility>
#include <vector>

#include "cairn/core/types.h"

namespace cairn {

/// Index of "the fixed world" in Contact::part_b (fixtures).
inline constexpr int kWorld = -1;

/// Which boundary features made the contact.
enum class ContactFeature {
  kVertexOfAOnEdgeOfB,  ///< 2-D: vertex `index_a` of a touches edge `index_b` of b (normal:
                        ///< b's edge normal)
  kVertexOfBOnEdgeOfA,  ///< 2-D: vertex `index_b` of b touches edge `index_a` of a (normal:
                        ///< −a's edge normal)
  kFixture,             ///< a fixel (index `index_a` into Assembly::fixtures()) pushing on a
  kFaceFace,    ///< 3-D: a vertex of the intersection of face `index_a` of a and `index_b` of b
  kVertexFace,  ///< 3-D: vertex `index_a` of a on face `index_b` of b
  kFaceVertex,  ///< 3-D: vertex `index_b` of b on face `index_a` of a
  kEdgeFace,    ///< 3-D: an end of edge `index_a` of a lying on face `index_b` of b
  kFaceEdge,    ///< 3-D: an end of edge `index_b` of b lying on face `index_a` of a
  kEdgeEdge,    ///< 3-D: edge `index_a` of a crossing edge `index_b` of b
  kInterface,   ///< 3-D: vertex `index_b` of given interface `index_a` (Assembly::interfaces())
};

/// "vertex-edge", "edge-vertex", "fixture", "face-face", "vertex-face",
/// "face-vertex", "edge-face", "face-edge", "edge-edge", "interface".
const char* to_string(ContactFeature feature);

/// One contact point.
struct Contact {
  int part_a = -1;        ///< index of part a (always a part)
  int part_b = kWorld;    ///< index of part b, or kWorld
  Vector3 p_WC{0, 0, 0};  ///< contact point, world frame (length)
  Vector3 n_W{0, 1, 0};   ///< unit normal from b into a, world frame
  double gap = 0;         ///< signed distance along n_W (length; < 0: penetration within tolerance)
  double mu = 0;          ///< Coulomb coefficient of the pair
  ContactFeature feature = ContactFeature::kVertexOfAOnEdgeOfB;
  int index_a = -1;  ///< the feature of a (vertex, edge, face; see `feature`), or fixture index
  int index_b = -1;  ///< the feature of b (see `feature`); -1 for fixtures
  /// 3-D: the contact polygon (patch) this point belongs to; the points of one
  /// face–face patch share it, every other point has its own. Numbered from 0
  /// over the whole configuration. 2-D: -1.
  int patch = -1;

  /// 2-D: t_W = ẑ × n_W, the positive friction direction on a.
  Vector3 t_W() const { return {-n_W.y(), n_W.x(), 0.0}; }
};

/// The contact `c` seen from its other side: a and b, their features and the
/// normal swapped (the same contact: its force on the new a is minus the old
/// one's on the old a).
Contact FlippedContact(Contact c);

/// An orthonormal basis (t1, t2) of the plane normal to the unit vector n, with
/// t1 × t2 = n, chosen by a fixed rule (deterministic, continuous wherever
/// n is not parallel to the world axis the rule switches on): t1 = the
/// normalised projection of the world x axis, or of the y axis when n is
/// within 45° of x.
std::pair<Vector3, Vector3> TangentBasis(const Vector3& n);

/// The D friction directions of a contact: the unit vectors
/// d_k = cos(2πk/D) t1 + sin(2πk/D) t2, k = 0..D−1, of TangentBasis(n) in 3-D,
/// and (+t_W, −t_W) in 2-D (D = 2). The friction force Σ β_k d_k with
/// β ≥ 0, Σ β_k ≤ μ f_n spans the D-gon inscribed in the Coulomb cone
/// (Stewart and Trinkle 1996): exact along each d_k, cos(π/D) of the cone
/// half-way between two of them.
std::vector<Vector3> FrictionDirections(const Contact& c, int dimension, int D);

}  // namespace cairn

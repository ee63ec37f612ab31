#pragma once
/// @file
/// Contact points between parts (2-D).
///
/// Convention (docs/notation.md): a contact joins part `a` and part `b`
/// (b = kWorld for a fixture). Its unit normal n_W points from b into a: a
/// compressive contact force f ≥ 0 acts on a as +f n_W and on b as −f n_W at
/// the point p_WC. The tangent is t_W = ẑ × n_W = (−n_y, n_x); a positive
/// friction force acts on a along +t_W.

#include <string>
#include <vector>

#include "cairn/core/types.h"

namespace cairn {

/// Index of "the fixed world" in Contact::part_b (fixtures).
inline constexpr int kWorld = -1;

/// Which boundary features made the contact.
enum class ContactFeature {
  kVertexOfAOnEdgeOfB,  ///< vertex `vertex` of a touches edge `edge` of b (normal: b's edge normal)
  kVertexOfBOnEdgeOfA,  ///< vertex `vertex` of b touches edge `edge` of a (normal: −a's edge
                        ///< normal)
  kFixture,             ///< a fixel (index `vertex` into Assembly::fixtures()) pushing on a
};

/// "vertex-edge", "edge-vertex", "fixture".
const char* to_string(ContactFeature feature);

/// One contact point.
struct Contact {
  int part_a = -1;      ///< index of part a (always a part)
  int part_b = kWorld;  ///< index of part b, or kWorld
  Vector2 p_WC{0, 0};   ///< contact point, world frame (length)
  Vector2 n_W{0, 1};    ///< unit normal from b into a, world frame
  double gap = 0;       ///< signed distance along n_W (length; < 0: penetration within tolerance)
  double mu = 0;        ///< Coulomb coefficient of the pair
  ContactFeature feature = ContactFeature::kVertexOfAOnEdgeOfB;
  int vertex = -1;  ///< vertex index (of a or b, see feature), or fixture index
  int edge = -1;    ///< edge index (of b or a, see feature); -1 for fixtures

  /// t_W = ẑ × n_W, the positive friction direction on a.
  Vector2 t_W() const { return {-n_W.y(), n_W.x()}; }
};

}  // namespace cairn

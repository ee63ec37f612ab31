#pragma once
// The corner rule of DetectContacts (docs/contacts.md): at a point where two
// parts touch with several normals (a corner touch), keep the normal(s) the
// local geometry and the rest of the configuration say the touch acts along.
// Private to the contact stage.

#include <functional>
#include <vector>

#include "cairn/contact/contact.h"

namespace cairn {

/// Whether part `part` has a face (2-D: an edge) that contains the point p_W
/// (within the length tolerance) and whose outward unit normal is m_W (within
/// the angle tolerance).
using HasFaceFn = std::function<bool(int part, const Vector3& p_W, const Vector3& m_W)>;

/// Whether part `part`'s material near the point p_W (on its boundary) lies
/// on the side m_W·(x − p_W) ≥ 0 of the plane through p_W normal to m_W
/// (within the tolerances): every face (2-D: edge) of the part that contains
/// p_W has all its vertices on that side, and (2-D) p_W is not a reflex
/// vertex. False is the safe answer when unsure.
using OnSideFn = std::function<bool(int part, const Vector3& p_W, const Vector3& m_W)>;

/// The geometric queries of the corner rule.
struct CornerQueries {
  HasFaceFn has_face;
  OnSideFn on_side;
};

/// Applies the corner rule to `contacts` (all found contacts of one
/// configuration), in place, keeping their order. Fixture and interface
/// contacts are never touched. `gravity` is the scene's gravity vector
/// (length/s², any magnitude; zero: no load direction), `tol` the length
/// tolerance (length), `angle_tol` the angle tolerance (rad). Returns the
/// number of contacts removed.
int ApplyCornerRule(std::vector<Contact>& contacts, const CornerQueries& queries,
                    const Vector3& gravity, double tol, double angle_tol);

}  // namespace cairn

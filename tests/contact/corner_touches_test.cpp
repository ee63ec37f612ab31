// The corner rule of DetectContacts (docs/contacts.md): which normals a
// touch keeps where a corner meets a corner, in 2-D and 3-D. Each case states
// the candidate normals the pair detectors find and the ones the rule keeps.
#include <gtest/gtest.h>

#include <cmath>

#include "cairn/contact/detect_contacts.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::Box;
using testing::Box3;

constexpr double kCornerTol = 1e-9;
constexpr double kCornerAngle = 1e-6;

std::vector<Contact> Detect(const Assembly& a) {
  return DetectContacts(a, Configuration::Assembled(a), kCornerTol, kCornerAngle);
}

// The contacts between the parts named x and y (either order).
std::vector<Contact> Between(const Assembly& a, const std::vector<Contact>& cs,
                             const std::string& x, const std::string& y) {
  const int i = a.FindPart(x), j = a.FindPart(y);
  std::vector<Contact> out;
  for (const Contact& c : cs)
    if ((c.part_a == i && c.part_b == j) || (c.part_a == j && c.part_b == i)) out.push_back(c);
  return out;
}

// The normal of c pointing into the part named `into`.
Vector3 NormalInto(const Assembly& a, const Contact& c, const std::string& into) {
  return c.part_a == a.FindPart(into) ? c.n_W : Vector3(-c.n_W);
}

bool Near(const Vector3& x, const Vector3& y) { return (x - y).norm() < 1e-9; }

AssemblyDef Def2(std::vector<PartDef> parts) {
  AssemblyDef def;
  def.gravity = Vector3(0, -1, 0);
  def.parts = std::move(parts);
  return def;
}

AssemblyDef Def3(std::vector<PartDef> parts) {
  AssemblyDef def;
  def.gravity = Vector3(0, 0, -1);
  def.parts = std::move(parts);
  return def;
}

// --- 2-D --------------------------------------------------------------------

// The flush joint: B rests on its support S and has slid right until
// its lower-right corner meets the upper-left corner of the fixed ledge L,
// across a gap; the tops of S and L are flush (y = 1). The pair B–L has the
// candidates up (L's top, B's bottom: flush) and −x (L's left face, B's right
// face: flush too, the corners are complementary). B's contacts with S lie on
// y = 1 with the same normal: the flush surface continues, so B–L keeps up
// only and B can slide on over the joint.
TEST(CornerRule, AFlushJointAcrossAGapKeepsOnlyTheFlushSurfacesNormal) {
  const Assembly a =
      Assembly::Create(Def2({Box("floor", -2, -1, 10, 0, true), Box("L", 4.5, 0, 9, 1, true),
                             Box("S", 0, 0, 4, 1), Box("B", 2.5, 1, 4.5, 2)}));
  const auto cs = Detect(a);
  const auto bl = Between(a, cs, "B", "L");
  ASSERT_EQ(bl.size(), 1u);
  EXPECT_TRUE(Near(bl[0].p_WC, Vector3(4.5, 1, 0)));
  EXPECT_TRUE(Near(NormalInto(a, bl[0], "B"), Vector3(0, 1, 0)));
  // The pair detector alone still finds both candidates.
  std::vector<Contact> raw;
  DetectPairContacts(a.part(a.FindPart("B")).polygon, a.part(a.FindPart("L")).polygon, 0, 1, 0,
                     kCornerTol, kCornerAngle, raw);
  EXPECT_EQ(raw.size(), 2u);
  // B–S: the two ends of the overlap x ∈ [2.5, 4], upwards.
  const auto bs = Between(a, cs, "B", "S");
  ASSERT_EQ(bs.size(), 2u);
  for (const Contact& c : bs) EXPECT_TRUE(Near(NormalInto(a, c, "B"), Vector3(0, 1, 0)));
}

// Without the gap the joint is a vertex shared by three parts (B's corner,
// S's and L's). B–S gives only up there (S's side face is parallel to B's,
// not opposed). For B–L both flush normals are continued: up by B's contact
// with S on y = 1, −x by S's contact with L on x = 4 (S and B are flush on
// the left of that plane). Neither is needed: B–S holds B up at the joint.
// Gravity (−y) is not inside {v_x > 0, v_y < 0}, so B–L keeps no normal, and
// S still pushes on L horizontally along their common face.
TEST(CornerRule, AFlushJointWithoutAGapIsAVertexOfThreeParts) {
  const Assembly a =
      Assembly::Create(Def2({Box("floor", -2, -1, 10, 0, true), Box("L", 4, 0, 9, 1, true),
                             Box("S", 0, 0, 4, 1), Box("B", 2, 1, 4, 2)}));
  const auto cs = Detect(a);
  EXPECT_TRUE(Between(a, cs, "B", "L").empty());
  const auto bs = Between(a, cs, "B", "S");
  ASSERT_EQ(bs.size(), 2u);
  for (const Contact& c : bs) EXPECT_TRUE(Near(NormalInto(a, c, "B"), Vector3(0, 1, 0)));
  const auto sl = Between(a, cs, "S", "L");
  ASSERT_EQ(sl.size(), 2u);
  for (const Contact& c : sl) EXPECT_TRUE(Near(NormalInto(a, c, "S"), Vector3(-1, 0, 0)));
}

// A lone diagonal corner touch: B's lower-left corner on the upper-right
// corner of the fixed block A, nothing else. The candidates up and +x are
// both flush and nothing continues either surface; gravity (−y) lies on the
// boundary of the forbidden cone {v_x < 0, v_y < 0}, not inside it, so the
// touch can carry no weight and keeps no normal: B may slide off the corner
// along either face (down A's right face, or left along its top).
TEST(CornerRule, ALoneDiagonalCornerTouchKeepsNoNormal) {
  const Assembly a = Assembly::Create(Def2({Box("A", 0, 0, 1, 1, true), Box("B", 1, 1, 2, 2)}));
  EXPECT_TRUE(Detect(a).empty());
}

// The same corner against a flush wall: B's left face is continued by the
// block K stacked on A (K's right face is flush with A's, x = 1). The +x
// normal continues on K, the up normal on nothing: B–A keeps +x only, so B
// can slide down the wall past A's corner, and A's corner does not hold B up.
TEST(CornerRule, ACornerOnAFlushWallKeepsTheWallsNormal) {
  const Assembly a = Assembly::Create(
      Def2({Box("A", 0, 0, 1, 1, true), Box("K", 0, 1, 1, 3, true), Box("B", 1, 1, 2, 2)}));
  const auto cs = Detect(a);
  const auto ba = Between(a, cs, "B", "A");
  ASSERT_EQ(ba.size(), 1u);
  EXPECT_TRUE(Near(NormalInto(a, ba[0], "B"), Vector3(1, 0, 0)));
  const auto bk = Between(a, cs, "B", "K");
  ASSERT_EQ(bk.size(), 2u);
  for (const Contact& c : bk) EXPECT_TRUE(Near(NormalInto(a, c, "B"), Vector3(1, 0, 0)));
}

// A block C on a vertex shared by three parts: C's lower-left corner sits on
// the common top corner of A and B (side by side, flush tops), C's bottom
// lies on B. C–A keeps the up normal (the surface continues on B): the load
// at the shared vertex rests on both parts below it.
TEST(CornerRule, ABlockOnAVertexOfThreePartsRestsOnBoth) {
  const Assembly a = Assembly::Create(
      Def2({Box("A", -2, -1, 0, 0, true), Box("B", 0, -1, 2, 0, true), Box("C", 0, 0, 1, 1)}));
  const auto cs = Detect(a);
  const auto ca = Between(a, cs, "C", "A");
  ASSERT_EQ(ca.size(), 1u);
  EXPECT_TRUE(Near(ca[0].p_WC, Vector3(0, 0, 0)));
  EXPECT_TRUE(Near(NormalInto(a, ca[0], "C"), Vector3(0, 1, 0)));
  EXPECT_EQ(Between(a, cs, "C", "B").size(), 2u);
}

// A wedge standing on its apex at the vertex shared by A and B: no face of
// the wedge is flush with a face of A or B, so every candidate is kept; in
// particular both A and B push the apex straight up.
TEST(CornerRule, AWedgeOnAVertexOfThreePartsKeepsEveryCandidate) {
  PartDef wedge;
  wedge.name = "C";
  wedge.polygon = {{0, 0}, {1, 1}, {-1, 1}};
  const Assembly a =
      Assembly::Create(Def2({Box("A", -2, -1, 0, 0, true), Box("B", 0, -1, 2, 0, true), wedge}));
  const auto cs = Detect(a);
  for (const char* below : {"A", "B"}) {
    SCOPED_TRACE(below);
    const auto ct = Between(a, cs, "C", below);
    ASSERT_EQ(ct.size(), 2u);  // up, and the normal of the wedge's face
    int up = 0;
    for (const Contact& c : ct) {
      EXPECT_TRUE(Near(c.p_WC, Vector3(0, 0, 0)));
      up += Near(NormalInto(a, c, "C"), Vector3(0, 1, 0));
    }
    EXPECT_EQ(up, 1);
  }
}

// Two squares tip to tip (diamonds): both pairs of faces at the tips are
// flush, nothing continues them, and gravity points into the forbidden cone
// (straight down, between the two faces): the load rests on the touch, so the
// normals most opposed to gravity are kept, here both (±45°, a tie).
TEST(CornerRule, ADiamondStandingOnADiamondsTipRestsOnIt) {
  PartDef low, high;
  low.name = "low";
  low.fixed = true;
  low.polygon = {{0, -2}, {1, -1}, {0, 0}, {-1, -1}};
  high.name = "high";
  high.polygon = {{0, 0}, {1, 1}, {0, 2}, {-1, 1}};
  const Assembly a = Assembly::Create(Def2({low, high}));
  const auto cs = Detect(a);
  ASSERT_EQ(cs.size(), 2u);
  for (const Contact& c : cs) {
    EXPECT_TRUE(Near(c.p_WC, Vector3(0, 0, 0)));
    EXPECT_NEAR(NormalInto(a, c, "high").y(), std::sqrt(0.5), 1e-12);
  }
}

// A block in the inner corner of an L (paper Fig. 6's B in its slot): at the
// L's reflex vertex the candidates up and +x are both flush, but neither
// separates the parts (the L's wall rises above the floor's plane, its floor
// runs past the wall's): they are two constraints that hold together, and
// both are kept (rule 0).
TEST(CornerRule, ABlockInAnInnerCornerKeepsBothNormals) {
  PartDef ell;
  ell.name = "L";
  ell.fixed = true;
  ell.polygon = {{0, 0}, {4, 0}, {4, 1}, {1, 1}, {1, 4}, {0, 4}};
  const Assembly a = Assembly::Create(Def2({ell, Box("B", 1, 1, 2, 2)}));
  int at_corner = 0, up = 0, right = 0;
  for (const Contact& c : Detect(a)) {
    if (!Near(c.p_WC, Vector3(1, 1, 0))) continue;
    ++at_corner;
    up += Near(NormalInto(a, c, "B"), Vector3(0, 1, 0));
    right += Near(NormalInto(a, c, "B"), Vector3(1, 0, 0));
  }
  EXPECT_EQ(at_corner, 2);
  EXPECT_EQ(up, 1);
  EXPECT_EQ(right, 1);
}

// --- 3-D --------------------------------------------------------------------

// The flush joint in 3-D: B (y ∈ [0.5, 1.5]) on S has slid until its bottom
// right edge lies on the top left edge of the ledge L, across a gap. The two
// ends of that edge each have the candidates +z and −x (both flush); B's
// face contact with S continues z = 1: only +z is kept.
TEST(CornerRule, AFlushJointIn3DKeepsOnlyTheFlushPlanesNormal) {
  const Assembly a = Assembly::Create(
      Def3({Box3("floor", {-2, -1, -1}, {10, 3, 0}, true), Box3("L", {4.5, 0, 0}, {9, 2, 1}, true),
            Box3("S", {0, 0, 0}, {4, 2, 1}), Box3("B", {2.5, 0.5, 1}, {4.5, 1.5, 2})}));
  const auto cs = Detect(a);
  const auto bl = Between(a, cs, "B", "L");
  ASSERT_EQ(bl.size(), 2u);
  for (const Contact& c : bl) {
    EXPECT_NEAR(c.p_WC.x(), 4.5, 1e-9);
    EXPECT_NEAR(c.p_WC.z(), 1, 1e-9);
    EXPECT_TRUE(Near(NormalInto(a, c, "B"), Vector3(0, 0, 1)));
  }
  for (const Contact& c : Between(a, cs, "B", "S"))
    EXPECT_TRUE(Near(NormalInto(a, c, "B"), Vector3(0, 0, 1)));
}

// A lone corner-to-corner touch in 3-D: B's lowest corner on the top corner
// of A, with the three pairs of faces at the touch flush. Nothing continues
// them and gravity (−z) is not inside the forbidden cone: no normal is kept.
TEST(CornerRule, ALoneCornerToCornerTouchIn3DKeepsNoNormal) {
  const Assembly a = Assembly::Create(
      Def3({Box3("A", {0, 0, 0}, {1, 1, 1}, true), Box3("B", {1, 1, 1}, {2, 2, 2})}));
  EXPECT_TRUE(Detect(a).empty());
}

// The same edge-to-edge touch with nothing else (B's bottom right edge on
// A's top left edge... here B above and beside A along x): +z and −x are
// flush at both ends, the two ends do not support each other, gravity is on
// the boundary of the forbidden cone: no normal. With a second block C under
// B's other end (flush with A's top), +z continues on C: only +z is kept.
TEST(CornerRule, AnEdgeToEdgeTouchIn3DKeepsTheNormalTheLoadRestsOn) {
  const PartDef A = Box3("A", {2, 0, 0}, {3, 1, 1}, true);
  const PartDef B = Box3("B", {0, 0, 1}, {2, 1, 2});
  EXPECT_TRUE(Detect(Assembly::Create(Def3({A, B}))).empty());
  const Assembly a = Assembly::Create(Def3({A, B, Box3("C", {0, 0, 0}, {1, 1, 1}, true)}));
  const auto cs = Detect(a);
  const auto ba = Between(a, cs, "B", "A");
  ASSERT_EQ(ba.size(), 2u);
  for (const Contact& c : ba) EXPECT_TRUE(Near(NormalInto(a, c, "B"), Vector3(0, 0, 1)));
}

// A box C on the edge shared by A and B below it (flush tops, C's bottom on
// B): C–A keeps +z where C's bottom edge lies on A's top edge.
TEST(CornerRule, ABoxOnAnEdgeOfThreePartsRestsOnBoth) {
  const Assembly a = Assembly::Create(
      Def3({Box3("A", {-2, 0, -1}, {0, 1, 0}, true), Box3("B", {0, 0, -1}, {2, 1, 0}, true),
            Box3("C", {0, 0, 0}, {1, 1, 1})}));
  const auto cs = Detect(a);
  const auto ca = Between(a, cs, "C", "A");
  ASSERT_EQ(ca.size(), 2u);
  for (const Contact& c : ca) {
    EXPECT_NEAR(c.p_WC.x(), 0, 1e-9);
    EXPECT_TRUE(Near(NormalInto(a, c, "C"), Vector3(0, 0, 1)));
  }
}

}  // namespace
}  // namespace cairn

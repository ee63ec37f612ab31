#include "cairn/geometry/assembly.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "cairn/core/error.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using testing::Box;
using ::testing::HasSubstr;

// A table and two blocks on it.
AssemblyDef TwoBlocks() {
  AssemblyDef def;
  def.name = "two blocks";
  def.parts = {Box("table", -5, -1, 5, 0, true), Box("A", 0, 0, 2, 1), Box("B", 0, 1, 1, 2)};
  def.parts[1].density = 2.0;
  def.parts[2].mass = 1.5;
  return def;
}

// Runs Create, expecting an InputError at `path` whose message contains `phrase`.
void ExpectError(const AssemblyDef& def, const std::string& path, const std::string& phrase) {
  try {
    Assembly::Create(def, "scene.json");
    ADD_FAILURE() << "no error; expected " << path << ": " << phrase;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    EXPECT_EQ(e.json_path(), path) << e.what();
    EXPECT_THAT(e.message(), HasSubstr(phrase)) << e.what();
  }
}

TEST(Assembly, MassesInertiaAndOrientation) {
  AssemblyDef def = TwoBlocks();
  // Give A clockwise: it comes back counter-clockwise.
  std::reverse(def.parts[1].polygon.begin(), def.parts[1].polygon.end());
  const Assembly a = Assembly::Create(def);
  ASSERT_EQ(a.num_parts(), 3);
  EXPECT_EQ(a.name(), "two blocks");
  const Part& pa = a.part(1);
  EXPECT_GT(SignedArea(pa.polygon), 0);
  EXPECT_DOUBLE_EQ(pa.area, 2.0);
  EXPECT_DOUBLE_EQ(pa.mass, 4.0);  // density 2 × area 2
  EXPECT_NEAR(pa.polar_inertia(), 4.0 * (4 + 1) / 12.0, 1e-12);
  EXPECT_TRUE(pa.centroid.isApprox(Vector3(1, 0.5, 0)));
  EXPECT_EQ(a.dimension(), 2);
  EXPECT_TRUE(a.gravity().isApprox(Vector3(0, -9.81, 0)));
  const Part& pb = a.part(2);
  EXPECT_DOUBLE_EQ(pb.mass, 1.5);  // mass given
  EXPECT_NEAR(pb.polar_inertia(), 1.5 * 2 / 12.0, 1e-12);
  EXPECT_DOUBLE_EQ(a.part(0).mass, 10.0);  // default density 1
  EXPECT_TRUE(a.part(0).fixed);
  EXPECT_EQ(a.FindPart("B"), 2);
  EXPECT_EQ(a.FindPart("nope"), -1);
}

TEST(Assembly, MassWinsOverDensity) {
  AssemblyDef def = TwoBlocks();
  def.parts[1].mass = 7.0;
  EXPECT_DOUBLE_EQ(Assembly::Create(def).part(1).mass, 7.0);
}

TEST(Assembly, SceneSizeAndTolerances) {
  const Assembly a = Assembly::Create(TwoBlocks());
  // The bounding box of all parts is [-5, 5] × [-1, 2].
  EXPECT_NEAR(a.scene_size(), std::hypot(10.0, 3.0), 1e-12);
  EXPECT_NEAR(a.length_tolerance(), 1e-6 * std::hypot(10.0, 3.0), 1e-18);
  const Tolerances t = a.MakeTolerances(0.5);
  EXPECT_NEAR(t.acceleration, 1e-6 * 9.81, 1e-15);
  EXPECT_NEAR(t.velocity, 1e-6 * 9.81 * 0.5, 1e-15);
  // The heaviest movable part is A (4 mass units); the table does not count.
  EXPECT_NEAR(t.force, 1e-9 * 4.0 * 9.81, 1e-18);

  AssemblyDef def = TwoBlocks();
  def.tolerance = 1e-3;
  EXPECT_DOUBLE_EQ(Assembly::Create(def).length_tolerance(), 1e-3);
  EXPECT_DOUBLE_EQ(Assembly::Create(def).MakeTolerances().length, 1e-3);
}

TEST(Assembly, FrictionPairsAreSymmetricAndTheWorldIsFrictionless) {
  AssemblyDef def = TwoBlocks();
  def.friction = 0.3;
  def.friction_pairs = {{"A", "table", 0.05}};
  const Assembly a = Assembly::Create(def);
  EXPECT_DOUBLE_EQ(a.Friction(1, 0), 0.05);
  EXPECT_DOUBLE_EQ(a.Friction(0, 1), 0.05);
  EXPECT_DOUBLE_EQ(a.Friction(1, 2), 0.3);
  EXPECT_DOUBLE_EQ(a.Friction(1, -1), 0.0);
  EXPECT_FALSE(a.IsFrictionless());

  AssemblyDef zero = TwoBlocks();
  zero.friction_pairs = {{"A", "B", 0.0}};
  EXPECT_TRUE(Assembly::Create(zero).IsFrictionless());
  zero.friction_pairs = {{"A", "B", 0.2}};
  EXPECT_FALSE(Assembly::Create(zero).IsFrictionless());
}

TEST(Assembly, FixtureNormalIsNormalised) {
  AssemblyDef def = TwoBlocks();
  def.fixtures = {{"B", {1, 1.5, 0}, {-3, 0, 0}}};
  const Assembly a = Assembly::Create(def);
  ASSERT_EQ(a.fixtures().size(), 1u);
  EXPECT_EQ(a.fixtures()[0].part, 2);
  EXPECT_TRUE(a.fixtures()[0].normal.isApprox(Vector3(-1, 0, 0)));
}

TEST(Assembly, FixtureNormalsAtVertices) {
  // Square B = [0, 1] × [1, 2]; its top-right corner (1, 2) is convex.
  const auto with_fixture = [](Vector2 point, Vector2 normal) {
    AssemblyDef def = TwoBlocks();
    def.fixtures = {{"B", Embed(point), Embed(normal)}};
    return def;
  };
  // Into the corner's wedge, or along one face pushing on the other: fine.
  EXPECT_NO_THROW(Assembly::Create(with_fixture({1, 2}, {-1, -1})));
  EXPECT_NO_THROW(Assembly::Create(with_fixture({1, 2}, {-1, 0})));
  EXPECT_NO_THROW(Assembly::Create(with_fixture({1, 2}, {0, -1})));
  // Out of the wedge.
  ExpectError(with_fixture({1, 2}, {1, -1}), "fixtures[0].normal", "points out of part 'B'");
  ExpectError(with_fixture({1, 2}, {1, 1}), "fixtures[0].normal", "points out of");
  // On an edge: tangent or outward is an error.
  ExpectError(with_fixture({1, 1.5}, {0, 1}), "fixtures[0].normal", "points out of");
  ExpectError(with_fixture({1, 1.5}, {1, 0}), "fixtures[0].normal", "points out of");

  // The reflex corner (1, 1) of an L-shape: into either face's material is fine.
  AssemblyDef l;
  PartDef part;
  part.name = "L";
  part.polygon = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  l.parts = {part};
  l.fixtures = {{"L", {1, 1, 0}, {1, -1, 0}}};
  EXPECT_NO_THROW(Assembly::Create(l));
  l.fixtures = {{"L", {1, 1, 0}, {-1, -1, 0}}};
  EXPECT_NO_THROW(Assembly::Create(l));
  l.fixtures = {{"L", {1, 1, 0}, {1, 1, 0}}};
  ExpectError(l, "fixtures[0].normal", "points out of part 'L'");
}

TEST(Assembly, NonFiniteNumbersAreRejected) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  AssemblyDef def = TwoBlocks();
  def.gravity = Vector3(0, nan, 0);
  ExpectError(def, "gravity", "finite");
  def = TwoBlocks();
  def.friction = inf;
  ExpectError(def, "friction", "finite");
  def = TwoBlocks();
  def.tolerance = nan;
  ExpectError(def, "tolerance", "finite");
  def = TwoBlocks();
  def.parts[1].polygon[2].x() = inf;
  ExpectError(def, "parts[1] (\"A\").polygon[2]", "finite");
  def = TwoBlocks();
  def.parts[1].density = nan;
  ExpectError(def, "parts[1] (\"A\").density", "finite");
  def = TwoBlocks();
  def.parts[2].mass = inf;
  ExpectError(def, "parts[2] (\"B\").mass", "finite");
  def = TwoBlocks();
  def.friction_pairs = {{"A", "B", nan}};
  ExpectError(def, "friction_pairs[0].mu", "finite");
  def = TwoBlocks();
  def.fixtures = {{"B", {1, nan, 0}, {-1, 0, 0}}};
  ExpectError(def, "fixtures[0].point", "finite");
  def.fixtures = {{"B", {1, 1.5, 0}, {-inf, 0, 0}}};
  ExpectError(def, "fixtures[0].normal", "finite");
}

// In 3-D each overlapping pair comes with how deep its witness lies in the
// part it is not on the surface of: a cube pushed 0.25 into another, a
// third 0.1 into the second, at most that deep.
// A model whose surfaces are approximations (an overlap allowance, the
// chordal tolerance of its facets) has the angle tolerance allowance / the
// smallest part's bounding-box diagonal, at most kMaxApproximatedAngle; an
// exact model keeps 1e-6 rad.
TEST(Assembly, AnApproximatedModelsAngleToleranceIsItsAllowanceOverItsSmallestPart) {
  AssemblyDef def;
  def.parts = {testing::Box3("table", {-2, -2, -1}, {2, 2, 0}, true),
               testing::Box3("cube", {0, 0, 0}, {0.5, 0.5, 0.5})};
  const double diagonal = std::sqrt(3 * 0.25);
  EXPECT_EQ(Assembly::Create(def).MakeTolerances().angle, 1e-6);
  def.overlap_allowance = 1e-4;
  EXPECT_DOUBLE_EQ(Assembly::Create(def).MakeTolerances().angle, 1e-4 / diagonal);
  def.overlap_allowance = 0.1;
  EXPECT_EQ(Assembly::Create(def).MakeTolerances().angle, limits::kMaxApproximatedAngle);
  def.overlap_allowance = 1e-9;  // below 1e-6 rad: the default stays
  EXPECT_EQ(Assembly::Create(def).MakeTolerances().angle, 1e-6);
}

TEST(Assembly, OverlapsIn3DSayHowDeep) {
  AssemblyDef def;
  def.parts = {testing::Box3("A", {0, 0, 0}, {1, 1, 1}, true),
               testing::Box3("B", {0.75, 0, 0}, {1.75, 1, 1}),
               testing::Box3("C", {1.65, 0, 0}, {2.65, 1, 1})};
  try {
    Assembly::Create(def, "scene.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "parts[1] (\"B\")") << e.what();
    const std::string m = e.message();
    EXPECT_THAT(m, HasSubstr("part 'B' overlaps part 'A' (parts[0])")) << m;
    EXPECT_THAT(m, HasSubstr("; 1 more overlapping pair: 'C' and 'B' (parts[2], parts[1]) at ("))
        << m;
    const auto depth_after = [&](size_t from) {
      const size_t end = m.find(" deep", from);
      EXPECT_NE(end, std::string::npos) << m;
      const size_t start = m.rfind(", ", end) + 2;
      return std::stod(m.substr(start, end - start));
    };
    const double ab = depth_after(0), bc = depth_after(m.find("more overlapping"));
    EXPECT_GT(ab, 0);
    EXPECT_LE(ab, 0.25 + 1e-9);
    EXPECT_GT(bc, 0);
    EXPECT_LE(bc, 0.1 + 1e-9);
  }
}

TEST(Assembly, Overlaps) {
  // A vertex deep inside another part.
  AssemblyDef def = TwoBlocks();
  def.parts[2] = Box("B", 1, 0.5, 3, 2);
  ExpectError(def, "parts[2] (\"B\")", "part 'B' overlaps part 'A' (parts[1])");
  // A cross: edges cross, no vertex of either inside the other.
  def = TwoBlocks();
  def.parts[1] = Box("A", 0, 1, 3, 2);
  def.parts[2] = Box("B", 1, 0.5, 2, 2.5);
  ExpectError(def, "parts[2] (\"B\")", "overlaps part 'A'");
  // Coincident shapes.
  def = TwoBlocks();
  def.parts[2] = Box("B", 0, 0, 2, 1);
  ExpectError(def, "parts[2] (\"B\")", "overlaps part 'A'");
  // Two fixed parts overlap too: a wall built into the table.
  def = TwoBlocks();
  def.parts.push_back(Box("wall", 4, -0.5, 5, 3, true));
  ExpectError(def, "parts[3] (\"wall\")", "part 'wall' overlaps part 'table' (parts[0])");
  // Every overlapping pair is listed, the lowest indices first (its later
  // part names the path), each with a point in both.
  def = TwoBlocks();
  def.parts[2] = Box("B", 1, 0.5, 3, 2);
  def.parts.push_back(Box("C", 10, 0, 11, 1));
  def.parts.push_back(Box("D", 10.5, 0.5, 11.5, 1.5));
  ExpectError(def, "parts[2] (\"B\")",
              "part 'B' overlaps part 'A' (parts[1]) by more than the tolerance");
  ExpectError(def, "parts[2] (\"B\")",
              "; 1 more overlapping pair: 'D' and 'C' (parts[4], parts[3]) at (");
  // Within the tolerance is touching, not overlap.
  def = TwoBlocks();
  def.parts[2] = Box("B", 0, 1 - 1e-7, 1, 2);
  EXPECT_NO_THROW(Assembly::Create(def));
  def.parts[2] = Box("B", 0, 1 - 1e-4, 1, 2);
  ExpectError(def, "parts[2] (\"B\")", "overlaps");
}

// A gripper pad G (a tool) beside block A on the table.
AssemblyDef TwoBlocksAndPad() {
  AssemblyDef def = TwoBlocks();
  def.parts.push_back(Box("G", 2, 0, 2.5, 0.5));
  def.parts[3].tool = true;
  return def;
}

TEST(Assembly, ToolsAreKeptAndMarked) {
  const Assembly a = Assembly::Create(TwoBlocksAndPad());
  ASSERT_EQ(a.num_parts(), 4);
  EXPECT_TRUE(a.part(3).tool);
  EXPECT_FALSE(a.part(3).fixed);
  EXPECT_FALSE(a.part(1).tool);
  EXPECT_FALSE(a.part(0).tool);
  EXPECT_EQ(a.FindPart("G"), 3);
  EXPECT_DOUBLE_EQ(a.part(3).mass, 0.25);  // a tool has mass like any part
}

TEST(Assembly, ToolCannotBeFixed) {
  AssemblyDef def = TwoBlocksAndPad();
  def.parts[3].fixed = true;
  ExpectError(def, "parts[3] (\"G\").tool", "part 'G' cannot be both fixed and a tool");
}

TEST(Assembly, ToolsAreCheckedForOverlap) {
  // A pad overlapping A at its start pose would penetrate A when gripped.
  AssemblyDef def = TwoBlocksAndPad();
  def.parts[3] = Box("G", 1.5, 0, 2.5, 0.5);
  def.parts[3].tool = true;
  ExpectError(def, "parts[3] (\"G\")", "part 'G' overlaps part 'A' (parts[1])");
}

TEST(Configuration, AssembledLeavesToolsOut) {
  const Assembly a = Assembly::Create(TwoBlocksAndPad());
  const Configuration config = Configuration::Assembled(a);
  ASSERT_EQ(config.present.size(), 4u);
  EXPECT_TRUE(config.present[0]);
  EXPECT_TRUE(config.present[1]);
  EXPECT_TRUE(config.present[2]);
  EXPECT_FALSE(config.present[3]);  // the tool, until a plan step grips it
  ASSERT_EQ(config.poses.size(), 4u);
  EXPECT_EQ(config.WorldPolygon(a, 3), a.part(3).polygon);  // at its start pose
}

TEST(Assembly, ManyTouchingPartsAreFast) {
  // A 25 × 25 wall of unit bricks on a table: 626 parts, all touching.
  AssemblyDef def;
  def.parts.push_back(Box("table", -1, -1, 26, 0, true));
  for (int r = 0; r < 25; ++r) {
    for (int c = 0; c < 25; ++c) {
      def.parts.push_back(
          Box("b" + std::to_string(r) + "_" + std::to_string(c), c, r, c + 1, r + 1));
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const Assembly a = Assembly::Create(def);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(a.num_parts(), 626);
  EXPECT_LT(seconds, 5.0);  // generous: sanitizers are on in the test build
}

TEST(Pose, RotatesAboutTheCentroidThenTranslates) {
  const Pose pose = Pose::Planar({10, 0}, std::numbers::pi / 2);
  const Vector3 c(1, 1, 0);
  EXPECT_TRUE(pose.Apply({2, 1, 0}, c).isApprox(Vector3(11, 2, 0)));
  EXPECT_TRUE(pose.Apply(c, c).isApprox(Vector3(11, 1, 0)));
  EXPECT_NEAR(pose.angle(), std::numbers::pi / 2, 1e-15);
}

TEST(Pose, RotateIsTheExponentialMap) {
  // A quarter turn about +x, given as a rotation vector, then another: a half turn.
  Pose pose;
  pose.Rotate({std::numbers::pi / 2, 0, 0});
  EXPECT_TRUE((pose.rotation * Vector3(0, 1, 0)).isApprox(Vector3(0, 0, 1), 1e-12));
  pose.Rotate({std::numbers::pi / 2, 0, 0});
  EXPECT_TRUE((pose.rotation * Vector3(0, 1, 0)).isApprox(Vector3(0, -1, 0), 1e-12));
  EXPECT_NEAR(pose.rotation.determinant(), 1.0, 1e-12);
}

TEST(Configuration, RotatingASquareByNinetyDegrees) {
  AssemblyDef def;
  def.parts = {Box("S", 0, 0, 2, 2)};
  const Assembly a = Assembly::Create(def);
  Configuration config = Configuration::Assembled(a);
  ASSERT_EQ(config.present.size(), 1u);
  EXPECT_TRUE(config.present[0]);
  // Assembled: the part's own polygon.
  EXPECT_EQ(config.WorldPolygon(a, 0), a.part(0).polygon);
  config.poses[0] = Pose::Planar({3, 0}, std::numbers::pi / 2);
  const Polygon p = config.WorldPolygon(a, 0);
  // About the centroid (1, 1) each vertex moves to the next one's place.
  const Polygon expected = {{2 + 3, 0}, {2 + 3, 2}, {0 + 3, 2}, {0 + 3, 0}};
  ASSERT_EQ(p.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(p[k].x(), expected[k].x(), 1e-12) << k;
    EXPECT_NEAR(p[k].y(), expected[k].y(), 1e-12) << k;
  }
  EXPECT_GT(SignedArea(p), 0);
  EXPECT_TRUE(config.WorldCentroid(a, 0).isApprox(Vector3(4, 1, 0)));
}

}  // namespace
}  // namespace cairn

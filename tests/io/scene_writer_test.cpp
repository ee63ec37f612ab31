// io/scene_writer.h: a model written as a scene file reads back as the same
// model, bit for bit (the numbers in their shortest exact form), and writing
// it again gives the same text.
#include "cairn/io/scene_writer.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "cairn/io/scene_reader.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

AssemblyDef Reparse(const AssemblyDef& def) {
  return ParseSceneJson(nlohmann::json::parse(WriteSceneJson(def)), "written");
}

void ExpectSameModel(const Assembly& a, const Assembly& b) {
  ASSERT_EQ(a.num_parts(), b.num_parts());
  EXPECT_EQ(a.dimension(), b.dimension());
  EXPECT_EQ(a.gravity(), b.gravity());
  for (int i = 0; i < a.num_parts(); ++i) {
    EXPECT_EQ(a.part(i).name, b.part(i).name);
    EXPECT_EQ(a.part(i).fixed, b.part(i).fixed) << a.part(i).name;
    EXPECT_EQ(a.part(i).mass, b.part(i).mass) << a.part(i).name;  // exact numbers
    EXPECT_EQ(a.part(i).centroid, b.part(i).centroid) << a.part(i).name;
    EXPECT_EQ(a.part(i).vertices, b.part(i).vertices) << a.part(i).name;
    for (int j = -1; j < a.num_parts(); ++j) EXPECT_EQ(a.Friction(i, j), b.Friction(i, j));
  }
  EXPECT_EQ(a.length_tolerance(), b.length_tolerance());
  EXPECT_EQ(a.fixtures().size(), b.fixtures().size());
}

TEST(WriteSceneJson, A2DAndA3DSceneReadBackAsTheSameModel) {
  for (const char* name : {"paper_fig1.json", "paper_fig9.json", "jenga.json"}) {
    SCOPED_TRACE(name);
    const AssemblyDef def = ReadSceneDef(testing::ExamplePath(name));
    ExpectSameModel(Assembly::Create(def), Assembly::Create(Reparse(def)));
    EXPECT_EQ(WriteSceneJson(Reparse(def)), WriteSceneJson(def));
  }
}

// Coordinates no short decimal holds (1/3, 0.1 + 0.2, a 1e-300 offset), a
// friction pair, a fixel, gravity off the axes and a name that needs JSON
// escapes: all of it comes back.
TEST(WriteSceneJson, AwkwardNumbersPairsAndFixelsComeBackExactly) {
  AssemblyDef def;
  def.name = "quote \" and \\ and \n newline";
  def.friction = 0.1 + 0.2;
  def.gravity = Vector3(1.0 / 3.0, -9.81, 0);
  const double third = 1.0 / 3.0;
  def.parts = {testing::Box("floor", -2, -1, 3, 0, true),
               testing::Box("block \"b\"", third, 0, 1 + third, 0.5 + 1e-300)};
  def.parts[1].polygon[2].x() += 1e-15;
  def.friction_pairs = {{"floor", "block \"b\"", 0.7}};
  def.fixtures = {{"block \"b\"", {1 + third, 0.25, 0}, {-1, 0, 0}}};
  const AssemblyDef back = Reparse(def);
  EXPECT_EQ(back.name, def.name);
  ASSERT_EQ(back.parts.size(), 2u);
  EXPECT_EQ(back.parts[1].name, def.parts[1].name);
  EXPECT_EQ(back.parts[1].polygon, def.parts[1].polygon);
  ASSERT_EQ(back.friction_pairs.size(), 1u);
  EXPECT_EQ(back.friction_pairs[0].mu, 0.7);
  ExpectSameModel(Assembly::Create(def), Assembly::Create(back));
  EXPECT_EQ(WriteSceneJson(back), WriteSceneJson(def));
}

// The overlap allowance (a STEP model's chordal tolerance) comes back, and
// with it the scene loads where its parts cross by more than the tolerance:
// two unit squares crossed by 0.01, refused at the tolerance 1e-3, read with
// an allowance of 0.02.
TEST(WriteSceneJson, TheOverlapAllowanceComesBackAndLetsPartsCross) {
  AssemblyDef def;
  def.tolerance = 1e-3;
  def.parts = {testing::Box("floor", 0, -1, 1, 0, true), testing::Box("block", 0, -0.01, 1, 1)};
  EXPECT_THROW(Assembly::Create(def), InputError);
  def.overlap_allowance = 0.02;
  const AssemblyDef back = Reparse(def);
  EXPECT_EQ(back.overlap_allowance, 0.02);
  const Assembly a = Assembly::Create(back);
  EXPECT_EQ(a.overlap_allowance(), 0.02);
  EXPECT_EQ(WriteSceneJson(back), WriteSceneJson(def));
}

}  // namespace
}  // namespace cairn

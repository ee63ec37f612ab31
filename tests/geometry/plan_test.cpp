#include "cairn/geometry/plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "cairn/core/error.h"
#include "scene_builders.h"

namespace cairn {
namespace {

using ::testing::HasSubstr;

using testing::Box;

// The blocks of paper Fig. 1 (examples/paper_fig1.json): A-D on the fixed
// table E, plus a gripper pad G (a tool) lying on the table at the right.
Assembly Fig1WithPad() {
  AssemblyDef def;
  def.parts = {Box("E", -6, -1, 6, 0),       Box("A", -1, 0, 1, 1),      Box("B", -3, 1, 3, 1.5),
               Box("C", -3, 1.5, -1.5, 2.5), Box("D", 1.5, 1.5, 3, 3.5), Box("G", 4, 0, 5, 0.2)};
  def.parts[0].fixed = true;
  def.parts[5].tool = true;
  return Assembly::Create(def, "fig1.json");
}

std::vector<Vector3> EmbedAll(const std::vector<Vector2>& path) {
  std::vector<Vector3> out;
  for (const Vector2& p : path) out.push_back(Embed(p));
  return out;
}

PlanStepDef Step(std::vector<std::string> remove, const std::vector<Vector2>& path) {
  PlanStepDef s;
  s.remove = std::move(remove);
  s.path = EmbedAll(path);
  s.has_path = true;
  return s;
}

PlanStepDef Straight(const std::string& part, const Vector2& direction, double distance) {
  PlanStepDef s;
  s.remove = {part};
  s.direction = Embed(direction);
  s.distance = distance;
  s.has_direction = true;
  return s;
}

// A valid two-step plan the bad cases modify.
PlanDef BasePlan() {
  PlanDef def;
  def.steps = {Step({"C"}, {{0, 0}, {0, 2}}), Step({"D"}, {{0, 3}})};
  return def;
}

TEST(PlanToString, Names) {
  EXPECT_STREQ(to_string(SupportMode::kFull), "full");
  EXPECT_STREQ(to_string(SupportMode::kNone), "none");
  EXPECT_STREQ(to_string(PlanMode::kDisassemble), "disassemble");
  EXPECT_STREQ(to_string(PlanMode::kAssemble), "assemble");
}

// Segments of lengths 3, 4 and 5: (0, 0) → (3, 0) → (3, 4) → (6, 8).
PlanStep ThreeSegments() {
  PlanStep step;
  step.path = EmbedAll({{0, 0}, {3, 0}, {3, 4}, {6, 8}});
  return step;
}

TEST(PlanStep, LengthSumsTheSegments) {
  EXPECT_DOUBLE_EQ(ThreeSegments().Length(), 12.0);
  PlanStep straight;
  straight.path = EmbedAll({{0, 0}, {-1, 1}});
  EXPECT_DOUBLE_EQ(straight.Length(), std::sqrt(2.0));
}

TEST(PlanStep, AtVerticesIsExact) {
  const PlanStep step = ThreeSegments();
  EXPECT_EQ(step.At(0), Vector3(0, 0, 0));
  EXPECT_EQ(step.At(3), Vector3(3, 0, 0));
  EXPECT_EQ(step.At(7), Vector3(3, 4, 0));
  EXPECT_EQ(step.At(12), Vector3(6, 8, 0));
}

TEST(PlanStep, AtMidSegments) {
  const PlanStep step = ThreeSegments();
  EXPECT_TRUE(step.At(1.5).isApprox(Vector3(1.5, 0, 0)));
  EXPECT_TRUE(step.At(5).isApprox(Vector3(3, 2, 0)));
  EXPECT_TRUE(step.At(9.5).isApprox(Vector3(4.5, 6, 0)));
  // Just past a vertex, on the next segment.
  EXPECT_NEAR(step.At(3.25).y(), 0.25, 1e-15);
  EXPECT_DOUBLE_EQ(step.At(3.25).x(), 3.0);
}

TEST(PlanStep, AtClampsToThePath) {
  const PlanStep step = ThreeSegments();
  EXPECT_EQ(step.At(-1), Vector3(0, 0, 0));
  EXPECT_EQ(step.At(12.5), Vector3(6, 8, 0));
  EXPECT_EQ(step.At(std::numeric_limits<double>::infinity()), Vector3(6, 8, 0));
  EXPECT_EQ(step.At(std::nan("")), Vector3(0, 0, 0));
}

TEST(PlanCreate, DefaultsAndNormalisedPaths) {
  const Assembly a = Fig1WithPad();
  PlanDef def;
  def.mode = PlanMode::kAssemble;
  def.dt = 0.5;
  def.speed = 2.0;
  PlanStepDef c = Step({"C"}, {{-4, 0}, {-4, 0}, {-4, 6}});  // no leading (0, 0), a repeat
  c.support = SupportMode::kNone;
  const PlanStepDef d = Straight("D", {0, 2}, 3);
  PlanStepDef ab = Step({"A", "B"}, {{0, 0}, {0, 0}, {-5, 0}});
  ab.grip = {"B", "G"};
  def.steps = {c, d, ab};

  const Plan plan = Plan::Create(def, a, "plan.json");
  EXPECT_EQ(plan.mode, PlanMode::kAssemble);
  EXPECT_EQ(plan.dt, 0.5);
  EXPECT_EQ(plan.speed, 2.0);
  ASSERT_EQ(plan.steps.size(), 3u);

  const PlanStep& s0 = plan.steps[0];
  EXPECT_EQ(s0.remove, std::vector<int>{3});
  EXPECT_EQ(s0.grip, std::vector<int>{3});  // default: all of remove
  EXPECT_EQ(s0.support, SupportMode::kNone);
  const std::vector<Vector2> p0 = {{0, 0}, {-4, 0}, {-4, 6}};
  EXPECT_EQ(s0.path, EmbedAll(p0));
  EXPECT_DOUBLE_EQ(s0.Length(), 10.0);

  const PlanStep& s1 = plan.steps[1];
  EXPECT_EQ(s1.support, SupportMode::kFull);
  const std::vector<Vector2> p1 = {{0, 0}, {0, 3}};  // distance along the unit direction
  EXPECT_EQ(s1.path, EmbedAll(p1));

  const PlanStep& s2 = plan.steps[2];
  EXPECT_EQ(s2.remove, (std::vector<int>{1, 2}));
  EXPECT_EQ(s2.grip, (std::vector<int>{2, 5}));  // B and the tool G; A is pushed
  const std::vector<Vector2> p2 = {{0, 0}, {-5, 0}};
  EXPECT_EQ(s2.path, EmbedAll(p2));
}

TEST(PlanCreate, ObliqueDirectionIsNormalised) {
  PlanDef def = BasePlan();
  def.steps[1] = Straight("D", {3, 4}, 10);
  const Plan plan = Plan::Create(def, Fig1WithPad());
  ASSERT_EQ(plan.steps[1].path.size(), 2u);
  EXPECT_TRUE(plan.steps[1].path[1].isApprox(Vector3(6, 8, 0)));
  EXPECT_DOUBLE_EQ(plan.steps[1].Length(), 10.0);
}

// One bad PlanDef: how to spoil BasePlan, and the error expected.
struct BadDef {
  const char* name;
  std::function<void(PlanDef&)> spoil;
  const char* path;
  const char* phrase;
};

void PrintTo(const BadDef& c, std::ostream* os) { *os << c.name; }

const double kNan = std::nan("");
const double kInf = std::numeric_limits<double>::infinity();

// clang-format off
const BadDef kBadDefs[] = {
  {"dt_zero", [](PlanDef& d) { d.dt = 0; }, "dt", "must be positive (got 0)"},
  {"dt_nan", [](PlanDef& d) { d.dt = kNan; }, "dt", "must be a finite number (got nan)"},
  {"speed_negative", [](PlanDef& d) { d.speed = -2; }, "speed", "must be positive (got -2)"},
  {"speed_inf", [](PlanDef& d) { d.speed = kInf; }, "speed", "must be a finite number (got inf)"},
  {"no_steps", [](PlanDef& d) { d.steps.clear(); }, "steps", "must list at least one step"},
  {"empty_remove", [](PlanDef& d) { d.steps[1].remove.clear(); }, "steps[1].remove",
   "must name at least one part"},
  {"unknown_remove", [](PlanDef& d) { d.steps[1].remove = {"D", "Z"}; }, "steps[1].remove[1]",
   "no part named 'Z'"},
  {"fixed_remove", [](PlanDef& d) { d.steps[0].remove = {"E"}; }, "steps[0].remove[0]",
   "part 'E' is fixed: fixed parts never move"},
  {"tool_remove", [](PlanDef& d) { d.steps[0].remove = {"C", "G"}; }, "steps[0].remove[1]",
   "part 'G' is a tool"},
  {"removed_twice_in_step", [](PlanDef& d) { d.steps[1].remove = {"D", "D"}; }, "steps[1].remove[1]",
   "names part 'D' twice (also steps[1].remove[0])"},
  {"removed_in_two_steps", [](PlanDef& d) { d.steps[1].remove = {"C"}; }, "steps[1].remove[0]",
   "part 'C' is already removed by steps[0].remove[0]"},
  {"unknown_grip", [](PlanDef& d) { d.steps[0].grip = {"Q"}; }, "steps[0] (\"C\").grip[0]", "no part named 'Q'"},
  {"fixed_grip", [](PlanDef& d) { d.steps[0].grip = {"C", "E"}; }, "steps[0] (\"C\").grip[1]",
   "part 'E' is fixed"},
  {"grip_twice", [](PlanDef& d) { d.steps[0].grip = {"C", "C"}; }, "steps[0] (\"C\").grip[1]",
   "names part 'C' twice (also steps[0].grip[0])"},
  {"grip_not_removed", [](PlanDef& d) { d.steps[0].grip = {"C", "B"}; }, "steps[0] (\"C\").grip[1]",
   "part 'B' is neither in this step's remove nor a tool"},
  {"both_forms", [](PlanDef& d) { d.steps[0].has_direction = true; d.steps[0].direction = Vector3(0, 1, 0);
                                  d.steps[0].distance = 1; }, "steps[0] (\"C\")", "has both path and direction"},
  {"neither_form", [](PlanDef& d) { d.steps[1].has_path = false; d.steps[1].path.clear(); }, "steps[1] (\"D\")",
   "has no path"},
  {"empty_path", [](PlanDef& d) { d.steps[1].path.clear(); }, "steps[1] (\"D\").path", "must have at least one point"},
  {"path_nan", [](PlanDef& d) { d.steps[0].path[1].y() = kNan; }, "steps[0] (\"C\").path[1]",
   "must have finite coordinates (got (0, nan))"},
  {"zero_length", [](PlanDef& d) { d.steps[1].path = EmbedAll({{0, 0}, {0, 0}}); }, "steps[1] (\"D\").path", "has zero length"},
  {"zero_direction", [](PlanDef& d) { d.steps[1] = Straight("D", {0, 0}, 1); },
   "steps[1] (\"D\").direction", "must not be zero"},
  {"direction_inf", [](PlanDef& d) { d.steps[1] = Straight("D", {kInf, 0}, 1); },
   "steps[1] (\"D\").direction", "must have finite coordinates"},
  {"negative_distance", [](PlanDef& d) { d.steps[1] = Straight("D", {0, 1}, -1); },
   "steps[1] (\"D\").distance", "must be positive (got -1)"},
};
// clang-format on

class BadPlanDef : public ::testing::TestWithParam<BadDef> {};

TEST_P(BadPlanDef, NamesPathAndFault) {
  const BadDef& c = GetParam();
  PlanDef def = BasePlan();
  c.spoil(def);
  const Assembly a = Fig1WithPad();
  try {
    Plan::Create(def, a, "plan.json");
    ADD_FAILURE() << "no error; expected " << c.path << ": " << c.phrase;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "plan.json");
    EXPECT_EQ(e.json_path(), c.path) << e.what();
    EXPECT_THAT(e.message(), HasSubstr(c.phrase)) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(AllFaults, BadPlanDef, ::testing::ValuesIn(kBadDefs),
                         [](const auto& param) { return std::string(param.param.name); });

TEST(PlanCreate, BasePlanIsValid) {
  // The bad cases above fail for their own fault, not the base plan's.
  EXPECT_NO_THROW(Plan::Create(BasePlan(), Fig1WithPad()));
}

TEST(PlanCreate, ToolMayBeGrippedAlone) {
  PlanDef def = BasePlan();
  def.steps[0].grip = {"G"};  // C is pushed by the pad
  const Plan plan = Plan::Create(def, Fig1WithPad());
  EXPECT_EQ(plan.steps[0].grip, std::vector<int>{5});
  EXPECT_EQ(plan.steps[0].remove, std::vector<int>{3});
}

}  // namespace
}  // namespace cairn

#include "cairn/io/plan_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/io/scene_reader.h"
#include "io/bad_input.h"
#include "test_paths.h"

namespace cairn {
namespace {

using nlohmann::json;
using testing::BadCase;
using testing::CaseText;
using testing::ExpectBadInput;
using ::testing::HasSubstr;
using testing::WriteTemp;

// The blocks of paper Fig. 1 (A-D on the fixed table E) and a gripper pad G,
// a tool, lying on the table at the right.
constexpr const char* kScene = R"({
  "cairn": 1,
  "gravity": [0, -1],
  "parts": [
    {"name": "E", "fixed": true, "box": {"min": [-6, -1], "max": [6, 0]}},
    {"name": "A", "box": {"min": [-1, 0], "max": [1, 1]}},
    {"name": "B", "box": {"min": [-3, 1], "max": [3, 1.5]}},
    {"name": "C", "box": {"min": [-3, 1.5], "max": [-1.5, 2.5]}},
    {"name": "D", "box": {"min": [1.5, 1.5], "max": [3, 3.5]}},
    {"name": "G", "tool": true, "box": {"min": [4, 0], "max": [5, 0.2]}}
  ]
})";

// The example of docs/plan-format.md.
constexpr const char* kPlanDocExample = R"({
  "cairn_plan": 1,
  "mode": "disassemble",
  "dt": 1.0,
  "speed": 1.0,
  "steps": [
    {"remove": ["C"], "path": [[0, 0], [-4, 0], [-4, 6]], "support": "none"},
    {"remove": ["A", "B"], "grip": ["A"], "path": [[0, 0], [-5, 0]]},
    {"remove": ["D"], "direction": [0, 1], "distance": 3}
  ]
})";

// A small valid plan the bad cases patch (RFC 7386 merge patch: a null
// removes a key, an array is replaced whole).
constexpr const char* kPlanBase = R"({
  "cairn_plan": 1,
  "steps": [
    {"remove": ["C"], "path": [[0, 0], [0, 2]]},
    {"remove": ["D"], "direction": [0, 1], "distance": 3}
  ]
})";

Assembly Scene() { return Assembly::Create(ParseSceneJson(json::parse(kScene), "scene.json")); }

// Writes `text` to a file named `name` in the test's temporary folder.
TEST(ReadPlan, DocumentedExampleOnPaperFig1) {
  const Assembly fig1 = ReadScene(testing::ExamplePath("paper_fig1.json"));
  const Plan plan = ReadPlan(WriteTemp("plan_doc_example.json", kPlanDocExample), fig1);
  EXPECT_EQ(plan.mode, PlanMode::kDisassemble);
  EXPECT_EQ(plan.dt, 1.0);
  EXPECT_EQ(plan.speed, 1.0);
  ASSERT_EQ(plan.steps.size(), 3u);
  const int a = fig1.FindPart("A"), b = fig1.FindPart("B"), c = fig1.FindPart("C"),
            d = fig1.FindPart("D");

  EXPECT_EQ(plan.steps[0].remove, std::vector<int>{c});
  EXPECT_EQ(plan.steps[0].grip, std::vector<int>{c});
  EXPECT_EQ(plan.steps[0].support, SupportMode::kNone);
  const std::vector<Vector3> p0 = {{0, 0, 0}, {-4, 0, 0}, {-4, 6, 0}};
  EXPECT_EQ(plan.steps[0].path, p0);

  EXPECT_EQ(plan.steps[1].remove, (std::vector<int>{a, b}));
  EXPECT_EQ(plan.steps[1].grip, std::vector<int>{a});  // B is pushed, not held
  EXPECT_EQ(plan.steps[1].support, SupportMode::kFull);

  const std::vector<Vector3> p2 = {{0, 0, 0}, {0, 3, 0}};
  EXPECT_EQ(plan.steps[2].remove, std::vector<int>{d});
  EXPECT_EQ(plan.steps[2].path, p2);
  EXPECT_DOUBLE_EQ(plan.steps[2].Length(), 3.0);
}

// Each plan of examples/plans/ is read against its scene: the example scene
// whose name, with an underscore, is the longest prefix of the plan's name
// (paper_fig1_dcba.plan.json → paper_fig1.json).
TEST(ReadPlan, EveryExamplePlanIsValid) {
  const std::filesystem::path examples = testing::SourcePath("examples");
  if (!std::filesystem::is_directory(examples / "plans")) GTEST_SKIP() << "no examples/plans/";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples / "plans")) {
    const std::string plan = entry.path().filename().string();
    if (plan.size() < 10 || plan.substr(plan.size() - 10) != ".plan.json") continue;
    std::string scene;
    for (const auto& candidate : std::filesystem::directory_iterator(examples)) {
      const std::string stem = candidate.path().stem().string();
      if (candidate.path().extension() == ".json" && plan.rfind(stem + "_", 0) == 0 &&
          stem.size() > scene.size()) {
        scene = stem;
      }
    }
    ASSERT_FALSE(scene.empty()) << "no scene for " << plan;
    EXPECT_NO_THROW(
        ReadPlan(entry.path().string(), ReadScene((examples / (scene + ".json")).string())))
        << plan;
    ++count;
  }
  EXPECT_GE(count, 1);
}

TEST(ParsePlanJson, DefaultsAndIndices) {
  const PlanDef def = ParsePlanJson(json::parse(kPlanBase), "base.json");
  EXPECT_EQ(def.mode, PlanMode::kDisassemble);
  EXPECT_EQ(def.dt, 1.0);
  EXPECT_EQ(def.speed, 1.0);
  ASSERT_EQ(def.steps.size(), 2u);
  const PlanStepDef& s0 = def.steps[0];
  EXPECT_EQ(s0.remove, std::vector<std::string>{"C"});
  EXPECT_TRUE(s0.grip.empty());  // Plan::Create fills in all of remove
  EXPECT_TRUE(s0.has_path);
  EXPECT_FALSE(s0.has_direction);
  EXPECT_EQ(s0.support, SupportMode::kFull);
  const PlanStepDef& s1 = def.steps[1];  // vector index = JSON index
  EXPECT_EQ(s1.remove, std::vector<std::string>{"D"});
  EXPECT_FALSE(s1.has_path);
  EXPECT_TRUE(s1.has_direction);
  EXPECT_EQ(s1.direction, Vector3(0, 1, 0));
  EXPECT_EQ(s1.distance, 3.0);
}

TEST(ReadPlan, AllKeysRoundTrip) {
  const std::string text = R"({
    "cairn_plan": 1, "mode": "assemble", "dt": 0.25, "speed": 4,
    "steps": [
      {"remove": ["C"], "grip": ["C", "G"], "path": [[-4, 0], [-4, 0], [-4, 6]], "support": "none"},
      {"remove": ["D"], "direction": [2, 0], "distance": 1.5, "support": "full"}
    ]})";
  const Plan plan = ReadPlan(WriteTemp("plan_all_keys.json", text), Scene());
  EXPECT_EQ(plan.mode, PlanMode::kAssemble);
  EXPECT_EQ(plan.dt, 0.25);
  EXPECT_EQ(plan.speed, 4.0);
  ASSERT_EQ(plan.steps.size(), 2u);
  EXPECT_EQ(plan.steps[0].remove, std::vector<int>{3});
  EXPECT_EQ(plan.steps[0].grip, (std::vector<int>{3, 5}));
  EXPECT_EQ(plan.steps[0].support, SupportMode::kNone);
  // The leading (0, 0) is implied and the repeated point dropped.
  const std::vector<Vector3> p0 = {{0, 0, 0}, {-4, 0, 0}, {-4, 6, 0}};
  EXPECT_EQ(plan.steps[0].path, p0);
  EXPECT_DOUBLE_EQ(plan.steps[0].Length(), 10.0);
  EXPECT_EQ(plan.steps[0].At(7), Vector3(-4, 3, 0));
  // direction (2, 0) is normalised: distance 1.5 along +x.
  const std::vector<Vector3> p1 = {{0, 0, 0}, {1.5, 0, 0}};
  EXPECT_EQ(plan.steps[1].path, p1);
  EXPECT_EQ(plan.steps[1].support, SupportMode::kFull);
}

// clang-format off
const BadCase kPlanBadCases[] = {
  // JSON itself.
  {"syntax", "{\"cairn_plan\": 1,\n  \"steps\": [}", nullptr, "", "invalid JSON at line 2, column 13"},
  {"empty_file", "", nullptr, "", "invalid JSON at line 1"},
  {"overflow_to_inf", "{\"cairn_plan\": 1,\n \"dt\": 1e400}", nullptr, "", "line 2, column 12: number overflow parsing '1e400' (numbers must be finite)"},
  {"duplicate_key", "{\"cairn_plan\": 1, \"steps\": [], \"dt\": 1, \"dt\": 2}", nullptr, "dt", "duplicate key"},
  {"duplicate_step_key", "{\"cairn_plan\": 1, \"steps\": [{\"remove\": [\"C\"], \"remove\": [\"D\"]}]}", nullptr,
   "steps[0].remove", "duplicate key"},
  {"not_object", "[1, 2]", nullptr, "", "a plan must be a JSON object, not an array"},
  // Version.
  {"missing_version", nullptr, R"({"cairn_plan": null})", "cairn_plan",
   "required key is missing (the plan format version: 1)"},
  {"scene_version_key", nullptr, R"({"cairn_plan": null, "cairn": 1})", "cairn_plan", "required key is missing"},
  {"wrong_version", nullptr, R"({"cairn_plan": 2})", "cairn_plan", "unsupported format version 2"},
  {"version_string", nullptr, R"({"cairn_plan": "1"})", "cairn_plan", "not a string"},
  // Unknown keys, at every level.
  {"unknown_top", nullptr, R"({"gripper": "left"})", "gripper",
   "unknown key (expected one of: cairn_plan, mode, dt, speed, steps)"},
  {"unknown_step_key", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "speed": 2}]})",
   "steps[0] (\"C\").speed", "unknown key (expected one of: remove, grip, path, direction, distance, support, hold, hold_at_rest, props, props_at_rest)"},
  // Wrong types and values of the top level.
  {"mode_type", nullptr, R"({"mode": 1})", "mode", "must be a string, not a number"},
  {"mode_value", nullptr, R"({"mode": "build"})", "mode", "must be \"disassemble\" or \"assemble\", not \"build\""},
  {"dt_type", nullptr, R"({"dt": "1s"})", "dt", "must be a number, not a string"},
  {"dt_zero", nullptr, R"({"dt": 0})", "dt", "must be positive (got 0)"},
  {"speed_negative", nullptr, R"({"speed": -1})", "speed", "must be positive (got -1)"},
  {"missing_steps", nullptr, R"({"steps": null})", "steps", "required key is missing"},
  {"steps_type", nullptr, R"({"steps": {"remove": ["C"]}})", "steps", "must be an array, not an object"},
  {"empty_steps", nullptr, R"({"steps": []})", "steps", "must list at least one step"},
  {"step_type", nullptr, R"({"steps": ["C"]})", "steps[0]", "must be an object, not a string"},
  // Wrong types in a step.
  {"missing_remove", nullptr, R"({"steps": [{"path": [[0, 1]]}]})", "steps[0].remove", "required key is missing"},
  {"remove_type", nullptr, R"({"steps": [{"remove": "C", "path": [[0, 1]]}]})", "steps[0].remove",
   "must be an array, not a string"},
  {"remove_entry_type", nullptr, R"({"steps": [{"remove": ["C", 4], "path": [[0, 1]]}]})", "steps[0].remove[1]",
   "must be a string, not a number"},
  {"grip_type", nullptr, R"({"steps": [{"remove": ["C"], "grip": "C", "path": [[0, 1]]}]})", "steps[0] (\"C\").grip",
   "must be an array, not a string"},
  {"grip_empty", nullptr, R"({"steps": [{"remove": ["C"], "grip": [], "path": [[0, 1]]}]})", "steps[0] (\"C\").grip",
   "must name at least one part"},
  {"path_type", nullptr, R"({"steps": [{"remove": ["C"], "path": [0, 1]}]})", "steps[0] (\"C\").path[0]",
   "must be an array of 2 numbers [x, y], not a number"},
  {"path_point_size", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 0], [0, 1, 2]]}]})", "steps[0] (\"C\").path[1]",
   "must have 2 numbers [x, y]"},
  {"path_coordinate_type", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 0], [0, "up"]]}]})",
   "steps[0] (\"C\").path[1][1]", "must be a number, not a string"},
  {"direction_without_distance", nullptr, R"({"steps": [{"remove": ["C"], "direction": [0, 1]}]})",
   "steps[0] (\"C\").distance", "required key is missing (a straight path needs both direction and distance)"},
  {"distance_without_direction", nullptr, R"({"steps": [{"remove": ["C"], "distance": 2}]})",
   "steps[0] (\"C\").direction", "required key is missing"},
  {"direction_type", nullptr, R"({"steps": [{"remove": ["C"], "direction": "up", "distance": 2}]})",
   "steps[0] (\"C\").direction", "must be an array of 2 numbers"},
  {"distance_type", nullptr, R"({"steps": [{"remove": ["C"], "direction": [0, 1], "distance": [2]}]})",
   "steps[0] (\"C\").distance", "must be a number, not an array"},
  {"support_value", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "support": "half"}]})",
   "steps[0] (\"C\").support", "must be \"full\" or \"none\", not \"half\""},
  {"support_type", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "support": false}]})",
   "steps[0] (\"C\").support", "must be a string, not a boolean"},
  // Parts: names, fixed parts, tools, repeats.
  {"empty_remove", nullptr, R"({"steps": [{"remove": [], "path": [[0, 1]]}]})", "steps[0].remove",
   "must name at least one part"},
  {"unknown_part", nullptr, R"({"steps": [{"remove": ["C", "Z"], "path": [[0, 1]]}]})", "steps[0].remove[1]",
   "no part named 'Z'"},
  {"unknown_grip", nullptr, R"({"steps": [{"remove": ["C"], "grip": ["c"], "path": [[0, 1]]}]})", "steps[0] (\"C\").grip[0]",
   "no part named 'c'"},
  {"fixed_removed", nullptr, R"({"steps": [{"remove": ["E"], "path": [[0, 1]]}]})", "steps[0].remove[0]",
   "part 'E' is fixed: fixed parts never move"},
  {"fixed_gripped", nullptr, R"({"steps": [{"remove": ["C"], "grip": ["C", "E"], "path": [[0, 1]]}]})",
   "steps[0] (\"C\").grip[1]", "part 'E' is fixed: fixed parts never move"},
  {"tool_removed", nullptr, R"({"steps": [{"remove": ["C", "G"], "path": [[0, 1]]}]})", "steps[0].remove[1]",
   "part 'G' is a tool, not part of the assembly: grip it, do not remove it"},
  {"grip_not_removed_not_tool", nullptr, R"({"steps": [{"remove": ["C"], "grip": ["D"], "path": [[0, 1]]}]})",
   "steps[0] (\"C\").grip[0]", "part 'D' is neither in this step's remove nor a tool"},
  {"grip_twice", nullptr, R"({"steps": [{"remove": ["C"], "grip": ["G", "G"], "path": [[0, 1]]}]})",
   "steps[0] (\"C\").grip[1]", "names part 'G' twice (also steps[0].grip[0])"},
  {"removed_twice_in_step", nullptr, R"({"steps": [{"remove": ["C", "D", "C"], "path": [[0, 1]]}]})",
   "steps[0].remove[2]", "names part 'C' twice (also steps[0].remove[0])"},
  {"removed_in_two_steps", nullptr,
   R"({"steps": [{"remove": ["C"], "path": [[0, 1]]}, {"remove": ["D"], "path": [[0, 1]]}, {"remove": ["A", "C"], "path": [[0, 1]]}]})",
   "steps[2].remove[1]", "part 'C' is already removed by steps[0].remove[0]"},
  // Holds: parts of the assembly at that step, not moving, each once.
  {"hold_type", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "hold": "B"}]})",
   "steps[0] (\"C\").hold", "must be an array, not a string"},
  {"hold_unknown", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "hold": ["Z"]}]})",
   "steps[0] (\"C\").hold[0]", "no part named 'Z'"},
  {"hold_fixed", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "hold": ["E"]}]})",
   "steps[0] (\"C\").hold[0]", "part 'E' is fixed"},
  {"hold_tool", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "hold_at_rest": ["G"]}]})",
   "steps[0] (\"C\").hold_at_rest[0]", "part 'G' is a tool, not part of the assembly: it cannot be held in place"},
  {"hold_twice", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "hold": ["B", "B"]}]})",
   "steps[0] (\"C\").hold[1]", "names part 'B' twice"},
  {"hold_moving", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "hold": ["C"]}]})",
   "steps[0] (\"C\").hold[0]", "part 'C' moves in this step: it cannot be held in place while it moves"},
  {"hold_removed_earlier", nullptr,
   R"({"steps": [{"remove": ["C"], "path": [[0, 1]]}, {"remove": ["D"], "path": [[0, 1]], "hold_at_rest": ["A", "C"]}]})",
   "steps[1] (\"D\").hold_at_rest[1]", "part 'C' is not there to hold: it is removed by steps[0].remove[0]"},
  // Props: fixels the scene would accept, under parts there and not moving.
  {"props_type", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "props": [1]}]})",
   "steps[0] (\"C\").props[0]", "must be an object, not a number"},
  {"props_unknown_key", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "props": [{"part": "B", "point": [0, 1.5], "normal": [0, -1], "force": 1}]}]})",
   "steps[0] (\"C\").props[0].force", "unknown key (expected one of: part, point, normal)"},
  {"props_off_boundary", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "props": [{"part": "B", "point": [0, 9], "normal": [0, 1]}]}]})",
   "steps[0] (\"C\").props[0]", "(0, 9) is not on the boundary of part 'B'"},
  {"props_moving", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "props": [{"part": "C", "point": [-2, 1.5], "normal": [0, 1]}]}]})",
   "steps[0] (\"C\").props[0].part", "part 'C' moves in this step: it cannot be propped while it moves"},
  // Paths.
  {"both_forms", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 1]], "direction": [0, 1], "distance": 1}]})",
   "steps[0] (\"C\")", "has both path and direction with distance: give one of them"},
  {"neither_form", nullptr, R"({"steps": [{"remove": ["C"]}]})", "steps[0] (\"C\")",
   "has no path: give path, or direction and distance"},
  {"empty_path", nullptr, R"({"steps": [{"remove": ["C"], "path": []}]})", "steps[0] (\"C\").path",
   "must have at least one point"},
  {"zero_length_path", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 0], [0, 0], [0, 0]]}]})", "steps[0] (\"C\").path",
   "has zero length"},
  {"zero_length_single_point", nullptr, R"({"steps": [{"remove": ["C"], "path": [[0, 0]]}]})", "steps[0] (\"C\").path",
   "has zero length"},
  {"zero_direction", nullptr, R"({"steps": [{"remove": ["C"], "direction": [0, 0], "distance": 1}]})",
   "steps[0] (\"C\").direction", "must not be zero"},
  {"zero_distance", nullptr, R"({"steps": [{"remove": ["C"], "direction": [0, 1], "distance": 0}]})",
   "steps[0] (\"C\").distance", "must be positive (got 0)"},
  {"negative_distance", nullptr, R"({"steps": [{"remove": ["C"], "direction": [0, 1], "distance": -2}]})",
   "steps[0] (\"C\").distance", "must be positive (got -2)"},
};
// clang-format on

class BadPlan : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadPlan, NamesFilePathAndFault) {
  const BadCase& c = GetParam();
  const std::string text = CaseText(c, kPlanBase);
  const std::string file = WriteTemp(std::string("bad_plan_") + c.name + ".json", text);
  const Assembly scene = Scene();
  ExpectBadInput(c, text, file, [&](const std::string& f) { ReadPlan(f, scene); });
}

INSTANTIATE_TEST_SUITE_P(AllFaults, BadPlan, ::testing::ValuesIn(kPlanBadCases),
                         [](const auto& param) { return std::string(param.param.name); });

TEST(ReadPlan, BasePlanIsValid) {
  // The bad cases above fail for their own fault, not the base plan's.
  EXPECT_NO_THROW(ReadPlan(WriteTemp("plan_base.json", kPlanBase), Scene()));
}

TEST(ReadPlan, MissingFile) {
  try {
    ReadPlan("/nonexistent/plan.json", Scene());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/plan.json");
    EXPECT_EQ(e.json_path(), "");
    EXPECT_THAT(e.message(), HasSubstr("cannot open"));
  }
}

// A step is named by the parts it removes, `steps[0] ("B", "D")`,
// in faults the reader finds and those Plan::Create finds; a fault of the
// remove list itself is reported at it, the part named in the message.
TEST(ReadPlan, FaultsOfAStepNameItsParts) {
  const Assembly scene = Scene();
  struct Case {
    const char* text;
    const char* path;
    const char* phrase;
  };
  const Case cases[] = {
      {R"({"cairn_plan": 1, "steps": [{"remove": ["B", "D"], "direction": [0, 0], "distance": 1}]})",
       R"(steps[0] ("B", "D").direction)", "must not be zero"},
      {R"({"cairn_plan": 1, "steps": [{"remove": ["C"], "direction": [0, "up"], "distance": 1}]})",
       R"(steps[0] ("C").direction[1])", "must be a number"},
      {R"({"cairn_plan": 1, "steps": [{"remove": ["E"], "direction": [0, 1], "distance": 1}]})",
       "steps[0].remove[0]", "part 'E' is fixed"},
  };
  for (const Case& c : cases) {
    const std::string file = WriteTemp("plan_named_step.json", c.text);
    try {
      ReadPlan(file, scene);
      ADD_FAILURE() << "no error: " << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), c.path) << e.what();
      EXPECT_THAT(e.what(), HasSubstr(file + ": " + c.path + ": " + c.phrase));
    }
  }
}

TEST(ParsePlanJson, RejectsNonFiniteNumbersOfABuiltDocument) {
  // A document built in C++ (not parsed from text) can hold NaN and infinity.
  json doc = json::parse(kPlanBase);
  doc["dt"] = std::nan("");
  try {
    ParsePlanJson(doc, "memory.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "memory.json");
    EXPECT_EQ(e.json_path(), "dt");
    EXPECT_THAT(e.message(), HasSubstr("must be a finite number (got nan)"));
  }
  doc = json::parse(kPlanBase);
  doc["steps"][0]["path"][1][0] = -HUGE_VAL;
  try {
    ParsePlanJson(doc, "");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "steps[0] (\"C\").path[1][0]");
    EXPECT_THAT(e.message(), HasSubstr("must be a finite number (got -inf)"));
  }
}

}  // namespace
}  // namespace cairn

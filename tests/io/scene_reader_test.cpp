#include "cairn/io/scene_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cairn/core/error.h"
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

// The example of docs/scene-format.md.
constexpr const char* kDocExample = R"({
  "cairn": 1,
  "name": "two blocks",
  "gravity": [0, -9.81],
  "friction": 0.3,
  "friction_pairs": [{"parts": ["A", "table"], "mu": 0.05}],
  "tolerance": 1e-6,
  "parts": [
    {"name": "table", "fixed": true, "polygon": [[-5, -1], [5, -1], [5, 0], [-5, 0]]},
    {"name": "A", "density": 2.0, "polygon": [[0, 0], [2, 0], [2, 1], [0, 1]]},
    {"name": "B", "mass": 1.5, "box": {"min": [0, 1], "max": [1, 2]}}
  ],
  "fixtures": [{"part": "B", "point": [1, 1.5], "normal": [-1, 0]}]
})";

// A small valid scene the bad cases patch (RFC 7386 merge patch: a null
// removes a key, an array is replaced whole).
constexpr const char* kBase = R"({
  "cairn": 1,
  "parts": [
    {"name": "table", "fixed": true, "polygon": [[-5, -1], [5, -1], [5, 0], [-5, 0]]},
    {"name": "A", "polygon": [[0, 0], [2, 0], [2, 1], [0, 1]]},
    {"name": "B", "box": {"min": [0, 1], "max": [1, 2]}}
  ]
})";

// Writes `text` to a file named `name` in the test's temporary folder.
TEST(ReadScene, DocumentedExampleRoundTrips) {
  const Assembly a = ReadScene(WriteTemp("doc_example.json", kDocExample));
  EXPECT_EQ(a.name(), "two blocks");
  ASSERT_EQ(a.num_parts(), 3);
  EXPECT_EQ(a.part(0).name, "table");
  EXPECT_TRUE(a.part(0).fixed);
  EXPECT_FALSE(a.part(1).fixed);
  EXPECT_DOUBLE_EQ(a.part(1).mass, 4.0);  // density 2 × area 2
  EXPECT_DOUBLE_EQ(a.part(2).mass, 1.5);  // mass given
  // The box became the counter-clockwise square [0, 1] × [1, 2].
  const Polygon box = {{0, 1}, {1, 1}, {1, 2}, {0, 2}};
  EXPECT_EQ(a.part(2).polygon, box);
  EXPECT_TRUE(a.gravity().isApprox(Vector3(0, -9.81, 0)));
  EXPECT_DOUBLE_EQ(a.Friction(1, 0), 0.05);
  EXPECT_DOUBLE_EQ(a.Friction(0, 1), 0.05);
  EXPECT_DOUBLE_EQ(a.Friction(1, 2), 0.3);
  EXPECT_DOUBLE_EQ(a.length_tolerance(), 1e-6);
  ASSERT_EQ(a.fixtures().size(), 1u);
  EXPECT_EQ(a.fixtures()[0].part, 2);
  EXPECT_TRUE(a.fixtures()[0].point.isApprox(Vector3(1, 1.5, 0)));
  EXPECT_TRUE(a.fixtures()[0].normal.isApprox(Vector3(-1, 0, 0)));
}

TEST(ParseSceneJson, DefaultsAndIndices) {
  const AssemblyDef def = ParseSceneJson(json::parse(kBase), "base.json");
  EXPECT_EQ(def.name, "");
  EXPECT_FALSE(def.gravity.has_value());  // Assembly::Create defaults it by dimension
  EXPECT_EQ(def.friction, 0.0);
  EXPECT_EQ(def.tolerance, 0.0);  // scaled to the scene by Assembly::Create
  ASSERT_EQ(def.parts.size(), 3u);
  EXPECT_EQ(def.parts[1].name, "A");  // vector index = JSON index
  EXPECT_FALSE(def.parts[1].density.has_value());
  EXPECT_FALSE(def.parts[1].mass.has_value());
  EXPECT_TRUE(def.friction_pairs.empty());
  EXPECT_TRUE(def.fixtures.empty());

  const Assembly a = Assembly::Create(def, "base.json");
  EXPECT_TRUE(a.IsFrictionless());
  EXPECT_DOUBLE_EQ(a.part(1).mass, 2.0);  // default density 1
  // Bounding box of all parts: [-5, 5] × [-1, 2].
  EXPECT_NEAR(a.length_tolerance(), 1e-6 * std::hypot(10.0, 3.0), 1e-18);
}

TEST(ParseSceneJson, MassWinsOverDensity) {
  json doc = json::parse(kBase);
  doc["parts"][1]["density"] = 3.0;
  doc["parts"][1]["mass"] = 0.5;
  EXPECT_DOUBLE_EQ(Assembly::Create(ParseSceneJson(doc, "")).part(1).mass, 0.5);
}

TEST(ParseSceneJson, ClockwisePolygonIsNormalised) {
  json doc = json::parse(kBase);
  doc["parts"][1]["polygon"] = json::parse("[[0, 0], [0, 1], [2, 1], [2, 0]]");
  const Assembly a = Assembly::Create(ParseSceneJson(doc, ""));
  EXPECT_GT(SignedArea(a.part(1).polygon), 0);
  EXPECT_DOUBLE_EQ(a.part(1).area, 2.0);
}

TEST(ParseSceneJson, ToolFlag) {
  json doc = json::parse(kBase);
  doc["parts"].push_back(
      json::parse(R"({"name": "G", "tool": true, "box": {"min": [3, 0], "max": [4, 0.5]}})"));
  doc["parts"][1]["tool"] = false;
  const AssemblyDef def = ParseSceneJson(doc, "");
  ASSERT_EQ(def.parts.size(), 4u);
  EXPECT_FALSE(def.parts[0].tool);  // default
  EXPECT_FALSE(def.parts[1].tool);  // explicit false
  EXPECT_TRUE(def.parts[3].tool);
  const Assembly a = Assembly::Create(def);
  EXPECT_TRUE(a.part(3).tool);
  EXPECT_FALSE(a.part(2).tool);
  const Configuration config = Configuration::Assembled(a);
  EXPECT_EQ(config.present, (std::vector<bool>{true, true, true, false}));
}

TEST(ReadScene, EveryExampleSceneIsValid) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testing::SourcePath("examples"))) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW(ReadScene(entry.path().string())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 10);
}

// clang-format off
const BadCase kBadCases[] = {
  // JSON itself.
  {"syntax", "{\"cairn\": 1,\n  \"parts\": [}", nullptr, "", "invalid JSON at line 2, column 13"},
  {"trailing_comma", "{\"cairn\": 1,\n}", nullptr, "", "invalid JSON at line 2"},
  {"empty_file", "", nullptr, "", "invalid JSON at line 1"},
  {"overflow_to_inf", "{\"cairn\": 1,\n \"friction\": 1e400}", nullptr, "", "line 2, column 18: number overflow parsing '1e400' (numbers must be finite)"},
  {"duplicate_key", "{\"cairn\": 1, \"parts\": [], \"cairn\": 1}", nullptr, "cairn", "duplicate key"},
  {"duplicate_nested_key", "{\"cairn\": 1, \"parts\": [{\"name\": \"a\", \"name\": \"b\"}]}", nullptr,
   "parts[0].name", "duplicate key"},
  {"not_object", "[1, 2]", nullptr, "", "must be a JSON object, not an array"},
  // Version.
  {"missing_cairn", nullptr, R"({"cairn": null})", "cairn", "required key is missing"},
  {"wrong_version", nullptr, R"({"cairn": 2})", "cairn", "unsupported format version 2"},
  {"version_string", nullptr, R"({"cairn": "1"})", "cairn", "not a string"},
  // Unknown keys, at every level.
  {"unknown_top", nullptr, R"({"colour": "red"})", "colour", "unknown key"},
  {"unknown_part_key", nullptr, R"({"parts": [{"name": "A", "colour": 1, "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0] (\"A\").colour", "unknown key (expected one of: name, fixed, tool, density"},
  {"unknown_box_key", nullptr, R"({"parts": [{"name": "A", "box": {"min": [0, 0], "max": [1, 1], "centre": [0, 0]}}]})",
   "parts[0] (\"A\").box.centre", "unknown key"},
  {"unknown_pair_key", nullptr, R"({"friction_pairs": [{"parts": ["A", "B"], "mu": 0.1, "kind": 1}]})",
   "friction_pairs[0].kind", "unknown key"},
  {"unknown_fixture_key", nullptr, R"({"fixtures": [{"part": "B", "point": [1, 1.5], "normal": [-1, 0], "force": 1}]})",
   "fixtures[0].force", "unknown key"},
  // Wrong types.
  {"gravity_type", nullptr, R"({"gravity": "down"})", "gravity", "must be an array of 2 numbers [x, y], not a string"},
  {"gravity_3d", nullptr, R"({"gravity": [0, 0, -9.81]})", "gravity", "must have 2 numbers [x, y] in a 2-D scene, not 3"},
  {"friction_type", nullptr, R"({"friction": "high"})", "friction", "must be a number, not a string"},
  {"tolerance_type", nullptr, R"({"tolerance": true})", "tolerance", "must be a number, not a boolean"},
  {"name_type", nullptr, R"({"name": 7})", "name", "must be a string, not a number"},
  {"parts_type", nullptr, R"({"parts": {"name": "A"}})", "parts", "must be an array, not an object"},
  {"part_type", nullptr, R"({"parts": ["A"]})", "parts[0]", "must be an object, not a string"},
  {"part_name_type", nullptr, R"({"parts": [{"name": 5, "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0].name", "must be a string"},
  {"fixed_type", nullptr, R"({"parts": [{"name": "A", "fixed": "yes", "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0] (\"A\").fixed", "must be true or false, not a string"},
  {"tool_type", nullptr, R"({"parts": [{"name": "A", "tool": 1, "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0] (\"A\").tool", "must be true or false, not a number"},
  {"density_type", nullptr, R"({"parts": [{"name": "A", "density": [1], "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0] (\"A\").density", "must be a number, not an array"},
  {"polygon_type", nullptr, R"({"parts": [{"name": "A", "polygon": {"x": 1}}]})", "parts[0] (\"A\").polygon", "must be an array"},
  {"vertex_coordinate_type", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, "0"], [0, 1]]}]})",
   "parts[0] (\"A\").polygon[1][1]", "must be a number, not a string"},
  {"vertex_size", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, 0, 0], [0, 1]]}]})",
   "parts[0] (\"A\").polygon[1]", "must have 2 numbers"},
  {"box_type", nullptr, R"({"parts": [{"name": "A", "box": [0, 0, 1, 1]}]})", "parts[0] (\"A\").box", "must be an object"},
  {"pair_names_type", nullptr, R"({"friction_pairs": [{"parts": ["A", 2], "mu": 0.1}]})",
   "friction_pairs[0].parts[1]", "must be a string"},
  {"pair_three_names", nullptr, R"({"friction_pairs": [{"parts": ["A", "B", "table"], "mu": 0.1}]})",
   "friction_pairs[0].parts", "must name exactly 2 parts, not 3"},
  {"fixture_point_type", nullptr, R"({"fixtures": [{"part": "B", "point": "corner", "normal": [-1, 0]}]})",
   "fixtures[0].point", "must be an array of 2 numbers"},
  // Missing fields.
  {"missing_parts", nullptr, R"({"parts": null})", "parts", "required key is missing"},
  {"empty_parts", nullptr, R"({"parts": []})", "parts", "at least one part"},
  {"missing_part_name", nullptr, R"({"parts": [{"polygon": [[0, 0], [1, 0], [0, 1]]}]})", "parts[0].name",
   "required key is missing"},
  {"missing_shape", nullptr, R"({"parts": [{"name": "A"}]})", "parts[0] (\"A\")", "missing a shape"},
  {"two_shapes", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, 0], [0, 1]], "box": {"min": [0, 0], "max": [1, 1]}}]})",
   "parts[0] (\"A\").box", "exactly one shape"},
  {"missing_box_max", nullptr, R"({"parts": [{"name": "A", "box": {"min": [0, 0]}}]})", "parts[0] (\"A\").box.max",
   "required key is missing"},
  {"missing_pair_mu", nullptr, R"({"friction_pairs": [{"parts": ["A", "B"]}]})", "friction_pairs[0].mu",
   "required key is missing"},
  {"missing_fixture_normal", nullptr, R"({"fixtures": [{"part": "B", "point": [1, 1.5]}]})",
   "fixtures[0].normal", "required key is missing"},
  // Numbers out of range.
  {"tolerance_zero", nullptr, R"({"tolerance": 0})", "tolerance", "must be positive"},
  {"overlap_allowance_negative", nullptr, R"({"overlap_allowance": -1e-5})", "overlap_allowance",
   "must not be negative (got -1e-05)"},
  {"overlap_allowance_type", nullptr, R"({"overlap_allowance": "1e-5"})", "overlap_allowance",
   "must be a number"},
  {"negative_friction", nullptr, R"({"friction": -0.1})", "friction", "must not be negative"},
  {"negative_pair_mu", nullptr, R"({"friction_pairs": [{"parts": ["A", "B"], "mu": -1}]})",
   "friction_pairs[0].mu", "must not be negative"},
  {"negative_mass", nullptr, R"({"parts": [{"name": "A", "mass": -2, "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0] (\"A\").mass", "must be positive (got -2)"},
  {"zero_density", nullptr, R"({"parts": [{"name": "A", "density": 0, "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0] (\"A\").density", "must be positive (got 0)"},
  {"inverted_box", nullptr, R"({"parts": [{"name": "A", "box": {"min": [0, 1], "max": [1, 0]}}]})",
   "parts[0] (\"A\").box", "min (0, 1) must be less than max (1, 0)"},
  // Names.
  {"duplicate_name", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, 0], [0, 1]]}, {"name": "A", "polygon": [[5, 0], [6, 0], [5, 1]]}]})",
   "parts[1].name", "duplicate part name 'A' (also parts[0])"},
  {"fixed_tool", nullptr, R"({"parts": [{"name": "G", "fixed": true, "tool": true, "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[0] (\"G\").tool", "part 'G' cannot be both fixed and a tool"},
  {"tool_overlaps", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [2, 0], [2, 1], [0, 1]]}, {"name": "G", "tool": true, "box": {"min": [1, 0.5], "max": [3, 2]}}]})",
   "parts[1] (\"G\")", "part 'G' overlaps part 'A' (parts[0])"},
  {"empty_name", nullptr, R"({"parts": [{"name": "", "polygon": [[0, 0], [1, 0], [0, 1]]}]})", "parts[0].name",
   "must not be empty"},
  {"pair_unknown_part", nullptr, R"({"friction_pairs": [{"parts": ["A", "C"], "mu": 0.1}]})",
   "friction_pairs[0].parts[1]", "no part named 'C'"},
  {"pair_same_part_twice", nullptr, R"({"friction_pairs": [{"parts": ["A", "A"], "mu": 0.1}]})",
   "friction_pairs[0].parts[1]", "names part 'A' twice"},
  {"pair_repeated", nullptr, R"({"friction_pairs": [{"parts": ["A", "B"], "mu": 0.1}, {"parts": ["B", "A"], "mu": 0.2}]})",
   "friction_pairs[1]", "repeats the pair"},
  {"fixture_unknown_part", nullptr, R"({"fixtures": [{"part": "Z", "point": [1, 1.5], "normal": [-1, 0]}]})",
   "fixtures[0].part", "no part named 'Z'"},
  // Geometry.
  {"two_vertices", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, 0]]}]})", "parts[0] (\"A\").polygon",
   "has 2 vertices; a polygon needs at least 3"},
  {"zero_area", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, 0], [3, 0]]}]})", "parts[0] (\"A\").polygon",
   "has zero area"},
  {"bow_tie", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [2, 2], [2, 0], [0, 2]]}]})",
   "parts[0] (\"A\").polygon", "self-intersecting: edge 0 crosses edge 2"},
  {"touching_edges", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [4, 0], [4, 2], [2, 0], [0, 2]]}]})",
   "parts[0] (\"A\").polygon", "self-intersecting: edge 0 touches edge 2"},
  {"repeated_vertex", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [2, 0], [2, 2], [0, 2], [2, 0]]}]})",
   "parts[0] (\"A\").polygon[4]", "self-intersecting: vertex 4 repeats vertex 1"},
  {"fold_back", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [4, 0], [4, 2], [4, 1], [0, 2]]}]})",
   "parts[0] (\"A\").polygon", "self-intersecting: edges 1 and 2 fold back onto each other"},
  {"overlap", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [2, 0], [2, 1], [0, 1]]}, {"name": "B", "box": {"min": [1, 0.5], "max": [3, 2]}}]})",
   "parts[1] (\"B\")", "part 'B' overlaps part 'A' (parts[0]) by more than the tolerance"},
  // Fixtures.
  {"fixture_off_part", nullptr, R"({"fixtures": [{"part": "B", "point": [1.5, 1.5], "normal": [-1, 0]}]})",
   "fixtures[0].point", "(1.5, 1.5) is not on the boundary of part 'B' (distance 0.5"},
  {"fixture_inside_part", nullptr, R"({"fixtures": [{"part": "B", "point": [0.5, 1.5], "normal": [-1, 0]}]})",
   "fixtures[0].point", "not on the boundary"},
  {"fixture_zero_normal", nullptr, R"({"fixtures": [{"part": "B", "point": [1, 1.5], "normal": [0, 0]}]})",
   "fixtures[0].normal", "must not be zero"},
  {"fixture_normal_out", nullptr, R"({"fixtures": [{"part": "B", "point": [1, 1.5], "normal": [1, 0]}]})",
   "fixtures[0].normal", "points out of part 'B'"},
  // Dimension.
  {"mixed_box_3d", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, 0], [0, 1]]}, {"name": "B", "box": {"min": [3, 0, 0], "max": [4, 1, 1]}}]})",
   "parts[1] (\"B\").box", "mixes 2-D and 3-D shapes"},
  {"mixed_polyhedron", nullptr, R"({"parts": [{"name": "A", "polygon": [[0, 0], [1, 0], [0, 1]]}, {"name": "B", "polyhedron": {}}]})",
   "parts[1] (\"B\").polyhedron", "mixes 2-D and 3-D shapes"},
  // 3-D scenes (the base's 2-D gravity and fixtures taken away).
  {"box_3d_inverted", nullptr, R"({"parts": [{"name": "A", "box": {"min": [0, 0, 0], "max": [1, 1, -1]}}]})",
   "parts[0] (\"A\").box", "min (0, 0, 0) must be less than max (1, 1, -1) in every coordinate"},
  {"gravity_2d_in_3d", nullptr, R"({"gravity": [0, -9.81], "parts": [{"name": "A", "box": {"min": [0, 0, 0], "max": [1, 1, 1]}}]})",
   "gravity", "must have 3 numbers [x, y, z] in a 3-D scene, not 2"},
  {"fixture_2d_in_3d", nullptr, R"({"fixtures": [{"part": "B", "point": [1, 1.5], "normal": [-1, 0]}], "parts": [{"name": "B", "box": {"min": [0, 0, 0], "max": [1, 1, 1]}}]})",
   "fixtures[0].point", "must have 3 numbers [x, y, z] in a 3-D scene, not 2"},
  {"polyhedron_few_vertices", nullptr, R"({"parts": [{"name": "A", "polyhedron": {"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "faces": [[0, 1, 2]]}}]})",
   "parts[0] (\"A\").polyhedron.vertices", "at least 4 vertices, not 3"},
  {"polyhedron_face_index", nullptr, R"({"parts": [{"name": "A", "polyhedron": {"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], "faces": [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 4]]}}]})",
   "parts[0] (\"A\").polyhedron.faces[3][2]", "must be a vertex index from 0 to 3, not 4"},
  {"polyhedron_three_faces", nullptr, R"({"parts": [{"name": "A", "polyhedron": {"vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], "faces": [[0, 2, 1], [0, 1, 3], [1, 2, 3]]}}]})",
   "parts[0] (\"A\").polyhedron", "a polyhedron needs at least 4 faces (got 3)"},
  {"polyhedron_open", nullptr, R"({"parts": [{"name": "A", "polyhedron": {"vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], "faces": [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]]}}]})",
   "parts[0] (\"A\").polyhedron", "the surface is open: edge"},
  {"mesh_missing", nullptr, R"({"parts": [{"name": "A", "mesh": "no_such_part.obj"}]})",
   "parts[0] (\"A\").mesh", "cannot read mesh"},
  {"polygon_in_3d", nullptr, R"({"parts": [{"name": "A", "box": {"min": [0, 0, 0], "max": [1, 1, 1]}}, {"name": "B", "polygon": [[0, 0], [1, 0], [0, 1]]}]})",
   "parts[1] (\"B\").polygon", "mixes 2-D and 3-D shapes"},
  {"friction_directions_2d", nullptr, R"({"friction_directions": 8})",
   "friction_directions", "applies to 3-D scenes only"},
  {"friction_directions_few", nullptr, R"({"friction_directions": 2, "parts": [{"name": "A", "box": {"min": [0, 0, 0], "max": [1, 1, 1]}}]})",
   "friction_directions", "must be from 3 to 64 (got 2)"},
};
// clang-format on

class BadScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScene, NamesFilePathAndFault) {
  const BadCase& c = GetParam();
  const std::string text = CaseText(c, kBase);
  const std::string file = WriteTemp(std::string("bad_") + c.name + ".json", text);
  ExpectBadInput(c, text, file, [](const std::string& f) { ReadScene(f); });
}

INSTANTIATE_TEST_SUITE_P(AllFaults, BadScene, ::testing::ValuesIn(kBadCases),
                         [](const auto& param) { return std::string(param.param.name); });

TEST(ReadScene, MissingFile) {
  try {
    ReadScene("/nonexistent/scene.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "/nonexistent/scene.json");
    EXPECT_THAT(e.message(), HasSubstr("cannot open"));
  }
}

TEST(ParseSceneJson, RejectsNonFiniteNumbersOfABuiltDocument) {
  // A document built in C++ (not parsed from text) can hold NaN and infinity.
  json doc = json::parse(kBase);
  doc["friction"] = std::nan("");
  EXPECT_THROW(
      {
        try {
          ParseSceneJson(doc, "");
        } catch (const InputError& e) {
          EXPECT_EQ(e.json_path(), "friction");
          EXPECT_THAT(e.message(), HasSubstr("finite"));
          throw;
        }
      },
      InputError);
  doc = json::parse(kBase);
  doc["parts"][1]["polygon"][2][0] = HUGE_VAL;
  try {
    ParseSceneJson(doc, "");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "parts[1] (\"A\").polygon[2][0]");
    EXPECT_THAT(e.message(), HasSubstr("must be a finite number (got inf)"));
  }
}

// A fault inside a part names the part after its JSON path,
// `parts[1] ("A").polygon`, whether the reader or Assembly::Create finds it.
TEST(ReadScene, FaultsInsideAPartNameThePart) {
  const std::string table =
      R"({"name": "E", "fixed": true, "box": {"min": [-2, -1], "max": [2, 0]}})";
  // A bow-tie (Assembly::Create's fault) and a bad coordinate (the reader's).
  const std::string bow_tie = R"({"cairn": 1, "parts": [)" + table +
                              R"(, {"name": "A", "polygon": [[0, 0], [1, 1], [1, 0], [0, 1]]}]})";
  const std::string bad_vertex = R"({"cairn": 1, "parts": [)" + table +
                                 R"(, {"name": "A", "polygon": [[0, 0], [1, "x"], [0, 1]]}]})";
  for (const auto& [text, path] :
       {std::pair{bow_tie, std::string("parts[1] (\"A\").polygon")},
        std::pair{bad_vertex, std::string("parts[1] (\"A\").polygon[1][1]")}}) {
    const std::string file = WriteTemp("scene_named_part.json", text);
    try {
      ReadScene(file);
      ADD_FAILURE() << "no error: " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), path);
      EXPECT_THAT(e.what(), HasSubstr(file + ": " + path + ": "));
    }
  }
}

// A name that is itself the fault is not shown as the part's name; a name
// with quotes and a newline is escaped as JSON escapes it, so the message
// stays on one line.
TEST(ReadScene, NamesAreEscapedAndNeverInvented) {
  const std::string bad_name =
      WriteTemp("scene_bad_name.json",
                R"({"cairn": 1, "parts": [{"name": 7, "polygon": [[0, 0], [1, 0], [0, 1]]}]})");
  try {
    ReadScene(bad_name);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), "parts[0].name");
  }
  const std::string odd = WriteTemp("scene_odd_name.json", R"({"cairn": 1, "parts": [
      {"name": "E", "fixed": true, "box": {"min": [-2, -1], "max": [2, 0]}},
      {"name": "say \"hi\"\nnow\\", "polygon": [[0, 0], [1, 1], [1, 0], [0, 1]]}]})");
  try {
    ReadScene(odd);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.json_path(), R"(parts[1] ("say \"hi\"\nnow\\").polygon)");
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(ParseSceneJson, NamesTheFileGiven) {
  try {
    ParseSceneJson(json::parse(R"({"cairn": 1, "parts": 3})"), "memory.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "memory.json");
    EXPECT_EQ(e.json_path(), "parts");
  }
}

// The files of examples/bad/, read through ReadScene.
struct BadFile {
  const char* file;
  const char* path;
  const char* phrase;
};

void PrintTo(const BadFile& c, std::ostream* os) { *os << c.file; }

class BadExampleFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(BadExampleFile, ErrorNamesTheFile) {
  const BadFile& c = GetParam();
  const std::string file = testing::ExamplePath(std::string("bad/") + c.file);
  try {
    ReadScene(file);
    ADD_FAILURE() << "no error reading " << file;
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr(c.file));
    EXPECT_EQ(e.json_path(), c.path) << e.what();
    EXPECT_THAT(e.message(), HasSubstr(c.phrase)) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    ExamplesBad, BadExampleFile,
    ::testing::Values(
        BadFile{"syntax_error.json", "", "invalid JSON at line 6, column 5"},
        BadFile{"self_intersecting.json", "parts[1] (\"bow-tie\").polygon",
                "self-intersecting: edge 1 crosses edge 3"},
        BadFile{"overlapping_parts.json", "parts[2] (\"B\")",
                "part 'B' overlaps part 'A' (parts[1])"},
        BadFile{"fixture_off_part.json", "fixtures[0].point", "not on the boundary of part 'B'"},
        BadFile{"mixed_dimensions.json", "parts[1] (\"cube\").box", "mixes 2-D and 3-D shapes"}),
    [](const auto& param) {
      std::string name = param.param.file;
      return name.substr(0, name.find('.'));
    });

}  // namespace
}  // namespace cairn

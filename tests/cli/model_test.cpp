// `cairn check`, `cairn simulate` and `cairn convert` on COMPAS assemblies
// run as a user runs them: the real binary, its stdout, stderr and
// exit code. The shared files are read in place from ../shared/datasets; a
// test that needs one skips, saying so, when it is absent. The expected
// verdicts are physics with known answers (../shared/datasets/*/README.md):
// analytic ones, the published CRA results, or statics checked independently.
#include "cairn/app/model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cairn/io/compas_reader.h"
#include "cairn/mechanics/static_equilibrium.h"
#include "cairn/stability/analyze.h"
#include "cli/cli_run.h"
#include "test_paths.h"

namespace cairn {
namespace {

using nlohmann::json;
using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;
using ::testing::HasSubstr;

// The path of a shared dataset file, or "" when it is absent.
std::string Shared(const std::string& rel) {
  const std::string dir = testing::SharedDir();
  if (dir.empty()) return "";
  const std::string path = dir + "/datasets/" + rel;
  return std::filesystem::is_regular_file(path) ? path : std::string();
}

#define SHARED_OR_SKIP(var, rel)                                                            \
  const std::string var = Shared(rel);                                                      \
  if (var.empty()) {                                                                        \
    GTEST_SKIP() << "shared/datasets/" << (rel) << " not found: skipping this COMPAS test"; \
  }

// A file in the test's temporary folder, removed first. The process id keeps
// tests run in parallel (ctest -j, two builds at once) off each other's files.
std::string TempPath(const std::string& name) {
  const std::string path =
      ::testing::TempDir() + "cairn_compas_" + std::to_string(::getpid()) + "_" + name;
  std::filesystem::remove(path);
  return path;
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

// The JSON document a command printed (the whole of stdout).
json Doc(const CliRun& r) {
  try {
    return json::parse(r.out);
  } catch (const json::exception& e) {
    ADD_FAILURE() << "stdout is not one JSON document (" << e.what() << "):\n"
                  << r.out.substr(0, 300);
    return json::object();
  }
}

// `cairn check FILE --format compas --friction MU EXTRA --json`.
CliRun CheckCompas(const std::string& file, double mu, const std::string& extra = "") {
  return Cairn("check " + file + " --format compas --friction " + std::to_string(mu) + " " + extra +
               " --json");
}

// The sum over contacts of the force (normal and friction) on part `a` from
// the others, in 3-D.
Vector3 ForceOn(const json& doc, const std::string& a) {
  Vector3 f = Vector3::Zero();
  for (const json& c : doc["contacts"]) {
    const double sign = c["parts"][0] == a ? 1 : c["parts"][1] == a ? -1 : 0;
    for (int k = 0; k < 3; ++k) {
      f[k] += sign * (c["normal_force"].get<double>() * c["normal"][k].get<double>() +
                      c["friction_force"][k].get<double>());
    }
  }
  return f;
}

// Every free block balanced by the reported contact forces: their sum on it
// is its weight, 9.81 × mass, straight up (COMPAS gravity is −z). The forces
// are summed in one pass over the contacts (ForceOn per part would read the
// document parts × contacts times: a minute on the Armadillo vault's 399
// blocks and 5031 contacts in the sanitized build).
void ExpectEveryBlockBalanced(const json& doc) {
  std::map<std::string, Vector3> force;
  for (const json& c : doc["contacts"]) {
    Vector3 on_first;
    for (int k = 0; k < 3; ++k)
      on_first[k] = c["normal_force"].get<double>() * c["normal"][k].get<double>() +
                    c["friction_force"][k].get<double>();
    const std::string a = c["parts"][0], b = c["parts"][1];
    force.try_emplace(a, Vector3::Zero()).first->second += on_first;
    force.try_emplace(b, Vector3::Zero()).first->second -= on_first;
  }
  for (const json& p : doc["parts"]) {
    if (p["fixed"]) continue;
    const auto it = force.find(p["name"]);
    const Vector3 f = it == force.end() ? Vector3::Zero() : it->second;
    const double w = 9.81 * p["mass"].get<double>();
    EXPECT_NEAR(f.z(), w, 1e-6 * w) << p["name"];
    EXPECT_NEAR(f.head<2>().norm(), 0, 1e-6 * w) << p["name"];
  }
}

double MassOf(const json& doc, const std::string& name) {
  for (const json& p : doc["parts"])
    if (p["name"] == name) return p["mass"].get<double>();
  ADD_FAILURE() << "no part " << name;
  return 0;
}

// ---- Verdicts ---------------------------------------------------------------

// A unit cube on a fixed unit cube: the single interface carries the weight
// (density 1, volume 1: 9.81), split over the corners of the face patch.
TEST(CompasCheck, TwoBlocksStand) {
  SHARED_OR_SKIP(file, "compas_assembly/two-blocks_assembly.json");
  const CliRun r = CheckCompas(file, 0.84);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(r.err, "");
  const json doc = Doc(r);
  EXPECT_EQ(doc["verdict"], "stable");
  EXPECT_EQ(doc["static_equilibrium"], true);
  EXPECT_EQ(doc["weakly_stable"], false);
  EXPECT_EQ(doc["formulation"], "stewart-trinkle");
  EXPECT_EQ(doc["dimension"], 3);
  EXPECT_EQ(doc["contacts"].size(), 4u);
  EXPECT_NEAR(MassOf(doc, "1"), 1.0, 1e-12);
  EXPECT_TRUE(ForceOn(doc, "1").isApprox(Vector3(0, 0, 9.81), 1e-9)) << ForceOn(doc, "1");
  // The summary says so too.
  const CliRun text = Cairn("check " + file + " --format compas --friction 0.84");
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_THAT(text.out, HasSubstr("STABLE"));
}

// Three boxes of different sizes, each on the one below, block 0 the support
// (the compas_cra example sets it; the file stores no is_support): they stand
// and each interface carries the weight above it. Without a support all fall.
TEST(CompasCheck, CubesStandOnTheirSupport) {
  SHARED_OR_SKIP(file, "compas_cra/cubes.json");
  const CliRun r = CheckCompas(file, 0.84, "--supports 0");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const json doc = Doc(r);
  EXPECT_EQ(doc["verdict"], "stable");
  EXPECT_EQ(doc["static_equilibrium"], true);
  const double g = 9.81, m1 = MassOf(doc, "1"), m2 = MassOf(doc, "2");
  EXPECT_NEAR(m2, (0.7699 + 0.8619) * (0.6947 + 0.7146) * 1.3, 1e-3);
  EXPECT_TRUE(ForceOn(doc, "2").isApprox(Vector3(0, 0, m2 * g), 1e-9));
  EXPECT_TRUE(ForceOn(doc, "1").isApprox(Vector3(0, 0, m1 * g), 1e-9));

  const CliRun free = CheckCompas(file, 0.84);
  EXPECT_EQ(free.exit_code, 1);
  EXPECT_EQ(Doc(free)["moving"], json({"0", "1", "2"}));
}

// Ten unit cubes, each shifted 0.13 in x from the one below, block 0 fixed.
// The m blocks above an interface have their centre of mass 0.13 (m + 1) / 2
// beyond the centre of the block below, which holds them iff that is at most
// 0.5: m ≤ 6. So the whole stack tips at its lowest interfaces; with the top
// 3 taken away (6 blocks on block 0) it stands, with only the top 2 it does
// not.
TEST(CompasCheck, LeaningStackFallsAndStandsWithoutItsTopThree) {
  SHARED_OR_SKIP(file, "compas_assembly/stack_assembly.json");
  const CliRun all = CheckCompas(file, 0.84);
  ASSERT_EQ(all.exit_code, 1) << all.err << all.out;
  const json doc = Doc(all);
  EXPECT_EQ(doc["verdict"], "unstable");
  EXPECT_EQ(doc["static_equilibrium"], false);
  EXPECT_EQ(doc["weakly_stable"], false);
  EXPECT_EQ(doc["moving"], json({"1", "2", "3", "4", "5", "6", "7", "8", "9"}));

  const CliRun seven = CheckCompas(file, 0.84, "--without 7,8,9");
  ASSERT_EQ(seven.exit_code, 0) << seven.err << seven.out;
  const json d7 = Doc(seven);
  EXPECT_EQ(d7["verdict"], "stable");
  EXPECT_EQ(d7["static_equilibrium"], true);
  EXPECT_EQ(d7["without"], json({"7", "8", "9"}));

  const CliRun eight = CheckCompas(file, 0.84, "--without 8,9");
  EXPECT_EQ(eight.exit_code, 1) << eight.err;
  EXPECT_EQ(Doc(eight)["static_equilibrium"], false);
}

// The 30-voussoir arch (the 2 springers fixed): our independent static check
// needs μ ≥ 0.0845, so it stands at 0.84 and 0.1 and falls at 0.05 and
// without friction (Baraff's model then).
TEST(CompasCheck, ArchStandsWithEnoughFriction) {
  SHARED_OR_SKIP(file, "compas_assembly/arch_assembly.json");
  const CliRun r = CheckCompas(file, 0.84);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const json doc = Doc(r);
  EXPECT_EQ(doc["static_equilibrium"], true);
  EXPECT_EQ(doc["components"].size(), 1u);
  EXPECT_EQ(doc["components"][0]["parts"].size(), 28u);
  EXPECT_EQ(Cairn("check " + file + " --format compas --friction 0.1").exit_code, 0);
  const CliRun low = CheckCompas(file, 0.05);
  EXPECT_EQ(low.exit_code, 1);
  EXPECT_EQ(Doc(low)["static_equilibrium"], false);
  const CliRun none = CheckCompas(file, 0);
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_EQ(Doc(none)["formulation"], "baraff");
}

// The 52-block running-bond wall (10 first-course blocks fixed): horizontal
// bed joints only, so it stands at μ = 0.84 and even without friction.
TEST(CompasCheck, WallStands) {
  SHARED_OR_SKIP(file, "compas_assembly/wall_assembly.json");
  const CliRun r = CheckCompas(file, 0.84);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(Doc(r)["static_equilibrium"], true);
  const CliRun none = CheckCompas(file, 0);
  EXPECT_EQ(none.exit_code, 0) << none.err;
  EXPECT_EQ(Doc(none)["formulation"], "baraff");
}

// The 184-block cross vault (4 corners fixed) stands at μ = 0.84 (stored RBE
// result, and our LP). The static equilibrium is itself a solution of the LCP
// with every block at rest, and the report says that it decided the verdict
// (`decided_by`, `rest_solution`). Lemke's method is not run on its
// 14 772-variable Stewart–Trinkle LCP (it needs about r = 1080 pivots, more
// than its work budget; before the budget it ended on a secondary ray after
// 732). Only friction holds a vault's voussoirs (no frictionless equilibrium):
// rest is possible, not certified as guaranteed.
TEST(CompasCheck, CrossVaultStands) {
  SHARED_OR_SKIP(file, "compas_assembly/crossvault_assembly.json");
  const CliRun r = CheckCompas(file, 0.84);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out.substr(0, 2000);
  const json doc = Doc(r);
  EXPECT_EQ(doc["verdict"], "stable");
  EXPECT_EQ(doc["static_equilibrium"], true);
  EXPECT_EQ(doc["weakly_stable"], false);
  EXPECT_EQ(doc["moving"], json::array());
  ASSERT_EQ(doc["components"].size(), 1u);
  const json& c = doc["components"][0];
  EXPECT_EQ(c["parts"].size(), 180u);
  EXPECT_EQ(c["status"], "solved");
  EXPECT_EQ(c["rest_solution"], true);
  EXPECT_EQ(c["decided_by"], "equilibrium");
  EXPECT_EQ(c["frictionless_equilibrium"], false);
  EXPECT_EQ(doc["stability"], "not certified");
  EXPECT_THAT(c["message"].get<std::string>(), HasSubstr("Lemke's method not run"));
  EXPECT_LE(c["residual"].get<double>(), 1e-8);
  ExpectEveryBlockBalanced(doc);
}

// The same through the library (what `cairn check` computes without the
// equilibrium LP asked for): the fallback applies there too.
TEST(CompasLibrary, CrossVaultStandsByTheLcp) {
  SHARED_OR_SKIP(file, "compas_assembly/crossvault_assembly.json");
  CompasOptions options;
  options.friction = 0.84;
  const Assembly assembly = ReadCompasScene(file, options);
  EXPECT_EQ(assembly.num_parts(), 184);
  const StabilityResult result =
      AnalyzeConfiguration(assembly, Configuration::Assembled(assembly), StabilityOptions{});
  EXPECT_EQ(result.verdict, Verdict::kStable) << result.diagnostics;
  EXPECT_GT(result.contacts.size(), 2000u);
  ASSERT_EQ(result.components.size(), 1u);
  EXPECT_TRUE(result.components[0].rest_solution);
}

// ---- Jamming: blocks held only by a squeeze ---------------------------------

// The H frame: a crossbar between two fixed posts, touching only their
// vertical faces. Friction could hold it if something squeezed it (the static
// LP is feasible), but nothing does: it slides down. Weakly stable.
TEST(CompasCheck, HFrameIsHeldOnlyByJamming) {
  SHARED_OR_SKIP(file, "compas_cra/H.json");
  const CliRun r = CheckCompas(file, 0.84, "--supports 0,1");
  ASSERT_EQ(r.exit_code, 1) << r.err << r.out;
  const json doc = Doc(r);
  EXPECT_EQ(doc["verdict"], "unstable");
  EXPECT_EQ(doc["static_equilibrium"], true);
  EXPECT_EQ(doc["weakly_stable"], true);
  EXPECT_EQ(doc["stability"], "weak");  // rest possible, motion found: jamming
  EXPECT_EQ(doc["moving"], json({"2"}));
  EXPECT_EQ(doc["loaded_from_rest"], "gives way");
  const CliRun text = Cairn("check " + file + " --format compas --friction 0.84 --supports 0,1");
  EXPECT_THAT(text.out, HasSubstr("WEAKLY STABLE"));
  EXPECT_THAT(text.out, HasSubstr("falls: an equilibrium exists, but loaded from rest on "
                                  "compliant contacts 2 gives way"));
}

// The A frame: the crossbar's sides face outward and up, so moving down opens
// both interfaces and it falls. The static LP is feasible iff μ ≥ tan 30° ≈
// 0.577: weakly stable at 0.84, plainly unstable at 0.5.
TEST(CompasCheck, AFrameIsHeldOnlyByJammingWithEnoughFriction) {
  SHARED_OR_SKIP(file, "compas_cra/A.json");
  const CliRun r = CheckCompas(file, 0.84, "--supports 0,1");
  ASSERT_EQ(r.exit_code, 1) << r.err << r.out;
  const json doc = Doc(r);
  EXPECT_EQ(doc["static_equilibrium"], true);
  EXPECT_EQ(doc["weakly_stable"], true);
  EXPECT_EQ(doc["moving"], json({"2"}));
  const CliRun low = CheckCompas(file, 0.5, "--supports 0,1");
  ASSERT_EQ(low.exit_code, 1) << low.err;
  EXPECT_EQ(Doc(low)["static_equilibrium"], false);
  EXPECT_EQ(Doc(low)["weakly_stable"], false);
}

// The V-notch wedges, type-a … type-d (2 fixed blocks and a wedge; a, b: V
// faces 60° from horizontal; c, d: 30°), at μ = 0.84 (friction angle 40°).
// The example script turns the assembly about +y; --gravity turns gravity the
// other way instead: (0, 0, 9.81) is the assembly upside down, (9.81, 0, 0)
// turned by 90°.
struct WedgeCase {
  const char* file;
  const char* gravity;  // "" : upright
  int exit_code;
  bool static_equilibrium;
  bool weakly_stable;
};

void PrintTo(const WedgeCase& c, std::ostream* os) { *os << c.file << " g=" << c.gravity; }

class Wedges : public ::testing::TestWithParam<WedgeCase> {};

TEST_P(Wedges, Verdict) {
  const WedgeCase& c = GetParam();
  SHARED_OR_SKIP(file, std::string("compas_cra/") + c.file);
  std::string extra = "--supports 0,1";
  if (*c.gravity) extra += std::string(" --gravity=") + c.gravity;
  const CliRun r = CheckCompas(file, 0.84, extra);
  ASSERT_EQ(r.exit_code, c.exit_code) << r.err << r.out.substr(0, 1500);
  const json doc = Doc(r);
  EXPECT_EQ(doc["static_equilibrium"], c.static_equilibrium);
  EXPECT_EQ(doc["weakly_stable"], c.weakly_stable);
  if (c.exit_code == 1) {
    EXPECT_EQ(doc["moving"], json({"2"}));
  }
}

INSTANTIATE_TEST_SUITE_P(
    CompasCra, Wedges,
    ::testing::Values(
        // Upright the wedge sits in the V: held by both faces, no jamming.
        WedgeCase{"type-a.json", "", 0, true, false}, WedgeCase{"type-b.json", "", 0, true, false},
        WedgeCase{"type-c.json", "", 0, true, false}, WedgeCase{"type-d.json", "", 0, true, false},
        // Upside down it drops out. In the 60° V (a, b: less than twice the
        // friction angle) friction could wedge it (the static LP is feasible
        // at every rotation): held only by jamming, weakly stable. The 120° V
        // of c, d cannot: no equilibrium at all.
        WedgeCase{"type-a.json", "0,0,9.81", 1, true, true},
        WedgeCase{"type-b.json", "0,0,9.81", 1, true, true},
        WedgeCase{"type-c.json", "0,0,9.81", 1, false, false},
        WedgeCase{"type-d.json", "0,0,9.81", 1, false, false},
        // Turned by 90°: one 60° face of type-a is then 30° from horizontal
        // and holds it by friction (up to 100°); type-c's static limit is
        // 65.71°.
        WedgeCase{"type-a.json", "9.81,0,0", 0, true, false},
        WedgeCase{"type-c.json", "9.81,0,0", 1, false, false}),
    [](const ::testing::TestParamInfo<WedgeCase>& param_info) {
      std::string name = std::string(param_info.param.file) + "_" +
                         (*param_info.param.gravity ? param_info.param.gravity : "upright");
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

// type-d turned by 90°: its static limit is 70.03°, so it must be unstable,
// sliding out along its lower V face. (Lemke's path on the 48-variable LCP of
// its one movable block cycles among blurred ties until the pivot limit; the
// perturbed path, lemke.cpp, solves it.)
TEST(CompasCheck, WedgeDTurnedNinetyDegreesSlidesOut) {
  SHARED_OR_SKIP(file, "compas_cra/type-d.json");
  const CliRun r = CheckCompas(file, 0.84, "--supports 0,1 --gravity=9.81,0,0");
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const json doc = Doc(r);
  EXPECT_EQ(doc["static_equilibrium"], false);
  EXPECT_EQ(doc["verdict"], "unstable") << doc["diagnostics"];
  EXPECT_EQ(doc["moving"], json({"2"}));
  for (const json& p : doc["parts"]) {
    if (p["name"] != "2") continue;
    EXPECT_EQ(p["motion"], "slides");
    // Along the face whose normal is (-0.5, 0, 0.866): direction (0.866, 0, 0.5).
    const json& v = p["velocity"]["linear"];
    const Vector3 u(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
    EXPECT_GT(u.norm(), 0);
    EXPECT_NEAR(u.normalized().dot(Vector3(std::sqrt(3.0) / 2, 0, 0.5)), 1, 1e-6);
  }
}

// ---- convert ----------------------------------------------------------------

struct RoundTrip {
  const char* file;
  const char* model;    // flags for reading the COMPAS file (after --format, --friction 0.84)
  const char* without;  // blocks taken away for both checks
};

void PrintTo(const RoundTrip& c, std::ostream* os) { *os << c.file << " " << c.model; }

class ConvertRoundTrip : public ::testing::TestWithParam<RoundTrip> {};

// `cairn convert` writes a scene that `cairn check` reads back as the same
// model: the same verdict, the same contacts and the same LCPs.
TEST_P(ConvertRoundTrip, SameVerdictContactsAndLcps) {
  const RoundTrip& c = GetParam();
  SHARED_OR_SKIP(file, c.file);
  // ctest runs each case in its own process, in parallel: one file per case.
  std::string name = std::string(c.file) + c.model + c.without;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  const std::string out = TempPath(name + ".scene.json");
  const CliRun conv =
      Cairn("convert " + file + " " + out + " --format compas --friction 0.84 " + c.model);
  ASSERT_EQ(conv.exit_code, 0) << conv.err;
  EXPECT_EQ(conv.err, "");
  EXPECT_THAT(conv.out, HasSubstr("wrote " + out));
  ASSERT_TRUE(std::filesystem::is_regular_file(out));
  EXPECT_FALSE(std::filesystem::exists(out + ".tmp"));

  const std::string without = *c.without ? std::string(" --without ") + c.without : "";
  const CliRun a = CheckCompas(file, 0.84, std::string(c.model) + without);
  const CliRun b = Cairn("check " + out + without + " --json");
  ASSERT_EQ(a.exit_code, b.exit_code) << a.err << b.err;
  const json da = Doc(a), db = Doc(b);
  for (const char* key :
       {"verdict", "static_equilibrium", "weakly_stable", "moving", "formulation", "without"}) {
    EXPECT_EQ(da[key], db[key]) << key;
  }
  EXPECT_EQ(da["contacts"].size(), db["contacts"].size());
  ASSERT_EQ(da["components"].size(), db["components"].size());
  for (size_t i = 0; i < da["components"].size(); ++i) {
    EXPECT_EQ(da["components"][i]["lcp_size"], db["components"][i]["lcp_size"]);
    EXPECT_EQ(da["components"][i]["contacts"], db["components"][i]["contacts"]);
  }
  // The same parts, masses and centroids, to the last bit.
  EXPECT_EQ(da["parts"], db["parts"]);

  // The scene file itself: format 1, 3-D polyhedra, μ and the supports.
  std::ifstream in(out);
  const json scene = json::parse(in);
  EXPECT_EQ(scene["cairn"], 1);
  EXPECT_EQ(scene["friction"], 0.84);
  EXPECT_GT(scene["tolerance"].get<double>(), 0);
  for (const json& p : scene["parts"]) {
    EXPECT_TRUE(p.contains("polyhedron")) << p["name"];
    EXPECT_EQ(p["density"], 1.0);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Shared, ConvertRoundTrip,
    ::testing::Values(RoundTrip{"compas_assembly/two-blocks_assembly.json", "", ""},
                      RoundTrip{"compas_assembly/stack_assembly.json", "", ""},
                      RoundTrip{"compas_assembly/stack_assembly.json", "", "7,8,9"},
                      RoundTrip{"compas_assembly/arch_assembly.json", "", ""},
                      RoundTrip{"compas_cra/cubes.json", "--supports 0", ""},
                      RoundTrip{"compas_cra/H.json", "--supports 0,1", ""},
                      RoundTrip{"compas_cra/type-b.json", "--supports 0,1 --gravity=0,0,9.81", ""},
                      // Split faces (the planarity policy) survive the trip.
                      RoundTrip{"compas_cra/cube-curve-short.json", "--supports 0", ""}),
    [](const ::testing::TestParamInfo<RoundTrip>& param_info) {
      std::string name = std::string(param_info.param.file) + "_" + param_info.param.model + "_" +
                         param_info.param.without;
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

// Two unit cubes, "0" (a support) under "1": the COMPAS 2 layout, for the
// tests that must not depend on the shared files.
constexpr const char* kTwoCubes = R"({
  "dtype": "compas_assembly.datastructures/Assembly",
  "data": {"attributes": {"name": "two cubes"}, "graph": {"dtype": "compas.datastructures/Graph", "data": {
    "default_node_attributes": {"is_support": false},
    "node": {
      "0": {"is_support": true, "block": {"dtype": "compas_assembly.datastructures/Block", "data": {
        "vertex": {"0": {"x": 0, "y": 0, "z": 0}, "1": {"x": 1, "y": 0, "z": 0}, "2": {"x": 1, "y": 1, "z": 0},
                   "3": {"x": 0, "y": 1, "z": 0}, "4": {"x": 0, "y": 0, "z": 1}, "5": {"x": 1, "y": 0, "z": 1},
                   "6": {"x": 1, "y": 1, "z": 1}, "7": {"x": 0, "y": 1, "z": 1}},
        "face": {"0": [0, 3, 2, 1], "1": [4, 5, 6, 7], "2": [0, 1, 5, 4], "3": [1, 2, 6, 5],
                 "4": [2, 3, 7, 6], "5": [3, 0, 4, 7]}}}},
      "1": {"block": {"dtype": "compas_assembly.datastructures/Block", "data": {
        "vertex": {"0": {"x": 0, "y": 0, "z": 1}, "1": {"x": 1, "y": 0, "z": 1}, "2": {"x": 1, "y": 1, "z": 1},
                   "3": {"x": 0, "y": 1, "z": 1}, "4": {"x": 0, "y": 0, "z": 2}, "5": {"x": 1, "y": 0, "z": 2},
                   "6": {"x": 1, "y": 1, "z": 2}, "7": {"x": 0, "y": 1, "z": 2}},
        "face": {"0": [0, 3, 2, 1], "1": [4, 5, 6, 7], "2": [0, 1, 5, 4], "3": [1, 2, 6, 5],
                 "4": [2, 3, 7, 6], "5": [3, 0, 4, 7]}}}}},
    "edge": {}}}}
})";

TEST(CompasConvert, WritesTheFlagsIntoTheScene) {
  const std::string in = WriteFile("two_cubes.json", kTwoCubes);
  const std::string out = TempPath("two_cubes.scene.json");
  const CliRun r = Cairn("convert " + in + " " + out +
                         " --format compas --friction 0.3 --supports 1 --gravity=1,0,-9.81");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream f(out);
  const json scene = json::parse(f);
  EXPECT_EQ(scene["name"], "two cubes");
  EXPECT_EQ(scene["friction"], 0.3);
  EXPECT_EQ(scene["gravity"], json({1.0, 0.0, -9.81}));
  ASSERT_EQ(scene["parts"].size(), 2u);
  EXPECT_EQ(scene["parts"][0]["fixed"], true);  // is_support
  EXPECT_EQ(scene["parts"][1]["fixed"], true);  // --supports 1
  EXPECT_EQ(scene["parts"][1]["polyhedron"]["vertices"][4], json({0.0, 0.0, 2.0}));
  // Both fixed: nothing can move.
  EXPECT_EQ(Cairn("check " + out).exit_code, 0);
}

// A bad input writes nothing, not even over an existing file, and says what
// is wrong on one line of stderr, naming the file and where in it.
TEST(CompasConvert, BadInputWritesNothing) {
  json doc = json::parse(kTwoCubes);
  doc["data"]["graph"]["data"]["node"]["1"]["block"]["data"]["face"]["2"] = {0, 1, 5, 99};
  const std::string in = WriteFile("bad_face.json", doc.dump());
  const std::string out = WriteFile("bad_face.scene.json", "keep me");
  const CliRun r = Cairn("convert " + in + " " + out + " --format compas --friction 0.5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "cairn: error: " + in +
                ": data.graph.data.node.1 (\"1\").block.data.face.2[3]: vertex 99 does not "
                "exist (it is not a key of data.graph.data.node.1 (\"1\").block.data.vertex)\n");
  EXPECT_EQ(testing::Slurp(out), "keep me");
  EXPECT_FALSE(std::filesystem::exists(out + ".tmp"));

  // Overlapping blocks (a model fault) are named by their nodes too.
  json overlap = json::parse(kTwoCubes);
  for (auto& v : overlap["data"]["graph"]["data"]["node"]["1"]["block"]["data"]["vertex"])
    v["z"] = v["z"].get<double>() - 0.5;
  const std::string in2 = WriteFile("overlap.json", overlap.dump());
  const std::string out2 = TempPath("overlap.scene.json");
  const CliRun r2 = Cairn("convert " + in2 + " " + out2 + " --format compas --friction 0.5");
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_THAT(r2.err,
              HasSubstr(in2 + ": data.graph.data.node.1 (\"1\"): part '1' overlaps part '0' "
                              "(data.graph.data.node.0)"));
  // ... and says that --tolerance raises the tolerance (the COMPAS reader's
  // renamed error keeps the overlaps and their tolerance).
  EXPECT_THAT(r2.err, HasSubstr("(raise it with --tolerance, e.g. --tolerance 1e-"));
  EXPECT_FALSE(std::filesystem::exists(out2));

  // An output that cannot be written.
  const std::string good = WriteFile("good.json", kTwoCubes);
  const CliRun r3 =
      Cairn("convert " + good + " /nonexistent_dir/x.json --format compas --friction 0.5");
  EXPECT_EQ(r3.exit_code, 2);
  EXPECT_THAT(r3.err, HasSubstr("cannot write '/nonexistent_dir/x.json'"));
}

// A scene file converted to a scene file: shapes given as boxes, meshes and
// polygons come back as polygons and polyhedra, with tools, fixtures and
// friction pairs; `cairn check` then reports exactly the same document.
class ConvertScene : public ::testing::TestWithParam<const char*> {};

TEST_P(ConvertScene, ReportIsUnchanged) {
  const std::string file = ExamplePath(GetParam());
  const std::string out = TempPath(std::string("scene_") + GetParam());
  const CliRun conv = Cairn("convert " + file + " " + out);
  ASSERT_EQ(conv.exit_code, 0) << conv.err;
  const CliRun a = Cairn("check " + file + " --json");
  const CliRun b = Cairn("check " + out + " --json");
  EXPECT_EQ(a.exit_code, b.exit_code);
  json da = Doc(a), db = Doc(b);
  da.erase("scene_file");
  db.erase("scene_file");
  EXPECT_EQ(da, db);
}

INSTANTIATE_TEST_SUITE_P(Examples, ConvertScene,
                         ::testing::Values("paper_fig1.json", "paper_fig4_fixels.json",
                                           "paper_fig9.json", "paper_fig19.json", "wall.json"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           std::string name = param_info.param;
                           name = name.substr(0, name.size() - 5);
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

// ---- The flags --------------------------------------------------------------

TEST(CompasFlags, BadArgumentsExitTwoAndPrintNothing) {
  const std::string in = WriteFile("flags.json", kTwoCubes);
  const struct {
    std::string args;
    std::string error;  // a phrase of stderr
  } kCases[] = {
      {"check " + in + " --format compas", "--friction: is required with --format compas"},
      {"check " + in + " --format compas --friction -0.1", "--friction: must not be negative"},
      {"check " + in + " --format compas --friction nan", "--friction: must be a finite number"},
      {"check " + in + " --format compas --friction 0.5 --supports 7",
       "--supports: no part named '7'"},
      {"check " + in + " --format compas --friction 0.5 --without 7",
       "--without: no part named '7'"},
      {"check " + in + " --format compas --friction 0.5 --gravity 0,-9.81",
       "--gravity: must have 3 numbers"},
      {"check " + in + " --format compas --friction 0.5 --tolerance 0",
       "--tolerance: must be a positive length"},
      {"check " + in + " --format obj --friction 0.5", "--format"},
      // A COMPAS file read as a scene: say what to do.
      {"check " + in, "if this is a COMPAS assembly, give --format compas"},
      // A scene read as COMPAS.
      {"check " + ExamplePath("stack3.json") + " --format compas --friction 0.5",
       "not a COMPAS assembly"},
      {"simulate " + in + " " + in + " --format compas", "--friction: is required"},
  };
  for (const auto& c : kCases) {
    SCOPED_TRACE(c.args);
    const CliRun r = Cairn(c.args);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.out, "");
    EXPECT_THAT(r.err, HasSubstr(c.error));
  }
}

// --friction on a scene file replaces its default μ: the block on a 30°
// incline slides at the file's μ = 0.5 < tan 30° and holds at 0.6.
TEST(CompasFlags, FrictionOverridesAScenesDefault) {
  const std::string file = ExamplePath("incline_slides.json");
  EXPECT_EQ(Cairn("check " + file).exit_code, 1);
  EXPECT_EQ(Cairn("check " + file + " --friction 0.6").exit_code, 0);
  EXPECT_EQ(Cairn("check " + file + " --friction 0.55").exit_code, 1);
  // convert keeps it: a 2-D scene in, a 2-D scene out.
  const std::string out = TempPath("incline.scene.json");
  ASSERT_EQ(Cairn("convert " + file + " " + out + " --friction 0.6").exit_code, 0);
  std::ifstream f(out);
  const json scene = json::parse(f);
  EXPECT_EQ(scene["friction"], 0.6);
  EXPECT_TRUE(scene["parts"][0].contains("polygon"));
  EXPECT_EQ(Cairn("check " + out).exit_code, 0);
}

// ---- simulate ---------------------------------------------------------------

// Lifting the top cube off its support is stable; taking the leaning stack's
// top block first is not: the rest tips as soon as the step starts.
TEST(CompasSimulate, PlansNameBlocksByTheirKeys) {
  const std::string two = WriteFile("sim_two.json", kTwoCubes);
  const std::string lift = WriteFile(
      "lift.plan.json",
      R"({"cairn_plan": 1, "dt": 0.5, "steps": [{"remove": ["1"], "direction": [0, 0, 1], "distance": 1}]})");
  const CliRun r = Cairn("simulate " + two + " " + lift + " --format compas --friction 0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(Doc(r)["verdict"], "stable");

  SHARED_OR_SKIP(stack, "compas_assembly/stack_assembly.json");
  const std::string top = WriteFile(
      "stack_top.plan.json",
      R"({"cairn_plan": 1, "dt": 0.5, "steps": [{"remove": ["9"], "direction": [0, 0, 1], "distance": 1},
                                                 {"remove": ["8"], "direction": [0, 0, 1], "distance": 1}]})");
  const CliRun s =
      Cairn("simulate " + stack + " " + top + " --format compas --friction 0.84 --json");
  ASSERT_EQ(s.exit_code, 1) << s.err << s.out.substr(0, 1000);
  const json doc = Doc(s);
  EXPECT_EQ(doc["verdict"], "unstable");
  EXPECT_EQ(doc["failure"]["step"], 0);
  EXPECT_EQ(doc["failure"]["tick"], 0);
  EXPECT_THAT(doc["failure"]["parts"].get<std::vector<std::string>>(), ::testing::Contains("1"));
}

// ---- Stored interfaces (--interfaces stored) --------------------------------

// The interfaces compas_assembly stored give the same verdicts as the
// contacts Cairn finds: the stack falls and stands without its top 3; the
// two blocks stand, the upper carrying its weight through the one interface.
TEST(CompasInterfaces, StoredInterfacesGiveTheSameVerdicts) {
  SHARED_OR_SKIP(two, "compas_assembly/two-blocks_assembly.json");
  const CliRun r = CheckCompas(two, 0.84, "--interfaces stored");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json doc = Doc(r);
  EXPECT_EQ(doc["verdict"], "stable");
  ASSERT_EQ(doc["contacts"].size(), 4u);
  for (const json& c : doc["contacts"]) {
    EXPECT_EQ(c["feature"], "interface");
    EXPECT_EQ(c["patch"], 0);
  }
  EXPECT_TRUE(ForceOn(doc, "1").isApprox(Vector3(0, 0, 9.81), 1e-9)) << ForceOn(doc, "1");

  SHARED_OR_SKIP(stack, "compas_assembly/stack_assembly.json");
  const CliRun all = CheckCompas(stack, 0.84, "--interfaces stored");
  EXPECT_EQ(all.exit_code, 1) << all.err;
  EXPECT_EQ(Doc(all)["static_equilibrium"], false);
  const CliRun seven = CheckCompas(stack, 0.84, "--interfaces stored --without 7,8,9");
  EXPECT_EQ(seven.exit_code, 0) << seven.err;
  // The same contacts as found from the shapes.
  EXPECT_EQ(Doc(seven)["contacts"].size(),
            Doc(CheckCompas(stack, 0.84, "--without 7,8,9"))["contacts"].size());
}

// cube-curve-tall's two blocks interpenetrate by more than the default
// tolerance along their hand-made curved interface: from the shapes it is
// refused (overlap); its 72 stored interface polygons load it, and the upper
// block stands on the curved seam.
TEST(CompasInterfaces, StoredInterfacesLoadBlocksTooLooseForFoundContacts) {
  SHARED_OR_SKIP(file, "compas_cra/cube-curve-tall.json");
  const CliRun found = CheckCompas(file, 0.84, "--supports 0");
  EXPECT_EQ(found.exit_code, 2);
  EXPECT_THAT(found.err, HasSubstr("overlaps"));
  const CliRun r = CheckCompas(file, 0.84, "--supports 0 --interfaces stored");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json doc = Doc(r);
  EXPECT_EQ(doc["verdict"], "stable");
  EXPECT_EQ(doc["static_equilibrium"], true);
  const double m = MassOf(doc, "1");
  EXPECT_TRUE(ForceOn(doc, "1").isApprox(Vector3(0, 0, 9.81 * m), 1e-8)) << ForceOn(doc, "1");
}

TEST(CompasInterfaces, MisuseExitsTwo) {
  const std::string two = WriteFile("no_interfaces.json", kTwoCubes);
  const CliRun none = CheckCompas(two, 0.5, "--interfaces stored");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_THAT(none.err, HasSubstr("stores no interfaces"));
  const CliRun scene = Cairn("check " + ExamplePath("paper_fig9.json") + " --interfaces stored");
  EXPECT_EQ(scene.exit_code, 2);
  EXPECT_THAT(scene.err, HasSubstr("--interfaces: stored is for --format compas"));
  const CliRun bad = Cairn("check " + two + " --format compas --friction 0.5 --interfaces given");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.out, "");

  SHARED_OR_SKIP(stack, "compas_assembly/stack_assembly.json");
  const std::string lift = WriteFile(
      "lift9.plan.json",
      R"({"cairn_plan": 1, "dt": 0.5, "steps": [{"remove": ["9"], "direction": [0, 0, 1], "distance": 1}]})");
  const CliRun sim = Cairn("simulate " + stack + " " + lift +
                           " --format compas --friction 0.84 --interfaces stored");
  EXPECT_EQ(sim.exit_code, 2);
  EXPECT_EQ(sim.out, "");
  EXPECT_THAT(sim.err, HasSubstr(stack + ": interfaces: the contacts are given as interfaces"));
}

// A scene file's `interfaces`: two boxes that overlap by 1 cm (refused
// without interfaces) meet on the given square; the upper one stands on it,
// and falls when the square is moved out from under its centre of mass.
// Parts that overlap by more than the length tolerance: the message says
// that --tolerance raises it (and, for a scene, its `tolerance`), with the
// power of ten above the tolerance as the example; given a larger one, the
// model loads.
TEST(ModelTolerance, AnOverlapSaysThatToleranceRaisesIt) {
  const json scene = {
      {"cairn", 1},
      {"parts",
       {{{"name", "A"}, {"fixed", true}, {"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}}}},
        {{"name", "B"}, {"box", {{"min", {0, 0, 1 - 2e-5}}, {"max", {1, 1, 2}}}}}}}};
  const std::string file = testing::TempFile("model_overlap.json", scene.dump());
  const CliRun r = Cairn("check " + file);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("part 'B' overlaps part 'A' (parts[0]) by more than the tolerance "
                               "2.44949e-06"));
  EXPECT_THAT(r.err, HasSubstr("(raise it with --tolerance or the scene's `tolerance`, e.g. "
                               "--tolerance 1e-5; or, for parts meant to touch, read their "
                               "overlap as contact with --overlap-depth 3e-05)\n"));
  EXPECT_EQ(Cairn("check " + file + " --tolerance 1e-4").exit_code, 0);
  // ASAP's beams, whose meshes interpenetrate by up to ~1e-4 (inches).
  const std::string shared = testing::SharedDir();
  if (shared.empty()) GTEST_SKIP() << "shared/datasets not found: skipping the ASAP beam assembly";
  const CliRun beams = Cairn("check " + shared + "/datasets/asap_beam_assembly --format asap");
  EXPECT_EQ(beams.exit_code, 2);
  EXPECT_THAT(beams.err, HasSubstr("part '2' overlaps part '0' (parts[0]) by more than the "
                                   "tolerance 1.87702e-05"));
  EXPECT_THAT(beams.err, HasSubstr("(raise it with --tolerance, e.g. --tolerance 1e-4; or, for "
                                   "parts meant to touch, read their overlap as contact with "
                                   "--overlap-depth 5e-05)\n"));
  EXPECT_EQ(Cairn("check " + shared +
                  "/datasets/asap_beam_assembly --format asap --overlap-depth "
                  "1e-4 --fixed 6")
                .exit_code,
            0);
}

// Parts meant to touch whose meshes overlap (as exported): two posts on a
// base under a beam, each pressed 0.04 (4 % of a post's width) into what it
// stands on. Refused without an overlap depth, every pair listed with its
// depth and --overlap-depth advised; with one, every pair is noted with its
// depth and touches on the overlap's mid-surface: only vertical contacts, in
// the middle of each overlap, carrying the beam's weight; deeper than the
// depth, refused with the depth.
TEST(OverlapDepth, PostsPressedIntoTheirBaseAndBeamStandOnTheOverlapsMidSurfaces) {
  const json scene = {
      {"cairn", 1},
      {"parts",
       {{{"name", "base"}, {"fixed", true}, {"box", {{"min", {0, 0, 0}}, {"max", {4, 1, 1}}}}},
        {{"name", "left"}, {"box", {{"min", {0, 0, 0.96}}, {"max", {1, 1, 3}}}}},
        {{"name", "right"}, {"box", {{"min", {3, 0, 0.96}}, {"max", {4, 1, 3}}}}},
        {{"name", "beam"}, {"box", {{"min", {0, 0, 2.96}}, {"max", {4, 1, 3.5}}}}}}}};
  const std::string file = testing::TempFile("overlap_depth_posts.json", scene.dump());
  const CliRun refused = Cairn("check " + file);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr("part 'left' overlaps part 'base' (parts[0])"));
  EXPECT_THAT(refused.err, HasSubstr("3 more overlapping pairs"));
  EXPECT_THAT(refused.err, HasSubstr("0.04 deep; "));
  EXPECT_THAT(refused.err, HasSubstr("; or, for parts meant to touch, read their overlap as "
                                     "contact with --overlap-depth 0.06)\n"));

  const CliRun r = Cairn("check " + file + " --overlap-depth 0.05 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* pair :
       {"'base' and 'left'", "'base' and 'right'", "'left' and 'beam'", "'right' and 'beam'"})
    EXPECT_THAT(r.err, HasSubstr(std::string("parts ") + pair + " overlap 0.04 deep (deepest at "));
  const json out = json::parse(r.out);
  EXPECT_EQ(out["verdict"], "stable");
  ASSERT_EQ(out["contacts"].size(), 16u);  // a square patch per pair
  double on_beam = 0;
  for (const json& c : out["contacts"]) {
    EXPECT_NEAR(std::abs(c["normal"][2].get<double>()), 1.0, 1e-12) << c.dump();
    const double z = c["point"][2];
    EXPECT_TRUE(std::abs(z - 0.98) < 1e-9 || std::abs(z - 2.98) < 1e-9) << c.dump();
    if (c["parts"][1] == "beam") on_beam += c["normal_force"].get<double>();
  }
  EXPECT_NEAR(on_beam, 4 * 0.54 * 9.81, 1e-6);  // the beam's weight (density 1)

  const CliRun shallow = Cairn("check " + file + " --overlap-depth 0.03");
  EXPECT_EQ(shallow.exit_code, 2);
  EXPECT_THAT(shallow.err, HasSubstr("by more than the tolerance 0.03"));
  EXPECT_THAT(shallow.err, HasSubstr("(raise it with --overlap-depth or the scene's "
                                     "`overlap_depth`, e.g. --overlap-depth 0.06)\n"));
  const CliRun huge = Cairn("check " + file + " --overlap-depth 1");
  EXPECT_EQ(huge.exit_code, 2);
  EXPECT_THAT(huge.err, HasSubstr("--overlap-depth: too large: 1 is more than 0.05 of the "
                                  "smallest part's size"));
  const CliRun negative = Cairn("check " + file + " --overlap-depth -1");
  EXPECT_EQ(negative.exit_code, 2);
  EXPECT_THAT(negative.err, HasSubstr("--overlap-depth"));

  // The scene's own key, and convert keeps it; the beam leaves upward, the
  // posts are held by it.
  json keyed = scene;
  keyed["overlap_depth"] = 0.05;
  const std::string keyed_file = testing::TempFile("overlap_depth_key.json", keyed.dump());
  EXPECT_EQ(Cairn("check " + keyed_file).exit_code, 0);
  const std::string converted = testing::TempDir("overlap_depth_convert") + ".json";
  ASSERT_EQ(Cairn("convert " + file + " " + converted + " --overlap-depth 0.05").exit_code, 0);
  std::ifstream in(converted);
  EXPECT_EQ(json::parse(in)["overlap_depth"], 0.05);
  const CliRun up = Cairn("blocking " + keyed_file + " --direction 0,0,1");
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_THAT(up.out, HasSubstr("leave: beam   blocked: base by left*, right*, beam; left by "
                                "beam*; right by beam*"));
}

// An overlap read as contact holds nothing up that the contact would not: a
// cube pressed 0.03 sideways into a wall, nothing under it, falls, with or
// without friction (no squeeze: every contact is on the wall's face). In
// 2-D, an overlap depth is refused.
TEST(OverlapDepth, ACubePressedIntoAWallStillFalls) {
  const json scene = {
      {"cairn", 1},
      {"parts",
       {{{"name", "wall"}, {"fixed", true}, {"box", {{"min", {0, 0, 0}}, {"max", {1, 1, 2}}}}},
        {{"name", "cube"}, {"box", {{"min", {0.97, 0, 0.5}}, {"max", {1.97, 1, 1.5}}}}}}}};
  const std::string file = testing::TempFile("overlap_depth_wall.json", scene.dump());
  for (const char* mu : {"0", "0.5", "2"}) {
    const CliRun r =
        Cairn("check " + file + " --overlap-depth 0.05 --json --friction " + std::string(mu));
    ASSERT_EQ(r.exit_code, 1) << r.err;  // unstable
    const json out = json::parse(r.out);
    EXPECT_EQ(out["verdict"], "unstable") << mu;
    ASSERT_EQ(out["contacts"].size(), 4u);
    for (const json& c : out["contacts"]) {
      EXPECT_NEAR(c["normal"][0].get<double>(), 1.0, 1e-12) << c.dump();
      EXPECT_NEAR(c["point"][0].get<double>(), 0.985, 1e-12) << c.dump();
    }
  }
  const std::string flat = testing::TempFile(
      "overlap_depth_2d.json",
      R"({"cairn": 1, "parts": [{"name": "a", "fixed": true, "box": {"min": [0, 0], "max": [1, 1]}}]})");
  const CliRun r2 = Cairn("check " + flat + " --overlap-depth 0.01");
  EXPECT_EQ(r2.exit_code, 2);
  EXPECT_THAT(r2.err, HasSubstr("--overlap-depth: applies to 3-D models only"));
}

TEST(SceneInterfaces, GivenInterfacesAreTheContacts) {
  const std::string scene = R"({"cairn": 1, "friction": 0.5, "parts": [
    {"name": "base", "fixed": true, "box": {"min": [0, 0, 0], "max": [1, 1, 1]}},
    {"name": "top", "box": {"min": [0, 0, 0.99], "max": [1, 1, 2]}}],
   "interfaces": [{"parts": ["top", "base"], "normal": [0, 0, 2],
                   "points": [[X0, 0, 1], [X1, 0, 1], [X1, 1, 1], [X0, 1, 1]]}]})";
  const auto with = [&](const char* x0, const char* x1) {
    std::string s = scene;
    for (size_t at; (at = s.find("X0")) != std::string::npos;) s.replace(at, 2, x0);
    for (size_t at; (at = s.find("X1")) != std::string::npos;) s.replace(at, 2, x1);
    return s;
  };
  const std::string under = WriteFile("iface_under.json", with("0", "1"));
  const CliRun r = Cairn("check " + under + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json doc = Doc(r);
  EXPECT_EQ(doc["contacts"].size(), 4u);
  EXPECT_TRUE(ForceOn(doc, "top").isApprox(Vector3(0, 0, 9.81 * MassOf(doc, "top")), 1e-9));
  // The square [0.6, 1] × [0, 1]: the top's centre (x = 0.5) is off it.
  const std::string off = WriteFile("iface_off.json", with("0.6", "1"));
  const CliRun tips = Cairn("check " + off + " --json");
  EXPECT_EQ(tips.exit_code, 1) << tips.err;
  EXPECT_EQ(Doc(tips)["moving"], json({"top"}));
  // convert keeps them.
  const std::string out = TempPath("iface_converted.json");
  ASSERT_EQ(Cairn("convert " + under + " " + out).exit_code, 0);
  const CliRun again = Cairn("check " + out + " --json");
  EXPECT_EQ(Doc(again)["contacts"], doc["contacts"]);

  // Without the interfaces the boxes overlap.
  json bare = json::parse(with("0", "1"));
  bare.erase("interfaces");
  const CliRun overlap = Cairn("check " + WriteFile("iface_bare.json", bare.dump()));
  EXPECT_EQ(overlap.exit_code, 2);
  EXPECT_THAT(overlap.err, HasSubstr("overlaps"));

  // Bad interfaces: named at their JSON path.
  const struct {
    const char* x0;
    const char* x1;
    std::string patch;
    std::string error;
  } kBad[] = {
      {"0", "1", R"({"parts": ["top", "nope"]})", "interfaces[0].parts[1]: no part named 'nope'"},
      {"0", "1", R"({"points": [[0, 0, 1], [1, 0, 1]]})",
       "interfaces[0].points: needs at least 3 points"},
      {"0", "1", R"({"normal": [0, 0, 0]})", "interfaces[0].normal: must not be zero"},
      {"0", "1", R"({"points": [[0, 0, 1], [1, 0, 1], [1, 1, 1.5]]})", "interfaces[0].points[2]"},
  };
  for (const auto& c : kBad) {
    SCOPED_TRACE(c.error);
    json d = json::parse(with(c.x0, c.x1));
    d["interfaces"][0].merge_patch(json::parse(c.patch));
    const std::string f = WriteFile("iface_bad.json", d.dump());
    const CliRun b = Cairn("check " + f);
    EXPECT_EQ(b.exit_code, 2);
    EXPECT_EQ(b.out, "");
    EXPECT_THAT(b.err, HasSubstr(f + ": " + c.error));
  }
}

// ---- Every shared file, every friction: a verdict with its evidence --------

// Every COMPAS assembly of ../shared at μ = 0.1, 0.3, 0.5, 0.84 and 1.0 (the
// supports of docs/compas-format.md) gets a verdict, never "solver failure"
// A stable one is proved by forces that balance every free block
// (weight = 9.81 × mass, the equilibrium's postcondition) with `stability`
// "strong" or "not certified"; an unstable one names the blocks that move and
// how, and says whether rest was possible at all ("weak": jamming; null: no
// equilibrium).
struct SharedCase {
  const char* file;
  const char* model;
};

void PrintTo(const SharedCase& c, std::ostream* os) { *os << c.file << " " << c.model; }

// A parameterised test's name: its file, every other character an underscore.
template <typename Case>
std::string FileParamName(const ::testing::TestParamInfo<Case>& param_info) {
  std::string name = param_info.param.file;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

class EveryFriction : public ::testing::TestWithParam<SharedCase> {};

TEST_P(EveryFriction, AVerdictWithItsEvidence) {
  SHARED_OR_SKIP(file, GetParam().file);
  for (const double mu : {0.1, 0.3, 0.5, 0.84, 1.0}) {
    SCOPED_TRACE("mu " + std::to_string(mu));
    const CliRun r = CheckCompas(file, mu, GetParam().model);
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err << r.out.substr(0, 500);
    const json doc = Doc(r);
    ASSERT_NE(doc["verdict"], "solver failure") << doc["diagnostics"];
    for (const json& c : doc["components"]) EXPECT_NE(c["decided_by"], "undecided");
    if (doc["verdict"] == "stable") {
      EXPECT_EQ(r.exit_code, 0);
      EXPECT_TRUE(doc["stability"] == "strong" || doc["stability"] == "not certified" ||
                  doc["stability"] == "weak")
          << doc["stability"];
      EXPECT_EQ(doc["moving"], json::array());
      ExpectEveryBlockBalanced(doc);
      continue;
    }
    EXPECT_EQ(r.exit_code, 1);
    ASSERT_FALSE(doc["moving"].empty()) << doc["diagnostics"];
    EXPECT_EQ(doc["weakly_stable"], doc["stability"] == "weak");
    EXPECT_EQ(doc["stability"].is_null(), doc["static_equilibrium"] == false);
    std::set<std::string> moving;
    for (const json& m : doc["moving"]) moving.insert(m.get<std::string>());
    for (const json& p : doc["parts"]) {
      if (!moving.count(p["name"].get<std::string>())) continue;
      EXPECT_EQ(p["moving"], true);
      EXPECT_NE(p["motion"], "at rest") << p["name"];
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Shared, EveryFriction,
    ::testing::Values(
        SharedCase{"compas_assembly/arch_assembly.json", ""},
        SharedCase{"compas_assembly/crossvault_assembly.json", ""},
        SharedCase{"compas_assembly/stack_assembly.json", ""},
        SharedCase{"compas_assembly/two-blocks_assembly.json", ""},
        SharedCase{"compas_assembly/wall_assembly.json", ""},
        SharedCase{"compas_cra/A.json", "--supports 0,1"},
        SharedCase{"compas_cra/H.json", "--supports 0,1"},
        SharedCase{"compas_cra/cubes.json", "--supports 0"},
        SharedCase{"compas_cra/type-a.json", "--supports 0,1"},
        SharedCase{"compas_cra/type-b.json", "--supports 0,1"},
        SharedCase{"compas_cra/type-c.json", "--supports 0,1"},
        SharedCase{"compas_cra/type-d.json", "--supports 0,1"},
        SharedCase{"compas_cra/concave-short.json", "--supports 0"},
        SharedCase{"compas_cra/concave-long.json", "--supports 0"},
        SharedCase{"compas_cra/cube-curve-short.json", "--supports 0"},
        SharedCase{"compas_cra/cube-curve-tall.json", "--supports 0 --interfaces stored"},
        SharedCase{"compas_cra/curve-3-blocks.json", "--supports 0 --interfaces stored"},
        SharedCase{"compas_cra/shelf.json", "--supports 0"},
        SharedCase{"compas_cra/shelf-stable.json", "--supports 0"},
        SharedCase{"compas_cra/shelf-s1.json", "--supports 0"},
        SharedCase{"compas_cra/shelf-s2.json", "--supports 0"},
        SharedCase{"compas_cra/shelf-s3.json", "--supports 0"},
        SharedCase{"compas_cra/snake.json", "--supports 0"},
        SharedCase{"compas_cra/bridge.json", "--supports 0,1"},
        SharedCase{"compas_cra/armadillo_cra.json", "--interfaces stored"}),
    FileParamName<SharedCase>);

// ---- One answer per assembly: monotone in μ ---------------------------------

// More friction cannot make an assembly fall: on a grid of 20 values of μ from
// 0.05 to 2, once a model stands it stands at every larger μ (issue 32).
// Where rigid bodies leave the answer open (an equilibrium and a motion),
// loading from rest decides, so the verdict no longer follows whichever
// solution Lemke's method meets first.
constexpr double kFrictionGrid[] = {0.05, 0.15, 0.25, 0.35, 0.45, 0.55, 0.6, 0.65, 0.7, 0.75,
                                    0.8,  0.84, 0.85, 0.9,  0.95, 1.0,  1.1, 1.25, 1.5, 2.0};

struct MonotoneCase {
  const char* file;   // under ../shared/datasets (COMPAS), or examples/ when `example`
  const char* model;  // extra options
  bool example = false;
};

void PrintTo(const MonotoneCase& c, std::ostream* os) { *os << c.file << " " << c.model; }

class FrictionMonotone : public ::testing::TestWithParam<MonotoneCase> {};

TEST_P(FrictionMonotone, OnceItStandsItStandsAtEveryLargerMu) {
  const MonotoneCase& c = GetParam();
  std::string file;
  if (c.example) {
    file = ExamplePath(c.file);
  } else {
    SHARED_OR_SKIP(shared, c.file);
    file = shared;
  }
  std::string verdicts;
  double stands_from = -1;
  for (const double mu : kFrictionGrid) {
    const CliRun r = c.example ? Cairn("check " + file + " --friction " + std::to_string(mu) + " " +
                                       c.model + " --json")
                               : CheckCompas(file, mu, c.model);
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << "mu " << mu << ": " << r.err;
    const bool stands = r.exit_code == 0;
    verdicts += stands ? 'S' : 'F';
    if (stands && stands_from < 0) stands_from = mu;
    if (!stands) {
      EXPECT_LT(stands_from, 0) << "falls at mu " << mu << " after standing at " << stands_from
                                << ": " << verdicts;
    }
  }
  RecordProperty("verdicts", verdicts);
}

INSTANTIATE_TEST_SUITE_P(
    Examples, FrictionMonotone,
    ::testing::Values(
        MonotoneCase{"incline.json", "", true}, MonotoneCase{"incline_slides.json", "", true},
        MonotoneCase{"ladder.json", "", true}, MonotoneCase{"flush_joint.json", "", true},
        MonotoneCase{"flush_joint_wall.json", "", true}, MonotoneCase{"l_shapes.json", "", true},
        MonotoneCase{"overhang.json", "", true}, MonotoneCase{"paper_fig1.json", "", true},
        MonotoneCase{"paper_fig4.json", "", true}, MonotoneCase{"paper_fig6.json", "", true},
        MonotoneCase{"paper_fig14.json", "", true}, MonotoneCase{"paper_fig19.json", "", true},
        MonotoneCase{"peg_in_slot.json", "", true}, MonotoneCase{"pyramid10.json", "", true},
        MonotoneCase{"stack3.json", "", true}, MonotoneCase{"wall.json", "", true},
        MonotoneCase{"jenga.json", "", true}),
    FileParamName<MonotoneCase>);

// Every shared COMPAS file (supports as in docs/compas-format.md; the
// Armadillo vault's stored interfaces, as its check needs them): the same
// sweep through the check's verdict function
// (AnalyzeConfiguration, the rule loaded from rest; where no static
// equilibrium exists, the equilibrium LPs alone) with the strong proof
// left out (StabilityOptions::prove_strong: the verdict is the same, the
// search then runs only where loading from rest gives way), the model read
// once and its friction changed (Assembly::WithFriction). Tied to `cairn
// check` at the grid's first standing μ and the one before it.
class FrictionMonotoneVerdict : public ::testing::TestWithParam<MonotoneCase> {};

TEST_P(FrictionMonotoneVerdict, OnceItStandsItStandsAtEveryLargerMu) {
  const MonotoneCase& c = GetParam();
  SHARED_OR_SKIP(file, c.file);
  app::ModelArgs args;
  args.format = "compas";
  args.friction = 1.0;
  std::istringstream options(c.model);
  for (std::string flag, value; options >> flag >> value;) {
    if (flag == "--supports") {
      std::istringstream list(value);
      for (std::string key; std::getline(list, key, ',');) args.supports.push_back(key);
    } else if (flag == "--interfaces") {
      args.interfaces = value;
    }
  }
  const app::Model model = app::LoadModel(file, args);
  StabilityOptions verdict_only;
  verdict_only.prove_strong = false;
  const Configuration config = Configuration::Assembled(model.assembly);
  std::string verdicts;
  double stands_from = -1, last_falling = -1;
  for (const double mu : kFrictionGrid) {
    const Assembly at = model.assembly.WithFriction(mu, 1.0);
    // No static equilibrium, no standing (the check's first stage, whose
    // "falls" then only adds which parts move): the LPs alone decide there.
    bool equilibrium = true;
    for (const ContactLcp& lcp : BuildComponentLcps(at, config, verdict_only))
      equilibrium = equilibrium && FindStaticEquilibrium(lcp).exists;
    const bool stands = equilibrium && AnalyzeConfiguration(at, config, verdict_only).stable();
    verdicts += stands ? 'S' : 'F';
    if (stands && stands_from < 0) stands_from = mu;
    if (!stands && stands_from < 0) last_falling = mu;
    if (!stands) {
      EXPECT_LT(stands_from, 0) << "falls at mu " << mu << " after standing at " << stands_from
                                << ": " << verdicts;
    }
  }
  RecordProperty("verdicts", verdicts);
  if (stands_from > 0) {
    EXPECT_EQ(CheckCompas(file, stands_from, c.model).exit_code, 0);
  }
  if (last_falling > 0) {
    EXPECT_EQ(CheckCompas(file, last_falling, c.model).exit_code, 1);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Shared, FrictionMonotoneVerdict,
    ::testing::Values(
        MonotoneCase{"compas_assembly/arch_assembly.json", ""},
        MonotoneCase{"compas_assembly/crossvault_assembly.json", ""},
        MonotoneCase{"compas_assembly/stack_assembly.json", ""},
        MonotoneCase{"compas_assembly/two-blocks_assembly.json", ""},
        MonotoneCase{"compas_assembly/wall_assembly.json", ""},
        MonotoneCase{"compas_cra/A.json", "--supports 0,1"},
        MonotoneCase{"compas_cra/H.json", "--supports 0,1"},
        MonotoneCase{"compas_cra/cubes.json", "--supports 0"},
        MonotoneCase{"compas_cra/type-a.json", "--supports 0,1"},
        MonotoneCase{"compas_cra/type-b.json", "--supports 0,1"},
        MonotoneCase{"compas_cra/type-c.json", "--supports 0,1"},
        MonotoneCase{"compas_cra/type-d.json", "--supports 0,1"},
        MonotoneCase{"compas_cra/concave-short.json", "--supports 0"},
        MonotoneCase{"compas_cra/concave-long.json", "--supports 0"},
        MonotoneCase{"compas_cra/cube-curve-short.json", "--supports 0"},
        MonotoneCase{"compas_cra/shelf-stable.json", "--supports 0"},
        MonotoneCase{"compas_cra/snake.json", "--supports 0"},
        MonotoneCase{"compas_cra/cube-curve-tall.json", "--supports 0 --interfaces stored"},
        MonotoneCase{"compas_cra/curve-3-blocks.json", "--supports 0 --interfaces stored"},
        MonotoneCase{"compas_cra/shelf.json", "--supports 0"},
        MonotoneCase{"compas_cra/shelf-s1.json", "--supports 0"},
        MonotoneCase{"compas_cra/shelf-s2.json", "--supports 0"},
        MonotoneCase{"compas_cra/shelf-s3.json", "--supports 0"},
        MonotoneCase{"compas_cra/bridge.json", "--supports 0,1"},
        MonotoneCase{"compas_cra/armadillo_cra.json", "--interfaces stored"}),
    FileParamName<MonotoneCase>);

// `cairn margin --friction` gives the threshold of the check's verdict: the
// check stands just above it and falls just below it (and below the
// equilibrium's μ*, which is at most it).
TEST(CompasCheck, MarginsVerdictThresholdSplitsTheChecks) {
  for (const auto& [rel, supports] : std::vector<std::pair<std::string, std::string>>{
           {"compas_cra/snake.json", "0"}, {"compas_cra/A.json", "0,1"}}) {
    SCOPED_TRACE(rel);
    SHARED_OR_SKIP(file, rel);
    const CliRun m = Cairn("margin " + file + " --format compas --supports " + supports +
                           " --friction 0.84 --json");
    ASSERT_TRUE(m.exit_code == 0 || m.exit_code == 1) << m.err;
    const json margin = Doc(m)["margin"];
    ASSERT_TRUE(margin.contains("verdict_critical")) << margin.dump();
    const double eq = margin["critical"].get<double>();
    if (margin["verdict_critical"].is_null()) {  // never stands up to the search's end
      const double top = margin["verdict_searched_to"].get<double>();
      EXPECT_EQ(CheckCompas(file, top, "--supports " + supports).exit_code, 1);
      continue;
    }
    const double v = margin["verdict_critical"].get<double>();
    const double tol = margin["verdict_tolerance"].get<double>();
    EXPECT_GE(v, eq * (1 - 1e-9));
    EXPECT_EQ(CheckCompas(file, v * (1 + 1e-3), "--supports " + supports).exit_code, 0) << v;
    EXPECT_EQ(CheckCompas(file, (v - tol) * (1 - 1e-3), "--supports " + supports).exit_code, 1)
        << v;
  }
}

// Permuting and renaming the blocks of a file changes no verdict, no proof
// and no reported motion beyond the renaming: the LCP lists its bodies and
// contacts in a canonical order of the geometry (stability/analyze.cpp,
// CanonicalRanks) and the contacts are computed from the same side
// (contact/detect_contacts.cpp), so every solver sees the same problem.
TEST(CompasCheck, PermutingAndRenamingTheBlocksChangesNoAnswer) {
  struct Case {
    const char* file;
    std::vector<std::string> supports;
  };
  for (const Case& c :
       {Case{"compas_cra/shelf-stable.json", {"0"}}, Case{"compas_cra/snake.json", {"0"}},
        Case{"compas_cra/A.json", {"0", "1"}}}) {
    SCOPED_TRACE(c.file);
    SHARED_OR_SKIP(file, c.file);
    json doc = json::parse(std::ifstream(file));
    json& graph = doc["data"]["graph"]["data"];
    // New names: the keys reversed and offset (a block keeps its geometry).
    std::vector<std::string> keys;
    for (const auto& [k, v] : graph["node"].items()) keys.push_back(k);
    std::map<std::string, std::string> rename, back;
    for (size_t i = 0; i < keys.size(); ++i) {
      rename[keys[i]] = std::to_string(100 + keys.size() - i);
      back[rename[keys[i]]] = keys[i];
    }
    json nodes = json::object(), edges = json::object();
    for (auto it = keys.rbegin(); it != keys.rend(); ++it) nodes[rename[*it]] = graph["node"][*it];
    for (const auto& [u, vs] : graph["edge"].items())
      for (const auto& [v, e] : vs.items()) edges[rename[u]][rename[v]] = e;
    graph["node"] = nodes;
    graph["edge"] = edges;
    const std::string permuted = WriteFile("permuted.json", doc.dump());
    std::string supports, renamed_supports;
    for (const std::string& k : c.supports) {
      supports += (supports.empty() ? "" : ",") + k;
      renamed_supports += (renamed_supports.empty() ? "" : ",") + rename[k];
    }
    for (const double mu : {0.25, 0.55, 0.9}) {
      const json a = Doc(CheckCompas(file, mu, "--supports " + supports));
      const json b = Doc(CheckCompas(permuted, mu, "--supports " + renamed_supports));
      EXPECT_EQ(a["stable"], b["stable"]) << "mu " << mu;
      EXPECT_EQ(a["stability"], b["stability"]) << "mu " << mu;
      std::map<std::string, std::string> motion_a, motion_b;
      for (const json& p : a["parts"])
        if (p.value("moving", false)) motion_a[p["name"]] = p["motion"];
      for (const json& p : b["parts"])
        if (p.value("moving", false)) motion_b[back[p["name"]]] = p["motion"];
      EXPECT_EQ(motion_a, motion_b) << "mu " << mu;
    }
  }
}

// The outcomes of the CRA paper (Kao et al. 2022) that loading from rest
// reproduces: the H and A frames fall at μ 0.84 although an equilibrium
// exists (the squeeze nothing produces), the snake stands at 0.7; and the
// shelf, which the paper shows standing at 0.9, falls: its strut 9 tips off
// the inclined face of strut 5 (its centroid is outside that face's lower
// edge, and tipping lowers its top away from the frame's beam, so the beam
// never presses it down: docs/loaded-from-rest.md). `--rule equilibrium`
// gives the rigid-block-equilibrium answer: all four stand.
TEST(CompasCheck, TheCraOutcomesLoadedFromRest) {
  struct Case {
    const char* file;
    const char* supports;
    double mu;
    int exit_code;
    const char* loaded;  // loaded_from_rest
  };
  SHARED_OR_SKIP(shelf_file, "compas_cra/shelf.json");
  for (const Case& c : {Case{"compas_cra/H.json", "0,1", 0.84, 1, "gives way"},
                        Case{"compas_cra/A.json", "0,1", 0.84, 1, "gives way"},
                        Case{"compas_cra/snake.json", "0", 0.7, 0, "stands"},
                        Case{"compas_cra/shelf.json", "0", 0.9, 1, "gives way"}}) {
    SCOPED_TRACE(c.file);
    SHARED_OR_SKIP(file, c.file);
    const std::string supports = std::string("--supports ") + c.supports;
    const CliRun r = CheckCompas(file, c.mu, supports);
    ASSERT_EQ(r.exit_code, c.exit_code) << r.err << r.out.substr(0, 800);
    const json doc = Doc(r);
    EXPECT_EQ(doc["rule"], "loaded-from-rest");
    EXPECT_EQ(doc["static_equilibrium"], true);
    EXPECT_EQ(doc["loaded_from_rest"], c.loaded);
    EXPECT_NE(doc["stability"], "strong");
    if (c.exit_code == 1) {
      EXPECT_FALSE(doc["moving"].empty());
    }
    // The rigid-block-equilibrium rule: it stands, and strong stability is not
    // proved, so --require strong exits 3.
    const CliRun rbe = CheckCompas(file, c.mu, supports + " --rule equilibrium");
    EXPECT_EQ(rbe.exit_code, 0) << rbe.err;
    EXPECT_EQ(Doc(rbe)["rule"], "equilibrium");
    EXPECT_EQ(CheckCompas(file, c.mu, supports + " --rule equilibrium --require strong").exit_code,
              3);
  }
  // Why the shelf falls, computed another way: strut 9 stands on strut 5's
  // face, inclined more steeply than the friction angle (|n_x|/|n_z| > μ), so
  // on that face alone it slides; the only other contact is the frame's top
  // beam above it, whose push down an equilibrium needs. Sliding down the face
  // moves its top down and away from the beam (velocity z < 0), so loading
  // from rest never produces that push.
  {
    const json doc = Doc(CheckCompas(shelf_file, 0.9, "--supports 0"));
    bool on_five = false;
    for (const json& k : doc["contacts"]) {
      const std::set<std::string> pair = {k["parts"][0], k["parts"][1]};
      if (pair != std::set<std::string>{"5", "9"}) continue;
      on_five = true;
      const double nx = k["normal"][0].get<double>(), nz = k["normal"][2].get<double>();
      EXPECT_GT(std::abs(nx) / std::abs(nz), 0.9) << k.dump();
    }
    EXPECT_TRUE(on_five);
    for (const json& p : doc["parts"])
      if (p["name"] == "9") {
        ASSERT_TRUE(p["moving"].get<bool>());
        EXPECT_LT(p["velocity"]["linear"][2].get<double>(), 0);
      }
  }
  // Strut 9 alone, every other part held: it gives way. (At μ 0.9 Lemke's
  // method fails on this one's loaded-from-rest LCP in both forms, and the
  // equilibrium decides: the component's message says so.)
  SHARED_OR_SKIP(shelf, "compas_cra/shelf.json");
  for (const double mu : {1.0, 2.0, 5.0}) {
    const CliRun r = CheckCompas(shelf, mu, "--supports 0,1,2,3,4,5,6,7,8,10");
    ASSERT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(Doc(r)["moving"], json({"9"})) << "mu " << mu;
  }
  // The bridge with its weights (blocks 11–15) of density 3.51, as the CRA
  // example script makes them (a sidecar gives the densities): it stands at
  // μ 0.9, loaded from rest.
  SHARED_OR_SKIP(bridge, "compas_cra/bridge.json");
  const std::string sidecar =
      WriteFile("bridge_weights.json",
                R"({"cairn_sidecar": 1, "parts": {"11": {"density": 3.51}, "12": {"density": 3.51},
          "13": {"density": 3.51}, "14": {"density": 3.51}, "15": {"density": 3.51}}})");
  const CliRun heavy = CheckCompas(bridge, 0.9, "--supports 0,1 --sidecar " + sidecar);
  ASSERT_EQ(heavy.exit_code, 0) << heavy.err;
  const json heavy_doc = Doc(heavy);
  EXPECT_EQ(heavy_doc["loaded_from_rest"], "stands");
  const json light = Doc(CheckCompas(bridge, 0.9, "--supports 0,1"));
  double heavy_mass = 0, light_mass = 0;
  for (const json& p : heavy_doc["parts"])
    if (p["name"] == "11") heavy_mass = p["mass"].get<double>();
  for (const json& p : light["parts"])
    if (p["name"] == "11") light_mass = p["mass"].get<double>();
  EXPECT_NEAR(heavy_mass, 3.51 * light_mass, 1e-9);
  EXPECT_GT(light_mass, 0);
  // A model that is strongly stable passes --require strong.
  SHARED_OR_SKIP(cubes, "compas_cra/cubes.json");
  EXPECT_EQ(CheckCompas(cubes, 0.84, "--supports 0 --require strong").exit_code, 0);
}

// The cross vault just below its critical friction (μ* = 0.5471): no
// equilibrium, and the verdict says what moves. The mechanism LP's
// interior-point duals left a generator power of −1.2e-6 against gravity's
// power of 54.5, which failed the mechanism's check (1e-6 of the wrench
// scale) and left the component "undecided" after 5 s; the slack now also
// scales with gravity's power along the motion.
TEST(CompasCheck, CrossVaultBelowItsCriticalFrictionSaysWhatMoves) {
  SHARED_OR_SKIP(file, "compas_assembly/crossvault_assembly.json");
  const CliRun r = CheckCompas(file, 0.45);
  ASSERT_EQ(r.exit_code, 1) << r.err;
  const json doc = Doc(r);
  EXPECT_EQ(doc["static_equilibrium"], false);
  EXPECT_FALSE(doc["moving"].empty());
  for (const json& c : doc["components"]) EXPECT_NE(c["decided_by"], "undecided") << c.dump();
}

// `--require strong` on `simulate` and `plan`: a block wedged between two
// walls stands by the equilibrium rule (the walls can squeeze it) but can also
// slide down, so strong stability is not proved: `check` and `simulate` exit
// 3, and `plan` counts no state that holds it as stable. Loaded from rest,
// nothing squeezes it and it falls (exit 1).
TEST(RequireStrong, SimulateExitsThreeAndPlanFindsNoStableState) {
  const std::string scene = WriteFile("wedged.json", R"({"cairn": 1, "friction": 0.5, "parts": [
    {"name": "ground", "fixed": true, "box": {"min": [-4, -1], "max": [6, 0]}},
    {"name": "left wall", "fixed": true, "box": {"min": [-1, 0], "max": [0, 3]}},
    {"name": "right wall", "fixed": true, "box": {"min": [1, 0], "max": [2, 3]}},
    {"name": "wedged", "box": {"min": [0, 1], "max": [1, 2]}},
    {"name": "loose", "box": {"min": [3, 0], "max": [4, 1]}}]})");
  const std::string plan = WriteFile("lift_loose.plan.json", R"({"cairn_plan": 1, "dt": 0.25,
    "steps": [{"remove": ["loose"], "direction": [0, 1], "distance": 2, "support": "none"}]})");
  const std::string rbe = " --rule equilibrium";
  EXPECT_EQ(Cairn("check " + scene + rbe).exit_code, 0);
  EXPECT_EQ(Cairn("check " + scene + rbe + " --require strong").exit_code, 3);
  EXPECT_EQ(Cairn("check " + scene).exit_code, 1);

  const CliRun sim = Cairn("simulate " + scene + " " + plan + rbe + " --json");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_EQ(Doc(sim)["strong_at_rest"], false);
  EXPECT_EQ(Cairn("simulate " + scene + " " + plan + rbe + " --require strong").exit_code, 3);
  EXPECT_EQ(Cairn("simulate " + scene + " " + plan).exit_code, 1);

  const CliRun planned = Cairn("plan " + scene + rbe + " --json");
  ASSERT_EQ(planned.exit_code, 0) << planned.err;
  EXPECT_FALSE(Doc(planned)["sequences"].empty());
  const CliRun strong = Cairn("plan " + scene + rbe + " --require strong --json");
  ASSERT_EQ(strong.exit_code, 1) << strong.err;
  EXPECT_TRUE(Doc(strong)["sequences"].empty());
  EXPECT_NE(Doc(strong)["message"].get<std::string>().find("not stable"), std::string::npos);
}

}  // namespace
}  // namespace cairn

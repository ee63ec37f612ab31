// The `cairn margin` command, run as a user runs it: the real binary, its
// stdout, stderr and exit code. (Its physics: tests/stability/margin_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_run.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Cairn;
using testing::CliRun;
using testing::ExamplePath;

nlohmann::json Margin(const std::string& args, int exit_code = 0) {
  const CliRun r = Cairn("margin " + args + " --json");
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  return nlohmann::json::parse(r.out)["margin"];
}

// --friction alone: the critical μ of a block on a 20° incline is tan 20°,
// below μ = 0.5 (it stands: exit 0); on 30° it is tan 30° > 0.5 (exit 1).
TEST(CliMargin, FrictionJson) {
  const nlohmann::json m = Margin(ExamplePath("incline.json") + " --friction");
  EXPECT_EQ(m["quantity"], "friction");
  EXPECT_NEAR(m["critical"].get<double>(), std::tan(20 * M_PI / 180), 1e-5);
  EXPECT_EQ(m["of"], "mu");
  EXPECT_EQ(m["nominal"], 0.5);
  EXPECT_EQ(m["holds_at_nominal"], true);
  EXPECT_EQ(m["stability"], "weak");
  EXPECT_EQ(m["failing_below"][0]["part"], "block");
  EXPECT_EQ(m["failing_below"][0]["motion"], "slides");
  EXPECT_LT(m["failing_at"].get<double>(), m["critical"].get<double>());
  const nlohmann::json& cert = m["certificates"][0];
  EXPECT_EQ(cert["parts"], nlohmann::json::parse(R"(["block"])"));
  EXPECT_EQ(cert["mechanism"]["found"], true);
  EXPECT_EQ(cert["mechanism"]["parts"][0]["part"], "block");
  EXPECT_EQ(cert["equilibrium"]["contacts"].size(), 2u);
  EXPECT_LE(m["tolerance"].get<double>(), 1e-6);
  const nlohmann::json slides = Margin(ExamplePath("incline_slides.json") + " --friction", 1);
  EXPECT_NEAR(slides["critical"].get<double>(), std::tan(30 * M_PI / 180), 1e-5);
  EXPECT_EQ(slides["holds_at_nominal"], false);
}

// --friction MU with --tilt: MU is the model's μ; the tilt's keys.
TEST(CliMargin, TiltJsonWithFrictionValue) {
  const nlohmann::json m = Margin(ExamplePath("overhang.json") + " --friction 3 --tilt 0,0,1");
  EXPECT_EQ(m["quantity"], "tilt");
  EXPECT_EQ(m["axis"], nlohmann::json::parse("[0, 0, 1]"));
  ASSERT_EQ(m["critical_deg"].size(), 2u);
  EXPECT_NEAR(m["critical_deg"][0].get<double>(), -std::atan(0.8) * 180 / M_PI, 1e-5);
  EXPECT_NEAR(m["critical_deg"][1].get<double>(), std::atan(2.0) * 180 / M_PI, 1e-5);
  EXPECT_EQ(m["certificates"][1]["sense"], "positive");
}

// --load: the largest load, in force units and in the part's weight; null
// when the load alone is carried.
TEST(CliMargin, LoadJson) {
  const nlohmann::json m =
      Margin(ExamplePath("paper_fig16.json") + " --load Q --point 5,1.5 --direction 0,-1");
  EXPECT_EQ(m["quantity"], "load");
  EXPECT_EQ(m["part"], "Q");
  const double F = m["critical"].get<double>();
  EXPECT_NEAR(F, 0.48 * 6.96 / 4.52, 1e-6);
  EXPECT_NEAR(m["critical_weights"].get<double>(), F / m["part_weight"].get<double>(), 1e-12);
  const nlohmann::json any =
      Margin(ExamplePath("paper_fig16.json") + " --load Q --point 0,1.5 --direction 0,-1");
  EXPECT_TRUE(any["critical"].is_null());
}

// The same command prints the same document.
TEST(CliMargin, Deterministic) {
  const std::string args = "margin " + ExamplePath("ladder.json") + " --friction --json";
  EXPECT_EQ(Cairn(args).out, Cairn(args).out);
}

// Bad input: exit 2 and one line naming what is wrong; nothing on stdout.
TEST(CliMargin, BadInput) {
  const std::string scene = ExamplePath("incline.json");
  for (const std::string& args :
       {std::string("margin ") + scene, "margin " + scene + " --friction --tilt 0,0,1",
        "margin " + scene + " --tilt 1,0,0", "margin " + scene + " --tilt 0,0",
        "margin " + scene + " --load nope --point 0,0 --direction 1,0",
        "margin " + scene + " --load incline --point 0,0 --direction 1,0",
        "margin " + scene + " --load block --point 0,0", "margin " + scene + " --friction x",
        "margin " + scene + " --load block --point 0,0 --direction 0,0"}) {
    const CliRun r = Cairn(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_EQ(r.err.rfind("cairn: error: ", 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// The summary says what each list of parts is: for the friction margin the
// check just below μ* (the contact dynamics from rest) and the mechanism;
// for a tilt each sense, named; a long list is cut after 12 names, with how
// many more.
TEST(CliMargin, TextSaysWhatEachListIs) {
  CliRun r = Cairn("margin " + ExamplePath("incline.json") + " --friction");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  below it: the check at mu = "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" (the contact dynamics from rest) moves 1 part: block slides\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  below it: the mechanism at mu = "), std::string::npos) << r.out;
  r = Cairn("margin " + ExamplePath("wall.json") + " --tilt 0,0,1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("° (negative sense) / "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("° (positive sense)\n"), std::string::npos) << r.out;
  const size_t negative = r.out.find("\n  negative sense: the mechanism at -");
  const size_t positive = r.out.find("\n  positive sense: the mechanism at ");
  ASSERT_NE(negative, std::string::npos) << r.out;
  ASSERT_NE(positive, std::string::npos) << r.out;
  EXPECT_LT(negative, positive);
  // 35 bricks move each way: 12 named, then how many more.
  const nlohmann::json doc = Margin(ExamplePath("wall.json") + " --tilt 0,0,1");
  const size_t moving = doc["certificates"][0]["mechanism"]["parts"].size();
  ASSERT_GT(moving, 12u);
  const std::string more = ", … and " + std::to_string(moving - 12) + " more (every one: --json)\n";
  EXPECT_NE(r.out.find(more, negative), std::string::npos) << r.out;
  const std::string line = r.out.substr(negative + 1, r.out.find('\n', negative + 1) - negative);
  EXPECT_EQ(std::count(line.begin(), line.end(), ','), 12) << line;
  // A sense that holds all the way round says so.
  r = Cairn("margin " + ExamplePath("jenga.json") + " --tilt 0,0,1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("none in the negative sense (it holds all the way round) / none in the "
                       "positive sense"),
            std::string::npos)
      << r.out;
}

// No weight (zero gravity): the load is not given as a ratio of it.
TEST(CliMargin, LoadWithoutWeightGivesNoRatio) {
  const CliRun r = Cairn("margin " + ExamplePath("stack3.json") +
                         " --load A --point 0,1 --direction 1,0 --gravity=0,0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(A has no weight: gravity is zero)"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("of its weight"), std::string::npos) << r.out;
}

// A COMPAS file stores no friction: --friction without a value beside
// another margin is refused, saying that it needs the blocks' μ.
TEST(CliMargin, CompasFrictionNeedsAValue) {
  const std::string cubes = testing::SharedDir() + "/datasets/compas_cra/cubes.json";
  if (testing::SharedDir().empty() || !std::filesystem::exists(cubes))
    GTEST_SKIP() << "the shared data (CAIRN_SHARED_DIR) is absent";
  const CliRun r =
      Cairn("margin " + cubes + " --format compas --supports 0 --tilt 0,1,0 --friction");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(r.err.rfind("cairn: error: --friction: needs a value with --format compas: the blocks' "
                        "friction coefficient",
                        0),
            0u)
      << r.err;
  const CliRun ok = Cairn("margin " + cubes +
                          " --format compas --supports 0 --tilt 0,1,0 --friction 0.84 --json");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// simulate --margin friction: the least μ for which the plan (Fig. 4, A
// lifted) is stable at every tick. The check of it by the command itself:
// simulate with --friction just above is stable (exit 0), just below fails
// (exit 1) at the deciding tick.
TEST(CliMargin, SimulateMarginFriction) {
  const std::string scene = ExamplePath("paper_fig4.json");
  const std::string plan = ExamplePath("plans/paper_fig4_lift_a.plan.json");
  const CliRun r = Cairn("simulate " + scene + " " + plan + " --margin friction --json");
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
  const nlohmann::json m = nlohmann::json::parse(r.out)["margin"];
  EXPECT_EQ(m["quantity"], "friction");
  ASSERT_TRUE(m["critical"].is_number()) << m.dump();
  const double mu = m["critical"].get<double>();
  EXPECT_GT(mu, 0);
  EXPECT_LE(m["tolerance"].get<double>(), 1e-4 * mu);
  const nlohmann::json& deciding = m["deciding"];
  EXPECT_EQ(deciding["step"], 0);
  const auto run = [&](double f) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", f);
    return Cairn("simulate " + scene + " " + plan + " --friction " + buf + " --json");
  };
  EXPECT_EQ(run(mu * 1.001).exit_code, 0);
  const CliRun below = run(mu * 0.999);
  EXPECT_EQ(below.exit_code, 1);
  EXPECT_EQ(nlohmann::json::parse(below.out)["failure"]["tick"], deciding["tick"]);
  // A plan stable without friction: 0, and no deciding tick.
  const CliRun dcba =
      Cairn("simulate " + ExamplePath("paper_fig1.json") + " " +
            ExamplePath("plans/paper_fig1_dcba.plan.json") + " --margin friction --json");
  ASSERT_EQ(dcba.exit_code, 0) << dcba.err;
  const nlohmann::json m0 = nlohmann::json::parse(dcba.out)["margin"];
  EXPECT_EQ(m0["critical"], 0.0);
  EXPECT_TRUE(m0["deciding"].is_null());
}

}  // namespace
}  // namespace cairn

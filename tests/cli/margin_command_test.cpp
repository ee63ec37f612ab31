// The `cairn margin` command, run as a user runs it: the real binary, its
// stdout, stderr and exit code. (Its physics: tests/stability/margin_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

// check_report.h: the document of `cairn check --json` (a public contract)
// and its text summary, on the paper's Fig. 1.
#include "cairn/report/check_report.h"

#include <gtest/gtest.h>

#include <cmath>

#include "example_scene.h"

namespace cairn {
namespace {

TEST(StabilityToJson, TheContractsKeysAndTheForcesBalanceTheWeights) {
  const testing::ExampleScene fig1("paper_fig1.json");
  const Configuration config = Configuration::Assembled(fig1.assembly);
  const StabilityResult r = AnalyzeConfiguration(fig1.assembly, config);
  const nlohmann::json doc = StabilityToJson(fig1.assembly, config, r, {});
  for (const char* key :
       {"scene", "verdict", "stable", "dimension", "formulation", "without", "moving",
        "static_equilibrium", "weakly_stable", "stability", "force_unit", "parts", "contacts",
        "components", "tolerances", "diagnostics"})
    EXPECT_TRUE(doc.contains(key)) << key;
  EXPECT_EQ(doc["verdict"], "stable");
  EXPECT_EQ(doc["dimension"], 2);
  // The vertical components of the contact forces on the movable parts
  // balance their weights (normal forces along the normals, friction along
  // the tangents: the forces on part a of each contact).
  double up = 0, weight = 0;
  for (const nlohmann::json& c : doc["contacts"]) {
    const double fn = c["normal_force"];
    const double ny = c["normal"][1];
    const double nx = c["normal"][0];
    const double ft = c["friction_force"];  // along t = (−n_y, n_x)
    const double fy = fn * ny + ft * nx;
    const std::string a = c["parts"][0], b = c["parts"][1];
    if (!fig1.assembly.part(fig1.Part(a)).fixed) up += fy;
    if (b != "world" && !fig1.assembly.part(fig1.Part(b)).fixed) up -= fy;
  }
  for (const Part& p : fig1.assembly.parts())
    if (!p.fixed) weight += p.mass * fig1.assembly.gravity().norm();
  EXPECT_NEAR(up, weight, 1e-6 * weight);
}

TEST(StabilityToText, NamesTheVerdictAndTheMovingPart) {
  const testing::ExampleScene fig1("paper_fig1.json");
  Configuration config = Configuration::Assembled(fig1.assembly);
  config.present[fig1.Part("C")] = false;
  const StabilityResult r = AnalyzeConfiguration(fig1.assembly, config);
  ReportOptions options;
  options.without = {fig1.Part("C")};
  const std::string text = StabilityToText(fig1.assembly, config, r, options);
  EXPECT_NE(text.find("UNSTABLE"), std::string::npos) << text;
  EXPECT_NE(text.find("B "), std::string::npos) << text;  // B moves (the paper, Section II)
}

}  // namespace
}  // namespace cairn

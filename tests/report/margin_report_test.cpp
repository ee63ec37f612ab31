// report/margin_report.h: the margin in JSON and in words, on the block on
// a 20° incline whose critical friction is tan 20° (analytic).
#include "cairn/report/margin_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "cairn/io/scene_reader.h"
#include "test_paths.h"

namespace cairn {
namespace {

TEST(MarginReport, TheInclineAtTanTwentyDegreesInJsonAndInWords) {
  const AssemblyDef def = ReadSceneDef(testing::ExamplePath("incline.json"));
  const Assembly assembly = Assembly::Create(def);
  const Configuration config = Configuration::Assembled(assembly);
  const MarginRequest request;  // the friction margin
  const MarginResult result = ComputeMargin(def, assembly, config, request);
  ReportOptions report;
  report.scene_file = "incline.json";
  const nlohmann::json doc = MarginToJson(assembly, request, result, report);
  const nlohmann::json& m = doc["margin"];
  const double mu_star = std::tan(20 * std::numbers::pi / 180);
  EXPECT_EQ(m["quantity"], "friction");
  EXPECT_EQ(m["of"], "mu");
  EXPECT_EQ(m["nominal"], 0.5);
  EXPECT_NEAR(m["critical"].get<double>(), mu_star, 1e-5);
  EXPECT_TRUE(m["holds_at_nominal"].get<bool>());
  // Below it the block slides (it cannot turn on a face it presses flat).
  ASSERT_EQ(m["failing_below"].size(), 1u);
  EXPECT_EQ(m["failing_below"][0]["part"], "block");
  EXPECT_EQ(m["failing_below"][0]["motion"], "slides");
  EXPECT_LT(m["failing_at"].get<double>(), m["critical"].get<double>());
  const std::string text = MarginToText(assembly, request, result, report);
  EXPECT_NE(text.find("critical friction mu* = 0.36397"), std::string::npos) << text;
  EXPECT_NE(text.find("block slides"), std::string::npos) << text;
}

}  // namespace
}  // namespace cairn

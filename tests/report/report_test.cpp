// report.h: the force unit every report states.
#include "cairn/report/report.h"

#include <gtest/gtest.h>

#include "example_scene.h"

namespace cairn {
namespace {

TEST(ForceScale, ForceUnitsUnlessAPartNormalisesThemByItsWeight) {
  const testing::ExampleScene fig1("paper_fig1.json");
  ReportOptions options;
  EXPECT_EQ(ForceScale(fig1.assembly, options), std::make_pair(1.0, std::string("force units")));
  const int b = fig1.Part("B");
  options.normalize_part = b;
  const auto [scale, unit] = ForceScale(fig1.assembly, options);
  const Part& part = fig1.assembly.part(b);
  EXPECT_DOUBLE_EQ(scale, part.mass * fig1.assembly.gravity().norm());
  EXPECT_EQ(unit, "weight of B");
}

}  // namespace
}  // namespace cairn

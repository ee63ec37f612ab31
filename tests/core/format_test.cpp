// format.h: numbers and points as messages and reports write them.
#include "cairn/core/format.h"

#include <gtest/gtest.h>

namespace cairn {
namespace {

TEST(FormatNumber, SixSignificantDigitsAsStreamsWriteThem) {
  EXPECT_EQ(FormatNumber(0.5), "0.5");
  EXPECT_EQ(FormatNumber(1.0 / 3.0), "0.333333");
  EXPECT_EQ(FormatNumber(1e308), "1e+308");
}

TEST(FormatPoint, TwoOrThreeCoordinatesWithFourDigitsAndNoRoundoffDust) {
  EXPECT_EQ(FormatPoint({1, 1.25, 7}, 2), "(1, 1.25)");
  EXPECT_EQ(FormatPoint({1, 1.25, 7}, 3), "(1, 1.25, 7)");
  EXPECT_EQ(FormatPoint({1.0 / 3.0, -2, 0}, 2), "(0.3333, -2)");
  // A unit axis computed with roundoff reads as the axis.
  EXPECT_EQ(FormatPoint({1, 1e-17, -3e-12}, 3), "(1, 0, 0)");
  // Dust is relative to the largest coordinate: 1e-3 next to 1e7 is dust.
  EXPECT_EQ(FormatPoint({1e7, 1e-3, 0}, 2), "(1e+07, 0)");
}

}  // namespace
}  // namespace cairn

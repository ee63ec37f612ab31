#include "cairn/core/tolerances.h"

#include <gtest/gtest.h>

#include "cairn/core/error.h"

namespace cairn {
namespace {

// Tolerances scale with the scene: doubling the size doubles the length
// tolerance; the acceleration tolerance follows |g|; velocity follows |g|·Δt.
TEST(Tolerances, ScaleWithSceneSizeGravityAndStep) {
  const Tolerances a = Tolerances::Scaled(10.0, 9.81, 1.0, 5.0);
  const Tolerances b = Tolerances::Scaled(20.0, 1.0, 0.5, 5.0);
  EXPECT_DOUBLE_EQ(a.length, 1e-5);
  EXPECT_DOUBLE_EQ(b.length, 2e-5);
  EXPECT_DOUBLE_EQ(a.acceleration, 9.81e-6);
  EXPECT_DOUBLE_EQ(b.acceleration, 1e-6);
  EXPECT_DOUBLE_EQ(b.velocity, 0.5e-6);
}

TEST(Tolerances, OverrideAndDegenerateScales) {
  const Tolerances t = Tolerances::Scaled(0.0, 0.0, 0.0, 0.0, 1e-3);
  EXPECT_DOUBLE_EQ(t.length, 1e-3);
  EXPECT_GT(t.acceleration, 0.0);
  EXPECT_GT(t.velocity, 0.0);
  EXPECT_GT(t.force, 0.0);
}

TEST(InputError, WhatNamesFilePathAndMessage) {
  const InputError e("scene.json", "parts[2].polygon[3]", "is not a number");
  EXPECT_STREQ(e.what(), "scene.json: parts[2].polygon[3]: is not a number");
  EXPECT_EQ(e.json_path(), "parts[2].polygon[3]");
}

}  // namespace
}  // namespace cairn

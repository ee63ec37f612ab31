// planning/sequence.h: build orders with the fewest holds, on the examples.
#include "cairn/planning/sequence.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/io/scene_reader.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::ExamplePath;

// Three offset blocks on a table: each stands on the one below, so the order
// bottom-up needs no hold, and a block alone on the table stands: bound 0.
TEST(FindBuildSequence, AStackGoesUpWithoutSupport) {
  const Assembly a = ReadScene(ExamplePath("stack3.json"));
  const BuildSequence s = FindBuildSequence(a);
  ASSERT_TRUE(s.complete) << s.message;
  ASSERT_EQ(s.steps.size(), 3u);
  EXPECT_EQ(a.part(s.steps[0].part).name, "A");
  EXPECT_EQ(a.part(s.steps[2].part).name, "C");
  EXPECT_EQ(s.max_in_place, 0);
  EXPECT_EQ(s.lower_bound, 0);
  EXPECT_TRUE(s.optimal());
  for (const SequenceStep& step : s.steps) {
    EXPECT_TRUE(step.stands);
    EXPECT_TRUE(step.in_place.empty());
    // Arriving from above: against gravity's reverse.
    EXPECT_NEAR(step.direction.y(), -1.0, 1e-12);
  }
}

// The overhang example with no hold allowed: whatever it finds, no state
// holds a part, and an incomplete search says why.
TEST(FindBuildSequence, NoHoldAllowedMeansNone) {
  const Assembly a = ReadScene(ExamplePath("overhang.json"));
  SequenceOptions options;
  options.max_temporary = 0;
  const BuildSequence s = FindBuildSequence(a, options);
  for (const SequenceStep& step : s.steps) EXPECT_TRUE(step.in_place.empty());
  if (!s.complete) {
    EXPECT_FALSE(s.message.empty());
  }
}

TEST(FindBuildSequence, RefusesBadOptions) {
  const Assembly a = ReadScene(ExamplePath("stack3.json"));
  SequenceOptions options;
  options.beam_width = 0;
  EXPECT_THROW(FindBuildSequence(a, options), std::invalid_argument);
  options.beam_width = 1;
  options.directions = {Vector3::Zero()};
  EXPECT_THROW(FindBuildSequence(a, options), std::invalid_argument);
}

}  // namespace
}  // namespace cairn

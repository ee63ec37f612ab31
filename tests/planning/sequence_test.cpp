// planning/sequence.h: build orders with the fewest holds, on the examples.
#include "cairn/planning/sequence.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "cairn/io/scene_reader.h"
#include "cairn/stability/analyze.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::ExamplePath;

// A 2-D part of the polygon given (counter-clockwise).
PartDef part(const std::string& name, bool fixed, std::vector<Vector2> polygon) {
  PartDef p;
  p.name = name;
  p.fixed = fixed;
  p.polygon = std::move(polygon);
  return p;
}

// `s` is complete and places the parts named, in that order.
void ExpectOrder(const Assembly& a, const BuildSequence& s, const std::vector<std::string>& names) {
  ASSERT_TRUE(s.complete) << s.message;
  ASSERT_EQ(s.steps.size(), names.size());
  for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(a.part(s.steps[i].part).name, names[i]) << i;
}

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

// The cache of state checks only saves time: capped at 8 states (it starts
// afresh ever so often), the search finds the same order with the same
// holds, checking more states.
TEST(FindBuildSequence, TheCachesCapChangesNoAnswer) {
  int recomputed = 0;
  for (const char* example : {"wall.json", "pyramid14.json", "paper_fig4.json"}) {
    SCOPED_TRACE(example);
    const Assembly a = ReadScene(ExamplePath(example));
    SequenceOptions options;
    options.directions = {Vector3(0, 1, 0), Vector3(1, 0, 0), Vector3(-1, 0, 0)};
    const BuildSequence full = FindBuildSequence(a, options);
    options.max_cached_states = 8;
    const BuildSequence capped = FindBuildSequence(a, options);
    EXPECT_EQ(capped.complete, full.complete);
    EXPECT_EQ(capped.max_in_place, full.max_in_place);
    EXPECT_EQ(capped.placements, full.placements);
    ASSERT_EQ(capped.steps.size(), full.steps.size());
    for (size_t i = 0; i < full.steps.size(); ++i) {
      EXPECT_EQ(capped.steps[i].part, full.steps[i].part) << i;
      EXPECT_EQ(capped.steps[i].added, full.steps[i].added) << i;
      EXPECT_EQ(capped.steps[i].removed, full.steps[i].removed) << i;
    }
    EXPECT_GE(capped.states_checked, full.states_checked);
    if (capped.states_checked > full.states_checked) ++recomputed;
  }
  EXPECT_GE(recomputed, 2);  // the cap was reached
}

// A plug that just fits between two walls, on a key that comes in from the
// side under the right wall (2-D, μ 0.5). The plug alone has a rigid
// equilibrium (the walls could squeeze it: the LP passes it) but loaded
// from rest nothing squeezes it and it falls (the check's verdict,
// docs/loaded-from-rest.md). Both orders pass the LP, and the plug first
// wins the tie (by name); the confirmation rejects its first state, and the
// search, repaired with its beam confirmed by the verdict, builds the key
// first: the verdict rejects the plug-first state as it enters the beam.
TEST(FindBuildSequence, AStateTheLpPassesAndTheVerdictRejectsIsRepaired) {
  AssemblyDef def;
  def.friction = 0.5;
  def.parts = {part("ground", true, {{-5, -1}, {5, -1}, {5, 0}, {-5, 0}}),
               part("left", true, {{-2, 0}, {-1, 0}, {-1, 3}, {-2, 3}}),
               part("right", true, {{1, 1}, {2, 1}, {2, 3}, {1, 3}}),
               part("a_plug", false, {{-1, 1}, {1, 1}, {1, 2}, {-1, 2}}),
               part("b_key", false, {{-1, 0}, {1.8, 0}, {1.8, 1}, {-1, 1}})};
  const Assembly a = Assembly::Create(def, "plug and key");
  SequenceOptions options;
  options.directions = {Vector3(0, 1, 0), Vector3(1, 0, 0), Vector3(-1, 0, 0)};
  const BuildSequence s = FindBuildSequence(a, options);
  ExpectOrder(a, s, {"b_key", "a_plug"});
  EXPECT_EQ(s.repairs, 1);
  EXPECT_GE(s.verdict_rejections, 1);
  EXPECT_EQ(s.max_in_place, 0);
  EXPECT_TRUE(s.optimal());
  for (const SequenceStep& step : s.steps) EXPECT_TRUE(step.stands);
  // Arriving from above only, the key is blocked by the right wall for
  // good: no order exists. The LP-led search placed the plug alone; the
  // verdict rejects that, so the repaired search places it held (the
  // children the verdict turns down are tried with a support more), and
  // then the key cannot arrive. The bound says that in no order can every
  // part arrive.
  options.directions = {Vector3(0, 1, 0)};
  const BuildSequence blocked = FindBuildSequence(a, options);
  EXPECT_FALSE(blocked.complete);
  EXPECT_NE(blocked.message.find("no part left can arrive along the directions tried after 1 of 2"),
            std::string::npos)
      << blocked.message;
  ASSERT_EQ(blocked.steps.size(), 1u);
  EXPECT_EQ(a.part(blocked.steps[0].part).name, "a_plug");
  ASSERT_EQ(blocked.steps[0].added.size(), 1u);
  EXPECT_EQ(blocked.steps[0].added[0].kind, TemporaryKind::kHold);
  EXPECT_EQ(a.part(blocked.steps[0].added[0].part).name, "a_plug");
  EXPECT_TRUE(blocked.steps[0].stands);
  EXPECT_NE(blocked.lower_bound_reason.find("in none can every part arrive"), std::string::npos)
      << blocked.lower_bound_reason;
  // The state the LP passed: the plug alone has an equilibrium, and the
  // check says it falls.
  Configuration plug_alone = Configuration::Assembled(a);
  plug_alone.present[a.FindPart("b_key")] = false;
  EXPECT_FALSE(AnalyzeConfiguration(a, plug_alone).stable());
}

// A slanted post leans over a block on a pedestal (2-D, arriving from
// above): the post's centroid is lower, so the greedy order (lower parts
// first) would place it first, and then the block could never arrive: its
// way in from above is under the post's top. The search places the block
// first, and says the post closes the block's last way in by counting the
// parts it would strand.
TEST(FindBuildSequence, APartIsNotPlacedWhereItClosesAnothersLastWayIn) {
  AssemblyDef def;
  def.friction = 0.5;
  def.parts = {part("ground", true, {{-5, -1}, {8, -1}, {8, 0}, {-5, 0}}),
               part("pedestal", true, {{3, 0}, {4, 0}, {4, 2}, {3, 2}}),
               part("post", false, {{0, 0}, {2, 0}, {3.5, 4}, {1.5, 4}}),
               part("block", false, {{3, 2}, {4, 2}, {4, 2.5}, {3, 2.5}})};
  const Assembly a = Assembly::Create(def, "post over a block");
  // The premise: the post is lower, and it blocks the block from above.
  ASSERT_LT(a.part(a.FindPart("post")).centroid.y(), a.part(a.FindPart("block")).centroid.y());
  SequenceOptions options;
  options.beam_width = 1;  // greedy: no other state kept to fall back on
  const BuildSequence s = FindBuildSequence(a, options);
  ExpectOrder(a, s, {"block", "post"});
  EXPECT_EQ(s.max_in_place, 0);
  EXPECT_TRUE(s.optimal());
  for (const SequenceStep& step : s.steps) EXPECT_TRUE(step.stands);
}

// Parts that can only arrive from below a table (removed downwards, through
// it): none can arrive first, and both the search and the bound say so.
TEST(FindBuildSequence, PartsThatCannotArriveAreSaidToBeBlocked) {
  const Assembly a = ReadScene(ExamplePath("stack3.json"));
  SequenceOptions options;
  options.directions = {Vector3(0, -1, 0)};
  const BuildSequence s = FindBuildSequence(a, options);
  EXPECT_FALSE(s.complete);
  EXPECT_TRUE(s.steps.empty());
  EXPECT_NE(s.message.find("no part left can arrive along the directions tried after 0 of 3"),
            std::string::npos)
      << s.message;
  EXPECT_NE(s.lower_bound_reason.find("in none can every part arrive"), std::string::npos)
      << s.lower_bound_reason;
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

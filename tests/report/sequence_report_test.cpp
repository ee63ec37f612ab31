// report/sequence_report.h: the document and the words of a build order.
#include "cairn/report/sequence_report.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/io/scene_reader.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::ExamplePath;

// A hand-made order of stack3 with one hold: the keys of the public
// contract, the hold's force in the scene's force unit, and the words.
TEST(SequenceReport, KeysAndWords) {
  const Assembly a = ReadScene(ExamplePath("stack3.json"));
  BuildSequence s;
  s.complete = true;
  SequenceStep step;
  step.part = a.FindPart("A");
  step.direction = {0, -1, 0};
  step.stands = true;
  TemporarySupport t;
  t.part = step.part;
  t.point = a.part(t.part).centroid;
  step.added = {t};
  t.force = {0, 9.81, 0};
  step.in_place = {t};
  s.steps = {step};
  s.max_in_place = 1;
  s.placements = 1;
  s.lower_bound = 1;
  s.lower_bound_reason = "because";
  const nlohmann::json j = SequenceToJson(a, s, 0.5, {});
  EXPECT_EQ(j["order"], nlohmann::json({"A"}));
  const nlohmann::json& st = j["steps"][0];
  EXPECT_EQ(st["place"], "A");
  EXPECT_EQ(st["direction"], nlohmann::json({0.0, -1.0}));
  ASSERT_EQ(st["added"].size(), 1u);
  EXPECT_EQ(st["added"][0]["kind"], "hold");
  EXPECT_EQ(st["added"][0]["part"], "A");
  EXPECT_FALSE(st["added"][0].contains("force"));
  EXPECT_EQ(st["temporary_in_place"][0]["kind"], "hold");
  EXPECT_EQ(st["temporary_in_place"][0]["force"], nlohmann::json({0.0, 9.81}));
  EXPECT_EQ(st["verdict"], "stands");
  EXPECT_EQ(j["temporary"]["optimal"], true);
  EXPECT_EQ(j["stats"]["seconds"], 0.5);
  const std::string text = SequenceToText(a, s, {});
  EXPECT_NE(text.find("1. place A"), std::string::npos);
  EXPECT_NE(text.find("hold A"), std::string::npos);
  EXPECT_NE(text.find("(optimal)"), std::string::npos);
}

}  // namespace
}  // namespace cairn

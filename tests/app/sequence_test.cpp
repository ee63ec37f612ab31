// app/sequence.h: `cairn sequence` as the CLI runs it.
#include "cairn/app/sequence.h"

#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "test_paths.h"

namespace cairn::app {
namespace {

using testing::ExamplePath;

TEST(SequenceDocument, StackDocumentAndWords) {
  const Model m = LoadModel(ExamplePath("stack3.json"), {});
  const CommandResult r = SequenceDocument(m, {});
  EXPECT_EQ(r.exit, kExitStable);
  EXPECT_EQ(r.document["order"], nlohmann::json({"A", "B", "C"}));
  EXPECT_EQ(r.document["temporary"]["optimal"], true);
  EXPECT_NE(r.text.find("place A"), std::string::npos);
}

TEST(SequenceDocument, BadOptionsNameTheFlag) {
  const Model m = LoadModel(ExamplePath("stack3.json"), {});
  const auto refused = [&](const SequenceQuery& q) {
    try {
      SequenceDocument(m, q);
    } catch (const InputError& e) {
      return e.json_path();
    }
    return std::string("accepted");
  };
  SequenceQuery q;
  q.temporary = "crane";
  EXPECT_EQ(refused(q), "--temporary");
  for (const char* kinds : {"hold", "prop", "both"}) {
    q.temporary = kinds;
    EXPECT_EQ(refused(q), "accepted") << kinds;
  }
  q = {};
  q.direction = {0, 0};
  EXPECT_EQ(refused(q), "--direction");
  q = {};
  q.directions = "sideways";
  EXPECT_EQ(refused(q), "--directions");
  q.directions = "ndbg";  // built now
  EXPECT_EQ(refused(q), "accepted");
}

}  // namespace
}  // namespace cairn::app

#include "cairn/io/paths_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "cairn/core/error.h"
#include "cairn/io/scene_reader.h"
#include "io/bad_input.h"
#include "test_paths.h"

namespace cairn {
namespace {

using ::testing::HasSubstr;
using testing::WriteTemp;

Assembly Fig1() { return ReadScene(testing::ExamplePath("paper_fig1.json")); }

TEST(ReadCandidatePaths, ReadsPolylinesAndSteps) {
  const Assembly a = Fig1();
  const auto paths = ReadCandidatePaths(
      WriteTemp(
          "paths_good.json",
          R"({"C": [[[0, 0], [0, 2]], {"direction": [-1, 0], "distance": 3, "label": "left"}]})"),
      a);
  const int c = a.FindPart("C");
  ASSERT_EQ(paths.count(c), 1u);
  ASSERT_EQ(paths.at(c).size(), 2u);
  EXPECT_EQ(paths.at(c)[1].label, "left");
  EXPECT_DOUBLE_EQ(paths.at(c)[0].path.back().y(), 2.0);
}

// The key is the part's name; a fault inside one of its paths names
// the part after the key, `C ("C")[0].direction`; an unknown part's key is
// reported bare (the name is the fault), escaped so the message stays on one
// line.
TEST(ReadCandidatePaths, FaultsNameThePart) {
  const Assembly a = Fig1();
  struct Case {
    const char* text;
    const char* path;
    const char* phrase;
  };
  const Case cases[] = {
      {R"({"C": [{"direction": [0, 0], "distance": 1}]})", R"(C ("C")[0].direction)",
       "must not be zero"},
      {R"({"C": [[[0, 0], [0, 1]], [[0, 0], [0, "up"]]]})", R"(C ("C")[1].path[1][1])",
       "must be a number"},
      {R"({"C": [{"remove": ["C"], "path": [[0, 0], [0, 1]]}]})", R"(C ("C")[0].remove)",
       "give no `remove`"},
      {R"({"C": []})", R"(C ("C"))", "non-empty list"},
      {R"({"E": [[[0, 0], [0, 1]]]})", R"(E ("E"))", "is fixed"},
      {R"({"Q": [[[0, 0], [0, 1]]]})", "Q", "no part named 'Q'"},
      {R"({"Q\"\n": [[[0, 0], [0, 1]]]})", R"(Q\"\n)", R"(no part named 'Q\"\n')"},
  };
  for (const Case& c : cases) {
    const std::string file = WriteTemp("paths_bad.json", c.text);
    try {
      ReadCandidatePaths(file, a);
      ADD_FAILURE() << "no error: " << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.json_path(), c.path) << e.what();
      EXPECT_THAT(e.what(), HasSubstr(file + ": " + c.path + ": "));
      EXPECT_THAT(e.message(), HasSubstr(c.phrase)) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace cairn

// io/json_line.h: a line of a JSON-lines file with the readers' checks.
#include "cairn/io/json_line.h"

#include <gtest/gtest.h>

#include <string>

namespace cairn {
namespace {

TEST(ParseJsonLine, AJsonTextParses) {
  const JsonLine line = ParseJsonLine(R"({"id": 3, "command": "check", "model": "a.json"})");
  ASSERT_TRUE(line.value.has_value());
  EXPECT_EQ((*line.value)["id"], 3);
  EXPECT_TRUE(line.why.empty());
}

TEST(ParseJsonLine, RefusedWithWhereAndWhy) {
  const JsonLine dup = ParseJsonLine(R"({"id": 1, "options": {"a": 1, "a": 2}})");
  EXPECT_FALSE(dup.value);
  EXPECT_NE(dup.why.find("options.a"), std::string::npos) << dup.why;
  EXPECT_NE(dup.why.find("duplicate key"), std::string::npos) << dup.why;

  const JsonLine deep = ParseJsonLine(std::string(100000, '[') + std::string(100000, ']'));
  EXPECT_FALSE(deep.value);
  EXPECT_NE(deep.why.find("nested more than 256"), std::string::npos) << deep.why;

  const JsonLine nul = ParseJsonLine(std::string("{\"id\": 1}\0", 10));
  EXPECT_FALSE(nul.value);
  EXPECT_NE(nul.why.find("NUL byte"), std::string::npos) << nul.why;

  const JsonLine cut = ParseJsonLine(R"({"id": 1, "result": [1, 2)");
  EXPECT_FALSE(cut.value);
  EXPECT_TRUE(cut.cut_short);

  const JsonLine junk = ParseJsonLine(R"({"id": 1} trailing)");
  EXPECT_FALSE(junk.value);
  EXPECT_FALSE(junk.cut_short);
  EXPECT_NE(junk.why.find("at column"), std::string::npos) << junk.why;
}

}  // namespace
}  // namespace cairn

// error.h: an InputError says where (file, JSON path with the part's name)
// and what, in one line that no name can break.
#include "cairn/core/error.h"

#include <gtest/gtest.h>

namespace cairn {
namespace {

TEST(InputError, WhatIsFileThenPathThenMessage) {
  const InputError e("scene.json", "parts[1].polygon", "self-intersecting");
  EXPECT_STREQ(e.what(), "scene.json: parts[1].polygon: self-intersecting");
  EXPECT_EQ(e.file(), "scene.json");
  EXPECT_EQ(e.json_path(), "parts[1].polygon");
  EXPECT_EQ(e.message(), "self-intersecting");
}

TEST(JsonQuoted, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(JsonQuoted("A"), "\"A\"");
  EXPECT_EQ(JsonQuoted("a\"b\\c\nd"), "\"a\\\"b\\\\c\\nd\"");
  EXPECT_EQ(JsonQuoted(std::string("x\x01y")), "\"x\\u0001y\"");
  EXPECT_EQ(EscapedName("a\"b"), "a\\\"b");
}

TEST(NamedPath, PutsTheNamesAfterThePathAndLeavesOutEmptyOnes) {
  EXPECT_EQ(NamedPath("parts[1]", "A"), "parts[1] (\"A\")");
  EXPECT_EQ(NamedPath("steps[0]", std::vector<std::string>{"B", "C"}), "steps[0] (\"B\", \"C\")");
  EXPECT_EQ(NamedPath("parts[2]", ""), "parts[2]");
  EXPECT_EQ(NamedPath("parts[3]", "new\nline"), "parts[3] (\"new\\nline\")");
}

}  // namespace
}  // namespace cairn

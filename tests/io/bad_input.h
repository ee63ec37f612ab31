#pragma once
// The harness shared by the scene and plan readers' bad-input tables: a case
// is a whole document or a merge patch of a valid base document, and every
// fault must name the file, the exact JSON path and a key phrase, in one short
// lowercase clause.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "cairn/core/error.h"

namespace cairn::testing {

/// One bad input: a whole document (`text`) or a merge patch of the base.
struct BadCase {
  const char* name;
  const char* text;    // nullptr: use patch
  const char* patch;   // merge patch of the base document
  const char* path;    // the JSON path the error must name
  const char* phrase;  // a phrase the message must contain
};

inline void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

/// Writes `text` to a file named `name` in the test's temporary folder.
inline std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

/// The document of a case: its text, or `base` with its patch merged in.
inline std::string CaseText(const BadCase& c, const char* base) {
  if (c.text) return c.text;
  nlohmann::json doc = nlohmann::json::parse(base);
  doc.merge_patch(nlohmann::json::parse(c.patch));
  return doc.dump(2);
}

/// Writes the case to `file`, calls read(file) and checks the InputError.
template <typename Read>
void ExpectBadInput(const BadCase& c, const std::string& text, const std::string& file, Read read) {
  using ::testing::HasSubstr;
  try {
    read(file);
    ADD_FAILURE() << "no error; expected " << c.path << ": " << c.phrase << "\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.json_path(), c.path) << e.what();
    EXPECT_THAT(e.message(), HasSubstr(c.phrase)) << e.what();
    EXPECT_THAT(std::string(e.what()), HasSubstr(file));
    // One short clause, starting lowercase (JSON errors start with "invalid JSON").
    EXPECT_FALSE(e.message().empty());
    EXPECT_EQ(e.message().find('\n'), std::string::npos) << e.what();
    EXPECT_TRUE(std::islower(static_cast<unsigned char>(e.message()[0])) ||
                !std::isalpha(static_cast<unsigned char>(e.message()[0])))
        << e.what();
  }
}

}  // namespace cairn::testing

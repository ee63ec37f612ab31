// STEP assemblies (include/cairn/io/step_reader.h, docs/step-format.md):
// Cairn's side. OpenCASCADE itself runs in another process,
// cairn-step-reader (src/io/step/), so that no other process of Cairn loads
// its libraries.
//
// ReadStepAssembly, as a table of contents:
//   0. The file checked and read whole (ReadInputFile), its text checked
//      (CheckStepText: NUL bytes, numbers that are not finite, references to
//      entities the file does not define).
//   1. FindStepReader: the reading program, beside the code of this function
//      (the `cairn` executable, the Python module) or where the build or the
//      install put it.
//   2. RunIsolatedProgram: the text read there under the limits of time and
//      memory (a crash, a hang or a runaway allocation of OpenCASCADE is an
//      InputError of the file); its answer decoded (step_codec.h).

#include "cairn/io/step_reader.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/core/format.h"
#include "cairn/core/tolerances.h"
#include "io/isolated_call.h"
#include "io/step_codec.h"

namespace cairn {

namespace {

// 0. What OpenCASCADE crashes on or spins on, found in the text first and
// said with its line: a NUL byte, a number that is not finite (1.E400, NAN,
// INF) or beyond kMaxStepNumber, a reference to an entity the file does not
// define.
//
// The largest magnitude of any number in a STEP file Cairn reads: a
// thousand times the scene's coordinate range (limits::kMaxCoordinate, so
// that a file in millimetres reaches it in metres). OpenCASCADE spins on a
// point at 1E308 (a pen part's coordinate so changed ran past 300 s).
constexpr double kMaxStepNumber = 1e3 * limits::kMaxCoordinate;
void CheckStepText(const std::string& text, const std::string& path) {
  const auto line_of = [&](size_t offset) {
    return 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
  };
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    throw InputError(path, "",
                     "a NUL byte at line " + std::to_string(line_of(nul)) +
                         " (a STEP file is text; is this a binary file?)");
  const auto fail = [&](size_t line, const std::string& entity, const std::string& what) {
    throw InputError(path, "",
                     "line " + std::to_string(line) + (entity.empty() ? "" : " (#" + entity + ")") +
                         ": " + what);
  };
  const auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
  const auto is_alpha = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  struct Reference {
    std::string id, entity;
    size_t line;
  };
  std::set<std::string> defined;
  std::vector<Reference> references;
  std::string entity;  // the entity whose definition is being read
  size_t line = 1;
  const size_t n = text.size();
  size_t i = 0;
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line, ++i;
    } else if (c == '\'' || c == '"') {  // a string or binary: to its end ('' is a quote)
      for (++i; i < n; ++i) {
        if (text[i] == '\n') ++line;
        if (text[i] != c) continue;
        if (c == '\'' && i + 1 < n && text[i + 1] == '\'') {
          ++i;
          continue;
        }
        ++i;
        break;
      }
    } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {  // a comment
      const size_t end = text.find("*/", i + 2);
      const size_t stop = end == std::string::npos ? n : end + 2;
      line +=
          static_cast<size_t>(std::count(text.begin() + static_cast<std::ptrdiff_t>(i),
                                         text.begin() + static_cast<std::ptrdiff_t>(stop), '\n'));
      i = stop;
    } else if (c == '#') {  // an entity: defined when `=` follows
      size_t j = i + 1;
      while (j < n && text[j] == '0' && j + 1 < n && is_digit(text[j + 1])) ++j;
      const size_t start = j;
      while (j < n && is_digit(text[j])) ++j;
      const std::string id = text.substr(start, j - start);
      size_t k = j;
      while (k < n && (text[k] == ' ' || text[k] == '\t' || text[k] == '\r' || text[k] == '\n'))
        ++k;
      if (!id.empty() && k < n && text[k] == '=') {
        defined.insert(id);
        entity = id;
      } else if (!id.empty()) {
        references.push_back({id, entity, line});
      }
      i = j;
    } else if (is_digit(c) || ((c == '+' || c == '-') && i + 1 < n &&
                               (is_digit(text[i + 1]) || text[i + 1] == '.'))) {
      // A number: sign, digits, fraction, exponent.
      size_t j = i + 1;
      while (j < n && (is_digit(text[j]) || text[j] == '.')) ++j;
      if (j < n && (text[j] == 'E' || text[j] == 'e')) {
        size_t k = j + 1;
        if (k < n && (text[k] == '+' || text[k] == '-')) ++k;
        if (k < n && is_digit(text[k])) {
          while (k < n && is_digit(text[k])) ++k;
          j = k;
        }
      }
      const std::string number = text.substr(i, j - i);
      const double value = std::strtod(number.c_str(), nullptr);
      if (!std::isfinite(value))
        fail(line, entity,
             "the number " + number + " is not finite (beyond the range of a double)");
      if (std::abs(value) > kMaxStepNumber)
        fail(line, entity,
             "the number " + number +
                 " is beyond the range Cairn reads (|x| <= " + FormatNumber(kMaxStepNumber) + ")");
      i = j;
    } else if (c == '.' && i + 1 < n && is_alpha(text[i + 1])) {  // an enumeration .NAME.
      size_t j = i + 1;
      while (j < n && (is_alpha(text[j]) || is_digit(text[j]) || text[j] == '_')) ++j;
      i = j < n && text[j] == '.' ? j + 1 : j;
    } else if (is_alpha(c) || c == '_') {  // a keyword: an entity's type when `(` follows
      size_t j = i;
      while (j < n && (is_alpha(text[j]) || is_digit(text[j]) || text[j] == '_' || text[j] == '-'))
        ++j;
      std::string word = text.substr(i, j - i);
      for (char& ch : word) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
      size_t k = j;
      while (k < n && (text[k] == ' ' || text[k] == '\t' || text[k] == '\r' || text[k] == '\n'))
        ++k;
      if ((word == "NAN" || word == "INF" || word == "INFINITY") && !(k < n && text[k] == '('))
        fail(line, entity,
             text.substr(i, j - i) + " is not a number a STEP file can hold (numbers are finite)");
      i = j;
    } else {
      if (c == ';') entity.clear();
      ++i;
    }
  }
  for (const Reference& r : references)
    if (!defined.count(r.id))
      fail(r.line, r.entity, "refers to #" + r.id + ", which the file does not define");
}

// 1. The reading program: $CAIRN_STEP_READER when set; else
// cairn-step-reader in the folder of the binary that holds this code (the
// `cairn` executable, or the Python module's library), in its ../bin, where
// `cmake --install` put it, and where the build made it. Throws (a runtime
// error, exit 4: an incomplete installation, not bad input) naming where it
// looked.
std::string FindStepReader() {
  namespace fs = std::filesystem;
  constexpr const char* kName = "cairn-step-reader";
  std::vector<fs::path> candidates;
  if (const char* given = std::getenv("CAIRN_STEP_READER"); given && *given)
    candidates.emplace_back(given);
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&ReadStepAssembly), &info) && info.dli_fname) {
    std::error_code ec;
    const fs::path self = fs::canonical(info.dli_fname, ec);
    if (!ec) {
      candidates.push_back(self.parent_path() / kName);
      candidates.push_back(self.parent_path().parent_path() / "bin" / kName);
    }
  }
#ifdef CAIRN_STEP_READER_INSTALLED
  candidates.emplace_back(CAIRN_STEP_READER_INSTALLED);
#endif
#ifdef CAIRN_STEP_READER_BUILT
  candidates.emplace_back(CAIRN_STEP_READER_BUILT);
#endif
  std::string looked;
  for (const fs::path& c : candidates) {
    if (::access(c.c_str(), X_OK) == 0) return c.string();
    looked += (looked.empty() ? "" : ", ") + c.string();
  }
  throw std::runtime_error(
      "STEP reader: the program cairn-step-reader, which reads STEP files, is not installed "
      "(looked in: " +
      looked + "; CAIRN_STEP_READER names another)");
}

// A number as text that reads back to the same double.
std::string Exact(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

}  // namespace

StepModel ReadStepAssembly(const std::string& path, const StepReadOptions& options) {
  const std::string text = ReadInputFile(path, options.max_input_size, "STEP file");
  if (options.check_text) CheckStepText(text, path);
  io_internal::IsolationLimits limits;
  limits.time_limit = options.time_limit;
  limits.memory_limit = options.memory_limit;
  const io_internal::IsolatedResult result = io_internal::RunIsolatedProgram(
      {FindStepReader(), path, Exact(options.mesh_tolerance), std::to_string(options.memory_limit),
       step_codec::EncodePairs(options)},
      text, limits);
  using Status = io_internal::IsolatedResult::Status;
  switch (result.status) {
    case Status::kDone: {
      step_codec::Reader r(result.output);
      if (r.Byte() == 'M') {
        StepModel model = step_codec::ReadModel(r);
        // Facets lie within the chordal tolerance of their surfaces, on
        // either side of a pin's and its hole's: the parts may cross by that
        // much where they touch in CAD (docs/step-format.md).
        for (const StepPartReport& part : model.parts)
          if (part.approximated)
            model.def.overlap_allowance =
                std::max(model.def.overlap_allowance, part.mesh_tolerance);
        return model;
      }
      std::string file = r.Str(), json_path = r.Str(), message = r.Str();
      throw InputError(std::move(file), std::move(json_path), std::move(message));
    }
    case Status::kTimedOut:
      throw InputError(path, "",
                       "OpenCASCADE could not read this file (it took longer than " +
                           FormatNumber(options.time_limit) + " s)");
    case Status::kCrashed:
      if (result.signal == 0 && result.exit_code == 127)
        throw std::runtime_error("STEP reader: cairn-step-reader could not be started");
      throw InputError(path, "",
                       "OpenCASCADE could not read this file (it crashed" +
                           (result.signal ? " with " + io_internal::SignalName(result.signal)
                                          : ": exit status " + std::to_string(result.exit_code)) +
                           ")");
    case Status::kNoFork:
      break;
  }
  throw std::runtime_error("STEP reader: " + result.output);
}

}  // namespace cairn

// cairn-step-reader: the process in which OpenCASCADE reads one STEP file
// for Cairn (ReadStepAssembly starts it; it is not meant to be run by hand).
//
//   cairn-step-reader PATH MESH_TOLERANCE MEMORY_LIMIT PAIRS < TEXT > ANSWER
//
// TEXT is the file's contents as Cairn read and checked them (standard input
// is a copy in memory, not the file: what was checked is what is read).
// ANSWER is the answer's length (8 bytes, native order) and the answer of
// step_codec.h; PAIRS the parts to fasten, make touch and measure the common
// volume of (step_codec::EncodePairs). Exit 0 when an answer was written (a model or an
// InputError), 2 on wrong arguments; anything else is a crash, reported by Cairn. The limits of
// time and memory are set by the parent (isolated_call.h).

#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "io/isolated_call.h"
#include "io/step/occt_reader.h"
#include "io/step_codec.h"

namespace {

std::string ReadStdin() {
  std::string text;
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(STDIN_FILENO, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<size_t>(n));
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) return 2;
  cairn::StepReadOptions options;
  options.mesh_tolerance = std::strtod(argv[2], nullptr);
  options.memory_limit = std::strtoull(argv[3], nullptr, 10);
  try {
    cairn::step_codec::DecodePairs(argv[4], options);
  } catch (const std::runtime_error&) {
    return 2;
  }
  const std::string answer = cairn::ReadInChild(argv[1], ReadStdin(), options);
  const std::uint64_t size = answer.size();
  const std::string header(reinterpret_cast<const char*>(&size), sizeof size);
  using cairn::io_internal::WriteAll;
  return WriteAll(STDOUT_FILENO, header.data(), header.size()) &&
                 WriteAll(STDOUT_FILENO, answer.data(), answer.size())
             ? 0
             : 3;
}

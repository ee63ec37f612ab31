#pragma once
// What every fuzz target shares: the input as a file (Cairn's readers take
// paths, and the file path is what users give), and the rule that decides a
// finding: an InputError is the right answer to bad input; anything else
// escaping (another exception, which the CLI would report as an internal
// error, exit 4) is a defect, and so is a crash, a sanitizer report or a
// hang (libFuzzer's -timeout).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "cairn/core/error.h"

namespace cairn::fuzz {

// The bytes in a file of this process's own (`suffix` for the readers that
// go by the extension), rewritten on every input.
inline std::string AsFile(const uint8_t* data, size_t size, const std::string& suffix) {
  static const std::string dir = std::filesystem::temp_directory_path().string();
  const std::string path = dir + "/cairn_fuzz_" + std::to_string(::getpid()) + suffix;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

// Runs `body`; an InputError is the expected answer to bad input, anything
// else is reported and aborts (a finding).
template <typename Body>
int Run(const char* target, Body&& body) {
  try {
    body();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: internal error (not an InputError): %s\n", target, e.what());
    std::abort();
  }
  return 0;
}

}  // namespace cairn::fuzz

#pragma once
// What every command does first: read the model with the command line's
// changes (docs/cli.md, "Reading the model"); and writing output files whole.

#include <string>

#include "cairn/geometry/assembly.h"
#include "cli/commands.h"

namespace cairn::cli {

/// A model read from a file with the command line's changes applied: the
/// definition (what convert writes, what the fixture search adds to) and the
/// validated Assembly.
struct Model {
  AssemblyDef def;
  Assembly assembly;
};

/// Reads `file` in `args.format` and applies --friction, --supports,
/// --tolerance and --gravity. @throws InputError: of the file (with its JSON
/// path), or of a flag (the flag as path).
Model LoadModel(const std::string& file, const ModelArgs& args);

/// Writes `text` to `path` whole or not at all: a temporary file beside it,
/// renamed over it once complete. @throws InputError naming `flag`.
void WriteAtomically(const std::string& path, const std::string& text, const std::string& flag);

/// A number as a user reads it (shortest round-trip-ish, `operator<<`).
std::string Num(double x);

}  // namespace cairn::cli

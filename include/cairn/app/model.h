#pragma once
/// @file
/// What every command does first, from the CLI and from Python alike: read
/// the model with the command line's changes (docs/cli.md, "Reading the
/// model"), and resolve the part names the commands are given.

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/io/compas_reader.h"
#include "cairn/io/input_file.h"

namespace cairn::app {

/// How the input file is read and what the command line changes in its model
/// (shared by check, simulate and convert; docs/cli.md, "Reading the model").
struct ModelArgs {
  /// "scene" (scene format v1, the default), "compas" (a COMPAS assembly),
  /// "step" (a STEP assembly, docs/step-format.md) or "asap" (an ASAP
  /// assembly folder: meshes and config.json).
  std::string format = "scene";
  /// --mesh-tolerance (step): the chordal tolerance of curved faces, metres;
  /// none: the reader's default (StepReadOptions).
  std::optional<double> mesh_tolerance;
  /// --fastened (step): pairs "A:B" of parts joined into one rigid part,
  /// their exact solids fused (StepReadOptions::fastened): bolts, pins and
  /// press fits that interfere with what they hold.
  std::vector<std::string> fastened;
  /// --touching (step): pairs "A:B" made to touch where they overlap: B
  /// loses what it shares with A (StepReadOptions::touching).
  std::vector<std::string> touching;
  /// --sidecar (step, asap): what the file does not carry (friction,
  /// densities, masses, fixed parts), io/sidecar_reader.h; empty: none.
  std::string sidecar;
  /// --friction: μ of every contact. Required with compas (the files store
  /// none); with scene it replaces the scene's `friction` (friction pairs keep
  /// theirs).
  std::optional<double> friction;
  /// --supports: parts (COMPAS blocks: node keys) fixed in addition to those
  /// the file fixes (`is_support`, `"fixed": true`).
  std::vector<std::string> supports;
  /// --tolerance: the length tolerance (contact distance, allowed overlap,
  /// planarity); replaces the scene's `tolerance` or the COMPAS default.
  std::optional<double> tolerance;
  /// --overlap-depth: how deep parts meant to touch may interpenetrate and be
  /// read as touching, on the overlap's mid-surface (length, 3-D;
  /// AssemblyDef::overlap_depth); replaces the scene's `overlap_depth`.
  std::optional<double> overlap_depth;
  /// --gravity: replaces the gravity (2 numbers in 2-D, 3 in 3-D); empty: the
  /// file's, or the default.
  std::vector<double> gravity;
  /// --interfaces: "detect" (contacts found from the shapes, the default) or
  /// "stored" (a COMPAS file's stored interfaces: CompasOptions::stored_interfaces).
  std::string interfaces = "detect";
  /// --max-input-size: bytes, the largest file read (the model, its meshes,
  /// the sidecar; input_file.h).
  std::uint64_t max_input_size = kDefaultMaxInputSize;
};

/// A model read from a file with the command line's changes applied: the
/// definition (what convert writes, what the fixture search adds to) and the
/// validated Assembly.
struct Model {
  AssemblyDef def;
  Assembly assembly;
  std::string file;  ///< the file (or document) it was read from: messages, `scene_file`
};

/// Reads `file` in `args.format` and applies --sidecar, --friction,
/// --supports, --tolerance and --gravity. `notes`, when given, gets one line
/// per part the reader approximated (STEP: curved faces tessellated) and by
/// how much. @throws InputError: of the file (with its JSON path), of the
/// sidecar (a mass or density it set that the model refuses), or of a flag
/// (the flag as path). Parts that overlap by more than the length tolerance
/// say that --tolerance raises it.
Model LoadModel(const std::string& file, const ModelArgs& args, std::ostream* notes = nullptr);

/// LoadModel for a COMPAS assembly already parsed (ParseCompasAssembly: the
/// Python module's `cairn.from_compas` of a dict): the model options applied
/// as for `--format compas`; `file` names the document in messages.
/// @throws InputError as LoadModel.
Model LoadCompasModel(const CompasAssembly& parsed, const std::string& file, const ModelArgs& args);

/// The index of the part `name` given to `flag` (`--without`, `--keep`, ...).
/// @throws InputError naming the flag when `file`'s model has no such part.
int ResolvePart(const Assembly& assembly, const std::string& name, const std::string& flag,
                const std::string& file);

/// The part of `--normalize NAME` (empty: none). @throws InputError naming the
/// flag: no such part, or one without weight.
std::optional<int> ResolveNormalize(const Assembly& assembly, const std::string& name,
                                    const std::string& file);

/// The assembled configuration with the `--without` parts taken away; their
/// indices are appended to `taken`. @throws InputError naming `--without`.
Configuration WithoutParts(const Assembly& assembly, const std::vector<std::string>& names,
                           const std::string& file, std::vector<int>& taken);

/// Commands that move parts (simulate, plan) refuse a model whose contacts
/// are given interfaces: they hold in the assembled configuration only.
/// `consequence` says what cannot be done. @throws InputError naming `file`.
void RefuseGivenInterfaces(const Assembly& assembly, const std::string& file,
                           const std::string& consequence);

}  // namespace cairn::app

#pragma once
/// @file
/// Reading scene files, format version 1 (docs/scene-format.md). The format is
/// a public contract: its key names never change within a version.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// Checks a parsed scene document (types, required fields, unknown keys,
/// finite numbers, the 2-D/3-D dimension) and converts it to an AssemblyDef.
/// @throws InputError naming `file` and the JSON path of the first fault.
/// `mesh` parts are read with ReadMesh, each file at most `max_input_size`
/// bytes (input_file.h).
AssemblyDef ParseSceneJson(const nlohmann::json& doc, const std::string& file,
                           std::uint64_t max_input_size = kDefaultMaxInputSize);

/// Reads and parses a scene file. @throws InputError (unreadable file, JSON
/// syntax error with its line and column, or any fault of ParseSceneJson).
/// Every file read (the scene, its meshes) is a regular file of at most
/// `max_input_size` bytes (ReadInputFile).
AssemblyDef ReadSceneDef(const std::string& path,
                         std::uint64_t max_input_size = kDefaultMaxInputSize);

/// ReadSceneDef followed by Assembly::Create: a validated Assembly.
/// @throws InputError.
Assembly ReadScene(const std::string& path, std::uint64_t max_input_size = kDefaultMaxInputSize);

}  // namespace cairn

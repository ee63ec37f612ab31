#pragma once
/// @file
/// Reading scene files, format version 1 (docs/scene-format.md). The format is
/// a public contract: its key names never change within a version.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "cairn/geometry/assembly.h"

namespace cairn {

/// Checks a parsed scene document (types, required fields, unknown keys,
/// finite numbers, the 2-D/3-D dimension) and converts it to an AssemblyDef.
/// @throws InputError naming `file` and the JSON path of the first fault.
AssemblyDef ParseSceneJson(const nlohmann::json& doc, const std::string& file);

/// Reads and parses a scene file. @throws InputError (unreadable file, JSON
/// syntax error with its line and column, or any fault of ParseSceneJson).
AssemblyDef ReadSceneDef(const std::string& path);

/// ReadSceneDef followed by Assembly::Create: a validated Assembly.
/// @throws InputError.
Assembly ReadScene(const std::string& path);

}  // namespace cairn

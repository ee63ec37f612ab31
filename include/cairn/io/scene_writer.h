#pragma once
// Writing a model as a scene file, format version 1 (docs/scene-format.md),
// for `cairn convert`.

#include <string>

#include "cairn/geometry/assembly.h"

namespace cairn {

/// The scene-format-v1 text of `def`: every field it sets, each part's shape
/// as a `polygon` (2-D) or a `polyhedron` (3-D; a box or mesh is written as the
/// polyhedron it was read as). Numbers are written in the shortest form that
/// reads back to the same double, so the scene read back is the same model
/// bit for bit. Arrays of numbers are written one per line (a vertex, a face)
/// to keep large files readable.
std::string WriteSceneJson(const AssemblyDef& def);

}  // namespace cairn

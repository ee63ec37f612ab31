#pragma once
/// @file
/// ASAP's assembly folders (Tian et al., "ASAP: Automated Sequence Planning
/// for Complex Robotic Assembly with Physical Feasibility", ICRA 2024;
/// github.com/yunshengtian/ASAP, `assets/<assembly>/`): one triangle mesh
/// `<key>.obj` per part in the part's own frame, and `config.json` giving
/// each part's poses (docs/scene-format.md, "ASAP assembly folders").
///
/// A part is placed by its `final_state` [x, y, z, rx, ry, rz]: the
/// translation and the rotation R = Rz(rz) · Ry(ry) · Rx(rx) (angles in
/// radians about the fixed x, y and z axes, in that order). Parts are named by
/// their keys, in numeric order; lengths are the meshes' units, unchanged.

#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// Reads `path`: an ASAP `config.json`, or the folder holding it. The meshes
/// are read with ReadMesh (coplanar triangles merged into faces).
/// @throws InputError naming the file and the JSON path: not an object of
/// parts, a part without `final_state` of 6 numbers, a mesh missing or bad.
/// config.json and every mesh are regular files of at most `max_input_size`
/// bytes (input_file.h).
AssemblyDef ReadAsapAssembly(const std::string& path,
                             std::uint64_t max_input_size = kDefaultMaxInputSize);

}  // namespace cairn

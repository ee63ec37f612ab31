#pragma once
/// @file
/// The sidecar: what a CAD file (STEP) or a folder of meshes (ASAP) does not
/// carry, in a small JSON file beside it (docs/step-format.md, "The
/// sidecar"):
///
///     {"cairn_sidecar": 1,
///      "friction": 0.5,
///      "density": 1200,
///      "parts": {"body": {"fixed": true}, "cap": {"mass": 0.004}}}
///
/// Every key but the version is optional. `density` is every part's default
/// (mass per volume, the model's units: kg/m³ for STEP), a part's own
/// `density` or `mass` overrides it; `fixed` fixes a part. Part names must be
/// the model's.

#include <map>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// Reads the sidecar at `path` and applies it to `def`. @throws InputError
/// naming the sidecar and the JSON path: unknown keys, a part the model does
/// not have, numbers out of range.
/// The sidecar is a regular file of at most `max_input_size` bytes. A mass
/// must be within limits::kMinMass..kMaxMass. Returns, for each part whose
/// mass or density the sidecar set, the JSON path in the sidecar that set it
/// (`parts.cap.mass`, `density`), by part name: faults that Assembly::Create
/// finds in those numbers (a mass out of range or too light beside the
/// others) are the sidecar's.
std::map<std::string, std::string> ApplySidecar(
    const std::string& path, AssemblyDef& def, std::uint64_t max_input_size = kDefaultMaxInputSize);

}  // namespace cairn

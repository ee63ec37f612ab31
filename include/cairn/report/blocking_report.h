#pragma once
/// @file
/// What `cairn blocking` prints: the NDBG of a configuration
/// (planning/blocking.h) as a JSON document (a public contract: its keys
/// never change within a version; docs/blocking.md lists them) or as a short
/// text, one line per cell.

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/planning/blocking.h"
#include "cairn/report/report.h"

namespace cairn {

/// The `cairn blocking --json` document. Top level: "scene", "name",
/// "dimension", "without" (names), "normals" (2 or 3 numbers each), "cells".
/// Each cell: "dimension" (0, 1, 2), "direction" (2 or 3 numbers), 2-D
/// "angles_deg" ([from, to], degrees counter-clockwise from +x), 3-D "signs",
/// "infinitesimal" and "infinity" (arcs as [blocked part, blocker] names, in
/// part order), "removable" (names). Uses `options.scene_file` and
/// `options.without`.
nlohmann::json NdbgToJson(const Assembly& assembly, const Ndbg& ndbg, const ReportOptions& options);

/// The summary's headline: the scene, the NDBG's dimension, its cells and
/// distinct normals, and the parts taken away (the blocking page's story).
std::string NdbgHeadline(const Assembly& assembly, const Ndbg& ndbg, const ReportOptions& options);

/// The human-readable summary: the headline (NdbgHeadline), then one line per cell: its
/// angles (2-D) or kind and signs (3-D), its direction, the parts that can
/// leave, and which parts are blocked by which to infinity (marked `*` when
/// infinitesimally too).
std::string NdbgToText(const Assembly& assembly, const Ndbg& ndbg, const ReportOptions& options);

}  // namespace cairn

#pragma once
/// @file
/// `cairn margin`'s result as a user reads it: a JSON document (a public
/// contract: docs/margin.md lists every key) and a short text summary.

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/report/report.h"
#include "cairn/stability/margin.h"

namespace cairn {

/// The `cairn margin --json` document: {"scene", "scene_file", "dimension",
/// "without", "margin": {...}}.
nlohmann::json MarginToJson(const Assembly& assembly, const MarginRequest& request,
                            const MarginResult& result, const ReportOptions& options);

/// The human-readable summary of `cairn margin`.
std::string MarginToText(const Assembly& assembly, const MarginRequest& request,
                         const MarginResult& result, const ReportOptions& options);

}  // namespace cairn

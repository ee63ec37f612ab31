#pragma once
/// @file
/// `cairn check`'s result as a user reads it: a JSON document (a public
/// contract: its keys never change within a version) and a short text summary.

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/report/report.h"
#include "cairn/stability/analyze.h"

namespace cairn {

/// The `cairn check --json` document (docs/cli.md lists every key).
nlohmann::json StabilityToJson(const Assembly& assembly, const Configuration& config,
                               const StabilityResult& result, const ReportOptions& options);

/// The human-readable summary of `cairn check`.
std::string StabilityToText(const Assembly& assembly, const Configuration& config,
                            const StabilityResult& result, const ReportOptions& options);

}  // namespace cairn

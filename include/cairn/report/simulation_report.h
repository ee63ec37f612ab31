#pragma once
/// @file
/// `cairn simulate`'s result as a user reads it: the JSON document (a public
/// contract), the text summary and the timeline CSV.

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/plan.h"
#include "cairn/motion/simulate.h"
#include "cairn/report/report.h"

namespace cairn {

/// The `cairn simulate --json` document (docs/cli.md lists every key).
nlohmann::json SimulationToJson(const Assembly& assembly, const Plan& plan,
                                const SimulationResult& result, const ReportOptions& options);

/// The human-readable summary of `cairn simulate`: one line per step, and for
/// a failure when, which parts move and how, and which contacts break or slide.
std::string SimulationToText(const Assembly& assembly, const Plan& plan,
                             const SimulationResult& result, const ReportOptions& options);

/// The timeline CSV: a header, then one row per tick and contact (the data
/// behind the paper's force-versus-time figures).
std::string TimelineToCsv(const Assembly& assembly, const SimulationResult& result,
                          const ReportOptions& options);

}  // namespace cairn

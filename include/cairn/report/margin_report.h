#pragma once
/// @file
/// `cairn margin`'s result as a user reads it: a JSON document (a public
/// contract: docs/margin.md lists every key) and a short text summary.

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/motion/plan_margin.h"
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

/// `cairn simulate --margin friction`'s "margin" object: {"quantity":
/// "friction", "critical", "of", "nominal", "failing_at", "deciding" (the
/// first failure just below: step, tick, time, verdict, parts, description),
/// "method", "tolerance", "simulations"}.
nlohmann::json PlanMarginToJson(const Assembly& assembly, const PlanMargin& margin);

/// Its lines in `cairn simulate`'s summary.
std::string PlanMarginToText(const Assembly& assembly, const PlanMargin& margin);

}  // namespace cairn

#pragma once
/// @file
/// What `cairn plan` writes: the JSON document and text summary of a
/// PlannerResult, the AND/OR graph as Graphviz dot, and plan files (plan
/// format 1, docs/plan-format.md) for the sequences found.

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/plan.h"
#include "cairn/planning/planner.h"

namespace cairn {

/// A plan in plan format 1 (the document `cairn simulate` reads). Points and
/// directions have `dimension` numbers.
nlohmann::json PlanDefToJson(const PlanDef& plan, int dimension);

/// The `cairn plan --json` document (docs/planning.md lists every key).
nlohmann::json PlannerToJson(const Assembly& assembly, const PlannerResult& result,
                             const std::string& scene_file);

/// The human-readable summary of `cairn plan`.
std::string PlannerToText(const Assembly& assembly, const PlannerResult& result,
                          const std::string& scene_file);

/// The AND/OR graph in Graphviz dot: nodes (the parts present; unstable ones
/// filled red), edges (the parts removed and the path; green when stable in
/// disassembly, orange when stable only in assembly, red and dashed when
/// unstable both ways).
std::string PlannerToDot(const Assembly& assembly, const PlannerResult& result);

}  // namespace cairn

#pragma once
/// @file
/// Turning a StabilityResult into what a user reads: a JSON document (a public
/// contract: its keys never change within a version) and a short text summary.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/motion/simulate.h"
#include "cairn/stability/analyze.h"

namespace cairn {

/// What the report says besides the result.
struct ReportOptions {
  std::string scene_file;             ///< shown in the report
  std::optional<int> normalize_part;  ///< divide forces by this part's weight m|g|
  std::vector<int> without;           ///< parts taken away (shown in the report)
};

/// The scale forces are divided by (1, or the weight of the normalising part)
/// and its label ("force units", "weight of A").
std::pair<double, std::string> ForceScale(const Assembly& assembly, const ReportOptions& options);

/// The `cairn check --json` document (docs/cli.md lists every key).
nlohmann::json StabilityToJson(const Assembly& assembly, const Configuration& config,
                               const StabilityResult& result, const ReportOptions& options);

/// The human-readable summary of `cairn check`.
std::string StabilityToText(const Assembly& assembly, const Configuration& config,
                            const StabilityResult& result, const ReportOptions& options);

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

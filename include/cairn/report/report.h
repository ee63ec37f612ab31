#pragma once
/// @file
/// What every report shares: the options a command passes (the scene file, the
/// part forces are normalised by, the parts taken away) and the force unit.
/// The reports themselves: check_report.h (`cairn check`), simulation_report.h
/// (`cairn simulate`), blocking_report.h, plan_report.h, fixture_report.h.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"

namespace cairn {

/// How much of a check's contact forces its text lists (`cairn check
/// --contacts`); the JSON document always has every contact.
enum class ContactListing {
  kSummary,  ///< the most loaded contacts and each pair of parts' resultant
  kAll,      ///< every contact
  kNone,     ///< none
};

/// What the report says besides the result.
struct ReportOptions {
  std::string scene_file;                              ///< shown in the report
  std::optional<int> normalize_part;                   ///< divide forces by this part's weight m|g|
  std::vector<int> without;                            ///< parts taken away (shown in the report)
  ContactListing contacts = ContactListing::kSummary;  ///< check's text only
};

/// The scale forces are divided by (1, or the weight of the normalising part)
/// and its label ("force units", "weight of A").
std::pair<double, std::string> ForceScale(const Assembly& assembly, const ReportOptions& options);

}  // namespace cairn

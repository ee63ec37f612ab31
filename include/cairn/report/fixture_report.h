#pragma once
/// @file
/// What `cairn simulate --suggest-fixtures` writes about a FixtureSuggestion
/// (planning/fixtures.h): a JSON object (the `fixtures` key of the simulate
/// document; docs/fixtures.md lists every key) and a text section.

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/planning/fixtures.h"
#include "cairn/report/report.h"

namespace cairn {

/// The suggestion as JSON:
///   found (bool), message (string), candidates, simulations (int),
///   max_fixels (int, options.max_fixels), force_unit (string),
///   fixels: [{part, point, normal, face, step, max_force}] (points and
///     normals 2 numbers in 2-D, 3 in 3-D; max_force divided by the
///     --normalize weight when given),
///   scene_fixtures: [{part, point, normal}] (the fixels as the scene
///     format's `fixtures` entries, ready to paste),
///   verification: {verdict, stable, failure} (the plan re-run with the
///     fixels; failure: its description, or null).
nlohmann::json FixtureSuggestionToJson(const Assembly& assembly,
                                       const FixtureSuggestion& suggestion,
                                       const FixtureSearchOptions& search,
                                       const ReportOptions& options);

/// The suggestion for people: a heading with the verdict, one line per
/// fixel, and the scene-format `fixtures` entries to add.
std::string FixtureSuggestionToText(const Assembly& assembly, const FixtureSuggestion& suggestion,
                                    const FixtureSearchOptions& search,
                                    const ReportOptions& options);

}  // namespace cairn

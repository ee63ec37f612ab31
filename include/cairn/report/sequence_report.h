#pragma once
/// @file
/// `cairn sequence`'s document and words (docs/sequence.md).

#include <nlohmann/json.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/planning/sequence.h"
#include "cairn/report/report.h"

namespace cairn {

/// The JSON document: order, steps (place, direction, temporary_in_place,
/// added, removed, verdict), temporary (kind, max_in_place, placements,
/// lower_bound, lower_bound_reason, optimal), complete, message, stats
/// (states_checked, cache_hits, lp_warm_starts, seconds).
nlohmann::json SequenceToJson(const Assembly& assembly, const BuildSequence& s, double seconds,
                              const ReportOptions& options);

/// The report in words: one line per step, the supports and the bound.
std::string SequenceToText(const Assembly& assembly, const BuildSequence& s,
                           const ReportOptions& options);

}  // namespace cairn

#pragma once
/// @file
/// Reading plan files, format version 1 (docs/plan-format.md). The format is a
/// public contract: its key names never change within a version.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/plan.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// Checks a parsed plan document (types, required fields, unknown keys,
/// finite numbers, an empty `grip`) and converts it to a PlanDef. Vector
/// indices equal JSON indices. The checks against a scene are Plan::Create's.
/// Path points and directions have `dimension` numbers (the scene's: 2 or 3).
/// @throws InputError naming `file` and the JSON path of the first fault.
PlanDef ParsePlanJson(const nlohmann::json& doc, const std::string& file, int dimension = 2);

/// Reads and parses a plan file, then validates it against `assembly` with
/// Plan::Create. @throws InputError (unreadable file, JSON syntax error with
/// its line and column, a key repeated in one object, or any fault of
/// ParsePlanJson and Plan::Create). The file is a regular file of at most
/// `max_input_size` bytes (ReadInputFile).
Plan ReadPlan(const std::string& path, const Assembly& assembly,
              long long max_ticks = Plan::kDefaultMaxTicks,
              std::uint64_t max_input_size = kDefaultMaxInputSize);

}  // namespace cairn

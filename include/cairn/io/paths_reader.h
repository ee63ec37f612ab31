#pragma once
/// @file
/// Candidate paths for `cairn plan --paths` (docs/planning.md): a JSON object
/// from part name to a list of paths, each a polyline of displacements from
/// the part's assembled pose (`[[0, 0], [0, 2.5], [3, 2.5]]`) or an object
/// with the keys of a plan step except `remove` (`path`, or `direction` and
/// `distance`; `support`; `grip` for tools that move with the part) and an
/// optional `label` (default "given path k").

#include <map>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/plan.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// Reads a candidate-paths file. Each path is checked as a plan step of its
/// part would be (ParsePlanJson, Plan::Create). @throws InputError naming
/// `file` and the place of the fault, the key named as the part it is
/// (NamedPath: `C ("C")[2].path[1]`; an unknown part's key bare, `Q`):
/// unreadable file, JSON syntax, unknown, fixed or tool parts, empty lists, a
/// `remove` key, and every fault of a plan step.
std::map<int, std::vector<CandidatePath>> ReadCandidatePaths(
    const std::string& file, const Assembly& assembly,
    std::uint64_t max_input_size = kDefaultMaxInputSize);

}  // namespace cairn

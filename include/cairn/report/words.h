#pragma once
/// @file
/// Cairn's results in words: how a part moves, why a step failed, why a path
/// or a fixel search did not succeed. The stages below keep their results
/// structured (PartMotion, MotionFailure, PathTrial, FixtureSuggestion); only
/// this stage phrases them, so that every report says the same thing the
/// same way. Numbers and points are written by cairn/core/format.h.

#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/motion/simulate.h"
#include "cairn/planning/fixtures.h"
#include "cairn/planning/planner.h"
#include "cairn/stability/analyze.h"

namespace cairn {

/// How a part moves: its kind ("tips", ...) and, for a part that tips, its
/// pivot and turning sense (2-D) or axis (3-D), else the unit direction of its
/// centroid's motion: "tips about (1, 1.25) clockwise", "slides along (1, 0, 0)".
/// With the scene's `gravity`, a part that slides more than kVerticalWord off
/// the horizontal slides "down" or "up": "slides down along (-0.64, 0, -0.77)".
std::string DescribeMotion(const PartMotion& m, int dimension,
                           const Vector3& gravity = Vector3::Zero());

/// A sliding direction this far off the horizontal (the sine of its angle
/// with the plane normal to gravity, dimensionless; 15°) is "down" or "up".
inline constexpr double kVerticalWord = 0.2588;

/// The story of a static check in words, one line per part that moves, as
/// the result page says it: the part's name, how it moves (DescribeMotion)
/// and why, from what decided its component: "10 slides down along (…),
/// because no equilibrium exists".
std::vector<std::string> CheckStory(const Assembly& assembly, const StabilityResult& result);

/// A failure of a plan in one line: when, what (who pushes whom, how each
/// part moves, which gripped part is unsupported, what runs into what), the
/// contacts that break or slide, and the solver's note if the LCP could not
/// be solved: "t = 0.4 s (step 1, tick 2): C tips about (2, 1) clockwise;
/// contact C-B at (2, 1) breaks". Words count a plan's steps from 1, as a
/// person does (MotionFailure::step, like the JSON's `step`, from 0).
std::string DescribeFailure(const Assembly& assembly, const MotionFailure& failure);

/// Why a path of the planner is not stable both ways: "disassembly: <the
/// failure>", "assembly: ...", or Proposition 1's reason. Empty when it is.
std::string PathTrialFailure(const Assembly& assembly, const PathTrial& trial);

/// What a fixel search found, or why it found nothing: "2 fixels make the plan
/// stable", "no fixels found: step 1 (<the failure>): the budget of ...".
std::string FixtureMessage(const Assembly& assembly, const FixtureSuggestion& suggestion);

}  // namespace cairn

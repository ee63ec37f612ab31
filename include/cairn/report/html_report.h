#pragma once
/// @file
/// The result page (`--html FILE`, docs/html.md): one self-contained HTML file
/// that draws the scene and the result, opens from disk in any browser, with
/// no network and nothing to install.
///
/// The page is three parts, all inline: the page data (a JSON document in a
/// `<script type="application/json">`, every `<` written `\u003c` so no text
/// of the scene can end the script), the viewer (web/dist/viewer.js: the
/// page's code and three.js, bundled by web/build.mjs, committed, and
/// embedded by the C++ build), and a few lines of HTML. The page data holds
/// the command's `--json` document unchanged (`result`) plus what it takes to
/// draw it: the parts' shapes (`scene`), and per kind the poses, roles and
/// contact forces of every tick (simulate: `frames`) or the rest state of the
/// assemblies a plan's sequences pass through (plan: `plan.nodes`).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/motion/simulate.h"
#include "cairn/planning/planner.h"
#include "cairn/planning/sequence.h"
#include "cairn/report/report.h"
#include "cairn/stability/analyze.h"

namespace cairn {

/// One analysed tick of a simulation as the page shows it: where every part
/// was and what the plan does with it (recorded through
/// SimulationOptions::on_analysis; the contacts come from the timeline).
struct SimulationFrame {
  int step = -1;
  int tick = 0;
  double time = 0;  ///< s
  std::vector<bool> present;
  std::vector<Pose> poses;
  /// What the plan's step does with each part: kPrescribed (gripped, tools
  /// included), kCarried (removed with them), kJudged (must stay put).
  std::vector<PartRole> roles;
};

/// At most this many ticks are put on a simulation's page; a longer one keeps
/// every step's first and last tick, the failure and evenly spaced ticks
/// between (the page says so).
inline constexpr int kMaxPageFrames = 2000;
/// At most this many of a plan's sequences are listed on its page (all of
/// them are in `result`).
inline constexpr int kMaxPageSequences = 50;

/// `cairn check --html`: the check `doc` (StabilityToJson: the parts taken
/// away, the contacts and motions are all in it) drawn on the assembly, with
/// its `story` in words (CheckStory: the parts that move, how and why).
std::string CheckPage(const Assembly& assembly, const nlohmann::json& doc,
                      const std::vector<std::string>& story, const ReportOptions& options);

/// `cairn margin --html`: the margin `doc` (MarginToJson: each component's
/// equilibrium at its critical value and the mechanism just past it) drawn on
/// the assembly, the mechanism animated; its story is `text` (MarginToText),
/// line by line.
std::string MarginPage(const Assembly& assembly, const nlohmann::json& doc, const std::string& text,
                       const ReportOptions& options);

/// `cairn blocking --html`: the NDBG `doc` (NdbgToJson) drawn on the
/// assembly, a cell at a time: its direction, the parts that can leave along
/// it and what blocks the others; `text` (NdbgHeadline), line by line, is
/// the story.
std::string BlockingPage(const Assembly& assembly, const nlohmann::json& doc,
                         const std::string& text, const ReportOptions& options);

/// `cairn simulate --html`: `result` must have been simulated with
/// SimulationOptions::record_timeline; `frames` in the order analysed;
/// `margin_text`, the text summary's margin lines (PlanMarginToText) or
/// empty, is added to the story.
std::string SimulationPage(const Assembly& assembly, const SimulationResult& result,
                           const std::vector<SimulationFrame>& frames, const nlohmann::json& doc,
                           const std::string& margin_text, const ReportOptions& options);

/// `cairn plan --html`: the page checks the rest state of every assembly
/// that the first kMaxPageSequences sequences pass through (one static check
/// each) to draw its contact forces.
std::string PlanPage(const Assembly& assembly, const PlannerResult& result,
                     const nlohmann::json& doc, const ReportOptions& options);

/// At most this many contacts are put on a build order's page, over all its
/// states; the states after have no forces drawn (the page says so).
inline constexpr size_t kMaxPageContacts = 200000;

/// `cairn sequence --html`: `sequence` found with
/// SequenceOptions::record_contacts (the forces of each state), `doc` its
/// document.
std::string SequencePage(const Assembly& assembly, const BuildSequence& sequence,
                         const nlohmann::json& doc, const ReportOptions& options);

/// The page of `data` (kind, title, scene, result, ...): the HTML text.
/// Exposed for tests of the escaping.
std::string HtmlPage(const nlohmann::json& data);

}  // namespace cairn

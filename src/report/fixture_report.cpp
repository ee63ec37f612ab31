#include "cairn/report/fixture_report.h"

#include <sstream>

#include "cairn/core/format.h"
#include "cairn/report/words.h"
#include "report/report_common.h"

namespace cairn {

namespace {
using report_internal::Clean;
using report_internal::ForceRoundoffScale;
using report_internal::Num;
}  // namespace

nlohmann::json FixtureSuggestionToJson(const Assembly& assembly,
                                       const FixtureSuggestion& suggestion,
                                       const FixtureSearchOptions& search,
                                       const ReportOptions& options) {
  using nlohmann::json;
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  const int dim = assembly.dimension();
  json doc;
  doc["found"] = suggestion.found;
  doc["message"] = FixtureMessage(assembly, suggestion);
  doc["max_fixels"] = search.max_fixels;
  doc["candidates"] = suggestion.candidates;
  doc["simulations"] = suggestion.simulations;
  doc["force_unit"] = force_unit;
  json fixels = json::array(), entries = json::array();
  for (const SuggestedFixel& s : suggestion.fixels) {
    json f = report_internal::FixtureToJson(s.fixture, dim);
    f["face"] = s.face;
    f["step"] = s.step;
    f["max_force"] = Clean(s.max_force / force_scale, ForceRoundoffScale(assembly, force_scale));
    fixels.push_back(f);
    entries.push_back(report_internal::FixtureToJson(s.fixture, dim));
  }
  doc["fixels"] = fixels;
  doc["scene_fixtures"] = entries;
  const SimulationResult& v = suggestion.verification;
  doc["verification"] = {
      {"verdict", to_string(v.verdict)},
      {"stable", v.stable()},
      {"failure", v.failure ? json(DescribeFailure(assembly, *v.failure)) : json(nullptr)}};
  return doc;
}

std::string FixtureSuggestionToText(const Assembly& assembly, const FixtureSuggestion& suggestion,
                                    const FixtureSearchOptions& search,
                                    const ReportOptions& options) {
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  const int dim = assembly.dimension();
  std::ostringstream os;
  os << "Fixel suggestion (at most " << search.max_fixels
     << "): " << (suggestion.found ? "FOUND" : "NONE") << " - "
     << FixtureMessage(assembly, suggestion) << '\n';
  for (size_t i = 0; i < suggestion.fixels.size(); ++i) {
    const SuggestedFixel& s = suggestion.fixels[i];
    os << "  fixel " << i + 1 << ": " << s.fixture.part << " at "
       << FormatPoint(s.fixture.point, dim) << ", normal " << FormatPoint(s.fixture.normal, dim)
       << " (" << s.face << "), for step " << s.step + 1 << ": max force "
       << Num(s.max_force / force_scale) << ' ' << force_unit << '\n';
  }
  const SimulationResult& v = suggestion.verification;
  if (!suggestion.fixels.empty()) {
    os << "  verified: the plan with "
       << (suggestion.fixels.size() == 1 ? "this fixel" : "these fixels") << " is "
       << to_string(v.verdict);
    if (v.failure) os << ": " << DescribeFailure(assembly, *v.failure);
    os << '\n';
    nlohmann::json entries = nlohmann::json::array();
    for (const SuggestedFixel& s : suggestion.fixels)
      entries.push_back(report_internal::FixtureToJson(s.fixture, dim));
    os << "  scene fixtures to add: " << entries.dump() << '\n';
  }
  os << "  (" << suggestion.candidates << " candidate points, " << suggestion.simulations
     << " simulations)\n";
  return os.str();
}

}  // namespace cairn

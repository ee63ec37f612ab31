#include "cairn/report/sequence_report.h"

#include <sstream>
#include <vector>

#include "report/report_common.h"

namespace cairn {

namespace {

using report_internal::Angular;
using report_internal::Names;
using report_internal::Num;
using report_internal::Vec;

// The state's verdict in the check's words.
const char* VerdictWord(const SequenceStep& step) { return step.stands ? "stands" : "falls"; }

}  // namespace

nlohmann::json SequenceToJson(const Assembly& assembly, const BuildSequence& s, double seconds,
                              const ReportOptions& options) {
  const int dim = assembly.dimension();
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  nlohmann::json doc;
  doc["scene"] = assembly.name();
  if (!options.scene_file.empty()) doc["scene_file"] = options.scene_file;
  doc["dimension"] = dim;
  doc["complete"] = s.complete;
  doc["stopped"] = s.stopped;
  doc["message"] = s.message;
  doc["force_unit"] = force_unit;
  nlohmann::json order = nlohmann::json::array(), steps = nlohmann::json::array();
  for (const SequenceStep& step : s.steps) {
    order.push_back(assembly.part(step.part).name);
    nlohmann::json j;
    j["place"] = assembly.part(step.part).name;
    j["direction"] = Vec(step.direction, dim);
    nlohmann::json in_place = nlohmann::json::array();
    for (const TemporarySupport& t : step.in_place) {
      const Part& part = assembly.part(t.part);
      in_place.push_back({{"kind", to_string(t.kind)},
                          {"part", part.name},
                          {"point", Vec(part.centroid, dim)},
                          {"normal", nullptr},
                          {"force", Vec(t.force / force_scale, dim)},
                          {"torque", Angular(t.torque / force_scale, dim)}});
    }
    j["temporary_in_place"] = in_place;
    j["added"] = Names(assembly, step.added);
    j["removed"] = Names(assembly, step.removed);
    j["verdict"] = VerdictWord(step);
    j["stability"] = to_string(step.stability);
    steps.push_back(j);
  }
  doc["order"] = order;
  doc["steps"] = steps;
  doc["temporary"] = {{"kinds", {"hold"}},
                      {"max_in_place", s.max_in_place},
                      {"placements", s.placements},
                      {"lower_bound", s.lower_bound},
                      {"lower_bound_reason", s.lower_bound_reason},
                      {"optimal", s.optimal()}};
  doc["stats"] = {{"states_checked", s.states_checked},
                  {"cache_hits", s.cache_hits},
                  {"repairs", s.repairs},
                  {"lp_warm_starts", s.warm_starts},
                  {"seconds", seconds}};
  return doc;
}

std::string SequenceToText(const Assembly& assembly, const BuildSequence& s,
                           const ReportOptions& options) {
  const int dim = assembly.dimension();
  std::ostringstream os;
  os << assembly.name() << ": "
     << (s.complete ? "build order of " + std::to_string(s.steps.size()) + " parts"
                    : "NO COMPLETE BUILD ORDER")
     << "  ["
     << (s.max_in_place == 0 ? std::string("no support")
                             : std::to_string(s.max_in_place) + " hold(s) at once, " +
                                   std::to_string(s.placements) + " in all")
     << "]\n";
  if (!s.message.empty()) os << "  " << s.message << '\n';
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  for (size_t i = 0; i < s.steps.size(); ++i) {
    const SequenceStep& step = s.steps[i];
    os << "  " << i + 1 << ". place " << assembly.part(step.part).name << " along ["
       << Num(step.direction.x()) << ", " << Num(step.direction.y());
    if (dim == 3) os << ", " << Num(step.direction.z());
    os << "]: " << VerdictWord(step);
    for (int h : step.added) os << "; hold " << assembly.part(h).name;
    for (int h : step.removed) os << "; release " << assembly.part(h).name;
    for (const TemporarySupport& t : step.in_place)
      os << "; " << assembly.part(t.part).name << " held with " << Num(t.force.norm() / force_scale)
         << ' ' << force_unit;
    os << '\n';
  }
  os << "  supports at once: " << s.max_in_place << ", lower bound " << s.lower_bound
     << (s.optimal() ? " (optimal)" : "") << ": " << s.lower_bound_reason << '\n';
  os << "  " << s.states_checked << " states checked (" << s.cache_hits << " cached)\n";
  return os.str();
}

}  // namespace cairn

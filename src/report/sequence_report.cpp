#include "cairn/report/sequence_report.h"

#include <sstream>
#include <vector>

#include "cairn/core/format.h"
#include "report/report_common.h"

namespace cairn {

namespace {

using report_internal::Angular;
using report_internal::Names;
using report_internal::Num;
using report_internal::Vec;

// The state's verdict in the check's words.
const char* VerdictWord(const SequenceStep& step) { return step.stands ? "stands" : "falls"; }

// A support: its kind, part, point and (a prop) normal; in place, also what
// it carries.
nlohmann::json SupportToJson(const Assembly& assembly, const TemporarySupport& t, int dim,
                             const double* force_scale) {
  const bool prop = t.kind == TemporaryKind::kProp;
  nlohmann::json j = {{"kind", to_string(t.kind)},
                      {"part", assembly.part(t.part).name},
                      {"point", Vec(t.point, dim)},
                      {"normal", prop ? Vec(t.normal, dim) : nlohmann::json(nullptr)}};
  if (force_scale) {
    j["force"] = Vec(t.force / *force_scale, dim);
    j["torque"] = prop ? nlohmann::json(nullptr) : Angular(t.torque / *force_scale, dim);
  }
  return j;
}

// "hold A", "prop under A at (1, 2)".
std::string SupportWords(const Assembly& assembly, const TemporarySupport& t) {
  if (t.kind == TemporaryKind::kHold) return "hold " + assembly.part(t.part).name;
  return "prop under " + assembly.part(t.part).name + " at " +
         FormatPoint(t.point, assembly.dimension());
}

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
    nlohmann::json in_place = nlohmann::json::array(), added = nlohmann::json::array(),
                   removed = nlohmann::json::array();
    for (const TemporarySupport& t : step.in_place)
      in_place.push_back(SupportToJson(assembly, t, dim, &force_scale));
    for (const TemporarySupport& t : step.added)
      added.push_back(SupportToJson(assembly, t, dim, nullptr));
    for (const TemporarySupport& t : step.removed)
      removed.push_back(SupportToJson(assembly, t, dim, nullptr));
    j["temporary_in_place"] = in_place;
    j["added"] = added;
    j["removed"] = removed;
    j["verdict"] = VerdictWord(step);
    j["stability"] = to_string(step.stability);
    steps.push_back(j);
  }
  doc["order"] = order;
  doc["steps"] = steps;
  nlohmann::json kinds = nlohmann::json::array();
  for (TemporaryKind k : s.kinds) kinds.push_back(to_string(k));
  doc["temporary"] = {{"kinds", kinds},
                      {"max_in_place", s.max_in_place},
                      {"placements", s.placements},
                      {"lower_bound", s.lower_bound},
                      {"lower_bound_reason", s.lower_bound_reason},
                      {"optimal", s.optimal()}};
  doc["stats"] = {{"states_checked", s.states_checked},
                  {"cache_hits", s.cache_hits},
                  {"repairs", s.repairs},
                  {"verdict_rejections", s.verdict_rejections},
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
                             : std::to_string(s.max_in_place) + " support(s) at once, " +
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
    for (const TemporarySupport& t : step.added) os << "; " << SupportWords(assembly, t);
    for (const TemporarySupport& t : step.removed)
      os << (t.kind == TemporaryKind::kHold ? "; release " : "; take out the prop under ")
         << assembly.part(t.part).name;
    for (const TemporarySupport& t : step.in_place)
      os << "; " << (t.kind == TemporaryKind::kHold ? "" : "the prop under ")
         << assembly.part(t.part).name
         << (t.kind == TemporaryKind::kHold ? " held with " : " carries ")
         << Num(t.force.norm() / force_scale) << ' ' << force_unit;
    os << '\n';
  }
  os << "  supports at once: " << s.max_in_place << ", lower bound " << s.lower_bound
     << (s.optimal() ? " (optimal)" : "") << ": " << s.lower_bound_reason << '\n';
  os << "  " << s.states_checked << " states checked (" << s.cache_hits << " cached)\n";
  return os.str();
}

}  // namespace cairn

// The result page (docs/html.md): the page data of each kind, and the HTML
// text around it.

#include "cairn/report/html_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <utility>

#include "report/report_common.h"
#include "viewer_bundle.h"

namespace cairn {
namespace {

using report_internal::ContactRecord;
using report_internal::ForceRoundoffScale;

using nlohmann::json;

// Numbers on the page keep 7 significant digits: far below what a drawing
// shows, and a third of the text of a double's 17.
double Short(double x) {
  if (!std::isfinite(x) || x == 0) return std::isfinite(x) ? 0.0 : x;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g", x);
  return std::strtod(buf, nullptr);
}

json Triple(const Vector3& v) { return json::array({Short(v.x()), Short(v.y()), Short(v.z())}); }

// --- the scene: shapes at the assembled pose, world frame ------------------

json PartShape(const Assembly& a, int i) {
  const Part& p = a.part(i);
  json j = {{"name", p.name},
            {"fixed", p.fixed},
            {"tool", p.tool},
            {"mass", Short(p.mass)},
            {"centroid", Triple(p.centroid)}};
  if (!a.is_3d()) {
    json outline = json::array();
    for (const Vector2& v : p.polygon) outline.push_back({Short(v.x()), Short(v.y())});
    j["outline"] = outline;
    return j;
  }
  // 3-D: the triangles of every face (outward), and the face boundaries as
  // the drawn edges (each edge once).
  const Polyhedron& poly = *p.polyhedron;
  json vertices = json::array(), triangles = json::array(), edges = json::array();
  for (const Vector3& v : poly.vertices())
    for (int k = 0; k < 3; ++k) vertices.push_back(Short(v[k]));
  for (const auto& face : poly.face_triangles())
    for (const auto& t : face)
      for (int k : t) triangles.push_back(k);
  std::set<std::pair<int, int>> seen;
  for (const std::vector<int>& face : poly.faces())
    for (size_t k = 0; k < face.size(); ++k) {
      const int u = face[k], v = face[(k + 1) % face.size()];
      if (seen.insert({std::min(u, v), std::max(u, v)}).second) {
        edges.push_back(u);
        edges.push_back(v);
      }
    }
  j["vertices"] = vertices;
  j["triangles"] = triangles;
  j["edges"] = edges;
  return j;
}

json SceneData(const Assembly& a, const ReportOptions& options) {
  const auto [force_scale, force_unit] = ForceScale(a, options);
  json parts = json::array();
  for (int i = 0; i < a.num_parts(); ++i) parts.push_back(PartShape(a, i));
  json fixtures = json::array();
  for (const Fixture& f : a.fixtures())
    fixtures.push_back(
        {{"part", f.part}, {"point", Triple(f.point)}, {"normal", Triple(f.normal)}});
  return {{"name", a.name()},
          {"file", options.scene_file},
          {"dimension", a.dimension()},
          {"size", Short(a.scene_size())},
          {"gravity", Triple(a.gravity())},
          {"force_unit", force_unit},
          // Arrows are drawn to the scale of the heaviest movable part's weight.
          {"force_reference", Short(a.max_weight() / force_scale)},
          {"parts", parts},
          {"fixtures", fixtures}};
}

// --- contacts: the records --json writes (report_common.h, ContactRecord) ---

// Every number of `j` to 7 significant digits (Short).
void ShortNumbers(json& j) {
  if (j.is_number_float()) j = Short(j.get<double>());
  if (j.is_array() || j.is_object())
    for (json& x : j) ShortNumbers(x);
}

// The records, their numbers short: the page of Jenga's pull (47 ticks, 29 000
// contacts) is 5.7 MB so, 6.2 MB with every double's 17 digits.
json Contacts(const Assembly& a, const std::vector<ContactReport>& contacts, double force_scale) {
  const double forces = ForceRoundoffScale(a, force_scale);
  json out = json::array();
  for (const ContactReport& c : contacts) {
    json record = ContactRecord(a, c, force_scale, forces);
    ShortNumbers(record);
    out.push_back(std::move(record));
  }
  return out;
}

// --- a simulation's ticks ---------------------------------------------------

// The poses of the parts away from their assembled pose, as
// [index, tx, ty, tz, qx, qy, qz, qw].
json MovedPoses(const std::vector<Pose>& poses) {
  json out = json::array();
  for (size_t i = 0; i < poses.size(); ++i) {
    const Pose& p = poses[i];
    if (p.translation.isZero(0) && p.rotation.isIdentity(0)) continue;
    const Eigen::Quaterniond q(p.rotation);
    out.push_back({static_cast<int>(i), Short(p.translation.x()), Short(p.translation.y()),
                   Short(p.translation.z()), Short(q.x()), Short(q.y()), Short(q.z()),
                   Short(q.w())});
  }
  return out;
}

// What the gripper does with each part, as the page colours it.
json Roles(const Assembly& a, const std::vector<PartRole>& roles) {
  json out = json::array();
  for (size_t i = 0; i < roles.size(); ++i) {
    const char* role = nullptr;
    if (roles[i] == PartRole::kCarried) role = "carried";
    if (IsDriven(roles[i])) role = a.part(static_cast<int>(i)).tool ? "tool" : "gripped";
    if (role) out.push_back({static_cast<int>(i), role});
  }
  return out;
}

// Which frames go on the page: all of them, or (beyond kMaxPageFrames) each
// step's first and last, the failure's, and evenly spaced ones.
std::vector<size_t> PageFrameIndices(const std::vector<SimulationFrame>& frames,
                                     const SimulationResult& result) {
  std::vector<size_t> keep;
  if (frames.size() <= static_cast<size_t>(kMaxPageFrames)) {
    for (size_t k = 0; k < frames.size(); ++k) keep.push_back(k);
    return keep;
  }
  std::set<size_t> chosen;
  const size_t stride = (frames.size() + kMaxPageFrames / 2 - 1) / (kMaxPageFrames / 2);
  for (size_t k = 0; k < frames.size(); ++k) {
    const bool step_edge = k == 0 || k + 1 == frames.size() ||
                           frames[k].step != frames[k - 1].step ||
                           frames[k].step != frames[k + 1].step;
    const bool failure = result.failure && frames[k].step == result.failure->step &&
                         frames[k].tick == result.failure->tick;
    if (step_edge || failure || k % stride == 0) chosen.insert(k);
  }
  return {chosen.begin(), chosen.end()};
}

json Frames(const Assembly& a, const SimulationResult& result,
            const std::vector<SimulationFrame>& frames, double force_scale) {
  // The timeline's rows of each (step, tick), in order.
  std::map<std::pair<int, int>, std::vector<ContactReport>> contacts;
  for (const TimelineRow& row : result.timeline)
    contacts[{row.step, row.tick}].push_back(row.contact);
  json out = json::array();
  for (size_t k : PageFrameIndices(frames, result)) {
    const SimulationFrame& f = frames[k];
    json absent = json::array();
    for (size_t i = 0; i < f.present.size(); ++i)
      if (!f.present[i]) absent.push_back(static_cast<int>(i));
    const auto it = contacts.find({f.step, f.tick});
    out.push_back({{"step", f.step},
                   {"tick", f.tick},
                   {"time", Short(f.time)},
                   {"poses", MovedPoses(f.poses)},
                   {"absent", absent},
                   {"roles", Roles(a, f.roles)},
                   {"contacts",
                    it != contacts.end() ? Contacts(a, it->second, force_scale) : json::array()}});
  }
  return out;
}

// --- a plan's nodes -----------------------------------------------------------

// The plan's page data: the rest state (contacts and forces) of every
// assembly that the listed sequences and the one-way removals start from,
// keyed by its present parts ("0,1,3"), and the present parts of each one-way
// removal (`noninvertible_steps`, in order).
class PlanNodes {
 public:
  PlanNodes(const Assembly& a, double force_scale) : a_(a), force_scale_(force_scale) {}

  void AddSequences(const PlannerResult& result, size_t shown) {
    for (size_t s = 0; s < shown; ++s) {
      // A sequence with fixels stands only with them: its nodes are not
      // drawn with forces.
      if (!result.sequences[s].fixels.empty()) continue;
      Configuration config = Configuration::Assembled(a_);
      for (const PlannedStep& step : result.sequences[s].steps) {
        Add(config);
        for (const std::string& name : step.step.remove) config.present[a_.FindPart(name)] = false;
      }
    }
  }

  // `remaining` names the movable parts of the node, the kept ones aside:
  // those are the movable parts the root node does not list.
  void AddOneWay(const PlannerResult& result, const json& noninvertible) {
    std::vector<bool> kept(a_.num_parts(), false);
    for (int i = 0; i < a_.num_parts(); ++i) kept[i] = !a_.part(i).fixed && !a_.part(i).tool;
    if (!result.nodes.empty())
      for (int i : result.nodes.front().parts) kept[i] = false;
    for (const json& n : noninvertible) {
      Configuration config = Configuration::Assembled(a_);
      for (int i = 0; i < a_.num_parts(); ++i) config.present[i] = a_.part(i).fixed || kept[i];
      for (const json& name : n["remaining"]) config.present[a_.FindPart(name)] = true;
      oneway_.push_back(Present(config));
      if (oneway_.size() <= static_cast<size_t>(kMaxPageSequences) && n["fixels"].is_null())
        Add(config);
    }
  }

  json ToJson(size_t shown) const {
    return {{"sequences_shown", shown}, {"nodes", nodes_}, {"oneway", oneway_}};
  }

 private:
  static std::vector<int> Present(const Configuration& config) {
    std::vector<int> present;
    for (size_t i = 0; i < config.present.size(); ++i)
      if (config.present[i]) present.push_back(static_cast<int>(i));
    return present;
  }
  void Add(const Configuration& config) {
    std::string key;
    for (int i : Present(config)) key += (key.empty() ? "" : ",") + std::to_string(i);
    if (nodes_.contains(key)) return;
    const StabilityResult r = AnalyzeConfiguration(a_, config, {}, nullptr, &workspace_);
    nodes_[key] = Contacts(a_, r.contacts, force_scale_);
  }

  const Assembly& a_;
  double force_scale_;
  StabilityWorkspace workspace_;
  json nodes_ = json::object();
  json oneway_ = json::array();
};

std::string Title(const Assembly& a, const ReportOptions& options) {
  return !a.name().empty() ? a.name() : options.scene_file;
}

// The page data made text for a <script> element: every '<' escaped, so no
// string of the scene ("</script>", "<!--") can end or change the element.
std::string ScriptSafeJson(const json& data) {
  const std::string text = data.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size() + text.size() / 64);
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

// For the <title>: the characters HTML gives a meaning to, as references.
std::string HtmlText(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string HtmlPage(const json& data) {
  const std::string title = data.value("title", std::string("Cairn")) + " — cairn " +
                            data.value("kind", std::string("result"));
  std::string page;
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<meta name=\"generator\" content=\"Cairn\">\n";
  page += "<title>" + HtmlText(title) + "</title>\n</head>\n<body>\n<div id=\"cairn-app\"></div>\n";
  page += "<script id=\"cairn-data\" type=\"application/json\">";
  page += ScriptSafeJson(data);
  page += "</script>\n<script>\n";
  for (const char* chunk : report_internal::kViewerBundle) page += chunk;
  page += "\n</script>\n</body>\n</html>\n";
  return page;
}

std::string CheckPage(const Assembly& assembly, const json& doc,
                      const std::vector<std::string>& story, const ReportOptions& options) {
  return HtmlPage({{"cairn_page", 1},
                   {"kind", "check"},
                   {"title", Title(assembly, options)},
                   {"scene", SceneData(assembly, options)},
                   {"result", doc},
                   {"story", story}});
}

namespace {

// A command's text summary as the page's story: its lines, without their
// indentation.
json StoryOfText(const std::string& text) {
  json story = json::array();
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const size_t start = line.find_first_not_of(' ');
    if (start != std::string::npos) story.push_back(line.substr(start));
  }
  return story;
}

// A page of `kind` whose data is the command's document and whose story is
// its text summary.
std::string DocumentPage(const char* kind, const Assembly& assembly, const json& doc,
                         const std::string& text, const ReportOptions& options) {
  return HtmlPage({{"cairn_page", 1},
                   {"kind", kind},
                   {"title", Title(assembly, options)},
                   {"scene", SceneData(assembly, options)},
                   {"result", doc},
                   {"story", StoryOfText(text)}});
}

}  // namespace

std::string MarginPage(const Assembly& assembly, const json& doc, const std::string& text,
                       const ReportOptions& options) {
  return DocumentPage("margin", assembly, doc, text, options);
}

std::string BlockingPage(const Assembly& assembly, const json& doc, const std::string& text,
                         const ReportOptions& options) {
  return DocumentPage("blocking", assembly, doc, text, options);
}

std::string SimulationPage(const Assembly& assembly, const SimulationResult& result,
                           const std::vector<SimulationFrame>& frames, const json& doc,
                           const std::string& margin_text, const ReportOptions& options) {
  const double force_scale = ForceScale(assembly, options).first;
  return HtmlPage({{"cairn_page", 1},
                   {"kind", "simulate"},
                   {"title", Title(assembly, options)},
                   {"scene", SceneData(assembly, options)},
                   {"result", doc},
                   {"story", StoryOfText(margin_text)},
                   {"frames", Frames(assembly, result, frames, force_scale)},
                   {"frames_total", frames.size()}});
}

std::string PlanPage(const Assembly& assembly, const PlannerResult& result, const json& doc,
                     const ReportOptions& options) {
  const double force_scale = ForceScale(assembly, options).first;
  const size_t shown = std::min(result.sequences.size(), static_cast<size_t>(kMaxPageSequences));
  PlanNodes nodes(assembly, force_scale);
  nodes.AddSequences(result, shown);
  nodes.AddOneWay(result, doc.value("noninvertible_steps", json::array()));
  return HtmlPage({{"cairn_page", 1},
                   {"kind", "plan"},
                   {"title", Title(assembly, options)},
                   {"scene", SceneData(assembly, options)},
                   {"result", doc},
                   {"plan", nodes.ToJson(shown)}});
}

std::string SequencePage(const Assembly& assembly, const BuildSequence& sequence, const json& doc,
                         const ReportOptions& options) {
  const double force_scale = ForceScale(assembly, options).first;
  json states = json::array();
  size_t contacts = 0;
  for (const SequenceStep& step : sequence.steps) {
    contacts += step.contacts.size();
    states.push_back(contacts <= kMaxPageContacts ? Contacts(assembly, step.contacts, force_scale)
                                                  : json(nullptr));
  }
  return HtmlPage({{"cairn_page", 1},
                   {"kind", "sequence"},
                   {"title", Title(assembly, options)},
                   {"scene", SceneData(assembly, options)},
                   {"result", doc},
                   {"sequence", {{"states", states}, {"max_contacts", kMaxPageContacts}}}});
}

}  // namespace cairn

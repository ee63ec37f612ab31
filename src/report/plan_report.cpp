#include "cairn/report/plan_report.h"

#include <cstdio>
#include <sstream>

#include "cairn/core/format.h"
#include "cairn/report/words.h"
#include "report/report_common.h"

namespace cairn {
namespace {

using nlohmann::json;
using report_internal::Clean;
using report_internal::Names;
using report_internal::Num;
using report_internal::Vec;

std::string Joined(const Assembly& a, const std::vector<int>& parts, const char* sep = "+") {
  std::string s;
  for (size_t k = 0; k < parts.size(); ++k) s += (k ? sep : "") + a.part(parts[k]).name;
  return s;
}

// One step in plan format: remove, grip (when it differs), the path in one of
// its two forms, support.
json StepToJson(const PlanStepDef& s, int dim) {
  json j;
  j["remove"] = s.remove;
  if (!s.grip.empty()) j["grip"] = s.grip;
  if (s.has_direction) {
    j["direction"] = Vec(s.direction, dim);
    j["distance"] = Clean(s.distance);
  } else {
    json path = json::array();
    for (const Vector3& p : s.path) path.push_back(Vec(p, dim));
    j["path"] = path;
  }
  j["support"] = to_string(s.support);
  if (!s.hold.empty()) j["hold"] = s.hold;
  if (s.has_hold_at_rest) j["hold_at_rest"] = s.hold_at_rest;
  const auto props = [&](const std::vector<FixtureDef>& list) {
    json out = json::array();
    for (const FixtureDef& f : list) out.push_back(report_internal::FixtureToJson(f, dim));
    return out;
  };
  if (!s.props.empty()) j["props"] = props(s.props);
  if (s.has_props_at_rest) j["props_at_rest"] = props(s.props_at_rest);
  return j;
}

// Fixels as `part`, `point`, `normal` (the scene format's `fixtures`).
json FixelsToJson(const Assembly& a, const std::vector<FixtureDef>& fixels) {
  json out = json::array();
  for (const FixtureDef& f : fixels)
    out.push_back(report_internal::FixtureToJson(f, a.dimension()));
  return out;
}

// Paths of the fixture search carry no assembly verdict.
bool AssemblyChecked(const PathTrial& t) { return t.decided_by.rfind("fixture search", 0) != 0; }

// A candidate path as the graph and the non-invertible list show it; the
// graph leaves out the points of the path (its label says which it is: a
// large graph has hundreds of thousands of trials).
json TrialToJson(const Assembly& a, const PathTrial& t, bool with_path = true) {
  const int dim = a.dimension();
  json j;
  j["label"] = t.candidate.label;
  if (with_path) {
    json path = json::array();
    for (const Vector3& p : t.candidate.path) path.push_back(Vec(p, dim));
    j["path"] = path;
  }
  j["support"] = to_string(t.candidate.support);
  if (!t.candidate.grip.empty()) j["tools"] = Names(a, t.candidate.grip);
  j["disassembly"] = to_string(t.disassembly);
  j["assembly"] = AssemblyChecked(t) ? json(to_string(t.assembly)) : json(nullptr);
  j["decided_by"] = t.decided_by;
  if (!t.fixels.empty()) j["fixels"] = FixelsToJson(a, t.fixels);
  if (const std::string why = PathTrialFailure(a, t); !why.empty()) j["failure"] = why;
  return j;
}

json SequenceToJson(const Assembly& a, const PlannerResult& r, const PlannedSequence& seq) {
  json steps = json::array(), checks = json::array();
  for (const PlannedStep& s : seq.steps) {
    steps.push_back(StepToJson(s.step, a.dimension()));
    const PathTrial& t = r.edges.empty() ? PathTrial{} : r.edges[s.edge].trials[s.trial];
    checks.push_back(
        {{"label", t.candidate.label},
         {"disassembly", to_string(t.disassembly)},
         {"assembly", AssemblyChecked(t) ? json(to_string(t.assembly)) : json(nullptr)},
         {"decided_by", t.decided_by}});
  }
  json out = {{"steps", steps}, {"invertible", seq.invertible}, {"checks", checks}};
  if (!seq.fixels.empty()) out["fixels"] = FixelsToJson(a, seq.fixels);
  return out;
}

// "D up", "A+B -x", "C given path 2".
std::string StepLabel(const PlannerResult& r, const PlannedStep& s) {
  std::string names;
  for (size_t k = 0; k < s.step.remove.size(); ++k) names += (k ? "+" : "") + s.step.remove[k];
  if (r.edges.empty()) return names;
  return names + " " + r.edges[s.edge].trials[s.trial].candidate.label;
}

}  // namespace

json PlanDefToJson(const PlanDef& plan, int dimension) {
  json doc;
  doc["cairn_plan"] = 1;
  doc["mode"] = to_string(plan.mode);
  doc["dt"] = plan.dt;
  doc["speed"] = plan.speed;
  json steps = json::array();
  for (const PlanStepDef& s : plan.steps) steps.push_back(StepToJson(s, dimension));
  doc["steps"] = steps;
  return doc;
}

json PlannerToJson(const Assembly& assembly, const PlannerResult& r, const std::string& scene) {
  json doc;
  doc["scene"] = scene;
  doc["dimension"] = assembly.dimension();
  doc["dt"] = r.dt;
  doc["speed"] = r.speed;
  doc["complete"] = r.complete;
  doc["message"] = r.message;
  json seqs = json::array();
  for (const PlannedSequence& s : r.sequences) seqs.push_back(SequenceToJson(assembly, r, s));
  doc["sequences"] = seqs;
  json as = json::array();
  for (const PlannedSequence& s : r.assembly_only) as.push_back(SequenceToJson(assembly, r, s));
  doc["assembly_only_sequences"] = as;

  // Every path whose disassembly and assembly verdicts differ.
  json nonin = json::array();
  for (const PlanEdge& e : r.edges)
    for (const PathTrial& t : e.trials)
      if (t.disassembly != t.assembly && AssemblyChecked(t)) {
        json j = TrialToJson(assembly, t);
        j["remove"] = Names(assembly, e.remove);
        j["remaining"] = Names(assembly, r.nodes[e.from].parts);
        nonin.push_back(j);
      }
  doc["noninvertible_steps"] = nonin;

  json nodes = json::array(), edges = json::array();
  for (size_t i = 0; i < r.nodes.size(); ++i) {
    const PlanNode& n = r.nodes[i];
    nodes.push_back({{"id", i},
                     {"parts", Names(assembly, n.parts)},
                     {"stable", n.stable},
                     {"expanded", n.expanded}});
  }
  for (const PlanEdge& e : r.edges) {
    json trials = json::array();
    for (const PathTrial& t : e.trials) trials.push_back(TrialToJson(assembly, t, false));
    edges.push_back(
        {{"from", e.from},
         {"to", e.to},
         {"remove", Names(assembly, e.remove)},
         {"trials", trials},
         {"chosen", e.chosen >= 0 ? json(e.chosen) : json(nullptr)},
         {"assembly_chosen", e.assembly_chosen >= 0 ? json(e.assembly_chosen) : json(nullptr)}});
  }
  doc["graph"] = {{"nodes", nodes}, {"edges", edges}};
  const PlannerStats& s = r.stats;
  doc["stats"] = {{"nodes", s.nodes},
                  {"edges", s.edges},
                  {"checks", s.node_checks + s.path_simulations},
                  {"node_checks", s.node_checks},
                  {"path_simulations", s.path_simulations},
                  {"decided_by_nodes", s.decided_by_nodes},
                  {"pruned_by_proposition_1", s.pruned_by_proposition_1},
                  {"memo_hits", s.memo_hits},
                  {"sequences_total", s.sequences_total},
                  {"threads", s.threads},
                  {"time", s.seconds},
                  {"ranks", s.ranks}};
  // Spread over MPI ranks: the seconds each spent on its tasks and on
  // exchanging results (waiting for the others included).
  if (s.ranks > 1) {
    doc["stats"]["rank_time"] = s.rank_seconds;
    doc["stats"]["communication_time"] = s.communication_seconds;
  }
  return doc;
}

std::string PlannerToText(const Assembly& assembly, const PlannerResult& r,
                          const std::string& scene) {
  std::ostringstream os;
  const PlannerStats& s = r.stats;
  os << "cairn plan: " << scene << " (" << assembly.dimension() << "-D, " << assembly.num_parts()
     << " parts)\n";
  const bool fixels = !r.sequences.empty() && !r.sequences.front().fixels.empty();
  if (fixels)
    os << r.sequences.size() << " sequence" << (r.sequences.size() == 1 ? "" : "s")
       << " stable with fixels (none is stable without)\n";
  else if (r.complete)
    os << Num(s.sequences_total) << " stable disassembly sequence"
       << (s.sequences_total == 1 ? "" : "s") << " (the AND/OR graph enumerated completely)\n";
  else if (r.sequences.empty())
    os << "0 stable disassembly sequences\n";
  else
    os << r.sequences.size() << " stable disassembly sequence"
       << (r.sequences.size() == 1 ? "" : "s") << " found (best-first search)\n";
  for (size_t k = 0; k < r.sequences.size(); ++k) {
    const PlannedSequence& seq = r.sequences[k];
    os << "  " << k + 1 << ". ";
    for (size_t i = 0; i < seq.steps.size(); ++i)
      os << (i ? ", " : "") << StepLabel(r, seq.steps[i]);
    if (!seq.fixels.empty()) {
      os << "  [with " << seq.fixels.size() << " fixel" << (seq.fixels.size() == 1 ? "" : "s")
         << ":";
      for (const FixtureDef& f : seq.fixels)
        os << " " << f.part << " at " << FormatPoint(f.point, assembly.dimension()) << " pushing "
           << FormatPoint(f.normal, assembly.dimension()) << ";";
      os << "]\n";
    } else {
      os << (seq.invertible ? "  [invertible]" : "  [not invertible: the assembly differs]")
         << '\n';
    }
  }
  if (!r.assembly_only.empty()) {
    os << "Stable only as assemblies (the reverse, taken apart, is not stable):\n";
    for (size_t k = 0; k < r.assembly_only.size(); ++k) {
      os << "  " << k + 1 << ". ";
      const PlannedSequence& seq = r.assembly_only[k];
      for (size_t i = seq.steps.size(); i-- > 0;)
        os << (i + 1 < seq.steps.size() ? ", " : "") << StepLabel(r, seq.steps[i]);
      os << "  (in assembly order)\n";
    }
  }
  bool header = false;
  for (const PlanEdge& e : r.edges)
    for (const PathTrial& t : e.trials) {
      if (t.disassembly == t.assembly || !AssemblyChecked(t)) continue;
      if (!header) os << "Not invertible (disassembly and assembly differ):\n";
      header = true;
      os << "  " << Joined(assembly, e.remove) << " " << t.candidate.label << " from {"
         << Joined(assembly, r.nodes[e.from].parts, ", ") << "}: disassembly "
         << to_string(t.disassembly) << ", assembly " << to_string(t.assembly);
      if (const std::string why = PathTrialFailure(assembly, t); !why.empty())
        os << " (" << why << ")";
      os << '\n';
    }
  if (!r.message.empty()) os << r.message << '\n';
  os << "Work: " << s.nodes << " nodes, " << s.edges << " edges, " << s.node_checks
     << " node checks, " << s.path_simulations << " path simulations; " << s.decided_by_nodes
     << " paths decided by node checks (Corollary 2), " << s.pruned_by_proposition_1
     << " edges pruned (Proposition 1); " << Num(s.seconds) << " s on " << s.threads << " thread"
     << (s.threads == 1 ? "" : "s")
     << (s.ranks > 1 ? " on each of " + std::to_string(s.ranks) + " ranks" : std::string()) << '\n';
  return os.str();
}

std::string PlannerToDot(const Assembly& assembly, const PlannerResult& r) {
  std::ostringstream os;
  os << "digraph andor {\n  rankdir=TB;\n  node [shape=box, fontname=Helvetica];\n"
     << "  edge [fontname=Helvetica, fontsize=10];\n";
  for (size_t i = 0; i < r.nodes.size(); ++i) {
    const PlanNode& n = r.nodes[i];
    const std::string label = n.parts.empty() ? "(empty)" : Joined(assembly, n.parts, " ");
    os << "  n" << i << " [label=\"" << label << "\"";
    if (!n.stable) os << ", style=filled, fillcolor=\"#f4b0b0\"";
    os << "];\n";
  }
  for (const PlanEdge& e : r.edges) {
    const int shown = e.chosen >= 0 ? e.chosen : (e.assembly_chosen >= 0 ? e.assembly_chosen : 0);
    const std::string label = Joined(assembly, e.remove) + " " + e.trials[shown].candidate.label;
    const char* style = e.chosen >= 0            ? "color=darkgreen"
                        : e.assembly_chosen >= 0 ? "color=orange"
                                                 : "color=red, style=dashed";
    os << "  n" << e.from << " -> n" << e.to << " [label=\"" << label << "\", " << style << "];\n";
  }
  os << "}\n";
  return os.str();
}

}  // namespace cairn

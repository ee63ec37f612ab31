#include "cairn/report/check_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "cairn/core/format.h"
#include "cairn/report/words.h"
#include "report/report_common.h"

namespace cairn {

namespace {
using report_internal::Angular;
using report_internal::Clean;
using report_internal::ContactRecord;
using report_internal::ForceRoundoffScale;
using report_internal::Tangential;
using report_internal::Vec;

// Nothing holds the assembly: no part present is fixed and no fixture (a
// contact with the world) touches any part, so everything falls together.
bool NothingFixed(const Assembly& assembly, const Configuration& config,
                  const StabilityResult& result) {
  for (int i = 0; i < assembly.num_parts(); ++i)
    if (config.present[i] && assembly.part(i).fixed) return false;
  for (const ContactReport& cr : result.contacts)
    if (cr.contact.part_a < 0 || cr.contact.part_b < 0) return false;
  return true;
}
}  // namespace

namespace {

using nlohmann::json;

// What the JSON writers of a check share: the scene's dimension, the
// formulation's words (velocity or acceleration), the force unit and the
// scale of motions.
struct CheckJsonContext {
  const Assembly& assembly;
  int dim;
  bool st;             // Stewart–Trinkle: velocities; else accelerations
  double force_scale;  // forces are divided by it
  double g;            // motions are cleaned relative to it
};

// Parts: every present part; movable ones carry their motion.
json PartsToJson(const CheckJsonContext& cx, const Configuration& config,
                 const StabilityResult& result) {
  const Assembly& assembly = cx.assembly;
  const int dim = cx.dim;
  const bool st = cx.st;
  const double g = cx.g;
  json parts = json::array();
  std::vector<const PartMotion*> motion_of(assembly.num_parts(), nullptr);
  for (const PartMotion& m : result.parts) motion_of[m.part] = &m;
  for (int i = 0; i < assembly.num_parts(); ++i) {
    if (!config.present[i]) continue;
    const Part& p = assembly.part(i);
    json jp;
    jp["name"] = p.name;
    jp["fixed"] = p.fixed;
    jp["mass"] = p.mass;
    jp["centroid"] = Vec(config.WorldCentroid(assembly, i), dim);
    if (const PartMotion* m = motion_of[i]) {
      jp["moving"] = m->moving;
      jp["motion"] = to_string(m->kind);
      json mo;
      mo["linear"] = Vec(m->linear, dim, g);
      mo["angular"] = Angular(m->angular, dim, g);
      jp[st ? "velocity" : "acceleration"] = mo;
      if (m->pivot) jp["pivot"] = Vec(*m->pivot, dim);
      if (m->pivot && dim == 3) jp["axis"] = Vec(m->angular.normalized(), dim);
    }
    parts.push_back(jp);
  }
  return parts;
}

// Each contact: where, its normal, the forces and the relative motion.
json ContactsToJson(const CheckJsonContext& cx, const StabilityResult& result) {
  const Assembly& assembly = cx.assembly;
  const int dim = cx.dim;
  const bool st = cx.st;
  const double g = cx.g;
  const double force_scale = cx.force_scale;
  const double forces = ForceRoundoffScale(assembly, force_scale);
  json contacts = json::array();
  for (const ContactReport& cr : result.contacts) {
    const Contact& c = cr.contact;
    json jc = ContactRecord(assembly, cr, force_scale, forces);
    jc["feature"] = to_string(c.feature);
    jc["mu"] = c.mu;
    jc[st ? "normal_velocity" : "normal_acceleration"] = Clean(cr.normal_motion, g);
    jc[st ? "sliding_velocity" : "tangential_acceleration"] =
        Tangential(cr.tangent_motion, c, dim, g);
    jc["component"] = cr.component;
    contacts.push_back(jc);
  }
  return contacts;
}

// Each component: what decided it, what is proved, the solver's numbers.
json ComponentsToJson(const Assembly& assembly, const StabilityResult& result) {
  json comps = json::array();
  for (const ComponentReport& r : result.components) {
    json jr;
    json names = json::array();
    for (int i : r.parts) names.push_back(assembly.part(i).name);
    jr["parts"] = names;
    jr["contacts"] = r.num_contacts;
    jr["lcp_size"] = r.lcp_size;
    jr["decided_by"] = to_string(r.decided_by);
    jr["stability"] =
        r.stability == StabilityProof::kNone ? json(nullptr) : json(to_string(r.stability));
    jr["static_equilibrium"] = r.static_equilibrium ? json(*r.static_equilibrium) : json(nullptr);
    jr["frictionless_equilibrium"] =
        r.frictionless_equilibrium ? json(*r.frictionless_equilibrium) : json(nullptr);
    if (!r.equilibrium_method.empty()) jr["equilibrium_method"] = r.equilibrium_method;
    if (r.decided_by == DecidedBy::kMechanism) {
      json mech;
      json mparts = json::array(), held = json::array();
      for (int i : r.mechanism_parts) mparts.push_back(assembly.part(i).name);
      for (int i : r.held) held.push_back(assembly.part(i).name);
      mech["parts"] = mparts;
      mech["power"] = r.mechanism_power;
      mech["held"] = held;
      jr["mechanism"] = mech;
    }
    if (r.loaded_from_rest) {
      json loaded;
      loaded["outcome"] = to_string(*r.loaded_from_rest);
      json gives = json::array();
      for (int i : r.loaded_gives_way) gives.push_back(assembly.part(i).name);
      loaded["gives_way"] = gives;
      if (*r.loaded_from_rest == LoadedFromRest::Outcome::kStands)
        loaded["unbalanced"] = r.loaded_unbalanced;
      jr["loaded_from_rest"] = loaded;
    }
    if (!r.rigid_motion_parts.empty()) {
      json moved = json::array();
      for (int i : r.rigid_motion_parts) moved.push_back(assembly.part(i).name);
      jr["rigid_motion"] = moved;
    }
    if (r.search) {
      json search;
      search["outcome"] = to_string(*r.search);
      search["nodes"] = r.search_nodes;
      search["open"] = r.search_open;
      jr["search"] = search;
    }
    jr["status"] = to_string(r.status);
    jr["pivots"] = r.pivots;
    // Decided by a linear program's solution at rest rather than by Lemke's
    // method (weak stability: some solution of the LCP keeps the parts put).
    jr["rest_solution"] = r.rest_solution;
    jr["residual"] = r.residual;
    jr["consistency_residual"] = r.consistency_residual;
    if (!r.message.empty()) jr["message"] = r.message;
    comps.push_back(jr);
  }
  return comps;
}

}  // namespace

nlohmann::json StabilityToJson(const Assembly& assembly, const Configuration& config,
                               const StabilityResult& result, const ReportOptions& options) {
  const bool st = result.formulation == Formulation::kStewartTrinkle;
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  const double g = assembly.gravity().norm() > 0 ? assembly.gravity().norm() : 1.0;
  const int dim = assembly.dimension();
  const CheckJsonContext cx{assembly, dim, st, force_scale, g};
  json doc;
  doc["scene"] = assembly.name();
  if (!options.scene_file.empty()) doc["scene_file"] = options.scene_file;
  doc["verdict"] = to_string(result.verdict);
  doc["stable"] = result.stable();
  doc["dimension"] = dim;
  doc["formulation"] = to_string(result.formulation);
  if (dim == 3 && st) doc["friction_directions"] = assembly.friction_directions();
  if (st) doc["dt"] = result.dt;
  json without = json::array();
  for (int i : options.without) without.push_back(assembly.part(i).name);
  doc["without"] = without;
  json moving = json::array();
  for (int i : result.moving) moving.push_back(assembly.part(i).name);
  doc["moving"] = moving;
  doc["nothing_fixed"] = NothingFixed(assembly, config, result);
  doc["static_equilibrium"] =
      result.static_equilibrium ? json(*result.static_equilibrium) : json(nullptr);
  doc["weakly_stable"] = result.weakly_stable;
  // What is proved about rest: "strong" | "weak" | "not certified"; null when
  // no rest is possible (unstable without an equilibrium) or not examined.
  doc["stability"] =
      result.stability == StabilityProof::kNone ? json(nullptr) : json(to_string(result.stability));
  // The rule where rigid bodies leave the answer open, and what loading from
  // rest said (null when no component needed it).
  doc["rule"] = to_string(result.rule);
  doc["loaded_from_rest"] =
      result.loaded_from_rest ? json(to_string(*result.loaded_from_rest)) : json(nullptr);
  doc["force_unit"] = force_unit;

  doc["parts"] = PartsToJson(cx, config, result);
  doc["contacts"] = ContactsToJson(cx, result);
  doc["components"] = ComponentsToJson(assembly, result);
  doc["tolerances"] = {{"length", result.tolerances.length},
                       {"angle", result.tolerances.angle},
                       {st ? "velocity" : "acceleration",
                        st ? result.tolerances.velocity : result.tolerances.acceleration}};
  doc["diagnostics"] = result.diagnostics;
  return doc;
}

// ---- The text summary ----

namespace {
std::string Fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, std::abs(x) < 5e-13 ? 0.0 : x);
  return buf;
}
std::string TextPartName(const Assembly& a, int i) {
  return report_internal::PartName(a, i, "fixture");
}

// The summary's lists (moving parts, contacts, pairs of parts) stop after
// this many rows; --contacts all and --json give every one.
constexpr size_t kSummaryRows = 10;

// The headline: the scene, the verdict, the formulation; the parts taken
// away; a note when nothing is fixed.
void TextHeadline(const Assembly& assembly, const Configuration& config,
                  const StabilityResult& result, const ReportOptions& options,
                  std::ostringstream& os) {
  const bool st = result.formulation == Formulation::kStewartTrinkle;
  // Headline.
  os << (assembly.name().empty() ? options.scene_file : assembly.name()) << ": ";
  switch (result.verdict) {
    case Verdict::kStable:
      os << "STABLE";
      break;
    case Verdict::kUnstable:
      os << "UNSTABLE";
      break;
    case Verdict::kSolverFailure:
      os << "UNDECIDED (solver failure)";
      break;
  }
  os << "  [" << (st ? "Coulomb friction, Stewart-Trinkle step" : "frictionless, Baraff") << "]\n";
  if (!options.without.empty()) {
    os << "  without:";
    for (int i : options.without) os << ' ' << assembly.part(i).name;
    os << '\n';
  }
  if (NothingFixed(assembly, config, result))
    os << "  nothing is fixed: no part is fixed and no fixture holds one, so the whole assembly\n"
          "  falls. Fix the parts that rest on the ground: --fixed PART,... (also --supports;\n"
          "  COMPAS: node keys), the sidecar's \"fixed\": true (STEP, ASAP), or a part's\n"
          "  \"fixed\": true in a scene file\n";
}

std::string PartCount(size_t n) { return std::to_string(n) + (n == 1 ? " part" : " parts"); }

// Part names, comma-separated.
std::string Names(const Assembly& assembly, const std::vector<int>& parts) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + assembly.part(parts[i]).name;
  return out;
}

// What is proved about rest, and by what (the certificate, or the complete
// search for a moving solution and how far it got).
void TextStability(const StabilityResult& result, std::ostringstream& os) {
  bool searched = false;
  int nodes = 0, open = 0;
  std::string unsearched;
  for (const ComponentReport& c : result.components) {
    if (c.stability == StabilityProof::kStrong && c.search == MovingSolution::Outcome::kNone)
      searched = true;
    if (c.stability != StabilityProof::kNotCertified) continue;
    if (c.search == MovingSolution::Outcome::kBudget) {
      nodes += c.search_nodes;
      open += c.search_open;
    } else if (unsearched.empty()) {
      unsearched = c.search ? to_string(*c.search) : "not run";
    }
  }
  if (result.stability == StabilityProof::kStrong) {
    os << "  strongly stable: every solution of the contact problem is at rest ("
       << (searched ? "the complete search for a moving solution found none"
                    : "a frictionless equilibrium exists")
       << ")\n";
  } else if (result.stability == StabilityProof::kWeak && result.stable()) {
    os << "  weakly stable only: rest is possible, and so is a motion of the rigid parts\n";
  } else if (result.stability == StabilityProof::kNotCertified) {
    os << "  stability not certified as strong: rest is possible and no motion was found; ";
    if (unsearched.empty())
      os << "the complete search\n  for one stopped at its work budget after " << nodes
         << " branches, " << open << " still open\n";
    else
      os << "the search for one:\n  " << unsearched << " (see the component's message)\n";
  }
}

// One line on why it stands or falls where rigid bodies leave it open.
void TextWhy(const Assembly& assembly, const StabilityResult& result, std::ostringstream& os) {
  for (const ComponentReport& c : result.components) {
    if (!c.loaded_from_rest) continue;
    const std::string rigid =
        c.rigid_motion_parts.empty()
            ? std::string("no rigid motion found")
            : "a rigid solution also moves " + Names(assembly, c.rigid_motion_parts);
    switch (*c.loaded_from_rest) {
      case LoadedFromRest::Outcome::kStands:
        os << "  stands when loaded from rest on compliant contacts (rigid bodies leave it "
              "open: an equilibrium exists, "
           << rigid << ")\n";
        break;
      case LoadedFromRest::Outcome::kGivesWay:
        os << "  falls: an equilibrium exists, but loaded from rest on compliant contacts "
           << (c.loaded_gives_way.empty() ? std::string("it") : Names(assembly, c.loaded_gives_way))
           << " gives way: nothing produces the forces that equilibrium needs\n";
        break;
      case LoadedFromRest::Outcome::kNotRun:
      case LoadedFromRest::Outcome::kFailed:
        os << "  stands by the equilibrium: loading from rest " << to_string(*c.loaded_from_rest)
           << " (see the component's message)\n";
        break;
    }
  }
}

// The sizes, what decided the components (each one's message, once), and
// what is proved about rest.
void TextSummary(const Assembly& assembly, const StabilityResult& result, std::ostringstream& os) {
  int movable = 0, pivots = 0, lcp_vars = 0;
  for (const PartMotion& m : result.parts) (void)m, ++movable;
  for (const ComponentReport& c : result.components) pivots += c.pivots, lcp_vars += c.lcp_size;
  os << "  " << movable << " movable part" << (movable == 1 ? "" : "s") << ", "
     << result.contacts.size() << " contacts, " << result.components.size() << " component"
     << (result.components.size() == 1 ? "" : "s") << "; LCP " << lcp_vars << " variables, "
     << pivots << " pivots\n";
  for (const ComponentReport& c : result.components) {
    if (c.rest_solution)
      os << "  component of " << PartCount(c.parts.size())
         << " decided by a solution at rest: " << c.message << '\n';
    else if (!c.message.empty())
      os << "  component of " << PartCount(c.parts.size()) << ", decided by "
         << to_string(c.decided_by) << ": " << c.message << '\n';
    if (c.decided_by == DecidedBy::kMechanism) {
      os << "  component of " << PartCount(c.parts.size())
         << ": no static equilibrium exists; a mechanism (a motion no contact resists and "
            "gravity drives) moves";
      for (int i : c.mechanism_parts) os << ' ' << assembly.part(i).name;
      if (!c.held.empty()) os << ", the others held to find how";
      os << '\n';
    }
  }
  if (result.weakly_stable)
    os << "  WEAKLY STABLE: a static equilibrium exists, but only with forces nothing produces\n"
          "  from rest (a squeeze between faces: jamming); the contact dynamics move\n";
  else if (result.static_equilibrium)
    os << "  static equilibrium: " << (*result.static_equilibrium ? "exists" : "none") << '\n';
  TextWhy(assembly, result, os);
  TextStability(result, os);
}

// What moves, and how (in a summary, the first kSummaryRows).
void TextMotions(const Assembly& assembly, const StabilityResult& result,
                 const ReportOptions& options, std::ostringstream& os) {
  const bool st = result.formulation == Formulation::kStewartTrinkle;
  const int dim = assembly.dimension();
  const bool all = options.contacts == ContactListing::kAll;
  size_t shown = 0, moving = 0;
  for (const PartMotion& m : result.parts) {
    if (!m.moving) continue;
    if (++moving > kSummaryRows && !all) continue;
    ++shown;
    const Part& p = assembly.part(m.part);
    const char* what = st ? "velocity" : "acceleration";
    os << "  " << p.name << ' ' << DescribeMotion(m, dim, assembly.gravity());
    os << ": centroid " << what << ' ' << FormatPoint(m.linear, dim) << ", angular "
       << (dim == 2 ? Fmt("%.4g", m.angular.z()) : FormatPoint(m.angular, dim)) << '\n';
  }
  if (moving > shown)
    os << "  … and " << moving - shown
       << " more moving parts (every one: --contacts all, --json)\n";
}

// One contact's line: "b pushes a" (the force on a from b acts along n).
void TextContact(const Assembly& assembly, const ContactReport& cr, double force_scale,
                 std::ostringstream& os) {
  const Contact& c = cr.contact;
  const int dim = assembly.dimension();
  os << "    " << TextPartName(assembly, c.part_b) << " pushes " << TextPartName(assembly, c.part_a)
     << " at " << FormatPoint(c.p_WC, dim) << " n=" << FormatPoint(c.n_W, dim) << "  normal "
     << Fmt("%.6g", cr.normal_force / force_scale);
  if (c.mu > 0 && dim == 2)
    os << "  friction " << Fmt("%.6g", cr.friction_force.dot(c.t_W()) / force_scale);
  else if (c.mu > 0)
    os << "  friction " << FormatPoint(cr.friction_force / force_scale, dim);
  if (cr.breaking) os << "  BREAKS";
  if (cr.sliding) os << "  SLIDES";
  os << '\n';
}

// The summary of the forces: the most loaded contacts, and per pair of parts
// the resultant of its contacts' forces (the sum of what the report holds).
void TextForceSummary(const Assembly& assembly, const StabilityResult& result, double force_scale,
                      const std::string& force_unit, std::ostringstream& os) {
  const int dim = assembly.dimension();
  const double roundoff = ForceRoundoffScale(assembly, force_scale);
  std::vector<size_t> order(result.contacts.size());
  size_t loaded = 0, breaking = 0, sliding = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    order[k] = k;
    const ContactReport& cr = result.contacts[k];
    if (Clean(cr.normal_force / force_scale, roundoff) > 0) ++loaded;
    breaking += cr.breaking ? 1 : 0;
    sliding += cr.sliding ? 1 : 0;
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) {
    return result.contacts[x].normal_force > result.contacts[y].normal_force;
  });
  os << "  contact forces (" << force_unit << "): " << loaded << " of " << result.contacts.size()
     << " contacts carry a normal force";
  if (breaking > 0) os << ", " << breaking << " break";
  if (sliding > 0) os << ", " << sliding << " slide";
  if (loaded == 0) {
    os << '\n';
  } else {
    const size_t shown = std::min(loaded, kSummaryRows);
    os << "; the " << (shown == 1 ? "most loaded" : std::to_string(shown) + " most loaded")
       << " (every contact: --contacts all):\n";
    for (size_t k = 0; k < shown; ++k)
      TextContact(assembly, result.contacts[order[k]], force_scale, os);
  }
  // Per pair: the pushed part and the part that pushes it, the sum of the
  // forces on the first.
  struct Pair {
    int pushed, pusher;
    int contacts = 0;
    Vector3 force = Vector3::Zero();
  };
  std::vector<Pair> pairs;
  // The one pushed: a movable part before a fixed one, the world never.
  const int n = assembly.num_parts();
  const auto rank = [&](int part) {
    return part < 0 ? std::numeric_limits<int>::max() : assembly.part(part).fixed ? n + part : part;
  };
  for (const ContactReport& cr : result.contacts) {
    const Contact& c = cr.contact;
    const bool a_first = rank(c.part_a) < rank(c.part_b);
    const int pushed = a_first ? c.part_a : c.part_b, pusher = a_first ? c.part_b : c.part_a;
    const Vector3 on_a = c.n_W * cr.normal_force + cr.friction_force;
    auto it = std::find_if(pairs.begin(), pairs.end(),
                           [&](const Pair& p) { return p.pushed == pushed && p.pusher == pusher; });
    if (it == pairs.end()) it = pairs.insert(pairs.end(), Pair{pushed, pusher});
    ++it->contacts;
    it->force += a_first ? on_a : Vector3(-on_a);
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& x, const Pair& y) { return x.force.norm() > y.force.norm(); });
  size_t nonzero = 0;
  for (const Pair& p : pairs) nonzero += Clean(p.force.norm() / force_scale, roundoff) > 0 ? 1 : 0;
  if (nonzero == 0) return;
  const size_t shown = std::min(nonzero, kSummaryRows);
  os << "  per pair of parts, the resultant of its contact forces (" << force_unit
     << "): " << (shown < nonzero ? "the " + std::to_string(shown) + " largest of " : std::string())
     << nonzero << " pair" << (nonzero == 1 ? "" : "s") << " with a force:\n";
  for (size_t k = 0; k < shown; ++k) {
    const Pair& p = pairs[k];
    os << "    " << TextPartName(assembly, p.pusher) << " pushes "
       << TextPartName(assembly, p.pushed) << " (" << p.contacts << " contact"
       << (p.contacts == 1 ? "" : "s") << "): " << FormatPoint(p.force / force_scale, dim)
       << ", magnitude " << Fmt("%.6g", p.force.norm() / force_scale) << '\n';
  }
}

// Every contact force, or a summary of them, or none.
void TextForces(const Assembly& assembly, const StabilityResult& result,
                const ReportOptions& options, std::ostringstream& os) {
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  switch (options.contacts) {
    case ContactListing::kNone:
      return;
    case ContactListing::kSummary:
      TextForceSummary(assembly, result, force_scale, force_unit, os);
      return;
    case ContactListing::kAll:
      os << "  contact forces (" << force_unit << "):\n";
      for (const ContactReport& cr : result.contacts) TextContact(assembly, cr, force_scale, os);
      return;
  }
}

}  // namespace

std::string StabilityToText(const Assembly& assembly, const Configuration& config,
                            const StabilityResult& result, const ReportOptions& options) {
  std::ostringstream os;
  TextHeadline(assembly, config, result, options, os);
  TextSummary(assembly, result, os);
  TextMotions(assembly, result, options, os);
  TextForces(assembly, result, options, os);
  return os.str();
}

}  // namespace cairn

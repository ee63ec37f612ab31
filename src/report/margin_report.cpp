#include "cairn/report/margin_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cairn/report/words.h"
#include "report/report_common.h"

namespace cairn {

namespace {

using nlohmann::json;
using report_internal::Angular;
using report_internal::Clean;
using report_internal::Names;
using report_internal::Num;
using report_internal::Tangential;
using report_internal::Vec;

json Optional(const std::optional<double>& x) { return x ? json(*x) : json(nullptr); }

// The equilibrium at the critical value: each contact's forces.
json EquilibriumToJson(const Assembly& assembly, const MarginEquilibrium& e) {
  const int dim = assembly.dimension();
  const double forces = report_internal::ForceRoundoffScale(assembly, 1.0);
  json contacts = json::array();
  for (size_t c = 0; c < e.contacts.size(); ++c) {
    const Contact& k = e.contacts[c];
    contacts.push_back(
        {{"a", report_internal::PartName(assembly, k.part_a, "world")},
         {"b", report_internal::PartName(assembly, k.part_b, "world")},
         {"point", Vec(k.p_WC, dim)},
         {"normal", Vec(k.n_W, dim)},
         {"normal_force", Clean(e.normal_force[static_cast<Eigen::Index>(c)], forces)},
         {"friction_force", Tangential(e.friction_force[c], k, dim, forces)}});
  }
  return {{"at", e.at}, {"residual", e.residual}, {"contacts", contacts}};
}

// The mechanism just past it: the parts that move and how (a direction).
json MechanismToJson(const Assembly& assembly, const MarginMechanism& m) {
  const int dim = assembly.dimension();
  json parts = json::array();
  for (size_t i = 0; i < m.parts.size(); ++i) {
    const Vector3 v = m.nu[i].head<3>(), w = m.nu[i].tail<3>();
    parts.push_back({{"part", assembly.part(m.parts[i]).name},
                     {"linear", Vec(v, dim, 1e-6)},
                     {"angular", Angular(w, dim, 1e-6)},
                     {"motion", to_string(m.kinds[i])}});
  }
  json out = {{"at", m.at}, {"found", m.found}, {"power", m.power}, {"parts", parts}};
  if (!m.found) out["message"] = m.message;
  return out;
}

json SideToJson(const Assembly& assembly, const MarginResult& r, const MarginSide& s,
                const char* sense) {
  json out = {{"sense", sense}, {"critical", Optional(s.critical)}};
  out["component"] = s.component >= 0 ? json(s.component) : json(nullptr);
  out["parts"] =
      s.component >= 0 ? Names(assembly, r.components[s.component].parts) : json::array();
  out["equilibrium"] = s.equilibrium ? EquilibriumToJson(assembly, *s.equilibrium) : json(nullptr);
  out["mechanism"] = s.mechanism ? MechanismToJson(assembly, *s.mechanism) : json(nullptr);
  return out;
}

// How strong stability is handled: the frictionless-equilibrium certificate.
json StrongToJson(const MarginResult& r) {
  json out = {{"certificate", "frictionless equilibrium (sufficient, not necessary)"}};
  switch (r.quantity) {
    case MarginQuantity::kFriction:
      out["every_mu"] = r.strong_all ? json(*r.strong_all) : json(nullptr);
      break;
    case MarginQuantity::kTilt: {
      json deg = json::array();
      for (const MarginSide& s : r.sides) deg.push_back(s.strong ? Optional(*s.strong) : json(0.0));
      out["certified_deg"] = deg;
      out["computed"] = r.method.find("exact") != std::string::npos;
      break;
    }
    case MarginQuantity::kLoad:
      out["certified_up_to"] =
          !r.sides.empty() && r.sides[0].strong ? Optional(*r.sides[0].strong) : json(0.0);
      break;
  }
  return out;
}

}  // namespace

json MarginToJson(const Assembly& assembly, const MarginRequest& req, const MarginResult& r,
                  const ReportOptions& options) {
  const int dim = assembly.dimension();
  json doc;
  doc["scene"] = assembly.name();
  if (!options.scene_file.empty()) doc["scene_file"] = options.scene_file;
  doc["dimension"] = dim;
  doc["without"] = Names(assembly, options.without);
  json m;
  m["quantity"] = to_string(r.quantity);
  m["solved"] = r.solved;
  if (!r.solved) m["message"] = r.message;
  m["holds_at_nominal"] = r.holds_at_nominal;
  m["stands_at_nominal"] = r.stands_at_nominal;
  m["rule"] = to_string(req.rule);
  switch (r.quantity) {
    case MarginQuantity::kFriction: {
      m["critical"] = r.sides.empty() ? json(nullptr) : Optional(r.sides[0].critical);
      m["of"] = r.factor ? "factor" : "mu";
      m["nominal"] = r.nominal;
      m["failing_at"] = Optional(r.failing_at);
      json failing = json::array();
      for (const PartMotion& p : r.failing_below)
        failing.push_back({{"part", assembly.part(p.part).name}, {"motion", to_string(p.kind)}});
      m["failing_below"] = failing;
      // The threshold of the verdict `cairn check` gives (loaded from rest
      // where rigid bodies leave it open); null: it stands at no μ allowed.
      if (r.verdict_computed) {
        m["verdict_critical"] = Optional(r.verdict_critical);
        m["verdict_tolerance"] = r.verdict_tolerance;
        m["verdict_checks"] = r.verdict_checks;
        m["verdict_searched_to"] = r.verdict_searched_to;
      }
      break;
    }
    case MarginQuantity::kTilt: {
      m["axis"] = Vec(r.axis, 3);
      json deg = json::array();
      for (const MarginSide& s : r.sides) deg.push_back(Optional(s.critical));
      m["critical_deg"] = deg;
      // The threshold of the check's verdict per sense: the largest angle
      // it stands at (null: every angle tried).
      if (r.verdict_computed) {
        json vdeg = json::array();
        for (const MarginSide& s : r.sides) vdeg.push_back(Optional(s.verdict_critical));
        m["verdict_critical_deg"] = vdeg;
      }
      break;
    }
    case MarginQuantity::kLoad: {
      // The largest load (null: any load along D is carried).
      const bool bounded = !r.sides.empty() && r.sides[0].critical.has_value();
      const double f = bounded ? *r.sides[0].critical : 0.0;
      m["part"] = assembly.part(req.part).name;
      m["point"] = Vec(req.point, dim);
      m["direction"] = Vec(req.direction.normalized(), dim);
      m["critical"] = bounded ? json(f) : json(nullptr);
      m["critical_weights"] =
          bounded && r.part_weight > 0 ? json(f / r.part_weight) : json(nullptr);
      m["part_weight"] = r.part_weight;
      // The threshold of the check's verdict: the largest load it stands
      // under (null: every load up to verdict_searched_to).
      if (r.verdict_computed) m["verdict_critical"] = Optional(r.sides[0].verdict_critical);
      break;
    }
  }
  if (r.verdict_computed && r.quantity != MarginQuantity::kFriction) {
    m["verdict_tolerance"] = r.verdict_tolerance;
    m["verdict_checks"] = r.verdict_checks;
    m["verdict_searched_to"] = r.verdict_searched_to;
  }
  m["method"] = r.method;
  m["tolerance"] = r.tolerance;
  m["lps"] = r.lps;
  m["stability"] = "weak";
  m["strong"] = StrongToJson(r);
  json sides = json::array();
  const char* senses[2] = {"negative", "positive"};
  for (size_t i = 0; i < r.sides.size(); ++i)
    sides.push_back(SideToJson(assembly, r, r.sides[i],
                               r.quantity == MarginQuantity::kTilt ? senses[i] : "critical"));
  m["certificates"] = sides;
  json comps = json::array();
  for (const ComponentMargin& c : r.components) {
    json crit = json::array();
    for (const std::optional<double>& x : c.critical) crit.push_back(Optional(x));
    comps.push_back(
        {{"parts", Names(assembly, c.parts)},
         {"holds_at_nominal", c.holds_at_nominal},
         {"critical", r.quantity == MarginQuantity::kTilt || crit.empty() ? crit : crit[0]},
         {"lps", c.lps}});
  }
  m["components"] = comps;
  doc["margin"] = m;
  return doc;
}

namespace {

// A tilt's critical angle in one sense ("negative", "positive").
std::string Deg(const std::optional<double>& x, const char* sense) {
  return x ? Num(*x) + "° (" + sense + " sense)"
           : std::string("none in the ") + sense + " sense (it holds all the way round)";
}

// A long list of parts is cut after this many names in the text (the JSON
// document lists every one).
constexpr size_t kListedParts = 12;

// "N parts: A, B, ... and K more": `names` cut after kListedParts.
std::string PartList(const std::vector<std::string>& names) {
  std::string out = std::to_string(names.size()) + (names.size() == 1 ? " part: " : " parts: ");
  const size_t shown = std::min(names.size(), kListedParts);
  for (size_t i = 0; i < shown; ++i) out += (i == 0 ? "" : ", ") + names[i];
  if (names.size() > shown)
    out += ", … and " + std::to_string(names.size() - shown) + " more (every one: --json)";
  return out;
}

// The mechanism of a side as a line: which side, where it was found (just
// past the critical value) and what it moves.
std::string MechanismLine(const Assembly& assembly, const MarginRequest& req, const MarginResult& r,
                          size_t side) {
  const MarginMechanism& m = *r.sides[side].mechanism;
  std::vector<std::string> names;
  for (int p : m.parts) names.push_back(assembly.part(p).name);
  std::string where;
  switch (r.quantity) {
    case MarginQuantity::kFriction:
      where = std::string("below it: the mechanism at ") + (r.factor ? "k = " : "mu = ") +
              Num(m.at) + " (a motion gravity drives and no contact resists)";
      break;
    case MarginQuantity::kTilt:
      where = std::string(side == 0 ? "negative" : "positive") + " sense: the mechanism at " +
              Num(m.at) + "° (a motion gravity drives and no contact resists)";
      break;
    case MarginQuantity::kLoad:
      where = "past it: the mechanism at a load of " + Num(m.at) + " on " +
              assembly.part(req.part).name +
              " (a motion the load and gravity drive and no contact resists)";
      break;
  }
  return "  " + where + " moves " + PartList(names) + '\n';
}

}  // namespace

std::string MarginToText(const Assembly& assembly, const MarginRequest& req, const MarginResult& r,
                         const ReportOptions& options) {
  std::ostringstream os;
  os << (assembly.name().empty() ? options.scene_file : assembly.name()) << ": ";
  if (!r.solved) {
    os << "margin UNDECIDED (" << r.message << ")\n";
    return os.str();
  }
  const MarginSide* side = r.sides.empty() ? nullptr : &r.sides[0];
  switch (r.quantity) {
    case MarginQuantity::kFriction:
      os << "critical friction " << (r.factor ? "factor k* = " : "mu* = ")
         << (side && side->critical ? Num(*side->critical) : std::string("none (no friction)"))
         << "  (nominal " << Num(r.nominal) << ")\n";
      if (!r.failing_below.empty()) {
        std::vector<std::string> names;
        for (const PartMotion& p : r.failing_below)
          names.push_back(assembly.part(p.part).name + ' ' + to_string(p.kind));
        os << "  below it: the check at " << (r.factor ? "k = " : "mu = ") << Num(*r.failing_at)
           << " (the contact dynamics from rest) moves " << PartList(names) << '\n';
      }
      if (r.verdict_computed)
        os << "  the check stands (loaded from rest where rigid bodies leave it open) "
           << (r.verdict_critical
                   ? "from " + std::string(r.factor ? "k = " : "mu = ") + Num(*r.verdict_critical) +
                         " (within " + Num(r.verdict_tolerance) + ")"
                   : "at no " + std::string(r.factor ? "k" : "mu") + " up to " +
                         Num(r.verdict_searched_to))
           << '\n';
      break;
    case MarginQuantity::kTilt:
      os << "critical tilt about [" << Num(r.axis.x()) << ", " << Num(r.axis.y()) << ", "
         << Num(r.axis.z()) << "]: " << Deg(r.sides[0].critical, "negative") << " / "
         << Deg(r.sides[1].critical, "positive") << '\n';
      if (r.verdict_computed && !r.stands_at_nominal)
        os << "  the check (--rule " << to_string(req.rule) << ") falls even untilted\n";
      else if (r.verdict_computed)
        os << "  the check stands (--rule " << to_string(req.rule) << ") up to "
           << Deg(r.sides[0].verdict_critical, "negative") << " / "
           << Deg(r.sides[1].verdict_critical, "positive") << " (within "
           << Num(r.verdict_tolerance) << "°)\n";
      break;
    case MarginQuantity::kLoad:
      os << "largest load on " << assembly.part(req.part).name << ": ";
      if (!side || !side->critical)
        os << "any (the load alone is carried)";
      else if (r.part_weight > 0)
        os << Num(*side->critical) << " force units (" << Num(*side->critical / r.part_weight)
           << " of its weight)";
      else
        os << Num(*side->critical) << " force units (" << assembly.part(req.part).name
           << " has no weight: "
           << (assembly.gravity().norm() > 0 ? "its mass is zero" : "gravity is zero") << ")";
      os << '\n';
      if (r.verdict_computed && side) {
        os << "  the check (--rule " << to_string(req.rule) << ") ";
        if (!r.stands_at_nominal)
          os << "falls even without the load";
        else if (side->verdict_critical)
          os << "stands under up to " << Num(*side->verdict_critical) << " (within "
             << Num(r.verdict_tolerance) << ")";
        else if (r.verdict_searched_to > 0)
          os << "stands under every load up to " << Num(r.verdict_searched_to);
        else
          os << "stands under any load";
        os << '\n';
      }
      break;
  }
  if (!r.holds_at_nominal)
    os << "  the assembly does not stand as given\n";
  else if (!r.stands_at_nominal)
    os << "  the assembly does not stand as given: an equilibrium exists, but `cairn check` "
          "(--rule "
       << to_string(req.rule) << ") says it falls\n";
  for (size_t i = 0; i < r.sides.size(); ++i) {
    const MarginSide& s = r.sides[i];
    if (s.component < 0 || !s.mechanism || !s.mechanism->found) continue;
    os << MechanismLine(assembly, req, r, i);
  }
  os << "  method: " << r.method << "; " << r.lps << (r.lps == 1 ? " LP" : " LPs") << "; tolerance "
     << Num(r.tolerance) << "; weak stability (rest possible)\n";
  return os.str();
}

// ---- simulate --margin friction ----

json PlanMarginToJson(const Assembly& assembly, const PlanMargin& pm) {
  json m;
  m["quantity"] = "friction";
  m["critical"] = Optional(pm.critical);
  m["of"] = pm.factor ? "factor" : "mu";
  m["nominal"] = pm.nominal;
  m["failing_at"] = Optional(pm.failing_at);
  if (pm.failure) {
    const MotionFailure& f = *pm.failure;
    m["deciding"] = {{"step", f.step},
                     {"tick", f.tick},
                     {"time", Clean(f.time)},
                     {"verdict", to_string(f.verdict)},
                     {"parts", Names(assembly, f.parts)},
                     {"description", DescribeFailure(assembly, f)}};
  } else {
    m["deciding"] = nullptr;
  }
  m["method"] = "bisection over simulations of the whole plan";
  m["tolerance"] = pm.tolerance;
  m["simulations"] = pm.simulations;
  return m;
}

std::string PlanMarginToText(const Assembly& assembly, const PlanMargin& pm) {
  std::ostringstream os;
  os << "  friction margin: " << (pm.factor ? "k* = " : "mu* = ")
     << (pm.critical ? Num(*pm.critical) : std::string("none (no friction makes it stable)"))
     << " (nominal " << Num(pm.nominal) << "; " << pm.simulations << " simulations)\n";
  if (pm.failure)
    os << "    below it (at " << Num(*pm.failing_at) << "), step " << pm.failure->step + 1
       << " tick " << pm.failure->tick << ": " << DescribeFailure(assembly, *pm.failure) << '\n';
  return os.str();
}

}  // namespace cairn

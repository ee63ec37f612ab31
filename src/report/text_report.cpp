#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cairn/report/report.h"
#include "report/report_common.h"

namespace cairn {

namespace {
std::string Fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, std::abs(x) < 5e-13 ? 0.0 : x);
  return buf;
}
std::string PartName(const Assembly& a, int i) {
  return report_internal::PartName(a, i, "fixture");
}
}  // namespace

std::string StabilityToText(const Assembly& assembly, const Configuration& config,
                            const StabilityResult& result, const ReportOptions& options) {
  const bool st = result.formulation == Formulation::kStewartTrinkle;
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  const int dim = assembly.dimension();
  std::ostringstream os;

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
  int movable = 0, pivots = 0, lcp_vars = 0;
  for (const PartMotion& m : result.parts) (void)m, ++movable;
  for (const ComponentReport& c : result.components) pivots += c.pivots, lcp_vars += c.lcp_size;
  os << "  " << movable << " movable part" << (movable == 1 ? "" : "s") << ", "
     << result.contacts.size() << " contacts, " << result.components.size() << " component"
     << (result.components.size() == 1 ? "" : "s") << "; LCP " << lcp_vars << " variables, "
     << pivots << " pivots\n";
  for (const ComponentReport& c : result.components) {
    if (c.rest_solution)
      os << "  component of " << c.parts.size()
         << " parts decided by a solution at rest: " << c.message << '\n';
    if (c.decided_by == DecidedBy::kMechanism) {
      os << "  component of " << c.parts.size()
         << " parts: no static equilibrium exists; a mechanism (a motion no contact resists and "
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
  if (result.stability == StabilityProof::kStrong)
    os << "  strongly stable: a frictionless equilibrium exists, so every solution of the contact\n"
          "  problem is at rest\n";
  else if (result.stability == StabilityProof::kNotCertified)
    os << "  stability not certified as strong: rest is possible and no motion was found, but\n"
          "  motion from rest is not ruled out\n";

  // What moves, and how.
  for (const PartMotion& m : result.parts) {
    if (!m.moving) continue;
    const Part& p = assembly.part(m.part);
    const char* what = st ? "velocity" : "acceleration";
    os << "  " << p.name << ' ' << DescribeMotion(m, dim);
    os << ": centroid " << what << ' ' << FormatPoint(m.linear, dim) << ", angular "
       << (dim == 2 ? Fmt("%.4g", m.angular.z()) : FormatPoint(m.angular, dim)) << '\n';
  }

  // Contact forces.
  os << "  contact forces (" << force_unit << "):\n";
  for (const ContactReport& cr : result.contacts) {
    const Contact& c = cr.contact;
    // The force on a from b acts along n: "b pushes a".
    os << "    " << PartName(assembly, c.part_b) << " pushes " << PartName(assembly, c.part_a)
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
  if (!result.diagnostics.empty()) os << "  diagnostics: " << result.diagnostics << '\n';
  (void)config;
  return os.str();
}

}  // namespace cairn

#include "cairn/report/simulation_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

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
std::string PartName(const Assembly& a, int i) { return report_internal::PartName(a, i, "world"); }
using report_internal::Names;
// The timeline CSV keeps 10 significant digits.
std::string Num(double x) { return report_internal::Num(x, 10); }
}  // namespace

nlohmann::json SimulationToJson(const Assembly& assembly, const Plan& plan,
                                const SimulationResult& result, const ReportOptions& options) {
  using nlohmann::json;
  const auto [force_scale, force_unit] = ForceScale(assembly, options);
  const double forces = ForceRoundoffScale(assembly, force_scale);
  const int dim = assembly.dimension();
  json doc;
  doc["verdict"] = to_string(result.verdict);
  // Every configuration checked from rest proved strongly stable (--require strong).
  doc["strong_at_rest"] = result.rest_strong;
  doc["stable"] = result.stable();
  doc["mode"] = to_string(plan.mode);
  doc["force_unit"] = force_unit;
  if (!result.failure) {
    doc["failure"] = nullptr;
  } else {
    const MotionFailure& f = *result.failure;
    json jf;
    jf["verdict"] = to_string(f.verdict);
    jf["step"] = f.step;
    jf["tick"] = f.tick;
    jf["released"] = f.released;  // assembling: when let go where they arrived
    jf["time"] = Clean(f.time);
    jf["parts"] = Names(assembly, f.parts);
    jf["pushed"] = Names(assembly, f.pushed);  // the free parts the moving ones push
    json motions = json::array();
    for (const PartMotion& m : f.motions) {
      json jm;
      jm["part"] = assembly.part(m.part).name;
      jm["motion"] = to_string(m.kind);
      jm["velocity"] = {{"linear", Vec(m.linear, dim)}, {"angular", Angular(m.angular, dim)}};
      if (m.pivot) jm["pivot"] = Vec(*m.pivot, dim);
      if (m.pivot && dim == 3) jm["axis"] = Vec(m.angular.normalized(), dim);
      motions.push_back(jm);
    }
    jf["motions"] = motions;
    json contacts = json::array();
    for (const ContactReport& c : f.contacts) {
      json jc = ContactRecord(assembly, c, force_scale, forces);
      jc["normal_velocity"] = Clean(c.normal_motion);
      jc["sliding_velocity"] = Tangential(c.tangent_motion, c.contact, dim);
      contacts.push_back(jc);
    }
    jf["contacts"] = contacts;
    jf["description"] = DescribeFailure(assembly, f);
    doc["failure"] = jf;
  }
  json steps = json::array();
  for (const MotionStepReport& r : result.steps) {
    const PlanStep& step = plan.steps[r.step];
    steps.push_back({{"index", r.step},
                     {"parts", Names(assembly, step.remove)},
                     {"grip", Names(assembly, step.grip)},
                     {"support", to_string(step.support)},
                     {"verdict", to_string(r.verdict)},
                     {"time_steps", r.ticks},
                     {"start_time", Clean(r.start_time)},
                     {"end_time", Clean(r.end_time)},
                     {"pivots", r.pivots},
                     {"warm_starts", r.warm_starts}});
  }
  doc["steps"] = steps;
  doc["diagnostics"] = result.diagnostics;
  return doc;
}

std::string SimulationToText(const Assembly& assembly, const Plan& plan,
                             const SimulationResult& result, const ReportOptions& options) {
  (void)options;
  std::ostringstream os;
  os << (assembly.name().empty() ? options.scene_file : assembly.name()) << ": "
     << (plan.mode == PlanMode::kAssemble ? "assembly" : "disassembly") << " plan ";
  switch (result.verdict) {
    case MotionVerdict::kStable:
      os << "STABLE";
      break;
    case MotionVerdict::kUnstable:
      os << "UNSTABLE";
      break;
    case MotionVerdict::kUnsupported:
      os << "UNSUPPORTED";
      break;
    case MotionVerdict::kInfeasible:
      os << "INFEASIBLE";
      break;
  }
  os << '\n';
  for (const MotionStepReport& r : result.steps) {
    const PlanStep& step = plan.steps[r.step];
    std::string names;
    for (int p : step.remove) names += (names.empty() ? "" : ", ") + assembly.part(p).name;
    os << "  step " << r.step + 1 << " (" << names << ", support " << to_string(step.support)
       << "): " << to_string(r.verdict) << "  [t = " << r.start_time << ".." << r.end_time << " s, "
       << r.ticks << " time steps, " << r.pivots << " pivots]\n";
    if (r.failure) os << "    " << DescribeFailure(assembly, *r.failure) << '\n';
  }
  if (!result.diagnostics.empty()) os << "  diagnostics: " << result.diagnostics << '\n';
  return os.str();
}

std::string TimelineToCsv(const Assembly& assembly, const SimulationResult& result,
                          const ReportOptions& options) {
  const double force_scale = ForceScale(assembly, options).first;
  std::ostringstream os;
  if (assembly.is_3d()) {
    // 3-D: points, normals and the tangential vectors have three components,
    // and each row names its contact polygon (patch).
    os << "time,step,tick,part_a,part_b,patch,x,y,z,normal_x,normal_y,normal_z,normal_force,"
          "friction_x,friction_y,friction_z,normal_velocity,sliding_x,sliding_y,sliding_z,"
          "breaks,slides\n";
    const auto xyz = [](const Vector3& v) {
      return Num(v.x()) + ',' + Num(v.y()) + ',' + Num(v.z());
    };
    for (const TimelineRow& row : result.timeline) {
      const ContactReport& c = row.contact;
      os << Num(row.time) << ',' << row.step << ',' << row.tick << ','
         << PartName(assembly, c.contact.part_a) << ',' << PartName(assembly, c.contact.part_b)
         << ',' << c.contact.patch << ',' << xyz(c.contact.p_WC) << ',' << xyz(c.contact.n_W) << ','
         << Num(c.normal_force / force_scale) << ',' << xyz(c.friction_force / force_scale) << ','
         << Num(c.normal_motion) << ',' << xyz(c.tangent_motion) << ',' << (c.breaking ? 1 : 0)
         << ',' << (c.sliding ? 1 : 0) << '\n';
    }
    return os.str();
  }
  os << "time,step,tick,part_a,part_b,x,y,normal_x,normal_y,normal_force,friction_force,"
        "normal_velocity,sliding_velocity,breaks,slides\n";
  for (const TimelineRow& row : result.timeline) {
    const ContactReport& c = row.contact;
    os << Num(row.time) << ',' << row.step << ',' << row.tick << ','
       << PartName(assembly, c.contact.part_a) << ',' << PartName(assembly, c.contact.part_b) << ','
       << Num(c.contact.p_WC.x()) << ',' << Num(c.contact.p_WC.y()) << ',' << Num(c.contact.n_W.x())
       << ',' << Num(c.contact.n_W.y()) << ',' << Num(c.normal_force / force_scale) << ','
       << Num(c.friction_force.dot(c.contact.t_W()) / force_scale) << ',' << Num(c.normal_motion)
       << ',' << Num(c.tangent_motion.dot(c.contact.t_W())) << ',' << (c.breaking ? 1 : 0) << ','
       << (c.sliding ? 1 : 0) << '\n';
  }
  return os.str();
}

}  // namespace cairn

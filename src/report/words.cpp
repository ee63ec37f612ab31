#include "cairn/report/words.h"

#include <algorithm>
#include <sstream>

#include "cairn/core/format.h"

namespace cairn {

std::string DescribeMotion(const PartMotion& m, int dimension, const Vector3& gravity) {
  std::string out = to_string(m.kind);
  if (m.kind == MotionKind::kSlides && gravity.norm() > 0 && m.linear.norm() > 0) {
    const double down = m.linear.normalized().dot(gravity.normalized());
    if (down >= kVerticalWord) out += " down";
    if (down <= -kVerticalWord) out += " up";
  }
  if (m.kind == MotionKind::kTips && m.pivot && dimension == 2)
    out += " about " + FormatPoint(*m.pivot, dimension) +
           (m.angular.z() > 0 ? " counter-clockwise" : " clockwise");
  else if (m.kind == MotionKind::kTips && m.pivot)
    out += " about the axis through " + FormatPoint(*m.pivot, dimension) + " along " +
           FormatPoint(m.angular.normalized(), dimension);
  else if (m.linear.norm() > 0)
    out += " along " + FormatPoint(m.linear.normalized(), dimension);
  return out;
}

namespace {

// What happens at the failure, by verdict.
void WriteWhat(const Assembly& a, const MotionFailure& f, std::ostringstream& os) {
  switch (f.verdict) {
    case MotionVerdict::kUnstable:
      if (!f.pushed.empty())
        os << a.NameList(f.pushers) << " pushes " << a.NameList(f.pushed) << ": ";
      for (size_t i = 0; i < f.motions.size(); ++i) {
        const PartMotion& m = f.motions[i];
        os << (i ? "; " : "") << a.part(m.part).name << ' '
           << DescribeMotion(m, a.dimension(), a.gravity());
      }
      break;
    case MotionVerdict::kUnsupported:
      os << a.NameList(f.parts)
         << " can no longer rest on the assembly: the gripper must carry it here";
      break;
    case MotionVerdict::kInfeasible:
      if (f.parts.size() >= 2)
        os << a.part(f.parts[0]).name << " runs into " << a.part(f.parts[1]).name;
      else
        os << "the motion of " << a.NameList(f.parts) << " is blocked";
      break;
    case MotionVerdict::kStable:
      os << "stable";
      break;
  }
}

}  // namespace

namespace {

// Why the parts of a component move, from what decided it.
std::string WhyItMoves(const ComponentReport& c) {
  if (c.static_equilibrium && !*c.static_equilibrium) return "because no equilibrium exists";
  if (c.loaded_from_rest && *c.loaded_from_rest == LoadedFromRest::Outcome::kGivesWay)
    return "because, loaded from rest, nothing produces the forces the equilibrium needs";
  if (c.static_equilibrium && *c.static_equilibrium)
    return "although an equilibrium exists: only forces nothing produces from rest hold it "
           "(jammed)";
  return "";
}

}  // namespace

std::vector<std::string> CheckStory(const Assembly& assembly, const StabilityResult& result) {
  std::vector<std::string> lines;
  for (const PartMotion& m : result.parts) {
    if (!m.moving) continue;
    std::string line = assembly.part(m.part).name + ' ' +
                       DescribeMotion(m, assembly.dimension(), assembly.gravity());
    for (const ComponentReport& c : result.components) {
      if (std::find(c.parts.begin(), c.parts.end(), m.part) == c.parts.end()) continue;
      const std::string why = WhyItMoves(c);
      if (!why.empty()) line += ", " + why;
    }
    lines.push_back(line);
  }
  return lines;
}

std::string DescribeFailure(const Assembly& a, const MotionFailure& f) {
  std::ostringstream os;
  os << "t = " << f.time << " s (step " << f.step + 1 << ", tick " << f.tick
     << (f.released ? ", let go in place" : "") << "): ";
  WriteWhat(a, f, os);
  for (const ContactReport& c : f.contacts) {
    if (!(c.breaking || c.sliding)) continue;
    os << "; contact " << a.part(c.contact.part_a).name << "-"
       << (c.contact.part_b >= 0 ? a.part(c.contact.part_b).name : std::string("fixture")) << " at "
       << FormatPoint(c.contact.p_WC, a.dimension()) << (c.breaking ? " breaks" : " slides");
  }
  if (!f.solver_note.empty()) os << "; the contact LCP could not be solved: " << f.solver_note;
  return os.str();
}

std::string PathTrialFailure(const Assembly& assembly, const PathTrial& trial) {
  if (trial.decided_by == "proposition 1")
    return "the rest does not stand without the removed parts";
  if (!trial.failure) return "";
  return std::string(trial.failure_mode == PlanMode::kDisassemble ? "disassembly: "
                                                                  : "assembly: ") +
         DescribeFailure(assembly, *trial.failure);
}

std::string FixtureMessage(const Assembly& assembly, const FixtureSuggestion& suggestion) {
  const size_t k = suggestion.fixels.size();
  if (suggestion.found && k == 0) return "the plan is stable without fixels";
  if (suggestion.found)
    return std::to_string(k) + (k == 1 ? " fixel makes" : " fixels make") + " the plan stable";
  std::string at;
  if (suggestion.stopped_at)
    at = "step " + std::to_string(suggestion.stopped_at->step + 1) + " (" +
         DescribeFailure(assembly, *suggestion.stopped_at) + ")";
  return "no fixels found: " + at + suggestion.stop_reason;
}

}  // namespace cairn

#include "cairn/motion/simulate.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <tuple>

#include "cairn/core/check.h"
#include "cairn/geometry/polygon.h"
#include "cairn/geometry/polyhedron.h"

namespace cairn {

const char* to_string(MotionVerdict v) {
  switch (v) {
    case MotionVerdict::kStable:
      return "stable";
    case MotionVerdict::kUnstable:
      return "unstable";
    case MotionVerdict::kUnsupported:
      return "unsupported";
    case MotionVerdict::kInfeasible:
      return "infeasible";
  }
  return "unknown";
}

namespace {

std::string Names(const Assembly& a, const std::vector<int>& parts) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? ", " : "") + a.part(parts[i]).name;
  return out;
}

// The unit direction from s towards larger s (forward) or smaller s
// (backward) along the step's path; zero at that end of the path.
Vector3 TravelDirection(const PlanStep& step, double s, bool forward) {
  const double L = step.Length();
  const double eps = 1e-9 * std::max(1.0, L);
  if (forward ? s >= L - eps : s <= eps) return Vector3::Zero();
  const double s2 = forward ? std::min(L, s + eps) : std::max(0.0, s - eps);
  const Vector3 d = step.At(s2) - step.At(s);
  return d.norm() > 0 ? Vector3(d.normalized()) : Vector3::Zero();
}

// The axis-aligned bounding box of a part in a configuration.
std::pair<Vector3, Vector3> WorldBox(const Assembly& a, const Configuration& config, int i) {
  const std::vector<Vector3> v = config.WorldVertices(a, i);
  std::pair<Vector3, Vector3> box{v[0], v[0]};
  for (const Vector3& p : v) box = {box.first.cwiseMin(p), box.second.cwiseMax(p)};
  return box;
}

// True when parts p and j of `config` overlap by more than `tol` (length).
bool Penetrates(const Assembly& a, const Configuration& config, int p, int j, double tol) {
  const auto box = WorldBox(a, config, p);
  const auto ob = WorldBox(a, config, j);
  if (((ob.first.array() > box.second.array() + tol) ||
       (box.first.array() > ob.second.array() + tol))
          .any())
    return false;
  if (a.is_3d())
    return FindPolyhedronOverlap(*a.part(p).polyhedron, config.WorldTransform(a, p),
                                 *a.part(j).polyhedron, config.WorldTransform(a, j), tol)
        .has_value();
  return FindOverlap(config.WorldPolygon(a, p), config.WorldPolygon(a, j), tol).has_value();
}

// A gripped part that overlaps another part beyond the tolerance.
struct Hit {
  int driven = -1;  // the gripped part
  int other = -1;   // the part it overlaps
};

// What the gripped parts run into at this tick: a part that cannot give way
// (`can_give_way` false: fixed, held) first, else a free part (a push), else
// nothing. Parts of the moving group are never hits.
std::optional<Hit> FindCollision(const Assembly& a, const Configuration& config,
                                 const std::vector<bool>& gripped,
                                 const std::vector<bool>& in_group,
                                 const std::vector<bool>& can_give_way, double tol) {
  std::optional<Hit> push;
  for (int p = 0; p < a.num_parts(); ++p) {
    if (!gripped[p]) continue;
    for (int j = 0; j < a.num_parts(); ++j) {
      if (j == p || !config.present[j] || in_group[j]) continue;
      if (!Penetrates(a, config, p, j, tol)) continue;
      if (!can_give_way[j]) return Hit{p, j};
      if (!push) push = Hit{p, j};
    }
  }
  return push;
}

// The distance along the step's path at which the gripped part `hit.driven`,
// clear of `hit.other` at u_clear and overlapping it at u_hit, first overlaps
// it beyond `tol`: bisection on the distance travelled, to 1e-9 of the path
// length (the other part stands still meanwhile: it is judged, not moved).
double FirstOverlap(const Assembly& a, Configuration config, const PlanStep& step, bool assemble,
                    const Hit& hit, double u_clear, double u_hit, double tol) {
  const double L = step.Length();
  const double eps = 1e-9 * std::max(1.0, L);
  while (u_hit - u_clear > eps) {
    const double mid = 0.5 * (u_clear + u_hit);
    config.poses[hit.driven] = Pose::Translation(step.At(assemble ? L - mid : mid));
    (Penetrates(a, config, hit.driven, hit.other, tol) ? u_hit : u_clear) = mid;
  }
  return u_hit;
}

// The judged parts that the gripper's motion pushes in the solve `r` of
// `config`. A moving judged part j is pushed by a part g through a contact
// that stays closed and carries force (not breaking, normal force above
// `force_tol`) while g's contact point moves into j:
//   v_g(p_WC) · n_j > vel_tol,
// n_j the contact normal pointing into j (n_W when j is part a, −n_W when it
// is b). The pushers are the gripped parts, moving with the gripper's
// velocity `v_drive` (only the driven motion: a guided part's own sinking
// under its weight is not a push), and then, transitively, the carried parts
// and the pushed ones, with their velocity in `r`,
//   v_g(p) = v_g + ω_g × (p − c_g).
// A judged part that moves for another reason (a support or a counterweight
// leaves, a guided part's weight tips it, it leans on a part sliding past
// it) is not pushed.
std::vector<int> PushedParts(const Assembly& assembly, const Configuration& config,
                             const StabilityResult& r, const std::vector<bool>& gripped,
                             const std::vector<bool>& carried, const Vector3& v_drive,
                             double force_tol, double vel_tol) {
  const int n = assembly.num_parts();
  std::vector<bool> moving(n, false), reached(gripped);
  std::vector<const PartMotion*> motion(n, nullptr);
  for (int p : r.moving) moving[p] = true;
  for (const PartMotion& m : r.parts) motion[m.part] = &m;
  // The velocity of part g's material point at p (world frame).
  const auto point_velocity = [&](int g, const Vector3& p) -> Vector3 {
    if (gripped[g]) return v_drive;
    if (motion[g] == nullptr) return Vector3::Zero();
    return motion[g]->linear + motion[g]->angular.cross(p - config.WorldCentroid(assembly, g));
  };
  std::vector<int> pushed;
  for (bool grew = true; grew;) {
    grew = false;
    for (const ContactReport& c : r.contacts) {
      const int a = c.contact.part_a, b = c.contact.part_b;
      if (b < 0 || c.breaking || !(c.normal_force > force_tol)) continue;
      for (const auto& [g, j, n_j] :
           {std::tuple{b, a, Vector3(c.contact.n_W)}, std::tuple{a, b, Vector3(-c.contact.n_W)}}) {
        if (!reached[g] || reached[j] || !(moving[j] || carried[j])) continue;
        if (point_velocity(g, c.contact.p_WC).dot(n_j) <= vel_tol) continue;
        reached[j] = true;
        if (moving[j]) pushed.push_back(j);
        grew = true;
      }
    }
  }
  std::sort(pushed.begin(), pushed.end());
  return pushed;
}

// Describes a failure for people.
std::string Describe(const Assembly& a, const MotionFailure& f, const PlanStep& step) {
  const int dim = a.dimension();
  std::ostringstream os;
  os << "t = " << f.time << " s (step " << f.step << ", tick " << f.tick << "): ";
  switch (f.verdict) {
    case MotionVerdict::kUnstable:
      if (!f.pushed.empty())
        os << Names(a, step.remove) << " pushes " << Names(a, f.pushed) << ": ";
      for (size_t i = 0; i < f.motions.size(); ++i) {
        const PartMotion& m = f.motions[i];
        os << (i ? "; " : "") << a.part(m.part).name << ' ' << DescribeMotion(m, dim);
      }
      break;
    case MotionVerdict::kUnsupported:
      os << Names(a, f.parts)
         << " can no longer rest on the assembly: the gripper must carry it here";
      break;
    case MotionVerdict::kInfeasible:
      if (f.parts.size() >= 2)
        os << a.part(f.parts[0]).name << " runs into " << a.part(f.parts[1]).name;
      else
        os << "the motion of " << Names(a, f.parts) << " is blocked";
      break;
    case MotionVerdict::kStable:
      os << "stable";
      break;
  }
  for (const ContactReport& c : f.contacts) {
    if (!(c.breaking || c.sliding)) continue;
    os << "; contact " << a.part(c.contact.part_a).name << "-"
       << (c.contact.part_b >= 0 ? a.part(c.contact.part_b).name : std::string("fixture")) << " at "
       << FormatPoint(c.contact.p_WC, dim) << (c.breaking ? " breaks" : " slides");
  }
  return os.str();
}

}  // namespace

SimulationResult SimulatePlan(const Assembly& assembly, const Plan& plan,
                              const SimulationOptions& options) {
  CAIRN_THROW_UNLESS(!assembly.has_interfaces(),
                     "SimulatePlan: the assembly's contacts are given interfaces of its assembled "
                     "configuration; its parts cannot move");
  SimulationResult result;
  const int n = assembly.num_parts();
  const bool assemble = plan.mode == PlanMode::kAssemble;

  // Steps in the order they happen; an assembly plan runs backwards.
  std::vector<int> order(plan.steps.size());
  std::iota(order.begin(), order.end(), 0);
  if (assemble) std::reverse(order.begin(), order.end());

  // The starting configuration: assembled (tools absent); when assembling,
  // the parts of every step are still outside.
  Configuration config = Configuration::Assembled(assembly);
  if (assemble)
    for (const PlanStep& step : plan.steps)
      for (int p : step.remove) config.present[p] = false;
  for (int p : options.absent) {
    CAIRN_THROW_UNLESS(p >= 0 && p < n,
                       "SimulatePlan: absent part " + std::to_string(p) + " out of range");
    config.present[p] = false;
  }

  std::vector<Vector6> nu(n, Vector6::Zero());  // each part's velocity after the last tick
  std::vector<bool> held(n, false);             // held in place after a failure (continue mode)
  StabilityWorkspace workspace;
  double time = 0;
  const double tick_length = plan.speed * plan.dt;

  for (const int k : order) {
    const PlanStep& step = plan.steps[k];
    MotionStepReport report;
    report.step = k;
    report.start_time = time;

    // Roles of the parts moving in this step.
    std::vector<bool> gripped(n, false), carried(n, false), in_group(n, false);
    for (int p : step.grip) gripped[p] = in_group[p] = true;
    for (int p : step.remove)
      if (!gripped[p]) carried[p] = in_group[p] = true;
    SupportMode support = step.support;

    // They enter (tools always; parts when assembling) at the start of the path.
    const double L = step.Length();
    const double s_start = assemble ? L : 0.0;
    for (int p = 0; p < n; ++p) {
      if (!in_group[p]) continue;
      config.present[p] = true;
      config.poses[p] = Pose::Translation(step.At(s_start));
      nu[p].setZero();
    }

    const int moves = std::max(1, static_cast<int>(std::ceil(L / tick_length - 1e-9)));
    bool step_failed = false;
    for (int tick = 0; tick <= moves; ++tick) {
      // Where the gripper is and where it goes during this tick.
      const double travelled = std::min(tick * tick_length, L);
      const double next = std::min((tick + 1) * tick_length, L);
      const double s = assemble ? L - travelled : travelled;
      const double dt = tick < moves ? (next - travelled) / plan.speed : plan.dt;
      // Time stepping: the contact LCP at a tick gives the motion over the
      // coming interval, with the gripper's velocity for that interval (zero
      // at the last tick: the gripper has stopped, and a part set into its
      // seat does not keep pushing); the carried parts are moved with it.
      const Vector3 v_g = tick < moves ? Vector3(plan.speed * TravelDirection(step, s, !assemble))
                                       : Vector3::Zero();
      // The path direction the gripper holds a guided part along: the coming
      // one, or at the end of the path the one it came along.
      const Vector3 guide =
          v_g.norm() > 0 ? Vector3(v_g.normalized()) : Vector3(-TravelDirection(step, s, assemble));
      const double t_now = time + travelled / plan.speed;
      for (int p = 0; p < n; ++p)
        if (gripped[p]) config.poses[p] = Pose::Translation(step.At(s));

      // The drive: who moves how. `at_rest` describes the node before the
      // step: the gripper has not moved yet, so its parts still rest on the
      // assembly with their weight (the paper's figures show their contact
      // forces until they are lifted).
      const auto make_drive = [&](bool at_rest) {
        DriveInputs d;
        d.role.assign(n, PartRole::kJudged);
        d.velocity.assign(n, Vector3::Zero());
        d.guide.assign(n, guide);
        d.nu_prev = nu;
        for (int p = 0; p < n; ++p) {
          if (gripped[p] && at_rest && !assembly.part(p).tool) {
            d.role[p] = PartRole::kCarried;
            d.nu_prev[p].setZero();
          } else if (gripped[p]) {
            const bool rigid = support == SupportMode::kFull || assembly.part(p).tool;
            d.role[p] = rigid ? PartRole::kPrescribed : PartRole::kGuided;
            d.velocity[p] = at_rest ? Vector3::Zero() : v_g;
          } else if (carried[p]) {
            d.role[p] = PartRole::kCarried;
          } else if (held[p]) {
            d.role[p] = PartRole::kPrescribed;  // held in place: velocity 0
          }
        }
        return d;
      };

      StabilityOptions so;
      so.dt = dt;
      so.lemke = options.lemke;
      const Tolerances tol = assembly.MakeTolerances(dt);
      so.tolerances = tol;
      // At tick 0 the verdict is first the node's, at rest (r); then the
      // gripper starts to move, and a second solve with the driven motion
      // (`moved`) tells which judged parts it pushes from the first instant
      // and how the carried parts move over the first interval.
      const DriveInputs drive = make_drive(tick == 0);
      if (options.on_analysis) options.on_analysis({k, tick, true, &config, &drive, &so});
      const StabilityResult r = AnalyzeConfiguration(assembly, config, so, &drive, &workspace);
      ++report.ticks;
      for (const ComponentReport& c : r.components) report.pivots += c.pivots;
      if (!r.diagnostics.empty())
        result.diagnostics +=
            "step " + std::to_string(k) + ", tick " + std::to_string(tick) + ": " + r.diagnostics;
      if (options.record_timeline)
        for (const ContactReport& c : r.contacts) result.timeline.push_back({t_now, k, tick, c});
      StabilityResult moved;
      const StabilityResult* motion = &r;
      if (tick == 0 && tick < moves) {
        const DriveInputs go = make_drive(false);
        if (options.on_analysis) options.on_analysis({k, tick, false, &config, &go, &so});
        moved = AnalyzeConfiguration(assembly, config, so, &go, &workspace);
        motion = &moved;
        if (!moved.diagnostics.empty())
          result.diagnostics +=
              "step " + std::to_string(k) + ", tick 0 (gripper moving): " + moved.diagnostics;
      }

      // Classify the tick: infeasible, unstable, unsupported, stable.
      // `judged` is the solve whose motions and contacts explain the failure.
      MotionFailure f;
      const StabilityResult* judged = &r;
      double failure_time = t_now;
      // Overlap: a gripped part inside a part that cannot give way (fixed, or
      // held after an earlier failure) is infeasible; inside a free part, it
      // has pushed that part since they touched (found by bisection between
      // the ticks): unstable from then, the part moving with the pusher.
      std::vector<bool> can_give_way(n);
      for (int p = 0; p < n; ++p)
        can_give_way[p] = !assembly.part(p).fixed && !assembly.part(p).tool && !held[p];
      if (const auto hit =
              FindCollision(assembly, config, gripped, in_group, can_give_way, tol.length)) {
        if (!can_give_way[hit->other]) {
          f.verdict = MotionVerdict::kInfeasible;
          f.parts = {hit->driven, hit->other};
        } else {
          const double u =
              tick > 0 ? FirstOverlap(assembly, config, step, assemble, *hit,
                                      std::min((tick - 1) * tick_length, L), travelled, tol.length)
                       : travelled;
          f.verdict = MotionVerdict::kUnstable;
          f.parts = f.pushed = {hit->other};
          failure_time = time + u / plan.speed;
          PartMotion m;
          m.part = hit->other;
          m.moving = true;
          m.kind = MotionKind::kSlides;
          m.linear = plan.speed * TravelDirection(step, assemble ? L - u : u, !assemble);
          f.motions = {m};
        }
      }
      if (f.verdict == MotionVerdict::kStable && !r.jammed.empty()) {
        f.verdict = MotionVerdict::kInfeasible;
        f.parts = r.jammed;
      }
      if (f.verdict == MotionVerdict::kStable && !r.moving.empty()) {
        f.verdict = MotionVerdict::kUnstable;
        f.parts = r.moving;
        if (tick > 0)  // the gripper moves: some may be pushed
          f.pushed =
              PushedParts(assembly, config, r, gripped, carried, v_g, tol.force, tol.velocity);
      }
      if (f.verdict == MotionVerdict::kStable && r.verdict == Verdict::kSolverFailure) {
        // Numerical trouble is never taken for stability.
        f.verdict = MotionVerdict::kUnstable;
        f.description = "the contact LCP could not be solved: " + r.diagnostics;
      }
      // Pushes at the first instant: judged parts that the driven motion
      // pushes (PushedParts) are unstable from t = the step's start. Judged
      // parts that start to move for another reason (a support or a
      // counterweight leaves) are judged at the next tick, as before; so are a
      // jam and a numerical failure of this solve, whose motions are then not
      // trusted (a ray termination of Lemke's method with friction is no
      // proof that no forces allow the motion: the next tick's solve confirms
      // a real jam, or the overlap check does).
      if (f.verdict == MotionVerdict::kStable && motion == &moved && moved.jammed.empty() &&
          moved.verdict != Verdict::kSolverFailure) {
        const std::vector<int> pushed =
            PushedParts(assembly, config, moved, gripped, carried, v_g, tol.force, tol.velocity);
        if (!pushed.empty()) {
          judged = &moved;
          f.verdict = MotionVerdict::kUnstable;
          f.parts = f.pushed = pushed;
        }
      }
      if (f.verdict == MotionVerdict::kStable && !r.unsupported.empty()) {
        if (options.carry_when_unsupported) {
          // The paper's Fig. 6 gripper: it takes the part's weight from here on.
          support = SupportMode::kFull;
        } else {
          f.verdict = MotionVerdict::kUnsupported;
          f.parts = r.unsupported;
        }
      }

      if (f.verdict != MotionVerdict::kStable && !step_failed) {
        f.step = k;
        f.tick = tick;
        f.time = failure_time;
        if (f.motions.empty())
          for (const PartMotion& m : judged->parts)
            if (std::find(f.parts.begin(), f.parts.end(), m.part) != f.parts.end())
              f.motions.push_back(m);
        // The contacts of the failing parts that break or slide.
        const auto involved = [&](int part) {
          return std::find(f.parts.begin(), f.parts.end(), part) != f.parts.end();
        };
        for (const ContactReport& c : judged->contacts)
          if ((c.breaking || c.sliding) &&
              (involved(c.contact.part_a) || involved(c.contact.part_b)))
            f.contacts.push_back(c);
        const std::string why = f.description;
        f.description = Describe(assembly, f, step) + (why.empty() ? "" : "; " + why);
        report.verdict = f.verdict;
        report.failure = f;
        if (!result.failure) result.failure = f;
        step_failed = true;
      }

      // Carry velocities to the next tick (a gripped part keeps only its own
      // off-path velocity: the gripper's may change direction at a corner);
      // move the carried parts.
      for (const PartMotion& m : motion->parts) {
        nu[m.part] << m.linear, m.angular;
        if (gripped[m.part]) nu[m.part].head<3>() -= v_g;
      }
      for (int p = 0; p < n; ++p) {
        if (!carried[p]) continue;
        config.poses[p].translation += nu[p].head<3>() * dt;
        config.poses[p].Rotate(nu[p].tail<3>() * dt);
      }
      if (f.verdict != MotionVerdict::kStable) {
        if (!options.continue_after_failure) break;
        // Continue as if the failure were prevented: hold the parts that
        // moved, let the gripper carry an unsupported part.
        if (f.verdict == MotionVerdict::kUnstable)
          for (int p : f.parts) held[p] = true, nu[p].setZero();
        if (f.verdict == MotionVerdict::kUnsupported) support = SupportMode::kFull;
      }
    }
    report.warm_starts = workspace.warm_starts;
    workspace.warm_starts = 0;
    time += L / plan.speed;
    report.end_time = time;
    result.steps.push_back(report);

    // The step is over: removed parts leave (or, assembling, stay placed);
    // tools always leave.
    for (int p = 0; p < n; ++p) {
      if (!in_group[p]) continue;
      config.present[p] = assemble && !assembly.part(p).tool;
      config.poses[p] = Pose{};
      nu[p].setZero();
    }
    if (step_failed && !options.continue_after_failure) break;
  }

  result.verdict = result.failure ? result.failure->verdict : MotionVerdict::kStable;
  return result;
}

}  // namespace cairn

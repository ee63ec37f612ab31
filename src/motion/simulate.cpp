#include "cairn/motion/simulate.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <tuple>

#include "cairn/core/check.h"
#include "cairn/core/tolerances.h"
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

// The unit direction from s towards larger s (forward) or smaller s
// (backward) along the step's path; zero at that end of the path.
Vector3 TravelDirection(const PlanStep& step, double s, bool forward) {
  const double L = step.Length();
  const double eps = numeric::kParameterSlack * std::max(1.0, L);
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
  const double eps = numeric::kParameterSlack * std::max(1.0, L);
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

// The parts of one step and what they do (roles fixed for the step).
struct StepState {
  int k = -1;  // index into Plan::steps
  const PlanStep* step = nullptr;
  std::vector<bool> gripped, carried, in_group;
  std::vector<bool> hold, hold_at_rest;  // held in place while the parts move; at rest
  // The scene with the step's props while its parts move, and at rest
  // (empty: no props, the scene as it is).
  std::optional<Assembly> with_props, with_props_at_rest;
  SupportMode support = SupportMode::kFull;  // may become kFull when the gripper carries
  double length = 0;                         // of the path
  int moves = 1;                             // ticks after the start
  MotionStepReport report;
  bool failed = false;
};

// Where the gripper is at a tick and where it goes during it.
struct TickMotion {
  int tick = 0;
  double travelled = 0;  // distance along the path so far
  double s = 0;          // the path parameter (L − travelled when assembling)
  double dt = 0;         // the interval to the next tick
  double t_now = 0;      // time of the tick
  Vector3 v_g;           // the gripper's velocity over the interval
  Vector3 guide;         // the direction the gripper holds a guided part along
  bool release = false;  // assembling: the step's parts, arrived, let go
};

// The solves of one tick: `r` at the tick; at tick 0 also `moved`, the
// solve with the gripper already moving, whose motions carry on.
struct TickAnalysis {
  StabilityResult r;
  StabilityResult moved;
  bool has_moved = false;
  const StabilityResult& motion() const { return has_moved ? moved : r; }
};

// A tick's verdict and the solve that explains it.
struct TickVerdict {
  MotionFailure failure;
  bool judged_by_moved = false;  // the motions and contacts of `moved`, not `r`
  double failure_time = 0;
};

// Algorithm 1 of the paper along a plan: the state carried from tick to
// tick and step to step, and one method per stage of a tick.
class PlanSimulation {
 public:
  PlanSimulation(const Assembly& assembly, const Plan& plan, const SimulationOptions& options)
      : a_(assembly),
        plan_(plan),
        options_(options),
        n_(assembly.num_parts()),
        assemble_(plan.mode == PlanMode::kAssemble),
        config_(StartingConfiguration()),
        nu_(n_, Vector6::Zero()),
        held_(n_, false),
        tick_length_(plan.speed * plan.dt) {}

  SimulationResult Run() {
    for (const int k : StepOrder()) {
      StepState st = EnterStep(k);
      bool going = true;
      for (int tick = 0; tick <= st.moves && going; ++tick) going = RunTick(st, tick);
      if (going && assemble_) RunTick(st, st.moves, /*release=*/true);
      LeaveStep(st);
      if (st.failed && !options_.continue_after_failure) break;
    }
    result_.verdict = result_.failure ? result_.failure->verdict : MotionVerdict::kStable;
    return std::move(result_);
  }

 private:
  // Steps in the order they happen; an assembly plan runs backwards.
  std::vector<int> StepOrder() const {
    std::vector<int> order(plan_.steps.size());
    std::iota(order.begin(), order.end(), 0);
    if (assemble_) std::reverse(order.begin(), order.end());
    return order;
  }

  // The starting configuration: assembled (tools absent); when assembling,
  // the parts of every step are still outside.
  Configuration StartingConfiguration() const {
    Configuration config = Configuration::Assembled(a_);
    if (assemble_)
      for (const PlanStep& step : plan_.steps)
        for (int p : step.remove) config.present[p] = false;
    for (int p : options_.absent) {
      CAIRN_THROW_UNLESS(p >= 0 && p < n_,
                         "SimulatePlan: absent part " + std::to_string(p) + " out of range");
      config.present[p] = false;
    }
    return config;
  }

  // Roles of the parts moving in step k; they enter (tools always; parts when
  // assembling) at the start of the path.
  StepState EnterStep(int k) {
    StepState st;
    st.k = k;
    st.step = &plan_.steps[k];
    st.report.step = k;
    st.report.start_time = time_;
    st.gripped.assign(n_, false);
    st.carried.assign(n_, false);
    st.in_group.assign(n_, false);
    for (int p : st.step->grip) st.gripped[p] = st.in_group[p] = true;
    for (int p : st.step->remove)
      if (!st.gripped[p]) st.carried[p] = st.in_group[p] = true;
    st.hold.assign(n_, false);
    st.hold_at_rest.assign(n_, false);
    for (int p : st.step->hold) st.hold[p] = true;
    for (int p : st.step->hold_at_rest) st.hold_at_rest[p] = true;
    if (!st.step->props.empty()) st.with_props = a_.WithFixtures(st.step->props);
    if (!st.step->props_at_rest.empty())
      st.with_props_at_rest = a_.WithFixtures(st.step->props_at_rest);
    st.support = st.step->support;
    st.length = st.step->Length();
    const double s_start = assemble_ ? st.length : 0.0;
    for (int p = 0; p < n_; ++p) {
      if (!st.in_group[p]) continue;
      config_.present[p] = true;
      config_.poses[p] = Pose::Translation(st.step->At(s_start));
      nu_[p].setZero();
    }
    st.moves = std::max(
        1, static_cast<int>(std::ceil(st.length / tick_length_ - numeric::kParameterSlack)));
    return st;
  }

  // One tick: place the gripper, analyse, classify, record a failure, move
  // on. False when the step stops here. Assembling, a step ends with its
  // parts let go where they arrived (`release`, at the last tick's place):
  // the mirror of a disassembly's first tick, which finds them resting there.
  bool RunTick(StepState& st, int tick, bool release = false) {
    TickMotion tm = GripperAt(st, tick);
    tm.release = release;
    for (int p = 0; p < n_; ++p)
      if (st.gripped[p]) config_.poses[p] = Pose::Translation(st.step->At(tm.s));
    StabilityOptions so;
    so.dt = tm.dt;
    so.lemke = options_.lemke;
    so.rule = options_.rule;
    const Tolerances tol = a_.MakeTolerances(tm.dt);
    so.tolerances = tol;
    const TickAnalysis an = Analyze(st, tm, so);
    for (const ComponentReport& c : an.r.components)
      if (c.stability == StabilityProof::kWeak || c.stability == StabilityProof::kNotCertified)
        result_.rest_strong = false;
    TickVerdict v = Classify(st, tm, an, tol);
    if (v.failure.verdict != MotionVerdict::kStable && !st.failed)
      RecordFailure(st, tm, v.judged_by_moved ? an.moved : an.r, v);
    AdvanceCarriedParts(st, tm, an.motion());
    if (v.failure.verdict == MotionVerdict::kStable) return true;
    if (!options_.continue_after_failure) return false;
    // Continue as if the failure were prevented: hold the parts that moved,
    // let the gripper carry an unsupported part.
    if (v.failure.verdict == MotionVerdict::kUnstable)
      for (int p : v.failure.parts) held_[p] = true, nu_[p].setZero();
    if (v.failure.verdict == MotionVerdict::kUnsupported) st.support = SupportMode::kFull;
    return true;
  }

  // Where the gripper is and where it goes during this tick.
  TickMotion GripperAt(const StepState& st, int tick) const {
    TickMotion tm;
    tm.tick = tick;
    const double L = st.length;
    tm.travelled = std::min(tick * tick_length_, L);
    const double next = std::min((tick + 1) * tick_length_, L);
    tm.s = assemble_ ? L - tm.travelled : tm.travelled;
    tm.dt = tick < st.moves ? (next - tm.travelled) / plan_.speed : plan_.dt;
    // Time stepping: the contact LCP at a tick gives the motion over the
    // coming interval, with the gripper's velocity for that interval (zero
    // at the last tick: the gripper has stopped, and a part set into its
    // seat does not keep pushing); the carried parts are moved with it.
    tm.v_g = tick < st.moves ? Vector3(plan_.speed * TravelDirection(*st.step, tm.s, !assemble_))
                             : Vector3::Zero();
    // The path direction the gripper holds a guided part along: the coming
    // one, or at the end of the path the one it came along.
    tm.guide = tm.v_g.norm() > 0 ? Vector3(tm.v_g.normalized())
                                 : Vector3(-TravelDirection(*st.step, tm.s, assemble_));
    tm.t_now = time_ + tm.travelled / plan_.speed;
    return tm;
  }

  // The drive: who moves how. `at_rest` describes the node before the step:
  // the gripper has not moved yet, so its parts still rest on the assembly
  // with their weight (the paper's figures show their contact forces until
  // they are lifted).
  // The step's held parts (PlanStep::hold) are held while its parts move,
  // its hold_at_rest while they rest in their assembled pose (InPlace); its
  // props likewise (SceneOf).
  // True when the step's parts rest in their assembled pose, let go: a
  // disassembly's first solve, an assembly's release.
  bool InPlace(const TickMotion& tm, bool at_rest) const {
    return at_rest && (assemble_ ? tm.release : tm.tick == 0);
  }

  // The scene the step's solves see: with its props (in place or moving).
  const Assembly& SceneOf(const StepState& st, bool in_place) const {
    const std::optional<Assembly>& a = in_place ? st.with_props_at_rest : st.with_props;
    return a ? *a : a_;
  }

  DriveInputs MakeDrive(const StepState& st, const TickMotion& tm, bool at_rest) const {
    DriveInputs d;
    d.role.assign(n_, PartRole::kJudged);
    d.velocity.assign(n_, Vector3::Zero());
    d.guide.assign(n_, tm.guide);
    d.nu_prev = nu_;
    const std::vector<bool>& hold = InPlace(tm, at_rest) ? st.hold_at_rest : st.hold;
    for (int p = 0; p < n_; ++p) {
      if (hold[p]) {
        d.role[p] = PartRole::kPrescribed;  // held in place: velocity 0
        d.nu_prev[p].setZero();
      } else if (tm.release && st.in_group[p] && !a_.part(p).tool) {
        d.nu_prev[p].setZero();  // let go where it arrived: judged, as every placed part
      } else if (st.gripped[p] && at_rest && !a_.part(p).tool) {
        d.role[p] = PartRole::kCarried;
        d.nu_prev[p].setZero();
      } else if (st.gripped[p]) {
        const bool rigid = st.support == SupportMode::kFull || a_.part(p).tool;
        d.role[p] = rigid ? PartRole::kPrescribed : PartRole::kGuided;
        d.velocity[p] = at_rest ? Vector3::Zero() : tm.v_g;
      } else if (st.carried[p]) {
        d.role[p] = PartRole::kCarried;
      } else if (held_[p]) {
        d.role[p] = PartRole::kPrescribed;  // held in place: velocity 0
      }
    }
    return d;
  }

  // At tick 0 the verdict is first the node's, at rest (r); then the gripper
  // starts to move, and a second solve with the driven motion (`moved`)
  // tells which judged parts it pushes from the first instant and how the
  // carried parts move over the first interval.
  TickAnalysis Analyze(StepState& st, const TickMotion& tm, const StabilityOptions& so) {
    TickAnalysis an;
    const int k = st.k, tick = tm.tick;
    const DriveInputs drive = MakeDrive(st, tm, tick == 0 || tm.release);
    if (options_.on_analysis)
      options_.on_analysis({k, tick, tm.t_now, true, &config_, &drive, &so});
    an.r = AnalyzeConfiguration(SceneOf(st, InPlace(tm, tick == 0 || tm.release)), config_, so,
                                &drive, &workspace_);
    ++st.report.ticks;
    for (const ComponentReport& c : an.r.components) st.report.pivots += c.pivots;
    if (!an.r.diagnostics.empty())
      result_.diagnostics += "step " + std::to_string(k + 1) + ", tick " + std::to_string(tick) +
                             ": " + an.r.diagnostics;
    if (options_.record_timeline)
      for (const ContactReport& c : an.r.contacts)
        result_.timeline.push_back({tm.t_now, k, tick, c});
    if (tick == 0 && tick < st.moves && !tm.release) {
      const DriveInputs go = MakeDrive(st, tm, false);
      if (options_.on_analysis)
        options_.on_analysis({k, tick, tm.t_now, false, &config_, &go, &so});
      an.moved = AnalyzeConfiguration(SceneOf(st, false), config_, so, &go, &workspace_);
      an.has_moved = true;
      if (!an.moved.diagnostics.empty())
        result_.diagnostics +=
            "step " + std::to_string(k + 1) + ", tick 0 (gripper moving): " + an.moved.diagnostics;
    }
    return an;
  }

  // Classify the tick: infeasible, unstable, unsupported, stable, in that
  // order of precedence.
  TickVerdict Classify(StepState& st, const TickMotion& tm, const TickAnalysis& an,
                       const Tolerances& tol) const {
    TickVerdict v;
    v.failure_time = tm.t_now;
    MotionFailure& f = v.failure;
    ClassifyOverlap(st, tm, tol, v);
    const StabilityResult& r = an.r;
    if (f.verdict == MotionVerdict::kStable && !r.jammed.empty()) {
      f.verdict = MotionVerdict::kInfeasible;
      f.parts = r.jammed;
    }
    if (f.verdict == MotionVerdict::kStable && !r.moving.empty()) {
      f.verdict = MotionVerdict::kUnstable;
      f.parts = r.moving;
      if (tm.tick > 0 && !tm.release)  // the gripper moves: some may be pushed
        f.pushed =
            PushedParts(a_, config_, r, st.gripped, st.carried, tm.v_g, tol.force, tol.velocity);
    }
    if (f.verdict == MotionVerdict::kStable && r.verdict == Verdict::kSolverFailure) {
      // Numerical trouble is never taken for stability.
      f.verdict = MotionVerdict::kUnstable;
      f.solver_note = r.diagnostics;
    }
    // Pushes at the first instant: judged parts that the driven motion
    // pushes (PushedParts) are unstable from t = the step's start. Judged
    // parts that start to move for another reason (a support or a
    // counterweight leaves) are judged at the next tick, as before; so are a
    // jam and a numerical failure of this solve, whose motions are then not
    // trusted (a ray termination of Lemke's method with friction is no
    // proof that no forces allow the motion: the next tick's solve confirms
    // a real jam, or the overlap check does).
    if (f.verdict == MotionVerdict::kStable && an.has_moved && an.moved.jammed.empty() &&
        an.moved.verdict != Verdict::kSolverFailure) {
      const std::vector<int> pushed = PushedParts(a_, config_, an.moved, st.gripped, st.carried,
                                                  tm.v_g, tol.force, tol.velocity);
      if (!pushed.empty()) {
        v.judged_by_moved = true;
        f.verdict = MotionVerdict::kUnstable;
        f.parts = f.pushed = pushed;
      }
    }
    if (f.verdict == MotionVerdict::kStable && !r.unsupported.empty()) {
      if (options_.carry_when_unsupported) {
        // The paper's Fig. 6 gripper: it takes the part's weight from here on.
        st.support = SupportMode::kFull;
      } else {
        f.verdict = MotionVerdict::kUnsupported;
        f.parts = r.unsupported;
      }
    }
    return v;
  }

  // Overlap: a gripped part inside a part that cannot give way (fixed, or
  // held after an earlier failure) is infeasible; inside a free part, it has
  // pushed that part since they touched (found by bisection between the
  // ticks): unstable from then, the part moving with the pusher.
  void ClassifyOverlap(const StepState& st, const TickMotion& tm, const Tolerances& tol,
                       TickVerdict& v) const {
    std::vector<bool> can_give_way(n_);
    for (int p = 0; p < n_; ++p)
      can_give_way[p] = !a_.part(p).fixed && !a_.part(p).tool && !held_[p] && !st.hold[p];
    const auto hit =
        FindCollision(a_, config_, st.gripped, st.in_group, can_give_way, tol.penetration);
    if (!hit) return;
    MotionFailure& f = v.failure;
    if (!can_give_way[hit->other]) {
      f.verdict = MotionVerdict::kInfeasible;
      f.parts = {hit->driven, hit->other};
      return;
    }
    const double L = st.length;
    const double u = tm.tick > 0 ? FirstOverlap(a_, config_, *st.step, assemble_, *hit,
                                                std::min((tm.tick - 1) * tick_length_, L),
                                                tm.travelled, tol.penetration)
                                 : tm.travelled;
    f.verdict = MotionVerdict::kUnstable;
    f.parts = f.pushed = {hit->other};
    v.failure_time = time_ + u / plan_.speed;
    PartMotion m;
    m.part = hit->other;
    m.moving = true;
    m.kind = MotionKind::kSlides;
    m.linear = plan_.speed * TravelDirection(*st.step, assemble_ ? L - u : u, !assemble_);
    f.motions = {m};
  }

  // The step's first failure, with the motions and the breaking or sliding
  // contacts of its parts from the solve that explains it.
  void RecordFailure(StepState& st, const TickMotion& tm, const StabilityResult& judged,
                     TickVerdict& v) {
    MotionFailure& f = v.failure;
    f.step = st.k;
    f.tick = tm.tick;
    f.released = tm.release;
    f.time = v.failure_time;
    if (f.motions.empty())
      for (const PartMotion& m : judged.parts)
        if (std::find(f.parts.begin(), f.parts.end(), m.part) != f.parts.end())
          f.motions.push_back(m);
    const auto involved = [&](int part) {
      return std::find(f.parts.begin(), f.parts.end(), part) != f.parts.end();
    };
    for (const ContactReport& c : judged.contacts)
      if ((c.breaking || c.sliding) && (involved(c.contact.part_a) || involved(c.contact.part_b)))
        f.contacts.push_back(c);
    if (!f.pushed.empty()) f.pushers = st.step->remove;
    st.report.verdict = f.verdict;
    st.report.failure = f;
    if (!result_.failure) result_.failure = f;
    st.failed = true;
  }

  // Carry velocities to the next tick (a gripped part keeps only its own
  // off-path velocity: the gripper's may change direction at a corner); move
  // the carried parts.
  void AdvanceCarriedParts(const StepState& st, const TickMotion& tm,
                           const StabilityResult& motion) {
    for (const PartMotion& m : motion.parts) {
      nu_[m.part] << m.linear, m.angular;
      if (st.gripped[m.part]) nu_[m.part].head<3>() -= tm.v_g;
    }
    for (int p = 0; p < n_; ++p) {
      if (!st.carried[p]) continue;
      config_.poses[p].translation += nu_[p].head<3>() * tm.dt;
      config_.poses[p].Rotate(nu_[p].tail<3>() * tm.dt);
    }
  }

  // The step is over: removed parts leave (or, assembling, stay placed);
  // tools always leave.
  void LeaveStep(StepState& st) {
    st.report.warm_starts = workspace_.TakeWarmStarts();
    time_ += st.length / plan_.speed;
    st.report.end_time = time_;
    result_.steps.push_back(st.report);
    for (int p = 0; p < n_; ++p) {
      if (!st.in_group[p]) continue;
      config_.present[p] = assemble_ && !a_.part(p).tool;
      config_.poses[p] = Pose{};
      nu_[p].setZero();
    }
  }

  const Assembly& a_;
  const Plan& plan_;
  const SimulationOptions& options_;
  const int n_;
  const bool assemble_;
  Configuration config_;
  std::vector<Vector6> nu_;  // each part's velocity after the last tick
  std::vector<bool> held_;   // held in place after a failure (continue mode)
  StabilityWorkspace workspace_;
  double time_ = 0;
  const double tick_length_;
  SimulationResult result_;
};

}  // namespace

SimulationResult SimulatePlan(const Assembly& assembly, const Plan& plan,
                              const SimulationOptions& options) {
  CAIRN_THROW_UNLESS(!assembly.has_interfaces(),
                     "SimulatePlan: the assembly's contacts are given interfaces of its assembled "
                     "configuration; its parts cannot move");
  return PlanSimulation(assembly, plan, options).Run();
}

}  // namespace cairn

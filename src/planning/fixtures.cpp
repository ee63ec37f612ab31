#include "cairn/planning/fixtures.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <tuple>

#include "cairn/core/check.h"
#include "cairn/core/format.h"
#include "cairn/geometry/polygon.h"
#include "cairn/geometry/polyhedron.h"

namespace cairn {

namespace {

// A candidate fixel opposes the motion when the power it could absorb,
// relative to the fastest point of the moving parts, exceeds this
// (dimensionless: roundoff of a unit-speed motion's projection).
constexpr double kLeastOpposition = 1e-6;
// Candidates whose opposition agrees to this relative resolution rank as
// ties (then: centres first, part, face, generation order).
constexpr double kRankResolution = 1e6;

}  // namespace

namespace {

// A candidate fixel: a point of a moving part's free boundary, pushing into it.
struct Candidate {
  int part = -1;
  Vector3 p_WF{0, 0, 0};  // the point, world frame, assembled pose
  Vector3 n_W{0, 0, 0};   // unit, into the part (the inward face normal)
  int face = -1;          // edge (2-D) or face (3-D) index of the part
  bool centre = false;    // an edge midpoint or face centroid
  int order = 0;          // generation order (a total order for ties)
  double opposition = 0;  // the point's velocity along the outward normal (length/s)
  std::string face_name;
};

// Where a step comes in the order the plan runs (an assembly plan runs
// backwards).
int RunPosition(const Plan& plan, int step) {
  return plan.mode == PlanMode::kAssemble ? static_cast<int>(plan.steps.size()) - 1 - step : step;
}

// True when the run gets past `step`: stable, or failing only later.
bool PassesStep(const Plan& plan, const SimulationResult& r, int step) {
  return r.stable() || RunPosition(plan, r.failure->step) > RunPosition(plan, step);
}

// The contacts of the failing tick (from the run's timeline).
std::vector<Contact> ContactsAt(const SimulationResult& r, const MotionFailure& f) {
  std::vector<Contact> out;
  for (const TimelineRow& row : r.timeline)
    if (row.step == f.step && row.tick == f.tick) out.push_back(row.contact.contact);
  return out;
}

// True when a contact of `part` with another part (fixtures do not count)
// lies on the face through `q` with outward normal `n_out`: on it within
// `on_face` (a predicate on the point) and with a normal parallel to it.
template <typename OnFace>
bool FaceInContact(const std::vector<Contact>& contacts, int part, const Vector3& n_out,
                   OnFace on_face) {
  constexpr double kParallel = 1e-6;  // 1 − cos of the angle between parallel normals
  for (const Contact& c : contacts) {
    if (c.part_b == kWorld) continue;
    if (c.part_a != part && c.part_b != part) continue;
    // n_W points from b into a: against the outward normal of a's face, along
    // b's.
    const double along = (c.part_a == part ? -1.0 : 1.0) * c.n_W.dot(n_out);
    if (along >= 1 - kParallel && on_face(c.p_WC)) return true;
  }
  return false;
}

}  // namespace

std::vector<FacePoint> FreeFacePoints(const Assembly& a, int part_index,
                                      const std::vector<Contact>& contacts, double tol) {
  std::vector<FacePoint> out;
  const Part& part = a.part(part_index);
  const auto add = [&](const Vector3& p, const Vector3& n_out, int face, bool centre,
                       const std::string& name) {
    FacePoint f;
    f.part = part_index;
    f.point = p;
    f.normal = -n_out + Vector3::Zero();  // + 0: no −0 in reports
    f.face = face;
    f.centre = centre;
    f.face_name = name;
    out.push_back(f);
  };
  if (!a.is_3d()) {
    const Polygon& poly = part.polygon;
    const int nv = static_cast<int>(poly.size());
    for (int e = 0; e < nv; ++e) {
      const Vector2 p0 = poly[e], p1 = poly[(e + 1) % nv];
      const Vector2 n2 = EdgeNormal(poly, e);
      const Vector3 n_out(n2.x(), n2.y(), 0);
      const bool busy = FaceInContact(contacts, part_index, n_out, [&](const Vector3& q) {
        return DistanceToSegment(q.head<2>(), p0, p1) <= tol;
      });
      if (busy) continue;
      const Vector3 a0(p0.x(), p0.y(), 0), a1(p1.x(), p1.y(), 0);
      const std::string name =
          "edge " + std::to_string(e) + " " + FormatPoint(a0, 2) + "-" + FormatPoint(a1, 2);
      add(0.5 * (a0 + a1), n_out, e, true, name);
      add(a0, n_out, e, false, name);
      add(a1, n_out, e, false, name);
    }
    return out;
  }
  const Polyhedron& poly = *part.polyhedron;
  for (int fi = 0; fi < static_cast<int>(poly.faces().size()); ++fi) {
    const Vector3& n_out = poly.face_normals()[fi];
    const Vector3& v0 = poly.vertices()[poly.faces()[fi][0]];
    const bool busy = FaceInContact(contacts, part_index, n_out, [&](const Vector3& q) {
      return std::abs(n_out.dot(q - v0)) <= tol;
    });
    if (busy) continue;
    // The face's area centroid, over its triangles.
    Vector3 centroid = Vector3::Zero();
    double area = 0;
    for (const auto& t : poly.face_triangles()[fi]) {
      const Vector3 &x = poly.vertices()[t[0]], &y = poly.vertices()[t[1]],
                    &z = poly.vertices()[t[2]];
      const double ta = 0.5 * (y - x).cross(z - x).norm();
      centroid += ta * (x + y + z) / 3;
      area += ta;
    }
    if (area <= 0) continue;
    centroid /= area;
    const std::string name = "face " + std::to_string(fi);
    add(centroid, n_out, fi, true, name);
    // Corners pulled 10% towards the centroid: a corner itself has no single
    // inward direction.
    for (int vi : poly.faces()[fi])
      add(centroid + 0.9 * (poly.vertices()[vi] - centroid), n_out, fi, false, name);
  }
  return out;
}

namespace {

// The candidate points of one moving part at the failing tick, with how
// much each opposes its motion. The part is judged, so it is at its
// assembled pose: its vertices are the Assembly's.
void PartCandidates(const Assembly& a, const PartMotion& m, const std::vector<Contact>& contacts,
                    double tol, std::vector<Candidate>& out) {
  const Part& part = a.part(m.part);
  for (const FacePoint& f : FreeFacePoints(a, m.part, contacts, tol)) {
    Candidate c;
    c.part = m.part;
    c.p_WF = f.point;
    c.n_W = f.normal;
    c.face = f.face;
    c.centre = f.centre;
    c.order = static_cast<int>(out.size());
    // The velocity of the point: v + ω × (p − c), with c the centroid.
    const Vector3 v = m.linear + m.angular.cross(f.point - part.centroid);
    c.opposition = -v.dot(f.normal);  // along the outward normal
    c.face_name = f.face_name;
    out.push_back(c);
  }
}

// The scene with `fixels` added after its own fixtures.
AssemblyDef WithFixels(const AssemblyDef& def, const std::vector<FixtureDef>& fixels) {
  AssemblyDef out = def;
  out.fixtures.insert(out.fixtures.end(), fixels.begin(), fixels.end());
  return out;
}

FixtureDef ToFixture(const Assembly& a, const Candidate& c) {
  return FixtureDef{a.part(c.part).name, c.p_WF, c.n_W};
}

// The next subset of {0..n-1} of the same size in lexicographic order;
// false after the last.
bool NextSubset(std::vector<int>& idx, int n) {
  const int k = static_cast<int>(idx.size());
  int i = k - 1;
  while (i >= 0 && idx[i] == n - k + i) --i;
  if (i < 0) return false;
  ++idx[i];
  for (int j = i + 1; j < k; ++j) idx[j] = idx[j - 1] + 1;
  return true;
}

}  // namespace

namespace {

// Parts that may carry a fixel: movable, not tools, never removed by the plan.
std::vector<bool> EligibleParts(const Assembly& assembly, const Plan& plan) {
  std::vector<bool> eligible(assembly.num_parts(), true);
  for (int p = 0; p < assembly.num_parts(); ++p)
    eligible[p] = !assembly.part(p).fixed && !assembly.part(p).tool;
  for (const PlanStep& step : plan.steps) {
    for (int p : step.remove) eligible[p] = false;
    for (int p : step.grip) eligible[p] = false;
  }
  return eligible;
}

// Why fixels cannot help with the failure `f` (at: where it happened), or
// empty; `room` is how many more fixels are allowed.
std::optional<std::string> Hopeless(const MotionFailure& f, int room,
                                    const FixtureSearchOptions& options) {
  if (f.verdict == MotionVerdict::kInfeasible)
    return " is infeasible: fixels cannot free a blocked motion";
  if (f.verdict == MotionVerdict::kUnsupported)
    return " is unsupported: the gripper must carry the part; fixels do not help";
  if (f.parts.empty())
    return " failed without a moving part (a solver failure): no fixels suggested";
  if (room <= 0)
    return " needs more than the " + std::to_string(options.max_fixels) + " fixels allowed";
  return std::nullopt;
}

// Candidates on the free faces of the moving parts `movers`, those that
// oppose the motion ranked by how much (near-ties: centres first, then part,
// face and generation order), each one the scene accepts (on the boundary,
// pushing into the part); at most options.max_candidates.
std::vector<Candidate> CandidatePool(const Assembly& assembly, const SimulationResult& current,
                                     const MotionFailure& f, const std::vector<int>& movers,
                                     const FixtureSearchOptions& options) {
  const std::vector<Contact> contacts = ContactsAt(current, f);
  std::vector<Candidate> all;
  double fastest = 0;
  for (const PartMotion& m : f.motions) {
    if (std::find(movers.begin(), movers.end(), m.part) == movers.end()) continue;
    PartCandidates(assembly, m, contacts, assembly.length_tolerance(), all);
    fastest = std::max(fastest, m.point_motion);
  }
  const double least = kLeastOpposition * fastest;
  std::vector<Candidate> opposing;
  for (const Candidate& c : all)
    if (c.opposition > least) opposing.push_back(c);
  double best = 0;
  for (const Candidate& c : opposing) best = std::max(best, c.opposition);
  const auto rank = [&](const Candidate& c) {
    return std::make_tuple(-std::llround(kRankResolution * c.opposition / best), c.centre ? 0 : 1,
                           c.part, c.face, c.order);
  };
  std::sort(opposing.begin(), opposing.end(),
            [&](const Candidate& x, const Candidate& y) { return rank(x) < rank(y); });
  std::vector<Candidate> pool;
  for (const Candidate& c : opposing) {
    if (static_cast<int>(pool.size()) >= options.max_candidates) break;
    if (!assembly.FixtureFault(ToFixture(assembly, c))) pool.push_back(c);
  }
  return pool;
}

// Subsets of `pool` by increasing size (at most `room`), each verified by
// re-running the plan with the fixels chosen so far: the first that passes
// the failing step, with its run. `budget` tells whether the simulation
// budget ran out first.
std::optional<std::pair<std::vector<int>, SimulationResult>> FirstPassingSubset(
    const AssemblyDef& def, const Assembly& assembly, const Plan& plan,
    const SimulationOptions& sim, const std::vector<FixtureDef>& chosen_defs,
    const std::vector<Candidate>& pool, int room, int failing_step,
    const FixtureSearchOptions& options, FixtureSuggestion& out, bool* budget) {
  const int n = static_cast<int>(pool.size());
  for (int size = 1; size <= std::min(room, n); ++size) {
    std::vector<int> idx(size);
    for (int i = 0; i < size; ++i) idx[i] = i;
    do {
      if (out.simulations >= options.max_simulations) {
        *budget = true;
        return std::nullopt;
      }
      std::vector<FixtureDef> trial = chosen_defs;
      for (int i : idx) trial.push_back(ToFixture(assembly, pool[i]));
      // Every fixel passed FixtureFault: the scene accepts them.
      const Assembly scene = Assembly::Create(WithFixels(def, trial));
      SimulationResult r = SimulatePlan(scene, plan, sim);
      ++out.simulations;
      if (PassesStep(plan, r, failing_step)) return std::make_pair(idx, std::move(r));
    } while (NextSubset(idx, n));
  }
  return std::nullopt;
}

// The verification (the last run, with every fixel chosen), each fixel's
// largest force in it, and where the search stopped.
void Conclude(const AssemblyDef& def, const SimulationResult& failed,
              const SimulationResult& current, const std::vector<SuggestedFixel>& chosen,
              const std::string& why, FixtureSuggestion& out) {
  out.found = current.stable();
  out.fixels = chosen;
  out.verification = chosen.empty() ? failed : current;
  const int base = static_cast<int>(def.fixtures.size());
  for (const TimelineRow& row : out.verification.timeline) {
    const Contact& c = row.contact.contact;
    if (c.feature != ContactFeature::kFixture || c.index_a < base) continue;
    SuggestedFixel& s = out.fixels[c.index_a - base];
    s.max_force = std::max(s.max_force, row.contact.normal_force);
  }
  if (!out.found) {
    out.stopped_at = current.failure;
    out.stop_reason = why;
  }
}

// The search's budgets: each at least 1.
void CheckSearchOptions(const FixtureSearchOptions& options) {
  CAIRN_THROW_UNLESS(options.max_fixels >= 1,
                     "SuggestFixtures: max_fixels must be at least 1, not " << options.max_fixels);
  CAIRN_THROW_UNLESS(
      options.max_candidates >= 1,
      "SuggestFixtures: max_candidates must be at least 1, not " << options.max_candidates);
  CAIRN_THROW_UNLESS(
      options.max_simulations >= 1,
      "SuggestFixtures: max_simulations must be at least 1, not " << options.max_simulations);
}

}  // namespace

FixtureSuggestion SuggestFixtures(const AssemblyDef& def, const Assembly& assembly,
                                  const Plan& plan, const SimulationResult& failed,
                                  const FixtureSearchOptions& options) {
  CheckSearchOptions(options);
  FixtureSuggestion out;
  if (failed.stable()) {
    out.found = true;
    out.verification = failed;
    return out;
  }
  // Runs stop at their first failure and keep their contacts.
  SimulationOptions sim = options.simulation;
  sim.continue_after_failure = false;
  sim.record_timeline = true;
  const std::vector<bool> eligible = EligibleParts(assembly, plan);
  // The run without fixels, with its timeline (`failed` may have none).
  SimulationResult current;
  if (!failed.timeline.empty()) {
    current = failed;
  } else {
    current = SimulatePlan(assembly, plan, sim);
    ++out.simulations;
  }

  // Failure by failure: candidates on the parts that move, then the fewest
  // of them that keep the failing step stable.
  std::vector<SuggestedFixel> chosen;
  std::vector<FixtureDef> chosen_defs;
  std::string why;  // why the search stopped short, when it did
  while (!current.stable()) {
    const MotionFailure& f = *current.failure;
    const int room = options.max_fixels - static_cast<int>(chosen.size());
    if (const auto hopeless = Hopeless(f, room, options)) {
      why = *hopeless;
      break;
    }
    std::vector<int> movers;
    for (int p : f.parts)
      if (eligible[p]) movers.push_back(p);
    if (movers.empty()) {
      why = ": the parts that move (" + assembly.NameList(f.parts) +
            ") are removed later in the plan, and a fixel would have to leave "
            "with them";
      break;
    }
    const std::vector<Candidate> pool = CandidatePool(assembly, current, f, movers, options);
    out.candidates += static_cast<int>(pool.size());
    if (pool.empty()) {
      why = ": no free face of " + assembly.NameList(movers) + " opposes its motion";
      break;
    }
    bool budget = false;
    auto passing = FirstPassingSubset(def, assembly, plan, sim, chosen_defs, pool, room, f.step,
                                      options, out, &budget);
    if (!passing) {
      const int n = static_cast<int>(pool.size());
      why = ": " + (budget ? "the budget of " + std::to_string(options.max_simulations) +
                                 " simulations ran out"
                           : "no set of at most " + std::to_string(std::min(room, n)) + " of the " +
                                 std::to_string(n) + " candidate fixels on " +
                                 assembly.NameList(movers) + " keeps it stable");
      break;
    }
    for (int i : passing->first) {
      SuggestedFixel s;
      s.fixture = ToFixture(assembly, pool[i]);
      s.part = pool[i].part;
      s.step = f.step;
      s.face = pool[i].face_name;
      chosen.push_back(s);
      chosen_defs.push_back(s.fixture);
    }
    current = std::move(passing->second);
  }
  Conclude(def, failed, current, chosen, why, out);
  return out;
}

}  // namespace cairn

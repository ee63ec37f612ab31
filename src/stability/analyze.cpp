#include "cairn/stability/analyze.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "cairn/contact/contact_reduction.h"
#include "cairn/contact/detect_contacts.h"
#include "cairn/core/tolerances.h"
#include "cairn/mechanics/static_equilibrium.h"
#include "cairn/stability/solve_component.h"

namespace cairn {

// The component solutions a workspace in reuse mode keeps (a build order's
// states have a few components each, most shared with the state before).
constexpr size_t kKeptSolutions = 256;

// The workspace's contents: the last Lemke basis of each component structure
// and the last rest-hypothesis LP basis.

struct StabilityWorkspace::Impl {
  /// One component structure and its last basis.
  struct Entry {
    /// The structure: LCP size, the bodies' part indices, then each contact's
    /// part_a, part_b, feature, index_a, index_b (compared exactly).
    std::vector<int> key;
    LcpBasis basis;
  };
  std::unordered_multimap<std::uint64_t, Entry> bases;  ///< hash of Entry::key → entry
  int warm_starts = 0;                                  ///< solves answered by a warm start
  /// The last rest-hypothesis LP basis of each set of bodies (BodiesHash; a
  /// hint, so no exact compare: a wrong basis costs iterations, not answers).
  /// Keyed by the bodies, not the contacts: the basis maps its rows and
  /// columns by contact identity (RestLpBasis), so the last tick's basis
  /// warm-starts the LP of a tick where contacts opened or closed.
  std::unordered_map<std::uint64_t, RestLpBasis> rest_bases;
  /// The contacts of the part pairs that did not move (DetectContacts).
  PairContactCache contacts;
  /// Reuse mode (set_reuse_solutions): each component's data (SolutionKey)
  /// and solution, by the data's hash; at most kKeptSolutions (then the
  /// store starts afresh).
  bool reuse = false;
  std::unordered_multimap<std::uint64_t, std::pair<std::vector<double>, ComponentSolution>>
      solutions;
  int reused = 0;
};

StabilityWorkspace::StabilityWorkspace() : impl_(std::make_unique<Impl>()) {}
StabilityWorkspace::~StabilityWorkspace() = default;
StabilityWorkspace::StabilityWorkspace(StabilityWorkspace&&) noexcept = default;
StabilityWorkspace& StabilityWorkspace::operator=(StabilityWorkspace&&) noexcept = default;
int StabilityWorkspace::warm_starts() const { return impl_->warm_starts; }
int StabilityWorkspace::TakeWarmStarts() {
  const int n = impl_->warm_starts;
  impl_->warm_starts = 0;
  return n;
}
int StabilityWorkspace::num_structures() const { return static_cast<int>(impl_->bases.size()); }
void StabilityWorkspace::set_reuse_solutions(bool on) { impl_->reuse = on; }
int StabilityWorkspace::reused() const { return impl_->reused; }

const char* to_string(MotionKind kind) {
  switch (kind) {
    case MotionKind::kAtRest:
      return "at rest";
    case MotionKind::kSlides:
      return "slides";
    case MotionKind::kTips:
      return "tips";
    case MotionKind::kFalls:
      return "falls";
  }
  return "unknown";
}

const char* to_string(PartRole role) {
  switch (role) {
    case PartRole::kJudged:
      return "judged";
    case PartRole::kCarried:
      return "carried";
    case PartRole::kGuided:
      return "guided";
    case PartRole::kPrescribed:
      return "prescribed";
  }
  return "unknown";
}

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::kStable:
      return "stable";
    case Verdict::kUnstable:
      return "unstable";
    case Verdict::kSolverFailure:
      return "solver failure";
  }
  return "unknown";
}

namespace {

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// Union–find over part indices.
int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

struct Component {
  std::vector<int> parts;     // movable parts, ascending
  std::vector<int> contacts;  // indices into the contact list, ascending
};

// The canonical order of the parts: by centroid (x, then y, then z), the
// part index only between parts whose centroids coincide. The LCP of a
// component lists its bodies and contacts in this order, and orients each
// contact between two movable parts from the earlier to the later, so that
// permuting or renaming the parts of a file changes no LCP, hence no answer
// of a solver whose choices follow the order of its unknowns (Lemke's
// method among several solutions).
std::vector<int> CanonicalRanks(const Assembly& assembly, const Configuration& config) {
  const int n = assembly.num_parts();
  std::vector<Vector3> centroid(n, Vector3::Zero());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  for (int i = 0; i < n; ++i)
    if (config.present[i]) centroid[i] = config.WorldCentroid(assembly, i);
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    const Vector3& a = centroid[x];
    const Vector3& b = centroid[y];
    if (a.x() != b.x()) return a.x() < b.x();
    if (a.y() != b.y()) return a.y() < b.y();
    if (a.z() != b.z()) return a.z() < b.z();
    return x < y;
  });
  std::vector<int> rank(n);
  for (int k = 0; k < n; ++k) rank[order[k]] = k;
  return rank;
}

// Movable parts joined by contacts (contacts with fixed parts or the world
// join nothing). Ordered by smallest part index: deterministic.
std::vector<Component> SplitComponents(const Assembly& assembly, const Configuration& config,
                                       const std::vector<Contact>& contacts,
                                       const std::vector<int>* rank) {
  const int n = assembly.num_parts();
  const auto movable = [&](int i) {
    return i >= 0 && config.present[i] && !assembly.part(i).fixed;
  };
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Contact& c : contacts)
    if (movable(c.part_a) && movable(c.part_b))
      parent[Find(parent, c.part_a)] = Find(parent, c.part_b);
  std::vector<int> index_of_root(n, -1);
  std::vector<Component> out;
  for (int i = 0; i < n; ++i) {
    if (!movable(i)) continue;
    const int r = Find(parent, i);
    if (index_of_root[r] < 0) {
      index_of_root[r] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[index_of_root[r]].parts.push_back(i);
  }
  for (int c = 0; c < static_cast<int>(contacts.size()); ++c) {
    const int owner = movable(contacts[c].part_a) ? contacts[c].part_a : contacts[c].part_b;
    out[index_of_root[Find(parent, owner)]].contacts.push_back(c);
  }
  // Each component's parts in the canonical order (CanonicalRanks), when
  // given; else ascending, the file's.
  if (!rank) return out;
  for (Component& comp : out)
    std::sort(comp.parts.begin(), comp.parts.end(),
              [rank](int x, int y) { return (*rank)[x] < (*rank)[y]; });
  return out;
}

PartRole RoleOf(const DriveInputs* drive, int part) {
  return drive && !drive->role.empty() ? drive->role[part] : PartRole::kJudged;
}

// The LCP of one component: its movable parts under gravity (gripped ones
// moving with the gripper), its contacts.
ContactLcp BuildComponent(const Assembly& assembly, const Configuration& config,
                          const std::vector<Contact>& contacts, const Component& comp,
                          Formulation formulation, double dt, const DriveInputs* drive,
                          LcpStorage storage, double length_tol,
                          std::vector<int>* lcp_index = nullptr,
                          std::vector<char>* flipped = nullptr,
                          const std::vector<int>* canonical = nullptr,
                          const std::vector<PartLoad>* loads = nullptr) {
  std::vector<BodyDynamics> bodies;
  for (int p : comp.parts) {
    const Part& part = assembly.part(p);
    BodyDynamics b;
    b.part = p;
    b.mass = part.mass;
    b.inertia = config.WorldInertia(assembly, p);
    b.p_WBcm = config.WorldCentroid(assembly, p);
    b.planar = !assembly.is_3d();
    b.F_ext.head<3>() = part.mass * assembly.gravity();
    if (loads) {
      for (const PartLoad& load : *loads) {
        if (load.part != p) continue;
        b.F_ext.head<3>() += load.force;
        b.F_ext.tail<3>() += (load.point - b.p_WBcm).cross(load.force);
      }
    }
    if (drive && !drive->nu_prev.empty()) b.nu_prev = drive->nu_prev[p];
    const PartRole role = RoleOf(drive, p);
    if (IsDriven(role)) {
      const Vector3 v = drive->velocity[p];
      b.nu_prescribed.head<3>() = v;
      b.motion = role == PartRole::kPrescribed ? BodyMotion::kPrescribed : BodyMotion::kGuided;
      // The gripper holds a guided part along the path, even when it stands
      // still (at the end of the path); with no direction at all, it is free.
      const Vector3 g = drive->guide.empty() ? Vector3::Zero() : drive->guide[p];
      if (role == PartRole::kGuided) {
        if (g.norm() > 0)
          b.guide = g.normalized();
        else if (v.norm() > 0)
          b.guide = v.normalized();
        else
          b.motion = BodyMotion::kFree;
      }
    }
    bodies.push_back(b);
  }
  // Only the corners of each planar contact patch: exact for the LCP and the
  // equilibrium LP (contact/contact_reduction.h); `lcp_index` maps the
  // component's contacts to the LCP's (−1: dropped, no force).
  // The contacts in the canonical order, each between two movable parts
  // oriented from the earlier part to the later (`flipped` says which were
  // turned, by the component's contact index).
  // Without `canonical` (CanonicalRanks, computed once per configuration by
  // the caller): the contacts in the file's order and orientation.
  std::vector<int> file_order;
  if (!canonical) {
    file_order.resize(assembly.num_parts());
    std::iota(file_order.begin(), file_order.end(), 0);
  }
  const std::vector<int>& rank = canonical ? *canonical : file_order;
  const auto movable = [&](int p) { return p >= 0 && !assembly.part(p).fixed; };
  std::vector<Contact> oriented(comp.contacts.size());
  if (flipped) flipped->assign(comp.contacts.size(), 0);
  for (size_t k = 0; k < comp.contacts.size(); ++k) {
    const Contact& c = contacts[comp.contacts[k]];
    const bool turn = movable(c.part_a) && movable(c.part_b) && rank[c.part_a] > rank[c.part_b];
    oriented[k] = turn ? FlippedContact(c) : c;
    if (flipped) (*flipped)[k] = turn;
  }
  std::vector<int> order(comp.contacts.size());
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](const Contact& c) {
    return std::make_tuple(rank[c.part_a], c.part_b < 0 ? -1 : rank[c.part_b], c.p_WC.x(),
                           c.p_WC.y(), c.p_WC.z(), c.n_W.x(), c.n_W.y(), c.n_W.z());
  };
  if (canonical)
    std::stable_sort(order.begin(), order.end(),
                     [&](int x, int y) { return key(oriented[x]) < key(oriented[y]); });
  std::vector<Contact> comp_contacts;
  for (int k : order) comp_contacts.push_back(oriented[k]);
  ContactReductionTolerances reduction;
  reduction.length = length_tol;
  reduction.gap = std::numeric_limits<double>::infinity();  // use_gaps = false below
  const std::vector<int> keep = HullContactSubset(comp_contacts, reduction);
  std::vector<Contact> kept;
  if (lcp_index) lcp_index->assign(comp_contacts.size(), -1);
  for (int i : keep) {
    if (lcp_index) (*lcp_index)[order[i]] = static_cast<int>(kept.size());
    kept.push_back(comp_contacts[i]);
  }
  LcpBuildOptions build;
  build.formulation = formulation;
  build.dt = dt;
  build.storage = storage;
  build.dimension = assembly.dimension();
  build.directions = assembly.friction_directions();
  return BuildContactLcp(std::move(bodies), std::move(kept), build);
}

// Whether every body of the component starts at rest (no velocity of the
// previous step).
bool AllAtRest(const ContactLcp& lcp) {
  for (const BodyDynamics& b : lcp.bodies)
    if (!b.nu_prev.isZero(0.0)) return false;
  return true;
}

// The structure of a component for warm starts (StabilityWorkspace::Entry::key):
// the LCP size, the bodies' part indices, then each contact's part_a, part_b,
// feature, vertex and edge. Visits the key's integers in order, without
// building it.
template <typename Visit>
void ForEachKeyInt(const ContactLcp& lcp, Visit&& visit) {
  visit(lcp.size());
  visit(static_cast<int>(lcp.bodies.size()));
  for (const BodyDynamics& b : lcp.bodies) visit(b.part);
  for (const Contact& c : lcp.contacts) {
    visit(c.part_a);
    visit(c.part_b);
    visit(static_cast<int>(c.feature));
    visit(c.index_a);
    visit(c.index_b);
  }
}

size_t KeySize(const ContactLcp& lcp) { return 2 + lcp.bodies.size() + 5 * lcp.contacts.size(); }

// 64-bit FNV-1a, one integer at a time.
struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void operator()(int v) {
    const auto u = static_cast<std::uint32_t>(v);
    for (int byte = 0; byte < 4; ++byte) {
      h ^= (u >> (8 * byte)) & 0xffU;
      h *= 0x100000001b3ULL;
    }
  }
  // A double's 8 bytes, lowest first.
  void operator()(double v) {
    std::uint64_t u;
    std::memcpy(&u, &v, sizeof u);
    (*this)(static_cast<int>(u & 0xffffffffU));
    (*this)(static_cast<int>(u >> 32));
  }
};

// The hash of the component's structure (the key's integers).
std::uint64_t KeyHash(const ContactLcp& lcp) {
  Fnv1a h;
  ForEachKeyInt(lcp, [&h](int v) { h(v); });
  return h.h;
}

// The hash of the component's bodies alone (StabilityWorkspace::rest_bases).
std::uint64_t BodiesHash(const ContactLcp& lcp) {
  Fnv1a h;
  h(static_cast<int>(lcp.bodies.size()));
  for (const BodyDynamics& b : lcp.bodies) h(b.part);
  return h.h;
}

// Everything a static check's solve of `lcp` depends on (reuse mode): the
// verdict's options, each body's data and each contact's, as numbers. The
// patches are numbered over the whole configuration: here in the order
// the component meets them (which points share a patch is what counts).
std::vector<double> SolutionKey(const ContactLcp& lcp, const StabilityOptions& o) {
  std::vector<double> k = {static_cast<double>(lcp.size()),
                           static_cast<double>(lcp.formulation),
                           lcp.build.dt,
                           static_cast<double>(o.rule),
                           static_cast<double>(o.prove_strong),
                           static_cast<double>(o.conservative),
                           static_cast<double>(lcp.num_directions)};
  const auto add = [&k](const auto& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i) k.push_back(m.data()[i]);
  };
  for (const BodyDynamics& b : lcp.bodies) {
    k.insert(k.end(), {static_cast<double>(b.part), b.mass, static_cast<double>(b.planar),
                       static_cast<double>(b.motion)});
    add(b.inertia), add(b.p_WBcm), add(b.F_ext), add(b.nu_prev), add(b.guide);
    add(b.nu_prescribed);
  }
  std::unordered_map<int, int> patch;
  for (const Contact& c : lcp.contacts) {
    const int own =
        c.patch < 0 ? -1 : patch.emplace(c.patch, static_cast<int>(patch.size())).first->second;
    k.insert(k.end(), {static_cast<double>(c.part_a), static_cast<double>(c.part_b), c.gap, c.mu,
                       static_cast<double>(c.feature), static_cast<double>(c.index_a),
                       static_cast<double>(c.index_b), static_cast<double>(own)});
    add(c.p_WC), add(c.n_W);
  }
  return k;
}

std::uint64_t SolutionHash(const std::vector<double>& key) {
  Fnv1a h;
  for (double v : key) h(v);
  return h.h;
}

bool KeyMatches(const std::vector<int>& key, const ContactLcp& lcp) {
  if (key.size() != KeySize(lcp)) return false;
  size_t i = 0;
  bool same = true;
  ForEachKeyInt(lcp, [&](int v) { same = same && key[i++] == v; });
  return same;
}

std::vector<int> MakeKey(const ContactLcp& lcp) {
  std::vector<int> key;
  key.reserve(KeySize(lcp));
  ForEachKeyInt(lcp, [&key](int v) { key.push_back(v); });
  return key;
}

// The workspace's basis for this component's structure, or null.
LcpBasis* FindBasis(StabilityWorkspace::Impl& ws, std::uint64_t hash, const ContactLcp& lcp) {
  const auto [first, last] = ws.bases.equal_range(hash);
  for (auto it = first; it != last; ++it)
    if (KeyMatches(it->second.key, lcp)) return &it->second.basis;
  return nullptr;
}

// Baraff for a frictionless scene, else Stewart–Trinkle; with a drive always
// Stewart–Trinkle (velocity level); options.formulation overrides both.
Formulation ChooseFormulation(const Assembly& assembly, const StabilityOptions& options,
                              const DriveInputs* drive) {
  return options.formulation.value_or(
      drive || !assembly.IsFrictionless() ? Formulation::kStewartTrinkle : Formulation::kBaraff);
}

// A part tips (rather than slides) when its instantaneous axis passes within
// the larger of these reaches of its centroid: twice its own radius, or half
// the scene's size (dimensionless factors of those lengths).
constexpr double kTipReachParts = 2.0;
constexpr double kTipReachScene = 0.5;

// How a part with centroid motion (lin, ang) moves, given whether it keeps any
// closed contact. `size` is the part's radius about its centroid.
void ClassifyMotion(PartMotion& m, bool keeps_contact, double size, double scene_size) {
  if (!m.moving) {
    m.kind = MotionKind::kAtRest;
    return;
  }
  Vector3 pivot;
  m.kind = ClassifyRigidMotion(m.linear, m.angular, keeps_contact, size, scene_size, &pivot);
  if (m.kind == MotionKind::kTips) m.pivot = pivot;  // made absolute by the caller
}

}  // namespace

MotionKind ClassifyRigidMotion(const Vector3& linear, const Vector3& angular, bool keeps_contact,
                               double size, double scene_size, Vector3* pivot) {
  if (!keeps_contact) return MotionKind::kFalls;
  // The instantaneous axis (Chasles): its point nearest the centroid is
  // r = ω × v / |ω|² (in 2-D the point of zero motion, (−v_y, v_x) / ω). A
  // part tips when that point lies within the scene (about its own size of a
  // contact); a far-away axis is a translation with a little spin.
  const double w2 = angular.squaredNorm();
  if (w2 > 0) {
    const Vector3 r = angular.cross(linear) / w2;
    if (r.norm() <= std::max(kTipReachParts * size, kTipReachScene * scene_size)) {
      if (pivot) *pivot = r;
      return MotionKind::kTips;
    }
  }
  return MotionKind::kSlides;
}

std::vector<ContactLcp> BuildComponentLcps(const Assembly& assembly, const Configuration& config,
                                           const StabilityOptions& options,
                                           const DriveInputs* drive) {
  const Tolerances tol =
      options.tolerances ? *options.tolerances : assembly.MakeTolerances(options.dt);
  const std::vector<Contact> contacts = DetectContacts(assembly, config, tol.length, tol.angle);
  std::vector<ContactLcp> out;
  // In the parts' own order: the margins' linear programs (whose optima do
  // not depend on it) and the benchmarks see the LCPs as the file lists them.
  for (const Component& comp : SplitComponents(assembly, config, contacts, nullptr))
    out.push_back(BuildComponent(
        assembly, config, contacts, comp, ChooseFormulation(assembly, options, drive), options.dt,
        drive, options.lcp_storage, tol.length, nullptr, nullptr, nullptr, &options.loads));
  return out;
}

namespace {

// The fastest point of a body moving with ν = (v, ω) about its centroid c:
// max |v + ω × (x − c)| over its vertices x.
double LargestPointMotion(const Vector6& nu, const Vector3& c,
                          const std::vector<Vector3>& vertices) {
  double out = 0;
  for (const Vector3& x : vertices)
    out = std::max(out, (nu.head<3>() + nu.tail<3>().cross(x - c)).norm());
  return out;
}

// The motion (velocity or acceleration) of a's material point at the
// contact over b's, from the bodies' motions (a part outside the component,
// fixed or the world, is at rest).
Vector3 RelativeMotion(const ContactLcp& lcp, const ContactSolution& s, const Contact& c) {
  Vector3 u = Vector3::Zero();
  for (size_t b = 0; b < lcp.bodies.size(); ++b) {
    const double sign = lcp.bodies[b].part == c.part_a   ? 1.0
                        : lcp.bodies[b].part == c.part_b ? -1.0
                                                         : 0.0;
    if (sign == 0.0) continue;
    const Vector6& nu = s.body_motion[b];
    u += sign * (nu.head<3>() + nu.tail<3>().cross(c.p_WC - lcp.bodies[b].p_WBcm));
  }
  return u;
}

// The contact motions of a virtual motion `nu` of the bodies (a mechanism,
// or a collapse when loaded from rest): no forces.
ContactSolution VirtualMotion(const ContactLcp& lcp, const std::vector<Vector6>& nu) {
  ContactSolution s;
  const int nc = static_cast<int>(lcp.contacts.size());
  s.body_motion = nu;
  s.normal_force = VectorX::Zero(nc);
  s.friction_force.assign(nc, Vector3::Zero());
  s.normal_motion = VectorX::Zero(nc);
  s.tangent_motion.assign(nc, Vector3::Zero());
  for (int c = 0; c < nc; ++c) {
    const Contact& ct = lcp.contacts[c];
    s.normal_motion[c] = lcp.normal_rows[c].Dot(nu);
    if (lcp.tangent2_rows.empty()) {
      s.tangent_motion[c] = ct.t_W() * lcp.tangent_rows[c].Dot(nu);
    } else {
      const auto [t1, t2] = TangentBasis(ct.n_W);
      s.tangent_motion[c] = t1 * lcp.tangent_rows[c].Dot(nu) + t2 * lcp.tangent2_rows[c].Dot(nu);
    }
  }
  return s;
}

// The per-component report of a solve (ComponentReport's solver fields).
ComponentReport ReportSolve(const Component& comp, const ContactLcp& lcp,
                            const ComponentSolution& s) {
  ComponentReport report;
  report.parts = comp.parts;  // canonical order (BuildComponent); the report lists them ascending
  std::sort(report.parts.begin(), report.parts.end());
  report.num_contacts = static_cast<int>(comp.contacts.size());
  report.lcp_size = lcp.size();
  report.decided_by = s.decided_by;
  report.stability = s.stability;
  report.status = s.lemke_tried ? s.lemke.status : LcpStatus::kSolved;
  if (s.decided_by == DecidedBy::kEquilibrium || s.decided_by == DecidedBy::kRestHypothesis)
    report.status = LcpStatus::kSolved;
  report.pivots = s.lemke.pivots;
  report.residual = s.residual;
  report.warm_start_used = s.lemke.warm_start_used;
  report.rest_solution =
      s.decided_by == DecidedBy::kEquilibrium || s.decided_by == DecidedBy::kRestHypothesis;
  report.lp_iterations = s.lp_iterations;
  if (s.equilibrium && s.equilibrium->solved) report.static_equilibrium = s.equilibrium->exists;
  report.frictionless_equilibrium = s.frictionless_equilibrium;
  if (s.equilibrium) report.equilibrium_method = s.equilibrium->method;
  for (int b : s.held) report.held.push_back(lcp.bodies[b].part);
  if (s.mechanism && s.mechanism->found) {
    report.mechanism_power = s.mechanism->power;
    for (int b : s.mechanism->moving) report.mechanism_parts.push_back(lcp.bodies[b].part);
  }
  if (s.loaded) {
    report.loaded_from_rest = s.loaded->outcome;
    report.loaded_unbalanced = s.loaded->equilibrium_residual;
    for (size_t b = 0; b < s.loaded->unbalanced.size(); ++b)
      if (s.loaded->outcome == LoadedFromRest::Outcome::kGivesWay &&
          s.loaded->unbalanced[b] > s.loaded->tolerance)
        report.loaded_gives_way.push_back(lcp.bodies[b].part);
  }
  for (int b : s.rigid_motion) report.rigid_motion_parts.push_back(lcp.bodies[b].part);
  if (s.search) {
    report.search = s.search->outcome;
    report.search_nodes = s.search->nodes;
    report.search_open = s.search->open;
  }
  for (size_t i = 0; i < s.notes.size(); ++i) report.message += (i ? "; " : "") + s.notes[i];
  return report;
}

// What the components prove about rest, for the whole configuration: none
// when something moves that no equilibrium could hold, weak when it moves
// although one could (jamming), else the weakest of the components' proofs.
StabilityProof Summarize(const StabilityResult& r) {
  if (r.verdict == Verdict::kUnstable)
    return r.weakly_stable ? StabilityProof::kWeak : StabilityProof::kNone;
  if (r.verdict != Verdict::kStable) return StabilityProof::kNone;
  StabilityProof out = StabilityProof::kStrong;
  for (const ComponentReport& c : r.components) {
    if (c.stability == StabilityProof::kWeak) return StabilityProof::kWeak;
    if (c.stability != StabilityProof::kStrong) out = StabilityProof::kNotCertified;
  }
  return out;
}

// The least favourable loaded-from-rest outcome over the components: gives
// way, failed, not run, stands (empty when none was loaded).
std::optional<LoadedFromRest::Outcome> LeastFavourable(const StabilityResult& r) {
  std::optional<LoadedFromRest::Outcome> out;
  const auto rank = [](LoadedFromRest::Outcome o) {
    switch (o) {
      case LoadedFromRest::Outcome::kGivesWay:
        return 3;
      case LoadedFromRest::Outcome::kFailed:
        return 2;
      case LoadedFromRest::Outcome::kNotRun:
        return 1;
      case LoadedFromRest::Outcome::kStands:
        return 0;
    }
    return 0;
  };
  for (const ComponentReport& c : r.components)
    if (c.loaded_from_rest && (!out || rank(*c.loaded_from_rest) > rank(*out)))
      out = c.loaded_from_rest;
  return out;
}

}  // namespace

namespace {

// AnalyzeConfiguration's stages over the state they share: the options, the
// contacts and components of the configuration, and the result being filled.
class ConfigurationAnalysis {
 public:
  ConfigurationAnalysis(const Assembly& assembly, const Configuration& config,
                        const StabilityOptions& options, const DriveInputs* drive,
                        StabilityWorkspace* workspace)
      : assembly_(assembly),
        config_(config),
        options_(options),
        drive_(drive),
        workspace_(workspace),
        static_check_(drive == nullptr) {
    result_.dt = options.dt;
    result_.tolerances =
        options.tolerances ? *options.tolerances : assembly.MakeTolerances(options.dt);
    result_.formulation = ChooseFormulation(assembly, options, drive);
    result_.rule = options.rule;
    st_ = result_.formulation == Formulation::kStewartTrinkle;
    motion_tol_ = st_ ? result_.tolerances.velocity : result_.tolerances.acceleration;
  }

  StabilityResult Run() {
    Detect();
    for (int ci = 0; ci < static_cast<int>(components_.size()); ++ci) AnalyzeComponent(ci);
    Conclude();
    return std::move(result_);
  }

 private:
  // DetectContacts, then SplitComponents; each part's vertices, once (the
  // point motions are measured at them).
  void Detect() {
    const Tolerances& tol = result_.tolerances;
    const auto t0 = Clock::now();
    contacts_ = DetectContacts(assembly_, config_, tol.length, tol.angle, nullptr,
                               workspace_ ? &workspace_->impl().contacts : nullptr);
    result_.profile.detect = Seconds(t0);
    rank_ = CanonicalRanks(assembly_, config_);
    components_ = SplitComponents(assembly_, config_, contacts_, &rank_);
    result_.contacts.resize(contacts_.size());
    for (size_t c = 0; c < contacts_.size(); ++c) result_.contacts[c].contact = contacts_[c];
    vertices_.resize(assembly_.num_parts());
    for (const Component& comp : components_)
      for (int p : comp.parts) vertices_[p] = config_.WorldVertices(assembly_, p);
  }

  // One component: BuildContactLcp, SolveComponent, the report of the solve,
  // RecoverSolution, ClassifyMotion.
  void AnalyzeComponent(int ci) {
    const Component& comp = components_[ci];
    auto t0 = Clock::now();
    std::vector<int> lcp_index;
    std::vector<char> flipped;
    const ContactLcp lcp =
        BuildComponent(assembly_, config_, contacts_, comp, result_.formulation, options_.dt,
                       drive_, options_.lcp_storage, result_.tolerances.length, &lcp_index,
                       &flipped, &rank_, &options_.loads);
    result_.profile.build += Seconds(t0);

    t0 = Clock::now();
    const ComponentSolution s = Solve(comp, lcp);
    result_.profile.solve += Seconds(t0);
    ComponentReport report = Record(ci, comp, lcp, s);

    // RecoverSolution: from the verified LCP solution, or the mechanism's
    // virtual motion.
    t0 = Clock::now();
    std::optional<ContactSolution> phys;
    const ContactLcp& solved = s.held_lcp ? *s.held_lcp : lcp;
    if (s.has_solution)
      phys = RecoverSolution(solved, s.z);
    else if (!s.collapse.empty())
      phys = VirtualMotion(lcp, s.collapse);
    else if (s.mechanism && s.mechanism->found)
      phys = VirtualMotion(lcp, s.mechanism->nu);
    if (!phys) {
      // No motion known: undecided, unless the verdict is that every part
      // gives way (a conservative verdict that did not seek how).
      if (s.gives_way_unexplained)
        any_moving_ = true;
      else if (s.decided_by != DecidedBy::kJammed)
        any_undecided_ = true;
      for (int p : comp.parts) {
        PartMotion m;
        m.part = p;
        m.component = ci;
        m.role = RoleOf(drive_, p);
        m.moving = s.gives_way_unexplained && m.role == PartRole::kJudged;
        result_.parts.push_back(m);
      }
      result_.components.push_back(report);
      return;
    }
    report.consistency_residual = phys->consistency_residual;
    // ClassifyMotion: contacts first, then parts.
    const std::vector<bool> keeps_contact = ClassifyContacts(comp, lcp, lcp_index, flipped, *phys);
    ClassifyParts(ci, comp, lcp, *phys, keeps_contact);
    result_.profile.classify += Seconds(t0);
    result_.components.push_back(report);
  }

  // SolveComponent: the policy of stability/solve_component.h, with the
  // workspace's warm starts.
  ComponentSolution Solve(const Component& comp, const ContactLcp& lcp) {
    SolveContext ctx;
    ctx.lemke = options_.lemke;
    ctx.static_check = static_check_;
    ctx.rule = options_.rule;
    ctx.prove_strong = options_.prove_strong;
    ctx.conservative = options_.conservative;
    // Whether an LCP solution moves a part that must stay put.
    ctx.moves = [this](const ContactLcp& l, const VectorX& z) {
      const ContactSolution sol = RecoverSolution(l, z);
      for (size_t b = 0; b < l.bodies.size(); ++b) {
        const int p = l.bodies[b].part;
        if (RoleOf(drive_, p) != PartRole::kJudged) continue;
        if (LargestPointMotion(sol.body_motion[b], l.bodies[b].p_WBcm, vertices_[p]) > motion_tol_)
          return true;
      }
      return false;
    };
    bool carried = false;
    for (int p : comp.parts) {
      const PartRole role = RoleOf(drive_, p);
      ctx.has_guided |= role == PartRole::kGuided;
      ctx.has_driven |= IsDriven(role);
      carried |= role == PartRole::kCarried;
    }
    // The rest hypothesis (StabilityOptions::rest_first): a driven 3-D
    // component with friction whose every part is judged or driven (a carried
    // part's motion is what the LCP must find).
    ctx.rest_first = options_.rest_first && !static_check_ && assembly_.is_3d() && st_ &&
                     lcp.num_friction > 0 && ctx.has_driven && !carried;
    // A component of a path's tick that nothing drives and that starts at
    // rest (tick 0, before the gripper moves) is a static check, decided as
    // `cairn check` decides it (one verdict: the equilibrium first, and the
    // rule where rigid bodies leave it open), rather than by Lemke's method
    // on the whole component (Jenga: 18 ms against 10). Small components
    // keep Lemke's forces where it finds rest (SolveComponent).
    if (!ctx.has_driven && AllAtRest(lcp)) ctx.static_check = true;
    if (workspace_ && workspace_->impl().reuse && ctx.static_check && !drive_)
      return Reused(lcp, ctx);
    std::uint64_t hash = 0;
    LcpBasis* basis = nullptr;
    if (workspace_) {
      hash = KeyHash(lcp);
      basis = FindBasis(workspace_->impl(), hash, lcp);
      ctx.warm_start = basis;
      if (ctx.rest_first) ctx.rest_warm = &workspace_->impl().rest_bases[BodiesHash(lcp)];
    }
    ComponentSolution s = SolveComponent(lcp, ctx);
    if (workspace_ && s.decided_by == DecidedBy::kLemke) {
      // A warm start returns the basis it was given: nothing to store.
      if (!basis)
        workspace_->impl().bases.emplace(
            hash, StabilityWorkspace::Impl::Entry{MakeKey(lcp), std::move(s.lemke.basis)});
      else if (!s.lemke.warm_start_used)
        *basis = std::move(s.lemke.basis);
      if (s.lemke.warm_start_used) ++workspace_->impl().warm_starts;
    }
    if (options_.check_equilibrium && !static_check_) {
      const StaticEquilibrium eq = FindStaticEquilibrium(lcp);
      if (eq.solved) s.equilibrium = eq;
    }
    return s;
  }

  // Reuse mode (StabilityWorkspace::set_reuse_solutions): the kept
  // solution of the same data, else a cold solve, kept.
  ComponentSolution Reused(const ContactLcp& lcp, const SolveContext& ctx) {
    StabilityWorkspace::Impl& w = workspace_->impl();
    std::vector<double> key = SolutionKey(lcp, options_);
    const std::uint64_t hash = SolutionHash(key);
    const auto [first, last] = w.solutions.equal_range(hash);
    for (auto it = first; it != last; ++it)
      if (it->second.first == key) {
        ++w.reused;
        return it->second.second;
      }
    ComponentSolution s = SolveComponent(lcp, ctx);
    if (w.solutions.size() >= kKeptSolutions) w.solutions.clear();
    w.solutions.emplace(hash, std::make_pair(std::move(key), s));
    return s;
  }

  // The component's report, the jammed parts and the diagnostics line.
  ComponentReport Record(int ci, const Component& comp, const ContactLcp& lcp,
                         const ComponentSolution& s) {
    ComponentReport report = ReportSolve(comp, lcp, s);
    // A driven part whose prescribed motion no contact forces allow is
    // jammed: the path drives it into something that cannot give way.
    if (s.decided_by == DecidedBy::kJammed) {
      report.message = "the gripper's motion is blocked (no contact forces allow it)" +
                       (report.message.empty() ? "" : "; " + report.message);
      for (int p : comp.parts)
        if (IsDriven(RoleOf(drive_, p))) result_.jammed.push_back(p);
    }
    if (!report.message.empty())
      result_.diagnostics += "component " + std::to_string(ci) + " (" +
                             std::to_string(comp.parts.size()) + " parts, " +
                             std::to_string(lcp.size()) + " LCP variables): decided by " +
                             to_string(s.decided_by) + ": " + report.message + "; ";
    for (int c : comp.contacts) result_.contacts[c].component = ci;
    return report;
  }

  // Each contact's forces and relative motion, and whether it breaks or
  // slides; whether each body keeps a closed contact.
  std::vector<bool> ClassifyContacts(const Component& comp, const ContactLcp& lcp,
                                     const std::vector<int>& lcp_index,
                                     const std::vector<char>& flipped,
                                     const ContactSolution& phys) {
    std::vector<bool> keeps_contact(comp.parts.size(), false);
    for (size_t k = 0; k < comp.contacts.size(); ++k) {
      ContactReport& cr = result_.contacts[comp.contacts[k]];
      if (const int m = lcp_index[k]; m >= 0) {
        // The LCP's contact may be seen from the other side (BuildComponent):
        // the force on a and a's motion over b turn with it.
        const double side = flipped[k] ? -1.0 : 1.0;
        cr.normal_force = phys.normal_force(m);
        cr.friction_force = side * phys.friction_force[m];
        cr.normal_motion = phys.normal_motion(m);
        cr.tangent_motion = side * phys.tangent_motion[m];
      } else {  // a dropped point of a patch: no force, the bodies' motion
        const Vector3 u = RelativeMotion(lcp, phys, cr.contact);
        cr.normal_force = 0;
        cr.friction_force.setZero();
        cr.normal_motion = u.dot(cr.contact.n_W);
        cr.tangent_motion = u - cr.normal_motion * cr.contact.n_W;
      }
      cr.breaking = cr.normal_motion > motion_tol_;
      cr.sliding = !cr.breaking && cr.tangent_motion.norm() > motion_tol_;
      if (!cr.breaking) {
        for (size_t b = 0; b < comp.parts.size(); ++b)
          if (comp.parts[b] == cr.contact.part_a || comp.parts[b] == cr.contact.part_b)
            keeps_contact[b] = true;
      }
    }
    return keeps_contact;
  }

  // Each part's motion and its kind; judged parts that move, guided parts
  // off their path.
  void ClassifyParts(int ci, const Component& comp, const ContactLcp& lcp,
                     const ContactSolution& phys, const std::vector<bool>& keeps_contact) {
    for (size_t b = 0; b < comp.parts.size(); ++b) {
      const int p = comp.parts[b];
      PartMotion m;
      m.part = p;
      m.component = ci;
      m.linear = phys.body_motion[b].head<3>();
      m.angular = phys.body_motion[b].tail<3>();
      const Vector3 c = lcp.bodies[b].p_WBcm;
      double radius = 0;
      for (const Vector3& v : vertices_[p]) radius = std::max(radius, (v - c).norm());
      m.point_motion = LargestPointMotion(phys.body_motion[b], c, vertices_[p]);
      m.role = RoleOf(drive_, p);
      m.moving = m.point_motion > motion_tol_;
      ClassifyMotion(m, keeps_contact[b], radius, assembly_.scene_size());
      if (m.pivot) m.pivot = *m.pivot + c;
      switch (m.role) {
        case PartRole::kJudged:
          if (m.moving) any_moving_ = true;
          break;
        case PartRole::kGuided: {
          // Off-path motion: everything but the gripper's own velocity.
          const Vector3 v_g = drive_->velocity[p];
          double off = 0;
          for (const Vector3& v : vertices_[p])
            off = std::max(off, (m.linear - v_g + m.angular.cross(v - c)).norm());
          if (off > motion_tol_) result_.unsupported.push_back(p);
          break;
        }
        case PartRole::kCarried:
        case PartRole::kPrescribed:
          break;
      }
      result_.parts.push_back(m);
    }
  }

  // The verdict, and what is proved about rest.
  void Conclude() {
    StabilityResult& r = result_;
    std::sort(r.parts.begin(), r.parts.end(),
              [](const PartMotion& x, const PartMotion& y) { return x.part < y.part; });
    for (const PartMotion& m : r.parts)
      if (m.moving && m.role == PartRole::kJudged) r.moving.push_back(m.part);
    std::sort(r.unsupported.begin(), r.unsupported.end());
    std::sort(r.jammed.begin(), r.jammed.end());
    // Unstable when a part that should stay put moves, or a driven part
    // cannot move as the gripper says; undecided only when no solve,
    // equilibrium or mechanism could decide a component (a defect, reported);
    // else stable. (A guided part off its path is the caller's concern: see
    // `unsupported`.)
    r.verdict = (any_moving_ || !r.jammed.empty())
                    ? Verdict::kUnstable
                    : (any_undecided_ ? Verdict::kSolverFailure : Verdict::kStable);
    bool all = true, known = true;
    for (const ComponentReport& c : r.components) {
      known = known && c.static_equilibrium.has_value();
      all = all && c.static_equilibrium.value_or(false);
    }
    if (known && (static_check_ || options_.check_equilibrium)) r.static_equilibrium = all;
    r.weakly_stable =
        r.verdict == Verdict::kUnstable && r.jammed.empty() && r.static_equilibrium.value_or(false);
    if (static_check_) {
      r.stability = Summarize(r);
      r.loaded_from_rest = LeastFavourable(r);
    }
  }

  const Assembly& assembly_;
  const Configuration& config_;
  const StabilityOptions& options_;
  const DriveInputs* drive_;
  StabilityWorkspace* workspace_;
  const bool static_check_;
  bool st_ = false;        // Stewart–Trinkle (velocities) rather than Baraff
  double motion_tol_ = 0;  // velocity or acceleration tolerance of a point
  std::vector<Contact> contacts_;
  std::vector<int> rank_;  // CanonicalRanks of the configuration, once
  std::vector<Component> components_;
  std::vector<std::vector<Vector3>> vertices_;  // per part, world frame
  bool any_moving_ = false, any_undecided_ = false;
  StabilityResult result_;
};

}  // namespace

StabilityResult AnalyzeConfiguration(const Assembly& assembly, const Configuration& config,
                                     const StabilityOptions& options, const DriveInputs* drive,
                                     StabilityWorkspace* workspace) {
  return ConfigurationAnalysis(assembly, config, options, drive, workspace).Run();
}

}  // namespace cairn

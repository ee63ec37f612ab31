// Build orders with temporary holds (planning/sequence.h, docs/sequence.md).

#include "cairn/planning/sequence.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cairn/mechanics/loaded_from_rest.h"
#include "cairn/mechanics/subset_equilibrium.h"
#include "cairn/planning/blocking.h"
#include "cairn/planning/fixtures.h"

namespace cairn {

const char* to_string(TemporaryKind kind) {
  switch (kind) {
    case TemporaryKind::kHold:
      return "hold";
    case TemporaryKind::kProp:
      return "prop";
  }
  return "?";
}

namespace {

// The most assemblies with parts held kept at once (Assembly::WithHeld): each
// is a copy of the scene's parts, and a beam meets a few hold sets per step.
constexpr size_t kMaxHeldAssemblies = 64;

// With a time limit, the share of it the search gets; the confirmation of
// its order by the check's verdict gets the rest. After a stop (Ctrl-C),
// the confirmation gets kConfirmAfterStop seconds.
constexpr double kSearchShare = 0.75;
constexpr double kConfirmAfterStop = 5.0;

// The lower bound by exhaustion: on models of at most this many movable
// parts (2ⁿ sets of parts), and up to this many supports at once.
constexpr int kExhaustiveParts = 10;
constexpr int kExhaustiveHolds = 3;

// The most LP bases kept (ComponentStands; a basis is two ints a row, 9 KB
// for the whole cross vault, 18 KB for the Armadillo): beyond, the cache
// starts afresh (the search needs only those of the beam's states).
constexpr size_t kMaxBases = 10000;

// On models of more movable parts than this, the beam's states are
// confirmed by the verdict from the start (Confirmed): a rejection found by
// the confirmation of the whole order would send the search back over a
// long way (the cross vault's 21st state of 180, the Armadillo's 10th of
// 366), and an order stopped by its time limit is cut at its first
// rejected state. On smaller ones the LP alone leads the search, and the
// few repairs cost less than a verdict at every depth (the 28-voussoir
// arch: 0.7 s against 1.7 s).
constexpr size_t kConfirmBeamFromParts = 60;

// The factor by which the loading LCP counted on the assembled contacts
// must exceed loading from rest's budget for the beam to take the verdict
// to be the equilibrium (VerdictIsTheEquilibrium; dimensionless).
constexpr double kLoadingBudgetMargin = 1.25;

// The most parts the check says move that are tried as the hold that makes a
// new state stand (after the part just placed).
constexpr int kMaxMovingTried = 3;

// The most prop points tried per part, the ones that most oppose its motion
// (SuggestFixtures' ranking), and the least opposition that counts, relative
// to the fastest point's speed (dimensionless: roundoff of a unit motion).
constexpr int kMaxPropsTried = 6;
constexpr double kLeastOpposition = 1e-6;

// A support of a state: a hold of `part`, or the prop `prop` (an index into
// the search's prop points) under it.
struct Support {
  TemporaryKind kind = TemporaryKind::kHold;
  int part = -1;
  int prop = -1;
  bool operator==(const Support& o) const {
    return kind == o.kind && part == o.part && prop == o.prop;
  }
  bool operator<(const Support& o) const {
    return std::tie(kind, part, prop) < std::tie(o.kind, o.part, o.prop);
  }
};

// ",h12" for a hold of part 12, ",p34" for prop point 34, in sorted order: a
// key for a set of supports.
std::string SupportKey(std::vector<Support> supports) {
  std::sort(supports.begin(), supports.end());
  std::string key;
  for (const Support& t : supports)
    key += t.kind == TemporaryKind::kHold ? ",h" + std::to_string(t.part)
                                          : ",p" + std::to_string(t.prop);
  return key;
}

// What a hold on `h` carries in the state checked as `r`: the force and the
// torque (about h's centroid) that balance h's weight and the contact forces
// of the free parts on it (force units, world).
std::pair<Vector3, Vector3> HoldWrench(const Assembly& assembly, int h, const StabilityResult& r) {
  const Part& part = assembly.part(h);
  Vector3 force = part.mass * assembly.gravity(), torque = Vector3::Zero();
  for (const ContactReport& c : r.contacts) {
    const Vector3 f = c.normal_force * c.contact.n_W + c.friction_force;  // on a
    const double sign = c.contact.part_a == h ? 1.0 : c.contact.part_b == h ? -1.0 : 0.0;
    if (sign == 0) continue;
    force += sign * f;
    torque += (c.contact.p_WC - part.centroid).cross(sign * f);
  }
  return {-force, -torque};
}

// One state of the beam: the parts placed, the supports in place (oldest
// first), and how it got there.
struct State {
  std::vector<bool> placed;
  std::vector<Support> supports;
  std::vector<SequenceStep> steps;
  int max_in_place = 0;
  int placements = 0;
  double height = 0;  // Σ of the placed parts' centroid heights against gravity (length)
  std::string names;  // the order's names, for ties
  int parent = -1;    // its parent's place in the beam it grew from (RunBeam)
  // The parts not placed that can no longer arrive (Stranded): an order
  // through this state can never be finished.
  int stranded = 0;
};

// A state's check, as the search needs it: whether it stands and, when it
// does not, the parts that cannot (those of the components without an
// equilibrium, or those the verdict says move).
struct Check {
  bool stands = false;
  std::vector<int> moving;
};

// The threads to run on: `requested`, or (≤ 0) the machine's.
int ThreadCount(int requested) {
  return requested > 0 ? requested
                       : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
}

// The parts held (kHold) or the prop points (kProp) of `supports`, sorted.
std::vector<int> SortedOf(const std::vector<Support>& supports, TemporaryKind kind) {
  std::vector<int> out;
  for (const Support& t : supports)
    if (t.kind == kind) out.push_back(kind == TemporaryKind::kHold ? t.part : t.prop);
  std::sort(out.begin(), out.end());
  return out;
}
std::vector<int> HeldOf(const std::vector<Support>& s) { return SortedOf(s, TemporaryKind::kHold); }
std::vector<int> PropsOf(const std::vector<Support>& s) {
  return SortedOf(s, TemporaryKind::kProp);
}

class Search {
 public:
  Search(const Assembly& assembly, const SequenceOptions& options);
  BuildSequence Run();

 private:
  // Stages of Run, in order.
  bool CheckAssembled();
  void ComputeAdjacencyAndBlocking();
  void ComputeBlocks();
  void ComputePropPoints(const std::vector<Contact>& assembled);
  void RunBeam(const State& start);
  void ComputeLowerBound();
  void ArgueLowerBound();
  void ExhaustiveLowerBound();
  int ConfirmAndMeasureHolds();
  std::vector<char> ConfirmStates(int n, const std::function<void(int, int)>& check);
  void MeasureStep(const StabilityResult& r, const std::vector<Support>& supports,
                   SequenceStep& step) const;
  State Prefix(int steps) const;
  void Apply(const SequenceStep& step, std::vector<Support>& supports) const;
  bool Confirmed(const State& s);
  bool AnyArrives(const std::vector<State>& beam) const;
  void WithOneSupportMore(const std::vector<State>& beam, const std::vector<State>& turned_down,
                          std::vector<State>& next);

  std::vector<State> Expand(const State& s);
  std::optional<State> Place(const State& s, int part, const Vector3& arrival,
                             std::optional<TemporaryKind> new_support);
  std::optional<std::vector<Support>> OneSupportMore(const State& s,
                                                     const std::vector<bool>& placed, int part,
                                                     const Check& as_is, TemporaryKind kind);
  std::vector<int> PropsFor(const StabilityResult& failing, int part) const;
  std::optional<Vector3> Arrival(const std::vector<bool>& placed, int part) const;
  std::vector<std::pair<int, Vector3>> Candidates(const State& s) const;
  int Stranded(const State& s, int part) const;
  const Check& Stands(const std::vector<bool>& placed, const std::vector<Support>& supports);
  const Check& StandsHeld(const std::vector<bool>& placed, const std::vector<int>& held);
  std::vector<std::vector<int>> FreeComponents(const std::vector<bool>& placed,
                                               const std::vector<int>& held) const;
  const Check& ComponentStands(const std::vector<bool>& placed,
                               const std::vector<Support>& supports,
                               const std::vector<int>& component);
  bool VerdictIsTheEquilibrium(const std::vector<int>& component,
                               const std::vector<bool>& present) const;
  std::pair<std::vector<Support>, std::string> ComponentKey(
      const std::vector<Support>& supports, const std::vector<int>& component) const;
  std::optional<SubsetEquilibrium::Basis> StartingBasis(const std::vector<Support>& supports,
                                                        const std::vector<int>& component) const;
  Check Evaluate(const std::vector<bool>& placed, const std::vector<Support>& supports,
                 const SubsetEquilibrium::Basis* start = nullptr,
                 std::optional<SubsetEquilibrium::Basis>* end = nullptr, bool filtered = false);
  Check FilterByLp(const std::vector<bool>& placed, const std::vector<int>& held, bool& unsure,
                   const SubsetEquilibrium::Basis* start = nullptr,
                   std::optional<SubsetEquilibrium::Basis>* end = nullptr);
  Configuration ConfigOf(const std::vector<bool>& placed) const;
  const Assembly& SupportAssembly(const std::vector<int>& held, const std::vector<int>& props);
  Assembly WithSupports(const std::vector<int>& held, const std::vector<int>& props) const;
  TemporarySupport Public(const Support& t) const;
  std::string SupportNames(std::vector<Support> supports) const;
  Support Internal(const TemporarySupport& t) const;
  bool Better(const State& a, const State& b) const;
  bool Stopped();
  bool ConfirmationOutOfTime();

  const Assembly& assembly_;
  const SequenceOptions& options_;
  Vector3 up_;
  std::vector<int> movable_;
  std::vector<TemporaryKind> kinds_;        // the kinds of support allowed, holds first
  std::vector<std::vector<int>> touching_;  // per part: the parts it touches assembled
  // The assembled contact points: their parts (a part < 0: a fixture) and
  // whether they have friction; the friction directions D per contact.
  struct AssembledContact {
    int a = -1, b = -1;
    bool frictional = false;
  };
  std::vector<AssembledContact> assembled_contacts_;
  int friction_directions_ = 0;
  std::vector<Vector3> directions_;              // removal directions
  std::vector<BlockingGraph> graphs_;            // per direction, to infinity
  std::vector<std::vector<int>> blocks_;         // per part: the parts it blocks in some direction
  std::unordered_map<std::string, Check> memo_;  // by state
  std::unordered_map<std::string, Check> component_memo_;  // by component of a state
  // The LP's basis of each component that stands, by its key (ComponentKey):
  // the start of the LPs of the components it joins when a part is placed.
  std::unordered_map<std::string, SubsetEquilibrium::Basis> bases_;
  // The part Place is placing and the supports of the state it is placed
  // in (null: not placing): where the LPs start (StartingBasis).
  // `hint`: what the LPs' proofs of infeasibility are kept by
  // (SubsetEquilibrium::Solve): the part placed, or the support taken out
  // (a state fails again and again by the same mechanism: the part that
  // cannot yet be placed, the cantilever a hold still carries).
  struct From {
    int part = -1;
    const std::vector<Support>* supports = nullptr;
    int hint = -1;
  } from_;
  // The filter: the assembled configuration's equilibrium LP per contact
  // component, kept between states (mechanics/subset_equilibrium.h), and
  // where each movable part is in it.
  std::vector<SubsetEquilibrium> subsets_;
  std::vector<std::vector<int>> subset_parts_;  // per component: its bodies' parts
  std::vector<int> subset_solves_;              // per component: its LP's solves so far
  std::map<std::pair<std::vector<int>, std::vector<int>>, Assembly> support_assemblies_;
  // The prop points (faces free in the assembled configuration) and, per
  // part, its points' indices (`--temporary prop|both`).
  std::vector<FacePoint> props_;
  std::vector<std::vector<int>> part_props_;
  StabilityWorkspace workspace_;
  BuildSequence out_;
  State best_;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
  std::chrono::steady_clock::time_point confirm_deadline_ =
      std::chrono::steady_clock::time_point::max();
  // False: a state stands when the LP finds an equilibrium (the filter);
  // true: by the check's verdict (after a confirmation rejected a state).
  bool full_ = false;
  // The states entering the beam are confirmed by the verdict (Confirmed):
  // after the confirmation of an order rejected a state the LP passed.
  bool confirm_beam_ = false;
  bool stop_seen_ = false;     // ConfirmationOutOfTime has seen the stop
  int unconfirmed_from_ = -1;  // the first step the confirmation had no time for
  // True while the lower bound is computed: the LPs' claims of infeasibility
  // are proofs (SubsetEquilibrium::set_checked).
  bool proving_ = false;
  // True while the beam searches: the verdict may reject a state the full
  // one accepts, never the reverse (StabilityOptions::conservative), which
  // the confirmation of the order then passes. Off for the assembled
  // state's check and the lower bound, whose answers are proofs.
  bool conservative_ = false;
  // How states are decided, in the caches' keys: by the filter, or by the
  // verdict (full_).
  std::string FilterMode() const {
    return std::string(proving_ ? "|proof" : "|lp") + (conservative_ ? "c" : "");
  }
  std::string Mode() const {
    return full_ ? std::string("|full") + (conservative_ ? "c" : "") : FilterMode();
  }
  // The verdict's options as the search stands (conservative_).
  StabilityOptions Verdict() const {
    StabilityOptions o = options_.stability;
    o.conservative = conservative_;
    return o;
  }
};

Search::Search(const Assembly& assembly, const SequenceOptions& options)
    : assembly_(assembly), options_(options) {
  const Vector3& g = assembly.gravity();
  up_ = g.norm() > 0 ? Vector3(-g / g.norm())
                     : (assembly.is_3d() ? Vector3(0, 0, 1) : Vector3(0, 1, 0));
  for (int p = 0; p < assembly.num_parts(); ++p)
    if (!assembly.part(p).fixed && !assembly.part(p).tool) movable_.push_back(p);
  directions_ = options.directions;
  if (directions_.empty()) directions_.push_back(up_);
  for (Vector3& d : directions_) {
    if (!d.allFinite() || d.norm() == 0)
      throw std::invalid_argument("a removal direction is zero or not finite");
    d.normalize();
    if (!assembly.is_3d()) d.z() = 0;
  }
  if (options.beam_width < 1) throw std::invalid_argument("beam_width must be at least 1");
  if (!options.holds && !options.props)
    throw std::invalid_argument("no kind of temporary support allowed (holds, props)");
  if (options.holds) kinds_.push_back(TemporaryKind::kHold);
  if (options.props) kinds_.push_back(TemporaryKind::kProp);
  if (!(options.time_limit >= 0) || !std::isfinite(options.time_limit))
    throw std::invalid_argument("time_limit must be finite and at least 0");
  if (options.time_limit > 0) {
    // The search gets kSearchShare of the time, the confirmation the rest.
    const auto now = std::chrono::steady_clock::now();
    const auto after = [&](double seconds) {
      return now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                       std::chrono::duration<double>(seconds));
    };
    deadline_ = after(kSearchShare * options.time_limit);
    confirm_deadline_ = after(options.time_limit);
  }
}

// The time limit passed, or a stop was asked for (once true, true for good).
// The confirmation's time is up: the time limit, or kConfirmAfterStop after
// a stop that was not the time limit's.
bool Search::ConfirmationOutOfTime() {
  const auto now = std::chrono::steady_clock::now();
  if (options_.stop && options_.stop() && !stop_seen_) {
    stop_seen_ = true;
    confirm_deadline_ = std::min(
        confirm_deadline_, now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                     std::chrono::duration<double>(kConfirmAfterStop)));
  }
  return now >= confirm_deadline_;
}

bool Search::Stopped() {
  if (out_.stopped) return true;
  out_.stopped =
      std::chrono::steady_clock::now() >= deadline_ || (options_.stop && options_.stop());
  return out_.stopped;
}

// ---- The state check, cached ---------------------------------------------

const Assembly& Search::SupportAssembly(const std::vector<int>& held,
                                        const std::vector<int>& props) {
  if (held.empty() && props.empty()) return assembly_;
  const auto key = std::make_pair(held, props);
  auto it = support_assemblies_.find(key);
  if (it != support_assemblies_.end()) return it->second;
  if (support_assemblies_.size() >= kMaxHeldAssemblies) support_assemblies_.clear();
  return support_assemblies_.emplace(key, WithSupports(held, props)).first->second;
}

// The scene with the parts `held` fixed and the props `props` as fixels.
Assembly Search::WithSupports(const std::vector<int>& held, const std::vector<int>& props) const {
  std::vector<FixtureDef> fixels;
  for (int k : props)
    fixels.push_back({assembly_.part(props_[k].part).name, props_[k].point, props_[k].normal});
  Assembly a = held.empty() ? assembly_ : assembly_.WithHeld(held);
  if (!fixels.empty()) a = a.WithFixtures(fixels);
  return a;
}

Configuration Search::ConfigOf(const std::vector<bool>& placed) const {
  Configuration config = Configuration::Assembled(assembly_);
  for (int p = 0; p < assembly_.num_parts(); ++p)
    config.present[p] = !assembly_.part(p).tool && (assembly_.part(p).fixed || placed[p]);
  return config;
}

// The filter: a component without a static equilibrium cannot stand (the
// verdict's first stage, without the explanation of how it falls, which on
// a large component costs ten times the LP), by the warm LPs. The parts of
// the components without one; `unsure` when an LP gave no verdict.
Check Search::FilterByLp(const std::vector<bool>& placed, const std::vector<int>& held,
                         bool& unsure, const SubsetEquilibrium::Basis* start,
                         std::optional<SubsetEquilibrium::Basis>* end) {
  Check c;
  unsure = false;
  for (size_t k = 0; k < subsets_.size(); ++k) {
    const std::vector<int>& parts = subset_parts_[k];
    std::vector<bool> present(parts.size()), free(parts.size());
    bool any_free = false;
    for (size_t b = 0; b < parts.size(); ++b) {
      present[b] = placed[parts[b]];
      free[b] = present[b] && !std::binary_search(held.begin(), held.end(), parts[b]);
      any_free = any_free || free[b];
    }
    if (!any_free) continue;
    // `start` is a basis of the component's subset (the only one with free parts).
    // While searching, the part being placed is the hint: the mechanism it
    // failed with in a state before is tried first (no simplex when it
    // still moves). A proof checks every warm claim of infeasibility.
    subsets_[k].set_checked(proving_);
    // The body the state changed at: the part placed, or the part a
    // support taken out held or propped.
    int focus = -1;
    if (const int n = assembly_.num_parts(); from_.hint >= 0) {
      const int part = from_.hint < n       ? from_.hint
                       : from_.hint < 2 * n ? from_.hint - n
                                            : props_[from_.hint - 2 * n].part;
      const auto at = std::find(parts.begin(), parts.end(), part);
      if (at != parts.end()) focus = static_cast<int>(at - parts.begin());
    }
    const SubsetEquilibrium::Answer answer =
        subsets_[k].Solve(present, free, start, proving_ ? -1 : from_.hint, focus);
    if (end && answer.solved && answer.exists) *end = subsets_[k].CurrentBasis();
    // After the first: from a kept basis, the last solve's, or a kept proof.
    if (subset_solves_[k]++ > 0) ++out_.warm_starts;
    if (!answer.solved) unsure = true;  // no LP verdict: the check decides this state
    if (!answer.solved || answer.exists) continue;
    if (answer.unbalanced.empty()) {
      for (size_t b = 0; b < parts.size(); ++b)
        if (free[b]) c.moving.push_back(parts[b]);
    } else {
      for (int b : answer.unbalanced) c.moving.push_back(parts[b]);
    }
  }
  return c;
}

const Check& Search::StandsHeld(const std::vector<bool>& placed, const std::vector<int>& held) {
  std::vector<Support> supports;
  for (int h : held) supports.push_back({TemporaryKind::kHold, h, -1});
  return Stands(placed, supports);
}

// Whether the parts `placed` stand with `supports` (cached): each of the
// state's components apart (ComponentStands), as the check decides them.
const Check& Search::Stands(const std::vector<bool>& placed, const std::vector<Support>& supports) {
  std::string key(placed.size(), '0');
  for (size_t p = 0; p < placed.size(); ++p)
    if (placed[p]) key[p] = '1';
  key += SupportKey(supports);
  key += Mode();
  const auto it = memo_.find(key);
  if (it != memo_.end()) {
    ++out_.cache_hits;
    return it->second;
  }
  if (options_.checkpoint) options_.checkpoint();
  ++out_.states_checked;
  Check c;
  c.stands = true;
  const std::vector<int> held = HeldOf(supports);
  for (const std::vector<int>& component : FreeComponents(placed, held)) {
    const Check k = ComponentStands(placed, supports, component);  // a copy: its cache may clear
    c.stands = c.stands && k.stands;
    c.moving.insert(c.moving.end(), k.moving.begin(), k.moving.end());
  }
  std::sort(c.moving.begin(), c.moving.end());
  if (memo_.size() >= options_.max_cached_states) memo_.clear();
  return memo_.emplace(std::move(key), std::move(c)).first->second;
}

// The state's components: its free parts (placed, neither fixed nor held)
// joined where two touch, in the assembled configuration (its contacts are
// the state's). Parts apart share no contact, and a fixed or held part
// carries whatever it must: the verdict, the LP's answer and the parts that
// move are those of each component apart. Before the contacts are known
// (the assembled state's own check), one component.
std::vector<std::vector<int>> Search::FreeComponents(const std::vector<bool>& placed,
                                                     const std::vector<int>& held) const {
  std::vector<int> free;
  for (int p : movable_)
    if (placed[p] && !std::binary_search(held.begin(), held.end(), p)) free.push_back(p);
  if (touching_.empty()) {
    if (free.empty()) return {};
    return {free};
  }
  std::vector<int> component(assembly_.num_parts(), -1);
  std::vector<std::vector<int>> out;
  for (int start : free) {
    if (component[start] >= 0) continue;
    out.emplace_back();
    std::vector<int> todo = {start};
    component[start] = static_cast<int>(out.size()) - 1;
    while (!todo.empty()) {
      const int p = todo.back();
      todo.pop_back();
      out.back().push_back(p);
      for (int q : touching_[p])
        if (component[q] < 0 && std::binary_search(free.begin(), free.end(), q)) {
          component[q] = component[start];
          todo.push_back(q);
        }
    }
    std::sort(out.back().begin(), out.back().end());
  }
  return out;
}

// The supports of a state a component of its free parts leans on (the
// holds it touches, the props under it), and the component's key (its
// parts and those supports) in the caches.
std::pair<std::vector<Support>, std::string> Search::ComponentKey(
    const std::vector<Support>& supports, const std::vector<int>& component) const {
  std::vector<Support> own;
  for (const Support& t : supports) {
    const bool on_it = std::binary_search(component.begin(), component.end(), t.part);
    bool touches = false;
    if (t.kind == TemporaryKind::kHold && !touching_.empty())
      for (int q : touching_[t.part])
        touches = touches || std::binary_search(component.begin(), component.end(), q);
    if (on_it || touches || touching_.empty()) own.push_back(t);
  }
  std::string key;
  for (int p : component) key += std::to_string(p) + ',';
  key += SupportKey(own);
  return {std::move(own), std::move(key)};
}

// Where the LP of `component` starts while Place places a part: the bases
// of the state it comes from (from_) that the component joins, those
// components having the parts of `component` less the part placed, plus the
// parts a new hold holds, less those a hold let go (a state of a part and
// a support fewer). The simplex then restores the placed part's balance and
// the changed holds' neighbours', a few pivots where the last LP's basis
// (null: when not placing, or no basis is known) takes hundreds.
std::optional<SubsetEquilibrium::Basis> Search::StartingBasis(
    const std::vector<Support>& supports, const std::vector<int>& component) const {
  if (!from_.supports || touching_.empty()) return std::nullopt;
  const std::vector<int> held = HeldOf(supports), held_before = HeldOf(*from_.supports);
  std::vector<bool> before(assembly_.num_parts(), false);
  for (int p : component) before[p] = true;
  for (int h : held)
    if (!std::binary_search(held_before.begin(), held_before.end(), h))
      for (int q : touching_[h]) before[h] = before[h] || before[q];
  for (int h : held_before)
    if (!std::binary_search(held.begin(), held.end(), h)) before[h] = false;
  before[from_.part] = false;
  std::optional<SubsetEquilibrium::Basis> start;
  for (const std::vector<int>& part_of : FreeComponents(before, held_before)) {
    const auto found = bases_.find(ComponentKey(*from_.supports, part_of).second);
    if (found == bases_.end()) continue;
    if (!start) start.emplace();
    const SubsetEquilibrium::Basis& b = found->second;
    start->basic_generators.insert(start->basic_generators.end(), b.basic_generators.begin(),
                                   b.basic_generators.end());
    start->basic_rows.insert(start->basic_rows.end(), b.basic_rows.begin(), b.basic_rows.end());
    start->rows.insert(start->rows.end(), b.rows.begin(), b.rows.end());
  }
  return start;
}

// Whether the free parts `component` of the state stand (cached by the
// component, the held parts it touches and the props under it).
const Check& Search::ComponentStands(const std::vector<bool>& placed,
                                     const std::vector<Support>& supports,
                                     const std::vector<int>& component) {
  auto [own, key] = ComponentKey(supports, component);
  const std::string memo_key = key + Mode();
  const auto it = component_memo_.find(memo_key);
  if (it != component_memo_.end()) return it->second;
  std::vector<bool> only(placed.size(), false);
  for (int p : component) only[p] = true;
  for (const Support& t : own)
    if (t.kind == TemporaryKind::kHold) only[t.part] = placed[t.part];
  // The verdict's first stage is the filter: where the filter has decided
  // the component (its answer kept in the filter's mode), a rejection
  // stands, and a pass leaves the verdict alone to decide.
  // In the beam, where the verdict is the equilibrium (VerdictIsTheEquilibrium),
  // it would solve the filter's LP again on the contacts found afresh: the
  // filter's pass stands too (the order's confirmation then checks the state
  // by the verdict, contacts found again).
  bool filtered = false;
  if (full_) {
    const auto lp = component_memo_.find(key + FilterMode());
    if (lp != component_memo_.end()) {
      if (!lp->second.stands || (conservative_ && VerdictIsTheEquilibrium(component, only))) {
        const Check answer = lp->second;  // a copy: the cache may clear
        if (component_memo_.size() >= options_.max_cached_states) component_memo_.clear();
        return component_memo_.emplace(memo_key, answer).first->second;
      }
      filtered = true;
    }
  }
  const std::optional<SubsetEquilibrium::Basis> start = StartingBasis(supports, component);
  std::optional<SubsetEquilibrium::Basis> end;
  Check c = Evaluate(only, own, start ? &*start : nullptr, &end, filtered);
  if (end) {
    if (bases_.size() >= kMaxBases) bases_.clear();
    bases_[key] = std::move(*end);
  }
  if (component_memo_.size() >= options_.max_cached_states) component_memo_.clear();
  return component_memo_.emplace(memo_key, std::move(c)).first->second;
}

// Whether the verdict on the free parts `component` (the parts `present`
// there: the component and the holds it leans on) is whether a static
// equilibrium exists: by `--rule equilibrium`, or where loading from rest
// is beyond its budget (LoadFromRestOptions::max_variables), so that the
// equilibrium decides (VerdictRule::kLoadedFromRest). Not with `--require
// strong`. The loading LCP's size, 2 n_ξ + n_c + (D + 1) n_f (n_ξ the free
// bodies' coordinates, n_c the contact points, n_f those with friction), is
// counted on the assembled contacts, and must exceed the budget by
// kLoadingBudgetMargin: contacts found afresh may be a few more or fewer.
bool Search::VerdictIsTheEquilibrium(const std::vector<int>& component,
                                     const std::vector<bool>& present) const {
  if (options_.require_strong) return false;
  if (options_.stability.rule == VerdictRule::kEquilibrium) return true;
  const auto there = [&](int p) { return p < 0 || assembly_.part(p).fixed || present[p]; };
  const auto in = [&](int p) { return std::binary_search(component.begin(), component.end(), p); };
  const int per_body = assembly_.is_3d() ? 6 : 3;
  long n = 2L * per_body * static_cast<long>(component.size());
  for (const AssembledContact& c : assembled_contacts_)
    if ((in(c.a) && there(c.b)) || (in(c.b) && there(c.a)))
      n += 1 + (c.frictional ? friction_directions_ + 1 : 0);
  return static_cast<double>(n) > kLoadingBudgetMargin * LoadFromRestOptions().max_variables;
}

// The check of the parts `placed` with `supports`, uncached. Without
// props: the filter, then (when it passes a state the confirmation rejected
// once, or is unsure) the check's verdict. With props: the filter with the
// propped parts held (a hold does all that props on its part can) rejects
// what no props can save; the verdict decides the rest. `filtered`: the
// filter has passed the state already, and the verdict alone decides.
Check Search::Evaluate(const std::vector<bool>& placed, const std::vector<Support>& supports,
                       const SubsetEquilibrium::Basis* start,
                       std::optional<SubsetEquilibrium::Basis>* end, bool filtered) {
  const std::vector<int> held = HeldOf(supports), props = PropsOf(supports);
  std::vector<int> held_or_propped = held;
  for (int k : props) held_or_propped.push_back(props_[k].part);
  std::sort(held_or_propped.begin(), held_or_propped.end());
  bool unsure = false;
  Check c = filtered ? Check{} : FilterByLp(placed, held_or_propped, unsure, start, end);
  if (c.moving.empty() && !full_ && !unsure && !subsets_.empty() && props.empty()) {
    c.stands = true;  // the filter's answer; the order's states are confirmed
  } else if (c.moving.empty()) {
    const StabilityResult r = AnalyzeConfiguration(SupportAssembly(held, props), ConfigOf(placed),
                                                   Verdict(), nullptr, &workspace_);
    c.stands = r.stable() && (!options_.require_strong || r.stability == StabilityProof::kStrong);
    c.moving = r.moving;
  }
  std::sort(c.moving.begin(), c.moving.end());
  return c;
}

// A support as the document gives it, and back.
TemporarySupport Search::Public(const Support& t) const {
  TemporarySupport out;
  out.kind = t.kind;
  out.part = t.part;
  if (t.kind == TemporaryKind::kProp) {
    out.point = props_[t.prop].point;
    out.normal = props_[t.prop].normal;
  } else {
    out.point = assembly_.part(t.part).centroid;
  }
  return out;
}

// The supports by name, sorted (holds "h:" before props "p:", a prop by its
// part's name and its place among that part's points): a tie-break that
// does not depend on the order the parts are given in.
std::string Search::SupportNames(std::vector<Support> supports) const {
  std::vector<std::string> names;
  for (const Support& t : supports) {
    const std::string& part = assembly_.part(t.part).name;
    if (t.kind == TemporaryKind::kHold) {
      names.push_back("h:" + part);
    } else {
      const std::vector<int>& own = part_props_[t.part];
      names.push_back("p:" + part + "#" +
                      std::to_string(std::find(own.begin(), own.end(), t.prop) - own.begin()));
    }
  }
  std::sort(names.begin(), names.end());
  std::string out;
  for (const std::string& n : names) out += n + '\n';
  return out;
}

Support Search::Internal(const TemporarySupport& t) const {
  Support out{t.kind, t.part, -1};
  if (t.kind == TemporaryKind::kProp)
    for (int k : part_props_[t.part])
      if (props_[k].point == t.point && props_[k].normal == t.normal) out.prop = k;
  return out;
}

// ---- Stages ----------------------------------------------------------------

// The assembly as designed must stand: the last state of every order.
bool Search::CheckAssembled() {
  std::vector<bool> all(assembly_.num_parts(), false);
  for (int p : movable_) all[p] = true;
  const Check assembled = Stands(all, {});
  if (assembled.stands) return true;
  bool anything_fixed = !assembly_.fixtures().empty();
  for (int p = 0; p < assembly_.num_parts(); ++p)
    anything_fixed = anything_fixed || assembly_.part(p).fixed;
  std::string moving;
  if (!assembled.moving.empty())
    moving = " (" + assembly_.NameList(assembled.moving) +
             (assembled.moving.size() == 1 ? " moves)" : " move)");
  out_.message = "the assembly itself does not stand" + moving +
                 std::string(options_.require_strong ? " with strong stability proved" : "") +
                 ": no build order ends in a standing state" +
                 (anything_fixed ? ""
                                 : "; nothing is fixed: fix the parts that rest on the ground "
                                   "(--fixed PART,...)");
  return false;
}

// The assembled configuration's contact components (one warm LP each),
// which parts touch, and, per removal direction, which parts block which to
// infinity.
void Search::ComputeAdjacencyAndBlocking() {
  const Configuration config = Configuration::Assembled(assembly_);
  touching_.assign(assembly_.num_parts(), {});
  std::vector<Contact> contacts;
  for (const ContactLcp& lcp : BuildComponentLcps(assembly_, config, options_.stability)) {
    contacts.insert(contacts.end(), lcp.contacts.begin(), lcp.contacts.end());
    friction_directions_ = lcp.num_directions;
    for (const Contact& c : lcp.contacts) {
      assembled_contacts_.push_back({c.part_a, c.part_b, c.mu > 0});
      if (c.part_a < 0 || c.part_b < 0) continue;  // a fixture
      touching_[c.part_a].push_back(c.part_b);
      touching_[c.part_b].push_back(c.part_a);
    }
    std::vector<int> parts;
    for (const BodyDynamics& body : lcp.bodies) parts.push_back(body.part);
    subsets_.emplace_back(lcp);
    subset_parts_.push_back(std::move(parts));
    subset_solves_.push_back(0);
  }
  for (auto& t : touching_) {
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
  }
  if (options_.props) ComputePropPoints(contacts);
  if (!options_.ndbg) {
    for (const Vector3& d : directions_)
      graphs_.push_back(ComputeBlockingGraph(assembly_, config, d, BlockingKind::kInfinity));
    return;
  }
  // The NDBG's cells, closest to up first (a cell's arcs to infinity hold
  // for every subset of the parts: a pair blocks or not whoever else is
  // there).
  graphs_ = InfinityGraphsUpFirst(ComputeNdbg(assembly_, config, options_.checkpoint).cells, up_);
  directions_.clear();
  for (const BlockingGraph& g : graphs_) directions_.push_back(g.direction);
}

// Per part, the parts it is in the way of in some removal direction (the
// only ones whose arrival its placing can close).
void Search::ComputeBlocks() {
  blocks_.assign(assembly_.num_parts(), {});
  for (const BlockingGraph& g : graphs_)
    for (int q = 0; q < assembly_.num_parts(); ++q)
      for (int p : g.blockers[q]) blocks_[p].push_back(q);
  for (auto& b : blocks_) {
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end()), b.end());
  }
}

// The points a prop may push at: on the faces of the movable parts that
// touch no part in the assembled configuration (a prop there is in no later
// part's way), as the scene would accept a fixel.
void Search::ComputePropPoints(const std::vector<Contact>& assembled) {
  part_props_.assign(assembly_.num_parts(), {});
  const double tol = assembly_.length_tolerance();
  for (int p : movable_)
    for (const FacePoint& f : FreeFacePoints(assembly_, p, assembled, tol)) {
      if (assembly_.FixtureFault({assembly_.part(p).name, f.point, f.normal})) continue;
      part_props_[p].push_back(static_cast<int>(props_.size()));
      props_.push_back(f);
    }
}

// The arrival direction of `part` past the placed and fixed parts: the
// reverse of the first removal direction no such part blocks.
std::optional<Vector3> Search::Arrival(const std::vector<bool>& placed, int part) const {
  for (size_t k = 0; k < graphs_.size(); ++k) {
    bool free = true;
    for (int q : graphs_[k].blockers[part]) free = free && !(assembly_.part(q).fixed || placed[q]);
    if (free) return Vector3(-directions_[k]);
  }
  return std::nullopt;
}

// The parts not placed in `s` that could arrive there and cannot once
// `part` is placed: it closes their last way in. Placed parts stay, so a
// part that cannot arrive never will (each direction's blockers only grow).
int Search::Stranded(const State& s, int part) const {
  std::vector<bool> placed = s.placed;
  placed[part] = true;
  int out = 0;
  for (int q : blocks_[part])
    if (q != part && !s.placed[q] && !assembly_.part(q).fixed && !assembly_.part(q).tool &&
        Arrival(s.placed, q) && !Arrival(placed, q))
      ++out;
  return out;
}

// The props of `part` worth trying in the state that does not stand, as its
// check `failing` explains it: the part's prop points that oppose its motion
// there (v + ω × (p − c) along the face's outward normal), the most opposing
// first (near-ties: centres first, then the points' order), at most
// kMaxPropsTried. Without a motion of the part, the points pushing most
// nearly up first (a prop from below).
std::vector<int> Search::PropsFor(const StabilityResult& failing, int part) const {
  const Part& p = assembly_.part(part);
  const PartMotion* motion = nullptr;
  for (const PartMotion& m : failing.parts)
    if (m.part == part && m.moving) motion = &m;
  std::vector<std::pair<double, int>> ranked;  // (−score, index)
  double fastest = 0;
  for (int k : part_props_[part]) {
    const Vector3 v =
        motion ? Vector3(motion->linear + motion->angular.cross(props_[k].point - p.centroid))
               : Vector3(-up_);
    fastest = std::max(fastest, v.norm());
    ranked.emplace_back(v.dot(props_[k].normal), k);  // the opposition, against the push
  }
  std::vector<int> out;
  std::stable_sort(ranked.begin(), ranked.end(), [&](const auto& a, const auto& b) {
    const double tie = kLeastOpposition * std::max(fastest, 1e-300);
    if (std::abs(a.first - b.first) > tie) return a.first < b.first;
    return props_[a.second].centre && !props_[b.second].centre;
  });
  for (const auto& [along, k] : ranked) {
    if (static_cast<int>(out.size()) >= kMaxPropsTried) break;
    if (-along > kLeastOpposition * fastest) out.push_back(k);
  }
  return out;
}

// The supports of `s` with one more of `kind` that makes `placed` (s's
// parts and the part just placed) stand: on `part`, then on the parts that
// cannot stand, the most recently placed first (the end of a growing
// cantilever); a prop at the points that most oppose the part's motion
// first. Empty when none does.
std::optional<std::vector<Support>> Search::OneSupportMore(const State& s,
                                                           const std::vector<bool>& placed,
                                                           int part, const Check& as_is,
                                                           TemporaryKind kind) {
  std::vector<int> tries = {part};
  for (auto step = s.steps.rbegin(); step != s.steps.rend(); ++step) {
    if (static_cast<int>(tries.size()) > kMaxMovingTried) break;
    if (std::binary_search(as_is.moving.begin(), as_is.moving.end(), step->part))
      tries.push_back(step->part);
  }
  const std::vector<int> held = HeldOf(s.supports);
  std::optional<StabilityResult> failing;  // the state's check, how its parts move: once
  for (int q : tries) {
    if (std::binary_search(held.begin(), held.end(), q)) continue;
    std::vector<Support> more = s.supports;
    more.push_back({});
    if (kind == TemporaryKind::kProp && !part_props_[q].empty()) {
      if (!failing)
        failing = AnalyzeConfiguration(SupportAssembly(held, PropsOf(s.supports)), ConfigOf(placed),
                                       options_.stability, nullptr, &workspace_);
      for (int k : PropsFor(*failing, q)) {
        more.back() = {TemporaryKind::kProp, q, k};
        if (Stands(placed, more).stands) return more;
      }
    }
    if (kind == TemporaryKind::kHold) {
      more.back() = {TemporaryKind::kHold, q, -1};
      if (Stands(placed, more).stands) return more;
    }
  }
  return std::nullopt;
}

// `s` with `part` placed under the supports in place (no `new_support`),
// or with one more of that kind (OneSupportMore); then every support it
// does without taken out, oldest first. Empty when that does not stand.
std::optional<State> Search::Place(const State& s, int part, const Vector3& arrival,
                                   std::optional<TemporaryKind> new_support) {
  std::vector<bool> placed = s.placed;
  placed[part] = true;
  std::optional<std::vector<Support>> supports;
  from_ = {part, &s.supports, part};  // the LPs start from s's bases
  struct Reset {
    From& from;
    ~Reset() { from = {}; }
  } reset{from_};
  const Check as_is = Stands(placed, s.supports);  // a copy: the cache may start afresh
  if (!new_support) {
    if (as_is.stands) supports = s.supports;
  } else if (!as_is.stands) {
    supports = OneSupportMore(s, placed, part, as_is, *new_support);
  }
  if (!supports) return std::nullopt;
  // Take out what the state does without, oldest first.
  for (size_t i = 0; i < supports->size();) {
    std::vector<Support> without = *supports;
    without.erase(without.begin() + static_cast<long>(i));
    const Support& out = (*supports)[i];
    const int n = assembly_.num_parts();
    from_.hint = out.kind == TemporaryKind::kHold ? n + out.part : 2 * n + out.prop;
    if (Stands(placed, without).stands) {
      supports = without;
    } else {
      ++i;
    }
  }
  State child;
  child.placed = std::move(placed);
  child.supports = *supports;
  child.steps = s.steps;
  SequenceStep step;
  step.part = part;
  step.direction = arrival;
  const auto has = [](const std::vector<Support>& in, const Support& t) {
    return std::find(in.begin(), in.end(), t) != in.end();
  };
  for (const Support& t : child.supports)
    if (!has(s.supports, t)) step.added.push_back(Public(t));
  for (const Support& t : s.supports)
    if (!has(child.supports, t)) step.removed.push_back(Public(t));
  child.stranded = s.stranded + Stranded(s, part);
  child.placements = s.placements + static_cast<int>(step.added.size());
  child.max_in_place = std::max(s.max_in_place, static_cast<int>(child.supports.size()));
  child.steps.push_back(std::move(step));
  child.height = s.height + up_.dot(assembly_.part(part).centroid);
  child.names = s.names + assembly_.part(part).name + '\n';
  return child;
}

// The children of `s`, in two passes over the parts that can arrive:
//   1. each placed under the holds in place (none added);
//   2. only when pass 1 gave fewer than beam_width children: each that did
//      not stand, with one hold more (within --max-temporary).
// A child of pass 2 has a placement more than any of pass 1 and, since a
// hold only ever adds support, never fewer holds than the same part placed
// in pass 1 would keep: pass 1's children are the ones the beam wants.
// The parts that can come next in `s`, with their arrival directions:
// those that touch a placed or fixed part (or, when none does, any), lower
// parts first (then names), none that closes another's last way in unless
// every one does (Stranded).
std::vector<std::pair<int, Vector3>> Search::Candidates(const State& s) const {
  std::vector<int> candidates, loose;
  for (int p : movable_) {
    if (s.placed[p]) continue;
    bool touches = false;
    for (int q : touching_[p]) touches = touches || assembly_.part(q).fixed || s.placed[q];
    (touches ? candidates : loose).push_back(p);
  }
  // A part that touches nothing placed arrives held (only when no other can).
  if (candidates.empty()) candidates = loose;
  // Lower parts first (then names): the order Better ranks children of one
  // state in when they need the same supports. A child that needs nothing
  // new is as good as a child of `s` gets, so once beam_width of them are
  // found, the candidates after them cannot enter the beam (Expand).
  const double tol = assembly_.length_tolerance();
  std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
    const double ha = up_.dot(assembly_.part(a).centroid), hb = up_.dot(assembly_.part(b).centroid);
    if (std::abs(ha - hb) > tol) return ha < hb;
    return assembly_.part(a).name < assembly_.part(b).name;
  });
  // A part that would close the last way in of another is placed only
  // when every part that can arrive would (then the order cannot be
  // finished, and the search says how far it gets).
  std::vector<std::pair<int, Vector3>> arriving, closing;
  for (int p : candidates)
    if (const std::optional<Vector3> arrival = Arrival(s.placed, p))
      (Stranded(s, p) == 0 ? arriving : closing).emplace_back(p, *arrival);
  return arriving.empty() ? closing : arriving;
}

std::vector<State> Search::Expand(const State& s) {
  std::vector<State> children;
  std::vector<std::pair<int, Vector3>> fell;
  const std::vector<std::pair<int, Vector3>> arriving = Candidates(s);
  int unimprovable = 0;
  for (const auto& [p, arrival] : arriving) {
    if (Stopped() || unimprovable >= options_.beam_width) break;
    std::optional<State> child = Place(s, p, arrival, std::nullopt);
    if (!child) {
      fell.emplace_back(p, arrival);
      continue;
    }
    if (child->supports.empty()) ++unimprovable;
    children.push_back(std::move(*child));
  }
  const int bound = options_.max_temporary;
  if (static_cast<int>(children.size()) >= options_.beam_width ||
      (bound >= 0 && static_cast<int>(s.supports.size()) + 1 > bound))
    return children;
  // Each kind allowed gives its own child: the beam weighs a hold that
  // carries a growing cantilever against props that each carry one part.
  for (const auto& [p, arrival] : fell)
    for (TemporaryKind kind : kinds_) {
      if (Stopped()) break;
      if (std::optional<State> child = Place(s, p, arrival, kind))
        children.push_back(std::move(*child));
    }
  return children;
}

// Fewer parts stranded (an order that can be finished first), fewer
// supports at once so far, fewer now, fewer placements, lower parts first,
// then names.
bool Search::Better(const State& a, const State& b) const {
  if (a.stranded != b.stranded) return a.stranded < b.stranded;
  if (a.max_in_place != b.max_in_place) return a.max_in_place < b.max_in_place;
  if (a.supports.size() != b.supports.size()) return a.supports.size() < b.supports.size();
  if (a.placements != b.placements) return a.placements < b.placements;
  const double tol = assembly_.length_tolerance();
  if (std::abs(a.height - b.height) > tol) return a.height < b.height;
  if (a.names != b.names) return a.names < b.names;
  return SupportNames(a.supports) < SupportNames(b.supports);
}

// The beam from `start` (its steps kept) to the last part, or as far as it
// gets: best_ is its best state.
void Search::RunBeam(const State& start) {
  conservative_ = true;
  struct Reset {
    bool& conservative;
    ~Reset() { conservative = false; }
  } reset{conservative_};
  std::vector<State> beam = {start};
  const size_t n = movable_.size();
  out_.complete = false;
  for (size_t depth = start.steps.size(); depth < n; ++depth) {
    std::map<std::string, State> unique;  // by (placed, held): the better kept
    for (size_t i = 0; i < beam.size(); ++i)
      for (State& c : Expand(beam[i])) {
        c.parent = static_cast<int>(i);
        std::string key(c.placed.begin(), c.placed.end());
        key += SupportKey(c.supports);
        auto it = unique.find(key);
        if (it == unique.end())
          unique.emplace(std::move(key), std::move(c));
        else if (Better(c, it->second))
          it->second = std::move(c);
      }
    // The best beam_width children, confirmed by the check's verdict once a
    // confirmation has rejected a state (the LP passed them all): a state
    // the verdict rejects is replaced now by the next best, rather than
    // found by the confirmation of the whole order and searched again.
    std::vector<State> children;
    for (auto& [key, state] : unique) children.push_back(std::move(state));
    std::sort(children.begin(), children.end(),
              [&](const State& a, const State& b) { return Better(a, b); });
    std::vector<State> next, turned_down;
    for (State& c : children) {
      if (next.size() >= static_cast<size_t>(options_.beam_width) || Stopped()) break;
      if (Confirmed(c)) {
        next.push_back(std::move(c));
      } else {
        ++out_.verdict_rejections;
        turned_down.push_back(std::move(c));
      }
    }
    const int rejected = static_cast<int>(turned_down.size());
    if (next.size() < static_cast<size_t>(options_.beam_width) && !turned_down.empty())
      WithOneSupportMore(beam, turned_down, next);
    if (Stopped()) {
      best_ = beam.front();
      out_.message = std::string(options_.stop && options_.stop() ? "stopped" : "time limit") +
                     " after " + std::to_string(depth) + " of " + std::to_string(n) +
                     " parts: the best order so far";
      return;
    }
    if (next.empty() && !AnyArrives(beam)) {
      best_ = beam.front();
      out_.message = "no part left can arrive along the directions tried after " +
                     std::to_string(depth) + " of " + std::to_string(n) +
                     " parts: each is blocked by the parts placed (--directions axes or ndbg "
                     "tries more)";
      return;
    }
    if (next.empty()) {
      best_ = beam.front();
      out_.message =
          "no part can be placed next within " +
          (options_.max_temporary < 0
               ? std::string("the holds tried")
               : "at most " + std::to_string(options_.max_temporary) + " support(s) in place") +
          " after " + std::to_string(depth) + " of " + std::to_string(n) + " parts" +
          (rejected > 0 ? " (the check's verdict rejected the " + std::to_string(rejected) +
                              " state(s) the equilibrium LP passed)"
                        : "");
      return;
    }
    beam = std::move(next);
    if (options_.status)
      options_.status(std::to_string(depth + 1) + "/" + std::to_string(n) +
                      " parts placed, supports at once " +
                      std::to_string(beam.front().max_in_place) + ", " +
                      std::to_string(out_.states_checked) + " states checked");
  }
  best_ = beam.front();
  if (!best_.supports.empty()) {
    out_.message = "the last state still needs its supports";
    return;
  }
  out_.complete = true;
}

// The children the verdict turned down (the LP passed them, so Expand did
// not try them with a support more) placed again with one support more of
// each kind allowed, judged by the verdict; the best of them join `next`
// while it has room.
void Search::WithOneSupportMore(const std::vector<State>& beam,
                                const std::vector<State>& turned_down, std::vector<State>& next) {
  const int bound = options_.max_temporary;
  std::vector<State> more;
  const bool full = full_;
  full_ = true;
  for (const State& c : turned_down) {
    const State& parent = beam[static_cast<size_t>(c.parent)];
    if (bound >= 0 && static_cast<int>(parent.supports.size()) + 1 > bound) continue;
    for (TemporaryKind kind : kinds_) {
      if (Stopped()) break;
      if (std::optional<State> alt =
              Place(parent, c.steps.back().part, c.steps.back().direction, kind))
        more.push_back(std::move(*alt));
    }
  }
  full_ = full;
  std::sort(more.begin(), more.end(), [&](const State& a, const State& b) { return Better(a, b); });
  for (State& m : more) {
    if (next.size() >= static_cast<size_t>(options_.beam_width)) break;
    const auto same = [&](const State& t) {
      return t.placed == m.placed && SupportKey(t.supports) == SupportKey(m.supports);
    };
    if (std::none_of(next.begin(), next.end(), same)) next.push_back(std::move(m));
  }
}

// Whether some part not yet placed in a state of `beam` can arrive.
bool Search::AnyArrives(const std::vector<State>& beam) const {
  for (const State& s : beam)
    for (int p : movable_)
      if (!s.placed[p] && Arrival(s.placed, p)) return true;
  return false;
}

// Whether the check's verdict confirms `s` (the LP passed it) when the beam
// is confirmed (confirm_beam_): each of its components by the verdict
// (cached: a component the state shares with its parent, confirmed with
// the parent, is not checked again).
bool Search::Confirmed(const State& s) {
  if (full_ || !confirm_beam_) return true;
  full_ = true;
  const bool stands = Stands(s.placed, s.supports).stands;
  full_ = false;
  return stands;
}

// The supports in place after `step`, from those before it.
void Search::Apply(const SequenceStep& step, std::vector<Support>& supports) const {
  for (const TemporarySupport& t : step.added) supports.push_back(Internal(t));
  for (const TemporarySupport& t : step.removed)
    supports.erase(std::find(supports.begin(), supports.end(), Internal(t)));
}

// The state after the first `steps` steps of best_.
State Search::Prefix(int steps) const {
  State s;
  s.placed.assign(assembly_.num_parts(), false);
  for (int i = 0; i < steps; ++i) {
    const SequenceStep& step = best_.steps[i];
    s.stranded += Stranded(s, step.part);
    s.placed[step.part] = true;
    Apply(step, s.supports);
    s.placements += static_cast<int>(step.added.size());
    s.max_in_place = std::max(s.max_in_place, static_cast<int>(s.supports.size()));
    s.height += up_.dot(assembly_.part(step.part).centroid);
    s.names += assembly_.part(step.part).name + '\n';
    s.steps.push_back(step);
  }
  return s;
}

// Every order passes through a state of one part and one of all parts but
// one: when none of either stands without support, every order needs one.
// Both on the equilibrium LP (the filter, with the verdict only where an LP
// is unsure): every rule's "stands" implies an equilibrium, so a bound on
// the LP holds for the verdict. Props are bounded by holds: a hold on a part
// does all that props on it can (the LP with the propped parts held is
// feasible when it is with the props), and each propped part has a prop.
void Search::ComputeLowerBound() {
  const bool full = full_;
  full_ = false;
  proving_ = true;
  ArgueLowerBound();
  ExhaustiveLowerBound();
  proving_ = false;
  full_ = full;
}

void Search::ArgueLowerBound() {
  out_.lower_bound = 0;
  if (movable_.empty()) return;
  std::vector<bool> placed(assembly_.num_parts(), false);
  bool one_stands = false;
  for (int p : movable_) {
    if (!Arrival(placed, p)) continue;
    placed[p] = true;
    one_stands = one_stands || Stands(placed, {}).stands;
    placed[p] = false;
    if (one_stands) break;
  }
  if (!one_stands) {
    out_.lower_bound = 1;
    out_.lower_bound_reason =
        "no part stands alone on the fixed parts: every order's first state needs a support";
    return;
  }
  if (!out_.complete || out_.max_in_place == 0 || Stopped()) {
    out_.lower_bound_reason = "a part stands alone on the fixed parts";
    return;
  }
  for (int p : movable_) placed[p] = true;
  bool all_but_one_stands = false;
  for (int p : movable_) {
    placed[p] = false;
    if (Arrival(placed, p)) all_but_one_stands = all_but_one_stands || Stands(placed, {}).stands;
    placed[p] = true;
    if (all_but_one_stands) break;
  }
  if (all_but_one_stands) {
    out_.lower_bound_reason =
        "a part stands alone on the fixed parts, and the assembly stands without a part that can "
        "go last";
    return;
  }
  out_.lower_bound = 1;
  out_.lower_bound_reason =
      "the assembly without any one part that can go last does not stand: every order's last "
      "state but one needs a support";
}

// Where the model is small (kExhaustiveParts movable parts at most) and the
// argued bound is below the order's: every set of parts an order can pass
// through, in turn (a set is reachable when it stands with at most b parts
// held, whichever, and a reachable set without one of its parts lets that
// part arrive last). The least b that reaches every part is the fewest any
// order needs: a proof by exhaustion, on the same check as the search's.
void Search::ExhaustiveLowerBound() {
  const int n = static_cast<int>(movable_.size());
  if (n == 0 || n > kExhaustiveParts || Stopped()) return;
  const int target = out_.complete ? out_.max_in_place : kExhaustiveHolds + 1;
  const auto placed_of = [&](unsigned mask) {
    std::vector<bool> placed(assembly_.num_parts(), false);
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) placed[movable_[i]] = true;
    return placed;
  };
  // Whether the parts of `mask` stand with some b of them held (b ≤ holds).
  const auto stands_with = [&](unsigned mask, int holds) {
    const std::vector<bool> placed = placed_of(mask);
    std::vector<int> in;
    for (int i = 0; i < n; ++i)
      if (mask & (1u << i)) in.push_back(movable_[i]);
    std::vector<int> held;
    const std::function<bool(size_t, int)> choose = [&](size_t from, int left) {
      if (StandsHeld(placed, held).stands) return true;
      if (left == 0) return false;
      for (size_t k = from; k < in.size(); ++k) {
        held.push_back(in[k]);
        const bool ok = choose(k + 1, left - 1);
        held.pop_back();
        if (ok) return true;
      }
      return false;
    };
    return choose(0, holds);
  };
  const unsigned all = (1u << n) - 1;
  // Whether every part can arrive in some order along the directions tried,
  // whatever stands: if not, no order exists, with any supports.
  std::vector<char> arrives(all + 1, 0);
  arrives[0] = 1;
  for (unsigned mask = 1; mask <= all; ++mask)
    for (int i = 0; i < n && !arrives[mask]; ++i) {
      const unsigned before = mask & ~(1u << i);
      arrives[mask] = (mask & (1u << i)) && arrives[before] &&
                      Arrival(placed_of(before), movable_[i]).has_value();
    }
  if (!arrives[all]) {
    out_.lower_bound_reason = "every order of the " + std::to_string(n) +
                              " parts tried: in none can every part arrive along the directions "
                              "tried (a part is blocked by those placed before it)";
    return;
  }
  for (int b = out_.lower_bound; b < target && b <= kExhaustiveHolds; ++b) {
    std::vector<char> reachable(all + 1, 0);
    reachable[0] = 1;
    for (unsigned mask = 1; mask <= all; ++mask) {
      if (Stopped()) return;
      bool from = false;
      for (int i = 0; i < n && !from; ++i) {
        const unsigned before = mask & ~(1u << i);
        from = (mask & (1u << i)) && reachable[before] && Arrival(placed_of(before), movable_[i]);
      }
      reachable[mask] = from && stands_with(mask, b);
    }
    const std::string by_holds =
        options_.props ? " (with holds, which do all that props on their parts can)" : "";
    if (reachable[all]) {
      out_.lower_bound = b;
      out_.lower_bound_reason = "every order of the " + std::to_string(n) +
                                " parts tried: the fewest supports at once any order needs" +
                                by_holds;
      return;
    }
    out_.lower_bound = b + 1;
    out_.lower_bound_reason = "every order of the " + std::to_string(n) +
                              " parts tried: none does with fewer supports at once" + by_holds;
  }
}

// Every state of the order checked again, afresh (no cache, no warm start),
// by the check's verdict, with what each hold carries. Returns the first
// step whose state does not stand (-1: none). The states are independent:
// they are checked on options_.threads threads, in order of their steps
// (ConfirmStates), and read in that order.
int Search::ConfirmAndMeasureHolds() {
  unconfirmed_from_ = -1;
  // Each step's parts and supports.
  const int steps = static_cast<int>(best_.steps.size());
  std::vector<std::vector<bool>> placed(steps);
  std::vector<std::vector<Support>> supports(steps);
  std::vector<bool> now(assembly_.num_parts(), false);
  std::vector<Support> in_place;
  for (int i = 0; i < steps; ++i) {
    const SequenceStep& step = best_.steps[i];
    now[step.part] = true;
    Apply(step, in_place);
    placed[i] = now;
    supports[i] = in_place;
  }
  // Each thread builds the scene with its state's supports (the search's
  // cache of them is not shared): a copy alive per thread at most. Each
  // has a workspace that keeps the components it solved (reuse mode: cold
  // solves, so the answers are fresh checks' whichever thread met them
  // first): the states it takes share most of them.
  std::vector<StabilityWorkspace> kept(static_cast<size_t>(ThreadCount(options_.threads)));
  for (StabilityWorkspace& w : kept) w.set_reuse_solutions(true);
  const std::vector<char> done = ConfirmStates(steps, [&](int i, int worker) {
    const std::vector<int> held = HeldOf(supports[i]), props = PropsOf(supports[i]);
    const std::optional<Assembly> scene = held.empty() && props.empty()
                                              ? std::nullopt
                                              : std::optional<Assembly>(WithSupports(held, props));
    MeasureStep(
        AnalyzeConfiguration(scene ? *scene : assembly_, ConfigOf(placed[i]), options_.stability,
                             nullptr, &kept[static_cast<size_t>(worker)]),
        supports[i], best_.steps[i]);
  });
  int first_failing = -1;
  for (int i = 0; i < steps; ++i) {
    if (!done[i]) {
      unconfirmed_from_ = i;
      return first_failing;
    }
    if (!best_.steps[i].stands && first_failing < 0) first_failing = i;
  }
  return first_failing;
}

// check(i, worker) for i = 0 … n − 1 (each touching only what is its own), on
// options_.threads threads taking the next step in turn; none taken once
// the confirmation's time is up, and every one taken is done: which were
// done is a prefix. The time and the caller's checkpoint are seen on this
// thread only.
std::vector<char> Search::ConfirmStates(int n, const std::function<void(int, int)>& check) {
  std::vector<char> out(n, 0);
  std::atomic<int> next{0};
  std::atomic<bool> stop{false};
  std::mutex failing;
  std::exception_ptr failed;  // the first a thread threw
  const auto take = [&]() -> int {
    const int i = stop ? n : next++;
    return i < n ? i : -1;
  };
  const int threads = std::min(n, ThreadCount(options_.threads));
  std::vector<std::thread> others;
  for (int t = 1; t < threads; ++t)
    others.emplace_back([&, t] {
      try {
        for (int i = take(); i >= 0; i = take()) {
          check(i, t);
          out[i] = 1;
        }
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failing);
        if (!failed) failed = std::current_exception();
        stop = true;
      }
    });
  try {
    while (true) {
      if (options_.checkpoint) options_.checkpoint();
      if (ConfirmationOutOfTime()) stop = true;
      const int i = take();
      if (i < 0) break;
      check(i, 0);
      out[i] = 1;
    }
  } catch (...) {
    stop = true;
    for (std::thread& t : others) t.join();
    throw;
  }
  for (std::thread& t : others) t.join();
  if (failed) std::rethrow_exception(failed);
  return out;
}

// A confirmed step's verdict, contacts and the wrench of each support in
// place, from its check `r`.
void Search::MeasureStep(const StabilityResult& r, const std::vector<Support>& supports,
                         SequenceStep& step) const {
  const std::vector<int> props = PropsOf(supports);
  const int scene_fixtures = static_cast<int>(assembly_.fixtures().size());
  step.stability = r.stability;
  step.stands = r.stable() && (!options_.require_strong || r.stability == StabilityProof::kStrong);
  if (options_.record_contacts) step.contacts = r.contacts;
  step.in_place.clear();
  for (const Support& s : supports) {
    TemporarySupport t = Public(s);
    if (s.kind == TemporaryKind::kProp) {
      // Its push: the fixel's contact (the scene's fixtures, then the
      // props in index order).
      const int fixture =
          scene_fixtures +
          static_cast<int>(std::lower_bound(props.begin(), props.end(), s.prop) - props.begin());
      for (const ContactReport& c : r.contacts)
        if (c.contact.part_b == kWorld && c.contact.feature == ContactFeature::kFixture &&
            c.contact.index_a == fixture)
          t.force += c.normal_force * c.contact.n_W;
    } else {
      std::tie(t.force, t.torque) = HoldWrench(assembly_, s.part, r);
    }
    step.in_place.push_back(t);
  }
}

BuildSequence Search::Run() {
  out_.kinds = kinds_;
  if (!CheckAssembled()) {
    out_.lower_bound_reason = "no order exists: the assembly itself does not stand";
    return out_;
  }
  ComputeAdjacencyAndBlocking();
  ComputeBlocks();
  // The search on the equilibrium LP, then its order confirmed state by
  // state by the check's verdict; where a state is rejected, the search
  // goes on from the state before it with the verdict itself (the repair).
  State start;
  start.placed.assign(assembly_.num_parts(), false);
  confirm_beam_ = movable_.size() > kConfirmBeamFromParts;
  RunBeam(start);
  for (int bad = ConfirmAndMeasureHolds(); bad >= 0; bad = ConfirmAndMeasureHolds()) {
    if (full_ || Stopped()) {
      // The order so far up to the state rejected: every state listed stands.
      const std::string rejected = "the fresh check of the state after placing '" +
                                   assembly_.part(best_.steps[bad].part).name + "' does not stand";
      out_.message = out_.message.empty() ? rejected : out_.message + "; " + rejected;
      out_.complete = false;
      best_ = Prefix(bad);
      break;
    }
    // First the beam's states confirmed by the verdict as they enter it,
    // then (rejected again) every state checked by the verdict.
    if (confirm_beam_) full_ = true;
    confirm_beam_ = true;
    ++out_.repairs;
    RunBeam(Prefix(bad));
  }
  if (unconfirmed_from_ >= 0 && unconfirmed_from_ < static_cast<int>(best_.steps.size())) {
    // The time ran out during the confirmation: the states it confirmed.
    const std::string cut =
        "the time ran out while the states were checked again: the order is "
        "cut after the " +
        std::to_string(unconfirmed_from_) + " confirmed";
    out_.message = out_.message.empty() ? cut : out_.message + "; " + cut;
    out_.complete = false;
    best_ = Prefix(unconfirmed_from_);
  }
  out_.max_in_place = best_.max_in_place;
  out_.placements = best_.placements;
  ComputeLowerBound();
  out_.steps = std::move(best_.steps);
  out_.warm_starts += workspace_.warm_starts();
  return out_;
}

}  // namespace

BuildSequence FindBuildSequence(const Assembly& assembly, const SequenceOptions& options) {
  if (!(options.holds && options.props)) return Search(assembly, options).Run();
  // Both kinds: a beam that may also prop keeps fewer of the states a hold
  // alone would reach (twice the children at each step), so the order with
  // holds alone is searched too (each in half the time), and the better
  // kept: never more supports at once than holds alone.
  SequenceOptions half = options;
  half.time_limit = options.time_limit / 2;
  half.props = false;
  half.status = nullptr;  // the other search tells where it is
  SequenceOptions with_props = half;
  with_props.props = true;
  with_props.status = options.status;
  BuildSequence holds, both;
  const int threads = ThreadCount(options.threads);
  if (threads >= 2) {
    // Side by side: each search owns its LPs, caches and workspace, and
    // half the threads for its confirmation.
    half.threads = with_props.threads = threads / 2;
    std::exception_ptr failed;
    std::thread side([&] {
      try {
        holds = Search(assembly, half).Run();
      } catch (...) {
        failed = std::current_exception();
      }
    });
    try {
      both = Search(assembly, with_props).Run();
    } catch (...) {
      side.join();
      throw;
    }
    side.join();
    if (failed) std::rethrow_exception(failed);
  } else {
    holds = Search(assembly, half).Run();
    both = Search(assembly, with_props).Run();
  }
  const auto rank = [](const BuildSequence& r) {
    return std::make_tuple(!r.complete, r.max_in_place, r.placements, -int(r.steps.size()));
  };
  BuildSequence& best = rank(holds) < rank(both) ? holds : both;
  const BuildSequence& other = &best == &holds ? both : holds;
  best.kinds = both.kinds;
  if (other.lower_bound > best.lower_bound) {  // both bounds are proofs
    best.lower_bound = other.lower_bound;
    best.lower_bound_reason = other.lower_bound_reason;
  }
  best.states_checked += other.states_checked;
  best.cache_hits += other.cache_hits;
  best.warm_starts += other.warm_starts;
  best.repairs += other.repairs;
  best.verdict_rejections += other.verdict_rejections;
  best.stopped = best.stopped || other.stopped;
  return std::move(best);
}

}  // namespace cairn

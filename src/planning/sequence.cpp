// Build orders with temporary holds (planning/sequence.h, docs/sequence.md).

#include "cairn/planning/sequence.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cairn/mechanics/subset_equilibrium.h"
#include "cairn/planning/blocking.h"

namespace cairn {

const char* to_string(TemporaryKind kind) {
  switch (kind) {
    case TemporaryKind::kHold:
      return "hold";
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

// The most parts the check says move that are tried as the hold that makes a
// new state stand (after the part just placed).
constexpr int kMaxMovingTried = 3;

// One state of the beam: the parts placed, the holds in place (oldest
// first), and how it got there.
struct State {
  std::vector<bool> placed;
  std::vector<int> held;
  std::vector<SequenceStep> steps;
  int max_in_place = 0;
  int placements = 0;
  double height = 0;  // Σ of the placed parts' centroid heights against gravity (length)
  std::string names;  // the order's names, for ties
};

// A state's check, as the search needs it: whether it stands and, when it
// does not, the parts that cannot (those of the components without an
// equilibrium, or those the verdict says move).
struct Check {
  bool stands = false;
  std::vector<int> moving;
};

class Search {
 public:
  Search(const Assembly& assembly, const SequenceOptions& options);
  BuildSequence Run();

 private:
  // Stages of Run, in order.
  bool CheckAssembled();
  void ComputeAdjacencyAndBlocking();
  void RunBeam(const State& start);
  void ComputeLowerBound();
  void ArgueLowerBound();
  void ExhaustiveLowerBound();
  int ConfirmAndMeasureHolds();
  State Prefix(int steps) const;

  std::vector<State> Expand(const State& s);
  std::optional<State> Place(const State& s, int part, const Vector3& arrival, bool with_new_hold);
  std::optional<Vector3> Arrival(const std::vector<bool>& placed, int part) const;
  const Check& Stands(const std::vector<bool>& placed, std::vector<int> held);
  Configuration ConfigOf(const std::vector<bool>& placed) const;
  const Assembly& HeldAssembly(const std::vector<int>& held_sorted);
  bool Better(const State& a, const State& b) const;
  bool Stopped();
  bool ConfirmationOutOfTime();

  const Assembly& assembly_;
  const SequenceOptions& options_;
  Vector3 up_;
  std::vector<int> movable_;
  std::vector<std::vector<int>> touching_;  // per part: the parts it touches assembled
  std::vector<Vector3> directions_;         // removal directions
  std::vector<BlockingGraph> graphs_;       // per direction, to infinity
  std::unordered_map<std::string, Check> memo_;
  // The filter: the assembled configuration's equilibrium LP per contact
  // component, kept between states (mechanics/subset_equilibrium.h), and
  // where each movable part is in it.
  std::vector<SubsetEquilibrium> subsets_;
  std::vector<std::vector<int>> subset_parts_;  // per component: its bodies' parts
  std::vector<int> subset_solves_;              // per component: its LP's solves so far
  std::map<std::vector<int>, Assembly> held_assemblies_;
  StabilityWorkspace workspace_;
  BuildSequence out_;
  State best_;
  std::chrono::steady_clock::time_point deadline_ = std::chrono::steady_clock::time_point::max();
  std::chrono::steady_clock::time_point confirm_deadline_ =
      std::chrono::steady_clock::time_point::max();
  // False: a state stands when the LP finds an equilibrium (the filter);
  // true: by the check's verdict (after a confirmation rejected a state).
  bool full_ = false;
  bool stop_seen_ = false;     // ConfirmationOutOfTime has seen the stop
  int unconfirmed_from_ = -1;  // the first step the confirmation had no time for
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

const Assembly& Search::HeldAssembly(const std::vector<int>& held_sorted) {
  if (held_sorted.empty()) return assembly_;
  auto it = held_assemblies_.find(held_sorted);
  if (it != held_assemblies_.end()) return it->second;
  if (held_assemblies_.size() >= kMaxHeldAssemblies) held_assemblies_.clear();
  return held_assemblies_.emplace(held_sorted, assembly_.WithHeld(held_sorted)).first->second;
}

Configuration Search::ConfigOf(const std::vector<bool>& placed) const {
  Configuration config = Configuration::Assembled(assembly_);
  for (int p = 0; p < assembly_.num_parts(); ++p)
    config.present[p] = !assembly_.part(p).tool && (assembly_.part(p).fixed || placed[p]);
  return config;
}

const Check& Search::Stands(const std::vector<bool>& placed, std::vector<int> held) {
  std::sort(held.begin(), held.end());
  std::string key(placed.size(), '0');
  for (size_t p = 0; p < placed.size(); ++p)
    if (placed[p]) key[p] = '1';
  for (int h : held) key += "," + std::to_string(h);
  key += full_ ? "|full" : "|lp";
  const auto it = memo_.find(key);
  if (it != memo_.end()) {
    ++out_.cache_hits;
    return it->second;
  }
  if (options_.checkpoint) options_.checkpoint();
  ++out_.states_checked;
  if (memo_.size() >= options_.max_cached_states)
    memo_.clear();  // no reference into it outlives a call
  Check c;
  // The filter: a component without a static equilibrium cannot stand (the
  // verdict's first stage, without the explanation of how it falls, which
  // on a large component costs ten times the LP), by the warm LPs.
  bool unsure = false;
  for (size_t k = 0; k < subsets_.size(); ++k) {
    const std::vector<int>& parts = subset_parts_[k];
    std::vector<bool> present(parts.size()), free(parts.size());
    bool any_free = false;
    for (size_t b = 0; b < parts.size(); ++b) {
      present[b] = placed[parts[b]];
      free[b] = present[b] && std::find(held.begin(), held.end(), parts[b]) == held.end();
      any_free = any_free || free[b];
    }
    if (!any_free) continue;
    const SubsetEquilibrium::Answer answer = subsets_[k].Solve(present, free);
    if (subset_solves_[k]++ > 0) ++out_.warm_starts;  // from the last solve's basis
    if (!answer.solved) unsure = true;                // no LP verdict: the check decides this state
    if (!answer.solved || answer.exists) continue;
    if (answer.unbalanced.empty()) {
      for (size_t b = 0; b < parts.size(); ++b)
        if (free[b]) c.moving.push_back(parts[b]);
    } else {
      for (int b : answer.unbalanced) c.moving.push_back(parts[b]);
    }
  }
  if (c.moving.empty() && !full_ && !unsure && !subsets_.empty()) {
    c.stands = true;  // the filter's answer; the order's states are confirmed
  } else if (c.moving.empty()) {
    const StabilityResult r = AnalyzeConfiguration(HeldAssembly(held), ConfigOf(placed),
                                                   options_.stability, nullptr, &workspace_);
    c.stands = r.stable() && (!options_.require_strong || r.stability == StabilityProof::kStrong);
    c.moving = r.moving;
  }
  std::sort(c.moving.begin(), c.moving.end());
  return memo_.emplace(std::move(key), std::move(c)).first->second;
}

// ---- Stages ----------------------------------------------------------------

// The assembly as designed must stand: the last state of every order.
bool Search::CheckAssembled() {
  std::vector<bool> all(assembly_.num_parts(), false);
  for (int p : movable_) all[p] = true;
  if (Stands(all, {}).stands) return true;
  out_.message = "the assembly itself does not stand" +
                 std::string(options_.require_strong ? " with strong stability proved" : "") +
                 ": no build order ends in a standing state";
  return false;
}

// The assembled configuration's contact components (one warm LP each),
// which parts touch, and, per removal direction, which parts block which to
// infinity.
void Search::ComputeAdjacencyAndBlocking() {
  const Configuration config = Configuration::Assembled(assembly_);
  touching_.assign(assembly_.num_parts(), {});
  for (const ContactLcp& lcp : BuildComponentLcps(assembly_, config, options_.stability)) {
    for (const Contact& c : lcp.contacts) {
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

// `s` with `part` placed under the holds in place (`with_new_hold` false),
// or with one more (true: the part itself, or a part the check says moves);
// then every hold it does without taken out, oldest first. Empty when that
// does not stand.
std::optional<State> Search::Place(const State& s, int part, const Vector3& arrival,
                                   bool with_new_hold) {
  std::vector<bool> placed = s.placed;
  placed[part] = true;
  std::optional<std::vector<int>> held;
  const Check as_is = Stands(placed, s.held);  // a copy: the cache may start afresh
  if (!with_new_hold) {
    if (as_is.stands) held = s.held;
  } else if (!as_is.stands) {
    // The part itself, then the parts that cannot stand, the most recently
    // placed first (the end of a growing cantilever).
    std::vector<int> tries = {part};
    for (auto step = s.steps.rbegin(); step != s.steps.rend(); ++step) {
      if (static_cast<int>(tries.size()) > kMaxMovingTried) break;
      const int q = step->part;
      if (std::binary_search(as_is.moving.begin(), as_is.moving.end(), q) &&
          std::find(s.held.begin(), s.held.end(), q) == s.held.end())
        tries.push_back(q);
    }
    for (int q : tries) {
      std::vector<int> h = s.held;
      h.push_back(q);
      if (Stands(placed, h).stands) {
        held = h;
        break;
      }
    }
  }
  if (!held) return std::nullopt;
  // Take out what the state does without, oldest first.
  for (size_t i = 0; i < held->size();) {
    std::vector<int> without = *held;
    without.erase(without.begin() + static_cast<long>(i));
    if (Stands(placed, without).stands) {
      held = without;
    } else {
      ++i;
    }
  }
  State child;
  child.placed = std::move(placed);
  child.held = *held;
  child.steps = s.steps;
  SequenceStep step;
  step.part = part;
  step.direction = arrival;
  for (int h : child.held)
    if (std::find(s.held.begin(), s.held.end(), h) == s.held.end()) step.added.push_back(h);
  for (int h : s.held)
    if (std::find(child.held.begin(), child.held.end(), h) == child.held.end())
      step.removed.push_back(h);
  child.placements = s.placements + static_cast<int>(step.added.size());
  child.max_in_place = std::max(s.max_in_place, static_cast<int>(child.held.size()));
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
std::vector<State> Search::Expand(const State& s) {
  std::vector<State> children;
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
  // found, the candidates after them cannot enter the beam.
  const double tol = assembly_.length_tolerance();
  std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
    const double ha = up_.dot(assembly_.part(a).centroid), hb = up_.dot(assembly_.part(b).centroid);
    if (std::abs(ha - hb) > tol) return ha < hb;
    return assembly_.part(a).name < assembly_.part(b).name;
  });
  std::vector<std::pair<int, Vector3>> arriving, fell;
  for (int p : candidates)
    if (const std::optional<Vector3> arrival = Arrival(s.placed, p))
      arriving.emplace_back(p, *arrival);
  int unimprovable = 0;
  for (const auto& [p, arrival] : arriving) {
    if (Stopped() || unimprovable >= options_.beam_width) break;
    std::optional<State> child = Place(s, p, arrival, /*with_new_hold=*/false);
    if (!child) {
      fell.emplace_back(p, arrival);
      continue;
    }
    if (child->held.empty()) ++unimprovable;
    children.push_back(std::move(*child));
  }
  const int bound = options_.max_temporary;
  if (static_cast<int>(children.size()) >= options_.beam_width ||
      (bound >= 0 && static_cast<int>(s.held.size()) + 1 > bound))
    return children;
  for (const auto& [p, arrival] : fell) {
    if (Stopped()) break;
    if (std::optional<State> child = Place(s, p, arrival, /*with_new_hold=*/true))
      children.push_back(std::move(*child));
  }
  return children;
}

// Fewer supports at once so far, fewer now, fewer placements, lower parts
// first, then names.
bool Search::Better(const State& a, const State& b) const {
  if (a.max_in_place != b.max_in_place) return a.max_in_place < b.max_in_place;
  if (a.held.size() != b.held.size()) return a.held.size() < b.held.size();
  if (a.placements != b.placements) return a.placements < b.placements;
  const double tol = assembly_.length_tolerance();
  if (std::abs(a.height - b.height) > tol) return a.height < b.height;
  return a.names < b.names;
}

// The beam from `start` (its steps kept) to the last part, or as far as it
// gets: best_ is its best state.
void Search::RunBeam(const State& start) {
  std::vector<State> beam = {start};
  const size_t n = movable_.size();
  out_.complete = false;
  for (size_t depth = start.steps.size(); depth < n; ++depth) {
    std::map<std::string, State> unique;  // by (placed, held): the better kept
    for (const State& s : beam)
      for (State& c : Expand(s)) {
        std::string key(c.placed.begin(), c.placed.end());
        for (int h : c.held) key += "," + std::to_string(h);
        auto it = unique.find(key);
        if (it == unique.end())
          unique.emplace(std::move(key), std::move(c));
        else if (Better(c, it->second))
          it->second = std::move(c);
      }
    if (Stopped()) {
      best_ = beam.front();
      out_.message = std::string(options_.stop && options_.stop() ? "stopped" : "time limit") +
                     " after " + std::to_string(depth) + " of " + std::to_string(n) +
                     " parts: the best order so far";
      return;
    }
    if (unique.empty()) {
      best_ = beam.front();
      out_.message =
          "no part can be placed next within " +
          (options_.max_temporary < 0
               ? std::string("the holds tried")
               : "at most " + std::to_string(options_.max_temporary) + " support(s) in place") +
          " after " + std::to_string(depth) + " of " + std::to_string(n) + " parts";
      return;
    }
    beam.clear();
    for (auto& [key, state] : unique) beam.push_back(std::move(state));
    std::sort(beam.begin(), beam.end(),
              [&](const State& a, const State& b) { return Better(a, b); });
    if (beam.size() > static_cast<size_t>(options_.beam_width))
      beam.resize(static_cast<size_t>(options_.beam_width));
    if (options_.status)
      options_.status(std::to_string(depth + 1) + "/" + std::to_string(n) +
                      " parts placed, supports at once " +
                      std::to_string(beam.front().max_in_place) + ", " +
                      std::to_string(out_.states_checked) + " states checked");
  }
  best_ = beam.front();
  if (!best_.held.empty()) {
    out_.message = "the last state still needs its holds";
    return;
  }
  out_.complete = true;
}

// The state after the first `steps` steps of best_.
State Search::Prefix(int steps) const {
  State s;
  s.placed.assign(assembly_.num_parts(), false);
  for (int i = 0; i < steps; ++i) {
    const SequenceStep& step = best_.steps[i];
    s.placed[step.part] = true;
    for (int h : step.added) s.held.push_back(h);
    for (int h : step.removed) s.held.erase(std::find(s.held.begin(), s.held.end(), h));
    s.placements += static_cast<int>(step.added.size());
    s.max_in_place = std::max(s.max_in_place, static_cast<int>(s.held.size()));
    s.height += up_.dot(assembly_.part(step.part).centroid);
    s.names += assembly_.part(step.part).name + '\n';
    s.steps.push_back(step);
  }
  return s;
}

// Every order passes through a state of one part and one of all parts but
// one: when none of either stands without support, every order needs one.
void Search::ComputeLowerBound() {
  ArgueLowerBound();
  ExhaustiveLowerBound();
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
      if (Stands(placed, held).stands) return true;
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
    if (reachable[all]) {
      out_.lower_bound = b;
      out_.lower_bound_reason = "every order of the " + std::to_string(n) +
                                " parts tried: the fewest supports at once any order needs";
      return;
    }
    out_.lower_bound = b + 1;
    out_.lower_bound_reason = "every order of the " + std::to_string(n) +
                              " parts tried: none does with fewer supports at once";
  }
}

// Every state of the order checked again, afresh (no cache, no warm start),
// by the check's verdict, with what each hold carries. Returns the first
// step whose state does not stand (-1: none).
int Search::ConfirmAndMeasureHolds() {
  int first_failing = -1;
  unconfirmed_from_ = -1;
  std::vector<bool> placed(assembly_.num_parts(), false);
  std::vector<int> held;
  for (size_t i = 0; i < best_.steps.size(); ++i) {
    SequenceStep& step = best_.steps[i];
    if (options_.checkpoint) options_.checkpoint();
    if (ConfirmationOutOfTime()) {
      unconfirmed_from_ = static_cast<int>(i);
      return first_failing;
    }
    placed[step.part] = true;
    for (int h : step.added) held.push_back(h);
    for (int h : step.removed) held.erase(std::find(held.begin(), held.end(), h));
    std::vector<int> sorted = held;
    std::sort(sorted.begin(), sorted.end());
    const Configuration config = ConfigOf(placed);
    const StabilityResult r =
        AnalyzeConfiguration(HeldAssembly(sorted), config, options_.stability);
    step.stability = r.stability;
    step.stands =
        r.stable() && (!options_.require_strong || r.stability == StabilityProof::kStrong);
    step.in_place.clear();
    for (int h : held) {
      TemporarySupport t;
      t.part = h;
      const Part& part = assembly_.part(h);
      Vector3 force = part.mass * assembly_.gravity(), torque = Vector3::Zero();
      for (const ContactReport& c : r.contacts) {
        const Vector3 f = c.normal_force * c.contact.n_W + c.friction_force;  // on a
        const double sign = c.contact.part_a == h ? 1.0 : c.contact.part_b == h ? -1.0 : 0.0;
        if (sign == 0) continue;
        force += sign * f;
        torque += (c.contact.p_WC - part.centroid).cross(sign * f);
      }
      t.force = -force;
      t.torque = -torque;
      step.in_place.push_back(t);
    }
    if (!step.stands && first_failing < 0) first_failing = static_cast<int>(i);
  }
  return first_failing;
}

BuildSequence Search::Run() {
  if (!CheckAssembled()) {
    ComputeLowerBound();
    return out_;
  }
  ComputeAdjacencyAndBlocking();
  // The search on the equilibrium LP, then its order confirmed state by
  // state by the check's verdict; where a state is rejected, the search
  // goes on from the state before it with the verdict itself (the repair).
  State start;
  start.placed.assign(assembly_.num_parts(), false);
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
    full_ = true;
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
  return Search(assembly, options).Run();
}

}  // namespace cairn

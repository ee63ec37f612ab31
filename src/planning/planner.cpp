#include "cairn/planning/planner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "cairn/contact/detect_contacts.h"
#include "cairn/core/check.h"
#include "cairn/core/error.h"
#include "cairn/core/format.h"
#include "cairn/core/tolerances.h"
#include "cairn/mechanics/rest_solution.h"
#include "cairn/planning/blocking.h"
#include "cairn/stability/analyze.h"
#include "planning/task_codec.h"

namespace cairn {

namespace {
// The fixture search on a failing path of `cairn plan --allow-fixtures`: at
// most this many candidate fixels and this many verifying simulations per
// path (a bounded search per edge, where `cairn simulate --suggest-fixtures`
// has its own defaults): counts of candidates and of simulations.
constexpr int kPathFixelCandidates = 8;
constexpr int kPathFixelSimulations = 60;
}  // namespace
namespace {

// The most sequences listed when the whole graph is enumerated and the user
// set no --max: beyond it the count is still exact (PlannerStats).
constexpr size_t kMaxListed = 10000;

// ---- Node keys -------------------------------------------------------------

// The movable parts present in a node, one bit per slot (an index into
// Planner::movable_), in 64-bit words: any number of parts.
using Key = std::vector<uint64_t>;

struct KeyHash {
  size_t operator()(const Key& k) const {
    uint64_t h = 1469598103934665603ull;
    for (uint64_t w : k) h = (h ^ w) * 1099511628211ull;
    return static_cast<size_t>(h);
  }
};

bool Has(const Key& k, int slot) { return (k[slot / 64] >> (slot % 64)) & 1u; }
void Set(Key& k, int slot) { k[slot / 64] |= uint64_t{1} << (slot % 64); }
void Clear(Key& k, int slot) { k[slot / 64] &= ~(uint64_t{1} << (slot % 64)); }
int Count(const Key& k) {
  int c = 0;
  for (uint64_t w : k) c += __builtin_popcountll(w);
  return c;
}

// ---- A small, deterministic worker pool -------------------------------------

// Best-first search evaluates this many of a node's edges at a time (in
// parallel where there are threads), speculatively: a fixed number, not the
// number of threads, so that which edges are evaluated, and so the graph and
// the statistics the search reports, are the same whatever the threads.
constexpr int kBestFirstBatch = 2;

// Runs task(i) for i in [0, n) on `threads` threads. Results go to slots the
// caller indexes by i, so the outcome does not depend on the interleaving.
void ParallelFor(int n, int threads, const std::function<void(int)>& task) {
  if (n <= 0) return;
  threads = std::max(1, std::min(threads, n));
  if (threads == 1) {
    for (int i = 0; i < n; ++i) task(i);
    return;
  }
  std::atomic<int> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto work = [&] {
    for (int i = next++; i < n; i = next++) {
      try {
        task(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
    // The LP solvers keep per-thread state; give it back before the thread
    // ends (LeakSanitizer would report it, rightly).
    ReleaseThreadSolverState();
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// The executor of a single process: every task here, on its threads.
class LocalExecutor final : public PlanExecutor {
 public:
  int processes() const override { return 1; }
  std::vector<std::string> Map(const std::vector<double>& cost, int threads,
                               const std::function<std::string(int)>& task) override {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::string> out(cost.size());
    ParallelFor(static_cast<int>(cost.size()), threads, [&](int i) { out[i] = task(i); });
    work_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  }
  void Times(std::vector<double>& work, std::vector<double>& communication) override {
    work = {work_};
    communication = {0.0};
  }

 private:
  double work_ = 0;
};

// Estimated costs of the tasks (PlanExecutor::Map balances by them), in
// units of one part's share of a configuration check: a check grows about
// with the square of the parts present (contacts, then the LCP), a simulated
// path with that times its time steps.
double NodeCheckCost(int parts) { return 1.0 + static_cast<double>(parts) * parts; }

// A direction for people: "up", "down", "+x", or "(0.7071, 0.7071)".
std::string DirectionLabel(const Vector3& d, const Vector3& up, int dimension) {
  if (d.dot(up) > 1 - numeric::kParameterSlack) return "up";
  if (d.dot(up) < -1 + numeric::kParameterSlack) return "down";
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < dimension; ++k) {
    if (d[k] > 1 - numeric::kParameterSlack) return std::string("+") + axes[k];
    if (d[k] < -1 + numeric::kParameterSlack) return std::string("-") + axes[k];
  }
  return FormatPoint(d, dimension);
}

// ---- The planner -------------------------------------------------------------

// One subassembly that can leave a node, with its candidate paths in the
// order they are tried.
struct EdgeCandidate {
  std::vector<int> remove;  // ascending part indices
  std::vector<CandidatePath> paths;
  double height = 0;  // highest centroid of S along "up": best-first order
};

// What one edge evaluation did (summed into PlannerStats afterwards, in a
// fixed order).
struct EdgeWork {
  int simulations = 0, by_nodes = 0, pruned = 0;
};

class Planner {
 public:
  Planner(const AssemblyDef& def, const Assembly& assembly, const PlannerOptions& options)
      : def_(def), assembly_(assembly), opt_(options) {}

  PlannerResult Run();

 private:
  // Setup.
  void ChooseParts();
  void ComputeDirections();
  // Nodes.
  int NodeIndex(const Key& key);  // creates the node (unchecked) when new
  void CheckNodes(std::vector<int> nodes);
  Configuration ConfigOf(const Key& key) const;
  std::vector<bool> PresentOf(const Key& key) const;
  std::vector<int> PartsOf(const Key& key) const;
  // Edges.
  std::vector<EdgeCandidate> Candidates(const Key& key) const;
  double StraightDistance(const std::vector<bool>& present, const std::vector<int>& s,
                          const Vector3& d) const;
  bool AllContactsOpen(const std::vector<Contact>& contacts, const std::vector<int>& s,
                       const Vector3& d) const;
  void AddEdges(int node, std::vector<EdgeCandidate> candidates);
  void EvaluateEdges(const std::vector<int>& edges);
  EdgeWork EvaluateEdge(PlanEdge& edge, const std::vector<Contact>& contacts) const;
  double EdgeCost(const PlanEdge& edge) const;
  PathTrial Trial(const Key& from_key, const std::vector<int>& s, const CandidatePath& c,
                  const std::vector<Contact>& contacts, EdgeWork& work) const;
  Plan OneStepPlan(const std::vector<int>& s, const CandidatePath& c, PlanMode mode) const;
  SimulationOptions NodeSimulation(const Key& from_key) const;
  SimulationResult Simulate(const Key& from_key, const std::vector<int>& s, const CandidatePath& c,
                            PlanMode mode) const;
  void FixtureSearch();
  // A path of the fixture search: the fixels it needs (none when it is
  // stable as is; at most `budget`), or empty when no fixels make it stable.
  std::optional<std::vector<FixtureDef>> FixelsForPath(const AssemblyDef& def,
                                                       const Assembly& fixed,
                                                       const std::vector<int>& remove,
                                                       const CandidatePath& c, const Key& key,
                                                       int budget);
  // Records the edge key → to of the fixture search, along `c` with the
  // fixels `added`; its index.
  int RecordFixtureEdge(const Key& key, const Key& to, const std::vector<int>& remove,
                        const CandidatePath& c, const std::vector<FixtureDef>& added);
  // Search.
  void Enumerate();
  void BestFirst();
  bool Visit(int node, std::vector<int>& stack);
  void ListSequences();
  PlannedSequence MakeSequence(const std::vector<int>& edges, bool assembly) const;

  const AssemblyDef& def_;
  const Assembly& assembly_;
  const PlannerOptions& opt_;
  PlannerResult result_;
  int threads_ = 1;
  int words_ = 1;
  std::vector<int> movable_;           // slot → part index
  std::vector<int> slot_of_;           // part index → slot, or −1
  std::vector<bool> base_present_;     // fixed and kept parts
  std::vector<BlockingGraph> graphs_;  // DBG to infinity per candidate direction
  std::vector<Vector3> lo_, hi_;       // each part's bounding box, assembled pose
  Vector3 up_{0, 1, 0};                // −gravity, unit
  std::vector<Key> keys_;              // node index → key
  std::unordered_map<Key, int, KeyHash> index_;
  std::vector<bool> checked_;                        // node index → stability known
  std::vector<std::vector<int>> out_edges_;          // node index → edge indices, in trial order
  std::vector<bool> evaluated_;                      // edge index → trials done
  std::vector<char> dead_;                           // best-first: node has no stable completion
  std::vector<std::vector<Contact>> node_contacts_;  // contacts per node (friction scenes)
  LocalExecutor local_;
  PlanExecutor* executor_ = &local_;  // where node checks and edges run
  // Try every candidate path of an edge (full enumeration: the verdicts of
  // all paths, non-invertible ones included), rather than stopping at the
  // first straight removal stable both ways (best-first search).
  bool all_paths_ = true;
  int found_ = 0;                              // best-first: sequences found
  std::vector<std::vector<int>> found_edges_;  // best-first: their edges
};

void Planner::ChooseParts() {
  const int n = assembly_.num_parts();
  std::vector<bool> keep(n, false);
  for (int p : opt_.keep) {
    CAIRN_THROW_UNLESS(p >= 0 && p < n, "PlanDisassembly: kept part out of range");
    keep[p] = true;
  }
  slot_of_.assign(n, -1);
  base_present_.assign(n, false);
  lo_.assign(n, Vector3::Zero());
  hi_.assign(n, Vector3::Zero());
  for (int p = 0; p < n; ++p) {
    const Part& part = assembly_.part(p);
    lo_[p] = hi_[p] = part.vertices.front();
    for (const Vector3& v : part.vertices) {
      lo_[p] = lo_[p].cwiseMin(v);
      hi_[p] = hi_[p].cwiseMax(v);
    }
    if (part.tool) continue;
    if (part.fixed || keep[p]) {
      base_present_[p] = true;
    } else {
      slot_of_[p] = static_cast<int>(movable_.size());
      movable_.push_back(p);
    }
  }
  words_ = std::max<int>(1, (static_cast<int>(movable_.size()) + 63) / 64);
}

// Candidate directions: the NDBG cells of the assembled configuration, each
// with its DBG to infinity (arcs between two parts do not depend on the
// others, so one graph serves every node); preferred first: closest to
// straight up (paper Corollary 1: motion against gravity never makes a
// path-dependent instability).
void Planner::ComputeDirections() {
  const Configuration config = Configuration::Assembled(assembly_);
  Ndbg ndbg;
  if (opt_.directions.empty()) {
    ndbg = ComputeNdbg(assembly_, config);
  } else {
    // The given directions alone, one cell each; a direction opposite one
    // already done has its graphs reversed (Reversed), not computed again.
    for (const Vector3& d : opt_.directions) {
      const auto opposite = std::find_if(
          ndbg.cells.begin(), ndbg.cells.end(),
          [&](const NdbgCell& c) { return (c.direction + d).norm() < numeric::kRoundoff; });
      if (opposite == ndbg.cells.end()) {
        ndbg.cells.push_back(ComputeBlockingAt(assembly_, config, d).cells[0]);
        continue;
      }
      NdbgCell cell = *opposite;
      cell.direction = d;
      for (int& sign : cell.signs) sign = -sign;
      if (!assembly_.is_3d()) {
        cell.angle_from = std::fmod(cell.angle_from + std::numbers::pi, 2 * std::numbers::pi);
        cell.angle_to = std::fmod(cell.angle_to + std::numbers::pi, 2 * std::numbers::pi);
      }
      cell.infinitesimal = Reversed(opposite->infinitesimal);
      cell.infinity = Reversed(opposite->infinity);
      ndbg.cells.push_back(std::move(cell));
    }
  }
  graphs_ = InfinityGraphsUpFirst(std::move(ndbg.cells), up_);
}

std::vector<bool> Planner::PresentOf(const Key& key) const {
  std::vector<bool> present = base_present_;
  for (size_t s = 0; s < movable_.size(); ++s)
    if (Has(key, static_cast<int>(s))) present[movable_[s]] = true;
  return present;
}

Configuration Planner::ConfigOf(const Key& key) const {
  Configuration config = Configuration::Assembled(assembly_);
  config.present = PresentOf(key);
  return config;
}

std::vector<int> Planner::PartsOf(const Key& key) const {
  std::vector<int> parts;
  for (size_t s = 0; s < movable_.size(); ++s)
    if (Has(key, static_cast<int>(s))) parts.push_back(movable_[s]);
  std::sort(parts.begin(), parts.end());
  return parts;
}

int Planner::NodeIndex(const Key& key) {
  const auto it = index_.find(key);
  if (it != index_.end()) {
    ++result_.stats.memo_hits;
    return it->second;
  }
  const int i = static_cast<int>(keys_.size());
  keys_.push_back(key);
  index_.emplace(key, i);
  PlanNode node;
  node.parts = PartsOf(key);
  result_.nodes.push_back(node);
  checked_.push_back(false);
  out_edges_.emplace_back();
  dead_.push_back(0);
  node_contacts_.emplace_back();
  return i;
}

// The stability of each node, once (the memo): the configuration with its
// parts at their assembled poses, from rest.
void Planner::CheckNodes(std::vector<int> nodes) {
  nodes.erase(std::remove_if(nodes.begin(), nodes.end(), [&](int i) { return checked_[i]; }),
              nodes.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  const bool friction = !assembly_.IsFrictionless();
  std::vector<double> cost;
  for (int i : nodes) cost.push_back(NodeCheckCost(Count(keys_[i])));
  // Each check's result travels as bytes (PlanExecutor): its verdict and,
  // with friction, its contacts (kept for the edges out of the node: with
  // friction, only contacts that open at once let node checks decide an
  // edge).
  const std::vector<std::string> results = executor_->Map(cost, threads_, [&](int k) {
    if (opt_.checkpoint) opt_.checkpoint();
    const Configuration config = ConfigOf(keys_[nodes[k]]);
    StabilityOptions options;
    options.rule = opt_.rule;
    const StabilityResult r = AnalyzeConfiguration(assembly_, config, options);
    planning_codec::Writer w;
    w.Put(static_cast<uint8_t>(r.stable() &&
                               (!opt_.require_strong || r.stability == StabilityProof::kStrong)));
    std::vector<Contact> contacts;
    if (friction) {
      const Tolerances tol = assembly_.MakeTolerances();
      contacts = DetectContacts(assembly_, config, tol.length, tol.angle);
    }
    w.Put(contacts);
    return w.Take();
  });
  for (size_t k = 0; k < nodes.size(); ++k) {
    planning_codec::Reader r(results[k]);
    uint8_t stable = 0;
    r.Get(stable);
    r.Get(node_contacts_[nodes[k]]);
    result_.nodes[nodes[k]].stable = stable != 0;
    checked_[nodes[k]] = true;
  }
  result_.stats.node_checks += static_cast<int>(nodes.size());
  if (opt_.on_progress) opt_.on_progress(result_.stats);
}

// How far a straight removal goes: until the bounding box of S clears the
// box of every part that stays (touching counts as clear), then S's own
// length along d, so the subassembly ends well away from the rest.
double Planner::StraightDistance(const std::vector<bool>& present, const std::vector<int>& s,
                                 const Vector3& d) const {
  Vector3 lo = lo_[s[0]], hi = hi_[s[0]];
  double dmin = std::numeric_limits<double>::infinity(), dmax = -dmin;
  std::vector<bool> in_s(assembly_.num_parts(), false);
  for (int p : s) {
    in_s[p] = true;
    lo = lo.cwiseMin(lo_[p]);
    hi = hi.cwiseMax(hi_[p]);
    for (const Vector3& v : assembly_.part(p).vertices) {
      dmin = std::min(dmin, v.dot(d));
      dmax = std::max(dmax, v.dot(d));
    }
  }
  const double eps = numeric::kRoundoff;
  double clear = 0;
  for (int j = 0; j < assembly_.num_parts(); ++j) {
    if (!present[j] || in_s[j]) continue;
    double t_j = std::numeric_limits<double>::infinity();
    for (int k = 0; k < assembly_.dimension(); ++k) {
      if (hi[k] <= lo_[j][k] || lo[k] >= hi_[j][k]) {
        t_j = 0;
        break;
      }
      if (d[k] > eps) t_j = std::min(t_j, (hi_[j][k] - lo[k]) / d[k]);
      if (d[k] < -eps) t_j = std::min(t_j, (hi[k] - lo_[j][k]) / -d[k]);
    }
    if (std::isfinite(t_j)) clear = std::max(clear, t_j);
  }
  return clear + (dmax - dmin);
}

// Every contact between S and the rest opens at once along d (d · n > 0 on
// S's side beyond the angle tolerance): after the first instant S touches
// nothing, so the rest sees only the nodes before and after.
bool Planner::AllContactsOpen(const std::vector<Contact>& contacts, const std::vector<int>& s,
                              const Vector3& d) const {
  const double tol = assembly_.MakeTolerances().angle;
  const auto in_s = [&](int p) { return p >= 0 && std::binary_search(s.begin(), s.end(), p); };
  for (const Contact& c : contacts) {
    const bool a = in_s(c.part_a), b = in_s(c.part_b);
    if (a == b) continue;
    const double opening = a ? d.dot(c.n_W) : -d.dot(c.n_W);
    if (opening <= tol) return false;
  }
  return true;
}

// The subassemblies that can leave the node, each with its paths: for every
// candidate direction and every part, the part's closure in DBG(d) (a union
// of strongly connected components) when it holds no fixed or kept part;
// plus the paths the user gave for single parts.
std::vector<EdgeCandidate> Planner::Candidates(const Key& key) const {
  const std::vector<bool> present = PresentOf(key);
  std::map<std::vector<int>, EdgeCandidate> by_set;
  const auto entry = [&](const std::vector<int>& s) -> EdgeCandidate& {
    EdgeCandidate& e = by_set[s];
    if (e.remove.empty()) {
      e.remove = s;
      e.height = -std::numeric_limits<double>::infinity();
      for (int p : s) e.height = std::max(e.height, assembly_.part(p).centroid.dot(up_));
    }
    return e;
  };
  // Given paths first, in the file's order.
  for (size_t slot = 0; slot < movable_.size(); ++slot) {
    if (!Has(key, static_cast<int>(slot))) continue;
    const auto it = opt_.given_paths.find(movable_[slot]);
    if (it == opt_.given_paths.end()) continue;
    EdgeCandidate& e = entry({movable_[slot]});
    for (const CandidatePath& c : it->second) e.paths.push_back(c);
  }
  std::vector<SupportMode> supports;
  if (opt_.support != SupportChoice::kNone) supports.push_back(SupportMode::kFull);
  if (opt_.support != SupportChoice::kFull) supports.push_back(SupportMode::kNone);
  for (const BlockingGraph& g : graphs_) {
    std::set<std::vector<int>> seen;
    for (size_t slot = 0; slot < movable_.size(); ++slot) {
      if (!Has(key, static_cast<int>(slot))) continue;
      const std::vector<int> s = BlockingClosure(g, movable_[slot], present);
      if (!seen.insert(s).second) continue;
      const bool movable = std::all_of(s.begin(), s.end(), [&](int p) { return slot_of_[p] >= 0; });
      if (!movable || (!opt_.subassemblies && s.size() > 1)) continue;
      // Lifting the whole assembly off the fixed parts in one piece is no
      // disassembly; the last subassembly left may leave whole (paper Fig. 17:
      // {A, B}, then {C, D}).
      if (s.size() > 1 && s.size() == movable_.size()) continue;
      EdgeCandidate& e = entry(s);
      const double distance = StraightDistance(present, s, g.direction);
      for (SupportMode support : supports) {
        CandidatePath c;
        c.path = {Vector3::Zero(), distance * g.direction};
        c.support = support;
        c.straight = true;
        c.direction = g.direction;
        c.label = DirectionLabel(g.direction, up_, assembly_.dimension());
        if (opt_.support == SupportChoice::kBoth)
          c.label += std::string(", support ") + to_string(support);
        e.paths.push_back(c);
      }
    }
  }
  std::vector<EdgeCandidate> out;
  for (auto& [s, e] : by_set) out.push_back(std::move(e));
  // Best first: the highest subassembly (a top-down disassembly rarely
  // leaves anything unsupported), the smaller one, then by parts.
  std::stable_sort(out.begin(), out.end(), [](const EdgeCandidate& a, const EdgeCandidate& b) {
    if (a.height != b.height) return a.height > b.height;
    return a.remove.size() < b.remove.size();
  });
  return out;
}

// Adds the node's edges (unevaluated), creating their target nodes in a
// fixed order.
void Planner::AddEdges(int node, std::vector<EdgeCandidate> candidates) {
  for (EdgeCandidate& c : candidates) {
    Key to = keys_[node];
    for (int p : c.remove) Clear(to, slot_of_[p]);
    const int to_node = NodeIndex(to);
    PlanEdge edge;
    edge.from = node;
    edge.to = to_node;
    edge.remove = c.remove;
    for (CandidatePath& p : c.paths) {
      PathTrial t;
      t.candidate = std::move(p);
      edge.trials.push_back(std::move(t));
    }
    out_edges_[node].push_back(static_cast<int>(result_.edges.size()));
    result_.edges.push_back(std::move(edge));
    evaluated_.push_back(false);
  }
  result_.nodes[node].expanded = true;
}

// The plan of one edge: S out of (or, assembling, into) the node along c.
Plan Planner::OneStepPlan(const std::vector<int>& s, const CandidatePath& c, PlanMode mode) const {
  Plan plan;
  plan.mode = mode;
  plan.dt = result_.dt;
  plan.speed = result_.speed;
  PlanStep step;
  step.remove = s;
  step.grip = s;
  for (int g : c.grip)
    if (std::find(step.grip.begin(), step.grip.end(), g) == step.grip.end()) step.grip.push_back(g);
  step.path = c.path;
  step.support = c.support;
  plan.steps.push_back(step);
  return plan;
}

// A simulation that starts from the node: the parts it lacks are absent.
SimulationOptions Planner::NodeSimulation(const Key& from_key) const {
  SimulationOptions so;
  so.carry_when_unsupported = true;
  so.rule = opt_.rule;
  if (opt_.checkpoint) {
    const std::function<void()> checkpoint = opt_.checkpoint;
    so.on_analysis = [checkpoint](const AnalysisInputs&) { checkpoint(); };
  }
  for (size_t slot = 0; slot < movable_.size(); ++slot)
    if (!Has(from_key, static_cast<int>(slot))) so.absent.push_back(movable_[slot]);
  return so;
}

SimulationResult Planner::Simulate(const Key& from_key, const std::vector<int>& s,
                                   const CandidatePath& c, PlanMode mode) const {
  return SimulatePlan(assembly_, OneStepPlan(s, c, mode), NodeSimulation(from_key));
}

PathTrial Planner::Trial(const Key& from_key, const std::vector<int>& s, const CandidatePath& c,
                         const std::vector<Contact>& contacts, EdgeWork& work) const {
  PathTrial t;
  t.candidate = c;
  // Corollary 2 with Proposition 2: S carried whole, rigidly, along a free
  // straight path; without friction, or with every contact opening at once,
  // the rest feels only the two nodes, both stable.
  const bool node_checks =
      c.straight && c.support == SupportMode::kFull && c.grip.empty() &&
      (assembly_.IsFrictionless() || AllContactsOpen(contacts, s, c.direction));
  if (node_checks) {
    t.disassembly = t.assembly = MotionVerdict::kStable;
    t.decided_by = "nodes";
    ++work.by_nodes;
    return t;
  }
  const SimulationResult dis = Simulate(from_key, s, c, PlanMode::kDisassemble);
  const SimulationResult as = Simulate(from_key, s, c, PlanMode::kAssemble);
  work.simulations += 2;
  t.disassembly = dis.verdict;
  t.assembly = as.verdict;
  t.decided_by = "simulation";
  if (dis.failure) {
    t.failure = dis.failure;
    t.failure_mode = PlanMode::kDisassemble;
  } else if (as.failure) {
    t.failure = as.failure;
    t.failure_mode = PlanMode::kAssemble;
  }
  return t;
}

// Tries the edge's paths in order: every given path, then the straight
// removals (all of them in full enumeration; in best-first search until one
// is stable both ways). Proposition 1 first: when the rest cannot
// stand without S, no path can help (and the assembly direction starts from
// that same unstable rest).
EdgeWork Planner::EvaluateEdge(PlanEdge& edge, const std::vector<Contact>& contacts) const {
  EdgeWork work;
  const Key& from_key = keys_[edge.from];
  if (!result_.nodes[edge.to].stable) {
    PathTrial& t = edge.trials.front();
    t.disassembly = t.assembly = MotionVerdict::kUnstable;
    t.decided_by = "proposition 1";
    edge.trials.resize(1);
    ++work.pruned;
    return work;
  }
  size_t tried = 0;
  for (; tried < edge.trials.size(); ++tried) {
    PathTrial& t = edge.trials[tried];
    t = Trial(from_key, edge.remove, t.candidate, contacts, work);
    const bool both =
        t.disassembly == MotionVerdict::kStable && t.assembly == MotionVerdict::kStable;
    if (both && t.candidate.straight && !all_paths_) {
      ++tried;
      break;
    }
  }
  edge.trials.resize(tried);
  for (size_t k = 0; k < edge.trials.size(); ++k) {
    const PathTrial& t = edge.trials[k];
    const bool dis = t.disassembly == MotionVerdict::kStable;
    const bool as = t.assembly == MotionVerdict::kStable;
    if (dis && as &&
        (edge.chosen < 0 || edge.trials[edge.chosen].assembly != MotionVerdict::kStable))
      edge.chosen = static_cast<int>(k);
    if (dis && edge.chosen < 0) edge.chosen = static_cast<int>(k);
    if (as &&
        (edge.assembly_chosen < 0 ||
         edge.trials[edge.assembly_chosen].disassembly != MotionVerdict::kStable) &&
        (dis || edge.assembly_chosen < 0))
      edge.assembly_chosen = static_cast<int>(k);
  }
  return work;
}

// An edge's estimated work: nothing much when Proposition 1 decides it or
// node checks do (a straight, fully supported removal without friction),
// else two simulations (disassembly and assembly) of its path's time steps
// on the parts present. With friction, whether the contacts open at once is
// not known before: such paths count as simulated (an upper bound).
double Planner::EdgeCost(const PlanEdge& edge) const {
  if (!result_.nodes[edge.to].stable) return 1.0;
  const double parts = Count(keys_[edge.from]);
  double cost = 1.0;
  for (const PathTrial& t : edge.trials) {
    const CandidatePath& c = t.candidate;
    if (c.straight && c.support == SupportMode::kFull && c.grip.empty() &&
        assembly_.IsFrictionless())
      continue;
    double length = 0;
    for (size_t k = 1; k < c.path.size(); ++k) length += (c.path[k] - c.path[k - 1]).norm();
    const double ticks = 1.0 + std::ceil(length / (result_.speed * result_.dt));
    cost += 2 * ticks * NodeCheckCost(static_cast<int>(parts));
  }
  return cost;
}

void Planner::EvaluateEdges(const std::vector<int>& edges) {
  std::vector<int> todo;
  for (int e : edges)
    if (!evaluated_[e]) todo.push_back(e);
  std::vector<int> targets;
  for (int e : todo) targets.push_back(result_.edges[e].to);
  CheckNodes(targets);
  // Each evaluation works on a copy of its edge and sends back what it found
  // (PlanExecutor): the trials tried, their verdicts and failures, the
  // chosen paths and the work done; the candidates are the same everywhere.
  std::vector<double> cost;
  for (int e : todo) cost.push_back(EdgeCost(result_.edges[e]));
  const std::vector<std::string> results = executor_->Map(cost, threads_, [&](int k) {
    PlanEdge edge = result_.edges[todo[k]];
    const EdgeWork work = EvaluateEdge(edge, node_contacts_[edge.from]);
    planning_codec::Writer w;
    w.Put(work.simulations), w.Put(work.by_nodes), w.Put(work.pruned);
    w.Put(edge.chosen), w.Put(edge.assembly_chosen);
    w.Put(static_cast<uint64_t>(edge.trials.size()));
    for (const PathTrial& t : edge.trials) w.Put(t);
    return w.Take();
  });
  for (size_t k = 0; k < todo.size(); ++k) {
    PlanEdge& edge = result_.edges[todo[k]];
    planning_codec::Reader r(results[k]);
    EdgeWork work;
    r.Get(work.simulations), r.Get(work.by_nodes), r.Get(work.pruned);
    r.Get(edge.chosen), r.Get(edge.assembly_chosen);
    uint64_t tried = 0;
    r.Get(tried);
    CAIRN_THROW_UNLESS(tried <= edge.trials.size(), "planner: an edge came back with more trials");
    edge.trials.resize(tried);
    for (PathTrial& t : edge.trials) r.Get(t);
    evaluated_[todo[k]] = true;
    result_.stats.path_simulations += work.simulations;
    result_.stats.decided_by_nodes += work.by_nodes;
    result_.stats.pruned_by_proposition_1 += work.pruned;
  }
  if (opt_.on_progress) opt_.on_progress(result_.stats);
}

// Full enumeration, by the number of parts present, largest first: expand
// every node that is stable and reached by an edge stable in disassembly or
// in assembly (an unstable node prunes every sequence through it:
// Proposition 1). Within a count, nodes are expanded and their edges
// evaluated in parallel; everything is merged in node order.
void Planner::Enumerate() {
  const int m = static_cast<int>(movable_.size());
  std::vector<std::vector<int>> bucket(m + 1);
  std::vector<bool> queued(1, true);
  bucket[m].push_back(0);
  for (int count = m; count >= 1; --count) {
    std::vector<int> level = bucket[count];
    std::sort(level.begin(), level.end());
    level.erase(
        std::remove_if(level.begin(), level.end(), [&](int i) { return !result_.nodes[i].stable; }),
        level.end());
    if (level.empty()) continue;
    std::vector<std::vector<EdgeCandidate>> cands(level.size());
    ParallelFor(static_cast<int>(level.size()), threads_,
                [&](int k) { cands[k] = Candidates(keys_[level[k]]); });
    std::vector<int> new_edges;
    for (size_t k = 0; k < level.size(); ++k) {
      const size_t first = result_.edges.size();
      AddEdges(level[k], std::move(cands[k]));
      for (size_t e = first; e < result_.edges.size(); ++e)
        new_edges.push_back(static_cast<int>(e));
    }
    EvaluateEdges(new_edges);
    queued.resize(result_.nodes.size(), false);
    for (int e : new_edges) {
      const PlanEdge& edge = result_.edges[e];
      if (edge.chosen < 0 && edge.assembly_chosen < 0) continue;
      if (queued[edge.to]) continue;
      queued[edge.to] = true;
      bucket[Count(keys_[edge.to])].push_back(edge.to);
    }
  }
  result_.complete = true;
}

// Best-first search: depth first along the most promising edge, edges
// evaluated lazily (kBestFirstBatch at a time, in parallel), nodes without a
// stable completion remembered.
bool Planner::Visit(int node, std::vector<int>& stack) {
  if (found_ >= opt_.max_sequences) return false;
  if (Count(keys_[node]) == 0) {
    found_edges_.push_back(stack);
    ++found_;
    return true;
  }
  if (!result_.nodes[node].expanded) AddEdges(node, Candidates(keys_[node]));
  bool any = false;
  const std::vector<int> edges = out_edges_[node];
  for (size_t k = 0; k < edges.size() && found_ < opt_.max_sequences; ++k) {
    if (!evaluated_[edges[k]]) {
      std::vector<int> batch;
      for (size_t b = k; b < edges.size() && static_cast<int>(batch.size()) < kBestFirstBatch; ++b)
        if (!evaluated_[edges[b]] && !dead_[result_.edges[edges[b]].to]) batch.push_back(edges[b]);
      if (batch.empty()) batch.push_back(edges[k]);
      EvaluateEdges(batch);
    }
    const PlanEdge& edge = result_.edges[edges[k]];
    if (edge.chosen < 0 || dead_[edge.to]) continue;
    stack.push_back(edges[k]);
    if (Visit(edge.to, stack)) any = true;
    stack.pop_back();
  }
  if (!any && found_ < opt_.max_sequences) dead_[node] = 1;
  return any;
}

void Planner::BestFirst() {
  std::vector<int> stack;
  Visit(0, stack);
  result_.complete = false;
  for (const std::vector<int>& edges : found_edges_)
    result_.sequences.push_back(MakeSequence(edges, false));
}

PlannedSequence Planner::MakeSequence(const std::vector<int>& edges, bool assembly) const {
  PlannedSequence seq;
  seq.invertible = true;
  for (int e : edges) {
    const PlanEdge& edge = result_.edges[e];
    PlannedStep step;
    step.edge = e;
    step.trial = assembly ? edge.assembly_chosen : edge.chosen;
    const PathTrial& t = edge.trials[step.trial];
    const CandidatePath& c = t.candidate;
    for (int p : edge.remove) step.step.remove.push_back(assembly_.part(p).name);
    if (!c.grip.empty()) {
      step.step.grip = step.step.remove;
      for (int g : c.grip) step.step.grip.push_back(assembly_.part(g).name);
    }
    if (c.straight) {
      step.step.has_direction = true;
      step.step.direction = c.direction;
      step.step.distance = (c.path.back() - c.path.front()).norm();
    } else {
      step.step.has_path = true;
      step.step.path = c.path;
    }
    step.step.support = c.support;
    step.assembly_stable = t.assembly == MotionVerdict::kStable;
    seq.invertible = seq.invertible && step.assembly_stable;
    seq.steps.push_back(std::move(step));
  }
  return seq;
}

// Counts the stable completions of every expanded node (a sum over its
// stable edges: monotone sequences are paths of a DAG), then lists the
// sequences in edge order: disassembly sequences, and those stable only as
// assemblies.
void Planner::ListSequences() {
  const int n = static_cast<int>(result_.nodes.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return Count(keys_[a]) < Count(keys_[b]); });
  std::vector<double> ways(n, 0), ways_as(n, 0);
  for (int v : order) {
    if (!result_.nodes[v].stable) continue;
    if (Count(keys_[v]) == 0) {
      ways[v] = ways_as[v] = 1;
      continue;
    }
    for (int e : out_edges_[v]) {
      const PlanEdge& edge = result_.edges[e];
      if (edge.chosen >= 0) ways[v] += ways[edge.to];
      if (edge.assembly_chosen >= 0) ways_as[v] += ways_as[edge.to];
    }
  }
  result_.stats.sequences_total = ways[0];
  const size_t limit =
      opt_.max_sequences > 0 ? static_cast<size_t>(opt_.max_sequences) : kMaxListed;

  std::vector<int> stack;
  std::function<void(int, bool, bool)> walk = [&](int v, bool assembly, bool some_unstable) {
    std::vector<PlannedSequence>& out = assembly ? result_.assembly_only : result_.sequences;
    if (out.size() >= limit) return;
    if (Count(keys_[v]) == 0) {
      if (!assembly || some_unstable) out.push_back(MakeSequence(stack, assembly));
      return;
    }
    for (int e : out_edges_[v]) {
      const PlanEdge& edge = result_.edges[e];
      const int trial = assembly ? edge.assembly_chosen : edge.chosen;
      if (trial < 0 || (assembly ? ways_as : ways)[edge.to] <= 0) continue;
      const bool unstable = edge.trials[trial].disassembly != MotionVerdict::kStable;
      stack.push_back(e);
      walk(edge.to, assembly, some_unstable || unstable);
      stack.pop_back();
      if (out.size() >= limit) return;
    }
  };
  if (ways[0] > 0) walk(0, false, false);
  if (ways_as[0] > 0) walk(0, true, false);
  if (result_.sequences.size() < ways[0])
    result_.message = "listed the first " + std::to_string(result_.sequences.size()) + " of " +
                      FormatNumber(ways[0]) + " stable sequences";
}

// --allow-fixtures: when no sequence is stable as it is, a search over
// (node, fixels in place) with the fewest fixels first (then the deepest
// node: the search dives towards a complete sequence). Each step of a
// candidate path is simulated with the fixels in place (those on the parts
// that leave are released first); when it fails, SuggestFixtures adds the
// fewest fixels, within what is left of the allowance, that make it stable.
// Fixels stay until their part leaves. A sequence's cost is the number of
// fixels it places.
std::optional<std::vector<FixtureDef>> Planner::FixelsForPath(const AssemblyDef& def,
                                                              const Assembly& fixed,
                                                              const std::vector<int>& remove,
                                                              const CandidatePath& c,
                                                              const Key& key, int budget) {
  const Plan plan = OneStepPlan(remove, c, PlanMode::kDisassemble);
  const SimulationOptions so = NodeSimulation(key);
  const SimulationResult sim = SimulatePlan(fixed, plan, so);
  ++result_.stats.path_simulations;
  std::vector<FixtureDef> added;
  if (sim.stable()) return added;
  if (budget <= 0 || sim.verdict != MotionVerdict::kUnstable) return std::nullopt;
  FixtureSearchOptions fo;
  fo.max_fixels = budget;
  fo.max_candidates = kPathFixelCandidates;
  fo.max_simulations = kPathFixelSimulations;
  fo.simulation = so;
  const FixtureSuggestion sug = SuggestFixtures(def, fixed, plan, sim, fo);
  result_.stats.path_simulations += sug.simulations;
  if (!sug.found) return std::nullopt;
  for (const SuggestedFixel& f : sug.fixels) added.push_back(f.fixture);
  return added;
}

int Planner::RecordFixtureEdge(const Key& key, const Key& to, const std::vector<int>& remove,
                               const CandidatePath& c, const std::vector<FixtureDef>& added) {
  PlanEdge edge;
  edge.from = NodeIndex(key);
  edge.to = NodeIndex(to);
  edge.remove = remove;
  PathTrial t;
  t.candidate = c;
  t.disassembly = MotionVerdict::kStable;
  t.assembly = MotionVerdict::kUnstable;
  // The assembly direction is not checked with fixels.
  t.decided_by =
      added.empty() ? "fixture search: simulation" : "fixture search: simulation with fixels";
  t.fixels = added;
  edge.trials.push_back(t);
  edge.chosen = 0;
  const int e = static_cast<int>(result_.edges.size());
  result_.edges.push_back(std::move(edge));
  evaluated_.push_back(true);
  return e;
}

void Planner::FixtureSearch() {
  struct State {
    Key key;
    std::vector<FixtureDef> fixels;  // in place
    std::vector<FixtureDef> placed;  // every fixel placed so far
    std::vector<int> edges;
  };
  constexpr int kMaxExpansions = 500;
  const int want = opt_.max_sequences > 0 ? opt_.max_sequences : 1;
  std::vector<State> states;
  // (fixels placed, −parts removed, state index): the smallest first.
  std::set<std::tuple<int, int, int>> open;
  std::set<std::pair<Key, std::string>> seen;
  const auto fixel_key = [](const std::vector<FixtureDef>& f) {
    std::ostringstream os;
    os.precision(17);
    for (const FixtureDef& x : f)
      os << x.part << ' ' << x.point.transpose() << ' ' << x.normal.transpose() << ';';
    return os.str();
  };
  const auto push = [&](State st) {
    if (!seen.emplace(st.key, fixel_key(st.fixels)).second) return;
    const int removed = static_cast<int>(movable_.size()) - Count(st.key);
    open.emplace(static_cast<int>(st.placed.size()), -removed, static_cast<int>(states.size()));
    states.push_back(std::move(st));
  };
  Key full(words_, 0);
  for (size_t slot = 0; slot < movable_.size(); ++slot) Set(full, static_cast<int>(slot));
  push({full, {}, {}, {}});
  int expansions = 0, found = 0;
  while (!open.empty() && found < want && expansions < kMaxExpansions) {
    const int id = std::get<2>(*open.begin());
    open.erase(open.begin());
    const State st = states[id];
    if (Count(st.key) == 0) {
      PlannedSequence seq = MakeSequence(st.edges, false);
      seq.fixels = st.placed;
      result_.sequences.push_back(std::move(seq));
      ++found;
      continue;
    }
    ++expansions;
    for (const EdgeCandidate& cand : Candidates(st.key)) {
      // The fixels on the leaving parts are released before the step.
      AssemblyDef def = def_;
      std::vector<FixtureDef> kept;
      for (const FixtureDef& f : st.fixels) {
        const int p = assembly_.FindPart(f.part);
        if (!std::binary_search(cand.remove.begin(), cand.remove.end(), p)) kept.push_back(f);
      }
      def.fixtures.insert(def.fixtures.end(), kept.begin(), kept.end());
      const Assembly fixed = Assembly::Create(def);
      const int budget = opt_.allow_fixtures - static_cast<int>(st.placed.size());
      for (const CandidatePath& c : cand.paths) {
        const std::optional<std::vector<FixtureDef>> added =
            FixelsForPath(def, fixed, cand.remove, c, st.key, budget);
        if (!added) continue;
        Key to = st.key;
        for (int p : cand.remove) Clear(to, slot_of_[p]);
        const int e = RecordFixtureEdge(st.key, to, cand.remove, c, *added);
        State next{to, kept, st.placed, st.edges};
        next.fixels.insert(next.fixels.end(), added->begin(), added->end());
        next.placed.insert(next.placed.end(), added->begin(), added->end());
        next.edges.push_back(e);
        push(std::move(next));
        break;  // one working path per subassembly
      }
    }
  }
  if (found == 0)
    result_.message = "no sequence is stable even with " + std::to_string(opt_.allow_fixtures) +
                      " fixel" + (opt_.allow_fixtures == 1 ? "" : "s") +
                      (expansions >= kMaxExpansions ? " (search budget exhausted)" : "");
  else
    result_.message = "no sequence is stable without fixtures; " + std::to_string(found) +
                      " found with fixels (fewest first)";
}

PlannerResult Planner::Run() {
  const auto start = std::chrono::steady_clock::now();
  if (assembly_.has_interfaces())
    throw InputError("", "interfaces",
                     "the contacts are given as interfaces of the assembled configuration: parts "
                     "cannot be moved, so no removal can be planned");
  threads_ = opt_.threads > 0 ? opt_.threads
                              : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  result_.stats.threads = threads_;
  if (opt_.executor) executor_ = opt_.executor;
  result_.stats.ranks = executor_->processes();
  const double g = assembly_.gravity().norm();
  up_ = g > 0 ? Vector3(-assembly_.gravity() / g)
              : (assembly_.is_3d() ? Vector3(0, 0, 1) : Vector3(0, 1, 0));
  // A time step of a hundredth of the scene, rounded to one significant digit.
  if (opt_.dt > 0) {
    result_.dt = opt_.dt;
  } else {
    const double raw = assembly_.scene_size() / 100;
    const double decade = std::pow(10.0, std::floor(std::log10(raw)));
    result_.dt = std::max(1.0, std::round(raw / decade)) * decade;
  }
  result_.speed = opt_.speed > 0 ? opt_.speed : 1.0;

  ChooseParts();
  ComputeDirections();
  Key full(words_, 0);
  for (size_t s = 0; s < movable_.size(); ++s) Set(full, static_cast<int>(s));
  NodeIndex(full);
  CheckNodes({0});
  if (!result_.nodes[0].stable) {
    result_.message = "the assembly itself is not stable: nothing can be taken out stably";
  } else if (opt_.max_sequences > 0) {
    all_paths_ = false;
    BestFirst();
  } else {
    Enumerate();
    ListSequences();
  }
  if (result_.sequences.empty() && result_.nodes[0].stable && opt_.allow_fixtures > 0) {
    result_.assembly_only.clear();
    FixtureSearch();
  }
  if (result_.sequences.empty() && result_.message.empty())
    result_.message = "no stable disassembly sequence";
  result_.stats.nodes = static_cast<int>(result_.nodes.size());
  result_.stats.edges = static_cast<int>(result_.edges.size());
  executor_->Times(result_.stats.rank_seconds, result_.stats.communication_seconds);
  result_.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!opt_.keep_graph) {
    result_.nodes.clear();
    result_.edges.clear();
  }
  return std::move(result_);
}

}  // namespace

PlannerResult PlanDisassembly(const AssemblyDef& def, const Assembly& assembly,
                              const PlannerOptions& options) {
  Planner planner(def, assembly, options);
  return planner.Run();
}

PlanDef SequenceToPlanDef(const PlannedSequence& sequence, const PlannerResult& result,
                          PlanMode mode) {
  PlanDef plan;
  plan.mode = mode;
  plan.dt = result.dt;
  plan.speed = result.speed;
  for (const PlannedStep& s : sequence.steps) plan.steps.push_back(s.step);
  return plan;
}

}  // namespace cairn

#pragma once
/// @file
/// Stable disassembly sequences over the AND/OR graph of subassemblies
/// (paper Sections VI-VIII; de Mello and Sanderson, paper ref. [12]).
///
/// Two-handed, monotone disassembly with the fixed parts as one hand: a node
/// of the graph is the set of movable parts still in the assembly (with the
/// fixed parts, and the parts the user keeps); an edge takes a subassembly S
/// out of node T along a path, leaving T \ S. S leaves whole, held by the
/// gripper (its further disassembly is a problem of its own). Every part is
/// at its assembled pose in every node, so an edge's stability depends on T,
/// S and the path only, never on the steps before it: a sequence is stable
/// when each of its edges is.
///
/// Geometric feasibility comes from the NDBG (planning/blocking.h): for each
/// cell direction d and each part i of T, the closure of i in DBG(d) is a
/// subassembly that can leave along d (unless it holds a fixed or kept part);
/// its default path is the straight removal along d, far enough for its
/// bounding box to clear every other part's. The user may add candidate paths
/// for single parts (PlannerOptions::given_paths).
///
/// Stability, with the paper's results used to save work (and counted in
/// PlannerStats):
///   - every node is checked once (AnalyzeConfiguration), memoised per node;
///   - Proposition 1: when T \ S is unstable, every path of the edge is, and
///     none is simulated (the assembly direction too: it starts from T \ S);
///   - Corollary 2 with Proposition 2: when S is gripped whole with full
///     support along a straight, geometrically free path, and the scene is
///     frictionless or every contact between S and T \ S opens at once, the
///     rest of the assembly sees only T and T \ S: the node checks decide the
///     edge in both directions;
///   - otherwise the edge is simulated along its path (motion/simulate.h) in
///     disassembly and, separately, in assembly (the reverse), because
///     friction can make them differ (paper Section VIII, Fig. 19).
///
/// Search: with max_sequences = 0 the graph is enumerated completely, level
/// by level (by the number of parts removed), the nodes of a level analysed
/// in parallel; results are merged in a fixed order, so the output does not
/// depend on the number of threads. With max_sequences = K the search is
/// best-first (depth first, the most promising edge first: the highest
/// subassembly, the path closest to straight up) and stops after K stable
/// sequences; dead nodes are memoised.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/plan.h"
#include "cairn/motion/simulate.h"
#include "cairn/planning/fixtures.h"

namespace cairn {

/// Which support modes straight removals are tried with.
enum class SupportChoice { kFull, kNone, kBoth };

struct PlannerStats;

/// Where the planner's independent work runs: the node checks of a level and
/// the evaluations of a batch of edges (each task is a pure function of the
/// graph so far). By default, this process's threads; a distributed executor
/// (the CLI's MPI one, src/cli/mpi.h) runs the same search on every process
/// and spreads each batch's tasks over the processes. The planner encodes a
/// task's result as bytes and decodes every task's result in index order, so
/// every process continues with the same graph and the result does not
/// depend on where a task ran.
class PlanExecutor {
 public:
  virtual ~PlanExecutor() = default;
  /// The processes the work is spread over (1: this one).
  virtual int processes() const = 0;
  /// Runs task(i) for the i this process is given (of [0, cost.size())), on
  /// up to `threads` threads, and returns every task's result, in index
  /// order, on every process. `cost[i]` estimates task i's work (arbitrary
  /// units): the tasks are balanced by it, not by their count. Every process
  /// calls Map with the same costs; a task that throws makes Map throw on
  /// every process.
  virtual std::vector<std::string> Map(const std::vector<double>& cost, int threads,
                                       const std::function<std::string(int)>& task) = 0;
  /// After the search, on every process: each process's seconds in tasks
  /// (`work`) and in exchanging results, waiting for the others included
  /// (`communication`), one entry per process.
  virtual void Times(std::vector<double>& work, std::vector<double>& communication) = 0;
};

/// Options of PlanDisassembly.
struct PlannerOptions {
  /// The node checks' and paths' rule where rigid bodies leave a static check
  /// open (stability/solve_component.h).
  VerdictRule rule = VerdictRule::kLoadedFromRest;
  /// A state is stable only when strong stability is proved (--require strong).
  bool require_strong = false;
  /// Stop after this many stable sequences (best-first search); 0: enumerate
  /// the whole graph and list every stable sequence.
  int max_sequences = 0;
  /// Worker threads; 0: every core.
  int threads = 0;
  /// Parts (indices) that stay in the assembly: never removed, always judged.
  std::vector<int> keep;
  /// Candidate paths given by the user, per part index, tried besides the
  /// straight removals.
  std::map<int, std::vector<CandidatePath>> given_paths;
  /// Support modes of the straight removals (the paper's default: full).
  SupportChoice support = SupportChoice::kFull;
  /// Consider subassemblies of more than one part (NDBG closures).
  bool subassemblies = true;
  /// The candidate directions of straight removals; empty: every cell of the
  /// NDBG of the assembled configuration. Given (e.g. ±x, ±y, ±z), the
  /// blocking graphs are computed at these alone (ComputeBlockingAt): for
  /// models whose NDBG has too many cells to try, such as tessellated CAD
  /// parts (a cell per facet of each cylinder).
  std::vector<Vector3> directions;
  /// Time step (s) and gripper speed (length/s) of simulated paths and of
  /// the plans written; 0: the scene's size / 100 and 1.
  double dt = 0, speed = 0;
  /// When no sequence is stable without fixtures: look for sequences stable
  /// with at most this many fixels (fewest first). 0: never.
  int allow_fixtures = 0;
  /// Keep the whole graph (nodes and edges with their verdicts) in the result
  /// (for --dot and --json).
  bool keep_graph = true;
  /// Called on the calling thread after each batch of node checks and of
  /// edge evaluations, with the statistics so far (the CLI's progress line).
  std::function<void(const PlannerStats&)> on_progress;
  /// Called often, on any worker thread (before each node check, at every
  /// time step of a simulated path): it may throw to abandon the search (a
  /// cooperative deadline: `cairn batch --job-timeout`). Empty: none.
  std::function<void()> checkpoint;
  /// Where node checks and edge evaluations run; null: this process's
  /// `threads`. Not owned.
  PlanExecutor* executor = nullptr;
};

/// One candidate path of an edge, as checked.
struct PathTrial {
  CandidatePath candidate;
  MotionVerdict disassembly = MotionVerdict::kStable;  ///< taking S out along the path
  MotionVerdict assembly = MotionVerdict::kStable;     ///< bringing S in along it backwards
  /// How it was decided: "nodes" (Corollary 2: node checks), "proposition 1"
  /// (T \ S unstable), "simulation" (along the path).
  std::string decided_by;
  /// The first failure along the path: the disassembly's, else the
  /// assembly's (`failure_mode` says which); none when stable or decided
  /// without simulating. In words: PathTrialFailure (cairn/report/words.h).
  std::optional<MotionFailure> failure;
  PlanMode failure_mode = PlanMode::kDisassemble;
  std::vector<FixtureDef> fixels;  ///< with allow_fixtures: the fixels that make it stable
};

/// An edge of the graph: S out of node `from`, leaving node `to`.
struct PlanEdge {
  int from = -1, to = -1;         ///< indices into PlannerResult::nodes
  std::vector<int> remove;        ///< S, ascending part indices
  std::vector<PathTrial> trials;  ///< the candidates tried, in the order tried
  /// Index into `trials` of the path the sequences use (stable both ways if
  /// any is, else stable in disassembly), or -1 when none is stable.
  int chosen = -1;
  int assembly_chosen = -1;  ///< a path stable in assembly, or -1
};

/// A node of the graph.
struct PlanNode {
  std::vector<int> parts;  ///< movable parts present (kept and fixed parts not listed)
  bool stable = false;     ///< the configuration stands
  bool expanded = false;   ///< its edges were generated (false: pruned or not reached)
};

/// One step of a sequence: the plan step and what was found about it.
struct PlannedStep {
  PlanStepDef step;  ///< in plan format (names, path, support)
  int edge = -1;     ///< index into PlannerResult::edges
  int trial = -1;    ///< index into the edge's trials
  bool assembly_stable = false;
};

/// A stable sequence.
struct PlannedSequence {
  std::vector<PlannedStep> steps;
  /// Its reverse, run as an assembly along the same paths, is stable too.
  bool invertible = false;
  std::vector<FixtureDef> fixels;  ///< with allow_fixtures: the fixels it needs
};

/// Work done.
struct PlannerStats {
  int nodes = 0;                    ///< nodes reached
  int edges = 0;                    ///< edges generated
  int node_checks = 0;              ///< AnalyzeConfiguration of a node (memoised: once per node)
  int path_simulations = 0;         ///< simulations along a path (each direction counts)
  int decided_by_nodes = 0;         ///< path trials decided by node checks (Corollary 2)
  int pruned_by_proposition_1 = 0;  ///< path trials decided because T \ S is unstable
  int memo_hits = 0;                ///< node results reused
  double seconds = 0;               ///< wall clock
  int threads = 1;
  double sequences_total = 0;        ///< with full enumeration: how many stable sequences exist
  int ranks = 1;                     ///< processes the work was spread over (PlanExecutor)
  std::vector<double> rank_seconds;  ///< per process: seconds in node checks and edges
  std::vector<double> communication_seconds;  ///< per process: seconds exchanging and waiting
};

/// Everything PlanDisassembly found.
struct PlannerResult {
  std::vector<PlannedSequence> sequences;  ///< stable disassembly sequences
  /// Sequences whose assembly (the reverse) is stable although their
  /// disassembly is not (non-invertibility, paper Section VIII).
  std::vector<PlannedSequence> assembly_only;
  std::vector<PlanNode> nodes;  ///< nodes[0] is the whole assembly
  std::vector<PlanEdge> edges;
  bool complete = false;  ///< the whole graph was enumerated
  double dt = 1, speed = 1;
  PlannerStats stats;
  std::string message;  ///< why nothing was found, notes on fixtures
};

/// Finds stable disassembly sequences of `assembly` (built from `def`; the
/// fixture search adds to it). @throws InputError when the assembly has more
/// than 63 movable parts to remove in full enumeration, or given interfaces.
PlannerResult PlanDisassembly(const AssemblyDef& def, const Assembly& assembly,
                              const PlannerOptions& options = {});

/// The plan of a sequence (plan format), in `mode`.
PlanDef SequenceToPlanDef(const PlannedSequence& sequence, const PlannerResult& result,
                          PlanMode mode);

}  // namespace cairn

// The sequence planner (planning/planner.h) on the paper's figures: Fig. 1
// (one stable linear sequence), Fig. 17 (only subassemblies), Fig. 6 with its
// exits (Table I), Fig. 9 (3-D, sequence and path), Fig. 19 (non-invertible);
// every sequence found replays stably in SimulatePlan, both ways; the output
// does not depend on the number of threads.

#include "cairn/planning/planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "cairn/io/paths_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "cairn/report/plan_report.h"
#include "example_scene.h"
#include "failure_brief.h"

namespace cairn {
namespace {

using Scene = testing::ExampleScene;
using testing::ExamplePath;

// The removal order of a sequence, as "D C B A" (subassemblies as "A+B").
std::string Order(const PlannedSequence& s) {
  std::string out;
  for (const PlannedStep& step : s.steps) {
    if (!out.empty()) out += " ";
    std::vector<std::string> names = step.step.remove;
    std::sort(names.begin(), names.end());
    for (size_t k = 0; k < names.size(); ++k) out += (k ? "+" : "") + names[k];
  }
  return out;
}

std::set<std::string> Orders(const std::vector<PlannedSequence>& seqs) {
  std::set<std::string> out;
  for (const PlannedSequence& s : seqs) out.insert(Order(s));
  return out;
}

// Replays a sequence as the plan file `cairn plan --emit-plans` writes, in
// `mode`, on the scene it was planned for.
SimulationResult Replay(const Scene& scene, const PlannedSequence& seq, const PlannerResult& r,
                        PlanMode mode) {
  const Plan plan = Plan::Create(SequenceToPlanDef(seq, r, mode), scene.assembly);
  return SimulatePlan(scene.assembly, plan);
}

// The edge out of the node with exactly `present` movable parts that
// removes exactly `remove`, or null.
const PlanEdge* FindEdge(const Scene& scene, const PlannerResult& r,
                         std::vector<std::string> present, std::vector<std::string> remove) {
  const auto indices = [&](const std::vector<std::string>& names) {
    std::vector<int> out;
    for (const std::string& n : names) out.push_back(scene.Part(n));
    std::sort(out.begin(), out.end());
    return out;
  };
  const std::vector<int> p = indices(present), s = indices(remove);
  for (const PlanEdge& e : r.edges)
    if (r.nodes[e.from].parts == p && e.remove == s) return &e;
  return nullptr;
}

const PathTrial* FindTrial(const PlanEdge& e, const std::string& label) {
  for (const PathTrial& t : e.trials)
    if (t.candidate.label == label) return &t;
  return nullptr;
}

// ---- Paper Fig. 1 -----------------------------------------------------------

TEST(PlannerFig1, ExactlyOneStableLinearSequenceDCBA) {
  const Scene scene("paper_fig1.json");
  PlannerOptions opt;
  opt.subassemblies = false;
  const PlannerResult r = PlanDisassembly(scene.def, scene.assembly, opt);
  ASSERT_TRUE(r.complete);
  EXPECT_EQ(r.stats.sequences_total, 1.0) << PlannerToText(scene.assembly, r, "fig1");
  ASSERT_EQ(r.sequences.size(), 1u);
  EXPECT_EQ(Order(r.sequences[0]), "D C B A");
  EXPECT_TRUE(r.sequences[0].invertible);
  // The paper: every sequence starting with A, B or C is unstable.
  for (const char* first : {"A", "B", "C"}) {
    const PlanEdge* e = FindEdge(scene, r, {"A", "B", "C", "D"}, {first});
    if (e) {
      EXPECT_LT(e->chosen, 0) << first;
    }
  }
  // It replays stably as a disassembly, and its reverse assembles stably.
  EXPECT_TRUE(Replay(scene, r.sequences[0], r, PlanMode::kDisassemble).stable());
  EXPECT_TRUE(Replay(scene, r.sequences[0], r, PlanMode::kAssemble).stable());
  // Frictionless, carried: every path was decided by node checks (Corollary 2).
  EXPECT_EQ(r.stats.path_simulations, 0);
  EXPECT_GT(r.stats.decided_by_nodes, 0);
  EXPECT_GT(r.stats.pruned_by_proposition_1, 0);
}

TEST(PlannerFig1, BestFirstFindsTheSameSequence) {
  const Scene scene("paper_fig1.json");
  PlannerOptions opt;
  opt.subassemblies = false;
  opt.max_sequences = 1;
  const PlannerResult r = PlanDisassembly(scene.def, scene.assembly, opt);
  ASSERT_EQ(r.sequences.size(), 1u);
  EXPECT_EQ(Order(r.sequences[0]), "D C B A");
  EXPECT_FALSE(r.complete);
}

// ---- Paper Fig. 17 ----------------------------------------------------------

TEST(PlannerFig17, NoSinglePartRemovalIsStableSubassembliesAreFound) {
  const Scene scene("paper_fig17.json");
  const PlannerResult r = PlanDisassembly(scene.def, scene.assembly, {});
  ASSERT_FALSE(r.sequences.empty()) << PlannerToText(scene.assembly, r, "fig17");
  // No single part leaves the whole assembly stably.
  int single = 0;
  for (const PlanEdge& e : r.edges) {
    if (e.from != 0 || e.remove.size() != 1) continue;
    ++single;
    EXPECT_LT(e.chosen, 0) << scene.assembly.part(e.remove[0]).name;
  }
  EXPECT_EQ(single, 4) << "A, C up; B, D sideways";
  // Every stable sequence takes {A, B} and {C, D} as subassemblies.
  for (const PlannedSequence& s : r.sequences) {
    const std::string order = Order(s);
    EXPECT_TRUE(order == "A+B C+D" || order == "C+D A+B") << order;
    EXPECT_TRUE(Replay(scene, s, r, PlanMode::kDisassemble).stable()) << order;
  }
}

// ---- Paper Fig. 6, Table I --------------------------------------------------

class PlannerFig6 : public ::testing::Test {
 protected:
  void SetUp() override {
    PlannerOptions opt;
    opt.keep = {scene_.Part("D"), scene_.Part("E")};
    opt.given_paths =
        ReadCandidatePaths(ExamplePath("paths/paper_fig6_exits.paths.json"), scene_.assembly);
    r_ = PlanDisassembly(scene_.def, scene_.assembly, opt);
  }
  // The verdict of taking `part` out through `exit` with `present` in place.
  MotionVerdict Verdict(std::vector<std::string> present, const std::string& part,
                        const std::string& exit) {
    const PlanEdge* e = FindEdge(scene_, r_, present, {part});
    if (!e) return MotionVerdict::kInfeasible;
    const PathTrial* t = FindTrial(*e, exit);
    if (!t) {
      // Proposition 1 decides every path at once.
      if (e->trials.size() == 1 && e->trials[0].decided_by == "proposition 1")
        return e->trials[0].disassembly;
      ADD_FAILURE() << part << " through " << exit << " was not tried";
      return MotionVerdict::kInfeasible;
    }
    return t->disassembly;
  }
  Scene scene_{"paper_fig6.json"};
  PlannerResult r_;
};

constexpr auto kStable = MotionVerdict::kStable;
constexpr auto kUnstable = MotionVerdict::kUnstable;

TEST_F(PlannerFig6, TableI_ACB) {
  // A through I, then C: stable through I only (II and III tip E).
  EXPECT_EQ(Verdict({"A", "B", "C"}, "A", "I"), kStable);
  EXPECT_EQ(Verdict({"B", "C"}, "C", "I"), kStable);
  EXPECT_EQ(Verdict({"B", "C"}, "C", "II"), kUnstable);
  EXPECT_EQ(Verdict({"B", "C"}, "C", "III"), kUnstable);
  EXPECT_EQ(Verdict({"B"}, "B", "I"), kStable);
}

TEST_F(PlannerFig6, TableI_CAB) {
  // C first: through I and II stable; III tips E (as the paper's text and
  // Fig. 7 say; Table I's row lists it stable: see tests/motion).
  EXPECT_EQ(Verdict({"A", "B", "C"}, "C", "I"), kStable);
  EXPECT_EQ(Verdict({"A", "B", "C"}, "C", "II"), kStable);
  EXPECT_EQ(Verdict({"A", "B", "C"}, "C", "III"), kUnstable);
  EXPECT_EQ(Verdict({"A", "B"}, "A", "I"), kStable);
}

TEST_F(PlannerFig6, TableI_ABC) {
  // C last, through II or III: unstable; carried through I it is stable in
  // this rebuild (tests/motion/paper_figures_test.cpp says why).
  EXPECT_EQ(Verdict({"C"}, "C", "II"), kUnstable);
  EXPECT_EQ(Verdict({"C"}, "C", "III"), kUnstable);
  EXPECT_EQ(Verdict({"C"}, "C", "I"), kStable);
}

TEST_F(PlannerFig6, SequencesUseOnlyStablePathsAndReplayStably) {
  ASSERT_FALSE(r_.sequences.empty());
  for (const PlannedSequence& s : r_.sequences) {
    const SimulationResult sim = Replay(scene_, s, r_, PlanMode::kDisassemble);
    EXPECT_TRUE(sim.stable()) << Order(s) << ": "
                              << (sim.failure ? testing::Brief(*sim.failure) : std::string());
  }
}

// ---- Paper Fig. 9 (3-D) -----------------------------------------------------

TEST(PlannerFig9, ACBIsRejectedCABIsFound) {
  const Scene scene("paper_fig9.json");
  PlannerOptions opt;
  opt.subassemblies = false;
  const PlannerResult r = PlanDisassembly(scene.def, scene.assembly, opt);
  const std::set<std::string> orders = Orders(r.sequences);
  EXPECT_TRUE(orders.count("C A B")) << PlannerToText(scene.assembly, r, "fig9");
  for (const std::string& o : orders) EXPECT_NE(o.substr(0, 1), "A") << o;
  EXPECT_FALSE(orders.count("A C B"));
  // Lifting A first leaves B to topple under C (Proposition 1).
  const PlanEdge* a_first = FindEdge(scene, r, {"A", "B", "C"}, {"A"});
  ASSERT_NE(a_first, nullptr);
  EXPECT_LT(a_first->chosen, 0);
  for (const PlannedSequence& s : r.sequences)
    if (Order(s) == "C A B") {
      EXPECT_TRUE(Replay(scene, s, r, PlanMode::kDisassemble).stable());
    }
}

// ---- Paper Fig. 19 ----------------------------------------------------------

TEST(PlannerFig19, HorizontalRemovalOfAAndItsInverseDiffer) {
  const Scene scene("paper_fig19.json");
  PlannerOptions opt;
  opt.support = SupportChoice::kNone;  // A's weight rests on B while it slides
  const PlannerResult r = PlanDisassembly(scene.def, scene.assembly, opt);
  const PlanEdge* a = FindEdge(scene, r, {"A", "B"}, {"A"});
  ASSERT_NE(a, nullptr);
  const PathTrial* right = FindTrial(*a, "+x");
  ASSERT_NE(right, nullptr) << PlannerToText(scene.assembly, r, "fig19");
  EXPECT_EQ(right->disassembly, MotionVerdict::kUnstable) << "A drags B to the right";
  EXPECT_EQ(right->assembly, MotionVerdict::kStable) << "the wall holds B while A slides in";
  // Lifting A is invertible; the sequences found use it.
  const PathTrial* up = FindTrial(*a, "up");
  ASSERT_NE(up, nullptr);
  EXPECT_EQ(up->disassembly, MotionVerdict::kStable);
  EXPECT_EQ(up->assembly, MotionVerdict::kStable);
  ASSERT_FALSE(r.sequences.empty());
  for (const PlannedSequence& s : r.sequences) EXPECT_TRUE(s.invertible) << Order(s);
  // The step is reported as not invertible; no sequence is stable only as
  // an assembly (lifting A is stable both ways).
  EXPECT_TRUE(r.assembly_only.empty());
}

TEST(PlannerFig19, WithALidOverAOnlyTheAssemblyIsStable) {
  // A fixed lid over A: A can only leave sideways, which drags B (μ 0.2 on
  // top, 0.05 below); sliding A in from the right is stable (the wall holds
  // B). No disassembly is stable; the assembly is, and it is reported apart.
  AssemblyDef def = ReadSceneDef(ExamplePath("paper_fig19.json"));
  PartDef lid;
  lid.name = "lid";
  lid.fixed = true;
  lid.polygon = {{0, 2}, {2.5, 2}, {2.5, 3}, {0, 3}};
  def.parts.push_back(lid);
  const Assembly a = Assembly::Create(def, "fig19+lid");
  PlannerOptions opt;
  opt.support = SupportChoice::kNone;
  const PlannerResult r = PlanDisassembly(def, a, opt);
  EXPECT_TRUE(r.sequences.empty()) << PlannerToText(a, r, "fig19+lid");
  ASSERT_FALSE(r.assembly_only.empty()) << PlannerToText(a, r, "fig19+lid");
  const PlannedSequence& s = r.assembly_only[0];
  ASSERT_EQ(s.steps.size(), 2u);
  EXPECT_EQ(s.steps[0].step.remove, std::vector<std::string>{"A"});
  EXPECT_GT(s.steps[0].step.direction.x(), 0.99) << "A leaves (and comes in) from the right";
  // Replayed as an assembly (B, then A slid in) it is stable; taken apart it is not.
  const Plan as = Plan::Create(SequenceToPlanDef(s, r, PlanMode::kAssemble), a);
  const Plan dis = Plan::Create(SequenceToPlanDef(s, r, PlanMode::kDisassemble), a);
  SimulationOptions so;
  so.carry_when_unsupported = true;
  EXPECT_TRUE(SimulatePlan(a, as, so).stable());
  EXPECT_EQ(SimulatePlan(a, dis, so).verdict, MotionVerdict::kUnstable);
}

// ---- Determinism ------------------------------------------------------------

TEST(PlannerDeterminism, SameOutputOnOneAndTwoThreads) {
  const Scene scene("paper_fig17.json");
  PlannerOptions one, two;
  one.threads = 1;
  two.threads = 2;
  nlohmann::json a =
      PlannerToJson(scene.assembly, PlanDisassembly(scene.def, scene.assembly, one), "s");
  nlohmann::json b =
      PlannerToJson(scene.assembly, PlanDisassembly(scene.def, scene.assembly, two), "s");
  for (nlohmann::json* j : {&a, &b}) {
    (*j)["stats"].erase("time");
    (*j)["stats"].erase("threads");
  }
  EXPECT_EQ(a.dump(), b.dump());
}

// An executor that plays several processes in one: it runs the tasks last
// first (as another process might finish them), records the costs it is
// given, and reports `ranks` processes. The planner's output must not depend
// on where or in which order its tasks ran.
class ReversedExecutor final : public PlanExecutor {
 public:
  explicit ReversedExecutor(int ranks) : ranks_(ranks) {}
  int processes() const override { return ranks_; }
  std::vector<std::string> Map(const std::vector<double>& cost, int,
                               const std::function<std::string(int)>& task) override {
    std::vector<std::string> out(cost.size());
    for (int i = static_cast<int>(cost.size()) - 1; i >= 0; --i) out[i] = task(i);
    costs.insert(costs.end(), cost.begin(), cost.end());
    return out;
  }
  void Times(std::vector<double>& work, std::vector<double>& communication) override {
    work.assign(ranks_, 1.0);
    communication.assign(ranks_, 0.0);
  }
  std::vector<double> costs;

 private:
  int ranks_;
};

TEST(PlannerDeterminism, AnExecutorsOrderOfTasksChangesNothing) {
  // With friction and both supports, paths are simulated (their results
  // travel as bytes) as well as decided by node checks.
  Scene scene("paper_fig6.json");
  scene.def.friction = 0.4;
  const Assembly assembly = Assembly::Create(scene.def, "paper_fig6.json");
  for (int max : {0, 2}) {
    PlannerOptions local, spread;
    local.threads = spread.threads = 1;
    local.support = spread.support = SupportChoice::kBoth;
    local.max_sequences = spread.max_sequences = max;
    ReversedExecutor executor(3);
    spread.executor = &executor;
    const PlannerResult a = PlanDisassembly(scene.def, assembly, local);
    const PlannerResult b = PlanDisassembly(scene.def, assembly, spread);
    EXPECT_EQ(a.stats.ranks, 1);
    EXPECT_EQ(b.stats.ranks, 3);
    EXPECT_EQ(b.stats.rank_seconds.size(), 3u);
    EXPECT_GT(b.stats.path_simulations, 0);
    nlohmann::json ja = PlannerToJson(assembly, a, "s"), jb = PlannerToJson(assembly, b, "s");
    for (nlohmann::json* j : {&ja, &jb})
      for (const char* k : {"time", "ranks", "rank_time", "communication_time"})
        (*j)["stats"].erase(k);
    EXPECT_EQ(ja.dump(), jb.dump()) << "--max " << max;
    // Every task had a positive cost, and simulated edges cost more than
    // node checks.
    ASSERT_FALSE(executor.costs.empty());
    EXPECT_GT(*std::min_element(executor.costs.begin(), executor.costs.end()), 0);
    EXPECT_GT(*std::max_element(executor.costs.begin(), executor.costs.end()),
              *std::min_element(executor.costs.begin(), executor.costs.end()));
  }
}

}  // namespace
}  // namespace cairn

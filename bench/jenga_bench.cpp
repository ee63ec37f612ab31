// Jenga benchmark (docs/benchmarks.md, "3-D: Jenga tower"): `cairn check` of
// the 54-block tower of examples/jenga.json and the 50-move pull of its
// layer-9 middle block (examples/plans/jenga_pull_l9.plan.json), through the
// library.
//
// Scenes:
//   Jenga         examples/jenga.json as it is: blocks 1.5 × 2.5 × 7.5 cm,
//                 0.5 mm apart within a layer (metres, kg; μ = 0.5).
//   JengaTouching the same tower with the blocks of each layer side by side
//                 (the gaps closed towards the middle block): every layer
//                 adds two face contacts that carry nothing at rest.
//
// Before the benchmarks, a summary (skip it with --no_summary):
//  - check: AnalyzeConfiguration of the assembled tower as `cairn check` makes
//    it (with the static-equilibrium LP) and without the LP: time (best of
//    --reps), verdict, contacts, LCP size, pivots, stage profile;
//  - simulate: SimulatePlan stopping at the first failure and with
//    continue_after_failure (best of --reps): time, verdict, failure, ticks,
//    pivots, rest-hypothesis solves and their simplex iterations;
//  - with --ticks, every analysis of the path replayed one by one with one
//    workspace (what SimulatePlan does): contacts, LCP size, how it was
//    solved, pivots or simplex iterations, time and stage profile.
// Then Google Benchmark cases Check/<scene>, CheckWithEquilibrium/<scene>,
// Simulate/<scene>[/continue].

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "cairn/report/words.h"
#include "cairn/stability/analyze.h"
#include "run_benchmarks.h"

namespace {

using cairn::Assembly;
using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

const std::string kSource = CAIRN_SOURCE_DIR;

// examples/jenga.json with each layer's blocks moved together until they
// touch: block _1 and _3 move towards _2 by the gap (0.5 mm), across the
// layer (y in odd layers, x in even ones).
Assembly MakeTouching() {
  cairn::AssemblyDef def = cairn::ReadSceneDef(kSource + "/examples/jenga.json");
  def.name += ", blocks touching within a layer";
  constexpr double kGap = 0.0005;
  for (cairn::PartDef& p : def.parts) {
    if (p.name.size() != 5 || p.name[0] != 'L') continue;  // "Lkk_i"
    const int layer = std::stoi(p.name.substr(1, 2));
    const int pos = p.name[4] - '0';
    const int axis = layer % 2 == 1 ? 1 : 0;
    for (cairn::Vector3& v : p.polyhedron->vertices) v[axis] -= (pos - 2) * kGap;
  }
  return Assembly::Create(def, "jenga_bench:touching");
}

struct Scene {
  std::string name;
  const Assembly* assembly;
  const cairn::Plan* plan;
};

cairn::StabilityResult Check(const Assembly& a, bool equilibrium) {
  cairn::StabilityOptions o;
  o.check_equilibrium = equilibrium;
  return cairn::AnalyzeConfiguration(a, cairn::Configuration::Assembled(a), o);
}

void PrintCheck(const Scene& s, bool equilibrium, int reps) {
  double best = 1e300;
  cairn::StabilityResult r;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = Clock::now();
    r = Check(*s.assembly, equilibrium);
    best = std::min(best, Since(t0));
  }
  int pivots = 0, lcp = 0;
  for (const auto& c : r.components) pivots += c.pivots, lcp = std::max(lcp, c.lcp_size);
  std::printf(
      "%s check%s: %.2f ms (best of %d), verdict %s%s, %zu contacts, %zu component(s), LCP %d, "
      "%d pivots; profile (ms) detect %.2f build %.2f solve %.2f classify %.2f\n",
      s.name.c_str(), equilibrium ? " with the equilibrium LP" : "", 1e3 * best, reps,
      cairn::to_string(r.verdict),
      r.static_equilibrium ? (*r.static_equilibrium ? " (equilibrium exists)" : " (no equilibrium)")
                           : "",
      r.contacts.size(), r.components.size(), lcp, pivots, 1e3 * r.profile.detect,
      1e3 * r.profile.build, 1e3 * r.profile.solve, 1e3 * r.profile.classify);
}

// Rest-hypothesis solves and simplex iterations over a run, from the analyses
// SimulatePlan makes (recorded and replayed with one workspace).
struct Analysis {
  cairn::Configuration config;
  cairn::DriveInputs drive;
  cairn::StabilityOptions options;
  int tick = 0;
  bool judged = true;
};

std::vector<Analysis> Record(const Scene& s, bool cont) {
  std::vector<Analysis> out;
  cairn::SimulationOptions o;
  o.continue_after_failure = cont;
  o.on_analysis = [&out](const cairn::AnalysisInputs& in) {
    out.push_back({*in.config, *in.drive, *in.options, in.tick, in.judged});
  };
  cairn::SimulatePlan(*s.assembly, *s.plan, o);
  return out;
}

void PrintSimulation(const Scene& s, bool cont, int reps, bool ticks) {
  cairn::SimulationOptions o;
  o.continue_after_failure = cont;
  double best = 1e300;
  cairn::SimulationResult r;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = Clock::now();
    r = cairn::SimulatePlan(*s.assembly, *s.plan, o);
    best = std::min(best, Since(t0));
  }
  const auto& st = r.steps.at(0);
  std::printf("%s simulate%s: %.3f s (best of %d), verdict %s, %d ticks, %d pivots\n",
              s.name.c_str(), cont ? " --continue" : "", best, reps, cairn::to_string(r.verdict),
              st.ticks, st.pivots);
  if (r.failure)
    std::printf("  first failure: %.300s\n",
                cairn::DescribeFailure(*s.assembly, *r.failure).c_str());

  // The same analyses replayed one by one (one workspace, as SimulatePlan).
  const std::vector<Analysis> path = Record(s, cont);
  cairn::StabilityWorkspace ws;
  int rest = 0, iterations = 0, pivots = 0, max_contacts = 0, max_lcp = 0;
  cairn::StageProfile sum;
  double total = 0;
  if (ticks)
    std::printf(
        "  tick  contacts   LCP  solved by      pivots  LP iter  time (ms)  detect  build  solve  "
        "classify  verdict\n");
  for (const Analysis& a : path) {
    const auto t0 = Clock::now();
    const cairn::StabilityResult res =
        cairn::AnalyzeConfiguration(*s.assembly, a.config, a.options, &a.drive, &ws);
    const double t = Since(t0);
    total += t;
    int p = 0, it = 0, lcp = 0;
    bool by_rest = false;
    for (const auto& c : res.components) {
      p += c.pivots, it += c.lp_iterations, lcp = std::max(lcp, c.lcp_size);
      by_rest |= c.rest_solution;
    }
    rest += by_rest, iterations += it, pivots += p;
    max_contacts = std::max(max_contacts, static_cast<int>(res.contacts.size()));
    max_lcp = std::max(max_lcp, lcp);
    sum.detect += res.profile.detect, sum.build += res.profile.build;
    sum.solve += res.profile.solve, sum.classify += res.profile.classify;
    if (ticks)
      std::printf("  %4d%c %8zu %5d  %-12s %7d %8d %10.2f %7.2f %6.2f %6.2f %9.2f  %s%s\n", a.tick,
                  a.judged ? ' ' : '*', res.contacts.size(), lcp,
                  by_rest ? "rest LP"
                          : (res.verdict == cairn::Verdict::kSolverFailure ? "(failed)" : "Lemke"),
                  p, it, 1e3 * t, 1e3 * res.profile.detect, 1e3 * res.profile.build,
                  1e3 * res.profile.solve, 1e3 * res.profile.classify,
                  cairn::to_string(res.verdict),
                  res.unsupported.empty() ? "" : " (guided part off its path)");
  }
  std::printf(
      "  replay: %zu analyses in %.3f s; up to %d contacts, LCP up to %d; %d by the rest LP (%d "
      "simplex iterations), %d Lemke pivots; stages (s) detect %.3f build %.3f solve %.3f "
      "classify %.3f\n",
      path.size(), total, max_contacts, max_lcp, rest, iterations, pivots, sum.detect, sum.build,
      sum.solve, sum.classify);
  if (ticks) std::printf("  (* tick 0's second solve, gripper moving)\n");
}

void BM_Check(benchmark::State& state, const Scene* s, bool equilibrium) {
  cairn::StabilityResult r;
  for (auto _ : state) {
    r = Check(*s->assembly, equilibrium);
    benchmark::DoNotOptimize(r.contacts.data());
  }
  int pivots = 0, lcp = 0;
  for (const auto& c : r.components) pivots += c.pivots, lcp = std::max(lcp, c.lcp_size);
  state.counters["contacts"] = static_cast<double>(r.contacts.size());
  state.counters["lcp"] = lcp;
  state.counters["pivots"] = pivots;
  state.counters["stable"] = r.stable() ? 1 : 0;
}

void BM_Simulate(benchmark::State& state, const Scene* s, bool cont) {
  cairn::SimulationOptions o;
  o.continue_after_failure = cont;
  cairn::SimulationResult r;
  for (auto _ : state) {
    r = cairn::SimulatePlan(*s->assembly, *s->plan, o);
    benchmark::DoNotOptimize(r.steps.data());
  }
  state.counters["ticks"] = r.steps.at(0).ticks;
  state.counters["pivots"] = r.steps.at(0).pivots;
  state.counters["fail_tick"] = r.failure ? r.failure->tick : -1;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  bool summary = true, ticks = false;
  int reps = 3;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no_summary")
      summary = false;
    else if (a == "--ticks")
      ticks = true;
    else if (a.rfind("--reps=", 0) == 0)
      reps = std::stoi(a.substr(7));
    else
      args.push_back(argv[i]);
  }
  static const Assembly jenga = cairn::ReadScene(kSource + "/examples/jenga.json");
  static const Assembly touching = MakeTouching();
  const std::string plan_file = kSource + "/examples/plans/jenga_pull_l9.plan.json";
  static const cairn::Plan plan = cairn::ReadPlan(plan_file, jenga);
  static const cairn::Plan plan_touching = cairn::ReadPlan(plan_file, touching);
  static const std::vector<Scene> scenes = {{"Jenga", &jenga, &plan},
                                            {"JengaTouching", &touching, &plan_touching}};
  if (summary) {
    std::printf("== jenga_bench summary ==\n");
    for (const Scene& s : scenes) {
      PrintCheck(s, true, reps);
      PrintCheck(s, false, reps);
      PrintSimulation(s, false, reps, ticks);
      PrintSimulation(s, true, reps, ticks);
    }
    std::printf("== end of summary ==\n");
  }
  for (const Scene& s : scenes) {
    const Scene* p = &s;
    benchmark::RegisterBenchmark(("Check/" + s.name).c_str(), BM_Check, p, false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("CheckWithEquilibrium/" + s.name).c_str(), BM_Check, p, true)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Simulate/" + s.name).c_str(), BM_Simulate, p, false)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("Simulate/" + s.name + "/continue").c_str(), BM_Simulate, p, true)
        ->Unit(benchmark::kMillisecond);
  }
  return cairn::bench::RunBenchmarks(args);
}

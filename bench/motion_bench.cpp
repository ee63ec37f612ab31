// Motion benchmark: SimulatePlan (Algorithm 1) and AnalyzeConfiguration along
// motion paths, on scenes built in code or read from examples/.
//
// Scenes:
//   Wall      a 2-D wall in running bond, 10 courses of bricks 2 × 1 (even
//             courses 10 full bricks, odd courses 9 full bricks and a half
//             brick 1 × 1 at each end, so both end faces are flush: 105 parts,
//             100 bricks' worth), on a fixed ground; μ = 0.6, g = (0, −9.81).
//             The end brick of course 4 (the 5th from the bottom, x ∈ [18, 20])
//             is pulled out of the wall's right end face along its course by 2
//             (its own length) in 50 ticks (speed 1, dt = 0.04), support
//             "none": it carries its weight and the courses above as it slides.
//             (In 2-D a brick can only leave a running-bond wall through an end
//             face: every other brick is locked in by its neighbours.)
//   TStand    pedestal P [−0.5, 0.5] × [0, 1] on a fixed table, plank B
//             [−3, 3] × [1, 1.2] on P, block C [−0.5, 0.5] × [1.2, 2.2] on B,
//             μ = 0.6, g = (0, −1). C is moved right by 1 with support "full",
//             at dt = 0.1, 0.01, 0.001 (speed 1: 10, 100, 1000 moves).
//   Fig6III   the paper's Fig. 6 (examples/paper_fig6.json, frictionless):
//             C leaves through exit III (examples/plans/
//             paper_fig6_c_exit3.plan.json: left by 6 along E's top, then up
//             by 4, support "none", speed 1) at the plan's dt = 0.2 and 10,
//             100, 1000 times finer (50, 500, 5000, 50 000 moves). E tips once
//             C passes x = −8.25 (s* of the paper's eq. 8), i.e. after 5.25 s.
//
// Cases (<dt> as "%g"):
//   Simulate/<scene>/<dt>[/continue] SimulatePlan on the whole plan: stops at the
//                                first failure, or goes on (continue_after_failure).
//   Check/Wall                   one AnalyzeConfiguration of the assembled wall, no
//                                drive (what `cairn check` does), with its profile.
//   Replay/<scene>/<dt>[/<part>]/warm|cold
//                                AnalyzeConfiguration on every analysis SimulatePlan
//                                makes along the path (configuration, drive, options,
//                                tick 0's second solve included), with one
//                                StabilityWorkspace (warm) or none (cold). A plan that
//                                fails has two parts: to_failure (what SimulatePlan
//                                analyses before it stops) and whole (with
//                                continue_after_failure).
//   Solve/<scene>/<dt>[/<part>]/warm|cold
//                                only SolveLemke on the LCPs of those analyses (the
//                                driven LCPs AnalyzeConfiguration solves), with the last
//                                basis of the same component (warm) or without (cold).
//                                (Not the wall: a wall tick takes seconds to minutes.)
// Before the benchmarks run, a summary of every path (verdicts, contacts, LCP
// sizes per component, pivots, warm starts, stage profile, warm and cold
// replays and solves, and a check that the replay makes SimulatePlan's own
// pivots and warm starts) is printed; the wall's ticks are analysed one by
// one, warm and cold, until --wall_budget=S seconds (default 120) have
// passed. --no_summary skips it.
// Counters: ticks, pivots/tick, contacts/tick, lcp (largest LCP size), warm
// (warm starts), and the stage profile per tick (seconds). Times are for the
// whole path: divide by `ticks` for a tick.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/motion/simulate.h"
#include "cairn/report/words.h"
#include "cairn/stability/analyze.h"
#include "run_benchmarks.h"
#include "scene_builders.h"  // tests/: the scene builders the tests use

namespace {

using cairn::Assembly;
using cairn::AssemblyDef;
using cairn::Configuration;
using cairn::PartDef;
using cairn::PartRole;
using cairn::Vector2;
using cairn::Vector3;
using cairn::testing::Box;

constexpr int kPulledCourse = 4;

// The running-bond wall of examples/wall.json (10 courses of 10 bricks); the
// pulled brick is "r4_9" (course 4, x ∈ [18, 20]).
Assembly MakeWall() {
  return Assembly::Create(cairn::testing::RunningBondWall(10, 10), "motion_bench:wall");
}

Assembly MakeTStand() {
  AssemblyDef def;
  def.name = "tstand";
  def.friction = 0.6;
  def.gravity = Vector3(0, -1, 0);
  def.parts.push_back(Box("table", -4, -1, 4, 0, true));
  def.parts.push_back(Box("P", -0.5, 0, 0.5, 1));
  def.parts.push_back(Box("B", -3, 1, 3, 1.2));
  def.parts.push_back(Box("C", -0.5, 1.2, 0.5, 2.2));
  return Assembly::Create(def, "motion_bench:tstand");
}

cairn::Plan OneStepPlan(const Assembly& a, const std::string& part, Vector2 direction,
                        double distance, cairn::SupportMode support, double dt) {
  cairn::PlanDef def;
  def.dt = dt;
  def.speed = 1.0;
  cairn::PlanStepDef step;
  step.remove = {part};
  step.direction = cairn::Embed(direction);
  step.distance = distance;
  step.has_direction = true;
  step.support = support;
  def.steps.push_back(step);
  return cairn::Plan::Create(def, a, "motion_bench:plan");
}

struct Scene {
  std::string name;
  const Assembly* assembly;
  cairn::Plan plan;
};

// "0.2", "0.0002": a dt as it appears in the benchmarks' names.
std::string DtLabel(double dt) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", dt);
  return buf;
}

// One analysis of a one-step disassembly plan, as SimulatePlan makes it: the
// configuration, the drive and the options (src/motion/simulate.cpp).
struct Tick {
  Configuration config;
  cairn::DriveInputs drive;
  cairn::StabilityOptions options;
  int tick = 0;        // tick index within the step
  bool judged = true;  // false: tick 0's second solve, gripper moving (gives only the motion)
};

// Every analysis SimulatePlan makes along a one-step plan with
// continue_after_failure, in order; without it, SimulatePlan makes the first
// `to_failure` of them and stops (all of them when the plan is stable).
struct TickPath {
  std::vector<Tick> ticks;
  size_t to_failure = 0;
  int fail_tick = -1;  // the first failing tick, -1: stable
};

// The analyses of a plan, recorded from SimulatePlan itself (with
// continue_after_failure, so the whole path; `to_failure` marks where a run
// without it stops: after the failing tick's analyses).
TickPath MakeTicks(const Scene& s) {
  TickPath out;
  cairn::SimulationOptions options;
  options.continue_after_failure = true;
  options.on_analysis = [&out](const cairn::AnalysisInputs& in) {
    out.ticks.push_back(Tick{*in.config, *in.drive, *in.options, in.tick, in.judged});
  };
  const cairn::SimulationResult r = cairn::SimulatePlan(*s.assembly, s.plan, options);
  out.fail_tick = r.failure ? r.failure->tick : -1;
  out.to_failure = out.ticks.size();
  if (r.failure) {
    out.to_failure = 0;
    while (out.to_failure < out.ticks.size() && out.ticks[out.to_failure].tick <= out.fail_tick)
      ++out.to_failure;
  }
  return out;
}

// How many ticks (tick indices) the analyses cover.
int NumTicks(std::span<const Tick> ticks) {
  return static_cast<int>(
      std::count_if(ticks.begin(), ticks.end(), [](const Tick& t) { return t.judged; }));
}

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// What one pass over the ticks measured. `pivots` counts every analysis;
// `judged_pivots` only the ticks' own (what SimulatePlan reports).
struct PassStats {
  double seconds = 0;
  int pivots = 0, judged_pivots = 0, contacts = 0, warm = 0, max_lcp = 0;
  cairn::StageProfile profile;
  std::vector<cairn::StabilityResult> results;
};

PassStats RunTicks(const Scene& s, std::span<const Tick> ticks, bool warm, bool keep) {
  PassStats st;
  cairn::StabilityWorkspace ws;
  const auto t0 = Clock::now();
  for (const Tick& t : ticks) {
    cairn::StabilityResult r = cairn::AnalyzeConfiguration(*s.assembly, t.config, t.options,
                                                           &t.drive, warm ? &ws : nullptr);
    for (const auto& c : r.components) {
      st.pivots += c.pivots;
      if (t.judged) st.judged_pivots += c.pivots;
      st.max_lcp = std::max(st.max_lcp, c.lcp_size);
    }
    st.contacts += static_cast<int>(r.contacts.size());
    st.profile.detect += r.profile.detect;
    st.profile.build += r.profile.build;
    st.profile.solve += r.profile.solve;
    st.profile.classify += r.profile.classify;
    if (keep) st.results.push_back(std::move(r));
  }
  st.seconds = Since(t0);
  st.warm = ws.warm_starts();
  return st;
}

// The LCP (M, q) of every component of every analysis: exactly what
// AnalyzeConfiguration solves there (with the drive). Dense LCPs only (up to
// kMaxDenseLcp variables; larger ones are stored factored).
struct Lcp {
  cairn::MatrixX M;
  cairn::VectorX q;
};
std::vector<std::vector<Lcp>> TickLcps(const Scene& s, std::span<const Tick> ticks) {
  std::vector<std::vector<Lcp>> out;
  for (const Tick& t : ticks) {
    out.emplace_back();
    for (cairn::ContactLcp& lcp :
         cairn::BuildComponentLcps(*s.assembly, t.config, t.options, &t.drive)) {
      if (!lcp.has_dense()) throw std::runtime_error("TickLcps: " + s.name + " has a factored LCP");
      out.back().push_back({std::move(lcp.M), std::move(lcp.q)});
    }
  }
  return out;
}

// One pass of SolveLemke over the LCPs, each component warm-started (warm)
// from the last basis solved for the same component index and LCP size (what
// the workspace does when the structure stays), or cold.
struct SolveStats {
  double seconds = 0;
  int pivots = 0, warm = 0, solves = 0;
};
SolveStats SolveTicks(std::span<const std::vector<Lcp>> lcps, bool warm) {
  SolveStats st;
  std::map<size_t, cairn::LcpBasis> last;  // component index → basis of the last solve
  const auto t0 = Clock::now();
  for (const auto& tick : lcps) {
    for (size_t k = 0; k < tick.size(); ++k) {
      const cairn::LcpBasis* basis = nullptr;
      if (warm) {
        auto it = last.find(k);
        if (it != last.end() &&
            static_cast<Eigen::Index>(it->second.basic_z.size()) == tick[k].q.size())
          basis = &it->second;
      }
      cairn::LcpResult r = cairn::SolveLemke(tick[k].M, tick[k].q, {}, basis);
      st.pivots += r.pivots;
      st.warm += r.warm_start_used;
      ++st.solves;
      if (warm && (r.status == cairn::LcpStatus::kSolved || r.status == cairn::LcpStatus::kTrivial))
        last[k] = std::move(r.basis);
    }
  }
  st.seconds = Since(t0);
  return st;
}

void SetProfileCounters(benchmark::State& state, const PassStats& st, int nticks) {
  state.counters["ticks"] = nticks;
  state.counters["pivots/tick"] = static_cast<double>(st.pivots) / nticks;
  state.counters["contacts/tick"] = static_cast<double>(st.contacts) / nticks;
  state.counters["lcp"] = st.max_lcp;
  state.counters["warm"] = st.warm;
  state.counters["detect/tick"] = st.profile.detect / nticks;
  state.counters["build/tick"] = st.profile.build / nticks;
  state.counters["solve/tick"] = st.profile.solve / nticks;
  state.counters["classify/tick"] = st.profile.classify / nticks;
}

void BM_Simulate(benchmark::State& state, const Scene* s, bool continue_after) {
  cairn::SimulationOptions o;
  o.continue_after_failure = continue_after;
  cairn::SimulationResult r;
  for (auto _ : state) {
    r = cairn::SimulatePlan(*s->assembly, s->plan, o);
    benchmark::DoNotOptimize(r.steps.data());
  }
  int ticks = 0, pivots = 0, warm = 0;
  for (const auto& st : r.steps) ticks += st.ticks, pivots += st.pivots, warm += st.warm_starts;
  state.counters["ticks"] = ticks;
  state.counters["pivots/tick"] = static_cast<double>(pivots) / ticks;
  state.counters["warm"] = warm;
  state.counters["stable"] = r.stable() ? 1 : 0;
  state.counters["fail_tick"] = r.failure ? r.failure->tick : -1;
  state.counters["fail_time"] = r.failure ? r.failure->time : -1;
}

void BM_Check(benchmark::State& state, const Assembly* a) {
  const Configuration config = Configuration::Assembled(*a);
  cairn::StabilityResult r;
  cairn::StageProfile sum;
  int64_t n = 0;
  for (auto _ : state) {
    r = cairn::AnalyzeConfiguration(*a, config);
    sum.detect += r.profile.detect, sum.build += r.profile.build;
    sum.solve += r.profile.solve, sum.classify += r.profile.classify;
    ++n;
  }
  int pivots = 0, lcp = 0;
  for (const auto& c : r.components) pivots += c.pivots, lcp = std::max(lcp, c.lcp_size);
  state.counters["contacts"] = static_cast<double>(r.contacts.size());
  state.counters["components"] = static_cast<double>(r.components.size());
  state.counters["lcp"] = lcp;
  state.counters["pivots"] = pivots;
  state.counters["stable"] = r.stable() ? 1 : 0;
  state.counters["detect"] = sum.detect / n;
  state.counters["build"] = sum.build / n;
  state.counters["solve"] = sum.solve / n;
  state.counters["classify"] = sum.classify / n;
}

void BM_Replay(benchmark::State& state, const Scene* s, std::span<const Tick> ticks, bool warm) {
  PassStats st, sum;
  int64_t n = 0;
  for (auto _ : state) {
    st = RunTicks(*s, ticks, warm, false);
    sum.profile.detect += st.profile.detect, sum.profile.build += st.profile.build;
    sum.profile.solve += st.profile.solve, sum.profile.classify += st.profile.classify;
    ++n;
  }
  st.profile.detect = sum.profile.detect / n, st.profile.build = sum.profile.build / n;
  st.profile.solve = sum.profile.solve / n, st.profile.classify = sum.profile.classify / n;
  SetProfileCounters(state, st, NumTicks(ticks));
}

void BM_Solve(benchmark::State& state, std::span<const std::vector<Lcp>> lcps, int nticks,
              bool warm) {
  SolveStats st;
  for (auto _ : state) {
    st = SolveTicks(lcps, warm);
    benchmark::ClobberMemory();
  }
  state.counters["ticks"] = nticks;
  state.counters["pivots/tick"] = static_cast<double>(st.pivots) / nticks;
  state.counters["warm"] = st.warm;
  state.counters["solves"] = st.solves;
}

// ---- The printed summary -------------------------------------------------

std::string Names(const Assembly& a, const std::vector<int>& parts) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? " " : "") + a.part(parts[i]).name;
  return out;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// SimulatePlan on the whole plan, stopping at the first failure and (reps_continue > 0)
// with continue_after_failure: best times of `reps` runs, verdicts, counts. Returns the two
// results (the second empty when not run).
std::pair<cairn::SimulationResult, cairn::SimulationResult> PrintSimulation(const Scene& s,
                                                                            int reps,
                                                                            int reps_continue) {
  std::pair<cairn::SimulationResult, cairn::SimulationResult> out;
  for (const bool cont : {false, true}) {
    if (cont) reps = reps_continue;
    if (reps == 0) continue;
    cairn::SimulationOptions o;
    o.continue_after_failure = cont;
    double best = 1e300;
    cairn::SimulationResult& r = cont ? out.second : out.first;
    for (int i = 0; i < reps; ++i) {
      const auto t0 = Clock::now();
      r = cairn::SimulatePlan(*s.assembly, s.plan, o);
      best = std::min(best, Since(t0));
    }
    const auto& st = r.steps.at(0);
    std::printf(
        "%s SimulatePlan%s: %.4f s (best of %d, %.2f us/tick), verdict %s, ticks %d, pivots %d "
        "(%.3f/tick), warm starts %d\n",
        s.name.c_str(), cont ? " (continue_after_failure)" : "", best, reps, 1e6 * best / st.ticks,
        cairn::to_string(r.verdict), st.ticks, st.pivots, double(st.pivots) / st.ticks,
        st.warm_starts);
    if (r.failure)
      std::printf("  first failure: %s\n", cairn::DescribeFailure(*s.assembly, *r.failure).c_str());
    if (!r.diagnostics.empty()) std::printf("  diagnostics: %.200s\n", r.diagnostics.c_str());
  }
  return out;
}

// Replays `ticks` warm and cold (AnalyzeConfiguration, then SolveLemke alone),
// checks the warm replay against SimulatePlan's own counts (`ref`), and with
// `per_tick` prints every analysis.
void PrintTicks(const Scene& s, std::span<const Tick> ticks, const std::string& what,
                const cairn::SimulationResult& ref, bool per_tick, int reps) {
  // The fastest of `reps` alternating warm and cold passes (noise on a shared
  // machine only adds time); the first pass keeps the results.
  PassStats warm, cold;
  for (int i = 0; i < reps; ++i) {
    for (const bool w : {true, false}) {
      PassStats st = RunTicks(s, ticks, w, i == 0);
      PassStats& best = w ? warm : cold;
      if (i == 0)
        best = std::move(st);
      else if (st.seconds < best.seconds)
        best.seconds = st.seconds, best.profile = st.profile;
    }
  }
  const int nt = NumTicks(ticks);
  std::printf(
      "%s replay %s (best of %d): %d ticks (%zu analyses); warm %.4f s (%.2f us/tick, %.3f "
      "pivots/tick, %d "
      "warm starts), cold %.4f s (%.2f us/tick, %.3f pivots/tick); cold/warm %.2fx\n",
      s.name.c_str(), what.c_str(), reps, nt, ticks.size(), warm.seconds, 1e6 * warm.seconds / nt,
      double(warm.pivots) / nt, warm.warm, cold.seconds, 1e6 * cold.seconds / nt,
      double(cold.pivots) / nt, cold.seconds / warm.seconds);
  const auto& st = ref.steps.at(0);
  const bool same =
      st.ticks == nt && st.pivots == warm.judged_pivots && st.warm_starts == warm.warm;
  std::printf(
      "  %s SimulatePlan: ticks %d/%d, pivots %d/%d, warm starts %d/%d (replay/SimulatePlan)\n",
      same ? "same counts as" : "DIFFERENT from", nt, st.ticks, warm.judged_pivots, st.pivots,
      warm.warm, st.warm_starts);
  for (const auto* p : {&warm, &cold})
    std::printf("  %s profile per tick (us): detect %.2f build %.2f solve %.2f classify %.2f\n",
                p == &warm ? "warm" : "cold", 1e6 * p->profile.detect / nt,
                1e6 * p->profile.build / nt, 1e6 * p->profile.solve / nt,
                1e6 * p->profile.classify / nt);
  const auto lcps = TickLcps(s, ticks);
  SolveStats sw, sc;
  for (int i = 0; i < reps; ++i) {
    for (const bool w : {true, false}) {
      const SolveStats pass = SolveTicks(lcps, w);
      SolveStats& best = w ? sw : sc;
      if (i == 0 || pass.seconds < best.seconds) best = pass;
    }
  }
  std::printf(
      "  SolveLemke alone: warm %.2f us/tick (%.3f pivots/tick, %d of %d solves warm), cold %.2f "
      "us/tick (%.3f pivots/tick); cold/warm %.2fx\n",
      1e6 * sw.seconds / nt, double(sw.pivots) / nt, sw.warm, sw.solves, 1e6 * sc.seconds / nt,
      double(sc.pivots) / nt, sc.seconds / sw.seconds);
  if (!per_tick) return;
  std::printf(
      "  tick  contacts  components(lcp sizes)            pivots warm cold_pivots  moving\n");
  for (size_t i = 0; i < ticks.size(); ++i) {
    const auto& r = warm.results[i];
    std::string sizes;
    int pivots = 0, wu = 0, cold_pivots = 0;
    for (const auto& c : r.components) {
      sizes += (sizes.empty() ? "" : ",") + std::to_string(c.lcp_size);
      pivots += c.pivots;
      wu += c.warm_start_used;
    }
    for (const auto& c : cold.results[i].components) cold_pivots += c.pivots;
    std::printf("  %4d%c %8zu  %2zu (%s)%*s %6d %4d %11d  %s%s%s\n", ticks[i].tick,
                ticks[i].judged ? ' ' : '*', r.contacts.size(), r.components.size(), sizes.c_str(),
                std::max(0, 28 - static_cast<int>(sizes.size())), "", pivots, wu, cold_pivots,
                Names(*s.assembly, r.moving).c_str(), r.unsupported.empty() ? "" : " unsupported: ",
                Names(*s.assembly, r.unsupported).c_str());
  }
  std::printf("  (* tick 0's second solve, gripper moving)\n");
}

// A plan's summary: SimulatePlan, then the replays up to the first failure
// and, when the plan fails, of the whole path (continue_after_failure); at
// coarse steps, every analysis of the path.
void PrintScene(const Scene& s, const TickPath& path, int reps) {
  const auto [stop, cont] = PrintSimulation(s, reps, path.fail_tick >= 0 ? reps : 0);
  const bool per_tick = s.plan.dt > 0.05, fails = path.fail_tick >= 0;
  const std::span<const Tick> all(path.ticks);
  PrintTicks(s, all.first(path.to_failure), fails ? "to the failure" : "whole path", stop,
             per_tick && !fails, reps);
  if (fails) PrintTicks(s, all, "whole path (continue)", cont, per_tick, reps);
}

// The wall's ticks one by one, warm (one workspace) and cold, each timed, until
// `budget` seconds have gone by (a tick of the 105-part wall takes seconds).
void PrintWallTicks(const Scene& s, std::span<const Tick> ticks, double budget) {
  cairn::StabilityWorkspace ws;
  const auto start = Clock::now();
  std::printf(
      "  tick  contacts comps lcp(s)  warm: pivots used  time(s)   cold: pivots time(s)  verdict "
      "[moving]  diagnostics\n");
  int done = 0;
  double warm_total = 0, cold_total = 0;
  for (const Tick& t : ticks) {
    if (Since(start) > budget) break;
    auto t0 = Clock::now();
    const auto rw = cairn::AnalyzeConfiguration(*s.assembly, t.config, t.options, &t.drive, &ws);
    const double tw = Since(t0);
    t0 = Clock::now();
    const auto rc = cairn::AnalyzeConfiguration(*s.assembly, t.config, t.options, &t.drive);
    const double tc = Since(t0);
    std::string sizes;
    int pw = 0, pc = 0, used = 0;
    for (const auto& c : rw.components) {
      sizes += (sizes.empty() ? "" : ",") + std::to_string(c.lcp_size);
      pw += c.pivots;
      used += c.warm_start_used;
    }
    for (const auto& c : rc.components) pc += c.pivots;
    std::printf("  %4d%c %8zu %5zu %-7s %12d %4d %8.3f %12d %8.3f  %s [%s] %.90s\n", t.tick,
                t.judged ? ' ' : '*', rw.contacts.size(), rw.components.size(), sizes.c_str(), pw,
                used, tw, pc, tc, cairn::to_string(rw.verdict),
                Names(*s.assembly, rw.moving).c_str(), rw.diagnostics.c_str());
    warm_total += tw, cold_total += tc;
    ++done;
  }
  std::printf(
      "  %d of %zu analyses in the budget (* tick 0's second solve): warm %.3f s, cold %.3f s\n",
      done, ticks.size(), warm_total, cold_total);
}

void PrintCheck(const Assembly& a, int reps) {
  const Configuration config = Configuration::Assembled(a);
  std::vector<double> times;
  cairn::StabilityResult r;
  for (int i = 0; i < reps; ++i) {
    const auto t0 = Clock::now();
    r = cairn::AnalyzeConfiguration(a, config);
    times.push_back(Since(t0));
  }
  std::string sizes;
  int pivots = 0;
  for (const auto& c : r.components) {
    sizes += (sizes.empty() ? "" : ",") + std::to_string(c.lcp_size);
    pivots += c.pivots;
  }
  std::printf(
      "%s check (AnalyzeConfiguration, assembled, no drive): %.4f s (median of %d), verdict %s, "
      "%zu contacts, %zu components (LCP sizes %s), %d pivots, %s\n"
      "  profile (ms): detect %.3f build %.3f solve %.3f classify %.3f\n",
      a.name().c_str(), Median(times), reps, cairn::to_string(r.verdict), r.contacts.size(),
      r.components.size(), sizes.c_str(), pivots, cairn::to_string(r.formulation),
      1e3 * r.profile.detect, 1e3 * r.profile.build, 1e3 * r.profile.solve,
      1e3 * r.profile.classify);
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  static const Assembly wall = MakeWall();
  static const Assembly tstand = MakeTStand();
  static const Assembly fig6 =
      cairn::ReadScene(std::string(CAIRN_SOURCE_DIR) + "/examples/paper_fig6.json");
  static const Scene wall_scene{"Wall", &wall,
                                OneStepPlan(wall, "r" + std::to_string(kPulledCourse) + "_9",
                                            Vector2(1, 0), 2.0, cairn::SupportMode::kNone, 0.04)};
  // The step-refinement scenes: the T-stand at dt = 0.1, 0.01, 0.001; the
  // Fig. 6 exit-III plan at its own dt (0.2) and 10, 100, 1000 times finer.
  static std::vector<Scene> scenes;
  for (const double dt : {0.1, 0.01, 0.001})
    scenes.push_back({"TStand/" + DtLabel(dt), &tstand,
                      OneStepPlan(tstand, "C", Vector2(1, 0), 1.0, cairn::SupportMode::kFull, dt)});
  const cairn::Plan exit3 = cairn::ReadPlan(
      std::string(CAIRN_SOURCE_DIR) + "/examples/plans/paper_fig6_c_exit3.plan.json", fig6);
  for (const int refine : {1, 10, 100, 1000}) {
    cairn::Plan plan = exit3;
    plan.dt /= refine;
    scenes.push_back({"Fig6III/" + DtLabel(plan.dt), &fig6, plan});
  }

  // Summary (plain timing, median of several runs).
  // --no_summary skips the summary; --wall_budget=S bounds the wall's ticks (s).
  bool summary = true;
  double wall_budget = 120;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--no_summary") summary = false;
    if (arg.rfind("--wall_budget=", 0) == 0) wall_budget = std::stod(arg.substr(14));
  }
  static const TickPath wall_ticks = MakeTicks(wall_scene);
  static std::vector<TickPath> paths;
  for (const Scene& s : scenes) paths.push_back(MakeTicks(s));
  if (summary) {
    std::printf("== motion_bench summary ==\n");
    PrintCheck(wall, 3);
    PrintSimulation(wall_scene, 3, 0);
    PrintWallTicks(wall_scene, wall_ticks.ticks, wall_budget);
    for (size_t i = 0; i < scenes.size(); ++i) PrintScene(scenes[i], paths[i], 5);
    std::printf("== end of summary ==\n");
    std::fflush(stdout);
  }

  benchmark::RegisterBenchmark("Check/Wall", BM_Check, &wall)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Simulate/Wall", BM_Simulate, &wall_scene, false)
      ->Unit(benchmark::kMillisecond);
  // The wall's whole path (continue_after_failure), its replay and its solves
  // take minutes (seconds per tick): the summary times them tick by tick.
  // A plan that fails is replayed up to its failure ("to_failure", what
  // SimulatePlan analyses) and whole ("whole", continue_after_failure).
  static std::vector<std::vector<std::vector<Lcp>>> lcps;
  lcps.reserve(scenes.size());
  for (size_t i = 0; i < scenes.size(); ++i) {
    const Scene* s = &scenes[i];
    const TickPath& path = paths[i];
    const bool fails = path.fail_tick >= 0;
    lcps.push_back(TickLcps(*s, path.ticks));
    benchmark::RegisterBenchmark(("Simulate/" + s->name).c_str(), BM_Simulate, s, false)
        ->Unit(benchmark::kMicrosecond);
    if (fails)
      benchmark::RegisterBenchmark(("Simulate/" + s->name + "/continue").c_str(), BM_Simulate, s,
                                   true)
          ->Unit(benchmark::kMicrosecond);
    const std::span<const Tick> all(path.ticks);
    const std::span<const std::vector<Lcp>> all_lcps(lcps.back());
    for (const bool whole : {false, true}) {
      if (whole && !fails) continue;
      const size_t count = whole ? all.size() : path.to_failure;
      const std::string part = fails ? (whole ? "/whole" : "/to_failure") : "";
      for (const bool warm : {true, false})
        benchmark::RegisterBenchmark(
            ("Replay/" + s->name + part + (warm ? "/warm" : "/cold")).c_str(), BM_Replay, s,
            all.first(count), warm)
            ->Unit(benchmark::kMicrosecond);
      for (const bool warm : {true, false})
        benchmark::RegisterBenchmark(
            ("Solve/" + s->name + part + (warm ? "/warm" : "/cold")).c_str(), BM_Solve,
            all_lcps.first(count), NumTicks(all.first(count)), warm)
            ->Unit(benchmark::kMicrosecond);
    }
  }

  std::vector<char*> args;
  for (int i = 0; i < argc; ++i)
    if (std::string(argv[i]) != "--no_summary" &&
        std::string(argv[i]).rfind("--wall_budget=", 0) != 0)
      args.push_back(argv[i]);
  return cairn::bench::RunBenchmarks(args);
}

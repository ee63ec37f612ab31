// Motion benchmark: SimulatePlan (Algorithm 1) and AnalyzeConfiguration along
// motion paths, on scenes built in code.
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
//
// Cases:
//   Simulate/<scene>[/dt]        SimulatePlan on the whole plan (stops at the first
//                                failure).
//   Check/Wall                   one AnalyzeConfiguration of the assembled wall, no
//                                drive (what `cairn check` does), with its profile.
//   Replay/<scene>/<dt>/warm|cold AnalyzeConfiguration on the configurations of every
//                                tick of the path, as SimulatePlan builds them, with
//                                one StabilityWorkspace (warm) or none (cold).
//   Solve/<scene>/<dt>/warm|cold only SolveLemke on the LCPs of those ticks, with the
//                                previous tick's basis (warm) or without (cold).
//                                (T-stand only: a wall tick takes seconds to minutes.)
// Before the benchmarks run, a summary of every path (verdicts, contacts, LCP
// sizes per component, pivots, warm starts, stage profile) is printed; the
// wall's ticks are analysed one by one, warm and cold, until --wall_budget=S
// seconds (default 120) have passed. --no_summary skips it.
// Counters: ticks, pivots/tick, contacts/tick, lcp (largest LCP size), warm
// (warm starts), and the stage profile per tick (seconds).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "cairn/motion/simulate.h"
#include "cairn/stability/analyze.h"
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

constexpr int kCourses = 10;
constexpr int kPulledCourse = 4;

// The running-bond wall; the pulled brick is "r4_9" (course 4, x ∈ [18, 20]).
Assembly MakeWall() {
  AssemblyDef def;
  def.name = "wall";
  def.friction = 0.6;
  def.parts.push_back(Box("ground", -2, -1, 22, 0, true));
  for (int r = 0; r < kCourses; ++r) {
    const double y = r;
    std::vector<std::pair<double, double>> spans;
    if (r % 2 == 0) {
      for (int k = 0; k < 10; ++k) spans.emplace_back(2.0 * k, 2.0 * k + 2);
    } else {
      spans.emplace_back(0, 1);
      for (int k = 0; k < 9; ++k) spans.emplace_back(1 + 2.0 * k, 3 + 2.0 * k);
      spans.emplace_back(19, 20);
    }
    for (size_t k = 0; k < spans.size(); ++k)
      def.parts.push_back(Box("r" + std::to_string(r) + "_" + std::to_string(k), spans[k].first, y,
                              spans[k].second, y + 1));
  }
  return Assembly::Create(def, "motion_bench:wall");
}

Assembly MakeTStand() {
  AssemblyDef def;
  def.name = "tstand";
  def.friction = 0.6;
  def.gravity = Vector2(0, -1);
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
  step.direction = direction;
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

// One tick of a one-step disassembly plan, as SimulatePlan builds it: the
// configuration, the drive and the options (src/motion/simulate.cpp).
struct Tick {
  Configuration config;
  cairn::DriveInputs drive;
  cairn::StabilityOptions options;
};

// The ticks of the plan's single step. The velocities carried from tick to
// tick (nu_prev) come from a warm reference pass; parts that move are not held
// (SimulatePlan stops there, or holds them with continue_after_failure), so
// after the first failure the ticks are those of "the wall as if nothing
// moved", which is what continue_after_failure analyses too, held parts aside.
std::vector<Tick> MakeTicks(const Scene& s, bool carry_velocities = true) {
  const Assembly& a = *s.assembly;
  const cairn::PlanStep& step = s.plan.steps[0];
  const int n = a.num_parts();
  const double L = step.Length(), tick_length = s.plan.speed * s.plan.dt;
  const int moves = std::max(1, static_cast<int>(std::ceil(L / tick_length - 1e-9)));
  std::vector<Tick> ticks;
  std::vector<Vector3> nu(n, Vector3::Zero());
  cairn::StabilityWorkspace ws;
  Configuration config = Configuration::Assembled(a);
  for (int tick = 0; tick <= moves; ++tick) {
    const double s_now = std::min(tick * tick_length, L);
    const double next = std::min((tick + 1) * tick_length, L);
    const double dt = tick < moves ? (next - s_now) / s.plan.speed : s.plan.dt;
    const bool moving_now = tick > 0 && tick < moves;
    const Vector2 dir = (step.At(std::min(L, s_now + 1e-9)) - step.At(s_now)).normalized();
    const Vector2 v_g = moving_now ? Vector2(s.plan.speed * dir) : Vector2::Zero();
    Tick t;
    for (int p : step.grip) config.poses[p] = cairn::Pose2{step.At(s_now), 0.0};
    t.config = config;
    t.drive.role.assign(n, PartRole::kJudged);
    t.drive.velocity.assign(n, Vector2::Zero());
    t.drive.nu_prev = nu;
    for (int p : step.grip) {
      if (tick == 0) {
        t.drive.role[p] = PartRole::kCarried;
      } else {
        t.drive.role[p] =
            step.support == cairn::SupportMode::kFull ? PartRole::kPrescribed : PartRole::kGuided;
        t.drive.velocity[p] = v_g;
      }
    }
    t.options.dt = dt;
    t.options.tolerances = a.MakeTolerances(dt);
    if (carry_velocities) {
      const cairn::StabilityResult r =
          cairn::AnalyzeConfiguration(a, t.config, t.options, &t.drive, &ws);
      for (const cairn::PartMotion& m : r.parts)
        nu[m.part] = Vector3(m.linear.x(), m.linear.y(), m.angular);
    }
    ticks.push_back(std::move(t));
  }
  return ticks;
}

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// What one pass over the ticks measured.
struct PassStats {
  double seconds = 0;
  int pivots = 0, contacts = 0, warm = 0, max_lcp = 0;
  cairn::StageProfile profile;
  std::vector<cairn::StabilityResult> results;
};

PassStats RunTicks(const Scene& s, const std::vector<Tick>& ticks, bool warm, bool keep) {
  PassStats st;
  cairn::StabilityWorkspace ws;
  const auto t0 = Clock::now();
  for (const Tick& t : ticks) {
    cairn::StabilityResult r = cairn::AnalyzeConfiguration(*s.assembly, t.config, t.options,
                                                           &t.drive, warm ? &ws : nullptr);
    for (const auto& c : r.components) {
      st.pivots += c.pivots;
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
  st.warm = ws.warm_starts;
  return st;
}

// The LCPs of every tick (same M, q as AnalyzeConfiguration builds with the drive).
std::vector<std::vector<cairn::ContactLcp>> TickLcps(const Scene& s,
                                                     const std::vector<Tick>& ticks) {
  // BuildComponentLcps has no drive; rebuild the driven LCPs here the way
  // AnalyzeConfiguration does is not public, so the solve-only case uses the
  // undriven LCPs of each tick's configuration (same sizes and structure).
  std::vector<std::vector<cairn::ContactLcp>> out;
  for (const Tick& t : ticks) {
    cairn::StabilityOptions o = t.options;
    o.formulation = cairn::Formulation::kStewartTrinkle;
    out.push_back(cairn::BuildComponentLcps(*s.assembly, t.config, o));
  }
  return out;
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

void BM_Replay(benchmark::State& state, const Scene* s, const std::vector<Tick>* ticks, bool warm) {
  PassStats st, sum;
  int64_t n = 0;
  for (auto _ : state) {
    st = RunTicks(*s, *ticks, warm, false);
    sum.profile.detect += st.profile.detect, sum.profile.build += st.profile.build;
    sum.profile.solve += st.profile.solve, sum.profile.classify += st.profile.classify;
    ++n;
  }
  st.profile.detect = sum.profile.detect / n, st.profile.build = sum.profile.build / n;
  st.profile.solve = sum.profile.solve / n, st.profile.classify = sum.profile.classify / n;
  SetProfileCounters(state, st, static_cast<int>(ticks->size()));
}

void BM_Solve(benchmark::State& state, const std::vector<std::vector<cairn::ContactLcp>>* lcps,
              bool warm) {
  int pivots = 0, warm_used = 0, nsolves = 0;
  for (auto _ : state) {
    pivots = warm_used = nsolves = 0;
    std::map<size_t, cairn::LcpBasis> last;  // component index → basis of the previous tick
    for (const auto& tick : *lcps) {
      for (size_t k = 0; k < tick.size(); ++k) {
        const cairn::LcpBasis* basis = nullptr;
        if (warm) {
          auto it = last.find(k);
          if (it != last.end() &&
              static_cast<Eigen::Index>(it->second.basic_z.size()) == tick[k].q.size())
            basis = &it->second;
        }
        cairn::LcpResult r = cairn::SolveLemke(tick[k].M, tick[k].q, {}, basis);
        pivots += r.pivots;
        warm_used += r.warm_start_used;
        ++nsolves;
        if (warm) last[k] = std::move(r.basis);
      }
    }
    benchmark::ClobberMemory();
  }
  state.counters["ticks"] = static_cast<double>(lcps->size());
  state.counters["pivots/tick"] = static_cast<double>(pivots) / lcps->size();
  state.counters["warm"] = warm_used;
  state.counters["solves"] = nsolves;
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

void PrintSimulation(const Scene& s, int reps, int reps_continue) {
  for (const bool cont : {false, true}) {
    if (cont) reps = reps_continue;
    if (reps == 0) continue;
    cairn::SimulationOptions o;
    o.continue_after_failure = cont;
    std::vector<double> times;
    cairn::SimulationResult r;
    for (int i = 0; i < reps; ++i) {
      const auto t0 = Clock::now();
      r = cairn::SimulatePlan(*s.assembly, s.plan, o);
      times.push_back(Since(t0));
    }
    const auto& st = r.steps.at(0);
    std::printf(
        "%s SimulatePlan%s: %.4f s (median of %d), verdict %s, ticks %d, pivots %d "
        "(%.1f/tick), warm starts %d\n",
        s.name.c_str(), cont ? " (continue_after_failure)" : "", Median(times), reps,
        cairn::to_string(r.verdict), st.ticks, st.pivots, double(st.pivots) / st.ticks,
        st.warm_starts);
    if (r.failure) std::printf("  first failure: %s\n", r.failure->description.c_str());
    if (!r.diagnostics.empty()) std::printf("  diagnostics: %s\n", r.diagnostics.c_str());
  }
}

void PrintTicks(const Scene& s, const std::vector<Tick>& ticks, bool per_tick) {
  const PassStats warm = RunTicks(s, ticks, true, true);
  const PassStats cold = RunTicks(s, ticks, false, true);
  const int nt = static_cast<int>(ticks.size());
  std::printf(
      "%s replay: %d ticks; warm %.4f s (%.1f us/tick, %.2f pivots/tick, %d warm starts), "
      "cold %.4f s (%.1f us/tick, %.2f pivots/tick); cold/warm %.2fx\n",
      s.name.c_str(), nt, warm.seconds, 1e6 * warm.seconds / nt, double(warm.pivots) / nt,
      warm.warm, cold.seconds, 1e6 * cold.seconds / nt, double(cold.pivots) / nt,
      cold.seconds / warm.seconds);
  for (const auto* p : {&warm, &cold})
    std::printf("  %s profile per tick (us): detect %.2f build %.2f solve %.2f classify %.2f\n",
                p == &warm ? "warm" : "cold", 1e6 * p->profile.detect / nt,
                1e6 * p->profile.build / nt, 1e6 * p->profile.solve / nt,
                1e6 * p->profile.classify / nt);
  if (!per_tick) return;
  std::printf(
      "  tick  contacts  components(lcp sizes)            pivots warm cold_pivots  moving\n");
  for (int i = 0; i < nt; ++i) {
    const auto& r = warm.results[i];
    std::string sizes;
    int pivots = 0, wu = 0, cold_pivots = 0;
    for (const auto& c : r.components) {
      sizes += (sizes.empty() ? "" : ",") + std::to_string(c.lcp_size);
      pivots += c.pivots;
      wu += c.warm_start_used;
    }
    for (const auto& c : cold.results[i].components) cold_pivots += c.pivots;
    std::printf(
        "  %4d  %8zu  %2zu (%s)%*s %6d %4d %11d  %s%s%s\n", i, r.contacts.size(),
        r.components.size(), sizes.c_str(), std::max(0, 28 - static_cast<int>(sizes.size())), "",
        pivots, wu, cold_pivots, Names(*s.assembly, r.moving).c_str(),
        r.unsupported.empty() ? "" : " unsupported: ", Names(*s.assembly, r.unsupported).c_str());
  }
}

// The wall's ticks one by one, warm (one workspace) and cold, each timed, until
// `budget` seconds have gone by (a tick of the 105-part wall takes seconds).
void PrintWallTicks(const Scene& s, const std::vector<Tick>& ticks, double budget) {
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
    std::printf("  %4d  %8zu %5zu %-7s %12d %4d %8.3f %12d %8.3f  %s [%s] %.90s\n", done,
                rw.contacts.size(), rw.components.size(), sizes.c_str(), pw, used, tw, pc, tc,
                cairn::to_string(rw.verdict), Names(*s.assembly, rw.moving).c_str(),
                rw.diagnostics.c_str());
    warm_total += tw, cold_total += tc;
    ++done;
  }
  std::printf("  %d of %zu ticks in the budget: warm %.3f s, cold %.3f s\n", done, ticks.size(),
              warm_total, cold_total);
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
  static const Scene wall_scene{"Wall", &wall,
                                OneStepPlan(wall, "r" + std::to_string(kPulledCourse) + "_9",
                                            Vector2(1, 0), 2.0, cairn::SupportMode::kNone, 0.04)};
  static std::vector<Scene> tstand_scenes;
  for (const double dt : {0.1, 0.01, 0.001})
    tstand_scenes.push_back(
        {"TStand/" + std::to_string(dt).substr(0, 5), &tstand,
         OneStepPlan(tstand, "C", Vector2(1, 0), 1.0, cairn::SupportMode::kFull, dt)});

  // Summary (plain timing, median of several runs).
  // --no_summary skips the summary; --wall_budget=S bounds the wall's ticks (s).
  bool summary = true;
  double wall_budget = 120;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--no_summary") summary = false;
    if (arg.rfind("--wall_budget=", 0) == 0) wall_budget = std::stod(arg.substr(14));
  }
  // The wall's ticks carry no velocities: every tick of it ends in a solver
  // failure (see docs/benchmarks.md), after which SimulatePlan carries zero.
  static const std::vector<Tick> wall_ticks = MakeTicks(wall_scene, false);
  static std::vector<std::vector<Tick>> tstand_ticks;
  for (const Scene& s : tstand_scenes) tstand_ticks.push_back(MakeTicks(s));
  if (summary) {
    std::printf("== motion_bench summary ==\n");
    PrintCheck(wall, 3);
    PrintSimulation(wall_scene, 3, 0);
    PrintWallTicks(wall_scene, wall_ticks, wall_budget);
    for (size_t i = 0; i < tstand_scenes.size(); ++i) {
      PrintSimulation(tstand_scenes[i], 5, 5);
      PrintTicks(tstand_scenes[i], tstand_ticks[i], tstand_scenes[i].plan.dt > 0.05);
    }
    std::printf("== end of summary ==\n");
    std::fflush(stdout);
  }

  static std::vector<std::vector<std::vector<cairn::ContactLcp>>> tstand_lcps;
  for (size_t i = 0; i < tstand_scenes.size(); ++i)
    tstand_lcps.push_back(TickLcps(tstand_scenes[i], tstand_ticks[i]));

  benchmark::RegisterBenchmark("Check/Wall", BM_Check, &wall)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("Simulate/Wall", BM_Simulate, &wall_scene, false)
      ->Unit(benchmark::kMillisecond);
  // The wall's whole path (continue_after_failure), its replay and its solves
  // take minutes (seconds per tick): the summary times them tick by tick.
  for (size_t i = 0; i < tstand_scenes.size(); ++i) {
    const Scene* s = &tstand_scenes[i];
    benchmark::RegisterBenchmark(("Simulate/" + s->name).c_str(), BM_Simulate, s, false)
        ->Unit(benchmark::kMicrosecond);
    for (const bool warm : {true, false})
      benchmark::RegisterBenchmark(
          ("Replay/" + s->name + "/" + std::string(warm ? "warm" : "cold")).c_str(), BM_Replay, s,
          &tstand_ticks[i], warm)
          ->Unit(benchmark::kMicrosecond);
    for (const bool warm : {true, false})
      benchmark::RegisterBenchmark(
          ("Solve/" + s->name + "/" + std::string(warm ? "warm" : "cold")).c_str(), BM_Solve,
          &tstand_lcps[i], warm)
          ->Unit(benchmark::kMicrosecond);
  }

  std::vector<char*> args;
  for (int i = 0; i < argc; ++i)
    if (std::string(argv[i]) != "--no_summary" &&
        std::string(argv[i]).rfind("--wall_budget=", 0) != 0)
      args.push_back(argv[i]);
  int bargc = static_cast<int>(args.size());
  benchmark::Initialize(&bargc, args.data());
  if (benchmark::ReportUnrecognizedArguments(bargc, args.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

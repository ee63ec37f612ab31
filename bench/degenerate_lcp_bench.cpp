// Degenerate contact LCPs: the component LCPs of scenes whose
// contacts are many coplanar points per interface, solved by Cairn's factored
// Lemke (SolveLemkeFactored), by the same after HullContactSubset has reduced
// every planar patch to its hull vertices, and by Siconos' lcp_lexicolemke on
// the dense M (when n ≤ --siconos_max), all in the same run.
//
// Cases (each skipped when its file is absent):
//   wall          examples/wall.json, assembled
//   jenga/tick-k  examples/jenga.json along examples/plans/jenga_pull_l9.plan.json:
//                 the analyses SimulatePlan makes at ticks --ticks (default
//                 1,20,45,46), recorded through SimulationOptions::on_analysis
//   crossvault    compas_assembly/crossvault_assembly.json, μ 0.84
//   armadillo     compas_cra/armadillo_cra.json, μ 0.84, stored interfaces
//   shelf, shelf-s1/s2/s3 (μ 0.84), shelf-stable (0.28), snake (0.48),
//   bridge (0.07), cube-curve-short (0.84): compas_cra, supports 0 (bridge 0, 1)
//
// Output: one line per (component, solver): n, status, pivots, time (ms,
// one solve; best of --reps), natural-map residual max_i |min(z_i, w_i)| on
// the LCP solved (the full one; for the reduced one, of the reduced z
// extended by zeros and checked on the full LCP with IsContactLcpSolution).
// Components with n < --min_n (default 200) are left out: they are not the
// degenerate ones.
//
// Usage: degenerate_lcp_bench [--cases a,b,...] [--reps N] [--siconos_max N]
//                             [--min_n N] [--ticks 1,20,46]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cairn/contact/contact_reduction.h"
#include "cairn/io/compas_reader.h"
#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/lcp/factored_lcp.h"
#include "cairn/mechanics/contact_model.h"
#include "cairn/motion/simulate.h"
#include "cairn/stability/analyze.h"
#include "contact/reduced_lcp.h"

#if defined(CAIRN_HAVE_SICONOS)
#include "LCP_Solvers.h"
#include "LinearComplementarityProblem.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "lcp_cst.h"
#endif

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

const std::string kSource = CAIRN_SOURCE_DIR;
const std::string kData = std::string(CAIRN_SHARED_DIR) + "/datasets/";

struct Options {
  std::set<std::string> cases;  // empty: all
  int reps = 1;
  int siconos_max = 2000;
  int min_n = 200;
  std::vector<int> ticks = {1, 20, 45, 46};
};

struct Outcome {
  std::string status;
  int pivots = 0;
  double ms = 0;
  double residual = 0;
  bool ok = false;
};

void Print(const std::string& name, int n, const char* solver, const Outcome& o) {
  std::printf("%-28s %6d  %-16s %-18s %7d %11.2f %10.2e\n", name.c_str(), n, solver,
              o.status.c_str(), o.pivots, o.ms, o.residual);
  std::fflush(stdout);
}

template <class F>
double BestOf(int reps, F&& f) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = Clock::now();
    f();
    best = std::min(best, Since(t0));
  }
  return 1e3 * best;
}

// The LCP with the contacts `keep` only (same bodies, formulation, D), factored.
cairn::ContactLcp Rebuild(const cairn::ContactLcp& lcp, const std::vector<int>& keep) {
  std::vector<cairn::Contact> contacts;
  contacts.reserve(keep.size());
  for (int i : keep) contacts.push_back(lcp.contacts[i]);
  cairn::LcpBuildOptions build = lcp.build;
  build.storage = cairn::LcpStorage::kFactored;
  return cairn::BuildContactLcp(lcp.bodies, contacts, build);
}

// The reduced solution z_r extended to the full LCP: zero at the dropped
// contacts; λ of a dropped frictional contact = max over its patch's kept
// contacts' λ (one body pair, one relative motion: their λ is the sliding
// speed, the same affine function as at the dropped point; see
// contact_reduction.h).
cairn::VectorX Extend(const cairn::ContactLcp& full, const cairn::ContactLcp& red,
                      const std::vector<int>& keep, const cairn::VectorX& z_r) {
  return cairn::testing::ExtendReducedSolution(full, red, keep, z_r);
}

void SolveAll(const std::string& name, const cairn::ContactLcp& lcp, const Options& opt) {
  const int n = lcp.size();
  if (n < opt.min_n) return;
  cairn::ContactLcp f = lcp;
  if (f.factored.size() != n)
    f = Rebuild(lcp, [&] {
      std::vector<int> all(lcp.contacts.size());
      for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
      return all;
    }());
  const double tol_scale = std::max(1.0, f.q.cwiseAbs().maxCoeff());

  // Cairn's factored Lemke on the full LCP.
  {
    cairn::LcpResult r;
    Outcome o;
    o.ms = BestOf(opt.reps, [&] { r = cairn::SolveLemkeFactored(f.factored, f.q); });
    o.status = cairn::to_string(r.status);
    o.pivots = r.pivots;
    o.residual = r.z.size() == n ? cairn::LcpResidual(f.factored, f.q, r.z) : -1;
    Print(name, n, "cairn", o);
  }
  // The same after the hull reduction.
  {
    std::vector<int> keep;
    cairn::ContactLcp red;
    cairn::LcpResult r;
    Outcome o;
    o.ms = BestOf(opt.reps, [&] {
      keep = cairn::HullContactSubset(f.contacts);
      red = Rebuild(f, keep);
      r = cairn::SolveLemkeFactored(red.factored, red.q);
    });
    o.status = cairn::to_string(r.status);
    o.pivots = r.pivots;
    if (r.status == cairn::LcpStatus::kSolved || r.status == cairn::LcpStatus::kTrivial) {
      const cairn::VectorX z = Extend(f, red, keep, r.z);
      o.residual = cairn::LcpResidual(f.factored, f.q, z);
      if (!cairn::IsContactLcpSolution(f, z, 1e-8 * tol_scale)) o.status += " (ext. FAILS)";
    } else {
      o.residual = -1;
    }
    char label[64];
    std::snprintf(label, sizeof label, "cairn+hull(%d)", red.size());
    Print(name, n, label, o);
  }
#if defined(CAIRN_HAVE_SICONOS)
  if (n <= opt.siconos_max) {
    const cairn::MatrixX Md = f.factored.ToDense();
    NumericsMatrix* M = NM_create(NM_DENSE, n, n);
    std::copy(Md.data(), Md.data() + Md.size(), M->matrix0);
    cairn::VectorX q = f.q;
    LinearComplementarityProblem problem;
    problem.size = n;
    problem.M = M;
    problem.q = q.data();
    SolverOptions* so = solver_options_create(SICONOS_LCP_LEMKE);
    so->iparam[SICONOS_IPARAM_MAX_ITER] = 100000;
    cairn::VectorX z = cairn::VectorX::Zero(n), w = cairn::VectorX::Zero(n);
    int info = 0;
    Outcome o;
    o.ms = BestOf(opt.reps, [&] { lcp_lexicolemke(&problem, z.data(), w.data(), &info, so); });
    const int it = so->iparam[SICONOS_IPARAM_ITER_DONE];
    o.pivots = info == 0 ? it + 1 : it;
    o.residual = cairn::LcpResidual(f.factored, f.q, z);
    o.status = info == 0
                   ? (cairn::IsContactLcpSolution(f, z, 1e-8 * tol_scale) ? "solved"
                                                                          : "solved (check FAILS)")
                   : "info " + std::to_string(info);
    Print(name, n, "siconos", o);
    solver_options_delete(so);
    NM_free(M);
  } else {
    Print(name, n, "siconos", Outcome{"skipped (n > max)", 0, 0, 0, false});
  }
#endif
}

void Components(const std::string& name, const cairn::Assembly& a,
                const cairn::Configuration& config, const Options& opt,
                const cairn::StabilityOptions& so = {}, const cairn::DriveInputs* drive = nullptr) {
  cairn::StabilityOptions o = so;
  o.lcp_storage = cairn::LcpStorage::kFactored;
  const auto lcps = cairn::BuildComponentLcps(a, config, o, drive);
  for (size_t k = 0; k < lcps.size(); ++k) SolveAll(name + "/" + std::to_string(k), lcps[k], opt);
}

bool Wanted(const Options& opt, const std::string& c) {
  return opt.cases.empty() || opt.cases.count(c) > 0;
}

void Compas(const std::string& name, const std::string& file, double mu, bool stored,
            const std::vector<std::string>& supports, const Options& opt) {
  if (!Wanted(opt, name)) return;
  const std::string path = kData + file;
  if (!std::filesystem::exists(path)) {
    std::printf("%s: %s not found, skipped\n", name.c_str(), path.c_str());
    return;
  }
  cairn::CompasOptions co;
  co.friction = mu;
  co.stored_interfaces = stored;
  cairn::CompasModel model = cairn::CompasToModel(cairn::ReadCompasAssembly(path), co, path);
  for (auto& p : model.def.parts)
    if (std::find(supports.begin(), supports.end(), p.name) != supports.end()) p.fixed = true;
  const cairn::Assembly a = cairn::CreateCompasAssembly(model, path);
  Components(name, a, cairn::Configuration::Assembled(a), opt);
}

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string t; std::getline(ss, t, ',');) out.push_back(t);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--cases") {
      for (const auto& c : Split(v)) opt.cases.insert(c);
    } else if (k == "--reps") {
      opt.reps = std::stoi(v);
    } else if (k == "--siconos_max") {
      opt.siconos_max = std::stoi(v);
    } else if (k == "--min_n") {
      opt.min_n = std::stoi(v);
    } else if (k == "--ticks") {
      opt.ticks.clear();
      for (const auto& t : Split(v)) opt.ticks.push_back(std::stoi(t));
    } else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
  }
#if !defined(CAIRN_HAVE_SICONOS)
  std::fprintf(stderr, "degenerate_lcp_bench: built without Siconos; only Cairn is measured\n");
#endif
  std::printf("%-28s %6s  %-16s %-18s %7s %11s %10s\n", "component", "n", "solver", "status",
              "pivots", "time (ms)", "residual");

  if (Wanted(opt, "wall")) {
    const cairn::Assembly wall = cairn::ReadScene(kSource + "/examples/wall.json");
    Components("wall", wall, cairn::Configuration::Assembled(wall), opt);
  }
  if (Wanted(opt, "jenga")) {
    const cairn::Assembly jenga = cairn::ReadScene(kSource + "/examples/jenga.json");
    const cairn::Plan plan =
        cairn::ReadPlan(kSource + "/examples/plans/jenga_pull_l9.plan.json", jenga);
    struct Analysis {
      cairn::Configuration config;
      cairn::DriveInputs drive;
      cairn::StabilityOptions options;
      int tick;
      bool judged;
    };
    std::vector<Analysis> path;
    cairn::SimulationOptions so;
    so.continue_after_failure = true;
    so.on_analysis = [&](const cairn::AnalysisInputs& in) {
      if (in.judged && std::find(opt.ticks.begin(), opt.ticks.end(), in.tick) != opt.ticks.end())
        path.push_back({*in.config, *in.drive, *in.options, in.tick, in.judged});
    };
    cairn::SimulatePlan(jenga, plan, so);
    for (const Analysis& an : path)
      Components("jenga/tick-" + std::to_string(an.tick), jenga, an.config, opt, an.options,
                 &an.drive);
  }
  Compas("crossvault", "compas_assembly/crossvault_assembly.json", 0.84, false, {}, opt);
  Compas("shelf", "compas_cra/shelf.json", 0.84, false, {"0"}, opt);
  Compas("shelf-s1", "compas_cra/shelf-s1.json", 0.84, false, {"0"}, opt);
  Compas("shelf-s2", "compas_cra/shelf-s2.json", 0.84, false, {"0"}, opt);
  Compas("shelf-s3", "compas_cra/shelf-s3.json", 0.84, false, {"0"}, opt);
  Compas("shelf-stable", "compas_cra/shelf-stable.json", 0.28, false, {"0"}, opt);
  Compas("snake", "compas_cra/snake.json", 0.48, false, {"0"}, opt);
  Compas("bridge", "compas_cra/bridge.json", 0.07, false, {"0", "1"}, opt);
  Compas("cube-curve-short", "compas_cra/cube-curve-short.json", 0.84, false, {"0"}, opt);
  Compas("armadillo", "compas_cra/armadillo_cra.json", 0.84, true, {}, opt);
  return 0;
}

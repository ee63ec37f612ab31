// LCP benchmark: Cairn's SolveLemke against Siconos' lcp_lexicolemke (the
// SICONOS_LCP_LEMKE solver) on the same problems in the same run.
//
// Cases:
//   RandomPsd/n     M = BᵀB with B uniform in [−1, 1] (seeded), q uniform in
//                   [−1, 1]; n = 50, 100, 200, 400.
//   Fc2d/<name>     the 2-D friction-contact LCPs shared/lcp_data/plain/fc2d_*
//                   (skipped when the shared data is absent).
//   Scene/<example>[-without-X]/<k>  the LCP of component k of a bundled
//                   example scene (examples/*.json), as `cairn check` builds it.
//   WarmStart/200   a RandomPsd problem re-solved after a 1e-6 perturbation of
//                   q, cold (no basis) vs warm (the previous basis).
//   Wall/<c>x<b>    the Stewart–Trinkle LCP of a running-bond wall of c
//                   courses of b bricks at rest (one component, redundant
//                   contacts): dense SolveLemke and Siconos on the dense M,
//                   CairnFactored/ SolveLemkeFactored on G W Gᵀ + K.
// Counters: n, pivots (Siconos: iterations + 1 on success, as the shared
// README counts them), residual max_i |min(z_i, w_i)|, ok (1 when solved).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cairn/io/scene_reader.h"
#include "cairn/lcp/factored_lcp.h"
#include "cairn/lcp/lcp_io.h"
#include "cairn/lcp/lemke.h"
#include "cairn/stability/analyze.h"
#include "scene_builders.h"

#if defined(CAIRN_HAVE_SICONOS)
#include "LCP_Solvers.h"
#include "LinearComplementarityProblem.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "lcp_cst.h"
#endif

namespace {

using cairn::LcpProblem;
using cairn::MatrixX;
using cairn::VectorX;

// A seeded random PSD problem: M = BᵀB, q uniform in [−1, 1].
LcpProblem RandomPsd(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixX B(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) B(i, j) = u(rng);
  }
  LcpProblem p;
  p.M = B.transpose() * B;
  p.q.resize(n);
  for (int i = 0; i < n; ++i) p.q[i] = u(rng);
  return p;
}

void SetCounters(benchmark::State& state, const LcpProblem& p, int pivots, const VectorX& z,
                 bool ok) {
  state.counters["n"] = static_cast<double>(p.q.size());
  state.counters["pivots"] = pivots;
  state.counters["residual"] = cairn::LcpResidual(p.M, p.q, z);
  state.counters["ok"] = ok ? 1 : 0;
}

void BM_Cairn(benchmark::State& state, const LcpProblem& p) {
  cairn::LcpResult r;
  for (auto _ : state) {
    r = cairn::SolveLemke(p.M, p.q);
    benchmark::DoNotOptimize(r.z.data());
  }
  const bool ok = r.status == cairn::LcpStatus::kSolved || r.status == cairn::LcpStatus::kTrivial;
  SetCounters(state, p, r.pivots, r.z, ok);
}

// Lemke on the factored matrix (the dense p.M is used only for the counters).
void BM_CairnFactored(benchmark::State& state, const cairn::FactoredLcpMatrix& F,
                      const LcpProblem& p) {
  cairn::LcpResult r;
  for (auto _ : state) {
    r = cairn::SolveLemkeFactored(F, p.q);
    benchmark::DoNotOptimize(r.z.data());
  }
  const bool ok = r.status == cairn::LcpStatus::kSolved || r.status == cairn::LcpStatus::kTrivial;
  SetCounters(state, p, r.pivots, r.z, ok);
}

#if defined(CAIRN_HAVE_SICONOS)
// Siconos' Lemke with lexicographic ratio test on dense M (its own tableau is
// built inside lcp_lexicolemke, so that is timed; the NumericsMatrix copy of
// M is made once, outside the loop).
void BM_Siconos(benchmark::State& state, const LcpProblem& p) {
  const int n = static_cast<int>(p.q.size());
  NumericsMatrix* M = NM_create(NM_DENSE, n, n);
  std::copy(p.M.data(), p.M.data() + p.M.size(), M->matrix0);  // Both column-major.
  VectorX q = p.q;
  LinearComplementarityProblem problem;
  problem.size = n;
  problem.M = M;
  problem.q = q.data();
  SolverOptions* options = solver_options_create(SICONOS_LCP_LEMKE);
  options->iparam[SICONOS_IPARAM_MAX_ITER] = 100000;
  VectorX z = VectorX::Zero(n), w = VectorX::Zero(n);
  int info = 0;
  for (auto _ : state) {
    lcp_lexicolemke(&problem, z.data(), w.data(), &info, options);
    benchmark::DoNotOptimize(z.data());
  }
  const int iterations = options->iparam[SICONOS_IPARAM_ITER_DONE];
  SetCounters(state, p, info == 0 ? iterations + 1 : iterations, z, info == 0);
  solver_options_delete(options);
  NM_free(M);
}
#endif

// Warm start: re-solve a perturbed q from the basis of the unperturbed solve.
void BM_WarmStart(benchmark::State& state, const LcpProblem& p, bool warm) {
  const cairn::LcpResult first = cairn::SolveLemke(p.M, p.q);
  LcpProblem perturbed = p;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e-6, 1e-6);
  for (Eigen::Index i = 0; i < perturbed.q.size(); ++i) perturbed.q[i] += u(rng);
  cairn::LcpResult r;
  for (auto _ : state) {
    r = cairn::SolveLemke(perturbed.M, perturbed.q, {}, warm ? &first.basis : nullptr);
    benchmark::DoNotOptimize(r.z.data());
  }
  SetCounters(state, perturbed, r.pivots, r.z, r.status == cairn::LcpStatus::kSolved);
  state.counters["warm_used"] = r.warm_start_used ? 1 : 0;
}

// Registers one problem for both solvers, Cairn first.
void RegisterPair(const std::string& name, const LcpProblem& p) {
  benchmark::RegisterBenchmark(("Cairn/" + name).c_str(), BM_Cairn, p)
      ->Unit(benchmark::kMicrosecond);
#if defined(CAIRN_HAVE_SICONOS)
  benchmark::RegisterBenchmark(("Siconos/" + name).c_str(), BM_Siconos, p)
      ->Unit(benchmark::kMicrosecond);
#endif
}

}  // namespace

int main(int argc, char** argv) {
#if !defined(CAIRN_HAVE_SICONOS)
  std::fprintf(stderr, "lcp_bench: built without Siconos; only Cairn is measured\n");
#endif
  for (int n : {50, 100, 200, 400}) {
    RegisterPair("RandomPsd/" + std::to_string(n), RandomPsd(n, 1000u + static_cast<unsigned>(n)));
  }
  // The friction-contact LCPs of the shared data, smallest first.
  const std::filesystem::path plain = std::filesystem::path(CAIRN_SHARED_DIR) / "lcp_data/plain";
  if (std::filesystem::is_directory(plain)) {
    std::vector<std::pair<Eigen::Index, std::filesystem::path>> files;
    for (const auto& entry : std::filesystem::directory_iterator(plain)) {
      const std::string file = entry.path().filename().string();
      if (file.rfind("fc2d_", 0) != 0) continue;
      files.emplace_back(cairn::ReadLcpPlain(entry.path().string()).q.size(), entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& [n, path] : files) {
      RegisterPair("Fc2d/" + path.stem().string().substr(5), cairn::ReadLcpPlain(path.string()));
    }
  } else {
    std::fprintf(stderr, "lcp_bench: %s not found, skipping the fc2d cases\n",
                 plain.string().c_str());
  }
  // The LCPs of the bundled example scenes (small: one per contact component).
  const std::vector<std::pair<std::string, std::string>> scenes = {
      {"incline.json", ""},    {"incline_slides.json", ""}, {"ladder.json", ""},
      {"stack3.json", ""},     {"paper_fig1.json", ""},     {"paper_fig1.json", "C"},
      {"paper_fig4.json", ""}, {"paper_fig4.json", "A"},    {"overhang_tips.json", ""}};
  for (const auto& [file, without] : scenes) {
    const cairn::Assembly assembly =
        cairn::ReadScene(std::string(CAIRN_SOURCE_DIR) + "/examples/" + file);
    cairn::Configuration config = cairn::Configuration::Assembled(assembly);
    if (!without.empty()) config.present[assembly.FindPart(without)] = false;
    const auto lcps = cairn::BuildComponentLcps(assembly, config);
    std::string name = "Scene/" + file.substr(0, file.size() - 5);
    if (!without.empty()) name += "-without-" + without;
    for (size_t k = 0; k < lcps.size(); ++k) {
      if (lcps[k].size() == 0) continue;
      const MatrixX M = lcps[k].has_dense() ? lcps[k].M : lcps[k].factored.ToDense();
      RegisterPair(name + "/" + std::to_string(k), LcpProblem{M, lcps[k].q});
    }
  }

  // Running-bond walls: dense against factored on the same LCP.
  static std::vector<cairn::FactoredLcpMatrix> wall_matrices;
  wall_matrices.reserve(8);
  for (const auto& [courses, bricks] :
       std::vector<std::pair<int, int>>{{2, 3}, {3, 5}, {6, 5}, {10, 5}, {10, 10}}) {
    const cairn::Assembly wall =
        cairn::Assembly::Create(cairn::testing::RunningBondWall(courses, bricks), "wall");
    cairn::StabilityOptions options;
    options.lcp_storage = cairn::LcpStorage::kBoth;
    const auto lcps =
        cairn::BuildComponentLcps(wall, cairn::Configuration::Assembled(wall), options);
    const std::string name = "Wall/" + std::to_string(courses) + "x" + std::to_string(bricks);
    const LcpProblem p{lcps[0].M, lcps[0].q};
    RegisterPair(name, p);
    wall_matrices.push_back(lcps[0].factored);
    benchmark::RegisterBenchmark(("CairnFactored/" + name).c_str(), BM_CairnFactored,
                                 wall_matrices.back(), p)
        ->Unit(benchmark::kMicrosecond);
  }

  const LcpProblem warm_problem = RandomPsd(200, 4242u);
  benchmark::RegisterBenchmark("Cairn/ColdStart/200", BM_WarmStart, warm_problem, false)
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("Cairn/WarmStart/200", BM_WarmStart, warm_problem, true)
      ->Unit(benchmark::kMicrosecond);

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// The friction deficit LP φ(k) of the Armadillo vault (mechanics/margin_lp.h)
// at a row of friction factors: its value, slope, solver, time, and whether
// its dual motion is a mechanism where it fails.
//   build/bench/margin_bench [SHARED_DATASETS_DIR] [k ...]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cairn/io/compas_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/mechanics/margin_lp.h"
#include "cairn/stability/analyze.h"

namespace {

// Milliseconds since t0.
double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// `--tilt SCENE AX AY AZ`: each LP of the tilt margin about that axis, timed.
int TiltPieces(int argc, char** argv) {
  using namespace cairn;
  if (argc < 6) return 2;

  const Assembly a = ReadScene(argv[2]);
  const auto lcps = BuildComponentLcps(a, Configuration::Assembled(a));
  for (const auto& lcp : lcps) {
    std::vector<Vector6> F0, F1;
    Vector3 g = a.gravity();
    Vector3 ax(std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]));
    for (const auto& b : lcp.bodies) {
      F0.push_back(b.F_ext);
      Vector6 w = Vector6::Zero();
      w.head<3>() = -b.mass * ax.cross(g);
      F1.push_back(w);
    }
    int ng = 0;
    for (int f : lcp.friction_of) ng += f < 0 ? 1 : lcp.num_directions;
    std::printf("bodies %zu contacts %zu generators %d\n", lcp.bodies.size(), lcp.contacts.size(),
                ng);
    for (int rep = 0; rep < 2; ++rep) {
      auto t0 = std::chrono::steady_clock::now();
      auto e = FindStaticEquilibrium(lcp);
      std::printf("equilibrium %s %.1f ms\n", e.method, Since(t0));
      t0 = std::chrono::steady_clock::now();
      e = FindStaticEquilibrium(WithLoads(lcp, F1));
      std::printf("carried F1 %d %s %.1f ms\n", e.exists, e.method, Since(t0));
      t0 = std::chrono::steady_clock::now();
      auto r = OptimizeLoadParameter(lcp, F1, true, -1e300, false);
      std::printf("max t %g %s %d it %.1f ms\n", r.value, r.method, r.iterations, Since(t0));
      t0 = std::chrono::steady_clock::now();
      std::vector<Vector6> past(F0);
      for (size_t b = 0; b < past.size(); ++b) past[b] = F0[b] + r.value * 1.001 * F1[b];
      auto m = FindMechanism(WithLoads(lcp, past));
      std::printf("mechanism %d %.1f ms\n", m.found, Since(t0));
      t0 = std::chrono::steady_clock::now();
      e = FindStaticEquilibrium(lcp, {.frictionless = true});
      std::printf("frictionless %d %s %.1f ms\n", e.exists, e.method, Since(t0));
      t0 = std::chrono::steady_clock::now();
      r = OptimizeLoadParameter(lcp, F1, true, -1e300, true);
      std::printf("frictionless max t %g %s %.1f ms\n", r.value, r.method, Since(t0));
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--tilt") return TiltPieces(argc, argv);
  const std::string data = argc > 1 ? argv[1] : std::string(CAIRN_SHARED_DIR) + "/datasets";
  std::vector<double> ks;
  for (int i = 2; i < argc; ++i) ks.push_back(std::atof(argv[i]));
  if (ks.empty()) ks = {0.0, 0.1, 0.2, 0.21, 0.214, 0.2147, 0.2148, 0.22, 0.3, 0.84};
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  const std::string path = data + "/compas_cra/armadillo_cra.json";
  if (!std::filesystem::exists(path)) {
    std::printf("%s: not found, skipped\n", path.c_str());
    return 0;
  }
  cairn::CompasOptions opt;
  opt.friction = 1.0;
  opt.stored_interfaces = true;
  const cairn::Assembly a = cairn::ReadCompasScene(path, opt);
  const auto lcps = cairn::BuildComponentLcps(a, cairn::Configuration::Assembled(a));
  for (const cairn::ContactLcp& lcp : lcps) {
    if (lcp.contacts.size() < 100) continue;
    cairn::FrictionDeficitLp deficit(lcp);
    for (double k : ks) {
      const auto t0 = std::chrono::steady_clock::now();
      const cairn::FrictionDeficit d = deficit.Solve(k);
      const double t = Since(t0);
      // Where it fails: does the LP's dual motion pass the mechanism check?
      const char* dual = "";
      if (d.solved && !d.exists && !d.motion.empty())
        dual = cairn::VerifyMechanism(cairn::WithFrictionFactor(lcp, k), d.motion).found
                   ? "dual: mechanism"
                   : "dual: no mechanism";
      std::printf("k %.6f: phi %.3e slope %.4e %s %s %5d it %.1f ms %s\n", k, d.deficit, d.slope,
                  d.solved ? (d.exists ? "stands" : "-") : "FAILED", d.method, d.iterations, t,
                  dual);
    }
  }
}

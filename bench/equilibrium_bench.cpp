// The static-equilibrium LPs of the shared COMPAS vaults and of Jenga, timed
// component by component: the equilibrium (generator form; barrier or dual
// simplex by size), the frictionless equilibrium (the strong-stability
// certificate) and the mechanism LP. Reports solver, iterations and time.
//   build-bench/bench/equilibrium_bench [SHARED_DATASETS_DIR]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cairn/io/compas_reader.h"
#include "cairn/io/scene_reader.h"
#include "cairn/mechanics/static_equilibrium.h"
#include "cairn/stability/analyze.h"

namespace {

double Since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void Run(const std::string& label, const cairn::Assembly& a) {
  cairn::StabilityOptions o;
  o.lcp_storage = cairn::LcpStorage::kFactored;
  auto t0 = std::chrono::steady_clock::now();
  const auto lcps = cairn::BuildComponentLcps(a, cairn::Configuration::Assembled(a), o);
  const double build = Since(t0);
  for (size_t i = 0; i < lcps.size(); ++i) {
    const cairn::ContactLcp& lcp = lcps[i];
    if (lcp.contacts.empty()) continue;
    t0 = std::chrono::steady_clock::now();
    const auto eq = cairn::FindStaticEquilibrium(lcp);
    const double t_eq = Since(t0);
    t0 = std::chrono::steady_clock::now();
    const auto fl = cairn::FindStaticEquilibrium(lcp, {.frictionless = true});
    const double t_fl = Since(t0);
    std::printf(
        "%-22s comp %2zu: %4zu bodies %5zu contacts | equilibrium %-3s %-14s %6d it %7.3f s"
        " | frictionless %-3s %-14s %6d it %7.3f s",
        label.c_str(), i, lcp.bodies.size(), lcp.contacts.size(),
        eq.solved ? (eq.exists ? "yes" : "no") : "?", eq.method, eq.iterations, t_eq,
        fl.solved ? (fl.exists ? "yes" : "no") : "?", fl.method, fl.iterations, t_fl);
    if (eq.solved && !eq.exists) {
      t0 = std::chrono::steady_clock::now();
      const auto m = cairn::FindMechanism(lcp);
      std::printf(" | mechanism %s, %zu bodies, %.3f s", m.found ? "found" : "none",
                  m.moving.size(), Since(t0));
    }
    std::printf(" (LCP build %.3f s)\n", build);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : std::string(CAIRN_SHARED_DIR) + "/datasets";
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  Run("jenga", cairn::ReadScene(std::string(CAIRN_SOURCE_DIR) + "/examples/jenga.json"));
  struct Case {
    const char* file;
    double mu;
    bool stored;
    std::vector<std::string> supports;
  };
  const std::vector<Case> cases = {
      {"compas_assembly/crossvault_assembly.json", 0.84, false, {}},
      {"compas_cra/armadillo_cra.json", 0.84, true, {}},
      {"compas_assembly/crossvault_assembly.json", 0.3, false, {}},
      {"compas_cra/armadillo_cra.json", 0.1, true, {}},
      {"compas_cra/shelf.json", 0.84, false, {"0"}},
      {"compas_cra/shelf-s1.json", 0.84, false, {"0"}},
      {"compas_cra/H.json", 0.84, false, {"0", "1"}},
  };
  for (const Case& c : cases) {
    const std::string path = data + "/" + c.file;
    if (!std::filesystem::exists(path)) {
      std::printf("%s: not found, skipped\n", path.c_str());
      continue;
    }
    cairn::CompasOptions opt;
    opt.friction = c.mu;
    opt.stored_interfaces = c.stored;
    cairn::CompasAssembly ca = cairn::ReadCompasAssembly(path);
    for (auto& b : ca.blocks)
      for (const auto& s : c.supports)
        if (b.name == s) b.is_support = true;
    const cairn::CompasModel model = cairn::CompasToModel(ca, opt, path);
    Run(std::filesystem::path(c.file).filename().string(),
        cairn::CreateCompasAssembly(model, path));
  }
}

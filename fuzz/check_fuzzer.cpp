// Fuzz target: the whole check behind the readers on small scenes: read →
// contacts → the solve policy (equilibrium LP, LCP) → the verdict. Every
// scene that reads must get a verdict: "solver failure" is a finding (the
// solve policy promises an answer), and so is any exception.
#include <cstdlib>

#include "cairn/io/scene_reader.h"
#include "cairn/stability/analyze.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return cairn::fuzz::Run("check_fuzzer", [&] {
    const cairn::Assembly a = cairn::ReadScene(cairn::fuzz::AsFile(data, size, ".scene.json"));
    // Small scenes only: the target is the numerics' robustness, not speed.
    if (a.num_parts() > 12) return;
    int vertices = 0;
    for (int i = 0; i < a.num_parts(); ++i) vertices += static_cast<int>(a.part(i).vertices.size());
    if (vertices > 200) return;
    const cairn::StabilityResult r =
        cairn::AnalyzeConfiguration(a, cairn::Configuration::Assembled(a), {});
    if (r.verdict == cairn::Verdict::kSolverFailure) {
      std::fprintf(stderr, "check_fuzzer: undecided: %s\n", r.diagnostics.c_str());
      std::abort();
    }
  });
}

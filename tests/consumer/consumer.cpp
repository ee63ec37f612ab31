// A user's program against the installed library: reads the paper's Fig. 1
// scene, checks it whole (it stands) and without C (B falls: the paper's
// Section II example). Exit 0 when both verdicts are right.
#include <cstdio>
#include <string>

#include "cairn/io/scene_reader.h"
#include "cairn/stability/analyze.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer paper_fig1.json\n");
    return 2;
  }
  const cairn::Assembly assembly = cairn::ReadScene(argv[1]);
  cairn::Configuration config = cairn::Configuration::Assembled(assembly);
  const cairn::StabilityResult whole = cairn::AnalyzeConfiguration(assembly, config);
  config.present[assembly.FindPart("C")] = false;
  const cairn::StabilityResult without_c = cairn::AnalyzeConfiguration(assembly, config);
  std::printf("whole: %s, without C: %s\n", whole.stable() ? "stable" : "unstable",
              without_c.stable() ? "stable" : "unstable");
  return whole.stable() && !without_c.stable() ? 0 : 1;
}

// Fuzz target: the candidate-paths reader (`cairn plan --paths`) against
// paper Fig. 6.
#include "cairn/io/paths_reader.h"
#include "cairn/io/scene_reader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const cairn::Assembly fig6 =
      cairn::ReadScene(CAIRN_SOURCE_DIR "/examples/paper_fig6.json");
  return cairn::fuzz::Run("paths_fuzzer", [&] {
    (void)cairn::ReadCandidatePaths(cairn::fuzz::AsFile(data, size, ".paths.json"), fig6);
  });
}

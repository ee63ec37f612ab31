// Fuzz target: the plan reader and Plan::Create against fixed scenes (paper
// Fig. 1 in 2-D, Fig. 9 in 3-D; the first byte picks one).
#include "cairn/io/plan_reader.h"
#include "cairn/io/scene_reader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const cairn::Assembly fig1 =
      cairn::ReadScene(CAIRN_SOURCE_DIR "/examples/paper_fig1.json");
  static const cairn::Assembly fig9 =
      cairn::ReadScene(CAIRN_SOURCE_DIR "/examples/paper_fig9.json");
  if (size == 0) return 0;
  const cairn::Assembly& scene = data[0] % 2 ? fig9 : fig1;
  return cairn::fuzz::Run("plan_fuzzer", [&] {
    (void)cairn::ReadPlan(cairn::fuzz::AsFile(data + 1, size - 1, ".plan.json"), scene);
  });
}

// Fuzz target: the scene reader and the model's validation (ReadScene:
// JSON syntax, keys, types, ranges, shapes, overlaps, fixtures, interfaces).
#include "cairn/io/scene_reader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return cairn::fuzz::Run("scene_fuzzer", [&] {
    (void)cairn::ReadScene(cairn::fuzz::AsFile(data, size, ".scene.json"));
  });
}

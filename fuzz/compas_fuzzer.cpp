// Fuzz target: the COMPAS reader and its conversion to a model (both ways of
// taking the contacts: found from the shapes, or the stored interfaces).
#include "cairn/io/compas_reader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return cairn::fuzz::Run("compas_fuzzer", [&] {
    const std::string path = cairn::fuzz::AsFile(data, size, ".compas.json");
    cairn::CompasOptions options;
    options.friction = 0.5;
    options.stored_interfaces = size % 2 == 1;
    (void)cairn::ReadCompasScene(path, options);
  });
}

// Fuzz target: mesh parts (Assimp's OBJ and STL readers, then Cairn's merge
// of coplanar triangles into faces and the polyhedron's validation). The
// first byte picks the format.
#include "cairn/geometry/polyhedron.h"
#include "cairn/io/mesh_reader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const char* suffix = data[0] % 2 ? ".stl" : ".obj";
  return cairn::fuzz::Run("mesh_fuzzer", [&] {
    const cairn::PolyhedronDef def =
        cairn::ReadMesh(cairn::fuzz::AsFile(data + 1, size - 1, suffix));
    (void)cairn::Polyhedron::Check(def, 1e-6);
  });
}

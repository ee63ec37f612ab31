// Fuzz target: `cairn margin` behind the scene reader, on small scenes. The
// input's last byte picks the margin (critical friction; tilt about z, x or an
// oblique axis; a load on the first movable part at its centroid along a
// direction) and the rest is the scene file. Every scene that reads must get
// a margin: an LP that fails (MarginResult::solved false, the CLI's exit 4)
// is a finding, and so is any exception but an InputError.
#include <cstdlib>

#include "cairn/geometry/assembly.h"
#include "cairn/io/scene_reader.h"
#include "cairn/stability/margin.h"
#include "fuzz_input.h"

namespace {

// The margin asked for: one of seven, by `selector`.
cairn::MarginRequest RequestOf(const cairn::Assembly& a, uint8_t selector) {
  cairn::MarginRequest r;
  switch (selector % 7) {
    case 0:
    case 1:
      r.quantity = cairn::MarginQuantity::kFriction;
      break;
    case 2:
      r.quantity = cairn::MarginQuantity::kTilt;
      r.axis = {0, 0, 1};
      break;
    case 3:
      r.quantity = cairn::MarginQuantity::kTilt;
      r.axis = a.is_3d() ? cairn::Vector3(1, 0, 0) : cairn::Vector3(0, 0, -1);
      break;
    case 4:
      r.quantity = cairn::MarginQuantity::kTilt;
      r.axis = a.is_3d() ? cairn::Vector3(1, 2, 3) : cairn::Vector3(0, 0, 1);
      break;
    default:
      r.quantity = cairn::MarginQuantity::kLoad;
      for (int i = 0; i < a.num_parts() && r.part < 0; ++i)
        if (!a.part(i).fixed) r.part = i;
      if (r.part < 0) {
        r.quantity = cairn::MarginQuantity::kFriction;
        break;
      }
      r.point = a.part(r.part).centroid;
      r.direction = selector % 7 == 5 ? cairn::Vector3(1, 0, 0) : cairn::Vector3(-1, 1, 0);
      break;
  }
  return r;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  return cairn::fuzz::Run("margin_fuzzer", [&] {
    const cairn::AssemblyDef def =
        cairn::ReadSceneDef(cairn::fuzz::AsFile(data, size - 1, ".scene.json"));
    const cairn::Assembly a = cairn::Assembly::Create(def);
    // Small scenes only: the target is the LPs' robustness, not speed.
    if (a.num_parts() > 12) return;
    int vertices = 0;
    for (int i = 0; i < a.num_parts(); ++i) vertices += static_cast<int>(a.part(i).vertices.size());
    if (vertices > 200) return;
    const cairn::MarginRequest request = RequestOf(a, data[size - 1]);
    const cairn::MarginResult r =
        cairn::ComputeMargin(def, a, cairn::Configuration::Assembled(a), request);
    if (!r.solved) {
      std::fprintf(stderr, "margin_fuzzer: %s margin failed: %s\n", cairn::to_string(r.quantity),
                   r.message.c_str());
      std::abort();
    }
  });
}

#pragma once
// A static check that also decides whether a static equilibrium exists
// (StabilityOptions::check_equilibrium): the tests of the equilibrium LP
// (tests/mechanics) and of the proof of rest (tests/stability) use it.
#include "cairn/geometry/assembly.h"
#include "cairn/stability/analyze.h"

namespace cairn::testing {

inline StabilityResult CheckWithEquilibrium(const AssemblyDef& def) {
  const Assembly a = Assembly::Create(def, "test");
  StabilityOptions options;
  options.check_equilibrium = true;
  return AnalyzeConfiguration(a, Configuration::Assembled(a), options);
}

}  // namespace cairn::testing

#pragma once
// A bundled example scene read as a user's file: its definition (which the
// fixture search and the planner add to) and the validated Assembly.
#include <string>

#include "cairn/geometry/assembly.h"
#include "cairn/io/scene_reader.h"
#include "test_paths.h"

namespace cairn::testing {

struct ExampleScene {
  AssemblyDef def;
  Assembly assembly;
  explicit ExampleScene(const std::string& name)
      : def(ReadSceneDef(ExamplePath(name))), assembly(Assembly::Create(def, name)) {}
  /// The index of the part `name`, or −1.
  int Part(const std::string& name) const { return assembly.FindPart(name); }
};

}  // namespace cairn::testing

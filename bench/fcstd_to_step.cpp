// A FreeCAD A2plus assembly as a STEP assembly, for the STEP benchmarks
// (bench/truck_blocking.sh): each part's shape, as FreeCAD stores it in the
// .FCStd (a BREP file placed by its location), becomes one named instance of
// an XCAF document written by OpenCASCADE's STEP writer, as
// tests/step_writer.h writes the tests' files.
// Usage: fcstd_to_step PARTS OUT.step, PARTS a file of lines "label brep-file"
// (paths relative to PARTS' folder), as bench/truck_blocking.sh extracts them.
#include <BRepTools.hxx>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "step_writer.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: fcstd_to_step PARTS OUT.step\n";
    return 2;
  }
  const std::filesystem::path list(argv[1]);
  std::ifstream in(list);
  if (!in) {
    std::cerr << "fcstd_to_step: cannot read " << list << "\n";
    return 2;
  }
  std::vector<cairn::testing::StepInstance> parts;
  std::string label, file;
  while (in >> label >> file) {
    TopoDS_Shape shape;
    BRep_Builder builder;
    const std::string path = (list.parent_path() / file).string();
    if (!BRepTools::Read(shape, path.c_str(), builder)) {
      std::cerr << "fcstd_to_step: " << path << ": not a BREP file OpenCASCADE reads\n";
      return 2;
    }
    // FreeCAD stores a part's placement as its shape's location: the
    // product is the shape in its own frame, the instance places it.
    parts.push_back({label, shape.Located(TopLoc_Location()), shape.Location().Transformation()});
  }
  if (!cairn::testing::WriteStepAssembly(argv[2], list.stem().string(), parts)) {
    std::cerr << "fcstd_to_step: cannot write " << argv[2] << "\n";
    return 1;
  }
  std::cout << parts.size() << " parts written to " << argv[2] << "\n";
  return 0;
}

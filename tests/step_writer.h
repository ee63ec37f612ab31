#pragma once
// STEP files written by OpenCASCADE itself, for the tests of --format step
// (tests/io/step_reader_test.cpp, tests/cli/step_command_test.cpp): an XCAF
// document with named products and instances, written by
// STEPCAFControl_Writer, as a CAD system would export it.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Writer.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <cmath>
#include <gp_Trsf.hxx>
#include <string>
#include <vector>

// LeakSanitizer: OpenCASCADE keeps the tables of its STEP session to the end
// of the process, and its writer leaks each direction's coordinates (as
// cairn-step-reader suppresses for reading, src/io/step/occt_reader.cpp), in
// the test binaries that write STEP files.
#if defined(__SANITIZE_ADDRESS__)
extern "C" __attribute__((weak)) const char* __lsan_default_suppressions() {
  return "leak:IFSelect_Editor::IFSelect_Editor\n"
         "leak:TPrsStd_DriverTable::Get\n"
         "leak:Standard_MMgrRaw::Allocate\n"
         "leak:Standard_MMgrRaw::Reallocate\n"
         "leak:GeomToStep_MakeDirection::GeomToStep_MakeDirection\n";
}
extern "C" __attribute__((weak)) const char* __lsan_default_options() {
  return "print_suppressions=0";
}
#endif

namespace cairn::testing {

inline void QuietOcct() {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
}

/// One component of a written assembly: a product (its shape and name) placed
/// by a location, possibly inside a sub-assembly.
struct StepInstance {
  std::string product;
  TopoDS_Shape shape;  // the product's shape, in its own frame (mm)
  gp_Trsf place;       // where the instance puts it
};

/// Writes an assembly named `name` of the instances (products with the same
/// name share one XCAF label, so a product used twice is one product with two
/// instances), the instances of `sub` inside a sub-assembly `sub_name` placed
/// by `sub_place`. Millimetres (OCCT's default). Returns false on failure.
inline bool WriteStepAssembly(const std::string& path, const std::string& name,
                              const std::vector<StepInstance>& top,
                              const std::string& sub_name = "",
                              const std::vector<StepInstance>& sub = {},
                              const gp_Trsf& sub_place = gp_Trsf()) {
  QuietOcct();
  Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
  Handle(TDocStd_Document) doc;
  app->NewDocument("MDTV-XCAF", doc);
  Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  std::vector<std::pair<std::string, TDF_Label>> products;
  const auto product = [&](const StepInstance& in) {
    for (const auto& [n, label] : products)
      if (n == in.product) return label;
    const TDF_Label label = tool->AddShape(in.shape, false);
    TDataStd_Name::Set(label, in.product.c_str());
    products.emplace_back(in.product, label);
    return label;
  };
  const TDF_Label root = tool->NewShape();
  TDataStd_Name::Set(root, name.c_str());
  for (const StepInstance& in : top)
    tool->AddComponent(root, product(in), TopLoc_Location(in.place));
  if (!sub.empty()) {
    const TDF_Label s = tool->NewShape();
    TDataStd_Name::Set(s, sub_name.c_str());
    for (const StepInstance& in : sub)
      tool->AddComponent(s, product(in), TopLoc_Location(in.place));
    tool->AddComponent(root, s, TopLoc_Location(sub_place));
  }
  tool->UpdateAssemblies();
  STEPCAFControl_Writer writer;
  writer.SetNameMode(true);
  const bool ok =
      writer.Transfer(doc, STEPControl_AsIs) && writer.Write(path.c_str()) == IFSelect_RetDone;
  app->Close(doc);
  return ok;
}

/// Writes one bare shape (no assembly structure, no names).
inline bool WriteStepShape(const std::string& path, const TopoDS_Shape& shape) {
  QuietOcct();
  STEPControl_Writer writer;
  return writer.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone &&
         writer.Write(path.c_str()) == IFSelect_RetDone;
}

inline gp_Trsf Translation(double x, double y, double z) {
  gp_Trsf t;
  t.SetTranslation(gp_Vec(x, y, z));
  return t;
}

inline TopoDS_Shape Box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), gp_Pnt(x1, y1, z1)).Shape();
}

/// A cylinder of radius r standing on (x, y, z0), height h, along +z, its
/// parametrisation's origin (its seam) turned by `turn` radians about z.
inline TopoDS_Shape Cylinder(double x, double y, double z0, double r, double h, double turn = 0) {
  const gp_Ax2 axes(gp_Pnt(x, y, z0), gp_Dir(0, 0, 1), gp_Dir(std::cos(turn), std::sin(turn), 0));
  return BRepPrimAPI_MakeCylinder(axes, r, h).Shape();
}

// The test model, in millimetres (the equivalent scene: PegSceneJson, in
// metres): a table; a block on it with a square pocket 20 × 20 × 30 from its
// top; the product `peg` (20 × 20 × 50) used twice, inside a sub-assembly
// `pegs` lifted by 10 mm: standing in the pocket, and lying on the block
// (turned 90° about x).
inline bool WritePegAssembly(const std::string& path) {
  const TopoDS_Shape table = Box(0, 0, -20, 200, 200, 0);
  const TopoDS_Shape block =
      BRepAlgoAPI_Cut(Box(50, 50, 0, 150, 150, 40), Box(65, 90, 10, 85, 110, 41)).Shape();
  const TopoDS_Shape peg = Box(0, 0, 0, 20, 20, 50);
  gp_Trsf lying;  // (0..20, −50..0, 0..20) turned, then to x 100..120, y 90..140, z 40..60
  lying.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)), M_PI / 2);
  lying.SetTranslationPart(gp_Vec(100, 140, 30));  // + the sub-assembly's 10 mm
  return WriteStepAssembly(
      path, "pegs_on_a_table", {{"table", table, gp_Trsf()}, {"block", block, gp_Trsf()}}, "pegs",
      {{"peg", peg, Translation(65, 90, 0)}, {"peg", peg, lying}}, Translation(0, 0, 10));
}

// The same model as a scene file (metres): the block as a polyhedron with its
// pocket.
inline std::string PegSceneJson() {
  return R"({"cairn": 1, "name": "pegs_on_a_table", "parts": [
  {"name": "table", "box": {"min": [0, 0, -0.02], "max": [0.2, 0.2, 0]}},
  {"name": "block", "polyhedron": {
    "vertices": [[0.05,0.05,0],[0.15,0.05,0],[0.15,0.15,0],[0.05,0.15,0],
                 [0.05,0.05,0.04],[0.15,0.05,0.04],[0.15,0.15,0.04],[0.05,0.15,0.04],
                 [0.065,0.09,0.04],[0.085,0.09,0.04],[0.085,0.11,0.04],[0.065,0.11,0.04],
                 [0.065,0.09,0.01],[0.085,0.09,0.01],[0.085,0.11,0.01],[0.065,0.11,0.01]],
    "faces": [[3,2,1,0],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7],
              [4,5,9,8],[5,6,10,9],[6,7,11,10],[7,4,8,11],
              [8,9,13,12],[9,10,14,13],[10,11,15,14],[11,8,12,15],[12,13,14,15]]}},
  {"name": "peg", "box": {"min": [0.065, 0.09, 0.01], "max": [0.085, 0.11, 0.06]}},
  {"name": "peg_2", "box": {"min": [0.1, 0.09, 0.04], "max": [0.12, 0.14, 0.06]}}
]})";
}

}  // namespace cairn::testing

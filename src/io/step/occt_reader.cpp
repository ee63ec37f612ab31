// STEP assemblies through OpenCASCADE's XCAF, in the reading process
// cairn-step-reader (main.cpp beside it): the only code of Cairn that includes
// OpenCASCADE, so that no other process loads its 26 libraries (a tenth of a
// second of every `cairn`'s start, and of every test's, when `cairn_io`
// linked them). Cairn's side is src/io/step_reader.cpp.
//
// ReadInChild, as a table of contents:
//   1. ReadDocument: the text into an XCAF document (names on), its length unit.
//   2. CollectLeaves: the assembly tree walked from the free shapes; each leaf
//      instance with its composed location (world = L_root · ... · L_leaf).
//   3. PartNames: product names, instances of one product numbered.
//   4. OneSolid: each leaf's single solid, closed (no free edge); a closed
//      shell read as the solid it bounds (SolidOfClosedShell).
//   4b. FastenParts, MakePartsTouch: the joins the user asked for, on the
//      exact solids; the common volumes Cairn asked for.
//   5. The chordal tolerance: one for the assembly (step_reader.h).
//   6. ToPolyhedron: exact planar faces and tessellated others, welded, the
//      tessellated triangles merged where coplanar; a solid OpenCASCADE's
//      mesher fails on converted to B-spline surfaces and meshed again.
//   7. The model or the error, serialised (step_codec.h).

#include "io/step/occt_reader.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepGProp.hxx>
#include <BRepLib.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <Precision.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Wire.hxx>  // IWYU pragma: keep
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <new>
#include <set>
#include <sstream>
#include <variant>

#include "cairn/core/error.h"
#include "cairn/core/format.h"
#include "cairn/core/tolerances.h"
#include "cairn/geometry/mesh_faces.h"
#include "cairn/geometry/polyhedron.h"
#include "cairn/io/input_file.h"
#include "io/step_codec.h"

// LeakSanitizer (the CI's sanitized build): OpenCASCADE 7.6 (Debian) keeps
// the tables its STEP session builds once (IFSelect_Editor's, the singleton of
// TPrsStd_DriverTable, and what they hold, allocated by its own allocator) to
// the end of the process without freeing them, which LSan reports as leaks
// (about 3 kB, the same for every file read). Its libraries have no frame
// pointers, so those stacks end in OpenCASCADE's allocator: these frames of
// OpenCASCADE, and nothing of Cairn's, are suppressed, in the binaries that
// read STEP: cairn-step-reader, and the tests that write STEP files
// (tests/step_writer.h).
#if defined(__SANITIZE_ADDRESS__)
#define CAIRN_LSAN_OCCT 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CAIRN_LSAN_OCCT 1
#endif
#endif
#ifdef CAIRN_LSAN_OCCT
extern "C" const char* __lsan_default_suppressions() {
  return "leak:IFSelect_Editor::IFSelect_Editor\n"
         "leak:TPrsStd_DriverTable::Get\n"
         "leak:Standard_MMgrRaw::Allocate\n"
         "leak:Standard_MMgrRaw::Reallocate\n";
}
// ... without the summary of the suppressions used on standard error, which
// is the command's own.
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
#endif

namespace cairn {

namespace {

using step_codec::WriteError;
using step_codec::WriteModel;
using step_codec::Writer;

// The coplanarity tolerances of the merge of tessellated triangles: normals
// within 1e-5 rad, as ReadMesh's (MeshReadOptions); vertices within the
// model's length tolerance of the region's plane (MergeTolerance), with which
// Polyhedron::Check will judge the faces.
constexpr double kMergeAngleTol = 1e-5;
// Welding: positions closer than this fraction of the part's size are one
// vertex (BRepMesh gives the faces of a shared edge the same nodes; this only
// absorbs the last bit of a location's arithmetic).
constexpr double kWeldFactor = 1e-9;
// Deeper assembly trees than this are taken for a cycle in a broken file.
constexpr int kMaxAssemblyDepth = 64;

// OpenCASCADE prints its warnings on stdout; Cairn's output is its own.
void SilenceOcct() {
  static std::once_flag once;
  std::call_once(once, [] {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  });
}

// The XCAF document of one file, closed (its memory released) on scope exit.
class Document {
 public:
  Document() {
    app_ = XCAFApp_Application::GetApplication();
    app_->NewDocument("MDTV-XCAF", doc_);
  }
  ~Document() {
    if (!doc_.IsNull() && doc_->IsOpened()) app_->Close(doc_);
  }
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;
  Handle(TDocStd_Document) doc() const { return doc_; }

 private:
  Handle(XCAFApp_Application) app_;
  Handle(TDocStd_Document) doc_;
};

// 1. The file's `text` into `doc`; returns the length unit of the shapes in
// metres.
double ReadDocument(const std::string& path, const std::string& text, Document& document) {
  STEPCAFControl_Reader reader;
  reader.SetNameMode(true);
  reader.SetColorMode(false);
  reader.SetLayerMode(false);
  reader.SetPropsMode(false);
  std::istringstream stream(text);
  if (reader.ChangeReader().ReadStream(path.c_str(), stream) != IFSelect_RetDone)
    throw InputError(path, "", "not a STEP file (OpenCASCADE cannot read it)");
  Handle(TDocStd_Document) doc = document.doc();
  if (!reader.Transfer(doc))
    throw InputError(path, "", "the STEP file's shapes cannot be transferred (no solids?)");
  // The reader converts the file's unit to the document's, which it records
  // (OCCT 7.6: millimetres unless the document says otherwise).
  double unit = 0.001;
  if (!XCAFDoc_DocumentTool::GetLengthUnit(document.doc(), unit) || !(unit > 0)) unit = 0.001;
  return unit;
}

// A label's TDataStd_Name as UTF-8; empty when it has none.
std::string LabelName(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return "";
  const TCollection_ExtendedString& s = name->Get();
  std::string out(static_cast<size_t>(s.LengthOfCString()) + 1, '\0');
  char* buf = out.data();
  const int n = s.ToUTF8CString(buf);
  out.resize(static_cast<size_t>(std::max(n, 0)));
  return out;
}

// One leaf instance: its product's name, its instance's name, its shape placed
// in the world (the file's unit).
struct Leaf {
  std::string product;
  std::string instance;
  TopoDS_Shape shape;
};

// 2. The leaves under `label`, placed by `loc` (the composed locations of
// the instances above).
void CollectLeaves(const Handle(XCAFDoc_ShapeTool) & tool, const TDF_Label& label,
                   const TopLoc_Location& loc, const std::string& instance, int depth,
                   const std::string& path, std::vector<Leaf>& out) {
  if (depth > kMaxAssemblyDepth)
    throw InputError(path, "",
                     "the assembly tree is deeper than " + std::to_string(kMaxAssemblyDepth) +
                         " levels (a cycle?)");
  if (XCAFDoc_ShapeTool::IsAssembly(label)) {
    TDF_LabelSequence components;
    XCAFDoc_ShapeTool::GetComponents(label, components, false);
    for (int k = 1; k <= components.Length(); ++k) {
      const TDF_Label& component = components.Value(k);
      TDF_Label referred;
      if (!XCAFDoc_ShapeTool::GetReferredShape(component, referred)) continue;
      CollectLeaves(tool, referred, loc * XCAFDoc_ShapeTool::GetLocation(component),
                    LabelName(component), depth + 1, path, out);
    }
    return;
  }
  const TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(label);
  if (shape.IsNull()) return;
  out.push_back({LabelName(label), instance, shape.Moved(loc)});
}

// 3. Part names: the product's name; the instances of a product used several
// times numbered `name`, `name_2`, ... in file order; a product without a
// name takes its instance's, or "part_<k>". Unique in the end.
std::vector<std::string> PartNames(const std::vector<Leaf>& leaves) {
  std::vector<std::string> base(leaves.size());
  std::map<std::string, int> uses;
  for (size_t k = 0; k < leaves.size(); ++k) {
    base[k] = !leaves[k].product.empty()    ? leaves[k].product
              : !leaves[k].instance.empty() ? leaves[k].instance
                                            : "part_" + std::to_string(k + 1);
    ++uses[base[k]];
  }
  std::vector<std::string> names(leaves.size());
  std::map<std::string, int> seen;
  std::map<std::string, bool> taken;
  for (const auto& [name, n] : uses) taken[name] = true;
  for (size_t k = 0; k < leaves.size(); ++k) {
    const int nth = ++seen[base[k]];
    if (nth == 1) {
      names[k] = base[k];
      continue;
    }
    int suffix = nth;
    std::string name = base[k] + "_" + std::to_string(suffix);
    while (taken.count(name)) name = base[k] + "_" + std::to_string(++suffix);
    taken[name] = true;
    names[k] = name;
  }
  return names;
}

// 4a. A leaf without a solid whose faces close into one shell (a part
// modelled as a closed surface): the solid that shell bounds, oriented with
// its material inside; a null solid otherwise. The faces are sewn first
// (within OpenCASCADE's confusion tolerance), so that faces exported one by
// one count as one shell.
TopoDS_Solid SolidOfClosedShell(const TopoDS_Shape& shape) {
  BRepBuilderAPI_Sewing sewing(Precision::Confusion());
  int faces = 0;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next(), ++faces) sewing.Add(e.Current());
  if (faces == 0) return {};
  sewing.Perform();
  std::vector<TopoDS_Shell> shells;
  for (TopExp_Explorer e(sewing.SewedShape(), TopAbs_SHELL); e.More(); e.Next())
    shells.push_back(TopoDS::Shell(e.Current()));
  if (shells.size() != 1 || !BRep_Tool::IsClosed(shells[0])) return {};
  BRepBuilderAPI_MakeSolid make(shells[0]);
  if (!make.IsDone()) return {};
  TopoDS_Solid solid = make.Solid();
  if (!BRepLib::OrientClosedSolid(solid)) return {};
  return solid;
}

// 4. The one solid of a leaf, closed; `note` says so when it was a closed
// shell. @throws InputError naming the part.
TopoDS_Solid OneSolid(const TopoDS_Shape& shape, const std::string& path, const std::string& part,
                      std::string& note) {
  std::vector<TopoDS_Solid> solids;
  for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next())
    solids.push_back(TopoDS::Solid(e.Current()));
  if (solids.empty()) {
    if (const TopoDS_Solid solid = SolidOfClosedShell(shape); !solid.IsNull()) {
      solids.push_back(solid);
      note = "it is a closed shell, not a solid: read as the solid it bounds";
    }
  }
  if (solids.empty())
    throw InputError(path, "",
                     "part '" + part +
                         "' has no solid (a surface model or an open shell): Cairn needs closed "
                         "solids");
  if (solids.size() > 1)
    throw InputError(path, "",
                     "part '" + part + "' has " + std::to_string(solids.size()) +
                         " solids: Cairn takes one solid per part (make each body a part of "
                         "its own in the CAD system)");
  // Closed: every edge (but the degenerate ones, a cone's apex) bounds two
  // faces, or is a seam (one face on both sides).
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndUniqueAncestors(solids[0], TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int free_edges = 0;
  for (int k = 1; k <= edge_faces.Extent(); ++k) {
    const TopoDS_Edge& edge = TopoDS::Edge(edge_faces.FindKey(k));
    if (BRep_Tool::Degenerated(edge)) continue;
    const TopTools_ListOfShape& faces = edge_faces.FindFromIndex(k);
    if (faces.Extent() >= 2) continue;
    if (faces.Extent() == 1 && BRep_Tool::IsClosed(edge, TopoDS::Face(faces.First()))) continue;
    ++free_edges;
  }
  if (free_edges > 0)
    throw InputError(path, "",
                     "part '" + part + "' is not closed: its shell is open (" +
                         std::to_string(free_edges) + " edge" + (free_edges == 1 ? "" : "s") +
                         " bound only one face)");
  return solids[0];
}

// The parts' names, exact solids and notes, as reading and joining them
// leave them (steps 3 to 4b).
struct Solids {
  std::vector<std::string> names;
  std::vector<TopoDS_Solid> solids;
  std::vector<std::string> notes;  // what was done to each, for its report
};

// The index of the part named `name`. @throws InputError naming `option`
// ("" for a request of Cairn's own, where the file is at fault).
size_t FindPart(const Solids& parts, const std::string& name, const std::string& option,
                const std::string& path) {
  const auto it = std::find(parts.names.begin(), parts.names.end(), name);
  if (it != parts.names.end()) return static_cast<size_t>(it - parts.names.begin());
  // A part fastened to others is named by its group ("a+b").
  for (const std::string& group : parts.names)
    if (("+" + group + "+").find("+" + name + "+") != std::string::npos)
      throw InputError("", option,
                       "part '" + EscapedName(name) + "' of " + path + " is fastened into '" +
                           EscapedName(group) + "': give that name");
  throw InputError(
      option.empty() ? path : "", option,
      "no part named '" + EscapedName(name) + "'" + (option.empty() ? "" : " in " + path));
}

// The one solid of a boolean operation's result; a null solid when it has
// none or several.
TopoDS_Solid SingleSolid(const TopoDS_Shape& shape) {
  TopoDS_Solid one;
  int count = 0;
  for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next(), ++count)
    one = TopoDS::Solid(e.Current());
  return count == 1 ? one : TopoDS_Solid();
}

// The volume of a shape (the file's unit, cubed).
double Volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props);
  return std::abs(props.Mass());
}

// 4b. Each group of parts joined by StepReadOptions::fastened (pairs that
// share a part make one group) fused into one solid, where the group's first
// part was, named by the group's names joined with '+'. @throws InputError
// naming --fastened: an unknown name, a part fastened to itself, a group
// whose fusion is not one solid (parts that neither touch nor overlap).
void FastenParts(const std::string& path, const StepReadOptions& options, Solids& parts) {
  if (options.fastened.empty()) return;
  const size_t n = parts.names.size();
  std::vector<size_t> group(n);
  for (size_t k = 0; k < n; ++k) group[k] = k;
  const auto root = [&](size_t k) {
    while (group[k] != k) k = group[k] = group[group[k]];
    return k;
  };
  for (const auto& [a, b] : options.fastened) {
    const size_t ra = root(FindPart(parts, a, "--fastened", path));
    const size_t rb = root(FindPart(parts, b, "--fastened", path));
    if (a == b)
      throw InputError("", "--fastened", "part '" + EscapedName(a) + "' is fastened to itself");
    group[std::max(ra, rb)] = std::min(ra, rb);
  }
  Solids joined;
  for (size_t k = 0; k < n; ++k) {
    if (root(k) != k) continue;  // in the group of an earlier part
    std::vector<size_t> members;
    for (size_t j = k; j < n; ++j)
      if (root(j) == k) members.push_back(j);
    std::string name = parts.names[k], note = parts.notes[k], listed = "'" + parts.names[k] + "'";
    TopoDS_Shape fused = parts.solids[k];
    for (size_t m = 1; m < members.size(); ++m) {
      const size_t j = members[m];
      BRepAlgoAPI_Fuse fuse(fused, parts.solids[j]);
      if (!fuse.IsDone())
        throw InputError("", "--fastened",
                         "OpenCASCADE could not fuse part '" + EscapedName(parts.names[j]) +
                             "' with " + listed + " in " + path);
      fused = fuse.Shape();
      name += "+" + parts.names[j];
      listed += ", '" + EscapedName(parts.names[j]) + "'";
      if (!parts.notes[j].empty()) note += (note.empty() ? "" : "; ") + parts.notes[j];
    }
    const TopoDS_Solid one = SingleSolid(fused);
    if (one.IsNull())
      throw InputError("", "--fastened",
                       "parts " + listed + " of " + path +
                           " fused are not one solid: fastened parts must touch or overlap");
    if (members.size() > 1)
      note = "parts " + listed +
             " fastened (--fastened): one rigid part, their exact solids fused" +
             (note.empty() ? "" : "; " + note);
    joined.names.push_back(name);
    joined.solids.push_back(one);
    joined.notes.push_back(note);
  }
  parts = std::move(joined);
}

// 4b. Each pair (a, b) of StepReadOptions::touching: b's solid less what it
// shares with a's, so that b touches a along a's surface. @throws
// InputError naming --touching: an unknown name, a part made to touch
// itself, a cut that leaves b in pieces or nothing.
void MakePartsTouch(const std::string& path, const StepReadOptions& options, double unit,
                    Solids& parts) {
  for (const auto& [a, b] : options.touching) {
    const size_t ia = FindPart(parts, a, "--touching", path);
    const size_t ib = FindPart(parts, b, "--touching", path);
    if (ia == ib)
      throw InputError("", "--touching", "part '" + EscapedName(a) + "' is paired with itself");
    BRepAlgoAPI_Cut cut(parts.solids[ib], parts.solids[ia]);
    const TopoDS_Solid rest = cut.IsDone() ? SingleSolid(cut.Shape()) : TopoDS_Solid();
    if (rest.IsNull())
      throw InputError("", "--touching",
                       "part '" + EscapedName(b) + "' of " + path + " less what it shares with '" +
                           EscapedName(a) + "' is not one solid: it cannot be made to touch it");
    const double removed = (Volume(parts.solids[ib]) - Volume(rest)) * unit * unit * unit;
    parts.solids[ib] = rest;
    std::string& note = parts.notes[ib];
    note += std::string(note.empty() ? "" : "; ") + "cut by part '" + EscapedName(a) +
            "' where they overlap (--touching): " + FormatNumber(removed) +
            " m^3 less, it touches that part's surface there";
  }
}

// The diagonal of a shape's bounding box (the file's unit).
double Diagonal(const TopoDS_Shape& shape) {
  Bnd_Box box;
  BRepBndLib::AddOptimal(shape, box, false, false);
  if (box.IsVoid()) return 0;
  return std::sqrt(box.SquareExtent());
}

Vector3 ToVector(const gp_Pnt& p, double unit) {
  return Vector3(p.X() * unit, p.Y() * unit, p.Z() * unit);
}

// Welds positions closer than `eps` into one vertex: a hash grid of cell
// `eps`, each point looked up in its cell and the 26 around it.
class Welder {
 public:
  explicit Welder(double eps) : eps_(eps) {}
  int Add(const Vector3& p) {
    const std::array<long long, 3> c = Cell(p);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid_.end()) continue;
          for (const int v : it->second)
            if ((vertices_[v] - p).norm() <= eps_) return v;
        }
    const int v = static_cast<int>(vertices_.size());
    vertices_.push_back(p);
    grid_[c].push_back(v);
    return v;
  }
  const std::vector<Vector3>& vertices() const { return vertices_; }

 private:
  std::array<long long, 3> Cell(const Vector3& p) const {
    return {static_cast<long long>(std::floor(p.x() / eps_)),
            static_cast<long long>(std::floor(p.y() / eps_)),
            static_cast<long long>(std::floor(p.z() / eps_))};
  }
  double eps_;
  std::vector<Vector3> vertices_;
  std::map<std::array<long long, 3>, std::vector<int>> grid_;
};

// A planar face bounded by straight edges: its triangles are exact (no
// chordal error).
bool IsPlanarStraight(const TopoDS_Face& face) {
  if (BRepAdaptor_Surface(face).GetType() != GeomAbs_Plane) return false;
  for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (BRep_Tool::Degenerated(edge) || !BRep_Tool::IsGeometric(edge)) return false;
    if (BRepAdaptor_Curve(edge).GetType() != GeomAbs_Line) return false;
  }
  return true;
}

// ... and without holes: one polygon, its outer wire.
bool IsExactPlanar(const TopoDS_Face& face) {
  int wires = 0;
  for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) ++wires;
  return wires == 1 && IsPlanarStraight(face);
}

// The outward unit normal of a planar face (the plane's normal, reversed
// for a reversed face).
gp_Dir OutwardNormal(const TopoDS_Face& face) {
  const gp_Pln plane = BRepAdaptor_Surface(face).Plane();
  gp_Dir n = plane.Axis().Direction();
  if (face.Orientation() == TopAbs_REVERSED) n.Reverse();
  return n;
}

// The polygon of an exact planar face: its outer wire in order, each edge
// with the nodes BRepMesh put on it (shared with the neighbouring faces'
// triangles, so the solid stays closed where a tessellated face meets it),
// turned to the face's outward normal (right-hand rule).
std::vector<Vector3> ExactPolygon(const TopoDS_Face& face, const Handle(Poly_Triangulation) & tri,
                                  const TopLoc_Location& tri_loc, double unit) {
  const gp_Trsf to_world = tri_loc.Transformation();
  std::vector<Vector3> polygon;
  for (BRepTools_WireExplorer we(BRepTools::OuterWire(face), face); we.More(); we.Next()) {
    const TopoDS_Edge& edge = we.Current();
    const gp_Pnt start = BRep_Tool::Pnt(we.CurrentVertex());
    std::vector<gp_Pnt> nodes;
    const Handle(Poly_PolygonOnTriangulation)& on_tri =
        BRep_Tool::PolygonOnTriangulation(edge, tri, tri_loc);
    if (!on_tri.IsNull()) {
      for (int k = 1; k <= on_tri->NbNodes(); ++k)
        nodes.push_back(tri->Node(on_tri->Node(k)).Transformed(to_world));
      // The nodes follow the edge's parameter: walk them from this wire's
      // current vertex.
      if (nodes.size() >= 2 &&
          nodes.back().SquareDistance(start) < nodes.front().SquareDistance(start))
        std::reverse(nodes.begin(), nodes.end());
      nodes.pop_back();  // the next edge's first node
    } else {
      nodes.push_back(start);
    }
    for (const gp_Pnt& p : nodes) polygon.push_back(ToVector(p, unit));
  }
  // Newell's normal of the polygon against the face's outward normal.
  Vector3 newell(0, 0, 0);
  for (size_t k = 0; k < polygon.size(); ++k)
    newell += polygon[k].cross(polygon[(k + 1) % polygon.size()]);
  const gp_Dir n = OutwardNormal(face);
  if (newell.dot(Vector3(n.X(), n.Y(), n.Z())) < 0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

// The name of a face's surface type, for the notes.
std::string SurfaceKind(const TopoDS_Face& face) {
  switch (BRepAdaptor_Surface(face).GetType()) {
    case GeomAbs_Plane:
      return "plane";
    case GeomAbs_Cylinder:
      return "cylinder";
    case GeomAbs_Cone:
      return "cone";
    case GeomAbs_Sphere:
      return "sphere";
    case GeomAbs_Torus:
      return "torus";
    case GeomAbs_BezierSurface:
      return "Bezier surface";
    case GeomAbs_BSplineSurface:
      return "B-spline surface";
    case GeomAbs_SurfaceOfRevolution:
      return "surface of revolution";
    case GeomAbs_SurfaceOfExtrusion:
      return "surface of extrusion";
    case GeomAbs_OffsetSurface:
      return "offset surface";
    default:
      return "surface";
  }
}

// BRepMesh over `solid` to `deflection`; the index of the first face it left
// without triangles (TopExp_Explorer's order), or −1.
int Mesh(const TopoDS_Solid& solid, double deflection) {
  const BRepMesh_IncrementalMesh mesher(solid, deflection, false, kMeshAngularDeflection, false);
  if (!mesher.IsDone()) throw Standard_Failure("BRepMesh_IncrementalMesh did not finish");
  int face_index = 0;
  for (TopExp_Explorer e(solid, TopAbs_FACE); e.More(); e.Next(), ++face_index) {
    TopLoc_Location loc;
    if (BRep_Tool::Triangulation(TopoDS::Face(e.Current()), loc).IsNull()) return face_index;
  }
  return -1;
}

// 6a. The solid meshed. OpenCASCADE's mesher leaves some valid faces without
// triangles (cones whose parametrisation it mishandles: OCCT issue #572, the
// shear mold's part 14_001 and the APLAN benchmark's pump and clutch). Then
// the whole solid is converted to B-spline surfaces (BRepBuilderAPI_NurbsConvert:
// the same geometry, the topology kept, so shared edges stay shared) and
// meshed again, and the part's note says so. Its planar faces, B-splines
// now, are tessellated too, and merged back into polygons with the others.
TopoDS_Solid MeshedSolid(const TopoDS_Solid& solid, double deflection, StepPartReport& report) {
  const int failed = Mesh(solid, deflection);
  if (failed < 0) return solid;
  TopExp_Explorer e(solid, TopAbs_FACE);
  for (int k = 0; k < failed; ++k) e.Next();
  const std::string what =
      "face " + std::to_string(failed) + " (a " + SurfaceKind(TopoDS::Face(e.Current())) + ")";
  BRepBuilderAPI_NurbsConvert convert(solid, true);
  TopoDS_Solid nurbs;
  if (convert.IsDone())
    for (TopExp_Explorer s(convert.Shape(), TopAbs_SOLID); s.More() && nurbs.IsNull(); s.Next())
      nurbs = TopoDS::Solid(s.Current());
  if (nurbs.IsNull())
    throw Standard_Failure((what + " has no triangles, and the solid cannot be converted to "
                                   "B-spline surfaces")
                               .c_str());
  const int again = Mesh(nurbs, deflection);
  if (again >= 0)
    throw Standard_Failure((what + " has no triangles, nor face " + std::to_string(again) +
                            " of the solid converted to B-spline surfaces")
                               .c_str());
  report.fallback = what +
                    " could not be meshed by OpenCASCADE: the part was converted to B-spline "
                    "surfaces and meshed again";
  return nurbs;
}

// 6. The polyhedron of one solid (placed, in metres), tessellated to
// `deflection` (the file's unit).
PolyhedronDef ToPolyhedron(const TopoDS_Solid& exact, double deflection, double unit, double size_m,
                           double merge_tol, StepPartReport& report) {
  const TopoDS_Solid solid = MeshedSolid(exact, deflection, report);
  Welder welder(kWeldFactor * size_m);
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::vector<int>> polygons;
  int face_index = 0;
  for (TopExp_Explorer e(solid, TopAbs_FACE); e.More(); e.Next(), ++face_index) {
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    TopLoc_Location tri_loc;
    const Handle(Poly_Triangulation)& tri = BRep_Tool::Triangulation(face, tri_loc);
    if (tri.IsNull())
      throw Standard_Failure(("face " + std::to_string(face_index) + " has no triangles").c_str());
    if (IsExactPlanar(face)) {
      std::vector<int> polygon;
      for (const Vector3& p : ExactPolygon(face, tri, tri_loc, unit)) {
        const int v = welder.Add(p);
        if (polygon.empty() || polygon.back() != v) polygon.push_back(v);
      }
      while (polygon.size() > 1 && polygon.front() == polygon.back()) polygon.pop_back();
      polygons.push_back(std::move(polygon));
      ++report.exact_faces;
      continue;
    }
    // Tessellated: the face's triangles, turned outward for a reversed face
    // (exact still for a planar face with holes and straight edges).
    const gp_Trsf to_world = tri_loc.Transformation();
    std::vector<int> index(static_cast<size_t>(tri->NbNodes()) + 1);
    for (int k = 1; k <= tri->NbNodes(); ++k)
      index[k] = welder.Add(ToVector(tri->Node(k).Transformed(to_world), unit));
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (int t = 1; t <= tri->NbTriangles(); ++t) {
      int a = 0, b = 0, c = 0;
      tri->Triangle(t).Get(a, b, c);
      if (reversed) std::swap(b, c);
      triangles.push_back({index[a], index[b], index[c]});
    }
    if (IsPlanarStraight(face))
      ++report.exact_faces;
    else
      ++report.tessellated_faces;
  }
  report.approximated = report.tessellated_faces > 0;
  PolyhedronDef def;
  if (triangles.empty()) {
    def.vertices = welder.vertices();
  } else {
    def = MergeCoplanarTriangles(welder.vertices(), triangles, kMergeAngleTol, merge_tol);
  }
  for (std::vector<int>& polygon : polygons) def.faces.push_back(std::move(polygon));
  return def;
}

// The chordal tolerance's faults name `--mesh-tolerance` when the user gave
// one (it is the option's fault); with the default they are the file's, and
// say that the option exists.
[[noreturn]] void TessellationFault(const std::string& path, const StepReadOptions& options,
                                    double default_m, const std::string& what) {
  if (options.mesh_tolerance > 0)
    throw InputError("", "--mesh-tolerance",
                     FormatNumber(options.mesh_tolerance) + " m: " + what + " in " + path +
                         " (the default for this file is " + FormatNumber(default_m) + " m)");
  throw InputError(path, "",
                   what + " (tessellated within the default chordal tolerance " +
                       FormatNumber(default_m) + " m; --mesh-tolerance sets another)");
}

StepModel ReadStepModel(const std::string& path, const std::string& text,
                        const StepReadOptions& options) {
  SilenceOcct();
  Document document;
  StepModel model;
  model.length_unit = ReadDocument(path, text, document);
  const double unit = model.length_unit;

  // 2. Leaves, placed.
  const Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(document.doc()->Main());
  TDF_LabelSequence roots;
  tool->GetFreeShapes(roots);
  std::vector<Leaf> leaves;
  for (int k = 1; k <= roots.Length(); ++k)
    CollectLeaves(tool, roots.Value(k), TopLoc_Location(), LabelName(roots.Value(k)), 0, path,
                  leaves);
  // Leaves without faces (points, curves, empty products) are not parts.
  leaves.erase(std::remove_if(leaves.begin(), leaves.end(),
                              [](const Leaf& leaf) {
                                return !TopExp_Explorer(leaf.shape, TopAbs_FACE).More();
                              }),
               leaves.end());
  if (leaves.empty()) throw InputError(path, "", "the STEP file has no solids");

  // 3.–4. Names and solids.
  Solids parts;
  parts.names = PartNames(leaves);
  parts.notes.resize(leaves.size());
  for (size_t k = 0; k < leaves.size(); ++k)
    parts.solids.push_back(OneSolid(leaves[k].shape, path, parts.names[k], parts.notes[k]));

  // 4b. What the user joined: fastened parts fused, touching ones cut; and
  // the common volumes asked for.
  FastenParts(path, options, parts);
  MakePartsTouch(path, options, unit, parts);
  for (const auto& [a, b] : options.common_volumes_of) {
    const TopoDS_Solid& sa = parts.solids[FindPart(parts, a, "", path)];
    const TopoDS_Solid& sb = parts.solids[FindPart(parts, b, "", path)];
    BRepAlgoAPI_Common common(sa, sb);
    if (!common.IsDone())
      throw Standard_Failure(
          ("the common volume of parts '" + a + "' and '" + b + "' could not be computed").c_str());
    model.common_volumes.push_back(Volume(common.Shape()) * unit * unit * unit);
  }
  const std::vector<std::string>& names = parts.names;
  const std::vector<TopoDS_Solid>& solids = parts.solids;
  const std::vector<std::string>& solid_notes = parts.notes;
  std::vector<double> diagonals;
  for (const TopoDS_Solid& solid : solids) diagonals.push_back(Diagonal(solid));

  // 5. One chordal tolerance (the file's unit) for the whole assembly: the
  // user's within what OpenCASCADE tessellates (Precision::Confusion() of
  // the file's unit), not finer than kMinMeshToleranceFactor of the smallest
  // part, and below its size.
  const size_t smallest_k =
      static_cast<size_t>(std::min_element(diagonals.begin(), diagonals.end()) - diagonals.begin());
  const double smallest = diagonals[smallest_k];
  if (!(smallest > 0) || !std::isfinite(smallest))
    throw InputError(
        path, "", "part '" + EscapedName(names[smallest_k]) + "' has no extent (an empty solid?)");
  const double default_deflection = kDefaultMeshToleranceFactor * smallest;
  const double default_m = default_deflection * unit;
  if (options.mesh_tolerance > 0) {
    if (!(options.mesh_tolerance / unit >= Precision::Confusion()))
      throw InputError("", "--mesh-tolerance",
                       FormatNumber(options.mesh_tolerance) +
                           " m is finer than OpenCASCADE tessellates " + path + ": at least " +
                           FormatNumber(Precision::Confusion() * unit) +
                           " m (the default for this file is " + FormatNumber(default_m) + " m)");
    const double finest = kMinMeshToleranceFactor * smallest;
    if (!(options.mesh_tolerance / unit >= finest))
      throw InputError("", "--mesh-tolerance",
                       FormatNumber(options.mesh_tolerance) + " m is finer than " +
                           FormatNumber(kMinMeshToleranceFactor) + " of the part '" +
                           EscapedName(names[smallest_k]) + "' of " + path + " (" +
                           FormatNumber(smallest * unit) + " m across): at least " +
                           FormatNumber(finest * unit) + " m (the default for this file is " +
                           FormatNumber(default_m) + " m)");
    if (!(options.mesh_tolerance / unit < smallest))
      throw InputError("", "--mesh-tolerance",
                       FormatNumber(options.mesh_tolerance) + " m is larger than the part '" +
                           EscapedName(names[smallest_k]) + "' of " + path + " (" +
                           FormatNumber(smallest * unit) +
                           " m across): give less (the default for this file is " +
                           FormatNumber(default_m) + " m)");
  }
  const double deflection =
      options.mesh_tolerance > 0 ? options.mesh_tolerance / unit : default_deflection;

  // 6. The parts.
  model.def.name = std::filesystem::path(path).stem().string();
  for (size_t k = 0; k < solids.size(); ++k) {
    StepPartReport report;
    report.name = names[k];
    report.mesh_tolerance = deflection * unit;
    GProp_GProps props;
    BRepGProp::VolumeProperties(solids[k], props);
    report.exact_volume = std::abs(props.Mass()) * unit * unit * unit;
    GProp_GProps surface;
    BRepGProp::SurfaceProperties(solids[k], surface);
    report.exact_area = surface.Mass() * unit * unit;
    PartDef part;
    part.name = names[k];
    // The length tolerance the model will have: the scene default, or for
    // tessellated parts kStepLengthToleranceOfChord × the chord (below).
    const double tol = std::max(ToleranceFactors{}.length * diagonals[k] * unit,
                                kStepLengthToleranceOfChord * deflection * unit);
    try {
      part.polyhedron = ToPolyhedron(solids[k], deflection, unit, diagonals[k] * unit, tol, report);
    } catch (const Standard_Failure& e) {
      TessellationFault(path, options, default_m,
                        "part '" + EscapedName(names[k]) + "' cannot be tessellated (" +
                            (e.GetMessageString() && *e.GetMessageString() ? e.GetMessageString()
                                                                           : "OpenCASCADE") +
                            ")");
    }
    if (!solid_notes[k].empty())
      report.fallback = solid_notes[k] + (report.fallback.empty() ? "" : "; " + report.fallback);
    const auto made = Polyhedron::CheckAndCreate(*part.polyhedron, tol);
    if (const auto* polyhedron = std::get_if<Polyhedron>(&made))
      report.volume = polyhedron->mass().volume;
    model.def.parts.push_back(std::move(part));
    model.parts.push_back(report);
  }
  // A model with tessellated surfaces is no more accurate than its facets,
  // and CAD models of fits are often off by microns (the pen's button sits
  // 0.6 µm off its bore's axis): the length tolerance (contact distance,
  // allowed overlap) of such a model is a tenth of the chordal tolerance
  // unless the user gives one. (Larger, the polyhedron checks would take the
  // thin facets at a cone's apex for intersecting faces.)
  if (std::any_of(model.parts.begin(), model.parts.end(),
                  [](const StepPartReport& r) { return r.approximated; })) {
    model.def.tolerance = kStepLengthToleranceOfChord * deflection * unit;
    model.def.tolerance_option = "--mesh-tolerance";
    // Each part a valid solid at that tolerance: a tessellation too coarse
    // (facets that cross) is the chordal tolerance's fault.
    for (size_t k = 0; k < model.def.parts.size(); ++k) {
      const auto fault = Polyhedron::Check(*model.def.parts[k].polyhedron, model.def.tolerance);
      if (fault)
        TessellationFault(path, options, default_m,
                          "the tessellation of part '" + EscapedName(names[k]) +
                              "' is not a valid solid (" + fault->message + ")");
    }
  }
  return model;
}

}  // namespace

// What the child does: the model or the error, serialised. Never throws.
std::string ReadInChild(const std::string& path, const std::string& text,
                        const StepReadOptions& options) noexcept {
  Writer w;
  try {
    WriteModel(ReadStepModel(path, text, options), w);
  } catch (const InputError& e) {
    w = Writer();
    WriteError(e.file(), e.json_path(), e.message(), w);
  } catch (const Standard_Failure& e) {
    // OpenCASCADE's own exceptions on broken geometry: bad input, not a crash.
    w = Writer();
    WriteError(path, "",
               std::string("OpenCASCADE failed on this file: ") +
                   (e.GetMessageString() && *e.GetMessageString() ? e.GetMessageString()
                                                                  : e.DynamicType()->Name()),
               w);
  } catch (const std::bad_alloc&) {
    w = Writer();
    WriteError(path, "",
               "OpenCASCADE could not read this file: it needs more memory than the limit, " +
                   DescribeByteSize(options.memory_limit),
               w);
  } catch (const std::exception& e) {
    w = Writer();
    WriteError(path, "", std::string("OpenCASCADE could not read this file: ") + e.what(), w);
  } catch (...) {
    w = Writer();
    WriteError(path, "", "OpenCASCADE could not read this file", w);
  }
  return w.str();
}

}  // namespace cairn

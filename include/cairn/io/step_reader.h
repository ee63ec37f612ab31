#pragma once
/// @file
/// STEP assemblies (AP203, AP214, AP242: what every CAD system exports) read
/// directly, with OpenCASCADE (docs/step-format.md).
///
/// The assembly structure is read through XCAF: each leaf part instance
/// becomes a part, named by its product name (when one product is used
/// several times, its instances are `bolt`, `bolt_2`, `bolt_3`, ...), placed
/// by the composition of the locations from the root down, in metres (the
/// file's length unit converted).
///
/// Shapes: a planar face bounded by straight edges and without holes becomes
/// one polyhedron face exactly (its ordered outer wire, oriented outward from
/// the face's orientation); every other face (curved, or planar with holes or
/// curved edges) is tessellated by OCCT's BRepMesh to the chordal tolerance
/// `mesh_tolerance`, and coplanar triangles are merged as for meshes
/// (MergeCoplanarTriangles). Each part says whether it was approximated and by
/// how much (StepPartReport).
///
/// OpenCASCADE stays behind this header: nothing of it is visible to the
/// stages or programs that include it.

#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"

namespace cairn {

/// The default chordal tolerance of the tessellation, as a fraction of the
/// size of the smallest part (the diagonal of its bounding box): one tolerance
/// for the whole assembly, so that coaxial surfaces of two parts of one radius
/// (a pin in its hole) are tessellated alike and touch instead of
/// interpenetrating.
constexpr double kDefaultMeshToleranceFactor = 1e-3;

/// The angular deflection of the tessellation (rad): no facet of a curved
/// surface turns by more than this, whatever the chordal tolerance.
constexpr double kMeshAngularDeflection = 0.5;

/// The default length tolerance (contact distance, allowed overlap) of a model
/// with tessellated parts, as a fraction of the chordal tolerance: the model
/// is no more accurate than its facets, and CAD fits are often off by a few
/// microns. Models without tessellated parts keep the scene default.
constexpr double kStepLengthToleranceOfChord = 0.1;

/// How a STEP file is read.
struct StepReadOptions {
  /// m: the largest distance between a curved surface and its facets; ≤ 0:
  /// kDefaultMeshToleranceFactor × the smallest part's bounding-box diagonal.
  double mesh_tolerance = 0;
};

/// What reading did to one part.
struct StepPartReport {
  std::string name;           ///< the part's name in the model
  bool approximated = false;  ///< some face has a curved surface or edge (tessellated)
  int exact_faces = 0;        ///< planar faces with straight edges (exact)
  int tessellated_faces = 0;  ///< faces with a curved surface or edge (approximated)
  double mesh_tolerance = 0;  ///< m, the chordal tolerance used
  double exact_volume = 0;    ///< m³, of the exact solid (OCCT's BRepGProp)
  double exact_area = 0;      ///< m², of the exact solid's surface (BRepGProp)
  double volume = 0;          ///< m³, of the polyhedron the model holds
};

/// A STEP assembly as Cairn's model.
struct StepModel {
  AssemblyDef def;  ///< 3-D, parts in metres; gravity, friction, density: defaults
  std::vector<StepPartReport> parts;  ///< one per part of `def`, in order
  double length_unit = 1;             ///< the file's length unit in metres (0.001: mm)
  // def.tolerance: kStepLengthToleranceOfChord × the chordal tolerance when a
  // part is approximated (def.tolerance_option "--mesh-tolerance"), else 0.
};

/// Reads `path`. @throws InputError naming the file (and the part): not a
/// STEP file, no solids, a part with an open shell or several solids, a
/// tessellation that fails.
StepModel ReadStepAssembly(const std::string& path, const StepReadOptions& options = {});

}  // namespace cairn

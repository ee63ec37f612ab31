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
/// A STEP file is untrusted input, and OpenCASCADE crashes or never returns
/// on some broken files (a reference to an entity the file does not define,
/// NUL bytes, a coordinate NAN or 1.E400). The text is checked first for
/// those (each said with its line); then the reading, the transfer and the
/// tessellation run in a child process limited to kStepTimeLimit of wall time
/// and kStepMemoryLimit of address space, which passes the parts back: a
/// crash, a hang or a runaway allocation there is an InputError naming the
/// file ("OpenCASCADE could not read this file (it crashed with SIGSEGV)").
///
/// OpenCASCADE stays behind this header: nothing of it is visible to the
/// stages or programs that include it.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// The default chordal tolerance of the tessellation, as a fraction of the
/// size of the smallest part (the diagonal of its bounding box): one tolerance
/// for the whole assembly, so that coaxial surfaces of two parts of one radius
/// (a pin in its hole) are tessellated alike and touch instead of
/// interpenetrating.
constexpr double kDefaultMeshToleranceFactor = 1e-3;

/// The finest chordal tolerance accepted, as a fraction of the size of the
/// smallest part: 1/100 of the default. Finer, the curved faces of a part
/// become millions of facets (OpenCASCADE takes minutes over the pen's parts
/// at 1e-8 of their size), and the model is no more accurate for it: its
/// contacts are found to a tenth of the chord anyway.
constexpr double kMinMeshToleranceFactor = 1e-5;

/// The angular deflection of the tessellation (rad): no facet of a curved
/// surface turns by more than this, whatever the chordal tolerance.
constexpr double kMeshAngularDeflection = 0.5;

/// The default length tolerance (contact distance, allowed overlap) of a model
/// with tessellated parts, as a fraction of the chordal tolerance: the model
/// is no more accurate than its facets, and CAD fits are often off by a few
/// microns. Models without tessellated parts keep the scene default.
constexpr double kStepLengthToleranceOfChord = 0.1;

/// s: the wall time OpenCASCADE may take to read, transfer and tessellate one
/// STEP file; its process is killed after it. The pen's parts take well under
/// a second each; assemblies of thousands of parts, tens of seconds.
constexpr double kStepTimeLimit = 300;

/// bytes: the address space of the process that reads a STEP file (RLIMIT_AS;
/// not applied in builds with AddressSanitizer, whose shadow memory takes
/// terabytes of address space): 8 GiB.
constexpr std::uint64_t kStepMemoryLimit = std::uint64_t{8} << 30;

/// How a STEP file is read.
struct StepReadOptions {
  /// m: the largest distance between a curved surface and its facets; ≤ 0:
  /// kDefaultMeshToleranceFactor × the smallest part's bounding-box diagonal.
  /// Given (> 0), it must be at least kMinMeshToleranceFactor × the smallest
  /// part's bounding-box diagonal and OpenCASCADE's Precision::Confusion()
  /// (1e-7 of the file's length unit), and less than that diagonal; its
  /// faults are reported as `--mesh-tolerance`'s.
  double mesh_tolerance = 0;
  /// bytes: the largest file read (ReadInputFile).
  std::uint64_t max_input_size = kDefaultMaxInputSize;
  /// s: the wall-time limit of the reading process (kStepTimeLimit).
  double time_limit = kStepTimeLimit;
  /// bytes: its address-space limit (kStepMemoryLimit); 0: none.
  std::uint64_t memory_limit = kStepMemoryLimit;
  /// Check the text before OpenCASCADE reads it (NUL bytes, numbers that are
  /// not finite, references to undefined entities). false leaves only the
  /// process's limits between a broken file and OpenCASCADE (their tests).
  bool check_text = true;
  /// Pairs of parts (names in the model) joined into one rigid part
  /// (`--fastened A:B`): the exact solids of each group of pairs fused
  /// (OpenCASCADE's BRepAlgoAPI_Fuse) into one part, named by the group's
  /// names in the model's order joined with '+', where its first part was.
  /// They must touch or overlap: fused, they are one solid.
  std::vector<std::pair<std::string, std::string>> fastened;
  /// Pairs (a, b) made to touch where they overlap (`--touching A:B`): b's
  /// exact solid loses what it shares with a's (BRepAlgoAPI_Cut), so that
  /// b then touches a along a's surface. After `fastened`.
  std::vector<std::pair<std::string, std::string>> touching;
  /// Pairs of parts (names after `fastened`) whose exact common volume is
  /// wanted: StepModel::common_volumes (an interference's size).
  std::vector<std::pair<std::string, std::string>> common_volumes_of;
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
  /// What the reader did where OpenCASCADE's mesher failed, e.g. "face 6 (a
  /// cone) could not be meshed: the part was converted to B-spline surfaces
  /// and meshed again"; empty when the mesher succeeded at once.
  std::string fallback;
};

/// A STEP assembly as Cairn's model.
struct StepModel {
  AssemblyDef def;  ///< 3-D, parts in metres; gravity, friction, density: defaults
  std::vector<StepPartReport> parts;  ///< one per part of `def`, in order
  double length_unit = 1;             ///< the file's length unit in metres (0.001: mm)
  /// m³: the exact volume each pair of StepReadOptions::common_volumes_of
  /// shares (BRepAlgoAPI_Common), in order.
  std::vector<double> common_volumes;
  // def.tolerance: kStepLengthToleranceOfChord × the chordal tolerance when a
  // part is approximated (def.tolerance_option "--mesh-tolerance"), else 0;
  // def.overlap_allowance: the chordal tolerance when a part is approximated.
};

/// Reads `path`. @throws InputError naming the file (and the part): not a
/// regular file of at most `options.max_input_size` bytes, a fault of its
/// text (with its line), not a STEP file, no solids, a part with an open shell
/// or several solids, OpenCASCADE crashed or took longer than the limit;
/// naming `--mesh-tolerance` when that was given: out of range, or a
/// tessellation that fails or is not a valid solid.
StepModel ReadStepAssembly(const std::string& path, const StepReadOptions& options = {});

}  // namespace cairn

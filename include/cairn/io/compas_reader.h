#pragma once
/// @file
/// Reading block assemblies in the COMPAS JSON format of `compas_assembly` and
/// `compas_cra` (ETH Block Research Group), in two layers:
/// ReadCompasAssembly parses the file into its blocks as given (polygonal
/// faces, either orientation, not validated as solids); CompasToModel and
/// ReadCompasScene turn them into Cairn's model (one 3-D part per block), with
/// the planarity policy for slightly curved faces. The layouts read and the
/// mapping are described in docs/compas-format.md.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/geometry/polyhedron.h"
#include "cairn/io/input_file.h"

namespace cairn {

/// One block: a node of the assembly graph.
struct CompasBlock {
  /// The node key, as written in the file ("0", "12"): unique within the
  /// assembly and what the COMPAS scripts use to name blocks.
  std::string name;
  /// Vertices and faces of the block's mesh. The vertex keys of the file are
  /// renumbered 0..n−1 in increasing key order; faces keep their vertex order.
  PolyhedronDef shape;
  /// The node's `is_support` (or the graph's default for it): a fixed block.
  bool is_support = false;
  /// The node's `density` when the file gives one (callers use 1 otherwise).
  std::optional<double> density;
  /// Where the block is in the file, for error messages: the JSON path of the
  /// node ("data.graph.data.node.12") and of its mesh data
  /// ("data.graph.data.node.12.block.data").
  std::string path;
  std::string mesh_path;
  /// The key in the file of each face of `shape` (face f is `face_keys[f]`).
  std::vector<std::string> face_keys;
};

/// One interface stored on an edge (u, v) of the assembly graph: a planar
/// contact polygon between blocks u and v found by compas_assembly's or
/// compas_cra's `assembly_interfaces_numpy` (or made by hand with compas_cra),
/// docs/compas-format.md, "Stored interfaces". An edge may hold several.
struct CompasInterface {
  /// The node keys (block names) of the edge (u, v): a = u, b = v, as written
  /// in the file (`edge.<u>.<v>`).
  std::string a, b;
  /// The interface polygon, as stored: at least 3 points, on the plane through
  /// their centroid with `normal` (to kCompasInterfacePlanarity); convexity,
  /// winding (it varies between files) and repeated points are not checked.
  std::vector<Vector3> points;
  /// Unit normal from block b (v) into block a (u), Cairn's contact convention.
  /// The file's own normal (the frame's xaxis × yaxis; COMPAS 1:
  /// `interface_uvw[2]`) is the outward normal of u's face, pointing from u
  /// into v, in every shared file: this is its opposite, normalised. (The
  /// centroid of a's vertices minus b's has a positive dot product with it
  /// except at some interlocking joints, e.g. 3 of concave-*'s 7.)
  Vector3 normal{0, 0, 0};
  /// The JSON path of the interface in the file, for messages:
  /// "data.graph.data.edge.81.151.interfaces[0]" (COMPAS 1 edge attributes
  /// `interface_points`/`interface_uvw`: the edge, "value.edge.0.1").
  std::string where;
};

/// How far the points of a stored interface may lie from the plane through
/// their centroid with the stored normal, relative to the interface's size
/// (the diagonal of its points' bounding box). The shared files' interfaces
/// are planar to ~1e-14; this catches a normal that is not the polygon's.
inline constexpr double kCompasInterfacePlanarity = 1e-4;

/// The blocks of a COMPAS assembly, in increasing node-key order (numeric keys
/// by value, before any non-numeric keys, which sort as text).
struct CompasAssembly {
  /// The assembly's `attributes.name` ("Assembly", "CRA_Assembly"), or "".
  std::string name;
  std::vector<CompasBlock> blocks;
  /// The interfaces stored on the graph's edges, edge by edge in increasing
  /// key order of u, then of v (the order of `blocks`), each edge's in the
  /// order written; empty when no edge carries any.
  std::vector<CompasInterface> interfaces;
};

/// Converts a parsed COMPAS assembly document (COMPAS 2 `dtype`/`data`
/// wrappers, or the COMPAS 1 `dtype`/`value` wrapper and bare data) to its
/// blocks and stored interfaces, checking structure and types on the way.
/// An edge without interface data is skipped; an interface must join two
/// distinct nodes and have at least 3 finite points, a finite nonzero normal
/// and its points on the plane of that normal (kCompasInterfacePlanarity).
/// @throws InputError naming `file` and the JSON path of the first fault.
CompasAssembly ParseCompasAssembly(const nlohmann::json& doc, const std::string& file);

/// Reads and parses a COMPAS assembly file. @throws InputError (unreadable
/// file, JSON syntax error with its line and column, repeated keys, or any
/// fault of ParseCompasAssembly).
/// The file is a regular file of at most `max_input_size` bytes (ReadInputFile).
CompasAssembly ReadCompasAssembly(const std::string& path,
                                  std::uint64_t max_input_size = kDefaultMaxInputSize);

/// What a COMPAS file does not say.
struct CompasOptions {
  /// Coulomb coefficient of every contact (COMPAS files store none).
  double friction = 0;
  /// The model's length tolerance (contact distance, allowed overlap,
  /// planarity); ≤ 0: kCompasToleranceFactor × the diagonal of the bounding
  /// box of all blocks.
  double tolerance = 0;
  /// Use the stored interfaces (CompasAssembly::interfaces) as the contacts
  /// (AssemblyDef::interfaces) instead of finding contacts from the blocks'
  /// shapes, which then only give masses, and are not checked for overlap.
  /// For assemblies modelled too loosely for exact contacts (the Armadillo
  /// vault). The default tolerance is then kCompasInterfaceToleranceFactor.
  bool stored_interfaces = false;
};

/// The default length tolerance of a COMPAS model, relative to its size (the
/// diagonal of the bounding box of all blocks): 100 times Cairn's default for
/// scene files. COMPAS blocks are modelled in CAD to its tolerances (Rhino's
/// default is 0.001 units, on blocks of about a unit): neighbouring blocks of
/// the shared cross vault interpenetrate by more than 1e-5 of its size (less
/// than 1e-4), which scene files' 1e-6 rejects (docs/compas-format.md,
/// "Tolerance").
inline constexpr double kCompasToleranceFactor = 1e-4;

/// The default length tolerance with stored interfaces, relative to the size:
/// the shapes only give mass properties, so only their validity as solids
/// (planarity, self-intersection) depends on it. Scene files' default: at
/// 1e-4 split faces of the Armadillo's thin stones come within the tolerance
/// of each other; at 1e-6 every stone is a valid solid.
inline constexpr double kCompasInterfaceToleranceFactor = 1e-6;

/// A COMPAS assembly as Cairn's model, before validation by Assembly::Create.
struct CompasModel {
  /// One 3-D part per block, in the blocks' order: named by the node key,
  /// `fixed` when the block is a support, `density` the block's or 1, shape the
  /// block's mesh after the planarity policy; gravity unset (Cairn's 3-D default
  /// (0, 0, −9.81): COMPAS's −z), `friction` and `tolerance` set, no fixtures.
  AssemblyDef def;
  /// The JSON path of each part's node in the file (parts[i] is blocks[i]).
  std::vector<std::string> block_paths;
  /// With stored interfaces: the JSON path of each interface in the file
  /// (def.interfaces[i] is interfaces_paths[i]).
  std::vector<std::string> interface_paths;
  /// How many faces the planarity policy split into triangles, over all blocks.
  int split_faces = 0;
};

/// Builds the model of a parsed COMPAS assembly.
///
/// The planarity policy (docs/compas-format.md): with tol the model's length
/// tolerance (CompasOptions::tolerance, which Assembly::Create will use too),
/// a face whose vertices all lie within tol / 2 of the face's mean plane is
/// kept as written (Polyhedron::Check accepts it as planar).
/// Any other face — the curved voussoirs of vaults — is split into triangles
/// (ear clipping of its projection on the mean plane, always cutting the
/// shortest available diagonal, so two blocks that share a curved interface
/// with the same vertices split it the same way). Vertices are never moved.
/// Each block is then validated as a polyhedron here.
/// @throws InputError naming `file`, the JSON path of the block's node or face
///         (`data.graph.data.node.12.block.data.face.3`) and the fault: a
///         negative or non-finite `friction` (path "friction"), a non-finite
///         `tolerance` (path "tolerance"), a face that
///         cannot be split (its projection is not a simple polygon), a block
///         that is not a closed, manifold, non-self-intersecting solid.
CompasModel CompasToModel(const CompasAssembly& assembly, const CompasOptions& options,
                          const std::string& file);

/// Assembly::Create(model.def, file), with faults of the model (blocks that
/// overlap, ...) named by the block's JSON path in the COMPAS file instead of
/// `parts[i]`. Callers may change `model.def` first (fixed parts, gravity), as
/// long as the parts keep their order.
/// @throws InputError.
Assembly CreateCompasAssembly(const CompasModel& model, const std::string& file);

/// ReadCompasAssembly, CompasToModel and CreateCompasAssembly: the validated
/// Assembly of a COMPAS file. @throws InputError.
Assembly ReadCompasScene(const std::string& path, const CompasOptions& options,
                         std::uint64_t max_input_size = kDefaultMaxInputSize);

}  // namespace cairn

#pragma once
/// @file
/// Geometric feasibility of translational removals: directional blocking
/// graphs and the nondirectional blocking graph (NDBG) of Wilson and Latombe
/// ("Geometric reasoning about mechanical assembly", AIJ 1994; paper refs.
/// [16], [36]).
///
/// For a unit direction d, the directional blocking graph DBG(d) has an arc
/// i → j when part i, translated along d while every other part stays, runs
/// into part j:
///   - *infinitesimally* (BlockingKind::kInfinitesimal): i has a contact with j
///     whose normal n (from j into i) has d · n < 0 (beyond the angle
///     tolerance): the smallest motion along d pushes into j;
///   - *to infinity* (BlockingKind::kInfinity): i + t d overlaps the interior
///     of j (deeper than the length tolerance) for some t > 0. This contains
///     the infinitesimal relation.
/// A subassembly S can leave along d when no part of S has an arc to a
/// present part outside S (CanLeave); the smallest such S containing a part
/// i is the set of parts reachable from i (BlockingClosure), a union of
/// strongly connected components of DBG(d).
///
/// The NDBG partitions the directions into cells on which DBG(d) is
/// constant:
///   - 2-D: the circle of directions is cut at the critical directions (those
///     perpendicular to a contact normal, where the infinitesimal relation
///     changes, and the directions where a pair's swept overlap starts or
///     stops, which are directions of differences of the pair's vertices: the
///     vertices of their Minkowski difference). The cells are the critical
///     directions and the open arcs between them; both graphs are exact on
///     every cell.
///   - 3-D: the great circles d · n = 0 of the distinct contact normals cut
///     the sphere into vertices, open arcs and open faces: the exact
///     infinitesimal NDBG. The relation to infinity is evaluated at each
///     cell's representative direction by a swept-collision test.
///
/// Fixed parts are in the graphs like any other part (they block; a set that
/// contains one cannot leave), except that two fixed parts have no arcs
/// between them (neither ever moves; DetectContacts makes no contact between
/// them). Absent parts (Configuration::present; tools are absent unless a
/// configuration makes them present) have no arcs. Fixtures (fixels) block
/// nothing: the world has no part index, and a fixel is a retractable point
/// support that the stability analysis accounts for, not an obstacle.
///
/// Both relations are decided with the scene's tolerances
/// (Assembly::MakeTolerances): a contact blocks when |d · n| exceeds the
/// angle tolerance, and a swept overlap counts when it is deeper than the
/// length tolerance, so parts that slide along each other (a peg along its
/// slot's walls, a block along its neighbour) are not blocked. docs/blocking.md
/// describes the method.

#include <functional>
#include <vector>

#include "cairn/core/types.h"
#include "cairn/geometry/assembly.h"

namespace cairn {

/// Which motion a blocking graph is about.
enum class BlockingKind {
  kInfinitesimal,  ///< the smallest motion along d (from the contact normals)
  kInfinity,       ///< the whole translation along d, to infinity (swept collision)
};

/// "infinitesimal", "infinity".
const char* to_string(BlockingKind kind);

/// DBG(d): which parts each part runs into when translated along d.
struct BlockingGraph {
  Vector3 direction{0, 1, 0};  ///< d, unit, world frame (2-D: z = 0)
  BlockingKind kind = BlockingKind::kInfinity;
  /// (num_parts) blockers[i]: the parts j with an arc i → j, ascending.
  std::vector<std::vector<int>> blockers;
  /// (num_parts) fixed[i]: part i is fixed (Part::fixed), so a set holding it
  /// cannot leave (CanLeave). Empty in a graph built by hand: no part fixed.
  std::vector<bool> fixed;

  /// True when there is an arc i → j.
  bool Blocks(int i, int j) const;
};

/// The same relation along −d: i moving along −d runs into j exactly when j
/// moving along +d runs into i (the Minkowski difference i ⊖ j is j ⊖ i
/// reflected; a contact normal n from j into i blocks i at −d where it
/// blocks j at d), so the arcs are `graph`'s reversed. Blocking along both
/// directions of an axis costs one computation.
BlockingGraph Reversed(const BlockingGraph& graph);

/// One cell of the NDBG: a set of directions with one blocking graph each.
struct NdbgCell {
  /// The cell's dimension: 0 for a critical direction (2-D) or a vertex of
  /// the arrangement (3-D), 1 for an open arc, 2 for an open face (3-D).
  int cell_dimension = 1;
  /// A direction of the cell, unit: where the cell contains a world axis
  /// direction (±x, ±y, ±z), that one (the one closest to "up", −gravity,
  /// first; then +x, −x, +y, −y, +z, −z), else the middle of the arc (2-D, or
  /// a 3-D arc of a great circle), the vertex itself (3-D), or a point well
  /// inside the face (3-D: the normalised sum of its boundary arcs' middles).
  /// Removal paths use it; both graphs' `direction` is this one.
  Vector3 direction{0, 1, 0};
  /// 2-D: the cell's angular extent, radians counter-clockwise from +x in
  /// [0, 2π), from `angle_from` to `angle_to` (equal for a critical direction;
  /// angle_to < angle_from when the arc crosses +x; an arc with angle_to ==
  /// angle_from is the rest of the circle after its only critical direction;
  /// with no critical direction at all the one cell is the whole circle, 0 to
  /// 2π). 3-D: both 0.
  double angle_from = 0, angle_to = 0;
  /// 3-D: the sign (−1, 0, +1) of d · n_k for each of Ndbg::normals, the
  /// cell's position in the arrangement. 2-D: empty.
  std::vector<int> signs;
  BlockingGraph infinitesimal;  ///< DBG(d) for the smallest motion
  BlockingGraph infinity;       ///< DBG(d) for removal to infinity (at `direction` in 3-D)
  /// Movable (neither fixed nor tool) present parts that can leave alone to
  /// infinity along the cell's directions (no arc to another present part in
  /// `infinity`; 3-D: at `direction`), ascending.
  std::vector<int> removable;
};

/// The nondirectional blocking graph of one configuration.
struct Ndbg {
  int dimension = 2;
  /// The distinct contact normals between parts (unit, one of each ± pair:
  /// the one whose largest component is positive; in order of first
  /// appearance in DetectContacts' order) that define the cells: 3-D the
  /// great circles (NdbgCell::signs refer to them), 2-D the candidate
  /// critical directions ±(−n_y, n_x) of the infinitesimal relation.
  std::vector<Vector3> normals;
  /// 2-D: in counter-clockwise order from +x, critical directions and arcs
  /// alternating (each critical direction followed by the arc after it; the
  /// arc that crosses +x comes last). The partition is the coarsest one: a
  /// direction is critical only where some pair's relation (infinitesimal or
  /// to infinity) changes, so a perpendicular of a contact normal at which
  /// nothing changes does not cut the circle. 3-D: the full arrangement of
  /// the great circles: vertices, then arcs, then faces, each group sorted by
  /// its sign vector (lexicographically, −1 < 0 < +1).
  std::vector<NdbgCell> cells;
};

/// The cells' graphs to infinity (each at its cell's `direction`), the
/// closest to `up` first (stable otherwise), a direction met twice kept once:
/// the removal directions `cairn plan` and `cairn sequence` try in turn
/// (paper Corollary 1: motion against gravity never makes a path-dependent
/// instability).
std::vector<BlockingGraph> InfinityGraphsUpFirst(std::vector<NdbgCell> cells, const Vector3& up);

/// DBG(d) of `config` (every present part; tools absent unless present).
/// `direction` need not be unit (it is normalised); in 2-D its z is ignored.
/// @throws std::invalid_argument when the direction is zero or not finite.
BlockingGraph ComputeBlockingGraph(const Assembly& assembly, const Configuration& config,
                                   const Vector3& direction, BlockingKind kind);

/// The NDBG of `config`: its cells with both graphs each. Deterministic (the
/// same cells in the same order on every run and thread count).
/// `checkpoint`, when set, is called all through the computation (between
/// parts, pairs and direction tests); it may throw to abandon it (`cairn
/// batch --job-timeout`), and the exception passes through.
Ndbg ComputeNdbg(const Assembly& assembly, const Configuration& config,
                 const std::function<void()>& checkpoint = {});

/// The NDBG restricted to one direction (`cairn blocking --direction`): one
/// cell, `direction` normalised, with both graphs at it and the parts that can
/// leave. 3-D: the cell's `signs` and `cell_dimension` are those of the
/// arrangement cell that holds the direction (2 when it is on no great circle
/// of the normals, 1 on one, 0 on two or more); 2-D: the direction itself,
/// dimension 0, `angle_from` = `angle_to`. `normals` as ComputeNdbg's. In 2-D
/// the direction's z is ignored. `checkpoint` as ComputeNdbg's.
/// @throws std::invalid_argument when the direction is zero or not finite.
Ndbg ComputeBlockingAt(const Assembly& assembly, const Configuration& config,
                       const Vector3& direction, const std::function<void()>& checkpoint = {});

/// True when the set `in_s` (num_parts flags) can leave along the graph's
/// direction: it holds no fixed part (BlockingGraph::fixed) and no part of S
/// has an arc to a part that is present and outside S. Parts of S that are
/// not present are ignored. The empty set can leave.
/// @throws std::invalid_argument when the flags are not num_parts long.
bool CanLeave(const BlockingGraph& graph, const std::vector<bool>& in_s,
              const std::vector<bool>& present);

/// The smallest set containing `part` that can leave along the graph's
/// direction, among the `present` parts: every present part reachable from
/// `part` by arcs (ascending). It contains a fixed part when nothing with
/// `part` can leave.
std::vector<int> BlockingClosure(const BlockingGraph& graph, int part,
                                 const std::vector<bool>& present);

/// The strongly connected components of the graph restricted to the present
/// parts, each ascending, in a deterministic order (of their smallest part).
std::vector<std::vector<int>> StronglyConnectedComponents(const BlockingGraph& graph,
                                                          const std::vector<bool>& present);

}  // namespace cairn

// Blocking graphs and the NDBG (planning/blocking.h): 2-D cells against hand
// computations (two interlocking L-shapes, a peg in a slot), the 3-D
// infinitesimal arrangement of a box in a corner, blocking only at infinity,
// a swept test through a non-convex part, the paper's Fig. 1, the graph
// algorithms, postconditions and determinism.
#include "cairn/planning/blocking.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cairn/io/scene_reader.h"
#include "scene_builders.h"
#include "test_paths.h"

namespace cairn {
namespace {

using testing::Box;
using testing::Box3;
using testing::ExamplePath;

constexpr double kDeg = std::numbers::pi / 180.0;

Assembly Example(const std::string& name) { return ReadScene(ExamplePath(name)); }

// The arcs of a graph as (blocked, blocker) pairs.
std::set<std::pair<int, int>> Arcs(const BlockingGraph& g) {
  std::set<std::pair<int, int>> out;
  for (int i = 0; i < static_cast<int>(g.blockers.size()); ++i)
    for (const int j : g.blockers[i]) out.insert({i, j});
  return out;
}

using ArcSet = std::set<std::pair<int, int>>;

// One expected 2-D cell.
struct Cell2 {
  int dimension;
  double from_deg, to_deg;
  ArcSet infinitesimal, infinity;
  std::vector<int> removable;
};

void ExpectCells(const Ndbg& ndbg, const std::vector<Cell2>& expected) {
  ASSERT_EQ(ndbg.cells.size(), expected.size());
  for (size_t c = 0; c < expected.size(); ++c) {
    SCOPED_TRACE("cell " + std::to_string(c));
    const NdbgCell& cell = ndbg.cells[c];
    const Cell2& e = expected[c];
    EXPECT_EQ(cell.cell_dimension, e.dimension);
    EXPECT_NEAR(cell.angle_from, e.from_deg * kDeg, 1e-9);
    EXPECT_NEAR(cell.angle_to, e.to_deg * kDeg, 1e-9);
    EXPECT_EQ(Arcs(cell.infinitesimal), e.infinitesimal);
    EXPECT_EQ(Arcs(cell.infinity), e.infinity);
    EXPECT_EQ(cell.removable, e.removable);
    EXPECT_NEAR(cell.direction.norm(), 1.0, 1e-12);
    EXPECT_EQ(cell.infinity.direction, cell.direction);
  }
}

// Every 2-D cell's graphs are DBG(d) at its direction (the NDBG and the
// direct computation agree), the infinity relation contains the
// infinitesimal one, and the cells tile the circle in order.
void ExpectConsistent(const Assembly& assembly, const Configuration& config, const Ndbg& ndbg) {
  for (size_t c = 0; c < ndbg.cells.size(); ++c) {
    SCOPED_TRACE("cell " + std::to_string(c));
    const NdbgCell& cell = ndbg.cells[c];
    const BlockingGraph inf =
        ComputeBlockingGraph(assembly, config, cell.direction, BlockingKind::kInfinitesimal);
    const BlockingGraph far =
        ComputeBlockingGraph(assembly, config, cell.direction, BlockingKind::kInfinity);
    EXPECT_EQ(Arcs(inf), Arcs(cell.infinitesimal));
    EXPECT_EQ(Arcs(far), Arcs(cell.infinity));
    for (const auto& arc : Arcs(cell.infinitesimal)) EXPECT_TRUE(Arcs(cell.infinity).count(arc));
    if (ndbg.dimension == 2 && ndbg.cells.size() > 1) {
      const NdbgCell& next = ndbg.cells[(c + 1) % ndbg.cells.size()];
      EXPECT_EQ(cell.cell_dimension + next.cell_dimension, 1);  // alternating
      EXPECT_NEAR(next.angle_from, cell.angle_to, 1e-15);
      if (cell.cell_dimension == 1) {  // the direction lies inside the arc
        double span = cell.angle_to - cell.angle_from,
               off = std::atan2(cell.direction.y(), cell.direction.x()) - cell.angle_from;
        if (span <= 0) span += 2 * std::numbers::pi;
        if (off < 0) off += 2 * std::numbers::pi;
        EXPECT_GT(off, 0);
        EXPECT_LT(off, span);
      }
    }
  }
}

// Two L-shapes that close into a square frame: B (the upper one, part 1)
// rests on A's stem and foot. Hand-computed: B leaves to infinity for
// 0° ≤ θ ≤ 135° (at 135° its inner corner (3, 1) slides past A's corner
// (1, 3)); A, symmetrically, for 180° ≤ θ ≤ 315°. Between 135° and 180° B
// is free infinitesimally but runs into A's stem: blocked only at infinity.
TEST(Ndbg2d, InterlockingLShapesHandComputedCells) {
  const Assembly assembly = Example("l_shapes.json");
  const Configuration config = Configuration::Assembled(assembly);
  const int A = assembly.FindPart("A"), B = assembly.FindPart("B");
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  EXPECT_EQ(ndbg.dimension, 2);
  ASSERT_EQ(ndbg.normals.size(), 1u);  // both contacts push along ±y
  EXPECT_NEAR(std::abs(ndbg.normals[0].y()), 1.0, 1e-12);
  const ArcSet none, ab{{A, B}}, ba{{B, A}}, both{{A, B}, {B, A}};
  ExpectCells(ndbg, {
                        {0, 0, 0, none, ab, {B}},
                        {1, 0, 135, ab, ab, {B}},
                        {0, 135, 135, ab, ab, {B}},
                        {1, 135, 180, ab, both, {}},
                        {0, 180, 180, none, ba, {A}},
                        {1, 180, 315, ba, ba, {A}},
                        {0, 315, 315, ba, ba, {A}},
                        {1, 315, 0, ba, both, {}},
                    });
  // Representatives: the axes where the cell holds one, else the middle.
  EXPECT_EQ(ndbg.cells[0].direction, Vector3(1, 0, 0));
  EXPECT_EQ(ndbg.cells[1].direction, Vector3(0, 1, 0));  // up first
  EXPECT_NEAR(ndbg.cells[3].direction.x(), std::cos(157.5 * kDeg), 1e-12);
  EXPECT_EQ(ndbg.cells[4].direction, Vector3(-1, 0, 0));
  EXPECT_EQ(ndbg.cells[5].direction, Vector3(0, -1, 0));
  EXPECT_NEAR(ndbg.cells[7].direction.y(), std::sin(337.5 * kDeg), 1e-12);
  ExpectConsistent(assembly, config, ndbg);
}

// A peg in a slot of a fixed base: the peg leaves straight up only; the
// side walls' normals (±x) cut the circle nowhere, because nothing changes
// at ±y... except at the slot's axis itself.
TEST(Ndbg2d, PegInSlotHandComputedCells) {
  const Assembly assembly = Example("peg_in_slot.json");
  const Configuration config = Configuration::Assembled(assembly);
  const int base = assembly.FindPart("base"), peg = assembly.FindPart("peg");
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  EXPECT_EQ(ndbg.normals.size(), 2u);  // the floor (y) and the walls (x)
  const ArcSet both{{peg, base}, {base, peg}}, up{{base, peg}}, down{{peg, base}};
  ExpectCells(ndbg, {
                        {0, 90, 90, up, up, {peg}},
                        {1, 90, 270, both, both, {}},
                        {0, 270, 270, down, down, {}},
                        {1, 270, 90, both, both, {}},
                    });
  EXPECT_EQ(ndbg.cells[0].direction, Vector3(0, 1, 0));
  EXPECT_EQ(ndbg.cells[1].direction, Vector3(-1, 0, 0));
  EXPECT_EQ(ndbg.cells[3].direction, Vector3(1, 0, 0));
  ExpectConsistent(assembly, config, ndbg);
  // A hair off vertical, the peg is blocked (infinitesimally, by a wall).
  const Vector3 tilted(std::sin(1e-3), std::cos(1e-3), 0);
  EXPECT_TRUE(ComputeBlockingGraph(assembly, config, tilted, BlockingKind::kInfinitesimal)
                  .Blocks(peg, base));
  EXPECT_FALSE(ComputeBlockingGraph(assembly, config, Vector3(0, 5, 0), BlockingKind::kInfinity)
                   .Blocks(peg, base));
}

// Two blocks on a table with a gap: A (left) is not touched by B, so moving
// right it is blocked only to infinity; the critical direction where A's
// lower right corner just clears B's upper left corner is 45°.
TEST(BlockingGraph, BlockedOnlyAtInfinity) {
  AssemblyDef def;
  def.parts = {Box("table", -5, -1, 5, 0, true), Box("A", 0, 0, 1, 1), Box("B", 2, 0, 3, 1)};
  const Assembly assembly = Assembly::Create(def);
  const Configuration config = Configuration::Assembled(assembly);
  const int A = 1, B = 2;
  const Vector3 right(1, 0, 0);
  EXPECT_FALSE(
      ComputeBlockingGraph(assembly, config, right, BlockingKind::kInfinitesimal).Blocks(A, B));
  const BlockingGraph far = ComputeBlockingGraph(assembly, config, right, BlockingKind::kInfinity);
  EXPECT_TRUE(far.Blocks(A, B));
  EXPECT_FALSE(far.Blocks(B, A));
  EXPECT_TRUE(far.blockers[B].empty());
  EXPECT_TRUE(ComputeBlockingGraph(assembly, config, -right, BlockingKind::kInfinity).Blocks(B, A));
  // Just below 45° A's corner hits B's side; just above it clears B's top.
  const auto at = [&](double deg) {
    return ComputeBlockingGraph(assembly, config,
                                Vector3(std::cos(deg * kDeg), std::sin(deg * kDeg), 0),
                                BlockingKind::kInfinity)
        .Blocks(A, B);
  };
  EXPECT_TRUE(at(44.9));
  EXPECT_FALSE(at(45.0));
  EXPECT_FALSE(at(45.1));
  // The NDBG has 45° as a critical direction where A can leave, and the arc
  // below it (which holds +x) where it cannot, while not touching B.
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  int found = 0;
  for (size_t c = 0; c < ndbg.cells.size(); ++c) {
    const NdbgCell& cell = ndbg.cells[c];
    if (cell.cell_dimension == 0 && std::abs(cell.angle_from - 45 * kDeg) < 1e-9) {
      ++found;
      EXPECT_FALSE(cell.infinity.Blocks(A, B));
      const NdbgCell& before = ndbg.cells[(c + ndbg.cells.size() - 1) % ndbg.cells.size()];
      EXPECT_TRUE(before.infinity.Blocks(A, B));
      EXPECT_FALSE(before.infinitesimal.Blocks(A, B));
    }
  }
  EXPECT_EQ(found, 1);
  ExpectConsistent(assembly, config, ndbg);
}

// A box in a corner: a floor and two walls (fixed). The three normals' great
// circles are the coordinate planes: 6 vertices (±x, ±y, ±z), 12 arcs, 8
// octants. The box leaves exactly where d ≥ 0 componentwise: 7 cells.
TEST(Ndbg3d, BoxInACornerInfinitesimalArrangement) {
  AssemblyDef def;
  def.gravity = Vector3(0, 0, -9.81);
  def.parts = {Box3("floor", {-1, -1, -1}, {3, 3, 0}, true),
               Box3("wall_x", {-1, 0, 0}, {0, 3, 3}, true),
               Box3("wall_y", {0, -1, 0}, {3, 0, 3}, true), Box3("box", {0, 0, 0}, {1, 1, 1})};
  const Assembly assembly = Assembly::Create(def);
  const Configuration config = Configuration::Assembled(assembly);
  const int floor = 0, wall_x = 1, wall_y = 2, box = 3;
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  EXPECT_EQ(ndbg.dimension, 3);
  ASSERT_EQ(ndbg.normals.size(), 3u);
  int count[3] = {0, 0, 0}, free_cells = 0;
  for (const NdbgCell& cell : ndbg.cells) {
    ++count[cell.cell_dimension];
    const Vector3& d = cell.direction;
    SCOPED_TRACE("cell at " + std::to_string(d.x()) + ", " + std::to_string(d.y()) + ", " +
                 std::to_string(d.z()));
    EXPECT_EQ(static_cast<int>(std::count(cell.signs.begin(), cell.signs.end(), 0)),
              2 - cell.cell_dimension);
    EXPECT_EQ(cell.infinitesimal.Blocks(box, floor), d.z() < -1e-9);
    EXPECT_EQ(cell.infinitesimal.Blocks(box, wall_x), d.x() < -1e-9);
    EXPECT_EQ(cell.infinitesimal.Blocks(box, wall_y), d.y() < -1e-9);
    const bool free = d.minCoeff() > -1e-9;
    EXPECT_EQ(cell.removable == std::vector<int>{box}, free);
    free_cells += free ? 1 : 0;
    // Fixed parts have no arcs between them.
    EXPECT_FALSE(cell.infinity.Blocks(wall_x, floor));
    if (cell.cell_dimension == 2 && free) {  // the positive octant: its centre
      EXPECT_TRUE(d.isApprox(Vector3(1, 1, 1).normalized(), 1e-12));
    }
  }
  EXPECT_EQ(count[0], 6);
  EXPECT_EQ(count[1], 12);
  EXPECT_EQ(count[2], 8);
  EXPECT_EQ(free_cells, 7);
  EXPECT_EQ(ndbg.cells[0].cell_dimension, 0);
  EXPECT_EQ(ndbg.cells.back().cell_dimension, 2);
  ExpectConsistent(assembly, config, ndbg);
}

// A prism: the polygon `profile` in the (x, z) plane (counter-clockwise,
// x right, z up) extruded along y from 0 to `depth`.
PartDef Extruded(const std::string& name, const std::vector<std::array<double, 2>>& profile,
                 double depth, bool fixed = false) {
  PartDef p;
  p.name = name;
  p.fixed = fixed;
  PolyhedronDef d;
  const int n = static_cast<int>(profile.size());
  for (const double y : {0.0, depth})
    for (const auto& [x, z] : profile) d.vertices.emplace_back(x, y, z);
  std::vector<int> front, back;
  for (int k = 0; k < n; ++k) front.push_back(k), back.push_back(2 * n - 1 - k);
  d.faces = {front, back};
  for (int k = 0; k < n; ++k) d.faces.push_back({k, n + k, n + (k + 1) % n, (k + 1) % n});
  p.polyhedron = d;
  return p;
}

// The 3-D NDBG against DBG(d) computed afresh at every cell's direction
// (ExpectConsistent), where the swept tests are of non-convex pairs: a block
// in a U-channel's slot against its left wall, clear of the right one, under
// a lid on the channel's arms, against a wall behind it; a block on an
// inclined wedge adds a fourth normal.
// Within one NDBG a pair's "yes" leaves a cone of directions proved blocked
// (docs/blocking.md, step 3) that later cells of the pair take without a
// sweep; computed afresh, every direction is swept: the graphs must agree.
TEST(Ndbg3d, NonConvexPairsAgreeWithDirectGraphsInEveryCell) {
  AssemblyDef def;
  def.gravity = Vector3(0, 0, -9.81);
  const double s30 = 0.5, c30 = std::sqrt(3.0) / 2;
  def.parts = {
      Extruded("channel", {{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 0.5}, {1, 0.5}, {1, 2}, {0, 2}}, 1,
               true),
      Box3("inner", {1, 0.2, 0.5}, {1.6, 0.8, 1.1}), Box3("lid", {0, 0, 2}, {3, 1, 2.3}),
      Box3("back", {0, 1, 2}, {3, 1.5, 3}, true),  // against the lid: a normal along y
      Extruded("wedge", {{5, 0}, {5 + 2 * c30, 0}, {5, 2 * s30}}, 1, true),
      // A 1 × 0.5 block on the wedge's slope, 0.8 up it from its foot.
      Extruded("slider",
               {{5 + 1.2 * c30, 0.8 * s30},
                {5 + 1.2 * c30 + 0.5 * s30, 0.8 * s30 + 0.5 * c30},
                {5 + 0.2 * c30 + 0.5 * s30, 1.8 * s30 + 0.5 * c30},
                {5 + 0.2 * c30, 1.8 * s30}},
               1)};
  const Assembly assembly = Assembly::Create(def);
  const Configuration config = Configuration::Assembled(assembly);
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  EXPECT_GE(ndbg.normals.size(), 3u);
  EXPECT_GT(ndbg.cells.size(), 20u);
  ExpectConsistent(assembly, config, ndbg);
  // Opposite cells: their representatives are exact antipodes, and i runs
  // into j along d exactly when j runs into i along −d, so each one's graphs
  // are the other's reversed (the NDBG computes each swept test once for
  // both: this is what makes that sound).
  int opposite_pairs = 0;
  for (const NdbgCell& cell : ndbg.cells) {
    std::vector<int> minus = cell.signs;
    for (int& x : minus) x = -x;
    const auto it = std::find_if(ndbg.cells.begin(), ndbg.cells.end(), [&](const NdbgCell& o) {
      return o.signs == minus && &o != &cell;
    });
    ASSERT_NE(it, ndbg.cells.end());
    EXPECT_EQ(it->direction, Vector3(-cell.direction));
    EXPECT_EQ(Arcs(it->infinity), Arcs(Reversed(cell.infinity)));
    EXPECT_EQ(Arcs(it->infinitesimal), Arcs(Reversed(cell.infinitesimal)));
    ++opposite_pairs;
  }
  EXPECT_EQ(opposite_pairs, static_cast<int>(ndbg.cells.size()));
  // Physics: the inner block leaves the slot straight up only with the lid
  // gone; along +y it slides out of the open end.
  const int inner = 1, lid = 2;
  for (const NdbgCell& cell : ndbg.cells) {
    if (cell.direction.isApprox(Vector3::UnitZ(), 1e-12)) {
      EXPECT_TRUE(cell.infinity.Blocks(inner, lid));
      EXPECT_FALSE(cell.infinity.Blocks(inner, 0));
    }
    if (cell.direction.isApprox(Vector3::UnitY(), 1e-12)) {
      EXPECT_TRUE(cell.infinity.blockers[inner].empty());
    }
  }
}

// Two walls and no floor: the normals x and y lie in one plane, so both
// circles pass through ±z, two vertices with the same (zero) sign vector.
// 2 vertices, 4 arcs, 4 lunes; the box leaves where d_x ≥ 0 and d_y ≥ 0.
TEST(Ndbg3d, CoplanarNormalsTwoVertices) {
  AssemblyDef def;
  def.gravity = Vector3(0, 0, -9.81);
  def.parts = {Box3("wall_x", {-1, 0, 0}, {0, 3, 3}, true),
               Box3("wall_y", {0, -1, 0}, {3, 0, 3}, true), Box3("box", {0, 0, 1}, {1, 1, 2})};
  const Assembly assembly = Assembly::Create(def);
  const Configuration config = Configuration::Assembled(assembly);
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  ASSERT_EQ(ndbg.normals.size(), 2u);
  ASSERT_EQ(ndbg.cells.size(), 10u);
  EXPECT_EQ(ndbg.cells[0].direction, Vector3(0, 0, -1));
  EXPECT_EQ(ndbg.cells[1].direction, Vector3(0, 0, 1));
  int count[3] = {0, 0, 0}, free_cells = 0;
  for (const NdbgCell& cell : ndbg.cells) {
    ++count[cell.cell_dimension];
    const bool free = cell.direction.x() > -1e-9 && cell.direction.y() > -1e-9;
    EXPECT_EQ(cell.removable == std::vector<int>{2}, free);
    free_cells += free ? 1 : 0;
  }
  EXPECT_EQ(count[0], 2);
  EXPECT_EQ(count[1], 4);
  EXPECT_EQ(count[2], 4);
  EXPECT_EQ(free_cells, 5);
  ExpectConsistent(assembly, config, ndbg);
}

// A U-shaped channel (non-convex; profile in xz, open along y) with a peg
// standing on its floor, clear of its walls: up and along the channel the
// peg is free; sideways it is blocked, though only at infinity. The swept
// test runs through the non-convex part's event times.
TEST(BlockingGraph, SweptThroughNonConvexUSlot) {
  const std::vector<Vector2> profile = {{0, 0}, {3, 0}, {3, 2}, {2, 2},
                                        {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  PartDef u;
  u.name = "U";
  u.fixed = true;
  PolyhedronDef poly;
  for (double y : {0.0, 1.0})
    for (const Vector2& p : profile) poly.vertices.push_back({p.x(), y, p.y()});
  poly.faces.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  poly.faces.push_back({15, 14, 13, 12, 11, 10, 9, 8});
  for (int k = 0; k < 8; ++k) poly.faces.push_back({k, 8 + k, 8 + (k + 1) % 8, (k + 1) % 8});
  u.polyhedron = poly;
  AssemblyDef def;
  def.gravity = Vector3(0, 0, -9.81);
  def.parts = {u, Box3("peg", {1.2, 0.2, 1}, {1.8, 0.8, 2.5})};
  const Assembly assembly = Assembly::Create(def);
  const Configuration config = Configuration::Assembled(assembly);
  const int U = 0, peg = 1;
  const auto far = [&](const Vector3& d) {
    return ComputeBlockingGraph(assembly, config, d, BlockingKind::kInfinity).Blocks(peg, U);
  };
  const auto inf = [&](const Vector3& d) {
    return ComputeBlockingGraph(assembly, config, d, BlockingKind::kInfinitesimal).Blocks(peg, U);
  };
  EXPECT_FALSE(far({0, 0, 1}));
  EXPECT_FALSE(far({0, 1, 0}));  // along the channel
  EXPECT_FALSE(far({0, -1, 0}));
  EXPECT_TRUE(far({1, 0, 0}));
  EXPECT_TRUE(far({-1, 0, 0}));
  EXPECT_FALSE(inf({1, 0, 0}));  // not touching the walls
  EXPECT_TRUE(inf({0, 0, -1}));
  // The corner (1.8, ·, 1) clears the wall top (2, ·, 2) at slope dz/dx = 5.
  EXPECT_TRUE(far({1, 0, 4}));
  EXPECT_FALSE(far({1, 0, 6}));
  EXPECT_TRUE(far({1, 0.5, 4}));
  // The arrangement of the one normal (+z): the circle z = 0 (represented by
  // +x, where the walls block) and two hemispheres.
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  ASSERT_EQ(ndbg.cells.size(), 3u);
  EXPECT_EQ(ndbg.cells[0].cell_dimension, 1);
  EXPECT_EQ(ndbg.cells[0].direction, Vector3(1, 0, 0));
  EXPECT_TRUE(ndbg.cells[0].removable.empty());
  EXPECT_TRUE(ndbg.cells[0].infinitesimal.blockers[peg].empty());
  EXPECT_EQ(ndbg.cells[1].signs, std::vector<int>{-1});
  EXPECT_EQ(ndbg.cells[1].direction, Vector3(0, 0, -1));
  EXPECT_TRUE(ndbg.cells[1].removable.empty());
  EXPECT_EQ(ndbg.cells[2].signs, std::vector<int>{1});
  EXPECT_EQ(ndbg.cells[2].direction, Vector3(0, 0, 1));
  EXPECT_EQ(ndbg.cells[2].removable, std::vector<int>{peg});
}

// The paper's Fig. 1: D and C can leave upward; B (under C and D) and A
// (under B) cannot; A's closure upward is the whole stack.
TEST(Ndbg2d, PaperFig1Upward) {
  const Assembly assembly = Example("paper_fig1.json");
  const Configuration config = Configuration::Assembled(assembly);
  const int A = assembly.FindPart("A"), B = assembly.FindPart("B"), C = assembly.FindPart("C"),
            D = assembly.FindPart("D"), E = assembly.FindPart("E");
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  const NdbgCell* up = nullptr;
  for (const NdbgCell& cell : ndbg.cells)
    if (cell.direction == Vector3(0, 1, 0)) up = &cell;
  ASSERT_NE(up, nullptr);
  std::vector<int> expected = {C, D};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(up->removable, expected);
  EXPECT_TRUE(up->infinity.Blocks(B, C));
  EXPECT_TRUE(up->infinity.Blocks(B, D));
  EXPECT_TRUE(up->infinity.Blocks(A, B));
  EXPECT_FALSE(up->infinity.Blocks(A, C));  // C is beside A's column, not above it
  std::vector<bool> present(assembly.num_parts(), true);
  EXPECT_EQ(BlockingClosure(up->infinity, A, present), (std::vector<int>{A, B, C, D}));
  EXPECT_EQ(BlockingClosure(up->infinity, D, present), (std::vector<int>{D}));
  std::vector<bool> cd(assembly.num_parts(), false);
  cd[C] = cd[D] = true;
  EXPECT_TRUE(CanLeave(up->infinity, cd, present));
  cd[B] = true;
  EXPECT_TRUE(CanLeave(up->infinity, cd, present));  // B with C and D on it
  cd[E] = true;
  EXPECT_FALSE(CanLeave(up->infinity, cd, present));  // the fixed table never leaves
  // Downward nothing leaves, and the table blocks A and B.
  const BlockingGraph down =
      ComputeBlockingGraph(assembly, config, Vector3(0, -1, 0), BlockingKind::kInfinity);
  EXPECT_TRUE(down.Blocks(A, E));
  EXPECT_TRUE(down.Blocks(B, E));
  ExpectConsistent(assembly, config, ndbg);
  // Without D, the cell is the same and C alone can leave.
  Configuration without_d = config;
  without_d.present[D] = false;
  const BlockingGraph up2 =
      ComputeBlockingGraph(assembly, without_d, Vector3(0, 1, 0), BlockingKind::kInfinity);
  EXPECT_TRUE(up2.blockers[D].empty());
  EXPECT_FALSE(up2.Blocks(B, D));
}

// A 3-D tower (Jenga, 18 layers of 3 with gaps in each layer): one normal
// (z), three cells; upward only the top layer leaves. Timed.
TEST(Ndbg3d, JengaTopLayerLeavesUpward) {
  const Assembly assembly = Example("jenga.json");
  const Configuration config = Configuration::Assembled(assembly);
  const auto start = std::chrono::steady_clock::now();
  const Ndbg ndbg = ComputeNdbg(assembly, config);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("ComputeNdbg(jenga): %zu cells, %.3f s\n", ndbg.cells.size(), seconds);
  ASSERT_EQ(ndbg.cells.size(), 3u);
  const NdbgCell& up = ndbg.cells[2];
  ASSERT_EQ(up.direction, Vector3(0, 0, 1));
  std::vector<int> top = {assembly.FindPart("L18_1"), assembly.FindPart("L18_2"),
                          assembly.FindPart("L18_3")};
  EXPECT_EQ(up.removable, top);
  // Each block of layer 1 is blocked to infinity by every block above its
  // footprint: all of layer 2 (across it), and layers 3, 5, … only the
  // block right above it.
  const int l1 = assembly.FindPart("L01_2");
  EXPECT_TRUE(up.infinity.Blocks(l1, assembly.FindPart("L02_1")));
  EXPECT_TRUE(up.infinity.Blocks(l1, assembly.FindPart("L17_2")));
  EXPECT_FALSE(up.infinity.Blocks(l1, assembly.FindPart("L17_1")));
  EXPECT_EQ(up.infinitesimal.blockers[l1].size(), 3u);  // layer 2 only
}

// One direction (cairn blocking --direction): the NDBG's cell that holds it,
// found by the full arrangement, has the same graphs, signs and dimension;
// in 2-D, the direction itself, with the graphs of ComputeBlockingGraph.
TEST(ComputeBlockingAt, AgreesWithTheNdbgCellThatHoldsTheDirection) {
  for (const char* name : {"jenga.json", "paper_fig1.json", "l_shapes.json", "peg_in_slot.json"}) {
    SCOPED_TRACE(name);
    const Assembly assembly = Example(name);
    const Configuration config = Configuration::Assembled(assembly);
    const Ndbg ndbg = ComputeNdbg(assembly, config);
    for (const NdbgCell& cell : ndbg.cells) {
      const Ndbg one = ComputeBlockingAt(assembly, config, 2.5 * cell.direction);
      ASSERT_EQ(one.cells.size(), 1u);
      const NdbgCell& got = one.cells[0];
      EXPECT_EQ(one.normals, ndbg.normals);
      EXPECT_LT((got.direction - cell.direction).norm(), 1e-12);
      EXPECT_EQ(got.infinity.blockers, cell.infinity.blockers);
      EXPECT_EQ(got.removable, cell.removable);
      if (assembly.is_3d()) {
        EXPECT_EQ(got.signs, cell.signs);
        EXPECT_EQ(got.cell_dimension, cell.cell_dimension);
        EXPECT_EQ(got.infinitesimal.blockers, cell.infinitesimal.blockers);
      } else {
        EXPECT_EQ(got.cell_dimension, 0);
        EXPECT_EQ(got.infinitesimal.blockers, ComputeBlockingGraph(assembly, config, cell.direction,
                                                                   BlockingKind::kInfinitesimal)
                                                  .blockers);
      }
    }
  }
}

// i along −d runs into j exactly when j along +d runs into i: at every
// NDBG cell's direction of the bundled examples, both graphs computed along
// −d equal those along +d reversed (the planner reverses instead of
// computing ±x, ±y, ±z twice).
TEST(Reversed, EqualsTheGraphsComputedAlongTheOppositeDirection) {
  for (const char* name :
       {"jenga.json", "paper_fig1.json", "l_shapes.json", "peg_in_slot.json", "paper_fig9.json"}) {
    SCOPED_TRACE(name);
    const Assembly assembly = Example(name);
    const Configuration config = Configuration::Assembled(assembly);
    for (const NdbgCell& cell : ComputeNdbg(assembly, config).cells) {
      const NdbgCell back = ComputeBlockingAt(assembly, config, -cell.direction).cells[0];
      const NdbgCell forth = ComputeBlockingAt(assembly, config, cell.direction).cells[0];
      for (const auto& [computed, along] : {std::pair(&back.infinity, &forth.infinity),
                                            std::pair(&back.infinitesimal, &forth.infinitesimal)}) {
        const BlockingGraph reversed = Reversed(*along);
        EXPECT_LT((reversed.direction + along->direction).norm(), 1e-15);
        EXPECT_EQ(reversed.blockers, computed->blockers) << cell.direction.transpose();
        EXPECT_EQ(reversed.fixed, computed->fixed);
      }
    }
  }
}

// Nothing to run into: one cell, the whole circle (2-D) or sphere (3-D),
// represented by "up".
TEST(Ndbg, LonePartIsOneCell) {
  AssemblyDef def2;
  def2.parts = {Box("A", 0, 0, 1, 1)};
  const Assembly a2 = Assembly::Create(def2);
  const Ndbg n2 = ComputeNdbg(a2, Configuration::Assembled(a2));
  ASSERT_EQ(n2.cells.size(), 1u);
  EXPECT_EQ(n2.cells[0].cell_dimension, 1);
  EXPECT_EQ(n2.cells[0].angle_from, 0);
  EXPECT_NEAR(n2.cells[0].angle_to, 2 * std::numbers::pi, 1e-15);
  EXPECT_EQ(n2.cells[0].direction, Vector3(0, 1, 0));
  EXPECT_EQ(n2.cells[0].removable, std::vector<int>{0});
  AssemblyDef def3;
  def3.gravity = Vector3(0, 0, -9.81);
  def3.parts = {Box3("A", {0, 0, 0}, {1, 1, 1})};
  const Assembly a3 = Assembly::Create(def3);
  const Ndbg n3 = ComputeNdbg(a3, Configuration::Assembled(a3));
  ASSERT_EQ(n3.cells.size(), 1u);
  EXPECT_EQ(n3.cells[0].cell_dimension, 2);
  EXPECT_TRUE(n3.cells[0].signs.empty());
  EXPECT_EQ(n3.cells[0].direction, Vector3(0, 0, 1));
  EXPECT_EQ(n3.cells[0].removable, std::vector<int>{0});
}

TEST(GraphAlgorithms, ClosureComponentsAndCanLeave) {
  BlockingGraph g;
  g.blockers = {{1}, {0}, {0}, {}, {4}};  // 0 ⇄ 1, 2 → 0, 3 alone, a self-loop on 4
  g.fixed = {false, false, false, false, false};
  const std::vector<bool> all(5, true);
  EXPECT_EQ(StronglyConnectedComponents(g, all),
            (std::vector<std::vector<int>>{{0, 1}, {2}, {3}, {4}}));
  EXPECT_EQ(BlockingClosure(g, 2, all), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(BlockingClosure(g, 3, all), (std::vector<int>{3}));
  EXPECT_TRUE(CanLeave(g, {true, true, false, false, false}, all));
  EXPECT_FALSE(CanLeave(g, {true, false, false, false, false}, all));
  EXPECT_FALSE(CanLeave(g, {false, false, true, false, false}, all));
  // Absent blockers do not block.
  const std::vector<bool> no0 = {false, true, true, true, true};
  EXPECT_TRUE(CanLeave(g, {false, false, true, false, false}, no0));
  EXPECT_EQ(BlockingClosure(g, 2, no0), (std::vector<int>{2}));
  EXPECT_EQ(StronglyConnectedComponents(g, no0),
            (std::vector<std::vector<int>>{{1}, {2}, {3}, {4}}));
  // A fixed part never leaves.
  g.fixed[3] = true;
  EXPECT_FALSE(CanLeave(g, {false, false, false, true, false}, all));
  EXPECT_THROW(CanLeave(g, {true}, all), std::invalid_argument);
  EXPECT_THROW(BlockingClosure(g, 7, all), std::invalid_argument);
}

TEST(BlockingGraph, RejectsZeroDirection) {
  const Assembly assembly = Example("paper_fig1.json");
  const Configuration config = Configuration::Assembled(assembly);
  EXPECT_THROW(ComputeBlockingGraph(assembly, config, Vector3(0, 0, 1), BlockingKind::kInfinity),
               std::invalid_argument);  // 2-D: z is ignored
  EXPECT_THROW(ComputeBlockingGraph(assembly, config, Vector3(NAN, 1, 0), BlockingKind::kInfinity),
               std::invalid_argument);
}

bool SameNdbg(const Ndbg& a, const Ndbg& b) {
  if (a.dimension != b.dimension || a.normals != b.normals || a.cells.size() != b.cells.size())
    return false;
  for (size_t c = 0; c < a.cells.size(); ++c) {
    const NdbgCell &x = a.cells[c], &y = b.cells[c];
    if (x.cell_dimension != y.cell_dimension || x.direction != y.direction ||
        x.angle_from != y.angle_from || x.angle_to != y.angle_to || x.signs != y.signs ||
        x.infinitesimal.blockers != y.infinitesimal.blockers ||
        x.infinity.blockers != y.infinity.blockers || x.removable != y.removable)
      return false;
  }
  return true;
}

TEST(Ndbg, DeterministicAcrossRuns) {
  for (const char* name : {"paper_fig1.json", "l_shapes.json", "paper_fig9.json"}) {
    SCOPED_TRACE(name);
    const Assembly assembly = Example(name);
    const Configuration config = Configuration::Assembled(assembly);
    const Ndbg first = ComputeNdbg(assembly, config);
    EXPECT_FALSE(first.cells.empty());
    EXPECT_TRUE(SameNdbg(first, ComputeNdbg(assembly, config)));
    // A copy of the assembly (another object, the same model) too.
    const Assembly copy = Example(name);
    EXPECT_TRUE(SameNdbg(first, ComputeNdbg(copy, Configuration::Assembled(copy))));
  }
}

// Postconditions on every bundled example: infinitesimal ⊆ infinity, the
// removable parts are exactly the movable ones without arcs, and the 2-D
// cells agree with DBG(d) computed directly.
TEST(Ndbg, PostconditionsOnExamples) {
  for (const char* name : {"paper_fig1.json", "paper_fig4.json", "paper_fig6.json",
                           "paper_fig9.json", "stack3.json", "ladder.json", "l_shapes.json"}) {
    SCOPED_TRACE(name);
    const Assembly assembly = Example(name);
    const Configuration config = Configuration::Assembled(assembly);
    const Ndbg ndbg = ComputeNdbg(assembly, config);
    for (const NdbgCell& cell : ndbg.cells) {
      for (int i = 0; i < assembly.num_parts(); ++i) {
        const Part& p = assembly.part(i);
        const bool removable = std::binary_search(cell.removable.begin(), cell.removable.end(), i);
        EXPECT_EQ(removable, !p.fixed && !p.tool && cell.infinity.blockers[i].empty());
      }
    }
    if (ndbg.dimension == 2) ExpectConsistent(assembly, config, ndbg);
  }
}

// The NDBG as text, every number to the last bit: two computations that
// agree on it agree on everything the reports show.
std::string NdbgText(const Ndbg& ndbg) {
  std::string out;
  char buf[96];
  const auto vec = [&](const Vector3& v) {
    std::snprintf(buf, sizeof buf, "(%.17g %.17g %.17g)", v.x(), v.y(), v.z());
    out += buf;
  };
  const auto graph = [&](const BlockingGraph& g) {
    for (size_t i = 0; i < g.blockers.size(); ++i)
      for (const int j : g.blockers[i]) out += " " + std::to_string(i) + ">" + std::to_string(j);
  };
  for (const Vector3& n : ndbg.normals) vec(n);
  out += "\n";
  for (const NdbgCell& c : ndbg.cells) {
    std::snprintf(buf, sizeof buf, "%d %.17g %.17g ", c.cell_dimension, c.angle_from, c.angle_to);
    out += buf;
    vec(c.direction);
    for (const int s : c.signs) out += " " + std::to_string(s);
    out += " |";
    graph(c.infinitesimal);
    out += " |";
    graph(c.infinity);
    out += " | removable";
    for (const int r : c.removable) out += " " + std::to_string(r);
    out += "\n";
  }
  return out;
}

// FNV-1a, 64 bits.
std::uint64_t Fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

// Every bundled example's NDBG, recorded from the exhaustive computation
// (every pair tested at every candidate direction and arc middle): the cell
// count, the parts removable along some cell, and a hash of the whole NDBG
// to the last bit (NdbgText). The faster search of convex pairs' swept
// relation and the cached separating axes must give exactly these. (The
// hashes were taken again when candidates became the tangents of convex
// pieces: the cells, their graphs and removable parts stayed the same, and
// canonical angles moved by roundoff, 6e-14° at most. Fig. 4's again when
// the contacts of two movable parts came to be computed from the side of the
// part whose box comes first: `cairn blocking` prints the same text and JSON
// as before, byte for byte; only the order of Fig. 4's contacts within a pair,
// which the text hashed here lists, changed.)
TEST(Ndbg, BundledExamplesAsRecorded) {
  struct Recorded {
    const char* name;
    size_t cells;
    std::vector<int> removable_somewhere;
    std::uint64_t hash;
  };
  const std::vector<Recorded> recorded = {
      {"flush_joint.json", 24, {2, 3}, 0xb7619af0ad4109f8ull},
      {"flush_joint_wall.json", 32, {4}, 0xc43773cfa057c279ull},
      {"incline.json", 4, {1}, 0x8a82831bcd72db7full},
      {"incline_slides.json", 4, {1}, 0xde5321de9d780e51ull},
      {"jenga.json",
       3,
       {1,  2,  3,  6,  7,  8,  9,  12, 13, 14, 15, 18, 19, 20, 21, 24, 25, 26, 27,
        30, 31, 32, 33, 36, 37, 38, 39, 42, 43, 44, 45, 48, 49, 50, 51, 52, 53, 54},
       0x7a981c7b6ba8e608ull},
      {"l_shapes.json", 8, {0, 1}, 0x912a7bba9b89fdc8ull},
      {"ladder.json", 8, {2}, 0xfdfac7043a511918ull},
      {"overhang.json", 4, {1}, 0x1aa5812d6aa529acull},
      {"overhang_tips.json", 4, {1}, 0x1aa5812d6aa529acull},
      {"paper_fig1.json", 48, {1, 2, 3, 4}, 0x962cd972c9be1ccfull},
      {"paper_fig14.json", 76, {1, 2, 3, 4, 5}, 0x007105e3c28fbdd3ull},
      {"paper_fig15.json", 12, {1, 2}, 0x0d1e8af57626e9cfull},
      {"paper_fig16.json", 12, {1, 2}, 0x0d1e8af57626e9cfull},
      {"paper_fig17.json", 48, {1, 2, 3, 4}, 0x2d984fece917f131ull},
      {"paper_fig19.json", 16, {2, 3}, 0x1ca2ac99632d3c33ull},
      {"paper_fig4.json", 40, {1, 3}, 0x6addbbac6a93388dull},
      {"paper_fig4_fixels.json", 40, {1, 3}, 0x6addbbac6a93388dull},
      {"paper_fig6.json", 72, {3, 4, 5}, 0xb9630488de85b80cull},
      {"paper_fig9.json", 3, {1, 2, 3}, 0x1a7b3afd999ea07eull},
      {"peg_in_slot.json", 4, {1}, 0x8bfb9cd73ca6093dull},
      {"pyramid10.json", 164, {1, 4, 5, 7, 8, 9, 10}, 0x9fc44730281d5b2cull},
      {"pyramid14.json", 236, {1, 5, 6, 9, 10, 12, 13, 14}, 0xd13b3120acc929d0ull},
      {"stack3.json", 28, {1, 2, 3}, 0x219ae85219a4c3dfull},
      {"stack3_tips.json", 28, {1, 2, 3}, 0xe22dd04b1276b660ull},
      {"wall.json",
       1056,
       {1,  10, 11, 21, 22, 31, 32, 42, 43,  52,  53,  63,  64,  73, 74,
        84, 85, 94, 95, 96, 97, 98, 99, 100, 101, 102, 103, 104, 105},
       0x3c3bbde83431711cull},
  };
  for (const Recorded& r : recorded) {
    SCOPED_TRACE(r.name);
    const Assembly assembly = Example(r.name);
    const Ndbg ndbg = ComputeNdbg(assembly, Configuration::Assembled(assembly));
    std::set<int> removable;
    for (const NdbgCell& c : ndbg.cells) removable.insert(c.removable.begin(), c.removable.end());
    const std::uint64_t hash = Fnv1a(NdbgText(ndbg));
    EXPECT_EQ(ndbg.cells.size(), r.cells);
    EXPECT_EQ(std::vector<int>(removable.begin(), removable.end()), r.removable_somewhere);
    EXPECT_EQ(hash, r.hash);
  }
}

// A regular n-gon of radius r about (x, y), counter-clockwise.
PartDef NGon(const std::string& name, int n, double x, double y, double r) {
  PartDef p;
  p.name = name;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    p.polygon.push_back({x + r * std::cos(a), y + r * std::sin(a)});
  }
  return p;
}

// A part that touches nothing changes no other pair's relation: every cell
// of the NDBG with a free n-gon added has, among the other parts, the graphs
// of the scene without it at the cell's direction; and the n-gon's own arcs
// are those of DBG(d) computed directly (ExpectConsistent), beside the
// slot's walls (a non-convex part: every direction tested) and beside convex
// blocks (a convex pair: its run of directions searched).
TEST(Ndbg, FreePolygonChangesNoOtherPair) {
  const AssemblyDef base = ReadSceneDef(ExamplePath("paper_fig4.json"));
  const Assembly without = Assembly::Create(base);
  const Configuration config0 = Configuration::Assembled(without);
  const int n0 = without.num_parts();
  // Outside the slot (beside D), and in it, above the blocks.
  for (const auto& [x, y] : {std::pair(13.0, 1.5), std::pair(5.0, 6.5)}) {
    SCOPED_TRACE("n-gon at " + std::to_string(x) + ", " + std::to_string(y));
    AssemblyDef def = base;
    def.parts.push_back(NGon("free", 60, x, y, 0.9));
    const Assembly with = Assembly::Create(def);
    const Configuration config = Configuration::Assembled(with);
    const Ndbg ndbg = ComputeNdbg(with, config);
    ExpectConsistent(with, config, ndbg);
    for (const NdbgCell& cell : ndbg.cells) {
      for (const BlockingKind kind : {BlockingKind::kInfinitesimal, BlockingKind::kInfinity}) {
        const BlockingGraph alone = ComputeBlockingGraph(without, config0, cell.direction, kind);
        const BlockingGraph& got =
            kind == BlockingKind::kInfinity ? cell.infinity : cell.infinitesimal;
        for (int i = 0; i < n0; ++i) {
          std::vector<int> others;
          for (const int j : got.blockers[i])
            if (j < n0) others.push_back(j);
          EXPECT_EQ(others, alone.blockers[i]) << to_string(kind) << " part " << i;
        }
      }
    }
  }
}

// A many-sided part beside a non-convex one (Fig. 4's slot): free above the
// slot, and resting on a vertex on the top of a post. The cells do not
// multiply with the sides (the relation of two convex pieces changes only
// at the two tangents to their difference, not at every pair of vertices),
// and every open cell is one: the graphs computed directly at a quarter and
// at three quarters of its arc are the cell's.
TEST(Ndbg, ManySidedPolygonBesideANonConvexPart) {
  const AssemblyDef base = ReadSceneDef(ExamplePath("paper_fig4.json"));
  for (const auto& [x, y, r] : {std::tuple(7.0, 5.0, 1.0), std::tuple(9.5, 4.5, 0.5)}) {
    size_t cells_of_few = 0;
    for (const int n : {8, 2000}) {
      SCOPED_TRACE(std::to_string(n) + "-gon at " + std::to_string(x) + ", " + std::to_string(y));
      AssemblyDef def = base;
      def.parts[1] = NGon("A", n, x, y, r);
      const Assembly assembly = Assembly::Create(def);
      const Configuration config = Configuration::Assembled(assembly);
      const Ndbg ndbg = ComputeNdbg(assembly, config);
      ExpectConsistent(assembly, config, ndbg);
      if (n == 8) cells_of_few = ndbg.cells.size();
      EXPECT_LE(ndbg.cells.size(), cells_of_few + 8);
      for (const NdbgCell& cell : ndbg.cells) {
        if (cell.cell_dimension != 1) continue;
        double span = cell.angle_to - cell.angle_from;
        if (span <= 0) span += 2 * std::numbers::pi;
        for (const double at : {0.25, 0.75}) {
          const double a = cell.angle_from + at * span;
          const Vector3 d(std::cos(a), std::sin(a), 0);
          EXPECT_EQ(Arcs(ComputeBlockingGraph(assembly, config, d, BlockingKind::kInfinity)),
                    Arcs(cell.infinity))
              << "at " << a * 180 / std::numbers::pi << "°";
        }
      }
    }
  }
}

// The checkpoint is called while the NDBG is computed, and what it throws
// ends the computation and passes through (`cairn batch --job-timeout`).
TEST(Ndbg, CheckpointIsPolledAndMayAbandon) {
  struct Abandon {};
  for (const char* name : {"paper_fig4.json", "jenga.json"}) {
    SCOPED_TRACE(name);
    const Assembly assembly = Example(name);
    const Configuration config = Configuration::Assembled(assembly);
    int calls = 0;
    const Ndbg full = ComputeNdbg(assembly, config, [&] { ++calls; });
    EXPECT_GT(calls, assembly.num_parts());
    EXPECT_TRUE(SameNdbg(full, ComputeNdbg(assembly, config)));
    for (const int stop_at : {1, calls / 2, calls}) {
      int left = stop_at;
      EXPECT_THROW(ComputeNdbg(assembly, config,
                               [&] {
                                 if (--left == 0) throw Abandon{};
                               }),
                   Abandon);
    }
    int at_calls = 0;
    ComputeBlockingAt(assembly, config, Vector3(0, 1, 0.5), [&] { ++at_calls; });
    EXPECT_GT(at_calls, 0);
  }
}

}  // namespace
}  // namespace cairn

#pragma once
/// @file
/// BoxGrid: a uniform grid over axis-aligned boxes (a part's faces, edges or
/// triangles), so that the boxes that may come within a tolerance of a
/// query box are found without testing every one. Each box, grown by the
/// tolerance, is entered into the cells it covers; a query returns, in
/// ascending order and once each, the boxes that share a cell with it: a
/// superset of the boxes within the tolerance of the query (callers still
/// test their boxes exactly), in the order of a loop over all of them, so
/// that what a caller finds, and its order, are those of that loop. About
/// one box per cell: a pair of meshes of n faces costs O(n + pairs found)
/// instead of O(n²).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "cairn/core/types.h"

namespace cairn {

class BoxGrid {
 public:
  /// The boxes [lo[k], hi[k]] (length), each grown by `tol` (length).
  BoxGrid(const std::vector<Vector3>& lo, const std::vector<Vector3>& hi, double tol);

  /// The boxes that share a cell with [lo, hi], ascending, each once. The
  /// reference is valid until the next query (one thread at a time).
  const std::vector<int>& Query(const Vector3& lo, const Vector3& hi) const;
  /// The same boxes in no particular order (cheaper: not sorted), for a
  /// caller whose answer does not depend on the order.
  const std::vector<int>& QueryUnordered(const Vector3& lo, const Vector3& hi) const;

 private:
  int Cell(double x, int d) const;
  template <typename Fn>
  void ForCells(const Vector3& lo, const Vector3& hi, const Fn& fn) const {
    const int x0 = Cell(lo.x(), 0), x1 = Cell(hi.x(), 0), y0 = Cell(lo.y(), 1),
              y1 = Cell(hi.y(), 1), z0 = Cell(lo.z(), 2), z1 = Cell(hi.z(), 2);
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y)
        for (int z = z0; z <= z1; ++z) fn((static_cast<size_t>(x) * dims_[1] + y) * dims_[2] + z);
  }

  Vector3 lo_{0, 0, 0}, hi_{0, 0, 0}, cell_{0, 0, 0};
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::vector<int>> cells_;
  mutable std::vector<unsigned> stamp_;
  mutable unsigned query_ = 0;
  mutable std::vector<int> found_;
};

}  // namespace cairn

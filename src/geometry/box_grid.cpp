#include "cairn/geometry/box_grid.h"

namespace cairn {

namespace {
// The most cells along one axis (a grid of at most 256³ cells; about as many
// cells as boxes in all).
constexpr int kMaxCellsPerAxis = 256;
}  // namespace

BoxGrid::BoxGrid(const std::vector<Vector3>& lo, const std::vector<Vector3>& hi, double tol)
    : stamp_(lo.size(), 0) {
  const int n = static_cast<int>(lo.size());
  if (n == 0) return;
  lo_ = lo[0];
  hi_ = hi[0];
  for (int k = 0; k < n; ++k) {
    lo_ = lo_.cwiseMin(lo[k]);
    hi_ = hi_.cwiseMax(hi[k]);
  }
  lo_.array() -= tol;
  hi_.array() += tol;
  const Vector3 extent = hi_ - lo_;
  const double side = extent.maxCoeff() / std::max(1.0, std::cbrt(static_cast<double>(n)));
  for (int d = 0; d < 3; ++d) {
    dims_[d] = side > 0
                   ? std::clamp(static_cast<int>(std::ceil(extent[d] / side)), 1, kMaxCellsPerAxis)
                   : 1;
    cell_[d] = extent[d] / dims_[d];
  }
  cells_.resize(static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2]);
  for (int k = 0; k < n; ++k) {
    const Vector3 box_lo = lo[k].array() - tol, box_hi = hi[k].array() + tol;
    ForCells(box_lo, box_hi, [&](size_t c) { cells_[c].push_back(k); });
  }
}

const std::vector<int>& BoxGrid::Query(const Vector3& lo, const Vector3& hi) const {
  QueryUnordered(lo, hi);
  std::sort(found_.begin(), found_.end());
  return found_;
}

const std::vector<int>& BoxGrid::QueryUnordered(const Vector3& lo, const Vector3& hi) const {
  found_.clear();
  if (cells_.empty() || (lo.array() > hi_.array()).any() || (hi.array() < lo_.array()).any())
    return found_;
  if (++query_ == 0) {  // wrapped round: every stamp is old again
    std::fill(stamp_.begin(), stamp_.end(), 0u);
    query_ = 1;
  }
  ForCells(lo, hi, [&](size_t c) {
    for (const int k : cells_[c])
      if (stamp_[k] != query_) {
        stamp_[k] = query_;
        found_.push_back(k);
      }
  });
  return found_;
}

int BoxGrid::Cell(double x, int d) const {
  if (!(cell_[d] > 0)) return 0;
  const double i = std::floor((x - lo_[d]) / cell_[d]);
  return static_cast<int>(std::clamp(i, 0.0, static_cast<double>(dims_[d] - 1)));
}

}  // namespace cairn

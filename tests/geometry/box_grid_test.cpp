// geometry/box_grid.h: the grid finds every box within the tolerance of a
// query (what a loop over all of them would), ascending, once each.
#include "cairn/geometry/box_grid.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace cairn {
namespace {

bool Near(const Vector3& lo1, const Vector3& hi1, const Vector3& lo2, const Vector3& hi2,
          double tol) {
  return !((lo1.array() > hi2.array() + tol).any() || (lo2.array() > hi1.array() + tol).any());
}

// Random boxes of mixed sizes (slivers, a box over everything), in a flat
// layer and in space: every box near a query is found, in order, once.
TEST(BoxGrid, FindsEveryBoxALoopWouldInItsOrder) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> at(-10, 10), size(0, 0.5);
  for (const bool flat : {false, true}) {
    std::vector<Vector3> lo, hi;
    for (int k = 0; k < 2000; ++k) {
      const Vector3 c(at(rng), at(rng), flat ? 0.0 : at(rng));
      const Vector3 h(size(rng), k % 7 == 0 ? 0.0 : size(rng), flat ? 0.0 : size(rng));
      lo.push_back(c - h);
      hi.push_back(c + h);
    }
    lo.push_back(Vector3(-10, -10, flat ? 0 : -10));  // one box over all the others
    hi.push_back(Vector3(10, 10, flat ? 0 : 10));
    const double tol = 1e-3;
    const BoxGrid grid(lo, hi, tol);
    for (int q = 0; q < 300; ++q) {
      const Vector3 c(at(rng), at(rng), flat ? 0.0 : at(rng));
      const Vector3 h = q % 3 == 0 ? Vector3::Zero() : Vector3(size(rng), size(rng), size(rng));
      const std::vector<int> found = grid.Query(c - h, c + h);
      for (size_t i = 1; i < found.size(); ++i) ASSERT_LT(found[i - 1], found[i]);
      size_t next = 0;
      for (int k = 0; k < static_cast<int>(lo.size()); ++k) {
        if (!Near(c - h, c + h, lo[k], hi[k], tol)) continue;
        while (next < found.size() && found[next] < k) ++next;
        ASSERT_TRUE(next < found.size() && found[next] == k) << "box " << k << ", query " << q;
      }
    }
  }
}

TEST(BoxGrid, NothingFromAnEmptyGridOrFarAway) {
  const BoxGrid empty({}, {}, 0.1);
  EXPECT_TRUE(empty.Query(Vector3::Zero(), Vector3::Ones()).empty());
  const BoxGrid one({Vector3::Zero()}, {Vector3::Ones()}, 0.1);
  EXPECT_EQ(one.Query(Vector3(1.05, 0.5, 0.5), Vector3(1.05, 0.5, 0.5)), std::vector<int>{0});
  EXPECT_TRUE(one.Query(Vector3(2, 2, 2), Vector3(3, 3, 3)).empty());
}

}  // namespace
}  // namespace cairn

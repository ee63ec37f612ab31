#include "cairn/geometry/mesh_faces.h"

#include <Eigen/Geometry>  // IWYU pragma: keep
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <utility>

#include "cairn/geometry/polygon.h"

namespace cairn {

namespace {

std::uint64_t EdgeKey(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

// The boundary of a region as one closed loop of vertex indices, in the
// triangles' orientation; empty when the boundary is not a single simple loop
// (a hole, or a vertex where the boundary touches itself).
std::vector<int> BoundaryLoop(const std::vector<std::array<int, 3>>& triangles,
                              const std::vector<int>& region) {
  std::unordered_map<std::uint64_t, int> directed;  // edge a→b → count in the region
  for (int t : region)
    for (int k = 0; k < 3; ++k) ++directed[EdgeKey(triangles[t][k], triangles[t][(k + 1) % 3])];
  // Boundary edges: a→b whose b→a is not in the region.
  std::map<int, int> next;  // a → b (ordered, so the loop starts at the same vertex every run)
  int boundary_edges = 0;
  for (int t : region)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      if (directed.count(EdgeKey(b, a))) continue;
      if (next.count(a)) return {};  // two boundary edges leave a: pinched
      next[a] = b;
      ++boundary_edges;
    }
  if (next.empty()) return {};
  std::vector<int> loop;
  int v = next.begin()->first;
  for (int steps = 0; steps <= boundary_edges; ++steps) {
    loop.push_back(v);
    const auto it = next.find(v);
    if (it == next.end()) return {};
    v = it->second;
    if (v == loop.front()) break;
  }
  if (v != loop.front() || static_cast<int>(loop.size()) != boundary_edges) return {};  // holes
  return loop;
}

// True when the loop, seen in its plane (normal n), is a simple polygon to
// within length_tol: a single loop of edges can still touch itself in the
// plane, where many thin triangles meet at a point (a cone's apex
// tessellated finely), and Polyhedron::Check would refuse the face.
bool LoopIsSimple(const std::vector<Vector3>& vertices, const std::vector<int>& loop,
                  const Vector3& n, double length_tol) {
  const Vector3 u = n.unitOrthogonal(), v = n.cross(u);
  Polygon flat;
  for (const int i : loop) flat.push_back(Vector2(u.dot(vertices[i]), v.dot(vertices[i])));
  return !FindSelfIntersection(flat, length_tol).has_value();
}

}  // namespace

PolyhedronDef MergeCoplanarTriangles(const std::vector<Vector3>& vertices,
                                     const std::vector<std::array<int, 3>>& triangles,
                                     double angle_tol, double length_tol, MeshMergeStats* stats) {
  MeshMergeStats st;
  st.triangles_in = static_cast<int>(triangles.size());
  PolyhedronDef out;
  out.vertices = vertices;

  // Unit normals; degenerate triangles are dropped.
  const int nt = static_cast<int>(triangles.size());
  std::vector<Vector3> normal(nt);
  std::vector<bool> alive(nt, false);
  for (int t = 0; t < nt; ++t) {
    const Vector3& a = vertices[triangles[t][0]];
    const Vector3 n = (vertices[triangles[t][1]] - a).cross(vertices[triangles[t][2]] - a);
    if (n.norm() <= length_tol * length_tol) {
      ++st.degenerate_dropped;
      continue;
    }
    normal[t] = n.normalized();
    alive[t] = true;
  }
  // Triangles on the same three vertices: a copy with the same orientation
  // is the same face written twice (keep the first); one with the opposite
  // orientation is the other side of an internal wall (drop both).
  std::map<std::array<int, 3>, std::vector<int>> by_corners;
  for (int t = 0; t < nt; ++t) {
    if (!alive[t]) continue;
    std::array<int, 3> key = triangles[t];
    std::sort(key.begin(), key.end());
    by_corners[key].push_back(t);
  }
  for (const auto& [key, same] : by_corners) {
    if (same.size() < 2) continue;
    // The orientation of a triangle: its corners rotated to start at the
    // least index, then whether the next is the second least.
    const int second = key[1];
    const auto forward = [&](int t) {
      const auto& c = triangles[t];
      const int k = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
      return c[(k + 1) % 3] == second;
    };
    int ahead = 0, back = 0;
    for (const int t : same) (forward(t) ? ahead : back)++;
    // Pairs of opposite orientation cancel; of what is left (all of one
    // orientation) one triangle is the face, the others its copies.
    const int internal = 2 * std::min(ahead, back);
    const bool keep_ahead = ahead > back;
    int keep = ahead == back ? 0 : 1;
    for (const int t : same) {
      if (keep > 0 && forward(t) == keep_ahead) {
        --keep;
        continue;
      }
      alive[t] = false;
    }
    st.internal_dropped += internal;
    st.duplicates_dropped += std::abs(ahead - back) - (ahead == back ? 0 : 1);
  }
  // Triangles on each undirected edge.
  std::unordered_map<std::uint64_t, std::vector<int>> on_edge;
  for (int t = 0; t < nt; ++t) {
    if (!alive[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      on_edge[EdgeKey(std::min(a, b), std::max(a, b))].push_back(t);
    }
  }
  // Grow regions from each unvisited triangle, in index order (deterministic).
  const double cos_tol = std::cos(angle_tol);
  std::vector<bool> done(nt, false);
  for (int seed = 0; seed < nt; ++seed) {
    if (!alive[seed] || done[seed]) continue;
    const Vector3 n0 = normal[seed];
    const double d0 = n0.dot(vertices[triangles[seed][0]]);
    std::vector<int> region{seed}, stack{seed};
    done[seed] = true;
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        for (int u : on_edge[EdgeKey(std::min(a, b), std::max(a, b))]) {
          if (done[u] || normal[u].dot(n0) < cos_tol) continue;
          bool on_plane = true;
          for (int j = 0; j < 3; ++j)
            on_plane = on_plane && std::abs(n0.dot(vertices[triangles[u][j]]) - d0) <= length_tol;
          if (!on_plane) continue;
          done[u] = true;
          region.push_back(u);
          stack.push_back(u);
        }
      }
    }
    std::vector<int> loop =
        region.size() > 1 ? BoundaryLoop(triangles, region) : std::vector<int>{};
    if (loop.size() >= 3 && !LoopIsSimple(vertices, loop, n0, length_tol)) {
      loop.clear();
      ++st.regions_kept_as_triangles;
      for (int t : region) out.faces.push_back({triangles[t][0], triangles[t][1], triangles[t][2]});
      continue;
    }
    if (loop.size() >= 3) {
      out.faces.push_back(std::move(loop));
    } else {
      if (region.size() > 1) ++st.regions_kept_as_triangles;
      for (int t : region) out.faces.push_back({triangles[t][0], triangles[t][1], triangles[t][2]});
    }
  }
  st.faces_out = static_cast<int>(out.faces.size());
  if (stats) *stats = st;
  return out;
}

}  // namespace cairn

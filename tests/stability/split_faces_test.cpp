// The bundled example scenes with their faces split into more polygons: the
// same solids, so the same contacts and the same verdict (issue 31: a
// vertex inside a straight edge, lying on the edge of a neighbour's face it
// is beside, made a contact whose normal held a falling cube up).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/contact/detect_contacts.h"
#include "cairn/io/scene_reader.h"
#include "cairn/stability/analyze.h"
#include "test_paths.h"

namespace cairn {
namespace {

// Every edge cut at its midpoint: 2-D, each polygon edge; 3-D, each edge in
// both of its faces (one new vertex per edge, so the solid stays closed).
void SplitEveryEdge(PartDef& part) {
  if (!part.polygon.empty()) {
    Polygon split;
    for (size_t k = 0; k < part.polygon.size(); ++k) {
      split.push_back(part.polygon[k]);
      split.push_back(0.5 * (part.polygon[k] + part.polygon[(k + 1) % part.polygon.size()]));
    }
    part.polygon = split;
    return;
  }
  PolyhedronDef& p = *part.polyhedron;
  std::map<std::pair<int, int>, int> middle;
  for (auto& face : p.faces) {
    std::vector<int> split;
    for (size_t k = 0; k < face.size(); ++k) {
      const int a = face[k], b = face[(k + 1) % face.size()];
      const auto key = std::minmax(a, b);
      auto it = middle.find(key);
      if (it == middle.end()) {
        it = middle.emplace(key, static_cast<int>(p.vertices.size())).first;
        p.vertices.push_back(0.5 * (p.vertices[a] + p.vertices[b]));
      }
      split.push_back(a);
      split.push_back(it->second);
    }
    face = split;
  }
}

// 3-D: every convex face of four or more vertices cut into a fan of
// triangles from its first vertex.
void TriangulateFaces(PartDef& part) {
  if (!part.polyhedron) return;
  PolyhedronDef& p = *part.polyhedron;
  std::vector<std::vector<int>> faces;
  for (const auto& face : p.faces) {
    const size_t m = face.size();
    const Vector3 n = (p.vertices[face[1]] - p.vertices[face[0]])
                          .cross(p.vertices[face[2]] - p.vertices[face[1]]);
    bool convex = m > 3;
    for (size_t k = 0; k < m && convex; ++k) {
      const Vector3& a = p.vertices[face[k]];
      const Vector3& b = p.vertices[face[(k + 1) % m]];
      const Vector3& c = p.vertices[face[(k + 2) % m]];
      convex = (b - a).cross(c - b).dot(n) > 0;
    }
    if (!convex) {
      faces.push_back(face);
      continue;
    }
    for (size_t k = 1; k + 1 < m; ++k) faces.push_back({face[0], face[k], face[k + 1]});
  }
  p.faces = faces;
}

// The corners of the convex hull of points of one plane (u, w: a basis of
// it), without the points on its edges: Andrew's monotone chain on the
// points' coordinates rounded to `unit` (integers: exact turns), turning
// strictly left. Collinear points give the two ends of their segment.
std::vector<Vector3> HullCorners(const std::vector<Vector3>& points, const Vector3& u,
                                 const Vector3& w, double unit) {
  using Grid = std::array<long long, 2>;
  std::vector<std::pair<Grid, Vector3>> p;
  for (const Vector3& x : points)
    p.push_back({Grid{std::llround(x.dot(u) / unit), std::llround(x.dot(w) / unit)}, x});
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  p.erase(std::unique(p.begin(), p.end(),
                      [](const auto& a, const auto& b) { return a.first == b.first; }),
          p.end());
  if (p.size() < 3) {
    std::vector<Vector3> ends;
    for (const auto& q : p) ends.push_back(q.second);
    return ends;
  }
  const auto turn = [](const Grid& o, const Grid& a, const Grid& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::pair<Grid, Vector3>> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2].first, hull[k - 1].first, p[i].first) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2].first, hull[k - 1].first, p[i].first) <= 0) --k;
    hull[k++] = p[i];
  }
  std::vector<Vector3> corners;
  for (size_t i = 0; i + 1 < k; ++i) corners.push_back(hull[i].second);
  return corners;
}

// The contacts of a model grouped by pair of parts (names, ascending) and
// normal (from the second part into the first, to 1e-9), each group as the
// corners of its convex hull (rounded to 1e-9 of the scene): interior points
// and points on the hull's edges, which splitting adds, do not count.
using ContactKey = std::tuple<std::string, std::string, long, long, long>;
std::map<ContactKey, std::set<std::tuple<long, long, long>>> Hulls(const Assembly& a) {
  const Tolerances tol = a.MakeTolerances();
  const auto contacts = DetectContacts(a, Configuration::Assembled(a), tol.length, tol.angle);
  std::map<ContactKey, std::vector<Vector3>> groups;
  const auto round = [](double x, double unit) { return std::lround(x / unit); };
  for (const Contact& c : contacts) {
    std::string first = a.part(c.part_a).name;
    std::string second = c.part_b < 0 ? "(fixel)" : a.part(c.part_b).name;
    Vector3 n = c.n_W;
    if (first > second) std::swap(first, second), n = -n;
    groups[{first, second, round(n.x(), 1e-9), round(n.y(), 1e-9), round(n.z(), 1e-9)}].push_back(
        c.p_WC);
  }
  std::map<ContactKey, std::set<std::tuple<long, long, long>>> hulls;
  const double unit = 1e-9 * a.scene_size();
  for (const auto& [key, points] : groups) {
    const Vector3 n = Vector3(std::get<2>(key), std::get<3>(key), std::get<4>(key)).normalized();
    const Vector3 u = n.unitOrthogonal(), w = n.cross(u);
    for (const Vector3& p : HullCorners(points, u, w, unit))
      hulls[key].insert({round(p.x(), unit), round(p.y(), unit), round(p.z(), unit)});
  }
  return hulls;
}

class SplitFaces : public ::testing::TestWithParam<std::string> {};

TEST_P(SplitFaces, GiveTheSameContactsAndVerdict) {
  const std::string path = testing::ExamplePath(GetParam());
  const AssemblyDef def = ReadSceneDef(path);
  const Assembly plain = Assembly::Create(def, path);
  const auto hulls = Hulls(plain);
  const StabilityResult verdict = AnalyzeConfiguration(plain, Configuration::Assembled(plain));
  for (const bool triangulate : {false, true}) {
    if (triangulate && !plain.is_3d()) continue;
    SCOPED_TRACE(triangulate ? "faces cut into triangles" : "edges cut at their midpoints");
    AssemblyDef split_def = def;
    for (PartDef& part : split_def.parts)
      triangulate ? TriangulateFaces(part) : SplitEveryEdge(part);
    const Assembly split = Assembly::Create(split_def, path);
    const auto split_hulls = Hulls(split);
    for (const auto& [key, corners] : hulls) {
      const auto it = split_hulls.find(key);
      EXPECT_TRUE(it != split_hulls.end() && it->second == corners)
          << std::get<0>(key) << " on " << std::get<1>(key) << ", normal (" << std::get<2>(key)
          << ", " << std::get<3>(key) << ", " << std::get<4>(key)
          << ") e-9: " << (it == split_hulls.end() ? "gone" : "other corners")
          << ::testing::PrintToString(corners) << " vs "
          << (it == split_hulls.end() ? "" : ::testing::PrintToString(it->second));
    }
    for (const auto& [key, corners] : split_hulls)
      EXPECT_TRUE(hulls.count(key))
          << std::get<0>(key) << " on " << std::get<1>(key) << ", normal (" << std::get<2>(key)
          << ", " << std::get<3>(key) << ", " << std::get<4>(key) << ") e-9: new";
    const StabilityResult r = AnalyzeConfiguration(split, Configuration::Assembled(split));
    EXPECT_EQ(r.verdict, verdict.verdict);
    EXPECT_EQ(r.weakly_stable, verdict.weakly_stable);
  }
}

std::vector<std::string> ExampleScenes() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(testing::SourcePath("examples")))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Examples, SplitFaces, ::testing::ValuesIn(ExampleScenes()),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param.substr(0, param.param.size() - 5);
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace cairn

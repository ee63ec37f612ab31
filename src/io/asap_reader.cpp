#include "cairn/io/asap_reader.h"

#include <Eigen/Geometry>  // IWYU pragma: keep
#include <algorithm>
#include <filesystem>

#include "cairn/core/error.h"
#include "cairn/io/mesh_reader.h"
#include "io/json_checks.h"

namespace cairn {

namespace {

using io_internal::Child;
using io_internal::Index;
using io_internal::JsonChecker;
using nlohmann::json;

// Part keys in numeric order when they are numbers ("2" before "10"), else
// as text.
bool KeyLess(const std::string& a, const std::string& b) {
  const auto numeric = [](const std::string& s) {
    return !s.empty() && s.size() <= 18 &&
           std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  const bool na = numeric(a), nb = numeric(b);
  if (na && nb && a.size() != b.size()) return a.size() < b.size();
  if (na != nb) return na;
  return a < b;
}

// The pose of `final_state` [x, y, z, rx, ry, rz]: p_world = R p + t with
// R = Rz(rz) Ry(ry) Rx(rx).
Eigen::Isometry3d FinalPose(const json& state, const std::string& path, const JsonChecker& check) {
  check.Array(state, path);
  if (state.size() != 6)
    check.Fail(path,
               "must have 6 numbers [x, y, z, rx, ry, rz], not " + std::to_string(state.size()));
  double v[6];
  for (size_t k = 0; k < 6; ++k)
    v[k] =
        k < 3 ? check.Coordinate(state[k], Index(path, k)) : check.Number(state[k], Index(path, k));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      (Eigen::AngleAxisd(v[5], Vector3::UnitZ()) * Eigen::AngleAxisd(v[4], Vector3::UnitY()) *
       Eigen::AngleAxisd(v[3], Vector3::UnitX()))
          .toRotationMatrix();
  pose.translation() = Vector3(v[0], v[1], v[2]);
  return pose;
}

}  // namespace

AssemblyDef ReadAsapAssembly(const std::string& path, std::uint64_t max_input_size) {
  std::filesystem::path config = path;
  if (IsDirectory(path)) config /= "config.json";
  const std::string file = config.string();
  const json doc = io_internal::ReadJsonFile(file, max_input_size);
  const JsonChecker check(file);
  check.Object(doc, "");
  if (doc.empty()) check.Fail("", "has no parts (an ASAP config.json maps part keys to poses)");
  std::vector<std::string> keys;
  for (const auto& item : doc.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end(), KeyLess);
  AssemblyDef def;
  def.name = config.parent_path().filename().string();
  const std::filesystem::path folder = config.parent_path();
  for (const std::string& key : keys) {
    const std::string part_path = Child("", key);
    const json& part = check.Object(doc[key], part_path);
    const Eigen::Isometry3d pose = FinalPose(check.Require(part, "final_state", part_path),
                                             Child(part_path, "final_state"), check);
    const std::string mesh = (folder / (key + ".obj")).lexically_normal().string();
    PartDef p;
    p.name = key;
    p.shape_key = "mesh";
    try {
      MeshReadOptions options;
      options.max_input_size = max_input_size;
      MeshMergeStats stats;
      p.polyhedron = ReadMesh(mesh, options, &stats);
      if (std::string note = MeshRepairNote(key, mesh, stats); !note.empty())
        def.notes.push_back(std::move(note));
    } catch (const InputError& e) {
      check.Fail(part_path, "cannot read mesh '" + mesh + "': " + e.message());
    }
    for (Vector3& v : p.polyhedron->vertices) v = pose * v;
    def.parts.push_back(std::move(p));
  }
  return def;
}

}  // namespace cairn

#pragma once
/// @file
/// The model: an immutable, validated Assembly of rigid parts (shapes, mass,
/// materials, fixtures), built once from a plain AssemblyDef by
/// Assembly::Create. Everything that changes during an analysis (poses,
/// contacts, matrices, solver workspaces) lives elsewhere (Configuration and
/// the later stages), so one Assembly can be analysed by many threads.

#include <optional>
#include <string>
#include <vector>

#include "cairn/core/tolerances.h"
#include "cairn/core/types.h"
#include "cairn/geometry/polygon.h"

namespace cairn {

/// A part as the user describes it (scene file `parts[i]`).
struct PartDef {
  std::string name;
  bool fixed = false;  ///< Cannot move (a table, a wall).
  bool tool = false;   ///< A gripper's pad, not part of the assembly: present only while gripped.
  std::optional<double> density;  ///< mass per unit area; default 1.
  std::optional<double> mass;     ///< overrides density.
  Polygon polygon;                ///< World coordinates of the assembled pose, either orientation.
};

/// A fixel: a frictionless unilateral point contact with the fixed world
/// (scene file `fixtures[i]`). It pushes on the part along `normal`.
struct FixtureDef {
  std::string part;
  Vector2 point{0, 0};
  Vector2 normal{0, 0};
};

/// The friction coefficient between two named parts (`friction_pairs[i]`).
struct FrictionPairDef {
  std::string part_a;
  std::string part_b;
  double mu = 0;
};

/// A whole scene as the user describes it. Indices in the vectors are the
/// indices of the JSON arrays they came from, so validation errors can name
/// the JSON path.
struct AssemblyDef {
  std::string name;
  Vector2 gravity{0, -9.81};  ///< length/s²
  double friction = 0;        ///< default Coulomb coefficient (dimensionless)
  std::vector<FrictionPairDef> friction_pairs;
  double tolerance = 0;  ///< contact distance tolerance (length); ≤ 0: scaled to the scene
  std::vector<PartDef> parts;
  std::vector<FixtureDef> fixtures;
};

/// A validated part. Its polygon is counter-clockwise, in world coordinates of
/// the assembled pose.
struct Part {
  std::string name;
  bool fixed = false;
  bool tool = false;       ///< a gripper's pad: absent until a plan step grips it; never judged
  Polygon polygon;         ///< counter-clockwise, world frame (assembled pose)
  double area = 0;         ///< length²
  double mass = 0;         ///< mass units, > 0 (density × area unless the scene gives `mass`)
  Vector2 centroid{0, 0};  ///< p_WBcm: centre of mass in the world frame (assembled pose)
  double inertia = 0;      ///< moment of inertia about the centroid (mass·length²)
};

/// A validated fixture.
struct Fixture {
  int part = -1;         ///< index into Assembly::parts()
  Vector2 point{0, 0};   ///< p_WF, on the part's boundary (assembled pose)
  Vector2 normal{0, 0};  ///< n_W, unit: the direction the fixel pushes the part
};

/// The immutable, validated model.
class Assembly {
 public:
  /// Validates `def` and builds the Assembly. `source_file` is only used in
  /// error messages.
  /// @throws InputError naming the file, the JSON path (e.g.
  ///         `parts[2].polygon[3]`) and what is wrong: duplicate or unknown
  ///         names, fewer than 3 vertices, zero area, self-intersecting
  ///         polygons, NaN or infinite numbers, negative mass, density or
  ///         friction, parts that overlap by more than the tolerance, a fixture
  ///         point off its part or a fixture normal pointing out of it, a
  ///         part that is both fixed and a tool.
  static Assembly Create(const AssemblyDef& def, const std::string& source_file = "");

  const std::string& name() const { return name_; }
  int num_parts() const { return static_cast<int>(parts_.size()); }
  const std::vector<Part>& parts() const { return parts_; }
  const Part& part(int i) const { return parts_.at(i); }
  /// Index of the part with this name, or -1.
  int FindPart(const std::string& name) const;
  const std::vector<Fixture>& fixtures() const { return fixtures_; }
  const Vector2& gravity() const { return gravity_; }
  /// Coulomb coefficient between parts i and j (a friction pair if the scene
  /// names one, else the scene default). j = -1 means the fixed world
  /// (fixtures), which is always frictionless.
  double Friction(int i, int j) const;
  /// True when every contact in the scene is frictionless.
  bool IsFrictionless() const;
  /// The diagonal of the bounding box of all parts (length).
  double scene_size() const { return scene_size_; }
  /// The contact distance tolerance (length): the scene's, or 1e-6 · size.
  double length_tolerance() const { return tolerances_.length; }
  /// All tolerances, scaled to this scene for a time step `dt` (s).
  Tolerances MakeTolerances(double dt = 1.0) const;

 private:
  std::string name_;
  std::vector<Part> parts_;
  std::vector<Fixture> fixtures_;
  Vector2 gravity_{0, -9.81};
  double default_friction_ = 0;
  std::vector<std::pair<std::pair<int, int>, double>> pair_mu_;  // (min, max) index → μ
  double scene_size_ = 0;
  double tolerance_override_ = 0;
  double max_weight_ = 0;
  Tolerances tolerances_;
};

/// Where the parts are in one configuration, and which are present. A pose is
/// the rigid displacement of a part from its assembled pose: a rotation by
/// `rotation` (rad, counter-clockwise) about the part's assembled centroid,
/// then a translation by `translation` (length).
struct Pose2 {
  Vector2 translation{0, 0};
  double rotation = 0;
  /// The world position of a point given at the assembled pose.
  Vector2 Apply(const Vector2& p_assembled, const Vector2& centroid_assembled) const;
};

/// The mutable state of one configuration of an Assembly.
struct Configuration {
  std::vector<bool> present;  ///< (num_parts) false: the part has been taken away
  std::vector<Pose2> poses;   ///< (num_parts)

  /// Every part of the assembly present, at its assembled pose; tools
  /// (Part::tool) absent, also at their assembled (start) poses.
  static Configuration Assembled(const Assembly& assembly);
  /// Part i's polygon in this configuration (world frame, counter-clockwise).
  Polygon WorldPolygon(const Assembly& assembly, int i) const;
  /// Part i's centroid in this configuration (world frame).
  Vector2 WorldCentroid(const Assembly& assembly, int i) const;
};

}  // namespace cairn

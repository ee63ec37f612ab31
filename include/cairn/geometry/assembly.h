#pragma once
/// @file
/// The model: an immutable, validated Assembly of rigid parts (shapes, mass,
/// materials, fixtures), built once from a plain AssemblyDef by
/// Assembly::Create. Everything that changes during an analysis (poses,
/// contacts, matrices, solver workspaces) lives elsewhere (Configuration and
/// the later stages), so one Assembly can be analysed by many threads.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cairn/core/error.h"
#include "cairn/core/tolerances.h"
#include "cairn/core/types.h"
#include "cairn/geometry/polygon.h"
#include "cairn/geometry/polyhedron.h"

namespace cairn {

/// A part as the user describes it (scene file `parts[i]`). A 2-D part has a
/// `polygon`; a 3-D part a `polyhedron` (a scene's `polyhedron`, `box` with 3-D
/// corners, or `mesh`, as the reader turned it into vertices and faces).
struct PartDef {
  std::string name;
  bool fixed = false;  ///< Cannot move (a table, a wall).
  bool tool = false;   ///< A gripper's pad, not part of the assembly: present only while gripped.
  std::optional<double> density;  ///< mass per unit area (2-D) or volume (3-D); default 1.
  std::optional<double> mass;     ///< overrides density.
  Polygon polygon;  ///< 2-D: world coordinates of the assembled pose, either orientation.
  std::optional<PolyhedronDef> polyhedron;  ///< 3-D: world coordinates of the assembled pose.
  /// Where the shape's JSON path points in error messages ("polygon", "box",
  /// "polyhedron", "mesh"); empty: "polygon" or "polyhedron".
  std::string shape_key;
};

/// A fixel: a frictionless unilateral point contact with the fixed world
/// (scene file `fixtures[i]`). It pushes on the part along `normal`. 2-D
/// scenes leave z = 0.
struct FixtureDef {
  std::string part;
  Vector3 point{0, 0, 0};
  Vector3 normal{0, 0, 0};
};

/// A contact interface the model gives rather than Cairn finding it from the
/// shapes (scene file `interfaces[i]`; COMPAS files store them): a planar
/// contact polygon between two parts of the assembled configuration. 3-D
/// only. For models whose shapes are not exact enough to find contacts from
/// (CAD blocks that interpenetrate by more than any sensible tolerance, faces
/// far off plane: the Armadillo vault): with interfaces the contacts are
/// exactly these, and the parts are not checked for overlap.
struct InterfaceDef {
  std::string part_a;
  std::string part_b;
  std::vector<Vector3> points;  ///< the polygon's vertices (≥ 3), world frame, assembled pose
  Vector3 normal{0, 0, 0};      ///< from b into a (normalised on validation)
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
  /// length/s²; default (0, −9.81) in 2-D, (0, 0, −9.81) in 3-D. A 2-D scene
  /// must leave z = 0.
  std::optional<Vector3> gravity;
  double friction = 0;  ///< default Coulomb coefficient (dimensionless)
  /// 3-D: D, the number of edges of the linearised friction cone (Stewart and
  /// Trinkle's pyramid inscribed in the cone), ≥ 3; 0: the default 4. 2-D
  /// scenes always use the two directions ±t.
  int friction_directions = 0;
  std::vector<FrictionPairDef> friction_pairs;
  double tolerance = 0;  ///< contact distance tolerance (length); ≤ 0: scaled to the scene
  /// length: how much deeper than the length tolerance the parts may
  /// interpenetrate and still touch (Tolerances::penetration = the length
  /// tolerance + this); ≤ 0: none. Set by the STEP reader to the chordal
  /// tolerance of its facets; a scene file's `overlap_allowance`.
  double overlap_allowance = 0;
  /// length: how deep parts meant to touch may interpenetrate (beyond the
  /// length tolerance and the overlap allowance) and still be read as
  /// touching: each such overlap becomes contacts on its mid-surface
  /// (docs/contacts.md, "Overlapping meshes") and its depth is listed
  /// (Assembly::touching_overlaps); a deeper one is refused with the pair and
  /// its depth. 3-D only; at most limits::kMaxOverlapDepthFactor of the
  /// smallest part's bounding-box diagonal; ≤ 0: none. `--overlap-depth`, a
  /// scene file's `overlap_depth`.
  double overlap_depth = 0;
  /// The command-line options that set `tolerance`, `gravity` and
  /// `overlap_depth` instead of the file (e.g. "--tolerance"), if any: a
  /// fault of one is then reported against the option, not the file.
  std::string tolerance_option, gravity_option, overlap_depth_option;
  std::vector<PartDef> parts;
  std::vector<FixtureDef> fixtures;
  std::vector<InterfaceDef> interfaces;  ///< given contacts (3-D); empty: found from the shapes
  /// What reading the file did to it that its user should know, one line
  /// each (a mesh's repairs: triangles written twice or both sides of an
  /// internal wall left out); the commands print them as notes.
  std::vector<std::string> notes;
};

/// A validated interface (InterfaceDef).
struct Interface {
  int part_a = -1, part_b = -1;  ///< indices into Assembly::parts()
  std::vector<Vector3> points;   ///< world frame, assembled pose
  Vector3 normal{0, 0, 1};       ///< unit, from b into a
};

/// A validated part, in world coordinates of the assembled pose.
struct Part {
  std::string name;
  bool fixed = false;
  bool tool = false;  ///< a gripper's pad: absent until a plan step grips it; never judged
  Polygon polygon;    ///< 2-D: counter-clockwise, world frame (assembled pose); 3-D: empty
  /// 3-D: the validated, outward-oriented solid (shared: an Assembly is cheap
  /// to copy); 2-D: null.
  std::shared_ptr<const Polyhedron> polyhedron;
  std::vector<Vector3> vertices;  ///< every vertex, world frame (2-D: z = 0)
  double area = 0;                ///< 2-D: area (length²); 3-D: volume (length³)
  double mass = 0;  ///< mass units, > 0 (density × area or volume unless the scene gives `mass`)
  Vector3 centroid{0, 0, 0};  ///< p_WBcm: centre of mass in the world frame (assembled pose)
  /// Inertia tensor about the centroid, world axes of the assembled pose
  /// (mass·length²). 2-D: diag(I, I, I) with I the polar moment (only I_zz
  /// matters to planar motion).
  Matrix3 inertia = Matrix3::Zero();
  double polar_inertia() const { return inertia(2, 2); }  ///< 2-D: I about the centroid
};

/// A validated fixture.
struct Fixture {
  int part = -1;            ///< index into Assembly::parts()
  Vector3 point{0, 0, 0};   ///< p_WF, on the part's boundary (assembled pose)
  Vector3 normal{0, 0, 0};  ///< n_W, unit: the direction the fixel pushes the part
};

/// Two parts of an AssemblyDef that overlap by more than the tolerance.
struct PartOverlap {
  int later = -1, earlier = -1;  ///< indices into AssemblyDef::parts, later > earlier
  Vector3 witness{0, 0, 0};      ///< a point of both (z = 0 in 2-D)
  /// 3-D: how deep the witness lies inside the part it is not on the surface
  /// of (length; a lower bound on the overlap's depth; with an overlap depth,
  /// the deepest sample point's: PolyhedronOverlapDepth); 2-D: 0.
  double depth = 0;
};

/// Assembly::Create's error when parts overlap: every overlapping pair, the
/// one with the lowest indices first (its later part is the JSON path).
class OverlapError : public InputError {
 public:
  OverlapError(std::string file, std::string json_path, std::string message,
               std::vector<PartOverlap> overlaps, double tolerance)
      : InputError(std::move(file), std::move(json_path), std::move(message)),
        overlaps_(std::move(overlaps)),
        tolerance_(tolerance) {}
  const std::vector<PartOverlap>& overlaps() const { return overlaps_; }
  /// length: the depth beyond which parts overlap (the length tolerance plus
  /// the overlap allowance).
  double tolerance() const { return tolerance_; }

 private:
  std::vector<PartOverlap> overlaps_;
  double tolerance_ = 0;
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
  ///         friction, parts that overlap by more than the tolerance
  ///         (OverlapError, listing every pair), a fixture
  ///         point off its part or a fixture normal pointing out of it, a
  ///         part that is both fixed and a tool.
  static Assembly Create(const AssemblyDef& def, const std::string& source_file = "");

  const std::string& name() const { return name_; }
  int num_parts() const { return static_cast<int>(parts_.size()); }
  const std::vector<Part>& parts() const { return parts_; }
  const Part& part(int i) const { return parts_.at(i); }
  /// Index of the part with this name, or -1.
  /// The names of `parts`, joined by ", " (for messages: "A, B").
  std::string NameList(const std::vector<int>& parts) const;
  int FindPart(const std::string& name) const;
  const std::vector<Fixture>& fixtures() const { return fixtures_; }
  /// The given contact interfaces (AssemblyDef::interfaces); empty when the
  /// contacts are found from the shapes.
  const std::vector<Interface>& interfaces() const { return interfaces_; }
  /// True when the contacts are the given interfaces: they describe the
  /// assembled configuration only (parts may be taken away, not moved).
  bool has_interfaces() const { return !interfaces_.empty(); }
  /// 2 (polygons, planar motion) or 3 (polyhedra, six freedoms per part).
  int dimension() const { return dimension_; }
  bool is_3d() const { return dimension_ == 3; }
  /// length/s², world frame (z = 0 in 2-D).
  const Vector3& gravity() const { return gravity_; }
  /// D, the friction directions per contact: 2 in 2-D (±t), the scene's
  /// `friction_directions` (default 4) in 3-D.
  int friction_directions() const { return friction_directions_; }
  /// Coulomb coefficient between parts i and j (a friction pair if the scene
  /// names one, else the scene default). j = -1 means the fixed world
  /// (fixtures), which is always frictionless.
  double Friction(int i, int j) const;
  /// True when every contact in the scene is frictionless.
  bool IsFrictionless() const;
  /// This model with the scene's default μ replaced by `default_mu` and every
  /// friction pair's μ multiplied by `pair_factor` (both finite, ≥ 0): what
  /// Create would build from the definition so changed, without building it
  /// again (the friction margin probes one scene at many μ).
  Assembly WithFriction(double default_mu, double pair_factor) const;
  /// This model with gravity `g` (finite; the same magnitude keeps every
  /// tolerance as it is): the tilt margin's verdict turns gravity, not the parts.
  Assembly WithGravity(const Vector3& g) const;
  /// This model with the parts `held` (indices) fixed where they are, as a
  /// robot or a crane holds a block (`cairn sequence`'s holds). The scene's
  /// force scale (max_weight) and tolerances stay those of this model, so a
  /// state's check is judged on the scene's scale whatever is held.
  Assembly WithHeld(const std::vector<int>& held) const;
  /// This model with the fixels `added` after its own fixtures (index
  /// fixtures().size() + k), as Create would accept them (`cairn sequence`'s
  /// props). @throws std::invalid_argument naming the fault (FixtureFault).
  Assembly WithFixtures(const std::vector<FixtureDef>& added) const;
  /// The diagonal of the bounding box of all parts (length).
  double scene_size() const { return scene_size_; }
  /// The largest weight of a movable part, m |g| (force units; 0 without
  /// gravity): the scale of the scene's forces.
  double max_weight() const { return max_weight_; }
  /// The contact distance tolerance (length): the scene's, or 1e-6 · size.
  double length_tolerance() const { return tolerances_.length; }
  /// How much deeper than the length tolerance the parts may interpenetrate
  /// and still touch (length, ≥ 0; AssemblyDef::overlap_allowance).
  double overlap_allowance() const { return overlap_allowance_; }
  /// How deep parts may interpenetrate beyond the length tolerance and the
  /// overlap allowance and be read as touching, on the overlap's mid-surface
  /// (length, ≥ 0; AssemblyDef::overlap_depth).
  double overlap_depth() const { return overlap_depth_; }
  /// The pairs of parts that overlap by more than the length tolerance and
  /// the overlap allowance but within the overlap depth, as placed: each
  /// with its deepest point and depth (PolyhedronOverlapDepth), read as
  /// touching. Empty without an overlap depth.
  const std::vector<PartOverlap>& touching_overlaps() const { return touching_overlaps_; }
  /// All tolerances, scaled to this scene for a time step `dt` (s).
  /// Why Create would reject the fixel `f` added to this scene's fixtures
  /// (no such part, not finite, a zero normal, not on the part's boundary, not
  /// pushing into it); empty when it would accept it. Does not throw: the
  /// fixture search tests candidates with it.
  std::optional<std::string> FixtureFault(const FixtureDef& f) const;
  Tolerances MakeTolerances(double dt = 1.0) const;

 private:
  std::string name_;
  std::vector<Part> parts_;
  std::vector<Fixture> fixtures_;
  std::vector<Interface> interfaces_;
  int dimension_ = 2;
  Vector3 gravity_{0, -9.81, 0};
  int friction_directions_ = 2;
  double default_friction_ = 0;
  std::vector<std::pair<std::pair<int, int>, double>> pair_mu_;  // (min, max) index → μ
  double scene_size_ = 0;
  double tolerance_override_ = 0;
  double overlap_allowance_ = 0;
  double overlap_depth_ = 0;
  std::vector<PartOverlap> touching_overlaps_;
  double smallest_part_size_ = 0;  // length: the least bounding-box diagonal of a part
  double max_weight_ = 0;
  Tolerances tolerances_;
};

/// Where the parts are in one configuration, and which are present. A pose is
/// the rigid displacement of a part from its assembled pose: a rotation
/// `rotation` (R, world axes) about the part's assembled centroid, then a
/// translation by `translation` (length). In 2-D, R is a rotation about +z
/// and translation.z() = 0.
struct Pose {
  Vector3 translation{0, 0, 0};
  Matrix3 rotation = Matrix3::Identity();
  /// A planar pose: translation (x, y), rotation by `angle` (rad,
  /// counter-clockwise) about +z.
  static Pose Planar(const Vector2& translation, double angle = 0);
  /// The translation only.
  static Pose Translation(const Vector3& translation);
  /// The world position of a point given at the assembled pose.
  Vector3 Apply(const Vector3& p_assembled, const Vector3& centroid_assembled) const;
  /// The planar rotation angle (rad) about +z (2-D poses).
  double angle() const;
  /// Turns the pose by the rotation vector ω·dt (rad, world axes) about the
  /// part's centroid (the exponential map; exact for a constant ω).
  void Rotate(const Vector3& rotation_vector);
};

/// The mutable state of one configuration of an Assembly.
struct Configuration {
  std::vector<bool> present;  ///< (num_parts) false: the part has been taken away
  std::vector<Pose> poses;    ///< (num_parts)

  /// Every part of the assembly present, at its assembled pose; tools
  /// (Part::tool) absent, also at their assembled (start) poses.
  static Configuration Assembled(const Assembly& assembly);
  /// 2-D: part i's polygon in this configuration (world frame, counter-clockwise).
  Polygon WorldPolygon(const Assembly& assembly, int i) const;
  /// Part i's vertices in this configuration (world frame).
  std::vector<Vector3> WorldVertices(const Assembly& assembly, int i) const;
  /// 3-D: X_WB, the map from part i's assembled-pose coordinates to the world.
  Eigen::Isometry3d WorldTransform(const Assembly& assembly, int i) const;
  /// Part i's centroid in this configuration (world frame).
  Vector3 WorldCentroid(const Assembly& assembly, int i) const;
  /// Part i's inertia tensor about its centroid in this configuration (world axes).
  Matrix3 WorldInertia(const Assembly& assembly, int i) const;
};

}  // namespace cairn

#pragma once
/// @file
/// The contact LCPs of one contact-graph component, in 2-D and 3-D.
///
/// Generalised velocity of body k: ν_k = (v, ω) ∈ R⁶ at its centroid, world
/// axes; mass matrix M_k = diag(m I₃, I_W) with I_W the inertia tensor about
/// the centroid in world axes. A 2-D (planar) body is the same body with only
/// v_x, v_y and ω_z free: its effective inverse mass (below) is zero in the
/// other three directions, so 2-D and 3-D share one model. For a contact c
/// between a and b with point p and normal n (from b into a), the normal row is
///     J_n,c ν = n·v_a + ((p − c_a) × n)·ω_a − n·v_b − ((p − c_b) × n)·ω_b,
/// the relative normal velocity of a's material point over b's (a fixed part
/// or the world contributes nothing); a friction row is the same with a
/// friction direction d_k (FrictionDirections: ±t in 2-D, D directions in the
/// tangent plane in 3-D). The transpose J_nᵀ f is the wrench of the contact
/// force f on the bodies (the paper's W_n; W_f = [J_d1ᵀ … J_dDᵀ]).
///
/// Frictionless (Baraff 1994; the paper's eq. 1), acceleration level, from rest:
///     0 ≤ f  ⊥  a_n = J_n M⁻¹ J_nᵀ f + J_n M⁻¹ F_ext ≥ 0,
/// with body accelerations ν̇ = M⁻¹ (F_ext + J_nᵀ f).
///
/// With friction (Stewart & Trinkle 1996; the paper's eq. 5), one impulse step
/// of length Δt, unknowns z = (p_n, p_f, λ):
///     [ J_n M⁻¹ J_nᵀ  J_n M⁻¹ D   0 ] [p_n]   [J_n (M⁻¹F Δt + ν⁻) + d/Δt]
///     [ Dᵀ M⁻¹ J_nᵀ   Dᵀ M⁻¹ D    E ] [p_f] + [Dᵀ (M⁻¹F Δt + ν⁻)        ]  ⊥ z ≥ 0
///     [ μ             −Eᵀ         0 ] [λ  ]   [0                        ]
/// (D here the friction rows, D per frictional contact; E the blocks of ones.)
/// with ν⁺ = ν⁻ + M⁻¹ (F Δt + J_nᵀ p_n + D p_f). Contacts with μ = 0 carry no
/// friction unknowns (their p_f would be forced to zero anyway), which keeps
/// the LCP smaller and better conditioned.
///
/// Gripped bodies: a body whose velocity is partly or wholly prescribed (a
/// part moved by the gripper) has ν = ν_p + B ξ with ξ free; everything above
/// holds with M⁻¹ replaced by the effective inverse mass W = B (BᵀMB)⁻¹Bᵀ, ν⁻ by
/// its free part B Bᵀ ν⁻, and ν_p added to the free motion (constant
/// prescribed velocity: no inertial term). A fully prescribed body has W = 0:
/// it is a moving obstacle.
///
/// The products G M⁻¹ Gᵀ are formed per body: each row of G touches at most
/// two bodies, so the cost is Σ_k (rows at body k)², not rows² · bodies.

#include <vector>

#include "cairn/contact/contact.h"
#include "cairn/core/types.h"
#include "cairn/lcp/factored_lcp.h"

namespace cairn {

/// Which contact model an analysis uses.
enum class Formulation {
  kBaraff,          ///< frictionless, acceleration level (paper eq. 1)
  kStewartTrinkle,  ///< Coulomb friction, impulse-velocity level (paper eq. 5)
};

/// "baraff", "stewart-trinkle".
const char* to_string(Formulation f);

/// How a body of a component may move.
enum class BodyMotion {
  kFree,    ///< every velocity component is unknown
  kGuided,  ///< the velocity along `guide` is prescribed (a gripper pushing along a path without
            ///< carrying the part: support "none"); the rest is free
  kPrescribed,  ///< ν = nu_prescribed (held rigidly by a gripper: support "full"); no unknowns
};

/// One body of a component.
struct BodyDynamics {
  int part = -1;                      ///< index into Assembly::parts()
  double mass = 0;                    ///< mass units
  Matrix3 inertia = Matrix3::Zero();  ///< about the centroid, world axes, mass·length²
  Vector3 p_WBcm{0, 0, 0};            ///< centroid, world frame
  bool planar = false;                ///< 2-D: only v_x, v_y, ω_z are freedoms of the body
  Vector6 F_ext = Vector6::Zero();    ///< (f, τ) external wrench at the centroid
  Vector6 nu_prev = Vector6::Zero();  ///< (v, ω) before the step (Stewart–Trinkle only)
  BodyMotion motion = BodyMotion::kFree;
  Vector3 guide{1, 0, 0};                   ///< kGuided: unit direction of the prescribed velocity
  Vector6 nu_prescribed = Vector6::Zero();  ///< kGuided/kPrescribed: the prescribed part of ν

  /// The effective inverse mass W = B (Bᵀ M B)⁻¹ Bᵀ, where the columns of B
  /// span the free velocity directions (orthonormal): M⁻¹ for a free 3-D body,
  /// 0 for a prescribed one. A wrench F changes ν by W F.
  Matrix6 InverseMass() const;
  /// The projector B Bᵀ onto the free velocity directions.
  Matrix6 FreeProjector() const;
  /// B: orthonormal columns spanning the free velocity directions (none for a
  /// prescribed body; v_x, v_y, ω_z for a free planar one).
  Eigen::Matrix<double, 6, Eigen::Dynamic> FreeBasis() const;
};

/// How the LCP matrix of a component is stored.
enum class LcpStorage {
  kAuto,      ///< dense up to kMaxDenseLcp variables, factored above
  kDense,     ///< ContactLcp::M only
  kFactored,  ///< ContactLcp::factored only
  kBoth,      ///< both (tests compare the two solvers)
};

/// The largest LCP that kAuto stores densely. Above it the factored solver is
/// faster: its pivot costs O(k² + nnz(G)) against the dense tableau's O(n²)
/// (docs/benchmarks.md, "Dense and factored Lemke").
inline constexpr int kMaxDenseLcp = 96;

/// A row of G: a linear form on the generalised velocities of at most two bodies.
struct JacobianRow {
  int body[2] = {-1, -1};                             ///< local body indices, -1 when fixed/world
  Vector6 g[2] = {Vector6::Zero(), Vector6::Zero()};  ///< coefficients on (v, ω) of each body
  double Dot(const std::vector<Vector6>& nu) const;
};

/// How BuildContactLcp builds a component's LCP.
struct LcpBuildOptions {
  Formulation formulation = Formulation::kStewartTrinkle;
  double dt = 1.0;        ///< the time step (s) of the Stewart–Trinkle LCP
  bool use_gaps = false;  ///< each contact's gap in the d/Δt term; false: every contact closed
  LcpStorage storage = LcpStorage::kAuto;
  int dimension = 2;   ///< 2 or 3: chooses the friction directions
  int directions = 4;  ///< D, friction directions per contact in 3-D (ignored in 2-D)
  /// Compliant contacts (Stewart–Trinkle only): the normal rows get
  /// `normal_compliance` on their diagonal (w_n = … + c_n p_n) and each
  /// contact's friction rows `tangential_compliance` · d_kᵀd_j (w_k = … +
  /// c_t Σ_j d_kᵀd_j β_j): springs of stiffness 1/c in series with the rigid
  /// contact (velocity per impulse, 1/kg; 0: rigid). The loaded-from-rest
  /// collapse step (loaded_from_rest.cpp) uses them.
  double normal_compliance = 0.0;
  double tangential_compliance = 0.0;
};

/// The LCP of one component, and what is needed to read its solution.
struct ContactLcp {
  LcpBuildOptions build;  ///< how it was built (to build a variant of it)
  Formulation formulation = Formulation::kBaraff;
  double dt = 1.0;                       ///< s (Stewart–Trinkle only)
  std::vector<BodyDynamics> bodies;      ///< (nb)
  std::vector<Contact> contacts;         ///< (nc)
  std::vector<int> friction_of;          ///< (nc) index among frictional contacts, or -1
  int num_friction = 0;                  ///< nf: contacts with μ > 0 (Stewart–Trinkle)
  int num_directions = 2;                ///< D: friction directions per contact (2 in 2-D)
  std::vector<JacobianRow> normal_rows;  ///< (nc) J_n
  /// (nc) tangent rows for reporting: J_t1 (2-D: along t_W) and J_t2 (3-D
  /// only; empty in 2-D), for TangentBasis(n).
  std::vector<JacobianRow> tangent_rows, tangent2_rows;
  /// (nf·D) the friction rows J_dk of every frictional contact, D per contact,
  /// in the order of friction_of; their directions in friction_directions.
  std::vector<JacobianRow> direction_rows;
  std::vector<Vector3> friction_directions;  ///< (nf·D) unit d_k, world frame
  VectorX normal_offset;  ///< (nc) d/Δt in the normal rows (S–T with gaps), else 0
  /// (n x n) n = nc (Baraff) or nc + (D + 1) nf (Stewart–Trinkle); empty when
  /// the storage is kFactored (or kAuto above kMaxDenseLcp).
  MatrixX M;
  /// The same matrix as G W Gᵀ + K: G the rows above (plus zero rows for λ),
  /// W the block-diagonal effective inverse mass, K the E/μ blocks. Empty
  /// (size 0) when the storage is kDense (or kAuto up to kMaxDenseLcp).
  FactoredLcpMatrix factored;
  VectorX q;  ///< (n)
  int size() const { return static_cast<int>(q.size()); }
  bool has_dense() const { return M.rows() == q.size(); }
  /// M z, from whichever storage is present.
  VectorX Multiply(const VectorX& z) const;
};

/// Builds the LCP of one component. `gaps` uses each contact's gap (length)
/// in the Stewart–Trinkle d/Δt term when true, else treats every contact as
/// closed (d = 0, for a static check). `dimension` (2 or 3) chooses the
/// friction directions, `directions` is D in 3-D (ignored in 2-D).
ContactLcp BuildContactLcp(std::vector<BodyDynamics> bodies, std::vector<Contact> contacts,
                           const LcpBuildOptions& options);

/// Solves the component's LCP: SolveLemke on the dense M when it is stored,
/// else SolveLemkeFactored.
LcpResult SolveContactLcp(const ContactLcp& lcp, const LemkeParameters& params = {},
                          const LcpBasis* warm_start = nullptr);

/// IsLcpSolution on whichever storage is present.
bool IsContactLcpSolution(const ContactLcp& lcp, const VectorX& z, double tol);

/// The solution of a component's LCP in physical terms.
struct ContactSolution {
  std::vector<Vector6>
      body_motion;  ///< (nb) ν̇ (Baraff, length/s², rad/s²) or ν⁺ (S–T, length/s, rad/s)
  VectorX normal_force;  ///< (nc) f (Baraff) or p_n / Δt (S–T), force units, ≥ 0
  std::vector<Vector3> friction_force;  ///< (nc) on a, world frame, force units (0: frictionless)
  VectorX normal_motion;  ///< (nc) relative normal acceleration (Baraff) or velocity (S–T)
  /// (nc) relative tangential acceleration or velocity of a over b, world frame
  std::vector<Vector3> tangent_motion;
  /// max over rows of |(G ν) − w|: the LCP's w recomputed from the body motions.
  /// Checks the assembled LCP against the direct physics (should be ~1e-12).
  double consistency_residual = 0;
};

/// Maps an LCP solution z to body motions and contact forces.
ContactSolution RecoverSolution(const ContactLcp& lcp, const VectorX& z);

}  // namespace cairn

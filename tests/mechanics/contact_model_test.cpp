#include "cairn/mechanics/contact_model.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>  // IWYU pragma: keep

#include "cairn/lcp/lemke.h"

namespace cairn {
namespace {

// A w × h box of mass m resting on a fixed table at its two bottom corners.
struct BoxOnTable {
  double w = 2, h = 1, m = 3, g = 9.81, mu = 0;
  std::vector<BodyDynamics> Bodies() const {
    BodyDynamics b;
    b.part = 0;
    b.mass = m;
    b.inertia = Matrix3::Identity() * (m * (w * w + h * h) / 12);
    b.p_WBcm = {0, h / 2, 0};
    b.planar = true;
    b.F_ext << 0, -m * g, 0, 0, 0, 0;
    return {b};
  }
  std::vector<Contact> Contacts() const {
    std::vector<Contact> cs(2);
    for (int i = 0; i < 2; ++i) {
      cs[i].part_a = 0;
      cs[i].part_b = 1;  // a fixed part (not among the bodies)
      cs[i].p_WC = {i == 0 ? -w / 2 : w / 2, 0, 0};
      cs[i].n_W = {0, 1, 0};
      cs[i].mu = mu;
    }
    return cs;
  }
};

TEST(Baraff, DelassusMatrixOfABoxOnItsCornersMatchesTheHandFormula) {
  // A_ij = 1/m + r_i r_j / I with r = ∓w/2 (the lever of the vertical normal).
  const BoxOnTable box;
  const ContactLcp lcp = BuildContactLcp(box.Bodies(), box.Contacts(),
                                         LcpBuildOptions{Formulation::kBaraff, 1, false});
  const double I = box.m * (box.w * box.w + box.h * box.h) / 12;
  const double r = box.w / 2;
  ASSERT_EQ(lcp.size(), 2);
  EXPECT_NEAR(lcp.M(0, 0), 1 / box.m + r * r / I, 1e-14);
  EXPECT_NEAR(lcp.M(0, 1), 1 / box.m - r * r / I, 1e-14);
  EXPECT_NEAR(lcp.M(1, 0), lcp.M(0, 1), 1e-14);
  EXPECT_NEAR(lcp.q(0), -box.g, 1e-14);
  EXPECT_NEAR(lcp.q(1), -box.g, 1e-14);
  // The box rests: each corner carries half its weight, nothing accelerates.
  const LcpResult sol = SolveLemke(lcp.M, lcp.q);
  ASSERT_EQ(sol.status, LcpStatus::kSolved);
  const ContactSolution s = RecoverSolution(lcp, sol.z);
  EXPECT_NEAR(s.normal_force(0), box.m * box.g / 2, 1e-9);
  EXPECT_NEAR(s.normal_force(1), box.m * box.g / 2, 1e-9);
  EXPECT_NEAR(s.body_motion[0].norm(), 0.0, 1e-9);
  EXPECT_LT(s.consistency_residual, 1e-12);
}

TEST(Baraff, DelassusIsSymmetricPsdWithTheRankOfTheBodies) {
  // Four contacts on one body: rank ≤ 3 (the body's degrees of freedom).
  BoxOnTable box;
  auto cs = box.Contacts();
  auto extra = cs;
  for (auto& c : extra) c.p_WC.x() *= 0.5;
  cs.insert(cs.end(), extra.begin(), extra.end());
  const ContactLcp lcp =
      BuildContactLcp(box.Bodies(), cs, LcpBuildOptions{Formulation::kBaraff, 1, false});
  EXPECT_TRUE(lcp.M.isApprox(lcp.M.transpose(), 1e-14));
  Eigen::SelfAdjointEigenSolver<MatrixX> eig(lcp.M);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12);
  int rank = 0;
  for (int i = 0; i < 4; ++i) rank += eig.eigenvalues()(i) > 1e-10;
  EXPECT_EQ(rank, 2) << "vertical normals span only v_y and ω";
}

TEST(StewartTrinkle, LcpHasThePapersBlockStructure) {
  BoxOnTable box;
  box.mu = 0.3;
  const ContactLcp lcp = BuildContactLcp(box.Bodies(), box.Contacts(),
                                         LcpBuildOptions{Formulation::kStewartTrinkle, 0.5, false});
  // nc normal + 2 nc friction + nc λ.
  ASSERT_EQ(lcp.size(), 8);
  EXPECT_EQ(lcp.num_friction, 2);
  for (int f = 0; f < 2; ++f) {
    const int lam = 6 + f;
    EXPECT_EQ(lcp.M(lam, f), 0.3);         // μ
    EXPECT_EQ(lcp.M(lam, 2 + 2 * f), -1);  // −Eᵀ
    EXPECT_EQ(lcp.M(lam, 3 + 2 * f), -1);
    EXPECT_EQ(lcp.M(2 + 2 * f, lam), 1);  // E
    EXPECT_EQ(lcp.M(3 + 2 * f, lam), 1);
    EXPECT_EQ(lcp.M(lam, lam), 0);
  }
  EXPECT_NEAR(lcp.q(0), -box.g * 0.5, 1e-14);  // J_n M⁻¹ F Δt
  // At rest with friction: impulses carry the weight over Δt, ν⁺ = 0.
  const LcpResult sol = SolveLemke(lcp.M, lcp.q);
  ASSERT_EQ(sol.status, LcpStatus::kSolved);
  const ContactSolution s = RecoverSolution(lcp, sol.z);
  EXPECT_NEAR(s.normal_force(0) + s.normal_force(1), box.m * box.g, 1e-9);
  EXPECT_NEAR(s.body_motion[0].norm(), 0.0, 1e-9);
  EXPECT_LT(s.consistency_residual, 1e-12);
}

TEST(StewartTrinkle, FrictionlessContactsCarryNoFrictionUnknowns) {
  BoxOnTable box;
  auto cs = box.Contacts();
  cs[0].mu = 0.5;  // one frictional, one frictionless
  const ContactLcp lcp =
      BuildContactLcp(box.Bodies(), cs, LcpBuildOptions{Formulation::kStewartTrinkle, 1, false});
  EXPECT_EQ(lcp.num_friction, 1);
  EXPECT_EQ(lcp.size(), 2 + 3);
}

TEST(StewartTrinkle, GapsEnterAsDOverDtWhenAsked) {
  BoxOnTable box;
  box.mu = 0.2;
  auto cs = box.Contacts();
  cs[0].gap = 1e-3;
  const ContactLcp with =
      BuildContactLcp(box.Bodies(), cs, LcpBuildOptions{Formulation::kStewartTrinkle, 0.1, true});
  const ContactLcp without =
      BuildContactLcp(box.Bodies(), cs, LcpBuildOptions{Formulation::kStewartTrinkle, 0.1, false});
  EXPECT_NEAR(with.q(0) - without.q(0), 1e-3 / 0.1, 1e-15);
  EXPECT_EQ(with.q(1), without.q(1));
}

// Compliant contacts (LcpBuildOptions::normal_compliance and
// tangential_compliance): the matrix is the rigid one plus c_n on the
// normal rows' diagonal and c_t d_kᵀd_j in each contact's friction block, in
// the dense and the factored storage alike; and the box sinks into its
// springs: w_n = J_n ν⁺ + c_n p_n = 0 with the impulses carrying the weight,
// so ν⁺_y = −c_n p_n and m ν⁺_y = 2 p_n − m g Δt, p_n = m g Δt / (2 + m c_n).
TEST(StewartTrinkle, CompliantContactsAddTheirSpringsToTheMatrix) {
  BoxOnTable box;
  box.mu = 0.3;
  const double dt = 0.5, cn = 0.2, ct = 0.05;
  LcpBuildOptions rigid{Formulation::kStewartTrinkle, dt, false};
  rigid.storage = LcpStorage::kDense;
  LcpBuildOptions soft = rigid;
  soft.normal_compliance = cn;
  soft.tangential_compliance = ct;
  soft.storage = LcpStorage::kBoth;
  const ContactLcp a = BuildContactLcp(box.Bodies(), box.Contacts(), rigid);
  const ContactLcp b = BuildContactLcp(box.Bodies(), box.Contacts(), soft);
  ASSERT_EQ(b.size(), 8);
  MatrixX springs = MatrixX::Zero(8, 8);
  springs(0, 0) = springs(1, 1) = cn;
  for (int f = 0; f < 2; ++f)  // 2-D: d = ±t, d_kᵀd_j = ±1
    springs.block(2 + 2 * f, 2 + 2 * f, 2, 2) << ct, -ct, -ct, ct;
  EXPECT_LT((b.M - a.M - springs).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((b.factored.ToDense() - b.M).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(b.q, a.q);
  const LcpResult sol = SolveLemke(b.M, b.q);
  ASSERT_EQ(sol.status, LcpStatus::kSolved);
  const double pn = box.m * box.g * dt / (2 + box.m * cn);
  EXPECT_NEAR(sol.z(0), pn, 1e-12);
  EXPECT_NEAR(sol.z(1), pn, 1e-12);
  const ContactSolution s = RecoverSolution(b, sol.z);
  EXPECT_NEAR(s.body_motion[0].y(), -cn * pn, 1e-12);
  EXPECT_NEAR(s.body_motion[0].x(), 0.0, 1e-12);
}

}  // namespace
}  // namespace cairn

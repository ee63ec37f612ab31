// The 46-problem LCP conformance suite of shared/lcp_data: every row of
// expected.tsv is solved by SolveLemke and checked against what the README and
// the table say Lemke (covering vector e, lexicographic ties) must do.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cairn/lcp/factored_lcp.h"
#include "cairn/lcp/lcp_io.h"
#include "cairn/lcp/lemke.h"
#include "test_paths.h"

namespace cairn {
namespace {

// One row of expected.tsv (the columns this suite uses).
struct Row {
  std::string name;
  std::string file;
  int n = 0;
  std::string expected_lemke;
  std::string solution_set;
};
void PrintTo(const Row& row, std::ostream* os) { *os << row.name; }

std::string LcpDataDir() {
  const std::string shared = testing::SharedDir();
  return shared.empty() ? std::string() : shared + "/lcp_data";
}

std::vector<std::string> SplitTabs(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, '\t')) fields.push_back(field);
  return fields;
}

// The rows of expected.tsv, or one placeholder row (which skips) when the
// shared data is absent.
std::vector<Row> LoadRows() {
  const std::string dir = LcpDataDir();
  if (dir.empty()) return {Row{"shared_data_absent", "", 0, "", ""}};
  std::ifstream in(dir + "/expected.tsv");
  std::vector<Row> rows;
  std::string line;
  std::getline(in, line);  // Header.
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto f = SplitTabs(line);
    if (f.size() < 6) continue;
    rows.push_back(Row{f[0], f[1], std::stoi(f[2]), f[4], f[5]});
  }
  return rows;
}

bool StartsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// A number written as "a", "a/b" or a decimal; `tol` receives its precision
// (relative): 1e-12 for exact forms, half a unit of the last printed decimal
// otherwise (never below 1e-9).
double ParseEntry(const std::string& token, double* tol) {
  const auto slash = token.find('/');
  if (slash != std::string::npos) {
    *tol = 1e-12;
    return std::stod(token.substr(0, slash)) / std::stod(token.substr(slash + 1));
  }
  const auto dot = token.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(token.size() - dot - 1);
  *tol = std::max(1e-9, decimals == 0 ? 0.0 : std::pow(10.0, -decimals));
  return std::stod(token);
}

// The unique solution stated in the solution_set column, with a per-entry
// tolerance, or nothing when the column does not give a single point.
struct ExpectedZ {
  VectorX z;
  VectorX tol;
};
std::optional<ExpectedZ> ParseUniqueZ(const Row& row) {
  std::string s = row.solution_set;
  if (!StartsWith(s, "unique")) return std::nullopt;
  const int n = row.n;
  ExpectedZ out{VectorX::Zero(n), VectorX::Constant(n, 1e-9)};
  const auto paren = s.find("z=(");
  if (paren != std::string::npos) {
    const auto close = s.find(')', paren);
    std::stringstream ss(s.substr(paren + 3, close - paren - 3));
    std::string token;
    int i = 0;
    while (std::getline(ss, token, ',')) {
      if (i >= n) return std::nullopt;
      double tol = 0.0;
      out.z[i] = ParseEntry(token, &tol);
      out.tol[i] = tol;
      ++i;
    }
    if (i != n) return std::nullopt;
    return out;
  }
  if (s == "unique z_i=1/i") {
    for (int i = 0; i < n; ++i) out.z[i] = 1.0 / (i + 1);
    return out;
  }
  if (s == "unique z=2^n e_1") {
    out.z[0] = std::ldexp(1.0, n);
    return out;
  }
  if (s == "unique z=e_n") {
    out.z[n - 1] = 1.0;
    return out;
  }
  // "unique z=e_K" or "unique z=C e_K".
  const auto e = s.find("e_");
  if (StartsWith(s, "unique z=") && e != std::string::npos) {
    const std::string coef = s.substr(9, e - 9);
    const double c = coef.find_first_not_of(' ') == std::string::npos ? 1.0 : std::stod(coef);
    const int k = std::stoi(s.substr(e + 2));
    if (k < 1 || k > n) return std::nullopt;
    out.z[k - 1] = c;
    return out;
  }
  return std::nullopt;
}

class LcpConformance : public ::testing::TestWithParam<Row> {};

TEST_P(LcpConformance, MatchesExpectedOutcome) {
  if (LcpDataDir().empty()) {
    GTEST_SKIP() << "shared/lcp_data not found: skipping the 46-problem conformance suite";
  }
  const Row& row = GetParam();
  const LcpProblem p = ReadLcpFile(LcpDataDir() + "/" + row.file);
  ASSERT_EQ(p.q.size(), row.n);

  LemkeParameters params;
  const bool murty = StartsWith(row.name, "gen_murty_exp_");
  // Murty's problem needs 2^n pivots, above the default limit for n = 12.
  if (murty) params.max_pivots = 4 << row.n;
  const LcpResult r = SolveLemke(p.M, p.q, params);
  const double tol = 1e-8 * std::max(1.0, p.q.cwiseAbs().maxCoeff());

  if (StartsWith(row.expected_lemke, "ray")) {
    EXPECT_EQ(r.status, LcpStatus::kRayTermination) << to_string(r.status) << " " << r.message;
    return;
  }
  ASSERT_TRUE(StartsWith(row.expected_lemke, "solve")) << row.expected_lemke;
  ASSERT_EQ(r.status, LcpStatus::kSolved) << to_string(r.status) << ": " << r.message;
  EXPECT_TRUE(IsLcpSolution(p.M, p.q, r.z, tol)) << "residual " << r.residual;
  EXPECT_LE(LcpResidual(p.M, p.q, r.z), tol);

  // Where the solution is unique, compare z.
  if (const auto expected = ParseUniqueZ(row)) {
    for (int i = 0; i < row.n; ++i) {
      EXPECT_NEAR(r.z[i], expected->z[i],
                  expected->tol[i] * std::max(1.0, std::abs(expected->z[i])))
          << "z[" << i << "]";
    }
  }
  // Exact pivot counts where no ties occur (README): Murty 2^n, Fathi 2.
  if (murty) {
    EXPECT_EQ(r.pivots, 1 << row.n);
  }
  if (StartsWith(row.name, "gen_fathi_")) {
    EXPECT_EQ(r.pivots, 2);
  }
  if (row.name == "lcp_exp_murty2") {
    EXPECT_EQ(r.pivots, 64);
  }
  // The ill-conditioned slider-crank problem: the re-solve must give the
  // README's z to 1e-9 relative.
  if (row.name == "fc2d_FC2D_SliderCrankLagrangian00001") {
    const double z_ref[] = {0.0445252086260846, 0.000890504172521688, 9.16568839819786,
                            0.0440821717245079, 0.000881643434490158, 9.16568839819785};
    for (int i = 0; i < 6; ++i) {
      EXPECT_LE(std::abs(r.z[i] - z_ref[i]), 1e-9 * std::abs(z_ref[i])) << "z[" << i << "]";
    }
  }
  // Baraff's boxes: w is unique even where z is not.
  if (row.name == "gen_baraff_box_rest_4") {
    EXPECT_LE(r.w.cwiseAbs().maxCoeff(), 1e-9);
  }
  if (row.name == "gen_baraff_box_tip_4") {
    EXPECT_NEAR(r.w[0], 7.2443077, 1e-6);
    EXPECT_NEAR(r.w[3], 7.2443077, 1e-6);
    EXPECT_NEAR(r.w[1], 0.0, 1e-9);
    EXPECT_NEAR(r.w[2], 0.0, 1e-9);
  }
}

// The same problems through SolveLemkeFactored, with M written as
// G W Gᵀ + K with G empty and K = M: the reduced-basis pivoting, the rank-one
// updates of the basis inverse and the perturbation tie-breaking on the hard
// cases (cycling, Murty's exponential path, the ill-conditioned friction
// problems). Its path differs from the lexicographic one, so pivot counts are
// not compared; the verdict (solution or ray) and the solution are.
TEST_P(LcpConformance, FactoredSolverAgrees) {
  if (LcpDataDir().empty()) {
    GTEST_SKIP() << "shared/lcp_data not found: skipping the 46-problem conformance suite";
  }
  const Row& row = GetParam();
  const LcpProblem p = ReadLcpFile(LcpDataDir() + "/" + row.file);
  const int n = static_cast<int>(p.q.size());
  const SparseMatrixX G(n, 0), W(0, 0);
  const SparseMatrixX K = p.M.sparseView();
  const FactoredLcpMatrix F(G, W, K);
  LemkeParameters params;
  if (StartsWith(row.name, "gen_murty_exp_")) params.max_pivots = 4 << row.n;
  const LcpResult r = SolveLemkeFactored(F, p.q, params);
  const double tol = 1e-8 * std::max(1.0, p.q.cwiseAbs().maxCoeff());
  if (StartsWith(row.expected_lemke, "ray")) {
    EXPECT_EQ(r.status, LcpStatus::kRayTermination) << to_string(r.status) << " " << r.message;
    return;
  }
  ASSERT_EQ(r.status, LcpStatus::kSolved) << to_string(r.status) << ": " << r.message;
  EXPECT_TRUE(IsLcpSolution(p.M, p.q, r.z, tol)) << "residual " << r.residual;
  if (const auto expected = ParseUniqueZ(row)) {
    for (int i = 0; i < row.n; ++i) {
      EXPECT_NEAR(r.z[i], expected->z[i],
                  std::max(1e-7, expected->tol[i]) * std::max(1.0, std::abs(expected->z[i])))
          << "z[" << i << "]";
    }
  }
}

// The table has all 46 problems and every file exists and parses.
TEST(LcpConformanceTable, Has46Rows) {
  if (LcpDataDir().empty()) {
    GTEST_SKIP() << "shared/lcp_data not found: skipping the 46-problem conformance suite";
  }
  const auto rows = LoadRows();
  EXPECT_EQ(rows.size(), 46u);
}

std::string RowName(const ::testing::TestParamInfo<Row>& info) {
  std::string name = info.param.name;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(SharedLcpData, LcpConformance, ::testing::ValuesIn(LoadRows()), RowName);

}  // namespace
}  // namespace cairn

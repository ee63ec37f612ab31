// The equilibrium LP of sub-assemblies, kept between solves
// (cairn/mechanics/subset_equilibrium.h).

#include "cairn/mechanics/subset_equilibrium.h"

#include <algorithm>
#include <cmath>
#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <unordered_map>
#include <utility>

#include "cairn/core/check.h"
#include "mechanics/clp_solve.h"
#include "mechanics/equilibrium_lp.h"

namespace cairn {

using equilibrium_internal::EquilibriumLp;
using equilibrium_internal::kSimplexPrimalTolerance;
using equilibrium_internal::MakeEquilibriumLp;
using equilibrium_internal::MotionOfDuals;

namespace {

// A body moves along the infeasibility ray when its motion exceeds this
// fraction of the fastest body's (dimensionless): the ray's dust is not motion.
constexpr double kRayMotion = 1e-9;

// A ray y proves that no equilibrium exists (Farkas) when yᵀb > 0 while
// yᵀA_j ≤ 0 on every column that is on, y at 0 on the rows of absent and
// held bodies: then yᵀA x = yᵀb > 0 for an equilibrium x ≥ 0, yet yᵀA x ≤ 0. The
// two inequalities are read to these fractions of |y|·|A_j| and |y|·|b|
// (dimensionless): gravity's power along the motion must exceed the
// contacts' by far more than rounding.
constexpr double kFarkasColumnSlack = 1e-9;
constexpr double kFarkasPower = 1e-7;
// Unchecked (set_checked(false)), the column slack a kept ray is read with:
// the rays of a simplex that perturbed its costs (Clp does when it stalls)
// miss a certificate by the perturbation's size (1e-6 of the costs), and an
// unchecked warm claim is believed anyway.
constexpr double kUncheckedColumnSlack = 1e-5;

// An optimum is an equilibrium when every row balances, and every force is
// ≥ 0 (0 where the contact is off), to this fraction of the largest load a
// row balances (dimensionless; the simplex's own tolerance is 1e-10).
constexpr double kBalanceSlack = 1e-9;

// The fake bound Clp's dual simplex puts on the forces (unbounded above)
// while it works (force units, against the default 10¹⁰): where the warm
// basis leaves forces at a fake bound, Clp ends with its primal simplex,
// refactoring at every check. On the cross vault's states of 160 blocks
// and more that cleanup was most of a 400 ms solve; with this bound the
// LPs of a whole vault run took 79 s against 158 s, the same order
// (docs/benchmarks.md, "`bench/sequence_bench.sh`, sixth stop"). It must
// stay below 10²⁰, where Clp takes the bound as infinite and goes to its
// primal simplex at once.
constexpr double kDualBound = 1e18;

// The certificates kept per hint (Solve): the mechanisms of the last few
// states that failed when that part was placed.
constexpr size_t kCertificatesPerHint = 4;

// The neighbourhoods of the focus a local proof is looked for in (Solve,
// LocalProof): the free bodies within these numbers of contacts of it,
// under half of the free ones (beyond that the whole LP is the question).
// Those of at most kNearBodies bodies first: before the whole LP on states
// of kNearFromBodies free bodies or more, after kNearPivotsPerBody pivots a
// free body of it on smaller ones (whose LP is small enough for the
// regions' LPs to cost as much: on compas_assembly's wall, every state
// stands and proofs first made the run 0.5 s against 0.2 s); the larger
// ones after kWholeFirstIterations. A state that stands takes fewer pivots
// than these, most of the time (on the cross vault 22–45 on average below
// 80 blocks, 210 at 160–180; on the Armadillo under 2 000 9 times in 10),
// and one that fails more (150 and 1 700 on the vault).
constexpr int kLocalHops[] = {1, 2, 4, 8, 16, 32};
constexpr int kNearBodies = 48;
constexpr int kNearFromBodies = 60;
constexpr int kNearPivotsPerBody = 2;
constexpr int kWholeFirstIterations = 2000;

}  // namespace

struct SubsetEquilibrium::Impl {
  EquilibriumLp e;
  std::vector<std::pair<int, int>> sides;  // per generator: its contact's two bodies (-1: world)
  // The whole component's matrix, by column and by row, from which the
  // LP's columns and rows are taken.
  CoinPackedMatrix columns, rows;
  // The LP holds the rows of the free bodies and the columns of the
  // contacts that are on, nothing else: its basis is factorized, and its
  // columns priced, at every solve, and a state of 30 blocks of the
  // 180-block cross vault has a sixth of the rows and a tenth of the columns.
  std::vector<int> lp_column;  // per generator: its column in `lp`, or -1
  std::vector<int> generator;  // per column of `lp`: its generator
  std::vector<int> lp_row;     // per row of the component: its row in `lp`, or -1
  std::vector<int> row;        // per row of `lp`: the component's row
  ClpSimplex lp;

  void SetRows(const std::vector<bool>& keep_body);
  void SetColumns(const std::vector<bool>& on);
  // The statuses of `b` (Basis), the rows it did not hold with their slacks
  // basic, the columns it did not hold at their lower bound.
  void StartFrom(const Basis& b);
  // Whether `y` (over the component's rows, 0 on the others) proves that the
  // bodies `loose` cannot be balanced by the generators `on` (Farkas, read
  // with the slacks above); `y` is turned to the sign that does.
  bool Proves(std::vector<double>& y, const std::vector<bool>& loose, const std::vector<bool>& on,
              double column_slack) const;
  // The certificates of recent solves without an equilibrium, by the hint
  // they were solved with, the newest first.
  std::unordered_map<int, std::vector<std::vector<double>>> certificates;
  std::vector<int> Moved(const std::vector<double>& y, const std::vector<bool>& loose) const;
  // The ray of `lp` (over its rows) over the component's rows (0 on the others).
  std::vector<double> FullRay(const double* ray) const;
  // A certificate (over the component's rows) that moves only bodies near
  // `focus`, or empty (Solve, step 2): from the LPs of the regions around it.
  // The regions of more than `above` and at most `up_to` bodies.
  std::vector<double> LocalProof(const std::vector<bool>& loose, const std::vector<bool>& on,
                                 int focus, double column_slack, int above, int up_to) const;
  std::vector<std::vector<bool>> Regions(const std::vector<bool>& loose,
                                         const std::vector<bool>& on, int focus, int above,
                                         int up_to) const;
  std::vector<double> RegionRay(const std::vector<bool>& region, const std::vector<bool>& on) const;
};

SubsetEquilibrium::SubsetEquilibrium(const ContactLcp& lcp) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.e = MakeEquilibriumLp(lcp, /*frictionless=*/false);
  const int ng = static_cast<int>(m.e.generators.size());
  for (const equilibrium_internal::Generator& g : m.e.generators) {
    const JacobianRow& rn = lcp.normal_rows[g.contact];
    m.sides.emplace_back(rn.body[0], rn.body[1]);
  }
  m.columns = m.e.a.Matrix(m.e.nrows, ng);
  if (!m.columns.isColOrdered()) m.columns.reverseOrdering();
  m.rows.reverseOrderedCopyOf(m.columns);
  m.lp.setLogLevel(0);
  m.lp.setPrimalTolerance(kSimplexPrimalTolerance);
  m.lp.setDualBound(kDualBound);
  // Empty: each solve brings in the rows and columns of its state.
  const CoinPackedMatrix none(true, 0, 0, 0, nullptr, nullptr, nullptr, nullptr);
  m.lp.loadProblem(none, nullptr, nullptr, nullptr, nullptr, nullptr);
  m.lp_column.assign(ng, -1);
  m.lp_row.assign(m.e.nrows, -1);
}

namespace {

// The LP's rows (or columns) listed in `members` (by their index in the
// component) kept where `keep` says so: the others' LP indices returned,
// in order, for Clp to delete, and `position` (component index → LP index,
// -1 when out) made that of the kept ones.
template <typename Keep>
std::vector<int> KeepOnly(std::vector<int>& members, std::vector<int>& position, Keep keep) {
  std::vector<int> drop, kept;
  for (size_t i = 0; i < members.size(); ++i) {
    if (keep(members[i])) {
      kept.push_back(members[i]);
    } else {
      drop.push_back(static_cast<int>(i));
      position[members[i]] = -1;
    }
  }
  members = std::move(kept);
  for (size_t i = 0; i < members.size(); ++i) position[members[i]] = static_cast<int>(i);
  return drop;
}

// The vectors `add` of `m` (rows of a row-ordered matrix, columns of a
// column-ordered one) as Clp adds them: each entry whose other index the LP
// holds (`position` ≥ 0), at that LP index.
struct Vectors {
  std::vector<CoinBigIndex> starts = {0};
  std::vector<int> index;
  std::vector<double> value;
};
Vectors Gather(const CoinPackedMatrix& m, const std::vector<int>& add,
               const std::vector<int>& position) {
  Vectors out;
  const CoinBigIndex* start = m.getVectorStarts();
  const int* length = m.getVectorLengths();
  for (int v : add) {
    for (CoinBigIndex k = start[v]; k < start[v] + length[v]; ++k) {
      const int at = position[m.getIndices()[k]];
      if (at < 0) continue;
      out.index.push_back(at);
      out.value.push_back(m.getElements()[k]);
    }
    out.starts.push_back(static_cast<CoinBigIndex>(out.index.size()));
  }
  return out;
}

}  // namespace

// The LP's rows made those of the bodies `keep_body` (6 each): the others
// taken out, the new ones added as equalities with their slack basic and
// their entries in the columns the LP holds.
void SubsetEquilibrium::Impl::SetRows(const std::vector<bool>& keep_body) {
  const std::vector<int> drop =
      KeepOnly(row, lp_row, [&](int r) { return static_cast<bool>(keep_body[r / 6]); });
  if (!drop.empty()) lp.deleteRows(static_cast<int>(drop.size()), drop.data());
  std::vector<int> add;
  for (int r = 0; r < e.nrows; ++r)
    if (keep_body[r / 6] && lp_row[r] < 0) add.push_back(r);
  if (add.empty()) return;
  const Vectors v = Gather(rows, add, lp_column);
  std::vector<double> bound;
  for (int r : add) bound.push_back(e.rhs[r]);
  const int first = lp.numberRows();
  lp.addRows(static_cast<int>(add.size()), bound.data(), bound.data(), v.starts.data(),
             v.index.data(), v.value.data());
  if (!lp.statusArray()) lp.createStatus();  // before the first solve: a slack basis
  for (size_t k = 0; k < add.size(); ++k) {
    const int i = first + static_cast<int>(k);
    lp.setRowStatus(i, ClpSimplex::basic);
    row.push_back(add[k]);
    lp_row[add[k]] = i;
  }
}

// The LP's columns made those of the generators `on`: the ones that are off
// taken out, the new ones added at their lower bound (0) with their entries
// in the rows the LP holds, the others keeping their basis status.
void SubsetEquilibrium::Impl::SetColumns(const std::vector<bool>& on) {
  const std::vector<int> drop =
      KeepOnly(generator, lp_column, [&](int g) { return static_cast<bool>(on[g]); });
  if (!drop.empty()) lp.deleteColumns(static_cast<int>(drop.size()), drop.data());
  std::vector<int> add;
  for (size_t g = 0; g < on.size(); ++g)
    if (on[g] && lp_column[g] < 0) add.push_back(static_cast<int>(g));
  if (add.empty()) return;
  const Vectors v = Gather(columns, add, lp_row);
  const std::vector<double> lo(add.size(), 0.0), hi(add.size(), COIN_DBL_MAX),
      cost(add.size(), 0.0);
  const int first = lp.numberColumns();
  lp.addColumns(static_cast<int>(add.size()), lo.data(), hi.data(), cost.data(), v.starts.data(),
                v.index.data(), v.value.data());
  if (!lp.statusArray()) lp.createStatus();
  for (size_t k = 0; k < add.size(); ++k) {
    const int j = first + static_cast<int>(k);
    lp.setColumnStatus(j, ClpSimplex::atLowerBound);
    generator.push_back(add[k]);
    lp_column[add[k]] = j;
  }
}

std::vector<double> SubsetEquilibrium::Impl::FullRay(const double* ray) const {
  std::vector<double> full(static_cast<size_t>(e.nrows), 0.0);
  for (size_t i = 0; i < row.size(); ++i) full[row[i]] = ray[i];
  return full;
}

bool SubsetEquilibrium::Impl::Proves(std::vector<double>& y, const std::vector<bool>& loose,
                                     const std::vector<bool>& on, double column_slack) const {
  double y_norm = 0, b_norm = 0, power = 0;
  for (int r = 0; r < e.nrows; ++r) {
    if (!loose[r / 6]) {
      y[r] = 0;
      continue;
    }
    y_norm = std::max(y_norm, std::abs(y[r]));
    b_norm = std::max(b_norm, std::abs(e.rhs[r]));
    power += y[r] * e.rhs[r];
  }
  if (!(y_norm > 0)) return false;
  // The ray may point either way: the certificate is y or −y.
  if (power < 0) {
    for (double& v : y) v = -v;
    power = -power;
  }
  if (!(power > kFarkasPower * y_norm * b_norm)) return false;
  const CoinBigIndex* start = columns.getVectorStarts();
  const int* length = columns.getVectorLengths();
  const int* index = columns.getIndices();
  const double* value = columns.getElements();
  for (size_t g = 0; g < on.size(); ++g) {
    if (!on[g]) continue;
    double dot = 0, a_norm = 0;
    for (CoinBigIndex k = start[g]; k < start[g] + length[g]; ++k) {
      dot += y[index[k]] * value[k];
      a_norm = std::max(a_norm, std::abs(value[k]));
    }
    if (dot > column_slack * y_norm * a_norm) return false;
  }
  return true;
}

// The regions around `focus` the local answers are looked for in: the free
// bodies within each of kLocalHops contacts of it (through contacts that
// are on), smallest first, each larger than the one before, of more than
// `above` and at most `up_to` bodies, and under half the free bodies.
std::vector<std::vector<bool>> SubsetEquilibrium::Impl::Regions(const std::vector<bool>& loose,
                                                                const std::vector<bool>& on,
                                                                int focus, int above,
                                                                int up_to) const {
  const int nb = static_cast<int>(loose.size());
  if (focus < 0 || focus >= nb || !loose[focus]) return {};
  int n_loose = 0;
  for (bool l : loose) n_loose += l;
  std::vector<std::vector<int>> next(static_cast<size_t>(nb));
  for (size_t g = 0; g < on.size(); ++g) {
    const auto [a, b] = sides[g];
    if (!on[g] || a < 0 || b < 0 || !loose[a] || !loose[b]) continue;
    next[a].push_back(b);
    next[b].push_back(a);
  }
  // Breadth first from the focus: each body's number of contacts from it.
  std::vector<int> hops(static_cast<size_t>(nb), -1);
  std::vector<int> order = {focus};
  hops[focus] = 0;
  for (size_t i = 0; i < order.size(); ++i)
    for (int q : next[order[i]])
      if (hops[q] < 0) {
        hops[q] = hops[order[i]] + 1;
        order.push_back(q);
      }
  std::vector<std::vector<bool>> out;
  int tried = 0;  // the size of the last region
  for (int h : kLocalHops) {
    std::vector<bool> region(static_cast<size_t>(nb), false);
    int size = 0;
    for (int b : order)
      if (hops[b] <= h) region[b] = true, ++size;
    if (size == tried || size <= above) continue;
    if (size > up_to || 2 * size > n_loose) break;
    tried = size;
    out.push_back(std::move(region));
  }
  return out;
}

// The ray of the LP of the free bodies `region` (their rows, the columns of
// the generators that are on and touch them: every body outside held),
// over the component's rows; empty when that LP has an equilibrium or
// gives no ray.
std::vector<double> SubsetEquilibrium::Impl::RegionRay(const std::vector<bool>& region,
                                                       const std::vector<bool>& on) const {
  std::vector<int> position(static_cast<size_t>(e.nrows), -1), lp_rows;
  std::vector<double> bound;
  for (int r = 0; r < e.nrows; ++r)
    if (region[r / 6]) {
      position[r] = static_cast<int>(lp_rows.size());
      lp_rows.push_back(r);
      bound.push_back(e.rhs[r]);
    }
  std::vector<int> add;
  for (size_t g = 0; g < on.size(); ++g) {
    const auto [a, b] = sides[g];
    if (on[g] && ((a >= 0 && region[a]) || (b >= 0 && region[b])))
      add.push_back(static_cast<int>(g));
  }
  const Vectors v = Gather(columns, add, position);
  const int nrows = static_cast<int>(lp_rows.size()), ncols = static_cast<int>(add.size());
  const CoinPackedMatrix matrix(true, nrows, ncols, v.starts.back(), v.value.data(), v.index.data(),
                                v.starts.data(), nullptr);
  const std::vector<double> lo(static_cast<size_t>(ncols), 0.0),
      hi(static_cast<size_t>(ncols), COIN_DBL_MAX);
  ClpSimplex local;
  local.setLogLevel(0);
  local.setPrimalTolerance(kSimplexPrimalTolerance);
  local.setDualBound(kDualBound);
  local.loadProblem(matrix, lo.data(), hi.data(), nullptr, bound.data(), bound.data());
  clp::SolveBySimplex(local);
  if (clp::StatusOf(local) != clp::Status::kPrimalInfeasible) return {};
  std::unique_ptr<double[]> ray(local.infeasibilityRay());
  if (!ray) return {};
  std::vector<double> y(static_cast<size_t>(e.nrows), 0.0);
  for (int i = 0; i < nrows; ++i) y[lp_rows[i]] = ray[i];
  return y;
}

// Gravity that cannot be balanced near the part just placed (or let go) is
// usually unbalanced there already with every body around held: the LP of
// a region of a few dozen rows, from the slack basis, finds that proof where
// the whole LP's warm simplex takes a thousand pivots or more (on the cross
// vault's states of 80 blocks and more, up to 1 s each). A ray of the
// region's LP, 0 outside it, is a proof for the whole LP when Proves says
// so: the columns outside have no entry in the region's rows, those that
// join it to the rest are the region's own, with the rest's side held.
// Holding only helps the region stand, so where it still cannot, nothing
// can. A region that stands decides nothing (the rest is not held).
std::vector<double> SubsetEquilibrium::Impl::LocalProof(const std::vector<bool>& loose,
                                                        const std::vector<bool>& on, int focus,
                                                        double column_slack, int above,
                                                        int up_to) const {
  for (const std::vector<bool>& region : Regions(loose, on, focus, above, up_to)) {
    std::vector<double> y = RegionRay(region, on);
    if (!y.empty() && Proves(y, loose, on, column_slack)) return y;
  }
  return {};
}

SubsetEquilibrium::~SubsetEquilibrium() = default;
SubsetEquilibrium::SubsetEquilibrium(SubsetEquilibrium&&) noexcept = default;
SubsetEquilibrium& SubsetEquilibrium::operator=(SubsetEquilibrium&&) noexcept = default;

int SubsetEquilibrium::num_bodies() const { return static_cast<int>(impl_->e.P.size()); }

void SubsetEquilibrium::ForgetBasis() { impl_->lp.allSlackBasis(true); }

bool SubsetEquilibrium::SolutionBalances() const {
  const ClpSimplex& lp = impl_->lp;
  const double* x = lp.primalColumnSolution();
  const double* row_lo = lp.getRowLower();
  const double* row_hi = lp.getRowUpper();
  const double* col_hi = lp.getColUpper();
  std::vector<double> ax(static_cast<size_t>(lp.numberRows()), 0.0);
  lp.matrix()->times(x, ax.data());
  double load = 0;  // the largest load a row balances
  for (int r = 0; r < lp.numberRows(); ++r)
    if (row_lo[r] == row_hi[r]) load = std::max(load, std::abs(row_lo[r]));
  const double slack = kBalanceSlack * load;
  for (int j = 0; j < lp.numberColumns(); ++j)
    if (x[j] < -slack || (col_hi[j] <= 0 && std::abs(x[j]) > slack)) return false;
  for (int r = 0; r < lp.numberRows(); ++r)
    if (row_lo[r] == row_hi[r] && std::abs(ax[r] - row_lo[r]) > slack) return false;
  return true;
}

SubsetEquilibrium::Basis SubsetEquilibrium::CurrentBasis() const {
  const Impl& m = *impl_;
  Basis b;
  for (size_t j = 0; j < m.generator.size(); ++j)
    if (m.lp.getColumnStatus(static_cast<int>(j)) == ClpSimplex::basic)
      b.basic_generators.push_back(m.generator[j]);
  for (size_t i = 0; i < m.row.size(); ++i) {
    b.rows.push_back(m.row[i]);
    if (m.lp.getRowStatus(static_cast<int>(i)) == ClpSimplex::basic)
      b.basic_rows.push_back(m.row[i]);
  }
  return b;
}

void SubsetEquilibrium::Impl::StartFrom(const Basis& b) {
  for (int j = 0; j < lp.numberColumns(); ++j) lp.setColumnStatus(j, ClpSimplex::atLowerBound);
  for (int i = 0; i < lp.numberRows(); ++i) lp.setRowStatus(i, ClpSimplex::basic);
  for (int r : b.rows)
    if (lp_row[r] >= 0) lp.setRowStatus(lp_row[r], ClpSimplex::atLowerBound);
  for (int r : b.basic_rows)
    if (lp_row[r] >= 0) lp.setRowStatus(lp_row[r], ClpSimplex::basic);
  for (int g : b.basic_generators)
    if (lp_column[g] >= 0) lp.setColumnStatus(lp_column[g], ClpSimplex::basic);
}

// The bodies a certificate y moves (ν = −P y): those among `loose` faster
// than kRayMotion of the fastest.
std::vector<int> SubsetEquilibrium::Impl::Moved(const std::vector<double>& y,
                                                const std::vector<bool>& loose) const {
  const std::vector<Vector6> nu = MotionOfDuals(e, y.data());
  double fastest = 0;
  for (size_t b = 0; b < loose.size(); ++b)
    if (loose[b]) fastest = std::max(fastest, nu[b].norm());
  std::vector<int> out;
  if (!(fastest > 0)) return out;
  for (size_t b = 0; b < loose.size(); ++b)
    if (loose[b] && nu[b].norm() > kRayMotion * fastest) out.push_back(static_cast<int>(b));
  return out;
}

SubsetEquilibrium::Answer SubsetEquilibrium::Solve(const std::vector<bool>& present,
                                                   const std::vector<bool>& free,
                                                   const Basis* start, int hint, int focus) {
  Impl& m = *impl_;
  const int nb = num_bodies();
  CAIRN_CHECK(static_cast<int>(present.size()) == nb && static_cast<int>(free.size()) == nb);
  // Rows: those of the free bodies (an absent or held one balances nothing).
  // Columns: a contact is on when both its sides are there and one is free.
  std::vector<bool> loose_body(nb);
  for (int b = 0; b < nb; ++b) loose_body[b] = present[b] && free[b];
  const auto there = [&](int b) { return b < 0 || present[b]; };
  const auto loose = [&](int b) { return b >= 0 && loose_body[b]; };
  std::vector<bool> on(m.sides.size());
  for (size_t g = 0; g < m.sides.size(); ++g) {
    const auto [a, b] = m.sides[g];
    on[g] = there(a) && there(b) && (loose(a) || loose(b));
  }
  Answer out;
  const double column_slack = checked_ ? kFarkasColumnSlack : kUncheckedColumnSlack;
  // 1. A certificate of an earlier solve with this hint that proves this
  //    LP infeasible too: no simplex at all.
  std::vector<std::vector<double>>* known = hint >= 0 ? &m.certificates[hint] : nullptr;
  if (known)
    for (size_t k = 0; k < known->size(); ++k) {
      std::vector<double> y = (*known)[k];
      if (!m.Proves(y, loose_body, on, column_slack)) continue;
      std::rotate(known->begin(), known->begin() + static_cast<long>(k),
                  known->begin() + static_cast<long>(k) + 1);
      out.solved = true;
      out.reused = true;
      out.unbalanced = m.Moved(y, loose_body);
      return out;
    }
  // A proof is kept for the next solves with this hint.
  const auto keep = [&](std::vector<double> y) {
    if (!known) return;
    known->insert(known->begin(), std::move(y));
    if (known->size() > kCertificatesPerHint) known->pop_back();
  };
  // The answer of a proof near the focus.
  const auto local = [&](std::vector<double> y) {
    out.solved = out.local = true;
    out.unbalanced = m.Moved(y, loose_body);
    keep(std::move(y));
    return out;
  };
  // 2. The simplex, from `start` or the last basis. With a focus, proofs
  //    near it are looked for (LocalProof) before it or at its pauses (the
  //    constants above); without one, it goes on from where it was.
  m.SetColumns(on);  // columns out first: the rows then added carry fewer entries
  m.SetRows(loose_body);
  if (start) m.StartFrom(*start);
  if (focus >= 0) {
    int n_loose = 0;
    for (bool l : loose_body) n_loose += l;
    struct Pause {
      int after, above, up_to;  // pivots; the regions' sizes (bodies)
    };
    const int near = n_loose >= kNearFromBodies ? 0 : kNearPivotsPerBody * n_loose;
    const Pause pauses[] = {{near, 0, kNearBodies},
                            {kWholeFirstIterations, kNearBodies, COIN_INT_MAX}};
    for (const Pause& p : pauses) {
      if (p.after > out.iterations) {
        m.lp.setMaximumIterations(p.after - out.iterations);
        clp::SolveBySimplex(m.lp);
        out.iterations += m.lp.numberIterations();
        if (clp::StatusOf(m.lp) != clp::Status::kStopped) break;
      }
      std::vector<double> y = m.LocalProof(loose_body, on, focus, column_slack, p.above, p.up_to);
      if (!y.empty()) {
        m.lp.setMaximumIterations(COIN_INT_MAX);
        return local(std::move(y));
      }
    }
    m.lp.setMaximumIterations(COIN_INT_MAX);
  }
  if (focus < 0 || clp::StatusOf(m.lp) == clp::Status::kStopped) {
    clp::SolveBySimplex(m.lp);
    out.iterations += m.lp.numberIterations();
  }

  // 3. A warm start's claim of infeasibility stands when its ray is a
  //    Farkas certificate (or, unchecked, as it is), and its optimum when
  //    its forces balance; otherwise it is checked from the slack basis.
  //    After bounds that change from 0 to ∞ and rows freed, Clp's dual
  //    simplex from the old basis has said "infeasible" of a feasible LP
  //    (Fig. 4, all parts with the top one held, after the other subsets),
  //    and "optimal" with forces of −10¹⁴ that balance to 3 % (the cross
  //    vault, state 46 of a beam-1 search).
  std::vector<double> y;
  bool proved = false;
  const auto read_ray = [&] {
    std::unique_ptr<double[]> ray(m.lp.infeasibilityRay());
    y = ray ? m.FullRay(ray.get()) : std::vector<double>();
    proved = !y.empty() && m.Proves(y, loose_body, on, column_slack);
  };
  clp::Status status = clp::StatusOf(m.lp);
  if (status == clp::Status::kPrimalInfeasible) read_ray();
  if ((status == clp::Status::kPrimalInfeasible && !proved && checked_) ||
      (status == clp::Status::kOptimal && !SolutionBalances())) {
    m.lp.allSlackBasis(true);
    clp::SolveBySimplex(m.lp);
    out.iterations += m.lp.numberIterations();
    out.cold = true;
    status = clp::StatusOf(m.lp);
    if (status == clp::Status::kPrimalInfeasible) read_ray();
  }
  switch (status) {
    case clp::Status::kOptimal:
      if (!SolutionBalances()) {  // not even from the slack basis: no verdict
        m.lp.allSlackBasis(true);
        return out;
      }
      out.solved = out.exists = true;
      return out;
    case clp::Status::kPrimalInfeasible:
      out.solved = true;
      break;
    default:
      m.lp.allSlackBasis(true);  // start afresh next time
      return out;
  }
  // 4. The ray y (row duals' direction): the motion ν = −P y per body.
  if (y.empty()) return out;
  out.unbalanced = m.Moved(y, loose_body);
  if (proved) keep(std::move(y));
  return out;
}

}  // namespace cairn

#pragma once
// The equilibrium LP's data and helpers, shared by static_equilibrium.cpp and
// margin_lp.cpp (private to the mechanics stage; the mathematics is in
// cairn/mechanics/static_equilibrium.h).

#include <coin/ClpSimplex.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <vector>

#include "cairn/mechanics/contact_model.h"
#include "cairn/mechanics/static_equilibrium.h"

namespace cairn::equilibrium_internal {

// Rounding leaves coefficients of ~1e-17 where the geometry says 0 (a rotated
// face's normal, a moment arm along an axis). Kept, they make the simplex's
// bases near-singular (GLPK failed on them with GLP_EFAIL); coefficients below
// this fraction of the largest are dropped (dimensionless).
inline constexpr double kDropRelative = 1e-13;

// The simplex's primal feasibility tolerance (Clp's default is 1e-7 of the
// scaled rows): the forces at rest must balance tightly enough for the LCP
// check, which divides the unbalanced load by the parts' masses.
inline constexpr double kSimplexPrimalTolerance = 1e-10;

// One column of the equilibrium LP: the normal of a contact (direction −1) or
// the pyramid edge n + μ d_k of a frictional one.
struct Generator {
  int contact = -1;
  int direction = -1;
};

// The generators of every contact: D pyramid edges where the LCP has friction
// directions (and friction is wanted), else the normal alone.
std::vector<Generator> MakeGenerators(const ContactLcp& lcp, bool frictionless);

// The wrench (f, τ) at the centroid of side s's body of a unit generator force.
Vector6 GeneratorWrench(const ContactLcp& lcp, const Generator& g, int s);

// Sparse triplets (row, column, value), 0-based, with the dust dropped.
struct Triplets {
  std::vector<int> rows, cols;
  std::vector<double> values;
  void Add(int r, int c, double v) {
    if (v == 0.0) return;
    rows.push_back(r);
    cols.push_back(c);
    values.push_back(v);
  }
  void DropDust() {
    double largest = 0;
    for (double v : values) largest = std::max(largest, std::abs(v));
    size_t kept = 0;
    for (size_t k = 0; k < values.size(); ++k) {
      if (std::abs(values[k]) <= kDropRelative * largest) continue;
      rows[kept] = rows[k], cols[kept] = cols[k], values[kept] = values[k];
      ++kept;
    }
    rows.resize(kept), cols.resize(kept), values.resize(kept);
  }
  CoinPackedMatrix Matrix(int nrows, int ncols) const {
    CoinPackedMatrix m(/*colordered=*/true, rows.data(), cols.data(), values.data(),
                       static_cast<CoinBigIndex>(values.size()));
    // Empty trailing rows or columns (all dust) need the sizes given.
    m.setDimensions(nrows, ncols);
    return m;
  }
};

// The equilibrium LP's data: body b's equation k is row 6 b + k, projected on
// the body's free directions (a planar body's other three rows are empty).
struct EquilibriumLp {
  std::vector<Generator> generators;
  std::vector<Matrix6> P;  // (nb) free projectors
  Triplets a;
  std::vector<double> rhs;  // (6 nb) −P F_ext / load_scale
  int nrows = 0;
  // The unit of the LP's forces: the largest load entry (force units; 1
  // without loads). The LP solvers' tolerances are absolute (Clp: 1e-7 of a
  // row), so a part of mass 1e-15 would sit below them in force units; in
  // these units every problem's loads are O(1).
  double load_scale = 1.0;
};

EquilibriumLp MakeEquilibriumLp(const ContactLcp& lcp, bool frictionless);

// The row duals y of an LP over these rows as a virtual motion per body,
// ν_b = −P_b y_b (a generator's power under ν is minus its reduced cost's
// row part: the duals of the margin and mechanism LPs are their motions).
std::vector<Vector6> MotionOfDuals(const EquilibriumLp& e, const double* y);

// Loads the feasibility problem {A x = rhs, x ≥ 0} into a fresh Clp model.
void Load(const EquilibriumLp& e, ClpSimplex& lp);

// Reads the generator amounts (in load_scale units) into forces and the LCP's
// unknowns, refines them and checks the equilibrium from them. False when the
// residual is too large.
bool ReadEquilibrium(const ContactLcp& lcp, const EquilibriumLp& e, const double* lp_x, int ncols,
                     StaticEquilibrium& out);

}  // namespace cairn::equilibrium_internal

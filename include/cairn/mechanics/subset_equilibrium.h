#pragma once
/// @file
/// Static equilibrium of the sub-assemblies of one assembled configuration,
/// by one linear program kept between solves (`cairn sequence`'s filter,
/// docs/sequence.md).
///
/// A build order's states all sit at the assembled poses, so the contacts of
/// a state are the assembled configuration's contacts between the parts
/// present: the equilibrium LP of a state (static_equilibrium.h) is the LP
/// of the whole component without
///   - the balance rows of the bodies that are absent or held (a held body
///     is balanced by its holder, whatever it pulls or pushes with),
///   - the columns of the contacts that touch an absent body, or join two
///     bodies that are not free.
/// The LP holds only the rows and columns of the state: they are taken out
/// and put in as the states change (its size, and so the factorization's
/// and the pricing's work, is the state's, not the structure's). Successive
/// states differ by a part or a hold, so each solve starts from the last
/// one's basis (Clp's dual simplex, warm), a few pivots where a fresh LP
/// takes hundreds (a claim of infeasibility is believed when the
/// ray is a Farkas certificate, and checked from the slack basis when not). When no equilibrium
/// exists, the dual simplex's infeasibility ray is a virtual motion ν = −P y (the Farkas
/// certificate of the mechanism LP): the bodies it moves are the ones that cannot stand.

#include <memory>
#include <vector>

#include "cairn/mechanics/contact_model.h"

class ClpSimplex;

namespace cairn {

class SubsetEquilibrium {
 public:
  /// The LP of `lcp`: every body, every contact (the assembled component).
  explicit SubsetEquilibrium(const ContactLcp& lcp);
  ~SubsetEquilibrium();
  SubsetEquilibrium(SubsetEquilibrium&&) noexcept;
  SubsetEquilibrium& operator=(SubsetEquilibrium&&) noexcept;
  SubsetEquilibrium(const SubsetEquilibrium&) = delete;
  SubsetEquilibrium& operator=(const SubsetEquilibrium&) = delete;

  struct Answer {
    bool solved = false;  ///< the LP reached a verdict
    bool exists = false;  ///< the free bodies can be balanced by the contacts on
    /// No equilibrium: the bodies the infeasibility ray moves (local
    /// indices); empty when Clp gave no ray.
    std::vector<int> unbalanced;
    int iterations = 0;  ///< dual simplex pivots of this solve
    /// Solved again from the slack basis: a warm claim of infeasibility
    /// whose ray is not a Farkas certificate is checked so.
    bool cold = false;
  };

  /// `present[b]`: body b is there; `free[b]` (present): it must balance
  /// (false: held). Both num_bodies() long.
  Answer Solve(const std::vector<bool>& present, const std::vector<bool>& free);

  int num_bodies() const;

  /// The next solve starts from the slack basis (a cold solve).
  void ForgetBasis();

 private:
  // After a "primal infeasible": whether Clp's ray is a Farkas certificate
  // of it (then no cold solve is needed to believe it).
  bool RayProvesInfeasible() const;
  // After an "optimal": whether its forces are an equilibrium (≥ 0, off
  // where the contact is, balancing every free body's rows).
  bool SolutionBalances() const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cairn

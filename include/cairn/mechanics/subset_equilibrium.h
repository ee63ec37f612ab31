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
/// states differ by a part or a hold, so each solve starts from a basis
/// (Clp's dual simplex, warm): the caller's, a state's with a part fewer
/// (`Basis`), or the last solve's. A claim of infeasibility is believed when
/// its ray is a Farkas certificate, and solved again from the slack basis
/// when not (unless unchecked: `set_checked`). When no equilibrium exists,
/// the ray is a virtual motion ν = −P y (the Farkas certificate of the
/// mechanism LP): the bodies it moves are the ones that cannot stand. Such
/// a proof is kept by the solve's hint and tried first on the next solves
/// with that hint: a mechanism the parts added since do not stop is proved
/// again by a product, without a simplex.
///
/// A part that cannot be placed usually fails near where it goes: with a
/// `focus` (the part placed), the LP of the free bodies a few contacts from
/// it, every body around them held, is solved before the whole LP or at its
/// pauses (a few dozen rows, from the slack basis). Holding the rest only
/// helps the region stand, so a ray
/// of the region's LP that Proves accepts is a proof for the whole LP; on
/// the cross vault such proofs answer almost every state that fails, where
/// the whole LP's warm simplex took a thousand pivots, and the whole LP is
/// left for the states that stand.

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
    /// Proved by the certificate of an earlier solve (no simplex).
    bool reused = false;
    /// Proved by the LP of a few bodies around the focus, the others held.
    bool local = false;
  };

  /// A basis of a solve, by the component's generators and rows (not the
  /// LP's indices, which change as rows and columns come and go): the
  /// generators and the rows whose slacks are basic, and the rows the LP
  /// held (a row held and not basic has its slack at its bound).
  struct Basis {
    std::vector<int> basic_generators;
    std::vector<int> basic_rows;
    std::vector<int> rows;
  };

  /// `present[b]`: body b is there; `free[b]` (present): it must balance
  /// (false: held). Both num_bodies() long. The solve starts from `start`
  /// when given (the basis of a state with a part fewer: its columns keep
  /// their status, the rows it did not hold start with their slacks basic,
  /// the columns it did not hold at 0), else from the last solve's basis.
  /// A proof of infeasibility found with a `hint` ≥ 0 (for instance the
  /// part just placed) is tried first by the next solves with that hint.
  /// With a `focus` body (free; for instance the part just placed), a proof
  /// that moves only bodies near it is looked for too, by the LPs of the
  /// bodies a few contacts from it with every other body held (a few dozen
  /// rows): before the whole LP on large states, at its pauses on small ones.
  Answer Solve(const std::vector<bool>& present, const std::vector<bool>& free,
               const Basis* start = nullptr, int hint = -1, int focus = -1);

  /// Whether a warm claim of infeasibility must come with a Farkas
  /// certificate (default; else it is solved again from the slack basis).
  /// Unchecked, a warm claim with a ray is believed: a filter whose answers
  /// are confirmed later can afford the rare false "infeasible".
  void set_checked(bool checked) { checked_ = checked; }

  /// The basis the last solve ended with (meaningful after an equilibrium
  /// was found).
  Basis CurrentBasis() const;

  int num_bodies() const;

  /// The next solve starts from the slack basis (a cold solve).
  void ForgetBasis();

 private:
  // After an "optimal": whether its forces are an equilibrium (≥ 0, off
  // where the contact is, balancing every free body's rows).
  bool SolutionBalances() const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
  bool checked_ = true;
};

}  // namespace cairn

#pragma once
/// @file
/// Build orders with temporary supports (`cairn sequence`, docs/sequence.md):
/// the parts placed one a step from the fixed parts up, each arriving along a
/// direction free past the parts already placed, every state (the parts
/// placed so far with the supports in place) standing, with the fewest
/// supports in place at once, then the fewest placed in all; and a lower
/// bound that proves how far the order can be from the fewest.
///
/// A **hold** keeps a placed part where it is, as a robot or a crane holds a
/// block: all its freedoms fixed, pulling as well as pushing. A state with
/// held parts is checked as the same assembly with those parts fixed
/// (Assembly::WithHeld). A **prop** is a point support from the ground
/// under a part's face (falsework, a shore: the paper's fixel, a
/// frictionless push along the face's inward normal), at a point of a face
/// that touches no part in the assembled configuration (so it is in no later
/// part's way), chosen as SuggestFixtures chooses fixels: the points that
/// most oppose the part's motion in the state without it
/// (Assembly::WithFixtures). A support goes in at the step whose state
/// needs it and comes out as soon as the state stands without it.
///
/// The search, a beam over states (placed set, supports in place):
///   1. Candidates: the unplaced parts that touch a placed or fixed part and
///      whose arrival is free (no placed or fixed part blocks their removal
///      to infinity along the direction: planning/blocking.h).
///   2. Each candidate p placed: the state stands as it is; only when that
///      gives fewer than `beam_width` children, with one support more of
///      each kind allowed (a child each), on p or on a part the check says
///      moves (a prop at the points most opposing its motion; a hold); then
///      every support the new state does without comes out (the oldest
///      first). With both kinds, the search with holds alone runs too and
///      the better order is kept.
///   3. The children ranked by (most supports in place so far, supports now,
///      placements so far, the placed parts' height against gravity,
///      names, supports by name), the best `beam_width` kept.
/// A state is checked component by component (its free parts joined where
/// they touch), each component's check cached: the equilibrium LP
/// (mechanics/subset_equilibrium.h), then, where it passes a state that the
/// confirmation once rejected or has props, the check's verdict. Every state
/// the returned order passes through is confirmed by AnalyzeConfiguration
/// with the caller's rule (the verdict of `cairn check`).
///
/// The lower bound: every order passes through a state of one part (its
/// first) and one of all parts but one (before its last). When no single
/// part stands on the fixed parts alone, or no assembly missing one part
/// stands, every order needs at least one support in place at some step. On
/// models of at most 10 movable parts, every order is tried. Bounds are
/// proved with holds on the equilibrium LP; they bound props too (a hold on a
/// part does all that props on it can).
///
/// Deterministic: the same document for the parts given in any order, up to
/// ties broken by name.

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cairn/geometry/assembly.h"
#include "cairn/stability/analyze.h"

namespace cairn {

/// The kinds of temporary support the search may use.
enum class TemporaryKind { kHold, kProp };
const char* to_string(TemporaryKind kind);

/// Options of FindBuildSequence.
struct SequenceOptions {
  /// The kinds of support allowed (`--temporary hold|prop|both`): at least one.
  bool holds = true;
  bool props = false;
  /// The most supports in place at once; the search gives up beyond (-1: no
  /// bound).
  int max_temporary = -1;
  /// No supports at all (`--max-temporary 0`) is max_temporary = 0.
  /// Removal directions (unit, world); a part arrives along the reverse of
  /// the first that is free. Empty: against gravity only (arrive from above).
  std::vector<Vector3> directions;
  /// Instead of `directions`: the NDBG's cells of the assembled configuration
  /// (planning/blocking.h), the closest to straight up first, each at its
  /// cell's direction (`--directions ndbg`).
  bool ndbg = false;
  /// States kept per step (1: greedy).
  int beam_width = 4;
  /// Threads (0: every core): with both kinds of support, the search with
  /// holds alone and the one with both run side by side. No answer depends
  /// on it.
  int threads = 0;
  /// The most state checks cached (a key of a byte per part and the parts
  /// that move: about 600 bytes each on the 399-block Armadillo, so ≈ 120 MB
  /// at the default); when full the cache starts afresh. No answer depends
  /// on it, only the time.
  size_t max_cached_states = 200000;
  /// The check of a state (rule, require-strong is the caller's).
  StabilityOptions stability;
  /// Also require strong stability of every state (`--require strong`).
  bool require_strong = false;
  /// Called before each state check; may throw to abandon the search.
  std::function<void()> checkpoint;
  /// Seconds the search may take (0: no limit). At the limit, or when
  /// `stop` says so (a SIGINT), the search ends with the best order so far
  /// (BuildSequence::stopped), its states checked again and its bound.
  double time_limit = 0;
  std::function<bool()> stop;
  /// Told the parts placed, the best so far and the bound.
  std::function<void(const std::string&)> status;
  /// Keep each state's contacts, from the confirmation's check
  /// (SequenceStep::contacts: the page draws their forces).
  bool record_contacts = false;
};

/// One temporary support.
struct TemporarySupport {
  TemporaryKind kind = TemporaryKind::kHold;
  int part = -1;
  /// A prop: the point of the part's face it pushes at and the direction it
  /// pushes (unit, into the part), world frame, assembled pose. A hold: the
  /// part's centroid, and 0.
  Vector3 point{0, 0, 0};
  Vector3 normal{0, 0, 0};
  /// In place (SequenceStep::in_place), what it carries, from the state's
  /// check (force units, world): a hold, the force and torque (about the
  /// part's centroid) it exerts on the part so that the part's weight and the
  /// pushes of the free parts on it balance (contacts with fixed or other
  /// held parts are not counted: both are held); a prop, its push (along
  /// `normal`), torque 0. Zero in SequenceStep::added and removed.
  Vector3 force{0, 0, 0};
  Vector3 torque{0, 0, 0};
  /// The same support (kind, part, point, normal).
  bool operator==(const TemporarySupport& o) const {
    return kind == o.kind && part == o.part && point == o.point && normal == o.normal;
  }
};

/// One step: a part placed, and the supports in place after it.
struct SequenceStep {
  int part = -1;
  Vector3 direction{0, 0, 0};  ///< the arrival direction (unit, world)
  std::vector<TemporarySupport> in_place;
  /// Supports put in (just before the part arrives) and taken out (once it
  /// is in place) at this step.
  std::vector<TemporarySupport> added, removed;
  /// The state's check (the caller's rule): stands, and the proof.
  bool stands = false;
  StabilityProof stability = StabilityProof::kNone;
  /// With SequenceOptions::record_contacts: the state's contacts and their
  /// forces, as the check found them.
  std::vector<ContactReport> contacts;
};

/// What FindBuildSequence found.
struct BuildSequence {
  bool complete = false;             ///< every movable part placed, every state standing
  std::vector<TemporaryKind> kinds;  ///< the kinds of support the search could use
  std::vector<SequenceStep> steps;
  int max_in_place = 0;  ///< the most supports in place at once
  int placements = 0;    ///< supports put in, in all
  int lower_bound = 0;   ///< no order needs fewer at once (proved)
  std::string lower_bound_reason;
  bool optimal() const { return complete && max_in_place == lower_bound; }
  std::string message;  ///< why not complete
  /// The search ended at its time limit or when asked to stop: the order is
  /// the best so far (complete only if it got to the end first).
  bool stopped = false;
  int states_checked = 0;
  /// Times the confirmation rejected a state of the order the equilibrium
  /// LP had let through, and the search went on from there with the verdict.
  int repairs = 0;
  /// States the equilibrium LP passed and the check's verdict rejected
  /// before they entered the beam (each replaced there by the next best).
  int verdict_rejections = 0;
  int cache_hits = 0;
  int warm_starts = 0;
};

/// The build order of the movable parts of `assembly`, from its fixed parts
/// up (see the file comment). @throws std::invalid_argument on a bad option
/// (a zero direction, beam_width < 1).
BuildSequence FindBuildSequence(const Assembly& assembly, const SequenceOptions& options = {});

}  // namespace cairn

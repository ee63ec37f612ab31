#pragma once
// The perturbation of q that breaks the ties of degenerate LCPs (private to
// the lcp stage; see include/cairn/lcp/factored_lcp.h for why it works).
//
// Its size δ (relative to the data's scale s = max(|q|∞, |M|)) is tied to the
// pivot tolerance τ and the solution tolerance ε (both relative to s):
//
//   - δ ≫ τ. τ is the solver's bound on the roundoff of a pivoted entry or
//     value: anything at or below τ counts as zero. A degenerate basic value
//     is zero in exact arithmetic and ±τ in floating point; the perturbation
//     adds δ ρ_i (ρ_i ∈ [½, 1)) to it, which must dwarf that roundoff, or the
//     ties are again broken by roundoff (the wrong bases of the unperturbed
//     path). Margin: δ / τ.
//   - δ ≪ ε. The path ends on a basis of the perturbed problem, which is
//     re-solved with the true q and must pass the check at ε; a basis that is
//     feasible only thanks to the perturbation has values ≈ −δ, and the
//     fallback (the perturbed iterate itself) errs by ≈ δ. Margin: ε / δ.
//
// Both margins are ratios, so the perturbation is put at the geometric mean,
// δ = √(τ ε), which gives both the same margin √(ε / τ): with the default
// τ = 16 n 2⁻⁵² and ε = 1e-8 that is 170 at n = 100 (δ = 6e-11), 30 at
// n = 3000 (3e-10) and 10 at n = 30 000 (1e-9; the same δ as the fixed 1e-9
// of before, which left a margin of 10 on the τ side only and 10⁴ on the
// other at n = 100). When τ ≥ ε there is no room: δ = τ · kMinMargin then.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace cairn::internal {

// The least δ / τ ever used (when τ approaches ε).
inline constexpr double kMinMargin = 4.0;

// δ from the pivot tolerance τ and the solution tolerance ε (both relative).
inline double PerturbationSize(double pivot_tolerance, double solution_tolerance) {
  return std::max(std::sqrt(pivot_tolerance * solution_tolerance), kMinMargin * pivot_tolerance);
}

// ρ_i ∈ [½, 1): splitmix64 of (seed, i), the same on every platform and run.
inline double PerturbationWeight(uint64_t seed, uint64_t i) {
  uint64_t x = seed * 0x9E3779B97F4A7C15ull + i + 1;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return 0.5 + 0.5 * static_cast<double>(x >> 11) * 0x1.0p-53;
}

}  // namespace cairn::internal

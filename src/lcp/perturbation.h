#pragma once
// The perturbation of q that breaks the ties of degenerate LCPs (private to
// the lcp stage; see include/cairn/lcp/factored_lcp.h for why it works).

#include <cstdint>

namespace cairn::internal {

// The perturbation of q, relative to the data's scale: large against the
// roundoff of pivoted values (~1e-14), small against the solution tolerance
// (1e-8), so the final basis re-solved with the true q passes the check.
inline constexpr double kLcpPerturbation = 1e-9;

// ρ_i ∈ [½, 1): splitmix64 of (seed, i), the same on every platform and run.
inline double PerturbationWeight(uint64_t seed, uint64_t i) {
  uint64_t x = seed * 0x9E3779B97F4A7C15ull + i + 1;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return 0.5 + 0.5 * static_cast<double>(x >> 11) * 0x1.0p-53;
}

}  // namespace cairn::internal

#pragma once
/// @file
/// Three tiers of checks (after Drake's drake_assert.h):
///  - CAIRN_ASSERT(cond): internal invariant, compiled in only with
///    CAIRN_ENABLE_ASSERTS (the test build); aborts with the location.
///  - CAIRN_CHECK(cond): an invariant that must never fail; always on; aborts.
///  - CAIRN_THROW_UNLESS(cond, msg): caller input at a public boundary;
///    throws std::invalid_argument carrying `msg` (which should name the
///    offending values).

#include <sstream>
#include <stdexcept>
#include <string>

namespace cairn::internal {
[[noreturn]] void AbortWithMessage(const char* kind, const char* condition, const char* file,
                                   int line);
}  // namespace cairn::internal

#define CAIRN_CHECK(cond)                                                                       \
  do {                                                                                          \
    if (!(cond)) ::cairn::internal::AbortWithMessage("CAIRN_CHECK", #cond, __FILE__, __LINE__); \
  } while (0)

#if defined(CAIRN_ENABLE_ASSERTS)
#define CAIRN_ASSERT(cond)                                                                       \
  do {                                                                                           \
    if (!(cond)) ::cairn::internal::AbortWithMessage("CAIRN_ASSERT", #cond, __FILE__, __LINE__); \
  } while (0)
#else
#define CAIRN_ASSERT(cond) \
  do {                     \
  } while (false && (cond))
#endif

#define CAIRN_THROW_UNLESS(cond, msg)                     \
  do {                                                    \
    if (!(cond)) {                                        \
      std::ostringstream cairn_throw_os_;                 \
      cairn_throw_os_ << msg << " [failed: " #cond "]";   \
      throw std::invalid_argument(cairn_throw_os_.str()); \
    }                                                     \
  } while (0)

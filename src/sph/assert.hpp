#pragma once
// SPHCLIP_ASSERT: the first of the three error tiers (STYLE.md, "Errors"), a
// programmer's mistake. Unlike <cassert>'s assert, which CMake's
// RelWithDebInfo turns off with -DNDEBUG, it stays on in every build but
// Release and MinSizeRel, and in any sanitizer build, so the tests under
// AddressSanitizer check the invariants too. It is not for user input
// (that is an InputError) nor for numerical trouble (the watchdog).

#include <cstdio>
#include <cstdlib>

namespace sph {

#ifdef SPHCLIP_ASSERTS
inline constexpr bool asserts_enabled = true;
#else
inline constexpr bool asserts_enabled = false;
#endif

[[noreturn]] inline void assertion_failed(const char* expression, const char* file, int line,
                                          const char* function) {
    std::fprintf(stderr, "%s:%d: %s: internal error, assertion failed: %s\n", file, line, function,
                 expression);
    std::fflush(stderr);
    std::abort();
}

} // namespace sph

#ifdef SPHCLIP_ASSERTS
#define SPHCLIP_ASSERT(condition)                                                                  \
    ((condition) ? static_cast<void>(0)                                                            \
                 : ::sph::assertion_failed(#condition, __FILE__, __LINE__, __func__))
#else
// Not evaluated, but still compiled, so an assertion cannot rot.
#define SPHCLIP_ASSERT(condition) static_cast<void>(sizeof(static_cast<bool>(condition)))
#endif

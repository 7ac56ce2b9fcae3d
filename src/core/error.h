#pragma once
// penumbra::Error (the public error type) plus the internal invariant check. Library code throws
// Error for user mistakes; the CLI catches it and prints the one-line message with exit code 1.
#include "penumbra/error.h"

namespace penumbra {

// Invariant checks that are programming errors, not user errors: active unless NDEBUG, or always
// when PENUMBRA_ENABLE_ASSERTS is defined (the CI build that runs the suite with assertions on).
#if defined(NDEBUG) && !defined(PENUMBRA_ENABLE_ASSERTS)
#define PENUMBRA_ASSERT(cond) ((void)0)
#else
#define PENUMBRA_ASSERT(cond) \
    ((cond) ? (void)0 : ::penumbra::detail::assertFailed(#cond, __FILE__, __LINE__))
#endif

namespace detail {
[[noreturn]] void assertFailed(const char* expression, const char* file, int line);
}

}  // namespace penumbra

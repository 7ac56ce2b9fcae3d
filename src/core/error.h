#pragma once
// User-facing errors: bad files, bad settings, no Vulkan device. Library code throws these; the CLI
// catches them and prints the one-line message with a non-zero exit. Never exit() in library code.
#include <stdexcept>
#include <string>

namespace penumbra {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Invariant checks that are programming errors, not user errors: active in debug builds only.
#ifdef NDEBUG
#define PENUMBRA_ASSERT(cond) ((void)0)
#else
#define PENUMBRA_ASSERT(cond) \
    ((cond) ? (void)0 : ::penumbra::detail::assertFailed(#cond, __FILE__, __LINE__))
#endif

namespace detail {
[[noreturn]] void assertFailed(const char* expression, const char* file, int line);
}

}  // namespace penumbra

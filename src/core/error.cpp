#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace penumbra::detail {

void assertFailed(const char* expression, const char* file, int line) {
    std::fprintf(stderr, "penumbra: internal assertion failed: %s (%s:%d)\n", expression, file, line);
    std::abort();
}

}  // namespace penumbra::detail

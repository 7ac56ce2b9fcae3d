#pragma once
// User-facing errors: bad files, bad settings, no Vulkan device, a failed GPU call. Everything in
// Penumbra reports them by throwing penumbra::Error with a one-line message; the library never
// exits the process.
#include <stdexcept>
#include <string>

namespace penumbra {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace penumbra

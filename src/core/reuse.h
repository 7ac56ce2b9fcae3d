#pragma once
// Resetting an object that a steady-state frame refills, without giving its heap storage back: the
// vectors named keep their capacity (cleared), everything else returns to its default value. Frames
// that refill such objects allocate nothing once their storage has grown to a frame's size.
#include <tuple>
#include <utility>
#include <vector>

namespace penumbra {

template <typename T, typename... Elements>
void resetKeepingStorage(T& value, std::vector<Elements> T::*... members) {
    std::tuple<std::vector<Elements>...> kept{std::move(value.*members)...};
    value = T{};
    [&]<size_t... I>(std::index_sequence<I...>) {
        ((value.*members = std::move(std::get<I>(kept)), (value.*members).clear()), ...);
    }(std::index_sequence_for<Elements...>{});
}

}  // namespace penumbra

#pragma once
// The message of the penumbra::Error an action throws: tests check what the user would read.
#include <string>
#include <utility>

#include "penumbra/error.h"

namespace penumbra::testing {

// e.what() of the Error that `action()` throws, or "" when it throws none.
template <typename Action>
std::string errorMessage(Action&& action) {
    try {
        std::forward<Action>(action)();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace penumbra::testing

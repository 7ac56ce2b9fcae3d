#pragma once
// One scene load against its SceneLimits: what it has used so far, and the one-line refusal when a
// budget would be exceeded. Not part of the public API.
#include <cstdint>
#include <string>

#include "penumbra/scene_limits.h"

namespace penumbra {

// "over the fileBytes budget of 1073741824 (raise it with --limit fileBytes=N, or SceneLimits::maxFileBytes)"
std::string overBudget(const SceneLimits& limits, uint64_t SceneLimits::*field);

class LoadBudget {
public:
    // `name`: the scene file, the first word of every refusal.
    LoadBudget(std::string name, const SceneLimits& limits) : name_(std::move(name)), limits_(limits) {}

    const SceneLimits& limits() const { return limits_; }
    const std::string& name() const { return name_; }

    // Throws Error "<name>: <what> is <amount>, over the ... budget ..." when amount > the limit.
    void check(uint64_t amount, uint64_t SceneLimits::*field, const std::string& what) const;
    // Adds `amount` to the running total of `field` (textureBytes, vertices or indices), refusing it
    // first when the total would pass the limit: "<name>: <what> brings the <budget> to N, over ...".
    void charge(uint64_t amount, uint64_t SceneLimits::*field, const std::string& what);

private:
    uint64_t& totalOf(uint64_t SceneLimits::*field);

    std::string name_;
    const SceneLimits& limits_;
    uint64_t textureBytes_ = 0, vertices_ = 0, indices_ = 0;
};

}  // namespace penumbra

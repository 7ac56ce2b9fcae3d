#include "penumbra/scene_limits.h"

#include <array>
#include <cctype>

#include "core/error.h"
#include "scene/load_budget.h"

namespace penumbra {

namespace {

constexpr std::array<SceneLimitKey, 9> kKeys = {{
    {"fileBytes", "maxFileBytes", &SceneLimits::maxFileBytes, "bytes of the scene file, and of each file it references"},
    {"imageBytes", "maxImageBytes", &SceneLimits::maxImageBytes,
     "bytes of one image decoded to RGBA8 (width x height x 4), from its header before decoding"},
    {"textureBytes", "maxTextureBytes", &SceneLimits::maxTextureBytes, "bytes of every image decoded to RGBA8, together"},
    {"vertices", "maxVertices", &SceneLimits::maxVertices, "vertices of every mesh together"},
    {"indices", "maxIndices", &SceneLimits::maxIndices, "triangle indices of every mesh together"},
    {"nodes", "maxNodes", &SceneLimits::maxNodes, "nodes in the file"},
    {"nodeDepth", "maxNodeDepth", &SceneLimits::maxNodeDepth, "depth of the node hierarchy (a root node is at depth 1)"},
    {"lights", "maxLights", &SceneLimits::maxLights, "KHR_lights_punctual lights in the file"},
    {"jsonDepth", "maxJsonDepth", &SceneLimits::maxJsonDepth, "nesting of arrays and objects in the glTF's JSON"},
}};

const SceneLimitKey& keyOf(uint64_t SceneLimits::*field) {
    for (const SceneLimitKey& key : kKeys)
        if (key.field == field) return key;
    throw Error("internal: a SceneLimits member without a key");
}

// "64M" = 64 * 2^20; false for anything but digits with an optional K, M or G.
bool parseAmount(const std::string& text, uint64_t& value) {
    if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0]))) return false;
    size_t digits = 0;
    unsigned __int128 amount = 0;
    while (digits < text.size() && std::isdigit(static_cast<unsigned char>(text[digits]))) {
        amount = amount * 10 + unsigned(text[digits] - '0');
        if (amount > UINT64_MAX) return false;
        ++digits;
    }
    const std::string suffix = text.substr(digits);
    unsigned shift = 0;
    if (suffix == "K") shift = 10;
    else if (suffix == "M") shift = 20;
    else if (suffix == "G") shift = 30;
    else if (!suffix.empty()) return false;
    amount <<= shift;
    if (amount > UINT64_MAX) return false;
    value = uint64_t(amount);
    return true;
}

}  // namespace

std::span<const SceneLimitKey> sceneLimitKeys() { return kKeys; }

void setSceneLimit(SceneLimits& limits, const std::string& assignment) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos)
        throw Error("--limit expects NAME=VALUE (e.g. fileBytes=64M), got '" + assignment + "'");
    const std::string name = assignment.substr(0, equals);
    uint64_t value = 0;
    for (const SceneLimitKey& key : kKeys) {
        if (name != key.name) continue;
        if (!parseAmount(assignment.substr(equals + 1), value))
            throw Error("--limit " + assignment + ": the value must be a whole number, optionally followed by K, M or G");
        limits.*key.field = value;
        return;
    }
    std::string names;
    for (const SceneLimitKey& key : kKeys) names += (names.empty() ? "" : ", ") + std::string(key.name);
    throw Error("--limit " + assignment + ": unknown budget '" + name + "' (the budgets are " + names + ")");
}

std::string overBudget(const SceneLimits& limits, uint64_t SceneLimits::*field) {
    const SceneLimitKey& key = keyOf(field);
    return "over the " + std::string(key.name) + " budget of " + std::to_string(limits.*field) + " (raise it with --limit " +
           key.name + "=N, or SceneLimits::" + key.member + ")";
}

void LoadBudget::check(uint64_t amount, uint64_t SceneLimits::*field, const std::string& what) const {
    if (amount > limits_.*field)
        throw Error(name_ + ": " + what + " is " + std::to_string(amount) + ", " + overBudget(limits_, field));
}

void LoadBudget::charge(uint64_t amount, uint64_t SceneLimits::*field, const std::string& what) {
    uint64_t& total = totalOf(field);
    const uint64_t sum = amount > UINT64_MAX - total ? UINT64_MAX : total + amount;
    if (sum > limits_.*field)
        throw Error(name_ + ": " + what + " brings the " + keyOf(field).name + " to " + std::to_string(sum) + ", " +
                    overBudget(limits_, field));
    total = sum;
}

uint64_t& LoadBudget::totalOf(uint64_t SceneLimits::*field) {
    if (field == &SceneLimits::maxTextureBytes) return textureBytes_;
    if (field == &SceneLimits::maxVertices) return vertices_;
    if (field == &SceneLimits::maxIndices) return indices_;
    throw Error("internal: " + std::string(keyOf(field).name) + " is not a running total");
}

}  // namespace penumbra

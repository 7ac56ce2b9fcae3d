// Typed, validated reads of the shadow properties in glTF `extras` (the table of docs/scene-format.md).
#include <cmath>
#include <sstream>

#include "scene/gltf_internal.h"

namespace penumbra::gltf {
namespace {

const tinygltf::Value* findExtra(const tinygltf::Value& extras, const char* key) {
    if (!extras.IsObject() || !extras.Has(key)) return nullptr;
    return &extras.Get(key);
}

std::string formatNumber(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

}  // namespace

std::optional<bool> extraBool(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object,
                              const char* key) {
    const tinygltf::Value* value = findExtra(extras, key);
    if (!value) return std::nullopt;
    if (!value->IsBool()) ctx.fail(object + ": extras." + key + " must be true or false");
    return value->Get<bool>();
}

std::optional<float> extraNumber(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object,
                                 const char* key, float minValue, float maxValue) {
    const tinygltf::Value* value = findExtra(extras, key);
    if (!value) return std::nullopt;
    const std::string range = std::isinf(maxValue) ? ">= " + formatNumber(minValue)
                                                   : "in [" + formatNumber(minValue) + ", " + formatNumber(maxValue) + "]";
    if (!value->IsNumber()) ctx.fail(object + ": extras." + key + " must be a number " + range);
    const double number = value->GetNumberAsDouble();
    if (!std::isfinite(number) || number < minValue || number > maxValue)
        ctx.fail(object + ": extras." + key + " must be a number " + range + ", got " + formatNumber(number));
    return float(number);
}

std::optional<size_t> extraEnum(const LoadContext& ctx, const tinygltf::Value& extras, const std::string& object,
                                const char* key, const std::vector<std::string>& allowed) {
    const tinygltf::Value* value = findExtra(extras, key);
    if (!value) return std::nullopt;
    std::string choices;
    for (const std::string& a : allowed) choices += (choices.empty() ? "\"" : ", \"") + a + "\"";
    if (value->IsString()) {
        const std::string& text = value->Get<std::string>();
        for (size_t i = 0; i < allowed.size(); ++i)
            if (allowed[i] == text) return i;
        ctx.fail(object + ": extras." + key + " must be one of " + choices + ", got \"" + text + "\"");
    }
    ctx.fail(object + ": extras." + key + " must be one of " + choices);
}

}  // namespace penumbra::gltf

#include "app/bench_variations.h"

#include <algorithm>
#include <cmath>

namespace penumbra {

const std::vector<BenchVariation>& benchVariations() {
    using F = ShadowFilter;
    using B = CascadeBlend;
    // Sizes go up and down (new atlases every step), and every filter, blend and cascade count
    // appears with more and fewer shadowed lights.
    static const std::vector<BenchVariation> kCycle = {
        {1024, 1024, 4, F::PCF2x2, F::PCF5x5, B::Hard, 1.0f},
        {2048, 512, 2, F::PCF3x3, F::PCF2x2, B::Soft, 0.5f},
        {512, 2048, 1, F::PCF5x5, F::PCF7x7, B::Dither, 0.25f},
        {4096, 1024, 3, F::PCF7x7, F::PCF3x3, B::Hard, 0.0f},
        {1024, 4096, 4, F::PCF3x3, F::PCF5x5, B::Soft, 0.75f},
        {256, 256, 2, F::PCF2x2, F::PCF2x2, B::Dither, 1.0f},
        {2048, 2048, 4, F::PCF5x5, F::PCF7x7, B::Soft, 0.5f},
        {1024, 512, 1, F::PCF7x7, F::PCF3x3, B::Hard, 0.25f},
    };
    return kCycle;
}

Settings variedSettings(const Settings& base, const BenchVariation& step) {
    Settings settings = base;
    ShadowSettings& shadows = settings.shadows;
    shadows.directional.atlasSize = step.directionalAtlas;
    shadows.spot.atlasSize = step.spotAtlas;
    shadows.directional.cascadeCount = step.cascadeCount;
    shadows.directional.filter = step.directionalFilter;
    shadows.spot.filter = step.spotFilter;
    shadows.directional.cascadeBlend = step.blend;
    validateSettings(settings);
    return settings;
}

uint32_t applyShadowedLights(Renderer& renderer, const std::vector<Light>& original, float share) {
    const uint32_t keep = uint32_t(std::lround(share * float(original.size())));
    uint32_t shadowed = 0;
    for (uint32_t i = 0; i < original.size(); ++i) {
        Light light = original[i];
        if (i >= keep) light.shadows = LightShadows::None;
        shadowed += light.shadows != LightShadows::None;
        renderer.setLight(i, light);
    }
    return shadowed;
}

nlohmann::json variationJson(uint32_t period, const std::vector<MemorySample>& samples) {
    nlohmann::json json;
    json["period"] = period;
    json["steps"] = benchVariations().size();
    json["samples"] = nlohmann::json::array();
    double hostMax = 0.0, deviceMax = 0.0;
    for (const MemorySample& s : samples) {
        json["samples"].push_back({{"frame", s.frame}, {"step", s.step}, {"host_rss_mb", s.hostRssMegabytes},
                                   {"device_mb", s.deviceMegabytes}, {"shadowedLights", s.shadowedLights}});
        hostMax = std::max(hostMax, s.hostRssMegabytes);
        deviceMax = std::max(deviceMax, s.deviceMegabytes);
    }
    // Growth: the same step of the second and the last full cycle. The atlas sizes differ from step to
    // step, so only equal steps compare; the first cycle is where the memory blocks grow to the
    // largest step's need, so it is not the baseline. 0 when fewer than three cycles ran.
    const size_t steps = benchVariations().size();
    double hostGrowth = 0.0, deviceGrowth = 0.0;
    if (samples.size() >= 3 * steps) {
        const size_t lastCycle = (samples.size() / steps - 1) * steps;
        for (size_t i = 0; i < steps; ++i) {
            hostGrowth = std::max(hostGrowth, samples[lastCycle + i].hostRssMegabytes - samples[steps + i].hostRssMegabytes);
            deviceGrowth =
                std::max(deviceGrowth, samples[lastCycle + i].deviceMegabytes - samples[steps + i].deviceMegabytes);
        }
    }
    if (!samples.empty()) {
        json["host_rss_mb"] = {{"first", samples.front().hostRssMegabytes}, {"last", samples.back().hostRssMegabytes},
                               {"max", hostMax}, {"growth", hostGrowth}};
        json["device_mb"] = {{"first", samples.front().deviceMegabytes}, {"last", samples.back().deviceMegabytes},
                             {"max", deviceMax}, {"growth", deviceGrowth}};
    }
    return json;
}

}  // namespace penumbra

#pragma once
// `penumbra bench --vary-settings`: the long-run mode (memory must stay flat). Every `period` timed
// frames the bench moves to the next step of a fixed cycle that changes the directional and spot
// atlas sizes, the cascade count and blend, both filters, and (through Renderer::setLight) how many
// of the scene's lights cast shadows, so that every reallocation path runs again and again; host and
// device memory are sampled at the end of every period, to show that they stay flat.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "penumbra/renderer.h"
#include "penumbra/settings.h"

namespace penumbra {

struct BenchVariation {
    uint32_t directionalAtlas = 1024, spotAtlas = 1024, cascadeCount = 4;
    ShadowFilter directionalFilter = ShadowFilter::PCF2x2, spotFilter = ShadowFilter::PCF5x5;
    CascadeBlend blend = CascadeBlend::Hard;
    float shadowedLightShare = 1.0f;  // of the scene's lights, the first this share keep their shadows
};

// The cycle the bench walks through; step i of a run is kVariations[i % size].
const std::vector<BenchVariation>& benchVariations();

// `base` with the step's settings (validated).
Settings variedSettings(const Settings& base, const BenchVariation& step);
// Gives the first round(share * count) of `original`'s lights their own shadow mode and the rest
// none, through Renderer::setLight; returns how many cast shadows.
uint32_t applyShadowedLights(Renderer& renderer, const std::vector<Light>& original, float share);

struct MemorySample {
    uint64_t frame = 0;
    uint32_t step = 0;
    double hostRssMegabytes = 0.0;
    double deviceMegabytes = 0.0;
    uint32_t shadowedLights = 0;
};

// The JSON "vary" block: the period, each sample, and first / last / max / growth of host and device
// memory (growth: the largest increase between the same step of the second and of the last cycle;
// the first cycle is where the memory blocks grow to the largest step's need).
nlohmann::json variationJson(uint32_t period, const std::vector<MemorySample>& samples);

}  // namespace penumbra

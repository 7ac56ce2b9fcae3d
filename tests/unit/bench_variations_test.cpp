// penumbra bench --vary-settings: the cycle of settings and the memory summary.
#include <set>

#include <gtest/gtest.h>

#include "app/bench_variations.h"

using namespace penumbra;

namespace {

// `cycles` full cycles of samples; every step of cycle c holds base[c] MB of host and device memory.
std::vector<MemorySample> cyclesOf(const std::vector<double>& base) {
    std::vector<MemorySample> samples;
    const uint32_t steps = uint32_t(benchVariations().size());
    for (size_t c = 0; c < base.size(); ++c)
        for (uint32_t s = 0; s < steps; ++s)
            samples.push_back({uint64_t(samples.size() + 1) * 100, s, base[c] + s, 2.0 * base[c] + s, 1});
    return samples;
}

}  // namespace

TEST(BenchVariations, EveryStepIsValidAndTheCycleChangesEverySetting) {
    std::set<uint32_t> directional, spot, cascades;
    std::set<int> blends, filters;
    for (const BenchVariation& step : benchVariations()) {
        const Settings settings = variedSettings(Settings{}, step);  // throws when invalid
        directional.insert(settings.shadows.directional.atlasSize);
        spot.insert(settings.shadows.spot.atlasSize);
        cascades.insert(settings.shadows.directional.cascadeCount);
        blends.insert(int(settings.shadows.directional.cascadeBlend));
        filters.insert(int(settings.shadows.directional.filter));
    }
    EXPECT_GE(directional.size(), 3u);
    EXPECT_GE(spot.size(), 3u);
    EXPECT_EQ(cascades.size(), 4u);
    EXPECT_EQ(blends.size(), 3u);
    EXPECT_EQ(filters.size(), 4u);
}

TEST(BenchVariations, MemoryThatGrowsOnlyInTheFirstCycleHasNoGrowth) {
    const nlohmann::json json = variationJson(100, cyclesOf({10.0, 50.0, 50.0, 50.0}));
    EXPECT_EQ(json["samples"].size(), 4 * benchVariations().size());
    EXPECT_DOUBLE_EQ(json["host_rss_mb"]["growth"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(json["device_mb"]["growth"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(json["host_rss_mb"]["first"].get<double>(), 10.0);
}

TEST(BenchVariations, MemoryThatKeepsGrowingAfterTheFirstCycleIsGrowth) {
    const nlohmann::json json = variationJson(100, cyclesOf({10.0, 50.0, 53.0, 57.0}));
    EXPECT_DOUBLE_EQ(json["host_rss_mb"]["growth"].get<double>(), 7.0);
    EXPECT_DOUBLE_EQ(json["device_mb"]["growth"].get<double>(), 14.0);
}

TEST(BenchVariations, FewerThanThreeCyclesReportNoGrowth) {
    const nlohmann::json json = variationJson(100, cyclesOf({10.0, 50.0}));
    EXPECT_DOUBLE_EQ(json["host_rss_mb"]["growth"].get<double>(), 0.0);
}

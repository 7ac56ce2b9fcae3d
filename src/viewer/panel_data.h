#pragma once
// What the panels show, without a window (so it is unit-tested): the cascade split bar's spans, the
// stats panel's line of shadowed lights, and the camera combo's entries.
#include <string>
#include <vector>

#include "penumbra/scene.h"
#include "penumbra/settings.h"
#include "penumbra/shadow_stats.h"

namespace penumbra::viewer {

// The cascade split bar: where each cascade ends, as a fraction of shadows.maxDistance.
struct SplitBar {
    std::vector<float> ends;  // one per cascade, in [0, 1], not decreasing
    bool computed = false;    // the frame's splits (cascadeSplits log / practical), not the editable ratios
};

// Manual splits: the cascade ratios (the last cascade ends at 1). Log and practical splits: the
// frame's own, from its shadow stats (directional.cascadeSplits, metres) over maxDistance; no ends
// before a frame has finished (no splits).
SplitBar splitBarOf(const Settings& settings, const ShadowPlanStats& shadows);

// "directional lights reserved R, dropped D; spot/point reserved R, dropped D" from a frame's shadow
// stats (directional dropped: lightsConsidered - reserved).
std::string shadowLightCounts(const ShadowPlanStats& shadows);

// "[3, 5, 0]": per-tile counts as the stats panel prints them.
std::string countList(const std::vector<uint64_t>& counts);

// The camera combo's entries: the scene's camera (index -1), then each glTF camera by its name (index
// 0, 1, ...; "camera N" when it has none).
std::vector<std::string> cameraChoices(const Scene& scene);

}  // namespace penumbra::viewer

#pragma once
// Plans the spot and point light shadows of one frame into the "other" atlas: reservation
// (spot_reservation.h), dynamic tiling with scissored borders (spot_atlas_layout.h), one perspective
// view per spot light and six 90° views per point light (spot_projection.h), per-tile caster lists
// (spot_culling.h), and the packed OtherShadowData for the lit pass.
#include <vector>

#include "shadows/shadow_planner.h"

namespace penumbra {

// Filter reach in texels beyond the sample point: 1 for the bilinear 2x2 tap, else filterSize + 1
// (the tent's outermost bilinear fetch reads that far).
float otherShadowFilterReach(bool soft, ShadowFilter filter);

// casters = shadowCasterInstances(scene). shadowDistance drives the distance fade, as for directional
// lights.
OtherShadowPlan planOtherShadows(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                                 const std::vector<uint32_t>& casters, float shadowDistance, bool cullCasters = true);
// The same into `plan` (replaced), with `reservation` as working storage: both keep their storage, so
// planning again into the same two allocates nothing once they are warm.
void planOtherShadows(const Scene& scene, const CameraView& camera, const ShadowSettings& settings,
                      const std::vector<uint32_t>& casters, float shadowDistance, bool cullCasters, OtherShadowPlan& plan,
                      OtherLightReservation& reservation, uint64_t casterEpoch = 0);

}  // namespace penumbra

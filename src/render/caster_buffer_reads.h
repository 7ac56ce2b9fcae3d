#pragma once
// ShadowSystem's read of an engine's caster buffers into a Scene (caster_buffer_reads.cpp).
#include "gpu/device.h"
#include "penumbra/caster_buffers.h"

namespace penumbra {

// Checks the description (validateCasterBuffers), copies the streams, indices and alpha textures from
// the caller's objects after everything submitted to the queue before (one wait each), and builds the
// Scene of sceneFromCasterBuffers. Throws penumbra::Error.
Scene readCasterBuffers(gpu::Device& device, const CasterBuffers& casters, std::vector<Light> lights);

}  // namespace penumbra

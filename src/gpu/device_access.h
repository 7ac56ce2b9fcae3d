#pragma once
// What the library's own layers and the tests reach of a penumbra::Device beyond its public API: the
// gpu::Device behind it (render/ draws on it), and a device with faults injected (tests).
#include "gpu/device.h"
#include "penumbra/device.h"

namespace penumbra {

struct DeviceAccess {
    static gpu::Device& backend(Device& device) { return *device.device_; }
    // A device made with gpu::DeviceOptions, e.g. {options, faults}: PENUMBRA_FAULT_INJECTION is
    // not read.
    static Device makeDevice(const gpu::DeviceOptions& options);
};

namespace gpu {

// Penumbra's internal GPU layer behind `device`.
inline Device& backend(penumbra::Device& device) { return DeviceAccess::backend(device); }

}  // namespace gpu

}  // namespace penumbra

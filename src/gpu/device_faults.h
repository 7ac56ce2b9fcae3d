#pragma once
// Fault injection for tests (docs/robustness.md): the device fails as a driver can, so tests can check
// that each failure ends in one penumbra::Error naming where it happened, with nothing left half-done.
// Not part of the public API: tests pass it to gpu/device_access.h's makeDeviceWithFaults; programs
// (the CLI's process tests) set the PENUMBRA_FAULT_INJECTION environment variable, which every
// penumbra::Device reads when it is made.
#include <cstdint>

namespace penumbra::gpu {

// Counts are 1-based from the device's creation; 0 = never.
struct DeviceFaultInjection {
    uint64_t failAllocation = 0;      // the Nth memory allocation (of a buffer or texture) fails as if its
                                      // vkAllocateMemory returned VK_ERROR_OUT_OF_DEVICE_MEMORY
    uint64_t loseDeviceAtSubmit = 0;  // the Nth queue submission returns VK_ERROR_DEVICE_LOST (not submitted)
    uint64_t loseDeviceAtWait = 0;    // the Nth wait for a submission returns VK_ERROR_DEVICE_LOST
    uint32_t maxImageSize = 0;        // the device's maxImageDimension2D seems to be this (if smaller)
    uint64_t maxStorageBufferRange = 0;  // the device's maxStorageBufferRange seems to be this (if smaller)
    uint32_t maxDrawIndirectCount = 0;   // the device's maxDrawIndirectCount seems to be this (if smaller)
    // Every allocation's memory starts as this byte repeated (1..255; 0 = left as the driver gives it),
    // where the memory is host-visible (all of it on lavapipe). A discrete GPU hands out memory with old
    // contents, lavapipe fresh zero pages: this makes a pass that reads what nothing wrote fail on
    // lavapipe too.
    uint32_t garbageByte = 0;
    bool noSubgroupArithmetic = false;  // the device seems to lack arithmetic subgroup operations
    bool noStorageImageExtendedFormats = false;  // the device seems to lack shaderStorageImageExtendedFormats
    // The visibility-buffer resolve takes a GPU's path (compute, then copies into the targets) on a CPU
    // device too, which otherwise resolves with fragments (render/visibility_pass.h).
    bool computeResolve = false;
};

// PENUMBRA_FAULT_INJECTION, e.g. "allocation=3" or "submit=2,max-image-size=512" or
// "max-storage-buffer-range=1048576" or "max-draw-indirect-count=1" or "garbage=165" (unset or empty:
// none). Throws penumbra::Error naming the variable when an item is not key=N of a known key.
DeviceFaultInjection faultInjectionFromEnvironment();

}  // namespace penumbra::gpu

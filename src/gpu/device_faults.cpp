#include "gpu/device_faults.h"

#include <cstdlib>
#include <sstream>
#include <string>

#include "core/error.h"

namespace penumbra::gpu {

DeviceFaultInjection faultInjectionFromEnvironment() {
    DeviceFaultInjection faults;
    const char* text = std::getenv("PENUMBRA_FAULT_INJECTION");
    if (!text || !*text) return faults;
    std::stringstream list(text);
    for (std::string item; std::getline(list, item, ',');) {
        const size_t equals = item.find('=');
        const std::string key = item.substr(0, equals);
        char* end = nullptr;
        const unsigned long long value = equals == std::string::npos ? 0 : std::strtoull(item.c_str() + equals + 1, &end, 10);
        const bool number = equals != std::string::npos && end && *end == '\0' && end != item.c_str() + equals + 1;
        if (number && key == "allocation") faults.failAllocation = value;
        else if (number && key == "submit") faults.loseDeviceAtSubmit = value;
        else if (number && key == "wait") faults.loseDeviceAtWait = value;
        else if (number && key == "max-image-size" && value <= UINT32_MAX) faults.maxImageSize = uint32_t(value);
        else if (number && key == "max-storage-buffer-range") faults.maxStorageBufferRange = value;
        else if (number && key == "max-draw-indirect-count" && value >= 1 && value <= UINT32_MAX)
            faults.maxDrawIndirectCount = uint32_t(value);
        else if (number && key == "garbage" && value >= 1 && value <= 255) faults.garbageByte = uint32_t(value);
        else if (number && key == "no-subgroup-arithmetic" && value == 1) faults.noSubgroupArithmetic = true;
        else
            throw Error("PENUMBRA_FAULT_INJECTION: '" + item +
                        "' is not allocation=N, submit=N, wait=N, max-image-size=N, max-storage-buffer-range=N, max-draw-indirect-count=N, garbage=1..255 or no-subgroup-arithmetic=1");
    }
    return faults;
}

}  // namespace penumbra::gpu

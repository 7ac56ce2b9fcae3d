#pragma once
// The pipeline cache file: the driver's VkPipelineCache data behind Penumbra's own header (magic,
// payload size, FNV-1a hash). Drivers check only their own header, and a damaged payload can crash
// one in vkCreatePipelineCache; a file that fails these checks is never handed to the driver (the
// cache then starts empty and the file is written again). No Vulkan here, so it is unit-tested.
#include <optional>
#include <string>

namespace penumbra::gpu {

std::string packPipelineCache(const std::string& driverData);
// The driver data of a file packed by packPipelineCache; nullopt for anything else (a damaged,
// truncated or foreign file, an older format).
std::optional<std::string> unpackPipelineCache(const std::string& fileContent);

}  // namespace penumbra::gpu

// The persistent VkPipelineCache: read at start from the user's cache folder, written back (to a
// temporary name, then renamed) when the device goes. The driver checks the header (vendor, device,
// cache UUID) and ignores a cache from another driver; the file name carries them too, so several
// GPUs and drivers keep their own caches side by side. Penumbra's own header and hash
// (pipeline_cache_file.h) keep a damaged file from the driver.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "gpu/pipeline_cache_file.h"
#include "gpu/vk_internal.h"

namespace penumbra::gpu {

namespace {

std::string cacheFolder(const std::string& option) {
    if (option == "off") return "";
    if (option != "auto") return option;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/penumbra";
    if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/penumbra";
    return "";
}

std::string cacheFileName(const VkPhysicalDeviceProperties& properties) {
    std::ostringstream name;
    name << "pipelines-" << std::hex << properties.vendorID << "-" << properties.deviceID << "-"
         << properties.driverVersion << "-";
    for (uint8_t byte : properties.pipelineCacheUUID) name << (byte < 16 ? "0" : "") << uint32_t(byte);
    name << ".bin";
    return name.str();
}

}  // namespace

void Device::Impl::loadPipelineCache() {
    const std::string folder = cacheFolder(options.pipelineCache);
    std::string data;
    if (!folder.empty()) {
        pipelineCacheFile = folder + "/" + cacheFileName(properties);
        std::error_code error;
        if (std::filesystem::is_regular_file(pipelineCacheFile, error)) {
            std::ifstream file(pipelineCacheFile, std::ios::binary);
            const std::string content((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
            data = unpackPipelineCache(content).value_or(std::string());  // damaged: start empty
        }
    }
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    info.initialDataSize = data.size();
    info.pInitialData = data.empty() ? nullptr : data.data();
    if (vkCreatePipelineCache(device, &info, nullptr, &pipelineCache) != VK_SUCCESS) {
        // A damaged file: start empty (the driver validates the header, but not every driver the rest).
        info.initialDataSize = 0;
        info.pInitialData = nullptr;
        VK_CHECK(vkCreatePipelineCache(device, &info, nullptr, &pipelineCache));
    }
}

void Device::Impl::savePipelineCache() {
    if (!pipelineCache || pipelineCacheFile.empty()) return;
    size_t size = 0;
    if (vkGetPipelineCacheData(device, pipelineCache, &size, nullptr) != VK_SUCCESS || size == 0) return;
    std::string data(size, '\0');
    if (vkGetPipelineCacheData(device, pipelineCache, &size, data.data()) != VK_SUCCESS) return;
    data.resize(size);
    data = packPipelineCache(data);
    // A cache that cannot be written is not an error: the next start compiles again.
    std::error_code error;
    const std::filesystem::path path(pipelineCacheFile);
    std::filesystem::create_directories(path.parent_path(), error);
    const std::string temporary = pipelineCacheFile + ".tmp" + std::to_string(::getpid());
    {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        if (!file) return;
        file.write(data.data(), std::streamsize(data.size()));
        if (!file) {
            file.close();
            std::filesystem::remove(temporary, error);
            return;
        }
    }
    std::filesystem::rename(temporary, path, error);
    if (error) std::filesystem::remove(temporary, error);
}

}  // namespace penumbra::gpu

#include "gpu/pipeline_cache_file.h"

#include <cstdint>
#include <cstring>

namespace penumbra::gpu {

namespace {

constexpr char kMagic[8] = {'P', 'N', 'B', 'R', 'P', 'C', '0', '1'};
constexpr size_t kHeaderSize = sizeof(kMagic) + 2 * sizeof(uint64_t);

uint64_t fnv1a(const char* data, size_t size) {
    uint64_t hash = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < size; ++i) {
        hash ^= uint8_t(data[i]);
        hash *= 0x100000001b3ull;
    }
    return hash;
}

}  // namespace

std::string packPipelineCache(const std::string& driverData) {
    const uint64_t size = driverData.size();
    const uint64_t hash = fnv1a(driverData.data(), driverData.size());
    std::string file(kHeaderSize, '\0');
    std::memcpy(file.data(), kMagic, sizeof(kMagic));
    std::memcpy(file.data() + sizeof(kMagic), &size, sizeof(size));
    std::memcpy(file.data() + sizeof(kMagic) + sizeof(size), &hash, sizeof(hash));
    return file + driverData;
}

std::optional<std::string> unpackPipelineCache(const std::string& fileContent) {
    if (fileContent.size() < kHeaderSize || std::memcmp(fileContent.data(), kMagic, sizeof(kMagic)) != 0)
        return std::nullopt;
    uint64_t size = 0, hash = 0;
    std::memcpy(&size, fileContent.data() + sizeof(kMagic), sizeof(size));
    std::memcpy(&hash, fileContent.data() + sizeof(kMagic) + sizeof(size), sizeof(hash));
    if (size != fileContent.size() - kHeaderSize) return std::nullopt;
    if (fnv1a(fileContent.data() + kHeaderSize, size_t(size)) != hash) return std::nullopt;
    return fileContent.substr(kHeaderSize);
}

}  // namespace penumbra::gpu

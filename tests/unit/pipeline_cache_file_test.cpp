// The pipeline cache file's own header: a damaged cache file never reaches the driver.
#include <string>

#include <gtest/gtest.h>

#include "gpu/pipeline_cache_file.h"

using namespace penumbra::gpu;

namespace {
const std::string kDriverData = std::string("driver header and blobs ") + std::string(200, '\x7f');
}

TEST(PipelineCacheFile, PackedDataUnpacksToTheSameBytes) {
    EXPECT_EQ(unpackPipelineCache(packPipelineCache(kDriverData)), kDriverData);
    EXPECT_EQ(unpackPipelineCache(packPipelineCache("")), std::string());
}

TEST(PipelineCacheFile, AFlippedByteIsRefused) {
    std::string file = packPipelineCache(kDriverData);
    file[file.size() / 2] ^= 0x10;
    EXPECT_FALSE(unpackPipelineCache(file).has_value());
}

TEST(PipelineCacheFile, ATruncatedFileIsRefused) {
    const std::string file = packPipelineCache(kDriverData);
    EXPECT_FALSE(unpackPipelineCache(file.substr(0, file.size() - 1)).has_value());
    EXPECT_FALSE(unpackPipelineCache(file.substr(0, 5)).has_value());
}

TEST(PipelineCacheFile, AFileWithoutTheHeaderIsRefused) {
    EXPECT_FALSE(unpackPipelineCache(kDriverData).has_value());  // e.g. a bare cache of an older Penumbra
    EXPECT_FALSE(unpackPipelineCache("").has_value());
}

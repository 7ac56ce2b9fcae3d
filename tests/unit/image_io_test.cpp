// Image files in and out: PNG written whole or not at all, PNG / JPEG decoding through libpng and
// libjpeg-turbo with the size limit checked from the header, and the texture downscale.
#include <filesystem>
#include <string>
#include <vector>
#include <zlib.h>

#include <gtest/gtest.h>

#include "core/error.h"
#include "penumbra/files.h"
#include "core/image_decode.h"
#include "error_message.h"
#include "gltf_test_files.h"
#include "penumbra/image.h"

using namespace penumbra;
using penumbra::testing::errorMessage;
using penumbra::testing::readFile;
using penumbra::testing::TempDir;
using penumbra::testing::writeFile;

namespace {

// Files in `folder` (to see that nothing, not even a temporary, was left behind).
size_t fileCount(const std::string& folder) {
    size_t count = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(folder)) ++count;
    return count;
}

void appendChunk(std::string& png, const char* type, const std::string& data) {
    auto be32 = [&](uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8) png += char((v >> shift) & 0xFF);
    };
    be32(uint32_t(data.size()));
    const std::string body = std::string(type, 4) + data;
    png += body;
    be32(uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
}

// A PNG whose header claims width x height, with a one-byte (far too short) image stream.
std::string pngClaiming(uint32_t width, uint32_t height) {
    std::string png = "\x89PNG\r\n\x1a\n";
    std::string header;
    for (uint32_t v : {width, height})
        for (int shift = 24; shift >= 0; shift -= 8) header += char((v >> shift) & 0xFF);
    header += std::string("\x08\x06\x00\x00\x00", 5);  // 8-bit RGBA
    appendChunk(png, "IHDR", header);
    appendChunk(png, "IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8));
    appendChunk(png, "IEND", "");
    return png;
}

Image decode(const std::string& bytes) {
    return decodeImageRgba(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "test image");
}

}  // namespace

TEST(ImageIo, WrittenPngReadsBackTheSamePixels) {
    TempDir dir;
    Image image(3, 2, 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(i * 40);
    writePng(image, dir.file("a.png"));
    EXPECT_EQ(readPng(dir.file("a.png")).pixels, image.pixels);
    EXPECT_EQ(fileCount(dir.file("")), 1u);  // no temporary left beside it
}

TEST(ImageIo, PngIntoAMissingFolderIsAnErrorAndCreatesNothing) {
    TempDir dir;
    EXPECT_NE(errorMessage([&] { writePng(Image(2, 2, 1), dir.file("none/a.png")); }).find("cannot write"), std::string::npos);
    EXPECT_EQ(fileCount(dir.file("")), 0u);
}

TEST(ImageIo, PngOverADirectoryIsAnErrorAndLeavesIt) {
    TempDir dir;
    std::filesystem::create_directories(dir.file("out.png"));
    EXPECT_NE(errorMessage([&] { writePng(Image(2, 2, 1), dir.file("out.png")); }).find("it is a directory"),
              std::string::npos);
    EXPECT_TRUE(std::filesystem::is_directory(dir.file("out.png")));
    EXPECT_EQ(fileCount(dir.file("")), 1u);
}

TEST(ImageIo, CheckWritableCreatesNothing) {
    TempDir dir;
    checkWritable(dir.file("later.png"));
    EXPECT_EQ(fileCount(dir.file("")), 0u);
    EXPECT_NE(errorMessage([&] { checkWritable(dir.file("no/such/folder.png")); }).find("does not exist"), std::string::npos);
}

TEST(ImageIo, ReadingAMissingPngSaysItDoesNotExist) {
    TempDir dir;
    EXPECT_NE(errorMessage([&] { readPng(dir.file("absent.png")); }).find("cannot open file (it does not exist)"),
              std::string::npos);
}

TEST(ImageIo, DecodingRefusesFormatsOtherThanPngAndJpeg) {
    EXPECT_NE(errorMessage([&] { decode("BM\x36\x00\x00\x00 a bitmap"); }).find("not a PNG or JPEG image"), std::string::npos);
    EXPECT_NE(errorMessage([&] { decode(""); }).find("not a PNG or JPEG image"), std::string::npos);
}

TEST(ImageIo, DecodingRefusesAHugeImageFromItsHeaderAlone) {
    const std::string message = errorMessage([&] { decode(pngClaiming(20000, 20000)); });
    EXPECT_NE(message.find("the image is 20000x20000, larger than the 16384x16384 Penumbra decodes"), std::string::npos)
        << message;
}

TEST(ImageIo, TruncatedPngIsAnError) {
    EXPECT_NE(errorMessage([&] { decode(pngClaiming(64, 64)); }).find("PNG failed to decode"), std::string::npos);
}

TEST(ImageIo, JpegWithAnOverfullHuffmanTableDecodesWithinItsBuffer) {
    // fuzz_texture finding: stb_image 2.27 wrote past its Huffman size table on this file (UBSan,
    // index 257 of 257), which is why JPEGs are decoded by libjpeg-turbo; it recovers an image.
    const std::string jpeg =
        readFile(std::string(PENUMBRA_TEST_DATA_DIR) + "/../fuzz/corpus/texture/regression-jpeg-huffman-overflow");
    ASSERT_FALSE(jpeg.empty());
    const Image image = decode(jpeg);
    EXPECT_EQ(image.pixels.size(), size_t(image.width) * image.height * 4);
}

TEST(ImageIo, HeaderGivesTheSizeOfAPng) {
    const std::string png = pngClaiming(300, 20);
    const ImageHeader header = readImageHeader(reinterpret_cast<const uint8_t*>(png.data()), png.size(), "t");
    EXPECT_EQ(header.width, 300u);
    EXPECT_EQ(header.height, 20u);
}

TEST(ImageDownscale, ImageThatFitsIsReturnedAsIs) {
    const Image image(8, 4, 4, 7);
    EXPECT_EQ(downscaleToFit(image, 8).pixels, image.pixels);
}

TEST(ImageDownscale, LargerSideBecomesTheLimitAndTheAspectIsKept) {
    const Image small = downscaleToFit(Image(1000, 250, 4, 9), 100);
    EXPECT_EQ(small.width, 100u);
    EXPECT_EQ(small.height, 25u);
    EXPECT_EQ(small.pixels.size(), 100u * 25u * 4u);
}

TEST(ImageDownscale, PixelsAreAreaAverages) {
    Image checker(4, 4, 1);
    for (uint32_t y = 0; y < 4; ++y)
        for (uint32_t x = 0; x < 4; ++x) checker.at(x, y) = (x + y) % 2 ? 200 : 0;
    const Image half = downscaleToFit(checker, 2);
    for (uint8_t value : half.pixels) EXPECT_EQ(value, 100);
}

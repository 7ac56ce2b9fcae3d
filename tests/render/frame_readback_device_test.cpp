// gpu::Device::readBackAtFrameEnd: the pieces a frame reads back arrive in CompletedFrame::readback at
// the offsets the calls returned (render/frame_readback.h decodes them by these offsets).
#include <cstring>

#include "gpu/device.h"
#include "render_test_support.h"

namespace penumbra::test {
namespace {

class FrameReadbackDeviceTest : public RenderTest {};

TEST_F(FrameReadbackDeviceTest, EachPieceArrivesAtTheOffsetItsCallReturned) {
    gpu::Device& gpu = gpu::backend(device());
    std::vector<uint32_t> first(4), second(12), third(8);
    for (size_t i = 0; i < first.size(); ++i) first[i] = 1000 + uint32_t(i);
    for (size_t i = 0; i < second.size(); ++i) second[i] = 2000 + uint32_t(i);
    for (size_t i = 0; i < third.size(); ++i) third[i] = 3000 + uint32_t(i);
    auto buffer = [&](const std::vector<uint32_t>& values, const char* name) {
        return gpu.createBuffer(values.size() * 4, gpu::kBufferStorage | gpu::kBufferTransferSrc,
                                gpu::MemoryKind::DeviceLocal, values.data(), name);
    };
    const gpu::BufferHandle a = buffer(first, "readback a"), b = buffer(second, "readback b"), c = buffer(third, "readback c");
    gpu::CommandList commands = gpu.beginFrame();
    const uint64_t atA = gpu.readBackAtFrameEnd(commands, {a, 0, first.size() * 4});
    const uint64_t atB = gpu.readBackAtFrameEnd(commands, {b, 8, 40});  // values 2 to 11 of b
    const uint64_t atC = gpu.readBackAtFrameEnd(commands, {c, 0, third.size() * 4});
    const uint64_t frame = gpu.submitFrame(commands);
    gpu.waitFrame(frame);
    std::vector<gpu::CompletedFrame> done = gpu.takeCompletedFrames();
    ASSERT_EQ(done.size(), 1u);
    ASSERT_EQ(done[0].frameIndex, frame);
    EXPECT_EQ(atA, 0u);
    EXPECT_EQ(atB, 16u);
    EXPECT_EQ(atC, 56u);
    const std::vector<uint8_t>& bytes = done[0].readback;
    ASSERT_EQ(bytes.size(), 88u);
    auto valueAt = [&](uint64_t offset) {
        uint32_t value = 0;
        std::memcpy(&value, bytes.data() + offset, 4);
        return value;
    };
    EXPECT_EQ(valueAt(atA), 1000u);
    EXPECT_EQ(valueAt(atA + 12), 1003u);
    EXPECT_EQ(valueAt(atB), 2002u);
    EXPECT_EQ(valueAt(atB + 36), 2011u);
    EXPECT_EQ(valueAt(atC), 3000u);
    EXPECT_EQ(valueAt(atC + 28), 3007u);
    for (gpu::BufferHandle handle : {a, b, c}) gpu.destroy(handle);
}

// A frame allocation larger than the upload ring makes the ring grow: the slices handed out before stay
// usable (bound or copied later in the frame) until the frame is submitted.
TEST_F(FrameReadbackDeviceTest, SlicesAllocatedBeforeTheRingGrowsStayUsableInTheFrame) {
    gpu::Device& gpu = gpu::backend(device());
    const std::vector<uint32_t> values = {7, 11, 13, 17};
    const gpu::BufferHandle target = gpu.createBuffer(values.size() * 4, gpu::kBufferStorage | gpu::kBufferTransferDst |
                                                      gpu::kBufferTransferSrc, gpu::MemoryKind::DeviceLocal, nullptr, "grown ring target");
    gpu::CommandList commands = gpu.beginFrame();
    const gpu::FrameAllocation early = gpu.allocateFrameData(values.size() * 4);
    std::memcpy(early.mapped, values.data(), values.size() * 4);
    const gpu::FrameAllocation large = gpu.allocateFrameData(64ull << 20);  // more than any ring so far
    EXPECT_NE(large.slice.buffer.id, early.slice.buffer.id) << "the ring did not grow: the test tests nothing";
    commands.pass("copy from the outgrown ring", {gpu::use(target, gpu::Usage::TransferWrite)});
    commands.copyBuffer(early.slice, target, 0);
    gpu.waitFrame(gpu.submitFrame(commands));
    gpu.takeCompletedFrames();
    const std::vector<uint8_t> bytes = gpu.readBuffer(target);
    ASSERT_EQ(bytes.size(), values.size() * 4);
    EXPECT_EQ(std::memcmp(bytes.data(), values.data(), bytes.size()), 0);
    gpu.destroy(target);
}

}  // namespace
}  // namespace penumbra::test

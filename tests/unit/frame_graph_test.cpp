// The frame graph's barrier derivation (src/gpu/frame_graph.h), on the CPU: given declared passes,
// the barriers and layout transitions that must come before each.
#include <gtest/gtest.h>
#include <vulkan/vulkan_core.h>

#include <vector>

#include "gpu/frame_graph.h"
#include "gpu/handle_pool.h"

namespace penumbra::gpu {
namespace {

const BufferHandle kBuffer{1};
const BufferHandle kOther{2};
const TextureHandle kTexture{1};

std::vector<Barrier> declare(FrameGraph& graph, std::initializer_list<ResourceUse> uses) {
    const std::span<const Barrier> barriers = graph.declare("pass", std::span(uses.begin(), uses.size()));
    return {barriers.begin(), barriers.end()};
}

TEST(FrameGraphTest, StorageWriteThenSampledReadIsOneComputeToFragmentBarrier) {
    FrameGraph graph;
    declare(graph, {use(kTexture, Usage::ComputeWrite)});
    const std::vector<Barrier> barriers = declare(graph, {use(kTexture, Usage::FragmentSampled)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(barriers[0].srcAccess, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(barriers[0].dstStages, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    EXPECT_EQ(barriers[0].dstAccess, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    EXPECT_EQ(barriers[0].oldLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(barriers[0].newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

TEST(FrameGraphTest, ReadAfterReadNeedsNoBarrier) {
    FrameGraph graph;
    declare(graph, {use(kBuffer, Usage::ComputeWrite)});
    EXPECT_EQ(declare(graph, {use(kBuffer, Usage::ComputeRead)}).size(), 1u);
    EXPECT_TRUE(declare(graph, {use(kBuffer, Usage::ComputeRead)}).empty());
}

TEST(FrameGraphTest, AResourceNeverWrittenNeedsNoBarrier) {
    FrameGraph graph;
    EXPECT_TRUE(declare(graph, {use(kBuffer, Usage::GraphicsRead)}).empty());
    EXPECT_TRUE(declare(graph, {use(kBuffer, Usage::ComputeRead)}).empty());
}

TEST(FrameGraphTest, ASecondReaderInAnotherStageWaitsForTheWriteToo) {
    FrameGraph graph;
    declare(graph, {use(kBuffer, Usage::ComputeWrite)});
    declare(graph, {use(kBuffer, Usage::ComputeRead)});
    const std::vector<Barrier> barriers = declare(graph, {use(kBuffer, Usage::IndirectArguments)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(barriers[0].dstStages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT);
    EXPECT_EQ(barriers[0].dstAccess, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

TEST(FrameGraphTest, WriteAfterWriteWaitsForTheFirstWrite) {
    FrameGraph graph;
    declare(graph, {use(kBuffer, Usage::TransferWrite)});
    const std::vector<Barrier> barriers = declare(graph, {use(kBuffer, Usage::ComputeWrite)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    EXPECT_EQ(barriers[0].srcAccess, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    EXPECT_EQ(barriers[0].dstStages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

TEST(FrameGraphTest, WriteAfterReadWaitsForTheReadersWithoutMakingAnythingAvailable) {
    FrameGraph graph;
    declare(graph, {use(kBuffer, Usage::ComputeWrite)});
    declare(graph, {use(kBuffer, Usage::GraphicsRead)});
    const std::vector<Barrier> barriers = declare(graph, {use(kBuffer, Usage::TransferWrite)});
    ASSERT_EQ(barriers.size(), 1u);
    // The write before the reads is still in the source scope: it ordered them, and orders this write.
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT |
                                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    EXPECT_EQ(barriers[0].dstStages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    EXPECT_EQ(barriers[0].dstAccess, VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

TEST(FrameGraphTest, OnlyTheResourcesWithAHazardGetBarriers) {
    FrameGraph graph;
    declare(graph, {use(kBuffer, Usage::ComputeWrite), use(kOther, Usage::ComputeRead)});
    const std::vector<Barrier> barriers = declare(graph, {use(kBuffer, Usage::ComputeRead), use(kOther, Usage::ComputeRead)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].resource, (ResourceKey{kBuffer.id, false}));
}

TEST(FrameGraphTest, AFirstUseTransitionsFromUndefined) {
    FrameGraph graph;
    const std::vector<Barrier> barriers = declare(graph, {use(kTexture, Usage::DepthTarget)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_NONE);
    EXPECT_EQ(barriers[0].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(barriers[0].newLayout, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(graph.layout(kTexture), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
}

TEST(FrameGraphTest, DepthTargetThenSampledIsALayoutTransition) {
    FrameGraph graph;
    declare(graph, {use(kTexture, Usage::DepthTarget)});
    const std::vector<Barrier> barriers = declare(graph, {use(kTexture, Usage::FragmentSampled)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages,
              VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT);
    EXPECT_EQ(barriers[0].srcAccess, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    EXPECT_EQ(barriers[0].oldLayout, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(barriers[0].newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
}

TEST(FrameGraphTest, ASampledReadInAnotherStageChainsOnTheLayoutTransition) {
    FrameGraph graph;
    declare(graph, {use(kTexture, Usage::TransferWrite)});
    declare(graph, {use(kTexture, Usage::ComputeSampled)});  // the transition
    const std::vector<Barrier> barriers = declare(graph, {use(kTexture, Usage::FragmentSampled)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(barriers[0].srcAccess, VK_ACCESS_2_NONE);
    EXPECT_EQ(barriers[0].oldLayout, barriers[0].newLayout);
    EXPECT_TRUE(declare(graph, {use(kTexture, Usage::ComputeSampled)}).empty());
}

TEST(FrameGraphTest, DiscardedContentsTransitionFromUndefined) {
    FrameGraph graph;
    declare(graph, {use(kTexture, Usage::ColorTarget)});
    declare(graph, {use(kTexture, Usage::FragmentSampled)});
    const std::vector<Barrier> barriers = declare(graph, {discard(kTexture, Usage::ColorTarget)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(barriers[0].newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);  // after the sampling
}

TEST(FrameGraphTest, TwoUsesOfOneResourceInAPassAreOneBarrier) {
    FrameGraph graph;
    declare(graph, {use(kBuffer, Usage::ComputeWrite)});
    const std::vector<Barrier> barriers =
        declare(graph, {use(kBuffer, Usage::IndirectArguments), use(kBuffer, Usage::ComputeRead)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].dstStages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(barriers[0].dstAccess, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

TEST(FrameGraphTest, ASkippedPassLeavesTheLastWriteForTheNextReader) {
    // A cached atlas: frame 1 draws and samples it, frame 2 only samples it (no barrier: nothing changed).
    FrameGraph graph;
    graph.beginFrame();
    declare(graph, {use(kTexture, Usage::DepthTarget)});
    declare(graph, {use(kTexture, Usage::FragmentSampled)});
    graph.beginFrame();
    EXPECT_TRUE(declare(graph, {use(kTexture, Usage::FragmentSampled)}).empty());
    // Frame 3 draws again: after frame 2's sampling, from the layout it was left in.
    const std::vector<Barrier> barriers = declare(graph, {use(kTexture, Usage::DepthTarget)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
}

TEST(FrameGraphTest, AnAbandonedFrameLeavesTheStatesAsTheyWere) {
    FrameGraph graph;
    declare(graph, {use(kTexture, Usage::FragmentSampled)});
    graph.beginFrame();
    declare(graph, {use(kTexture, Usage::ColorTarget)});
    graph.abandonFrame();
    EXPECT_EQ(graph.layout(kTexture), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_TRUE(declare(graph, {use(kTexture, Usage::FragmentSampled)}).empty());
}

TEST(FrameGraphTest, AForgottenHandleStartsUnused) {
    FrameGraph graph;
    declare(graph, {use(kTexture, Usage::ColorTarget)});
    graph.forget({kTexture.id, true});
    EXPECT_EQ(graph.layout(kTexture), VK_IMAGE_LAYOUT_UNDEFINED);
    const std::vector<Barrier> barriers = declare(graph, {use(kTexture, Usage::ColorTarget)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_NONE);
}

// Handle ids carry a generation above the slot index (gpu/handle_pool.h): states are kept per slot.
constexpr uint32_t kGenerationShift = HandlePool<int>::kIndexBits;

TEST(FrameGraphTest, ALaterGenerationOfASlotStartsUnused) {
    FrameGraph graph;
    declare(graph, {use(kTexture, Usage::ColorTarget)});
    const TextureHandle reused{kTexture.id | (1u << kGenerationShift)};
    EXPECT_EQ(graph.layout(reused), VK_IMAGE_LAYOUT_UNDEFINED);
    const std::vector<Barrier> barriers = declare(graph, {use(reused, Usage::FragmentSampled)});
    ASSERT_EQ(barriers.size(), 1u);
    EXPECT_EQ(barriers[0].srcStages, VK_PIPELINE_STAGE_2_NONE);
    EXPECT_EQ(barriers[0].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
}

TEST(FrameGraphTest, StatesGrowWithSlotsNotWithGenerations) {
    FrameGraph graph;
    for (uint32_t generation = 0; generation < 4096; generation += 97)
        declare(graph, {use(BufferHandle{3u | (generation << kGenerationShift)}, Usage::ComputeWrite),
                        use(TextureHandle{2u | (generation << kGenerationShift)}, Usage::ColorTarget)});
    EXPECT_LE(graph.trackedSlots(), 4u + 3u);
}

TEST(FrameGraphTest, PrintsTheRecordedPassesAsMermaidWithAnEdgePerDependency) {
    FrameGraph graph;
    graph.setName({kBuffer.id, false}, "counts");
    graph.recordPasses = true;
    graph.beginFrame();
    graph.declare("cull", std::vector{use(kBuffer, Usage::ComputeWrite)});
    graph.declare("draw", std::vector{use(kBuffer, Usage::IndirectArguments)});
    const std::string mermaid = printFrameGraph(graph, "mermaid");
    EXPECT_NE(mermaid.find("p0[\"cull\"]"), std::string::npos) << mermaid;
    EXPECT_NE(mermaid.find("p1[\"draw (1 barrier)\"]"), std::string::npos) << mermaid;
    EXPECT_NE(mermaid.find("p0 -->|\"counts\"| p1"), std::string::npos) << mermaid;
    EXPECT_NE(printFrameGraph(graph, "dot").find("p0 -> p1 [label=\"counts\"]"), std::string::npos);
}

}  // namespace
}  // namespace penumbra::gpu

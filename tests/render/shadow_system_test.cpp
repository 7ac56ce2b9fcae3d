// ShadowSystem (penumbra/shadow_system.h) in an engine's own Vulkan: the shadow passes recorded into the
// caller's command buffer, the descriptors written into the caller's set, and the caller's own compute
// pass calling penumbraShadow (tests/glsl/shadow_system_ground.comp.glsl) computes the shadow term that
// Penumbra's own renderer shows as its shadow AOV, for cascades, virtual maps, a spot light's atlas tile
// and virtual faces. Tolerance: the AOV is 8-bit, and the caller's receiver point is the analytic ray hit
// where the rasterizer interpolates it; at most 1 level on 99.5 % of the ground's pixels, 3 on every one.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "caller_vulkan.h"
#include "penumbra/error.h"
#include "penumbra/files.h"
#include "penumbra/scene_builder.h"

namespace penumbra::test {
namespace {

constexpr uint32_t kWidth = 96, kHeight = 64;
constexpr float kGroundHalfSize = 20.0f;

// A ground plane at y = 0 and two boxes above and behind the camera: the camera sees nothing but the
// ground (and sky), so the caller's analytic receiver is every visible surface. Light 0: a sun that casts
// the boxes' shadows forward into the view; light 1: a spot light above the ground in view.
Scene groundOnlyScene() {
    SceneBuilder builder;
    Material ground;
    ground.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    const uint32_t material = builder.addMaterial(ground);
    builder.addInstance(builder.addMesh(makePlaneMesh(glm::vec2(2.0f * kGroundHalfSize), material)), glm::mat4(1.0f));
    const uint32_t box = builder.addMesh(makeBoxMesh({0.6f, 0.3f, 0.6f}, material));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), {0.4f, 2.6f, 5.5f}));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), {-1.2f, 2.2f, 5.0f}));
    builder.addInstance(box, glm::translate(glm::mat4(1.0f), {0.0f, 2.6f, 3.3f}));
    builder.addLight(makeDirectionalLight({0.25f, -1.0f, -0.9f}, 3.0f));
    builder.addLight(makeSpotLight({0.0f, 6.0f, 7.0f}, {0.0f, -6.0f, -7.0f}, 40.0f, 30.0f, 0.9f, 0.7f));
    builder.setCamera(makeLookAtCamera({0.0f, 1.2f, 4.0f}, {0.0f, 0.0f, -1.0f}, 0.9f));
    return builder.build();
}

struct GroundConstants {
    glm::mat4 worldFromClip;
    glm::uvec2 size;
    uint32_t light;
    float groundY;
    float groundHalfSize;
};

class ShadowSystemTest : public CallerVulkan {
protected:
    void TearDown() override {
        if (device) {
            vkDeviceWaitIdle(device);
            if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
            if (pipelineLayout) vkDestroyPipelineLayout(device, pipelineLayout, nullptr);
            for (VkDescriptorSetLayout layout : setLayouts) vkDestroyDescriptorSetLayout(device, layout, nullptr);
            if (descriptorPool) vkDestroyDescriptorPool(device, descriptorPool, nullptr);
            if (output) vkDestroyBuffer(device, output, nullptr);
            if (outputMemory) vkFreeMemory(device, outputMemory, nullptr);
        }
        CallerVulkan::TearDown();
    }

    // The caller's compute pass: set 0 its output buffer, set 1 the shadow descriptors (base 0).
    void makeGroundPass() {
        const std::vector<uint8_t> code =
            readFileBytes(std::string(PENUMBRA_TEST_SPIRV_DIR) + "/shadow_system_ground.comp.spv");
        VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
        moduleInfo.codeSize = code.size();
        moduleInfo.pCode = reinterpret_cast<const uint32_t*>(code.data());
        VkShaderModule module = VK_NULL_HANDLE;
        CHECK_VK(vkCreateShaderModule(device, &moduleInfo, nullptr, &module));
        VkDescriptorSetLayoutBinding outputBinding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT};
        VkDescriptorSetLayoutCreateInfo outputInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        outputInfo.bindingCount = 1;
        outputInfo.pBindings = &outputBinding;
        CHECK_VK(vkCreateDescriptorSetLayout(device, &outputInfo, nullptr, &setLayouts[0]));
        CHECK_VK(createShadowDescriptorSetLayout(device, VK_SHADER_STAGE_COMPUTE_BIT, 0, &setLayouts[1]));
        VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(GroundConstants)};
        VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layoutInfo.setLayoutCount = 2;
        layoutInfo.pSetLayouts = setLayouts.data();
        layoutInfo.pushConstantRangeCount = 1;
        layoutInfo.pPushConstantRanges = &range;
        CHECK_VK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &pipelineLayout));
        VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        pipelineInfo.stage.module = module;
        pipelineInfo.stage.pName = "main";
        pipelineInfo.layout = pipelineLayout;
        const VkResult created = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline);
        vkDestroyShaderModule(device, module, nullptr);
        CHECK_VK(created);

        VkDescriptorPoolSize sizes[4];
        shadowDescriptorPoolSizes(sizes);
        sizes[1].descriptorCount += 1;  // the output buffer
        VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        poolInfo.maxSets = 2;
        poolInfo.poolSizeCount = 3;
        poolInfo.pPoolSizes = sizes;
        CHECK_VK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &descriptorPool));
        VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        allocInfo.descriptorPool = descriptorPool;
        allocInfo.descriptorSetCount = 2;
        allocInfo.pSetLayouts = setLayouts.data();
        CHECK_VK(vkAllocateDescriptorSets(device, &allocInfo, sets.data()));

        VkBufferCreateInfo bufferInfo{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bufferInfo.size = sizeof(float) * kWidth * kHeight;
        bufferInfo.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        CHECK_VK(vkCreateBuffer(device, &bufferInfo, nullptr, &output));
        VkMemoryRequirements requirements;
        vkGetBufferMemoryRequirements(device, output, &requirements);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = requirements.size;
        alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                            VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        CHECK_VK(vkAllocateMemory(device, &alloc, nullptr, &outputMemory));
        CHECK_VK(vkBindBufferMemory(device, output, outputMemory, 0));
        VkDescriptorBufferInfo outputDescriptor{output, 0, VK_WHOLE_SIZE};
        VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        write.dstSet = sets[0];
        write.dstBinding = 0;
        write.descriptorCount = 1;
        write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        write.pBufferInfo = &outputDescriptor;
        vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);

        VkCommandPoolCreateInfo commandPoolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        commandPoolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        CHECK_VK(vkCreateCommandPool(device, &commandPoolInfo, nullptr, &pool));
        VkCommandBufferAllocateInfo cbInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        cbInfo.commandPool = pool;
        cbInfo.commandBufferCount = 1;
        CHECK_VK(vkAllocateCommandBuffers(device, &cbInfo, &commandBuffer));
    }

    // Submits the ended command buffer, signalling the shadow frame's completion value, and waits.
    void submitWithSignal(const ShadowFrameBindings& frame) {
        VkCommandBufferSubmitInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        commandInfo.commandBuffer = commandBuffer;
        const VkSemaphoreSubmitInfo signal = shadowFrameSignal(frame);
        VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit.commandBufferInfoCount = 1;
        submit.pCommandBufferInfos = &commandInfo;
        submit.signalSemaphoreInfoCount = 1;
        submit.pSignalSemaphoreInfos = &signal;
        EXPECT_EQ(vkQueueSubmit2(queue, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);
        vkQueueWaitIdle(queue);
    }

    // One frame of the caller: Penumbra's shadow passes, then its own pass reading them, submitted with
    // the frame's completion signal; returns the caller's shadow term per pixel (-1: no ground).
    std::vector<float> callerFrame(ShadowSystem& shadows, const Settings& settings, const CameraView& view, uint32_t light) {
        vkResetCommandBuffer(commandBuffer, 0);
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        vkBeginCommandBuffer(commandBuffer, &begin);
        const ShadowFrameBindings frame = recordShadowFrame(shadows, commandBuffer, settings, view);
        writeShadowDescriptors(device, sets[1], frame);
        vkCmdBindPipeline(commandBuffer, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(commandBuffer, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout, 0, 2, sets.data(), 0, nullptr);
        const GroundConstants constants{glm::inverse(view.clipFromWorld), {kWidth, kHeight}, light, 0.0f, kGroundHalfSize};
        vkCmdPushConstants(commandBuffer, pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(constants), &constants);
        vkCmdDispatch(commandBuffer, (kWidth + 7) / 8, (kHeight + 7) / 8, 1);
        VkMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        toHost.srcStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
        toHost.srcAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
        toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
        VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dependency.memoryBarrierCount = 1;
        dependency.pMemoryBarriers = &toHost;
        vkCmdPipelineBarrier2(commandBuffer, &dependency);
        vkEndCommandBuffer(commandBuffer);

        submitWithSignal(frame);
        std::vector<float> values(size_t(kWidth) * kHeight);
        void* mapped = nullptr;
        vkMapMemory(device, outputMemory, 0, VK_WHOLE_SIZE, 0, &mapped);
        std::memcpy(values.data(), mapped, values.size() * sizeof(float));
        vkUnmapMemory(device, outputMemory);
        return values;
    }

    // Renders the AOV with Penumbra's renderer and the caller's term with ShadowSystem (two frames, the
    // second compared), on one Penumbra device on the caller's VkDevice.
    void expectCallerShadowEqualsAov(const Settings& settings, uint32_t light) {
        makeGroundPass();
        if (HasFatalFailure()) return;
        Device penumbraDevice(externalVulkanDevice(instance, physicalDevice, device, queue, 0, false, true));
        Image aov;
        {
            Renderer renderer(penumbraDevice, groundOnlyScene());
            RenderRequest request;
            request.width = kWidth;
            request.height = kHeight;
            request.output = OutputMode::ShadowAov;
            request.aovLight = light;
            aov = renderer.render(request, settings).image;
        }
        std::vector<float> caller;
        {
            ShadowSystem shadows(penumbraDevice, groundOnlyScene());
            const CameraView view = resolveCameraView(shadows.scene(), kWidth, kHeight);
            callerFrame(shadows, settings, view, light);
            caller = callerFrame(shadows, settings, view, light);
            shadows.waitIdle();
            const std::vector<FrameStats> frames = shadows.takeCompletedFrames();
            ASSERT_EQ(frames.size(), 2u);
            EXPECT_EQ(frames[1].mainView, "none");
        }
        ASSERT_EQ(aov.pixels.size(), caller.size());
        size_t ground = 0, offByMore = 0, shadowed = 0, lit = 0;
        int worst = 0;
        for (size_t p = 0; p < caller.size(); ++p) {
            if (caller[p] < 0.0f) continue;
            ++ground;
            const int mine = int(std::lround(std::clamp(caller[p], 0.0f, 1.0f) * 255.0f));
            const int difference = std::abs(mine - int(aov.pixels[p]));
            offByMore += difference > 1;
            worst = std::max(worst, difference);
            shadowed += aov.pixels[p] < 64;
            lit += aov.pixels[p] > 192;
        }
        EXPECT_GT(ground, caller.size() / 2);
        EXPECT_GT(shadowed, ground / 50) << "the scene must show shadow";
        EXPECT_GT(lit, ground / 5) << "and light";
        EXPECT_LE(double(offByMore), 0.005 * double(ground)) << "worst " << worst;
        EXPECT_LE(worst, 3);
    }

    std::array<VkDescriptorSetLayout, 2> setLayouts{};
    std::array<VkDescriptorSet, 2> sets{};
    VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkBuffer output = VK_NULL_HANDLE;
    VkDeviceMemory outputMemory = VK_NULL_HANDLE;
    VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
};

TEST_F(ShadowSystemTest, CallersSunShadowWithCascadesEqualsTheShadowAov) {
    expectCallerShadowEqualsAov(Settings{}, 0);
}

TEST_F(ShadowSystemTest, CallersSunShadowWithVirtualMapsEqualsTheShadowAov) {
    Settings settings;
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    expectCallerShadowEqualsAov(settings, 0);
}

TEST_F(ShadowSystemTest, CallersSpotShadowFromTheAtlasEqualsTheShadowAov) {
    expectCallerShadowEqualsAov(Settings{}, 1);
}

TEST_F(ShadowSystemTest, CallersSpotShadowFromVirtualFacesEqualsTheShadowAov) {
    Settings settings;
    settings.shadows.spot.mode = SpotShadowMode::Virtual;
    expectCallerShadowEqualsAov(settings, 1);
}

// The caller's depth (ShadowViewDepth) is what marks the virtual pages: an empty one (all far, 0 in
// reversed Z) requests none, where Penumbra's own depth of the scene requests some.
TEST_F(ShadowSystemTest, TheCallersDepthMarksTheVirtualPages) {
    makeGroundPass();
    if (HasFatalFailure()) return;
    VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    imageInfo.imageType = VK_IMAGE_TYPE_2D;
    imageInfo.format = VK_FORMAT_D32_SFLOAT;
    imageInfo.extent = {kWidth, kHeight, 1};
    imageInfo.mipLevels = imageInfo.arrayLayers = 1;
    imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
    imageInfo.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    VkImage depth = VK_NULL_HANDLE;
    CHECK_VK(vkCreateImage(device, &imageInfo, nullptr, &depth));
    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, depth, &requirements);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = requirements.size;
    alloc.memoryTypeIndex = memoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    CHECK_VK(vkAllocateMemory(device, &alloc, nullptr, &memory));
    CHECK_VK(vkBindImageMemory(device, depth, memory, 0));
    images.emplace_back(depth, memory);  // the fixture frees it
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = depth;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = VK_FORMAT_D32_SFLOAT;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
    VkImageView depthView = VK_NULL_HANDLE;
    CHECK_VK(vkCreateImageView(device, &viewInfo, nullptr, &depthView));

    Settings settings;
    settings.shadows.directional.mode = DirectionalShadowMode::Virtual;
    uint32_t requested[2] = {};
    {
        Device penumbraDevice(externalVulkanDevice(instance, physicalDevice, device, queue, 0, false, true));
        ShadowSystem shadows(penumbraDevice, groundOnlyScene());
        const CameraView view = resolveCameraView(shadows.scene(), kWidth, kHeight);
        for (int withDepth = 0; withDepth < 2; ++withDepth) {
            vkResetCommandBuffer(commandBuffer, 0);
            VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
            vkBeginCommandBuffer(commandBuffer, &begin);
            // The caller's "depth prepass": cleared to empty, left in DEPTH_ATTACHMENT_OPTIMAL.
            imageBarrier(commandBuffer, depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
            const VkClearDepthStencilValue empty{0.0f, 0};
            vkCmdClearDepthStencilImage(commandBuffer, depth, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &empty, 1,
                                        &viewInfo.subresourceRange);
            imageBarrier(commandBuffer, depth, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
            const ShadowFrameBindings frame = recordShadowFrame(shadows, commandBuffer, settings, view,
                                                                withDepth ? depth : VK_NULL_HANDLE,
                                                                withDepth ? depthView : VK_NULL_HANDLE);
            vkEndCommandBuffer(commandBuffer);
            submitWithSignal(frame);
            shadows.waitIdle();
            const std::vector<FrameStats> frames = shadows.takeCompletedFrames();
            ASSERT_FALSE(frames.empty());
            requested[withDepth] = frames.back().virtualPages.requested;
        }
    }
    vkDestroyImageView(device, depthView, nullptr);
    EXPECT_GT(requested[0], 0u) << "Penumbra's own depth of the scene";
    EXPECT_EQ(requested[1], 0u) << "the caller's empty depth";
}

// The caller's own buffers of a scene's casters, as an engine keeps them: one interleaved vertex buffer
// (position, normal, uv: 32 bytes a vertex, meshes one after another, drawn with vertexOffset) and 16-bit
// indices after 8 bytes of something else.
struct CallerGeometry {
    std::vector<float> vertices;
    std::vector<uint16_t> indices{0xdead, 0xbeef, 0xdead, 0xbeef};  // the 8 bytes before indexOffset
    CasterBuffers casters;
};

CallerGeometry callerGeometryOf(const Scene& scene) {
    CallerGeometry geometry;
    std::vector<CasterMesh> meshes;
    for (const Mesh& mesh : scene.meshes) {
        meshes.push_back({uint32_t(geometry.indices.size() - 4), uint32_t(mesh.indices.size()),
                          int32_t(geometry.vertices.size() / 8)});
        for (const Vertex& v : mesh.vertices)
            geometry.vertices.insert(geometry.vertices.end(), {v.osPosition.x, v.osPosition.y, v.osPosition.z, v.osNormal.x,
                                                               v.osNormal.y, v.osNormal.z, v.uv.x, v.uv.y});
        for (uint32_t index : mesh.indices) geometry.indices.push_back(uint16_t(index));
    }
    geometry.casters.meshes = meshes;
    geometry.casters.vertexCount = uint32_t(geometry.vertices.size() / 8);
    geometry.casters.indexCount = uint32_t(geometry.indices.size() - 4);
    geometry.casters.indexType = CasterIndexType::Uint16;
    geometry.casters.indexOffset = 8;
    geometry.casters.positionStride = geometry.casters.uvStride = 32;
    geometry.casters.uvOffset = 24;
    for (const Instance& instance : scene.instances) {
        CasterInstance caster;
        caster.mesh = instance.meshIndex;
        caster.worldFromObject = instance.worldFromObject;
        caster.castShadows = instance.castShadows;
        geometry.casters.instances.push_back(caster);
    }
    return geometry;
}

class ShadowSystemCasterBuffersTest : public ShadowSystemTest {
protected:
    // The caller's buffers of `geometry` (TRANSFER_SRC usage, as ShadowSystem reads them) filled in.
    void upload(CallerGeometry& geometry) {
        const VkBufferUsageFlags usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
        const VkBuffer vertices = makeBuffer(geometry.vertices.data(), geometry.vertices.size() * sizeof(float), usage);
        const VkBuffer indices = makeBuffer(geometry.indices.data(), geometry.indices.size() * sizeof(uint16_t),
                                            VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        geometry.casters.vkPositionBuffer = geometry.casters.vkUvBuffer = reinterpret_cast<uint64_t>(vertices);
        geometry.casters.vkIndexBuffer = reinterpret_cast<uint64_t>(indices);
    }

    // A 4x4 B8G8R8A8 texture of the caller, blue and fully transparent (a swizzle that read blue as alpha
    // would make it opaque), sampled by its shaders: left in SHADER_READ_ONLY_OPTIMAL.
    CasterTexture transparentTexture() {
        const std::vector<uint8_t> texels(4 * 4 * 4, 0);
        std::vector<uint8_t> bgra = texels;
        for (size_t i = 0; i < bgra.size(); i += 4) bgra[i] = 255;
        const VkBuffer staging = makeBuffer(bgra.data(), bgra.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
        const VkImage image = makeImage(VK_FORMAT_B8G8R8A8_UNORM, 4, 4,
                                        VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
        vkResetCommandBuffer(commandBuffer, 0);
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(commandBuffer, &begin);
        imageBarrier(commandBuffer, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {4, 4, 1};
        vkCmdCopyBufferToImage(commandBuffer, staging, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        imageBarrier(commandBuffer, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        vkEndCommandBuffer(commandBuffer);
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &commandBuffer;
        EXPECT_EQ(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);  // not waited for: ShadowSystem's read is after it
        CasterTexture texture;
        texture.vkImage = reinterpret_cast<uint64_t>(image);
        texture.vkFormat = VK_FORMAT_B8G8R8A8_UNORM;
        texture.width = texture.height = 4;
        texture.vkImageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        return texture;
    }

    // The caller's ground term of light 0 (cascades), second frame, of a ShadowSystem made by `make`.
    template <typename Make>
    std::vector<float> groundTerm(Device& penumbraDevice, Make&& make) {
        ShadowSystem shadows = make(penumbraDevice);
        const CameraView view = resolveCameraView(groundOnlyScene(), kWidth, kHeight);
        callerFrame(shadows, Settings{}, view, 0);
        std::vector<float> term = callerFrame(shadows, Settings{}, view, 0);
        shadows.waitIdle();
        return term;
    }
};

size_t pixelsThatDiffer(const std::vector<float>& a, const std::vector<float>& b) {
    size_t count = 0;
    for (size_t p = 0; p < a.size(); ++p) count += a[p] != b[p];
    return count;
}

// The same geometry read from the caller's buffers (interleaved, 16-bit indices at an offset, meshes
// drawn with vertexOffset) casts exactly the shadows of the Scene holding it: same passes, same depths.
TEST_F(ShadowSystemCasterBuffersTest, TheCallersBuffersCastTheShadowsOfTheSceneTheyHold) {
    makeGroundPass();
    if (HasFatalFailure()) return;
    CallerGeometry geometry = callerGeometryOf(groundOnlyScene());
    upload(geometry);
    Device penumbraDevice(externalVulkanDevice(instance, physicalDevice, device, queue, 0, false, true));
    const std::vector<float> fromScene =
        groundTerm(penumbraDevice, [](Device& d) { return ShadowSystem(d, groundOnlyScene()); });
    const std::vector<float> fromBuffers = groundTerm(
        penumbraDevice, [&](Device& d) { return ShadowSystem(d, geometry.casters, groundOnlyScene().lights); });
    size_t shadowed = 0;
    for (float value : fromScene) shadowed += value >= 0.0f && value < 0.25f;
    EXPECT_GT(shadowed, fromScene.size() / 50) << "the scene must show shadow";
    EXPECT_EQ(pixelsThatDiffer(fromScene, fromBuffers), 0u);
}

// A clip caster whose alpha texture (the caller's, in B8G8R8A8) is transparent everywhere casts nothing:
// the texture was read, swizzled and sampled; the caller's image is back in its layout.
TEST_F(ShadowSystemCasterBuffersTest, AClipCasterWithATransparentAlphaTextureCastsNothing) {
    makeGroundPass();
    if (HasFatalFailure()) return;
    CallerGeometry geometry = callerGeometryOf(groundOnlyScene());
    upload(geometry);
    geometry.casters.alphaTextures.push_back(transparentTexture());
    geometry.casters.instances[1].shadowMode = MaterialShadowMode::Clip;
    geometry.casters.instances[1].alphaTexture = 0;
    Device penumbraDevice(externalVulkanDevice(instance, physicalDevice, device, queue, 0, false, true));
    const std::vector<float> clipped =
        groundTerm(penumbraDevice, [&](Device& d) { return ShadowSystem(d, geometry.casters, groundOnlyScene().lights); });
    const std::vector<float> withoutBox = groundTerm(penumbraDevice, [](Device& d) {
        Scene scene = groundOnlyScene();
        scene.instances[1].castShadows = false;
        return ShadowSystem(d, std::move(scene));
    });
    const std::vector<float> withBox =
        groundTerm(penumbraDevice, [](Device& d) { return ShadowSystem(d, groundOnlyScene()); });
    EXPECT_GT(pixelsThatDiffer(withBox, withoutBox), 20u) << "the box's shadow must be in view";
    EXPECT_EQ(pixelsThatDiffer(clipped, withoutBox), 0u);
}

TEST_F(ShadowSystemTest, ADeviceWithoutTimelineSemaphoresIsRefusedWithOneLine) {
    Device penumbraDevice(externalVulkanDevice(instance, physicalDevice, device, queue, 0));
    try {
        ShadowSystem shadows(penumbraDevice, groundOnlyScene());
        FAIL() << "no error";
    } catch (const Error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("timelineSemaphore"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos);
    }
}

}  // namespace
}  // namespace penumbra::test

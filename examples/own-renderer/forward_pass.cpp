#include "forward_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <penumbra/vulkan.h>

namespace own {

namespace {

struct VertexIn {
    glm::vec3 osPosition, osNormal;
    glm::vec2 uv;
};

struct DrawConstants {
    glm::mat4 worldFromObject;
    glm::vec4 baseColorFactor;
    float alphaCutoff;
    uint32_t flags;
};

struct FrameUniforms {
    glm::mat4 clipFromWorld;
    glm::vec4 wsLight0;
};

constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
constexpr VkFormat kShadowFormat = VK_FORMAT_R8_UNORM;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

VkShaderModule loadShader(VkDevice device, const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    const std::vector<char> code((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (code.empty() || code.size() % 4 != 0) throw std::runtime_error("cannot read the shader " + path);
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = code.size();
    info.pCode = reinterpret_cast<const uint32_t*>(code.data());
    VkShaderModule module = VK_NULL_HANDLE;
    OWN_VK(vkCreateShaderModule(device, &info, nullptr, &module));
    return module;
}

void imageBarrier(VkCommandBuffer commandBuffer, VkImage image, VkImageAspectFlags aspect, uint32_t firstMip,
                  uint32_t mips, VkImageLayout from, VkImageLayout to, VkPipelineStageFlags2 srcStage,
                  VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    barrier.srcStageMask = srcStage;
    barrier.srcAccessMask = srcAccess;
    barrier.dstStageMask = dstStage;
    barrier.dstAccessMask = dstAccess;
    barrier.oldLayout = from;
    barrier.newLayout = to;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {aspect, firstMip, mips, 0, 1};
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(commandBuffer, &dependency);
}

}  // namespace

ForwardPass::ForwardPass(VulkanContext& vulkan, const penumbra::Scene& scene, uint32_t width, uint32_t height,
                         const std::string& spirvDir, bool depthPrepass)
    : vk_(vulkan), width_(width), height_(height), depthPrepass_(depthPrepass) {
    meshRanges_ = uploadMeshes(scene);
    const std::vector<Draw>& meshes = meshRanges_;
    uploadTextures(scene);
    makeDescriptors(textures_.size());
    makePipelines(spirvDir);
    makeTargets();
    for (const penumbra::Instance& instance : scene.instances) {
        const penumbra::Mesh& mesh = scene.meshes[instance.meshIndex];
        const penumbra::Material& material = scene.materials[mesh.materialIndex];
        Draw placed = meshes[instance.meshIndex];
        placed.worldFromObject = instance.worldFromObject;
        placed.baseColorFactor = material.baseColorFactor;
        placed.alphaCutoff = material.alphaMode == penumbra::AlphaMode::Mask ? material.alphaCutoff : -1.0f;
        placed.flags = material.receiveShadows ? 1u : 0u;
        placed.doubleSided = material.doubleSided;
        placed.texture = material.baseColorTexture >= 0 ? uint32_t(material.baseColorTexture) + 1 : 0;
        draws_.push_back(placed);
    }
}

ForwardPass::~ForwardPass() {
    VkDevice device = vk_.device;
    vkDeviceWaitIdle(device);
    for (VkPipeline pipeline : pipelines_) vkDestroyPipeline(device, pipeline, nullptr);
    for (VkPipeline pipeline : prepassPipelines_) vkDestroyPipeline(device, pipeline, nullptr);
    vkDestroyPipelineLayout(device, layout_, nullptr);
    vkDestroyDescriptorPool(device, pool_, nullptr);
    for (VkDescriptorSetLayout layout : {frameLayout_, textureLayout_, shadowLayout_})
        vkDestroyDescriptorSetLayout(device, layout, nullptr);
    vkDestroySampler(device, sampler_, nullptr);
    for (Texture& texture : textures_) vk_.destroy(texture);
    for (Texture* target : {&color_, &shadow_, &depth_}) vk_.destroy(*target);
    for (Buffer* buffer : {&vertices_, &indices_, &frame_, &colorReadback_, &shadowReadback_}) vk_.destroy(*buffer);
}

// Every mesh's vertices and indices in one buffer each; returns each mesh's range.
std::vector<ForwardPass::Draw> ForwardPass::uploadMeshes(const penumbra::Scene& scene) {
    std::vector<Draw> ranges;
    std::vector<VertexIn> vertices;
    std::vector<uint32_t> indices;
    for (const penumbra::Mesh& mesh : scene.meshes) {
        Draw range;
        range.firstIndex = uint32_t(indices.size());
        range.indexCount = uint32_t(mesh.indices.size());
        range.vertexOffset = int32_t(vertices.size());
        for (const penumbra::Vertex& v : mesh.vertices) vertices.push_back({v.osPosition, v.osNormal, v.uv});
        indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
        ranges.push_back(range);
    }
    // TRANSFER_SRC: ShadowSystem reads its casters from them.
    vertices_ = vk_.createBuffer(std::max<size_t>(vertices.size(), 1) * sizeof(VertexIn),
                                 VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    indices_ = vk_.createBuffer(std::max<size_t>(indices.size(), 1) * sizeof(uint32_t),
                                VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    vertexCount_ = uint32_t(vertices.size());
    indexCount_ = uint32_t(indices.size());
    std::memcpy(vertices_.mapped, vertices.data(), vertices.size() * sizeof(VertexIn));
    std::memcpy(indices_.mapped, indices.data(), indices.size() * sizeof(uint32_t));
    frame_ = vk_.createBuffer(sizeof(FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
    return ranges;
}

penumbra::CasterBuffers ForwardPass::casterBuffers(const penumbra::Scene& scene) const {
    penumbra::CasterBuffers casters;
    casters.vkPositionBuffer = casters.vkUvBuffer = reinterpret_cast<uint64_t>(vertices_.buffer);
    casters.positionStride = casters.uvStride = sizeof(VertexIn);
    casters.positionOffset = offsetof(VertexIn, osPosition);
    casters.uvOffset = offsetof(VertexIn, uv);
    casters.vertexCount = vertexCount_;
    casters.vkIndexBuffer = reinterpret_cast<uint64_t>(indices_.buffer);
    casters.indexType = penumbra::CasterIndexType::Uint32;
    casters.indexCount = indexCount_;
    for (const Draw& range : meshRanges_) casters.meshes.push_back({range.firstIndex, range.indexCount, range.vertexOffset});
    for (size_t t = 0; t < scene.textures.size(); ++t) {
        const Texture& texture = textures_[t + 1];
        casters.alphaTextures.push_back({reinterpret_cast<uint64_t>(texture.image), uint32_t(texture.format), texture.width,
                                         texture.height, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, scene.textures[t].sampler});
    }
    for (const penumbra::Instance& instance : scene.instances) {
        const penumbra::Material& material = scene.materials[scene.meshes[instance.meshIndex].materialIndex];
        penumbra::CasterInstance caster;
        caster.mesh = instance.meshIndex;
        caster.worldFromObject = instance.worldFromObject;
        caster.castShadows = instance.castShadows;
        caster.shadowMode = material.shadows;
        caster.alpha = material.baseColorFactor.a;
        caster.alphaCutoff = material.alphaCutoff;
        caster.alphaTexture = material.baseColorTexture;
        caster.alphaMode = material.alphaMode;
        caster.doubleSided = material.doubleSided;
        caster.name = instance.nodeName;
        casters.instances.push_back(caster);
    }
    return casters;
}

// An sRGB RGBA8 texture with its mip chain (blits), left in SHADER_READ_ONLY_OPTIMAL.
Texture ForwardPass::uploadTexture(const penumbra::Image& rgba, bool srgb) {
    const uint32_t mips = uint32_t(std::floor(std::log2(double(std::max(rgba.width, rgba.height))))) + 1;
    Texture texture = vk_.createTexture(srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM, rgba.width, rgba.height,
                                        mips,
                                        VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                        VK_IMAGE_ASPECT_COLOR_BIT);
    Buffer staging = vk_.createBuffer(rgba.pixels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, rgba.pixels.data(), rgba.pixels.size());
    VkCommandBuffer cb = vk_.beginOneOff();
    imageBarrier(cb, texture.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, mips, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {rgba.width, rgba.height, 1};
    vkCmdCopyBufferToImage(cb, staging.buffer, texture.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    int32_t w = int32_t(rgba.width), h = int32_t(rgba.height);
    for (uint32_t mip = 1; mip < mips; ++mip) {
        imageBarrier(cb, texture.image, VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkImageBlit blit{};
        blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 0, 1};
        blit.srcOffsets[1] = {w, h, 1};
        w = std::max(w / 2, 1);
        h = std::max(h / 2, 1);
        blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 0, 1};
        blit.dstOffsets[1] = {w, h, 1};
        vkCmdBlitImage(cb, texture.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, texture.image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
    }
    if (mips > 1)
        imageBarrier(cb, texture.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, mips - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, 0,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    imageBarrier(cb, texture.image, VK_IMAGE_ASPECT_COLOR_BIT, mips - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    vk_.submitOneOff(cb);
    vk_.destroy(staging);
    return texture;
}

void ForwardPass::uploadTextures(const penumbra::Scene& scene) {
    penumbra::Image white(1, 1, 4, 255);
    textures_.push_back(uploadTexture(white, false));
    for (const penumbra::Texture& texture : scene.textures) textures_.push_back(uploadTexture(texture.rgba, true));
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    info.maxLod = VK_LOD_CLAMP_NONE;
    OWN_VK(vkCreateSampler(vk_.device, &info, nullptr, &sampler_));
}

// Set 0: the frame's uniforms; set 1: a base colour texture per material texture; set 2: the shadows.
void ForwardPass::makeDescriptors(size_t textureCount) {
    VkDevice device = vk_.device;
    const VkShaderStageFlags graphics = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    VkDescriptorSetLayoutBinding frameBinding{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, graphics};
    VkDescriptorSetLayoutBinding textureBinding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT};
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = 1;
    info.pBindings = &frameBinding;
    OWN_VK(vkCreateDescriptorSetLayout(device, &info, nullptr, &frameLayout_));
    info.pBindings = &textureBinding;
    OWN_VK(vkCreateDescriptorSetLayout(device, &info, nullptr, &textureLayout_));
    OWN_VK(penumbra::createShadowDescriptorSetLayout(device, VK_SHADER_STAGE_FRAGMENT_BIT, 0, &shadowLayout_));

    VkDescriptorPoolSize sizes[3];
    penumbra::shadowDescriptorPoolSizes(sizes);
    sizes[0].descriptorCount += 1;
    sizes[2].descriptorCount += uint32_t(textureCount);
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = uint32_t(textureCount) + 2;
    poolInfo.poolSizeCount = 3;
    poolInfo.pPoolSizes = sizes;
    OWN_VK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool_));
    VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    alloc.descriptorPool = pool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &frameLayout_;
    OWN_VK(vkAllocateDescriptorSets(device, &alloc, &frameSet_));
    alloc.pSetLayouts = &shadowLayout_;
    OWN_VK(vkAllocateDescriptorSets(device, &alloc, &shadowSet_));
    VkDescriptorBufferInfo frameInfo{frame_.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = frameSet_;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    write.pBufferInfo = &frameInfo;
    vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
    alloc.pSetLayouts = &textureLayout_;
    for (const Texture& texture : textures_) {
        VkDescriptorSet set = VK_NULL_HANDLE;
        OWN_VK(vkAllocateDescriptorSets(device, &alloc, &set));
        VkDescriptorImageInfo image{sampler_, texture.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        VkWriteDescriptorSet textureWrite{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        textureWrite.dstSet = set;
        textureWrite.descriptorCount = 1;
        textureWrite.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        textureWrite.pImageInfo = &image;
        vkUpdateDescriptorSets(device, 1, &textureWrite, 0, nullptr);
        textureSets_.push_back(set);
    }
}

void ForwardPass::makePipelines(const std::string& spirvDir) {
    VkDevice device = vk_.device;
    const VkDescriptorSetLayout sets[3] = {frameLayout_, textureLayout_, shadowLayout_};
    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawConstants)};
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 3;
    layoutInfo.pSetLayouts = sets;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &push;
    OWN_VK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout_));

    const VkShaderModule vertex = loadShader(device, spirvDir + "/forward.vert.spv");
    const VkShaderModule fragment = loadShader(device, spirvDir + "/forward.frag.spv");
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vertex;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fragment;
    stages[1].pName = "main";
    VkVertexInputBindingDescription binding{0, sizeof(VertexIn), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attributes[3] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(VertexIn, osPosition)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(VertexIn, osNormal)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(VertexIn, uv)}};
    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = 1;
    vertexInput.pVertexBindingDescriptions = &binding;
    vertexInput.vertexAttributeDescriptionCount = 3;
    vertexInput.pVertexAttributeDescriptions = attributes;
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;  // glTF's, kept by the y-flipped projection
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = VK_TRUE;
    // Reversed Z (penumbra/camera.h); after the engine's own depth prepass the forward pass tests against
    // its depth (the same vertex shader gives the same depth) and writes none.
    depth.depthWriteEnable = depthPrepass_ ? VK_FALSE : VK_TRUE;
    depth.depthCompareOp = depthPrepass_ ? VK_COMPARE_OP_GREATER_OR_EQUAL : VK_COMPARE_OP_GREATER;
    VkPipelineColorBlendAttachmentState blend[2] = {};
    blend[0].colorWriteMask = blend[1].colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                                        VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo colorBlend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    colorBlend.attachmentCount = 2;
    colorBlend.pAttachments = blend;
    const VkDynamicState dynamicStates[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic.dynamicStateCount = 2;
    dynamic.pDynamicStates = dynamicStates;
    const VkFormat colorFormats[2] = {kColorFormat, kShadowFormat};
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 2;
    rendering.pColorAttachmentFormats = colorFormats;
    rendering.depthAttachmentFormat = kDepthFormat;
    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.pNext = &rendering;
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertexInput;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &colorBlend;
    info.pDynamicState = &dynamic;
    info.layout = layout_;
    for (int doubleSided = 0; doubleSided < 2; ++doubleSided) {
        raster.cullMode = doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
        OWN_VK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipelines_[doubleSided]));
    }
    const VkShaderModule depthOnly = loadShader(device, spirvDir + "/depth.frag.spv");
    if (depthPrepass_) {  // depth only: no colour target, the depth written
        stages[1].module = depthOnly;
        rendering.colorAttachmentCount = 0;
        colorBlend.attachmentCount = 0;
        depth.depthWriteEnable = VK_TRUE;
        depth.depthCompareOp = VK_COMPARE_OP_GREATER;
        for (int doubleSided = 0; doubleSided < 2; ++doubleSided) {
            raster.cullMode = doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
            OWN_VK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &prepassPipelines_[doubleSided]));
        }
    }
    vkDestroyShaderModule(device, vertex, nullptr);
    vkDestroyShaderModule(device, fragment, nullptr);
    vkDestroyShaderModule(device, depthOnly, nullptr);
}

void ForwardPass::makeTargets() {
    const VkImageUsageFlags target = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    color_ = vk_.createTexture(kColorFormat, width_, height_, 1, target, VK_IMAGE_ASPECT_COLOR_BIT);
    shadow_ = vk_.createTexture(kShadowFormat, width_, height_, 1, target, VK_IMAGE_ASPECT_COLOR_BIT);
    // Sampled too: ShadowSystem reads it after the depth prepass (ShadowViewDepth).
    depth_ = vk_.createTexture(kDepthFormat, width_, height_, 1,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                               VK_IMAGE_ASPECT_DEPTH_BIT);
    colorReadback_ = vk_.createBuffer(VkDeviceSize(width_) * height_ * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    shadowReadback_ = vk_.createBuffer(VkDeviceSize(width_) * height_, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
}

void ForwardPass::drawAll(VkCommandBuffer cb, const VkPipeline pipelines[2]) {
    const VkViewport viewport{0.0f, 0.0f, float(width_), float(height_), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {width_, height_}};
    vkCmdSetViewport(cb, 0, 1, &viewport);
    vkCmdSetScissor(cb, 0, 1, &scissor);
    const VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cb, 0, 1, &vertices_.buffer, &offset);
    vkCmdBindIndexBuffer(cb, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
    for (int doubleSided = 0; doubleSided < 2; ++doubleSided) {
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines[doubleSided]);
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &frameSet_, 0, nullptr);
        if (pipelines == pipelines_)
            vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 2, 1, &shadowSet_, 0, nullptr);
        for (const Draw& draw : draws_) {
            if (draw.doubleSided != bool(doubleSided) || draw.indexCount == 0) continue;
            vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 1, 1, &textureSets_[draw.texture], 0, nullptr);
            const DrawConstants constants{draw.worldFromObject, draw.baseColorFactor, draw.alphaCutoff, draw.flags};
            vkCmdPushConstants(cb, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(constants), &constants);
            vkCmdDrawIndexed(cb, draw.indexCount, 1, draw.firstIndex, draw.vertexOffset, 0);
        }
    }
}

void ForwardPass::recordDepthPrepass(VkCommandBuffer cb, const glm::mat4& clipFromWorld, const glm::vec4& wsLight0) {
    const FrameUniforms uniforms{clipFromWorld, wsLight0};
    std::memcpy(frame_.mapped, &uniforms, sizeof(uniforms));
    imageBarrier(cb, depth_.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                 VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = depth_.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth.clearValue.depthStencil = {0.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {width_, height_}};
    rendering.layerCount = 1;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cb, &rendering);
    drawAll(cb, prepassPipelines_);
    vkCmdEndRendering(cb);
}

void ForwardPass::record(VkCommandBuffer cb, const glm::mat4& clipFromWorld, const glm::vec4& wsLight0) {
    const FrameUniforms uniforms{clipFromWorld, wsLight0};
    std::memcpy(frame_.mapped, &uniforms, sizeof(uniforms));
    const VkPipelineStageFlags2 attachments = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    for (VkImage image : {color_.image, shadow_.image})
        imageBarrier(cb, image, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0, attachments,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    // After a prepass the depth is as ShadowSystem left it: DEPTH_ATTACHMENT_OPTIMAL, its reads done.
    if (!depthPrepass_)
        imageBarrier(cb, depth_.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0,
                     VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    // The background: black, and "lit" (1) in the shadow term, as the shadow AOV's.
    VkRenderingAttachmentInfo colors[2] = {{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO},
                                           {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO}};
    colors[0].imageView = color_.view;
    colors[1].imageView = shadow_.view;
    for (VkRenderingAttachmentInfo& color : colors) {
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    }
    colors[0].clearValue.color = {{0.0f, 0.0f, 0.0f, 1.0f}};
    colors[1].clearValue.color = {{1.0f, 1.0f, 1.0f, 1.0f}};
    VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth.imageView = depth_.view;
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = depthPrepass_ ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {0.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {width_, height_}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 2;
    rendering.pColorAttachments = colors;
    rendering.pDepthAttachment = &depth;
    vkCmdBeginRendering(cb, &rendering);
    drawAll(cb, pipelines_);
    vkCmdEndRendering(cb);

    for (VkImage image : {color_.image, shadow_.image})
        imageBarrier(cb, image, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, attachments, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(cb, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, colorReadback_.buffer, 1, &copy);
    vkCmdCopyImageToBuffer(cb, shadow_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shadowReadback_.buffer, 1, &copy);
    VkMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    toHost.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.memoryBarrierCount = 1;
    dependency.pMemoryBarriers = &toHost;
    vkCmdPipelineBarrier2(cb, &dependency);
}

std::vector<uint8_t> ForwardPass::colorPixels() const {
    const auto* rgba = static_cast<const uint8_t*>(colorReadback_.mapped);
    std::vector<uint8_t> rgb(size_t(width_) * height_ * 3);
    for (size_t p = 0; p < size_t(width_) * height_; ++p)
        for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = rgba[p * 4 + c];
    return rgb;
}

std::vector<uint8_t> ForwardPass::shadowPixels() const {
    const auto* r8 = static_cast<const uint8_t*>(shadowReadback_.mapped);
    return std::vector<uint8_t>(r8, r8 + size_t(width_) * height_);
}

}  // namespace own

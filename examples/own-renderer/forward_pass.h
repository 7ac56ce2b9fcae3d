#pragma once
// The engine's own forward pass: the scene's meshes in its vertex and index buffers, its materials'
// base colour textures, one graphics pipeline writing colour and light 0's shadow term, and the draws.
// The shadows come in as one descriptor set of <penumbra/shadows.glsl> (set 2), which ShadowSystem fills.
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <penumbra/caster_buffers.h>
#include <penumbra/scene.h>

#include "vulkan_context.h"

namespace own {

class ForwardPass {
public:
    // depthPrepass: the engine draws its depth first (recordDepthPrepass), hands it to ShadowSystem, and
    // the forward pass tests against it.
    ForwardPass(VulkanContext& vulkan, const penumbra::Scene& scene, uint32_t width, uint32_t height,
                const std::string& spirvDir, bool depthPrepass);
    ~ForwardPass();
    ForwardPass(const ForwardPass&) = delete;
    ForwardPass& operator=(const ForwardPass&) = delete;

    // The engine's shadow casters for ShadowSystem: its own vertex buffer (positions and uvs), index
    // buffer and base colour textures (their alpha), with each instance's material as how it casts.
    penumbra::CasterBuffers casterBuffers(const penumbra::Scene& scene) const;
    VkDescriptorSet shadowSet() const { return shadowSet_; }
    VkImage depthImage() const { return depth_.image; }
    VkImageView depthView() const { return depth_.view; }
    // The depth prepass, before ShadowSystem's commands: leaves the depth in DEPTH_ATTACHMENT_OPTIMAL.
    void recordDepthPrepass(VkCommandBuffer commandBuffer, const glm::mat4& clipFromWorld, const glm::vec4& wsLight0);
    // Records the pass (after ShadowSystem's commands in the same command buffer) and the copies of its
    // two targets into host-visible buffers.
    void record(VkCommandBuffer commandBuffer, const glm::mat4& clipFromWorld, const glm::vec4& wsLight0);
    // After the submission finished: RGB colour and 8-bit shadow term.
    std::vector<uint8_t> colorPixels() const;
    std::vector<uint8_t> shadowPixels() const;

private:
    struct Draw {
        uint32_t firstIndex = 0, indexCount = 0;
        int32_t vertexOffset = 0;
        glm::mat4 worldFromObject{1.0f};
        glm::vec4 baseColorFactor{1.0f};
        float alphaCutoff = -1.0f;
        uint32_t flags = 0;
        bool doubleSided = false;
        uint32_t texture = 0;  // index into textureSets_ (0: white)
    };
    std::vector<Draw> uploadMeshes(const penumbra::Scene& scene);
    void uploadTextures(const penumbra::Scene& scene);
    Texture uploadTexture(const penumbra::Image& rgba, bool srgb);
    void makeDescriptors(size_t textureCount);
    void makePipelines(const std::string& spirvDir);
    void drawAll(VkCommandBuffer commandBuffer, const VkPipeline pipelines[2]);
    void makeTargets();

    VulkanContext& vk_;
    uint32_t width_, height_;
    Buffer vertices_, indices_, frame_, colorReadback_, shadowReadback_;
    std::vector<Texture> textures_;  // [0]: 1x1 white
    VkSampler sampler_ = VK_NULL_HANDLE;
    Texture color_, shadow_, depth_;
    VkDescriptorSetLayout frameLayout_ = VK_NULL_HANDLE, textureLayout_ = VK_NULL_HANDLE, shadowLayout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkDescriptorSet frameSet_ = VK_NULL_HANDLE, shadowSet_ = VK_NULL_HANDLE;
    std::vector<VkDescriptorSet> textureSets_;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipelines_[2] = {};  // back faces culled, double-sided
    VkPipeline prepassPipelines_[2] = {};
    bool depthPrepass_ = false;
    std::vector<Draw> draws_;
    std::vector<Draw> meshRanges_;  // per scene mesh: its range of the index buffer
    uint32_t vertexCount_ = 0, indexCount_ = 0;
};

}  // namespace own

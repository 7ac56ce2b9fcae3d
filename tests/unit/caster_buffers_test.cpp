// sceneFromCasterBuffers / validateCasterBuffers: an engine's caster buffers, once read, become the Scene
// ShadowSystem draws: instance for instance, each mesh with the vertices its triangles use, one scene
// mesh per (mesh, material) pair; descriptions that cannot be read get one line naming the field.
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "error_message.h"
#include "penumbra/caster_buffers.h"
#include "penumbra/scene_builder.h"

using namespace penumbra;

namespace {

constexpr uint64_t kSomeBuffer = 0x1000;  // any non-null handle: nothing here touches Vulkan

// Two quads in one stream (vertices 0-3 and 4-7; the second drawn with vertexOffset 4), both placed twice.
struct TwoQuads {
    CasterBuffers casters;
    CasterBufferContents contents;
    TwoQuads() {
        casters.vkPositionBuffer = casters.vkIndexBuffer = casters.vkUvBuffer = kSomeBuffer;
        casters.vertexCount = 8;
        contents.osPositions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {6, 2, 0}, {5, 2, 0}};
        for (const glm::vec3& p : contents.osPositions) contents.uvs.push_back({p.x * 0.25f, p.y * 0.5f});
        contents.indices = {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3};
        casters.indexCount = 12;
        casters.meshes = {{0, 6, 0}, {6, 6, 4}};
        for (uint32_t i = 0; i < 4; ++i) {
            CasterInstance instance;
            instance.mesh = i % 2;
            instance.worldFromObject = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, float(i)));
            casters.instances.push_back(instance);
        }
    }
    Scene scene() const { return sceneFromCasterBuffers(casters, contents, {makeDirectionalLight({0, -1, 0}, 3.0f)}); }
};

std::string sceneError(const TwoQuads& quads) {
    return penumbra::testing::errorMessage([&] { (void)quads.scene(); });
}

TEST(CasterBuffers, InstanceIOfTheBuffersIsInstanceIOfTheScene) {
    const TwoQuads quads;
    const Scene scene = quads.scene();
    ASSERT_EQ(scene.instances.size(), 4u);
    for (uint32_t i = 0; i < 4; ++i) {
        EXPECT_EQ(scene.instances[i].worldFromObject, quads.casters.instances[i].worldFromObject);
        const Mesh& mesh = scene.meshes[scene.instances[i].meshIndex];
        EXPECT_EQ(mesh.osBounds.max, i % 2 == 0 ? glm::vec3(1, 1, 0) : glm::vec3(6, 2, 0)) << "instance " << i;
    }
    EXPECT_EQ(scene.lights.size(), 1u);
}

TEST(CasterBuffers, AMeshKeepsOnlyTheVerticesItsTrianglesUseRebasedToItsFirst) {
    const Scene scene = TwoQuads().scene();
    ASSERT_EQ(scene.meshes.size(), 2u);  // two instances of each mesh share it: same material
    const Mesh& second = scene.meshes[scene.instances[1].meshIndex];
    ASSERT_EQ(second.vertices.size(), 4u);
    EXPECT_EQ(second.vertices[0].osPosition, glm::vec3(5, 0, 0));
    EXPECT_EQ(second.vertices[2].uv, glm::vec2(1.5f, 1.0f));
    EXPECT_EQ(second.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST(CasterBuffers, OneMeshWithTwoShadowModesBecomesTwoSceneMeshes) {
    TwoQuads quads;
    quads.casters.instances[2].shadowMode = MaterialShadowMode::Clip;
    quads.casters.instances[2].alphaMode = AlphaMode::Mask;
    quads.casters.instances[2].alphaCutoff = 0.3f;
    const Scene scene = quads.scene();
    EXPECT_EQ(scene.meshes.size(), 3u);
    EXPECT_NE(scene.instances[0].meshIndex, scene.instances[2].meshIndex);
    const Material& clip = scene.materials[scene.meshes[scene.instances[2].meshIndex].materialIndex];
    EXPECT_EQ(clip.shadows, MaterialShadowMode::Clip);
    EXPECT_EQ(clip.alphaMode, AlphaMode::Mask);
    EXPECT_FLOAT_EQ(clip.alphaCutoff, 0.3f);
}

TEST(CasterBuffers, AnAlphaTextureBecomesTheMaterialsBaseColourTexture) {
    TwoQuads quads;
    CasterTexture texture;
    texture.vkImage = kSomeBuffer;
    texture.vkFormat = 43;  // VK_FORMAT_R8G8B8A8_SRGB
    texture.width = texture.height = 2;
    texture.sampler.magFilter = TextureFilter::Nearest;
    quads.casters.alphaTextures.push_back(texture);
    quads.contents.alphaTextures.push_back(Image(2, 2, 4, 200));
    quads.casters.instances[1].shadowMode = MaterialShadowMode::Dither;
    quads.casters.instances[1].alphaTexture = 0;
    quads.casters.instances[1].alpha = 0.5f;
    const Scene scene = quads.scene();
    const Material& dither = scene.materials[scene.meshes[scene.instances[1].meshIndex].materialIndex];
    ASSERT_EQ(dither.baseColorTexture, 0);
    EXPECT_EQ(dither.baseColorFactor.a, 0.5f);
    EXPECT_EQ(scene.textures[0].sampler.magFilter, TextureFilter::Nearest);
    EXPECT_EQ(scene.textures[0].rgba.pixels[3], 200);
}

TEST(CasterBuffers, AnIndexOutsideTheStreamsIsRefused) {
    TwoQuads quads;
    quads.casters.meshes[1].vertexOffset = 5;  // index 3 + 5 = vertex 8 of 8
    EXPECT_EQ(sceneError(quads), "caster mesh 1: an index names vertex 8, outside the 8 vertices of the streams");
}

TEST(CasterBuffers, AMeshOutsideTheIndexBufferIsRefused) {
    TwoQuads quads;
    quads.casters.meshes[1].firstIndex = 9;
    EXPECT_EQ(sceneError(quads), "caster mesh 1: indices 9 + 6 run past indexCount 12");
}

TEST(CasterBuffers, AnAlphaTextureWithoutTextureCoordinatesIsRefused) {
    TwoQuads quads;
    CasterTexture texture{kSomeBuffer, 37, 1, 1, 5, {}};
    quads.casters.alphaTextures.push_back(texture);
    quads.contents.alphaTextures.push_back(Image(1, 1, 4));
    quads.casters.instances[3].alphaTexture = 0;
    quads.casters.instances[3].name = "fern";
    quads.casters.vkUvBuffer = 0;
    quads.contents.uvs.clear();
    EXPECT_EQ(sceneError(quads), "caster instance 3 'fern': an alphaTexture needs texture coordinates (vkUvBuffer)");
}

TEST(CasterBuffers, UnreadableDescriptionsNameTheirField) {
    CasterBuffers casters = TwoQuads().casters;
    casters.positionStride = 10;
    EXPECT_EQ(penumbra::testing::errorMessage([&] { validateCasterBuffers(casters); }),
              "caster buffers: positionStride must be a multiple of 4 of at least 12 and positionOffset a multiple of 4, got 10 and 0");
    casters = TwoQuads().casters;
    casters.instances[0].mesh = 7;
    EXPECT_EQ(penumbra::testing::errorMessage([&] { validateCasterBuffers(casters); }), "caster instance 0: mesh 7 of 2");
    casters = TwoQuads().casters;
    casters.alphaTextures.push_back({kSomeBuffer, 100, 4, 4, 5, {}});
    EXPECT_EQ(penumbra::testing::errorMessage([&] { validateCasterBuffers(casters); }),
              "caster alpha texture 0: VkFormat 100 is not R8_UNORM, R8G8B8A8_UNORM/_SRGB or B8G8R8A8_UNORM/_SRGB");
    casters = TwoQuads().casters;
    casters.vkIndexBuffer = 0;
    EXPECT_EQ(penumbra::testing::errorMessage([&] { validateCasterBuffers(casters); }),
              "caster buffers: no index buffer (vkIndexBuffer)");
}

}  // namespace

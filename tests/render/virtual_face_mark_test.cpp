// The spot and point lights' virtual page marking on the GPU (render/virtual_face_mark_pass.h) against
// its CPU reference (shadows/virtual_faces.h markVirtualFacePages), on lavapipe with validation: the
// main view's depth of the canonical spot and point light scenes gives the same requested pages.
//
// Tolerance (as for the directional marking, virtual_page_mark_test.cpp): the GPU and C++ round the
// reconstruction in the last bits, so a receiver within a rounding error of a page or mip boundary may
// request the page next to the CPU's. Allowed: at most 0.5 % of the CPU's pages (at least 2) differ, and
// each has a page the other side requested in the same level within one page, or in the same face's
// next finer or coarser mip over the same area.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "compare_test_support.h"
#include "render/virtual_face_mark_pass.h"
#include "render_test_support.h"
#include "shadows/spot_projection.h"
#include "virtual_shadow_test_support.h"

namespace penumbra::test {
namespace {

constexpr VirtualFaceConfig kConfig{.resolution = 2048, .pageSize = 32};  // 64 pages a side, 7 mips
constexpr float kMarginTexels = 2.0f;

// Every spot and point light of the scene as faces: a spot's cone, a point light's six 90 degree faces.
struct SceneFaces {
    std::vector<VirtualFace> faces;
    std::vector<VirtualFaceLight> lights;
};

SceneFaces sceneFaces(const Scene& scene) {
    SceneFaces out;
    for (const Light& light : scene.lights) {
        if (light.type == LightType::Directional) continue;
        const float nearDistance = std::max(light.shadowNearPlane, 0.05f);
        const float farDistance = light.range > 0.0f ? light.range : 50.0f;
        const bool point = light.type == LightType::Point;
        out.lights.push_back({uint32_t(out.faces.size()), point});
        if (point) {
            for (const glm::vec3& direction : pointLightFaceDirections())
                out.faces.push_back(makeVirtualFace(kConfig, light.wsPosition, direction, 1.0f, nearDistance, farDistance,
                                                    kMarginTexels));
        } else {
            const float cone = std::tan(std::min(light.outerConeAngle, kMaxShadowedSpotHalfAngle));
            out.faces.push_back(makeVirtualFace(kConfig, light.wsPosition, light.wsDirection, cone, nearDistance,
                                                farDistance, kMarginTexels));
        }
    }
    return out;
}

bool requested(const std::vector<uint32_t>& words, const VirtualPageTableLayout& layout, uint32_t level, int32_t x, int32_t y) {
    const int32_t side = int32_t(layout.pagesPerSide);
    if (level >= layout.levelCount || x < 0 || y < 0 || x >= side || y >= side) return false;
    const uint32_t bit = gpu_data::virtualPageBit(level, layout.pagesPerSide, uint32_t(x), uint32_t(y));
    return (words[bit / 32] >> (bit % 32)) & 1u;
}

bool hasNeighbour(const std::vector<uint32_t>& other, const VirtualPageTableLayout& layout, uint32_t level, int32_t x, int32_t y) {
    for (int32_t dy = -1; dy <= 1; ++dy)
        for (int32_t dx = -1; dx <= 1; ++dx)
            if (requested(other, layout, level, x + dx, y + dy)) return true;
    const uint32_t faces = layout.levelsPerBucket;
    if (requested(other, layout, level + faces, x >> 1, y >> 1)) return true;  // the next coarser mip
    for (int32_t dy = 0; dy <= 1 && level >= faces; ++dy)
        for (int32_t dx = 0; dx <= 1; ++dx)
            if (requested(other, layout, level - faces, 2 * x + dx, 2 * y + dy)) return true;
    return false;
}

class VirtualFaceMarkTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }

    // Returns the CPU's request count.
    uint32_t expectAgreement(const Scene& scene, float footprintScale) {
        const CameraView view = resolveCameraView(scene, 320, 180);
        const SceneFaces faces = sceneFaces(scene);
        const SceneDepth depth = renderSceneDepth(gpu(), scene, view);
        VirtualFaceMarkPass pass(gpu());
        const std::vector<uint32_t> onGpu =
            pass.markNow(depth.image, view, kConfig, faces.faces, faces.lights, kMarginTexels, footprintScale);
        const std::vector<uint32_t> onCpu =
            markVirtualFacePages(kConfig, faces.faces, faces.lights, view, depth.image, kMarginTexels, footprintScale);
        gpu().destroy(depth.texture);
        const VirtualPageTableLayout layout = virtualFaceTableLayout(kConfig, uint32_t(faces.faces.size()));
        EXPECT_EQ(onGpu.size(), onCpu.size());
        uint32_t cpuPages = 0, differing = 0, unexplained = 0;
        const uint32_t perLevel = layout.pagesPerSide * layout.pagesPerSide;
        for (uint32_t bit = 0; bit < layout.entryCount(); ++bit) {
            const bool g = (onGpu[bit / 32] >> (bit % 32)) & 1u, c = (onCpu[bit / 32] >> (bit % 32)) & 1u;
            cpuPages += c;
            if (g == c) continue;
            ++differing;
            const int32_t x = int32_t(bit % perLevel % layout.pagesPerSide), y = int32_t(bit % perLevel / layout.pagesPerSide);
            if (!hasNeighbour(g ? onCpu : onGpu, layout, bit / perLevel, x, y)) ++unexplained;
        }
        EXPECT_GT(cpuPages, 0u);
        EXPECT_LE(differing, std::max(2u, cpuPages / 200)) << differing << " of " << cpuPages << " pages differ";
        EXPECT_EQ(unexplained, 0u);
        return cpuPages;
    }
};

TEST_F(VirtualFaceMarkTest, TheSpotLightsSceneMarksTheSamePagesAsTheCpuReference) {
    expectAgreement(canonicalScene("spot_lights"), 0.5f);
}

TEST_F(VirtualFaceMarkTest, APointLightInARoomCornerMarksTheSamePagesOfItsFacesAsTheCpuReference) {
    const uint32_t fine = expectAgreement(canonicalScene("room_corner"), 0.5f);
    const uint32_t coarse = expectAgreement(canonicalScene("room_corner"), 4.0f);
    EXPECT_GT(fine, 2 * coarse) << "a larger footprint picks coarser mips: fewer pages";
}

}  // namespace
}  // namespace penumbra::test

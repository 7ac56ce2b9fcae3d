// The spot and point lights' virtual shadow lookup (shadows/virtual_shadow_lookup.h sampleVirtualFace) on
// pages chosen, allocated and drawn by the GPU passes (the faces' marking, the page table of fixed windows,
// the page drawing), against the ray tracer (reference/embree_scene.h): ground points that are clearly
// lit or clearly shadowed (the rays from the point and from 2 cm around it all agree) are classified alike;
// and the GLSL twin (penumbra/shadows/virtual_face_lookup.glsl, through the tests' virtual_face_probe.comp) equals it.
#include <cmath>
#include <cstring>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "penumbra/scene_builder.h"
#include "reference/embree_scene.h"
#include "render/compute_raster_pass.h"
#include "render/gpu_scene.h"
#include "render/virtual_face_mark_pass.h"
#include "render/virtual_page_draw_pass.h"
#include "render/virtual_page_table_pass.h"
#include "render_test_support.h"
#include "shadows/spot_projection.h"
#include "shadows/virtual_shadow_lookup.h"
#include "virtual_face_structs.h"
#include "virtual_shadow_test_support.h"

namespace penumbra::test {
namespace {

constexpr VirtualFaceConfig kConfig{.resolution = 4096, .pageSize = 128};  // 32 pages a side, 6 mips
constexpr uint32_t kPoolSide = 12;                                          // 144 physical pages
constexpr float kMargin = 2.0f;
const glm::vec3 kLight(0.3f, 2.5f, -0.2f);

// A 12 m ground with boxes and a pole around a point light 2.5 m up; every caster opaque.
Scene boxesAroundALight() {
    SceneBuilder builder;
    const uint32_t material = builder.addMaterial(Material{});
    builder.addInstance(builder.addMesh(makePlaneMesh(glm::vec2(12.0f), material)), glm::mat4(1.0f));
    const uint32_t box = builder.addMesh(makeBoxMesh(glm::vec3(0.25f), material));
    for (const glm::vec3& at : {glm::vec3(1.2f, 0.25f, 0.4f), glm::vec3(-1.0f, 0.25f, -1.1f), glm::vec3(0.2f, 0.25f, 1.6f),
                                glm::vec3(2.3f, 0.6f, -1.9f)})
        builder.addInstance(box, glm::translate(glm::mat4(1.0f), at));
    builder.addInstance(builder.addMesh(makeCylinderMesh(0.06f, 1.8f, material)),
                        glm::translate(glm::mat4(1.0f), glm::vec3(-0.4f, 0.0f, 0.9f)));
    Light light;
    light.type = LightType::Point;
    light.wsPosition = kLight;
    builder.addLight(light);
    return builder.build();
}

// 1 when every ray from the point and from 2 cm around it (on the ground) is blocked, 0 when none is, else -1.
int clearShadow(const EmbreeScene& tracer, const glm::vec3& wsReceiver) {
    int blocked = 0, rays = 0;
    for (const glm::vec3& offset : {glm::vec3(0.0f), glm::vec3(0.02f, 0, 0), glm::vec3(-0.02f, 0, 0), glm::vec3(0, 0, 0.02f),
                                    glm::vec3(0, 0, -0.02f)}) {
        const glm::vec3 from = wsReceiver + offset, toLight = kLight - from;
        blocked += tracer.occluded(from, glm::normalize(toLight), 1e-3f, glm::length(toLight) - 1e-3f);
        ++rays;
    }
    return blocked == rays ? 1 : blocked == 0 ? 0 : -1;
}

class VirtualFaceLookupTest : public RenderTest {
protected:
    gpu::Device& gpu() { return gpu::backend(device()); }
};

TEST_F(VirtualFaceLookupTest, GroundPointsAroundAPointLightAreShadowedWhereTheRayTracerSaysSo) {
    const Scene scene = boxesAroundALight();
    std::vector<VirtualFace> faces;
    for (const glm::vec3& direction : pointLightFaceDirections())
        faces.push_back(makeVirtualFace(kConfig, kLight, direction, 1.0f, 0.05f, 20.0f, kMargin));
    const VirtualFaceLight lights[] = {{0, true}};
    // The pages a 320 x 180 view of the ground needs, requested, allocated and drawn on the GPU.
    Camera camera;
    camera.worldFromView = glm::inverse(glm::lookAt(glm::vec3(0.0f, 4.0f, 5.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0)));
    camera.yfov = glm::radians(60.0f);
    const CameraView view = makeCameraView(camera, 320, 180);
    const SceneDepth depth = renderSceneDepth(gpu(), scene, view);
    gpu().destroy(depth.texture);
    VirtualFaceMarkPass mark(gpu());
    const std::vector<uint32_t> words = mark.markNow(depth.image, view, kConfig, faces, lights, kMargin, 1.0f);
    VirtualPageTablePass table(gpu(), virtualFaceTableLayout(kConfig, 6), kPoolSide * kPoolSide, 2);
    table.updateNow(words, glm::vec2(0.0f));
    GpuScene gpuScene(gpu(), scene);
    ComputeRasterPass raster(gpu(), gpuScene);
    VirtualPageDrawPass draw(gpu(), gpuScene, raster, kConfig, kPoolSide);
    std::vector<gpu_data::VirtualFaceData> faceData;
    for (const VirtualFace& face : faces) faceData.push_back(packVirtualFace(face));
    const uint64_t faceBytes = faceData.size() * sizeof(faceData[0]);
    const gpu::BufferHandle faceBuffer = gpu().createBuffer(faceBytes, gpu::kBufferStorage, gpu::MemoryKind::HostVisible,
                                                            faceData.data(), "test faces");
    gpu::CommandList commands = gpu().beginCommands();
    VirtualPageDrawInputs inputs{table.drawList(), table.entriesSlice(), nullptr, true, {}, 0};
    inputs.faces = {faceBuffer, 0, faceBytes};
    inputs.faceCount = 6;
    draw.record(commands, inputs);
    table.recordMarkDrawn(commands);
    gpu().submitAndWait(commands);
    const VirtualPageTableState state = table.readState();
    EXPECT_EQ(state.stats.overflowed, 0u);
    EXPECT_GT(state.stats.allocated, 20u);
    ShadowProbe probe(gpu(), true);
    const std::vector<uint16_t> pool = probe.readPool(draw.poolTexture());
    const gpu_data::VirtualShadowLookupData data = packVirtualFaceLookup(kConfig, 6, kPoolSide);

    // Ground points the view sees, each with its pixel's footprint, lifted 3 cm off the ground (a normal
    // offset of several texels of the mips they read).
    const EmbreeScene tracer(scene);
    std::vector<gpu_data::VirtualShadowProbePoint> probePoints;
    std::vector<VirtualShadowSample> onCpu;
    size_t points = 0, inShadow = 0, wrong = 0, unserved = 0;
    for (uint32_t y = 0; y < view.height; y += 2)
        for (uint32_t x = 0; x < view.width; x += 2) {
            const glm::vec3 ray = wsRayDirection(view, float(x) + 0.5f, float(y) + 0.5f);
            const std::optional<SurfaceHit> hit = tracer.intersectCamera(view.wsPosition, ray, 0.0f, 1e4f);
            if (!hit || hit->wsGeometricNormal.y < 0.99f || hit->wsPosition.y > 0.01f) continue;  // the ground only
            const glm::vec3 receiver = hit->wsPosition + glm::vec3(0.0f, 0.03f, 0.0f);
            const int clear = clearShadow(tracer, receiver);
            if (clear < 0) continue;
            const float vsDepth = -(view.viewFromWorld * glm::vec4(hit->wsPosition, 1.0f)).z;
            const float wsFootprint = wsPixelFootprint(view, vsDepth);
            const VirtualShadowSample s = sampleVirtualFace(data, {state.entries, pool}, faces, lights[0], receiver, wsFootprint);
            probePoints.push_back({receiver, wsFootprint});
            onCpu.push_back(s);
            ++points;
            inShadow += clear == 1;
            unserved += s.level == gpu_data::kVirtualShadowNoLevel;
            wrong += clear == 1 ? s.lit > 0.5f : s.lit < 0.5f;
        }
    std::printf("%zu ground points (%zu shadowed), %zu disagree with the ray tracer, %zu unserved\n", points, inShadow, wrong,
                unserved);
    EXPECT_GT(inShadow, 300u);
    EXPECT_GT(points - inShadow, 3000u);
    EXPECT_EQ(unserved, 0u) << "every marked receiver's page is drawn";
    EXPECT_LE(wrong, points / 200) << "at most 0.5 % disagree";
    // The GLSL lookup (what the lit pass runs) equals its CPU reference at the same points: the same level,
    // the shadow term within 1e-4 (the float rounding of the projection may pick another texel only within
    // a rounding error of a texel edge, where both weights are then near 0 or 1).
    const std::vector<gpu_data::VirtualShadowProbeResult> onGpu =
        probe.runFaces(data, table.entries(), table.entryCount(), draw.poolTexture(), {faceBuffer, 0, faceBytes}, 0, true,
                       probePoints);
    size_t differ = 0;
    for (size_t i = 0; i < onGpu.size(); ++i)
        differ += onGpu[i].level != onCpu[i].level || std::abs(onGpu[i].lit - onCpu[i].lit) > 1e-4f;
    EXPECT_LE(differ, onGpu.size() / 1000) << differ << " of " << onGpu.size() << " points differ";
    gpu().destroy(faceBuffer);
}

}  // namespace
}  // namespace penumbra::test

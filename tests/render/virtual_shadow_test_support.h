#pragma once
// Shared pieces of the virtual shadow map render tests: the demo scene's map configuration, view and light,
// the main view's depth (rendered by the main pass's depth prepass), the lookup's probe
// (virtual_shadow_probe.comp: the lookup at given points from a page table and a pool) and its comparison
// with the CPU reference, and ground points of a scene where the ray tracer's answer is clear.
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "pass_bindings.h"
#include "penumbra/scene.h"
#include "reference/embree_scene.h"
#include "render/frame_data.h"
#include "render/gpu_scene.h"
#include "render/main_pass.h"
#include "render/pass_layouts.h"
#include "render/screen_space_shadow_pass.h"
#include "render/virtual_page_storage.h"
#include "render/virtual_shadow_map.h"
#include "shadows/cascades.h"
#include "shadows/virtual_clipmap.h"
#include "shadows/virtual_page_depth.h"
#include "shadows/virtual_page_marking.h"
#include "shadows/virtual_shadow_lookup.h"
#include "shadows/visible_surfaces.h"
#include "virtual_page_structs.h"
#include "virtual_shadow_structs.h"

namespace penumbra::test {

// Pages of 32 texels, level 0 64 m wide (1.6 cm texels), as the marking tests' scene-scale clipmap; a pool
// of 32 x 32 pages, far more than the view requests.
inline VirtualShadowMapConfig mapConfig() {
    VirtualShadowMapConfig config;
    config.clipmap = {.resolution = 4096, .pageSize = 32, .levelCount = 10, .firstLevelSize = 64.0f};
    config.poolPagesPerSide = 32;
    config.keepFrames = 8;
    return config;
}

// A camera 10 m up and 11 m back from the demo's casters, looking down at them and at the ground their
// shadows fall on (toward -x and +z: the sun stands at +x, -z), out to the horizon at the top.
inline CameraView demoView(uint32_t width = 320, uint32_t height = 180) {
    Camera camera;
    const glm::vec3 eye(-3.0f, 7.0f, 8.0f), target(-1.5f, 0.0f, 1.5f);
    camera.worldFromView = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
    camera.yfov = glm::radians(60.0f);
    camera.zNear = 0.1f;
    return makeCameraView(camera, width, height);
}

// The scene's (first) directional light's direction.
inline glm::vec3 sceneLight(const Scene& scene) {
    for (const Light& light : scene.lights)
        if (light.type == LightType::Directional) return light.wsDirection;
    throw std::runtime_error("the scene has no directional light");
}

// The view's depth, rendered by the main pass's depth prepass (as the visible-surface reduction
// draws it) and read back; `texture` keeps it for marking on the GPU.
struct SceneDepth {
    Image image;
    gpu::TextureHandle texture;
};

inline SceneDepth renderSceneDepth(gpu::Device& gpu, const Scene& scene, const CameraView& view) {
    GpuScene gpuScene(gpu, scene);
    MainPass mainPass(gpu, gpuScene, scene, PipelineWarmup::OnDemand);
    const gpu_data::FrameData frame = cameraFrameData(view);
    const gpu::BufferHandle frameBuffer = gpu.createBuffer(sizeof(frame), gpu::kBufferUniform,
                                                             gpu::MemoryKind::HostVisible, &frame, "test frame");
    SceneDepth depth{Image(view.width, view.height, 4), {}};
    depth.texture = gpu.createTexture({view.width, view.height, gpu::Format::D32Float,
                                         gpu::kTextureDepthTarget | gpu::kTextureSampled, 1, "test depth"});
    const gpu::TextureHandle normals = gpu.createTexture(
        {view.width, view.height, gpu::Format::RGBA16Float, gpu::kTextureColorTarget, 1, "test normals"});
    const gpu::BufferHandle readback = gpu.createBuffer(depth.image.pixels.size(), gpu::kBufferTransferDst,
                                                          gpu::MemoryKind::HostVisible, nullptr, "test depth readback");
    MainPassInputs inputs;
    const auto writes = sceneDescriptorWrites(gpuScene, {frameBuffer, 0, sizeof(frame)}, {});
    inputs.writes.assign(writes.begin(), writes.end());
    MainPass::Target target;
    target.color = normals;
    target.depth = depth.texture;
    target.variant = ScreenSpaceShadowPass::prepassVariant();
    target.width = view.width;
    target.height = view.height;
    gpu::CommandList commands = gpu.beginCommands();
    mainPass.record(commands, scene, view, inputs, target);
    commands.pass("test/depth", {gpu::use(depth.texture, gpu::Usage::TransferRead),
                                 gpu::use(readback, gpu::Usage::TransferWrite)});
    commands.copyTextureToBuffer(depth.texture, readback);
    commands.pass("test/host", {gpu::use(readback, gpu::Usage::HostRead)});
    gpu.submitAndWait(commands);
    std::memcpy(depth.image.pixels.data(), gpu.mappedPointer(readback), depth.image.pixels.size());
    for (gpu::BufferHandle b : {frameBuffer, readback}) gpu.destroy(b);
    gpu.destroy(normals);
    return depth;
}

// Runs virtual_shadow_probe.comp over points, with a table and a pool texture; with faces,
// virtual_face_probe.comp (spot and point light faces' lookup, runFaces).
class ShadowProbe {
public:
    explicit ShadowProbe(gpu::Device& gpu, bool faces = false) : gpu_(gpu) {
        gpu::ComputePipelineDesc desc;
        desc.shader = desc.debugName = faces ? "virtual_face_probe.comp" : "virtual_shadow_probe.comp";
        desc.bindings = virtualShadowProbeBindings(faces);
        desc.pushConstantSize = sizeof(gpu_data::VirtualShadowProbeConstants);
        pipeline_ = gpu.createComputePipeline(desc);
        gpu::SamplerDesc nearest;
        nearest.filter = gpu::Filter::Nearest;
        nearest.addressMode = gpu::AddressMode::ClampToEdge;
        sampler_ = gpu.createSampler(nearest);
    }
    ~ShadowProbe() {
        gpu_.destroy(pipeline_);
        gpu_.destroy(sampler_);
    }
    ShadowProbe(const ShadowProbe&) = delete;
    ShadowProbe& operator=(const ShadowProbe&) = delete;

    // The lookup with a table the CPU wrote.
    std::vector<gpu_data::VirtualShadowProbeResult> run(const gpu_data::VirtualShadowLookupData& data,
                                                        const std::vector<gpu_data::VirtualPageEntry>& entries,
                                                        gpu::TextureHandle pool,
                                                        const std::vector<gpu_data::VirtualShadowProbePoint>& points) {
        const gpu::BufferHandle table = gpu_.createBuffer(entries.size() * sizeof(entries[0]), gpu::kBufferStorage,
                                                          gpu::MemoryKind::HostVisible, entries.data(), "probe entries");
        std::vector<gpu_data::VirtualShadowProbeResult> results = run(data, table, uint32_t(entries.size()), pool, points);
        gpu_.destroy(table);
        return results;
    }

    // The lookup with a table on the GPU (`entryCount` VirtualPageEntries, e.g. the page table pass's).
    std::vector<gpu_data::VirtualShadowProbeResult> run(const gpu_data::VirtualShadowLookupData& data, gpu::BufferHandle table,
                                                        uint32_t entryCount, gpu::TextureHandle pool,
                                                        const std::vector<gpu_data::VirtualShadowProbePoint>& points) {
        return run(data, table, pool, points, {}, {uint32_t(points.size()), entryCount, 0, 0});
    }

    // The faces' lookup (a probe made with faces) of the light whose faces start at firstFace (six when
    // `point`), faces: the table's VirtualFaceData.
    std::vector<gpu_data::VirtualShadowProbeResult> runFaces(const gpu_data::VirtualShadowLookupData& data,
                                                             gpu::BufferHandle table, uint32_t entryCount,
                                                             gpu::TextureHandle pool, gpu::BufferSlice faces,
                                                             uint32_t firstFace, bool point,
                                                             const std::vector<gpu_data::VirtualShadowProbePoint>& points) {
        return run(data, table, pool, points, faces, {uint32_t(points.size()), entryCount, firstFace, point ? 1u : 0u});
    }

private:
    std::vector<gpu_data::VirtualShadowProbeResult> run(const gpu_data::VirtualShadowLookupData& data, gpu::BufferHandle table,
                                                        gpu::TextureHandle pool,
                                                        const std::vector<gpu_data::VirtualShadowProbePoint>& points,
                                                        gpu::BufferSlice faces,
                                                        const gpu_data::VirtualShadowProbeConstants& constants) {
        using gpu::Usage;
        using namespace gpu_data;
        const auto hostBuffer = [&](uint32_t usage, const void* bytes, size_t size, const char* name) {
            return gpu_.createBuffer(size, usage, gpu::MemoryKind::HostVisible, bytes, name);
        };
        const gpu::BufferHandle lookup = hostBuffer(gpu::kBufferUniform, &data, sizeof(data), "probe lookup");
        const gpu::BufferHandle input = hostBuffer(gpu::kBufferStorage, points.data(), points.size() * sizeof(points[0]), "probe points");
        const gpu::BufferHandle output =
            hostBuffer(gpu::kBufferStorage, nullptr, points.size() * sizeof(VirtualShadowProbeResult), "probe results");
        gpu::CommandList commands = gpu_.beginCommands();
        commands.pass("test/probe", {gpu::use(pool, Usage::ComputeSampled), gpu::use(table, Usage::ComputeRead),
                                     gpu::use(input, Usage::ComputeRead), gpu::use(output, Usage::ComputeWrite)});
        commands.bindPipeline(pipeline_);
        const gpu::DescriptorWrite writes[] = {{kShadowProbeBindingLookup, {lookup, 0, sizeof(data)}},
                                               {kShadowProbeBindingEntries, table, {}, {}},
                                               {kShadowProbeBindingPool, {}, pool, sampler_},
                                               {kShadowProbeBindingPoints, input, {}, {}},
                                               {kShadowProbeBindingResults, output, {}, {}},
                                               {kShadowProbeBindingFaces, faces}};
        commands.pushDescriptors(std::span(writes, faces.buffer ? 6 : 5));
        commands.pushConstants(&constants, sizeof(constants));
        commands.dispatch((uint32_t(points.size()) + kVirtualShadowProbeGroup - 1) / kVirtualShadowProbeGroup, 1);
        commands.pass("test/host", {gpu::use(output, Usage::HostRead)});
        gpu_.submitAndWait(commands);
        std::vector<VirtualShadowProbeResult> results(points.size());
        std::memcpy(results.data(), gpu_.mappedPointer(output), results.size() * sizeof(results[0]));
        for (gpu::BufferHandle b : {lookup, input, output}) gpu_.destroy(b);
        return results;
    }

public:
    // A pool texture of side x side texels of `codes` (shadows/virtual_page_depth.h), row by row, in the
    // device's pool format (render/virtual_page_storage.h virtualPoolFormat).
    gpu::TextureHandle uploadPool(const std::vector<uint16_t>& codes, uint32_t side) {
        const gpu::Format format = virtualPoolFormat(gpu_);
        const std::vector<uint8_t> bytes = virtualPoolTexelBytes(codes, virtualPoolBytesPerTexel(format));
        const gpu::BufferHandle staging = gpu_.createBuffer(bytes.size(), gpu::kBufferTransferSrc, gpu::MemoryKind::HostVisible,
                                                            bytes.data(), "probe pool upload");
        const gpu::TextureHandle texture =
            gpu_.createTexture({side, side, format, gpu::kTextureSampled | gpu::kTextureTransferDst, 1, "probe pool"});
        gpu::CommandList commands = gpu_.beginCommands();
        commands.pass("test/upload", {gpu::use(staging, gpu::Usage::TransferRead), gpu::discard(texture, gpu::Usage::TransferWrite)});
        commands.copyBufferToTexture(staging, texture);
        gpu_.submitAndWait(commands);
        gpu_.destroy(staging);
        return texture;
    }

    // The pool texture's depth codes, row by row (from either pool format), through a buffer that
    // Device::readBuffer reads back.
    std::vector<uint16_t> readPool(gpu::TextureHandle texture) {
        const gpu::TextureDesc& desc = gpu_.textureDesc(texture);
        const uint32_t texelBytes = virtualPoolBytesPerTexel(desc.format);
        const gpu::BufferHandle copy = gpu_.createBuffer(size_t(desc.width) * desc.height * texelBytes,
                                                         gpu::kBufferTransferDst | gpu::kBufferTransferSrc,
                                                         gpu::MemoryKind::DeviceLocal, nullptr, "probe pool copy");
        gpu::CommandList commands = gpu_.beginCommands();
        commands.pass("test/pool", {gpu::use(texture, gpu::Usage::TransferRead), gpu::use(copy, gpu::Usage::TransferWrite)});
        commands.copyTextureToBuffer(texture, copy);
        gpu_.submitAndWait(commands);
        const std::vector<uint8_t> bytes = gpu_.readBuffer(copy);
        gpu_.destroy(copy);
        return virtualPoolCodesOfBytes(bytes, texelBytes);
    }

private:
    gpu::Device& gpu_;
    gpu::PipelineHandle pipeline_;
    gpu::SamplerHandle sampler_;
};

// The GPU lookup against its CPU reference (tolerances: tests/render/virtual_shadow_lookup_test.cpp's header).
// Whether the CPU's and the GPU's float rounding may legitimately pick another texel or level at a point.
inline bool nearAnEdge(const gpu_data::VirtualShadowLookupData& data, const glm::vec3& wsPosition, float footprint, int servedLevel) {
    const glm::vec2 texel0 = glm::vec2(data.lightRotationFromWorld * glm::vec4(wsPosition, 1.0f)) * data.texelsPerMetre;
    const int first = int(levelForFootprint({data.resolution, data.pageSize, data.levelCount, data.firstLevelSize}, footprint));
    const int last = servedLevel < 0 ? int(data.levelCount) - 1 : servedLevel;
    for (int level = first; level <= last; ++level)
        for (int axis = 0; axis < 2; ++axis) {
            const float t = std::ldexp(texel0[axis], -level);
            if (std::abs(t - std::round(t)) < 1e-3f) return true;
        }
    const double ratio = std::log2(double(footprint) * data.resolution / data.firstLevelSize);
    return std::abs(ratio - std::round(ratio)) < 2e-5;
}

// What a comparison of the GPU with the CPU found.
struct Agreement {
    size_t differ = 0, nearEdges = 0, fractional = 0, fellBack = 0, unserved = 0;
    std::vector<size_t> perLevel = std::vector<size_t>(gpu_data::kVirtualPageMaxLevels, 0);
};

inline Agreement compareWithCpu(const gpu_data::VirtualShadowLookupData& data, const VirtualShadowPages& pages,
                                const std::vector<gpu_data::VirtualShadowProbePoint>& points,
                                const std::vector<gpu_data::VirtualShadowProbeResult>& gpu) {
    Agreement a;
    const VirtualClipmapConfig config{data.resolution, data.pageSize, data.levelCount, data.firstLevelSize};
    for (size_t i = 0; i < points.size(); ++i) {
        const VirtualShadowSample cpu = sampleVirtualShadow(data, pages, points[i].wsPosition, points[i].wsFootprint);
        const bool agree = std::abs(cpu.lit - gpu[i].lit) <= 1e-4f && cpu.level == gpu[i].level;
        const bool edge = nearAnEdge(data, points[i].wsPosition, points[i].wsFootprint, cpu.level);
        a.nearEdges += edge;
        if (!agree && !edge) {
            if (a.differ < 10)
                ADD_FAILURE() << "point " << i << ": GPU " << gpu[i].lit << " at level " << gpu[i].level << ", CPU " << cpu.lit
                              << " at level " << cpu.level;
            ++a.differ;
        }
        a.fractional += cpu.lit > 0.0f && cpu.lit < 1.0f;
        if (cpu.level < 0) {
            ++a.unserved;
            continue;
        }
        ++a.perLevel[size_t(cpu.level)];
        a.fellBack += uint32_t(cpu.level) > levelForFootprint(config, points[i].wsFootprint);
    }
    return a;
}

// The light-space bounds of a scene's casters whose material does not cast opaque shadows (alpha-clipped,
// dithered: the ray tracer and the rasterizer cut them differently).
inline Aabb notOpaqueCasterBounds(const Scene& scene, const glm::mat4& rotation) {
    Aabb bounds;
    for (const Instance& instance : scene.instances) {
        const Material& material = scene.materials[scene.meshes[instance.meshIndex].materialIndex];
        if (instance.castShadows && instance.wsBounds.valid() && material.shadows != MaterialShadowMode::On)
            bounds.extend(instance.wsBounds.transformed(rotation));
    }
    return bounds;
}

inline bool insideXy(const Aabb& box, const glm::vec2& p, float margin) {
    return box.valid() && p.x >= box.min.x - margin && p.x <= box.max.x + margin && p.y >= box.min.y - margin &&
           p.y <= box.max.y + margin;
}

// The ray tracer's answer at a hit on horizontal ground where it is clear: 1 shadowed when the ray toward
// the light (travelling along wsLight) is blocked there and `radius` metres around, 0 lit when blocked
// nowhere there, -1 otherwise.
inline int clearShadowAt(const EmbreeScene& tracer, const SurfaceHit& hit, const glm::vec3& wsLight, float radius = 0.1f) {
    int blocked = 0;
    for (const glm::vec2 d : {glm::vec2(0), glm::vec2(radius, 0), glm::vec2(-radius, 0), glm::vec2(0, radius), glm::vec2(0, -radius)})
        blocked += tracer.occluded(hit.wsPosition + 0.001f * hit.wsGeometricNormal + glm::vec3(d.x, 0.0f, d.y), -wsLight, 0.0f, 1e4f);
    return blocked == 0 ? 0 : blocked == 5 ? 1 : -1;
}

// Ground points of a scene (what a camera from above sees of the instance named "ground") whose
// light-space xy (lightRotation) lies in lsDrawn, lifted 3 cm along the normal (the caller's normal
// bias), with the ray tracer's clear answer (clearShadowAt) and a footprint of 2 cm; points near
// alpha-clipped or dithered casters are left out (by their bounds in the cascades' light space, whose
// axes follow the world's: the tightest boxes around the demo's world-aligned casters).
inline void clearGroundPoints(const Scene& scene, const glm::mat4& lightRotation, const glm::vec3& wsLight, const Aabb& lsDrawn,
                              std::vector<gpu_data::VirtualShadowProbePoint>& points, std::vector<bool>& shadowed) {
    const EmbreeScene tracer(scene);
    const glm::mat4 castersRotation = lightRotationFromWorld(wsLight);
    const Aabb notOpaque = notOpaqueCasterBounds(scene, castersRotation);
    const float step = 0.173f, half = 12.0f;
    for (float z = -half; z <= half; z += step)
        for (float x = -half; x <= half; x += step) {
            const std::optional<SurfaceHit> hit = tracer.intersectCamera({x, scene.wsBounds.max.y + 1.0f, z}, {0, -1, 0}, 0.0f, 1e4f);
            if (!hit || scene.instances[hit->instanceIndex].nodeName != "ground") continue;
            const glm::vec3 receiver = hit->wsPosition + 0.03f * hit->wsGeometricNormal;
            const glm::vec2 ls(lightRotation * glm::vec4(receiver, 1.0f));
            if (!insideXy(lsDrawn, ls, -0.1f) || insideXy(notOpaque, glm::vec2(castersRotation * glm::vec4(receiver, 1.0f)), 0.2f))
                continue;
            const int clear = clearShadowAt(tracer, *hit, wsLight);
            if (clear < 0) continue;
            points.push_back({receiver, 0.02f});
            shadowed.push_back(clear == 1);
        }
}

// The ground the view sees, one point every `stride` pixels (the ray through the pixel's centre), with the
// pixel's world footprint there (wsPixelFootprint): what a lit pass looks up. Lifted along the normal by
// 3 cm and 1.5 footprints, a normal bias of at least 1.5 texels of the level the footprint picks (whose
// texels are no larger than it): for a light 40 degrees off the normal the 2 x 2 compare's texels lie up
// to 1.2 texels of depth below the receiver's plane, and the offset keeps 1.3 times its length. With the
// ray tracer's answer where it is clear over the offset and the compare's reach (clearShadowAt's radius);
// points near alpha-clipped or dithered casters left out.
inline void clearViewGroundPoints(const Scene& scene, const CameraView& view, const glm::mat4& lightRotation,
                                  const glm::vec3& wsLight, uint32_t stride,
                                  std::vector<gpu_data::VirtualShadowProbePoint>& points, std::vector<bool>& shadowed) {
    const EmbreeScene tracer(scene);
    const Aabb notOpaque = notOpaqueCasterBounds(scene, lightRotation);
    const glm::mat4 worldFromClip = glm::inverse(view.clipFromWorld);
    const glm::vec3 wsEye(glm::inverse(view.viewFromWorld)[3]);
    for (uint32_t y = stride / 2; y < view.height; y += stride)
        for (uint32_t x = stride / 2; x < view.width; x += stride) {
            const glm::vec3 wsOnRay = wsPositionFromDepth(worldFromClip, view, float(x) + 0.5f, float(y) + 0.5f, 0.5f);
            const std::optional<SurfaceHit> hit = tracer.intersectCamera(wsEye, glm::normalize(wsOnRay - wsEye), 0.0f, 1e4f);
            if (!hit || scene.instances[hit->instanceIndex].nodeName != "ground") continue;
            const float vsDepth = -(view.viewFromWorld * glm::vec4(hit->wsPosition, 1.0f)).z;
            const float footprint = wsPixelFootprint(view, vsDepth), offset = 0.03f + 1.5f * footprint;
            const glm::vec3 receiver = hit->wsPosition + offset * hit->wsGeometricNormal;
            if (insideXy(notOpaque, glm::vec2(lightRotation * glm::vec4(receiver, 1.0f)), 0.2f)) continue;
            const int clear = clearShadowAt(tracer, *hit, wsLight, 0.1f + offset + 2.0f * footprint);
            if (clear < 0) continue;
            points.push_back({receiver, footprint});
            shadowed.push_back(clear == 1);
        }
}

}  // namespace penumbra::test

#include "penumbra/reference.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include "core/error.h"
#include "reference/area_light.h"
#include "reference/embree_scene.h"

namespace penumbra {
namespace {

constexpr float kMinNDotL = 0.1f;
constexpr float kCreaseCos = 0.9f;
constexpr float kDepthStepFootprints = 2.0f;
// Shadow-ray origin offset along the geometric normal: a few float ulps of the hit point's coordinates
// (and of the scene's size, for points near the origin), enough to leave the surface, far below any
// shadow feature. It used to be 1e-4 of the scene's size: 6 cm on a 600 m ground, which shrank shadows.
constexpr float kOffsetScale = 1e-6f;
constexpr float kOffsetPerCoordinate = 8e-6f;

// What the first pass learns about a pixel; the second pass turns it into validity.
struct PixelSample {
    bool hit = false;
    bool surfaceValid = false;  // passes the per-pixel tests (N·L, cone, range, distance)
    uint32_t instance = 0;
    glm::vec3 wsPosition{0.0f};
    glm::vec3 wsNormal{0.0f};  // geometric, turned to face the camera
    float viewDepth = 0.0f;
};

const Light& shadowedLight(const Scene& scene, uint32_t lightIndex) {
    if (lightIndex >= scene.lights.size())
        throw Error("light " + std::to_string(lightIndex) + " does not exist (the scene has " +
                    std::to_string(scene.lights.size()) + " lights)");
    const Light& light = scene.lights[lightIndex];
    if (light.shadows == LightShadows::None || !(light.shadowStrength > 0.0f))
        throw Error("light " + std::to_string(lightIndex) + " '" + light.name + "' casts no shadows");
    return light;
}

// Strength fades linearly to 0 over the last `distanceFade` of maxShadowDistance, in view depth (as the
// lit pass: Catlike Coding "Directional Shadows", Fading Shadows); or (Unity URP's
// GetMainLightShadowFade) in the squared distance to the camera over the same band.
float distanceFadeFactor(float viewDepth, float cameraDistance, const ReferenceOptions& options) {
    if (!std::isfinite(options.maxShadowDistance)) return 1.0f;
    const float fade = std::max(options.distanceFade, 1e-6f);
    if (options.squaredFade) {
        const float start = options.maxShadowDistance * (1.0f - fade);
        const float band = options.maxShadowDistance * options.maxShadowDistance - start * start;
        return 1.0f - std::clamp((cameraDistance * cameraDistance - start * start) / band, 0.0f, 1.0f);
    }
    return std::clamp((1.0f - viewDepth / options.maxShadowDistance) / fade, 0.0f, 1.0f);
}

// The direction towards the light and the shadow ray's length from `wsOrigin`, plus whether the
// point lies inside the light's cone and range.
struct LightRay {
    glm::vec3 wsToLight{0.0f};
    float tFar = std::numeric_limits<float>::infinity();
    bool inside = true;
};

LightRay lightRay(const Light& light, const glm::vec3& wsOrigin, float epsilon) {
    LightRay r;
    if (light.type == LightType::Directional) {
        r.wsToLight = -light.wsDirection;
        return r;
    }
    const glm::vec3 toLight = light.wsPosition - wsOrigin;
    const float distance = glm::length(toLight);
    r.wsToLight = distance > 0.0f ? toLight / distance : -light.wsDirection;
    r.tFar = std::max(distance - epsilon, 0.0f);
    if (light.range > 0.0f && distance > light.range) r.inside = false;
    if (light.type == LightType::Spot && glm::dot(-r.wsToLight, light.wsDirection) < std::cos(light.outerConeAngle))
        r.inside = false;
    return r;
}

class Tracer {
public:
    Tracer(const Scene& scene, const CameraView& view, const Light& light, const ReferenceOptions& options)
        : scene_(scene), view_(view), light_(light), options_(options),
          footprintPerDepth_(2.0f * std::tan(0.5f * view.yfov) / float(view.height)) {
        epsilon_ = kOffsetScale * scene_.sceneScale();
    }

    // First pass: the shadow value and the per-pixel facts of pixel (x, y).
    uint8_t tracePixel(uint32_t x, uint32_t y, PixelSample& sample) const {
        const glm::vec3 dir = wsRayDirection(view_, float(x) + 0.5f, float(y) + 0.5f);
        // Near and far are planes perpendicular to the view axis, as in the rasterizer.
        const float cosForward = glm::dot(dir, view_.wsForward);
        if (cosForward <= 0.0f) return 255;
        const float tNear = view_.zNear / cosForward;
        const float tFar = std::isinf(view_.zFar) ? std::numeric_limits<float>::infinity() : view_.zFar / cosForward;
        const std::optional<SurfaceHit> hit = scene_.intersectCamera(view_.wsPosition, dir, tNear, tFar);
        if (!hit) return 255;

        const float facing = hit->frontFacing ? 1.0f : -1.0f;
        sample.hit = true;
        sample.instance = hit->instanceIndex;
        sample.wsPosition = hit->wsPosition;
        sample.wsNormal = facing * hit->wsGeometricNormal;
        sample.viewDepth = hit->t * cosForward;
        const glm::vec3 wsShadingNormal = facing * hit->wsShadingNormal;

        const glm::vec3 a = glm::abs(hit->wsPosition);
        const float epsilon = std::max(epsilon_, kOffsetPerCoordinate * std::max({a.x, a.y, a.z}));
        const glm::vec3 wsOrigin = hit->wsPosition + sample.wsNormal * epsilon;
        const LightRay toLight = lightRay(light_, wsOrigin, epsilon);
        const float fade = distanceFadeFactor(sample.viewDepth, hit->t, options_);
        sample.surfaceValid = toLight.inside && fade >= 1.0f &&
                              glm::dot(sample.wsNormal, toLight.wsToLight) >= kMinNDotL &&
                              glm::dot(wsShadingNormal, toLight.wsToLight) >= kMinNDotL;

        if (!hit->material->receiveShadows || fade <= 0.0f) return 255;
        const float visibility = options_.softSamples > 0 ? areaVisibility(wsOrigin, epsilon, x, y)
                                 : scene_.occluded(wsOrigin, toLight.wsToLight, 0.0f, toLight.tFar) ? 0.0f : 1.0f;
        const float value = 1.0f - light_.shadowStrength * fade * (1.0f - visibility);
        return uint8_t(std::lround(255.0f * std::clamp(value, 0.0f, 1.0f)));
    }

    // The fraction of softSamples shadow rays to the light's disk that reach it; the spiral turns by a
    // per-pixel angle so that neighbouring pixels don't share its pattern.
    float areaVisibility(const glm::vec3& wsOrigin, float epsilon, uint32_t x, uint32_t y) const {
        const uint32_t n = options_.softSamples;
        const float rotation = 6.2831853f * float((x * 73856093u ^ y * 19349663u) % 1024u) / 1024.0f;
        uint32_t visible = 0;
        for (uint32_t i = 0; i < n; ++i) {
            const AreaLightRay ray = areaLightRay(light_, wsOrigin, vogelDiskSample(i, n, rotation), epsilon);
            visible += scene_.occluded(wsOrigin, ray.wsDirection, 0.0f, ray.tFar) ? 0u : 1u;
        }
        return float(visible) / float(n);
    }

    // Second pass: a surface-valid pixel stays valid unless a neighbour is across a discontinuity.
    bool continuousWithNeighbours(const std::vector<PixelSample>& samples, uint32_t x, uint32_t y) const {
        const PixelSample& s = samples[size_t(y) * view_.width + x];
        const float maxPlaneDistance = kDepthStepFootprints * footprintPerDepth_ * s.viewDepth;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = int(x) + dx, ny = int(y) + dy;
                if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= int(view_.width) || ny >= int(view_.height))
                    continue;
                const PixelSample& n = samples[size_t(ny) * view_.width + size_t(nx)];
                if (!n.hit || n.instance != s.instance) return false;
                if (glm::dot(n.wsNormal, s.wsNormal) < kCreaseCos) return false;
                if (std::abs(glm::dot(n.wsPosition - s.wsPosition, s.wsNormal)) > maxPlaneDistance) return false;
            }
        }
        return true;
    }

private:
    EmbreeScene scene_;
    const CameraView& view_;
    const Light& light_;
    const ReferenceOptions& options_;
    float footprintPerDepth_ = 0.0f;
    float epsilon_ = 0.0f;
};

// Prints "reference: NN%" on stderr as rows complete, only for an interactive terminal, and ends the
// line when the trace ends: finished (at 100 %), cancelled or failed, so the next message starts on a
// line of its own.
class Progress {
public:
    Progress(bool show, uint32_t total) : show_(show && isatty(STDERR_FILENO) == 1), total_(total) {}
    ~Progress() {
        if (show_ && lastPercent_ >= 0) std::fputc('\n', stderr);
    }
    void rowsDone(uint32_t rows) {
        if (!show_) return;
        const uint32_t done = done_.fetch_add(rows) + rows;
        const int percent = int(uint64_t(done) * 100 / std::max(total_, 1u));
        std::lock_guard<std::mutex> lock(mutex_);
        if (percent <= lastPercent_) return;
        lastPercent_ = percent;
        std::fprintf(stderr, "\rreference: %3d%%", percent);
        std::fflush(stderr);
    }

private:
    bool show_;
    uint32_t total_;
    std::atomic<uint32_t> done_{0};
    std::mutex mutex_;
    int lastPercent_ = -1;
};

}  // namespace

ReferenceOptions referenceOptionsFor(const Settings& settings, const CameraView& view, uint32_t softSamples) {
    ReferenceOptions options;
    options.maxShadowDistance = std::min(settings.shadows.maxDistance, view.zFar);
    options.distanceFade = settings.shadows.distanceFade;
    options.squaredFade = settings.shadows.fadeMode == ShadowFadeMode::Squared;
    options.softSamples = softSamples;
    return options;
}

ReferenceImages traceReferenceShadow(const Scene& scene, const CameraView& view, uint32_t lightIndex,
                                     bool showProgress, const ReferenceOptions& options) {
    const Light& light = shadowedLight(scene, lightIndex);
    const Tracer tracer(scene, view, light, options);
    const uint32_t width = view.width, height = view.height;
    ReferenceImages result;
    result.shadow = Image(width, height, 1, 255);
    result.validMask = Image(width, height, 1, 0);
    std::vector<PixelSample> samples(size_t(width) * height);

    Progress progress(showProgress, height);
    auto cancelled = [&] { return options.cancel && options.cancel->load(); };
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height), [&](const tbb::blocked_range<uint32_t>& rows) {
        for (uint32_t y = rows.begin(); y != rows.end() && !cancelled(); ++y) {
            for (uint32_t x = 0; x < width; ++x)
                result.shadow.at(x, y) = tracer.tracePixel(x, y, samples[size_t(y) * width + x]);
        }
        progress.rowsDone(uint32_t(rows.size()));
        if (options.rowsDone) options.rowsDone->fetch_add(uint32_t(rows.size()));
    });
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height), [&](const tbb::blocked_range<uint32_t>& rows) {
        for (uint32_t y = rows.begin(); y != rows.end() && !cancelled(); ++y) {
            for (uint32_t x = 0; x < width; ++x) {
                const PixelSample& s = samples[size_t(y) * width + x];
                if (s.hit && s.surfaceValid && tracer.continuousWithNeighbours(samples, x, y))
                    result.validMask.at(x, y) = 255;
            }
        }
    });
    result.viewDepth.reserve(samples.size());
    for (const PixelSample& s : samples) {
        result.geometryPixels += s.hit ? 1 : 0;
        result.viewDepth.push_back(s.hit ? s.viewDepth : std::numeric_limits<float>::infinity());
    }
    for (uint8_t v : result.validMask.pixels) result.validPixels += v != 0 ? 1 : 0;
    return result;
}

}  // namespace penumbra

// `penumbra reference` and `penumbra compare`: the ray-traced yardstick for the shadow maps.
#include <cmath>
#include <cstdio>
#include <unistd.h>

#include "app/commands.h"
#include "penumbra/device.h"
#include "penumbra/error.h"
#include "penumbra/files.h"
#include "penumbra/reference.h"
#include "penumbra/renderer.h"
#include "penumbra/shadow_compare.h"

namespace penumbra {

int runReferenceCommand(const RenderOptions& options) {
    checkWritable(options.outputPath);
    checkWritable(options.maskPath);
    const Settings userSettings = loadSettings(options);
    const Scene scene = loadSceneFor(options);
    checkLightOption(options, scene);
    const CameraView view = resolveCameraView(scene, options.width, options.height);
    const Settings settings = withSceneDefaults(userSettings, scene, view);
    const ReferenceImages reference =
        traceReferenceShadow(scene, view, options.light, isatty(STDERR_FILENO), referenceOptionsFor(settings, view, options.softSamples));
    writePng(reference.shadow, options.outputPath);
    if (!options.maskPath.empty()) writePng(reference.validMask, options.maskPath);
    std::printf("reference: light %u, %llu of %llu pixels valid for comparison\n", options.light,
                (unsigned long long)reference.validPixels, (unsigned long long)(uint64_t(view.width) * view.height));
    return 0;
}

namespace {

// The shimmer measurement's step: the camera moved 2 cm sideways between two frames.
constexpr float kShimmerStepMetres = 0.02f;

ShimmerMetrics measureShimmer(const Scene& scene, const CameraView& view, const RenderOptions& options,
                              const Settings& settings, Renderer& renderer, const RenderRequest& request,
                              const Image& ours0, const ReferenceImages& reference0) {
    const CameraView moved = translatedCameraView(view, kShimmerStepMetres * wsCameraRight(view));
    const ReferenceImages reference1 =
        traceReferenceShadow(scene, moved, options.light, false, referenceOptionsFor(settings, moved, options.softSamples));
    const RenderResult ours1 = renderer.render(request, settings, moved);
    return compareShimmer(ours0, ours1.image, reference0.shadow, reference1.shadow, reference0.validMask,
                          reference1.validMask);
}

}  // namespace

int runCompareCommand(const RenderOptions& options) {
    checkWritable(options.diffPath);
    const Settings userSettings = loadSettings(options);
    Scene scene = loadSceneFor(options);
    checkLightOption(options, scene);
    const CameraView view = resolveCameraView(scene, options.width, options.height);
    const Settings settings = withSceneDefaults(userSettings, scene, view);
    // Trace first: it validates the light (exists, casts shadows) before the GPU is touched.
    const ReferenceImages reference =
        traceReferenceShadow(scene, view, options.light, isatty(STDERR_FILENO) && !options.json,
                             referenceOptionsFor(settings, view, options.softSamples));
    Device device = openDevice(options);
    Renderer renderer(device, std::move(scene));
    RenderRequest request = makeRenderRequest(options);
    request.output = OutputMode::ShadowAov;
    const RenderResult ours = renderer.render(request, settings, view);
    const CompareMetrics metrics = compareShadowImages(ours.image, reference.shadow, reference.validMask);
    ShimmerMetrics shimmer;
    if (options.shimmer)
        shimmer = measureShimmer(renderer.scene(), view, options, settings, renderer, request, ours.image, reference);
    if (!options.diffPath.empty()) {
        request.output = OutputMode::Color;
        const RenderResult colour = renderer.render(request, settings, view);
        writePng(makeDiffImage(colour.image, ours.image, reference.shadow, reference.validMask), options.diffPath);
    }
    // An explicit empty result rather than a misleading "0 % error" (bad input).
    if (metrics.validPixels == 0)
        std::fprintf(stderr, "penumbra: warning: no pixel is valid for comparison (nothing in view, or no surface "
                             "faces light %u within the shadow distance); the metrics are empty\n", options.light);
    if (options.json)
        std::printf("%s\n", (options.shimmer ? toJson(metrics, shimmer) : toJson(metrics)).c_str());
    else
        std::printf("%s%s", toText(metrics).c_str(), options.shimmer ? toText(shimmer).c_str() : "");  // lines end in \n
    if (options.validation && device.validationMessageCount() > 0)
        throw Error(std::to_string(device.validationMessageCount()) + " Vulkan validation messages (see above)");
    return 0;
}

}  // namespace penumbra

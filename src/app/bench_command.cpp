// `penumbra bench`: renders frame after frame through the persistent frame (frames in flight, no
// readback) and reports GPU time per pass (timestamps), CPU time per phase, the submit-to-fence frame
// time, what each shadow atlas drew, host and device memory at the first and last timed frame, and
// the GPU objects made after warm-up. Numbers, not pass/fail: the instrument behind docs/performance.md.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "app/bench_motion.h"
#include "app/bench_thread.h"
#include "app/bench_variations.h"
#include "app/commands.h"
#include "penumbra/files.h"
#include "penumbra/error.h"
#include "penumbra/device.h"
#include "penumbra/renderer.h"

namespace penumbra {

namespace {

struct Series {
    std::vector<double> values;
    double percentile(double p) const {
        if (values.empty()) return 0.0;
        std::vector<double> sorted = values;
        std::sort(sorted.begin(), sorted.end());
        const size_t index = size_t(std::ceil(p * double(sorted.size()))) - (p > 0.0 ? 1 : 0);
        return sorted[std::min(index, sorted.size() - 1)];
    }
    double median() const { return percentile(0.5); }
    double p95() const { return percentile(0.95); }
    double minimum() const { return values.empty() ? 0.0 : *std::min_element(values.begin(), values.end()); }
};

double hostRssMegabytes() {
    std::ifstream statm("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    statm >> size >> resident;
    return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// --camera orbit: the scene's camera turned about the vertical axis through `pivot`, the scene's
// centre (taken once: --move-objects widens the scene's bounds), a quarter degree more every frame,
// so the shadow plan (cascade spheres, culling) changes every frame.
CameraView benchCamera(const glm::vec3& pivot, const CameraView& start, const std::string& mode, uint64_t frame) {
    if (mode != "orbit") return start;
    const glm::mat4 turn = glm::translate(glm::mat4(1.0f), pivot) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(0.25f * float(frame)), glm::vec3(0, 1, 0)) *
                           glm::translate(glm::mat4(1.0f), -pivot);
    Camera camera;
    camera.worldFromView = turn * start.worldFromView;
    camera.yfov = start.yfov;
    camera.zNear = start.zNear;
    camera.zFar = start.zFar;
    return makeCameraView(camera, start.width, start.height);
}

struct SceneTotals {
    uint64_t triangles = 0;
};

SceneTotals sceneTotals(const Scene& scene) {
    SceneTotals totals;
    for (const Instance& instance : scene.instances) totals.triangles += scene.meshes[instance.meshIndex].indices.size() / 3;
    return totals;
}

// "[####    ] 17/100 frames" on stdout, redrawn in place, only for an interactive terminal. The line
// is erased when the bar goes away, also when a frame throws, so the report or the error message
// that follows starts on a line of its own.
class ProgressBar {
public:
    explicit ProgressBar(uint32_t total) : show_(isatty(STDOUT_FILENO) == 1), total_(std::max(total, 1u)) {}
    ~ProgressBar() {
        if (!drawn_) return;
        std::printf("\r%*s\r", kWidth + 32, "");
        std::fflush(stdout);
    }
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    void update(uint32_t done) {
        if (!show_) return;
        const int filled = int(double(done) / double(total_) * kWidth);
        std::printf("\r[%s%s] %u/%u frames", std::string(size_t(filled), '#').c_str(),
                    std::string(size_t(kWidth - filled), ' ').c_str(), done, total_);
        std::fflush(stdout);
        drawn_ = true;
    }

private:
    static constexpr int kWidth = 40;
    bool show_;
    uint32_t total_;
    bool drawn_ = false;
};

// Virtual shadow map pages per frame: the directional lights' or the spot and point lights' faces'.
struct PageSeries {
    Series requested, cached, allocated, drawn, evicted, overflowed, deferred, resident;
    uint32_t maps = 0, poolPages = 0, pagesPerFrame = 0, lodBiasSteps = 0;  // of the last timed frame
    uint32_t settled = 0;  // frames whose page update was skipped (VirtualPageCounts::settled)
    void add(const VirtualPageCounts& pages) {
        settled += pages.settled ? 1u : 0u;
        requested.values.push_back(pages.requested);
        cached.values.push_back(pages.cached);
        allocated.values.push_back(pages.allocated);
        drawn.values.push_back(pages.drawn);
        evicted.values.push_back(pages.evicted);
        overflowed.values.push_back(pages.overflowed);
        deferred.values.push_back(pages.deferred);
        resident.values.push_back(pages.resident);
        maps = pages.maps;
        poolPages = pages.poolPages;
        pagesPerFrame = pages.pagesPerFrame;
        lodBiasSteps = pages.lodBiasSteps;
    }
    nlohmann::json toJson(const char* mapsKey) const {
        return {{mapsKey, maps},
                {"poolPages", poolPages},
                {"pagesPerFrame", pagesPerFrame},
                {"lodBiasSteps", lodBiasSteps},
                {"settledFrames", settled},
                {"requested", requested.median()},
                {"cached", cached.median()},
                {"allocated", allocated.median()},
                {"drawn", drawn.median()},
                {"drawnMax", drawn.percentile(1.0)},
                {"evicted", evicted.median()},
                {"overflowed", overflowed.percentile(1.0)},
                {"deferred", deferred.percentile(1.0)},
                {"resident", resident.median()}};
    }
    void print(const char* what, const char* maps_) const {
        if (maps == 0) return;
        std::printf("%s per frame (median, %u %s, pool %u pages, at most %u drawn a frame): %.0f requested, %.0f cached, %.0f allocated, "
                    "%.0f drawn (most %.0f), %.0f evicted, %.0f resident; overflowed at most %.0f",
                    what, maps, maps_, poolPages, pagesPerFrame, requested.median(), cached.median(), allocated.median(), drawn.median(),
                    drawn.percentile(1.0), evicted.median(), resident.median(), overflowed.percentile(1.0));
        if (deferred.percentile(1.0) > 0) std::printf("; deferred at most %.0f", deferred.percentile(1.0));
        if (lodBiasSteps > 0) std::printf("; pool pressure: lodBias %u step(s) coarser at the end", lodBiasSteps);
        if (settled > 0) std::printf("; %u of %zu frames settled (page update skipped)", settled, requested.values.size());
        std::printf("\n");
    }
};

struct Measurements {
    std::map<std::string, Series> passes;
    std::map<std::string, Series> cpu;
    Series frame, gpuFrame, gpuPeriod;
    std::vector<AtlasDrawStats> atlases;  // of the last timed frame
    std::string raster, rasterChoice;     // of the last timed frame
    std::string mainView, mainViewChoice;
    uint32_t viewInstances = 0;  // of the last timed frame
    Series viewEarly, viewLate, viewTriangles;
    Series shadowMeshletsOutside, viewMeshletsOutside, viewMeshletsFacingAway;  // render.meshletCulling
    uint64_t rasterSimplified = 0;  // of rasterWork, items of a simplified level
    uint64_t rasterWork = 0, rasterMedium = 0, rasterLarge = 0, rasterChunks = 0, rasterDropped = 0;
    Series tilesRendered, tilesReused;
    PageSeries pages;      // shadows.directional.mode = virtual
    PageSeries facePages;  // shadows.spot.mode = virtual
    double lightsPerClusterMean = 0.0;  // of the last timed frame
    uint32_t lightsPerClusterMax = 0;
    void add(const FrameStats& stats) {
        for (const PassTiming& t : stats.gpuTimings) passes[t.name].values.push_back(t.milliseconds);
        cpu["plan"].values.push_back(stats.cpu.plan);
        cpu["culling"].values.push_back(stats.cpu.culling);
        cpu["upload"].values.push_back(stats.cpu.upload);
        cpu["record"].values.push_back(stats.cpu.record);
        cpu["submit"].values.push_back(stats.cpu.submit);
        cpu["readback"].values.push_back(stats.cpu.readback);
        // The frame's whole CPU cost, whose p95 the steady-frame target bounds (its own series: the p95
        // of a sum is not the sum of the p95s).
        cpu["total"].values.push_back(stats.cpu.plan + stats.cpu.culling + stats.cpu.upload + stats.cpu.record + stats.cpu.submit +
                                     stats.cpu.readback);
        cpu["thread"].values.push_back(stats.cpu.thread);
        frame.values.push_back(stats.submitToFenceMilliseconds);
        gpuFrame.values.push_back(stats.gpuFrameMilliseconds);
        if (stats.gpuFramePeriodMilliseconds > 0.0) gpuPeriod.values.push_back(stats.gpuFramePeriodMilliseconds);
        atlases = stats.atlases;
        tilesRendered.values.push_back(stats.tilesRendered);
        tilesReused.values.push_back(stats.tilesReused);
        pages.add(stats.virtualPages);
        facePages.add(stats.virtualFacePages);
        raster = stats.shadowRaster;
        rasterWork = stats.rasterWorkItems;
        rasterSimplified = stats.rasterSimplifiedItems;
        rasterMedium = stats.rasterMediumTriangles;
        rasterLarge = stats.rasterLargeTriangles;
        rasterChunks = stats.rasterChunks;
        rasterDropped = stats.rasterDropped;
        rasterChoice = stats.shadowRasterChoice;
        mainView = stats.mainView;
        mainViewChoice = stats.mainViewChoice;
        viewInstances = stats.viewInstances;
        viewEarly.values.push_back(stats.viewInstancesEarly);
        viewLate.values.push_back(stats.viewInstancesLate);
        viewTriangles.values.push_back(double(stats.viewTriangles));
        shadowMeshletsOutside.values.push_back(double(stats.shadowMeshletsOutside));
        viewMeshletsOutside.values.push_back(double(stats.viewMeshletsOutside));
        viewMeshletsFacingAway.values.push_back(double(stats.viewMeshletsFacingAway));
        lightsPerClusterMean = stats.lightsPerClusterMean;
        lightsPerClusterMax = stats.lightsPerClusterMax;
    }
};

}  // namespace

namespace {

double deviceMegabytes(const Device& device) { return double(device.deviceMemoryBytes()) / (1024.0 * 1024.0); }

// What the timed frames saw, besides the per-frame measurements.
struct TimedRun {
    Measurements measured;
    std::vector<std::string> warnings;  // of the last frame
    std::vector<MemorySample> samples;  // --vary-settings: one per period
    DeviceObjectCounts before, after;
    double rssFirst = 0.0, rssLast = 0.0, deviceFirst = 0.0, deviceLast = 0.0;
    uint32_t turnedLights = 0, movedInstances = 0;  // --light-motion, --move-objects: every frame
    FrameThreadCpus frameThread{-1};
};

// The frame loops' fixed inputs.
struct FrameLoop {
    const RenderRequest& request;
    const CameraView& start;
    glm::vec3 pivot{0.0f};  // of --camera orbit
    BenchMotion& motion;
};

// Submits frame `frame` (counted from the first warm-up frame): the lights and instances of
// --light-motion and --move-objects set first, then the camera of --camera.
uint64_t submitBenchFrame(Renderer& renderer, const BenchOptions& bench, const FrameLoop& loop, const Settings& settings,
                          uint64_t frame) {
    loop.motion.apply(renderer, frame);
    return renderer.submitFrame(loop.request, settings, benchCamera(loop.pivot, loop.start, bench.camera, frame), nullptr);
}

// The timed frames; with --vary-settings the settings and shadowed lights change every period.
TimedRun runTimedFrames(Device& device, Renderer& renderer, const BenchOptions& bench, const FrameLoop& loop,
                        const Settings& settings, uint64_t& frame) {
    const Scene& scene = renderer.scene();
    const std::vector<Light> originalLights = scene.lights;
    TimedRun run;
    run.frameThread = FrameThreadCpus(bench.pinCpu);
    run.before = device.liveObjects();
    run.rssFirst = hostRssMegabytes();
    run.deviceFirst = deviceMegabytes(device);
    run.turnedLights = loop.motion.turnedLights();
    run.movedInstances = loop.motion.movedInstances();
    Settings current = settings;
    uint32_t step = 0, shadowedLights = 0;
    ProgressBar progress(bench.frames);
    std::vector<FrameStats> finished;
    // The timed frames follow the warm-up without a pause, as an application's frames do: the warm-up
    // frames still in flight finish during the first timed ones and are left out by their index.
    uint64_t firstTimed = UINT64_MAX;
    auto take = [&](const FrameStats& stats) {
        if (stats.frameIndex < firstTimed) return;
        run.measured.add(stats);
        run.warnings = stats.warnings;
    };
    for (uint32_t i = 0; i < bench.frames; ++i) {
        if (bench.varyPeriod > 0 && i % bench.varyPeriod == 0) {
            step = (i / bench.varyPeriod) % uint32_t(benchVariations().size());
            current = variedSettings(settings, benchVariations()[step]);
            shadowedLights = applyShadowedLights(renderer, originalLights, benchVariations()[step].shadowedLightShare);
        }
        const uint64_t submitted = submitBenchFrame(renderer, bench, loop, current, frame++);
        if (i == 0) firstTimed = submitted;
        run.frameThread.observe();
        renderer.takeCompletedFrames(finished);  // exchanges elements with the renderer: no allocation once warm
        for (const FrameStats& stats : finished) take(stats);
        if (bench.varyPeriod > 0 && (i + 1) % bench.varyPeriod == 0)
            run.samples.push_back({i + 1, step, hostRssMegabytes(), deviceMegabytes(device), shadowedLights});
        if (i % 8 == 0 || i + 1 == bench.frames) progress.update(i + 1);
    }
    renderer.waitIdle();
    run.frameThread.unpin();
    for (const FrameStats& stats : renderer.takeCompletedFrames()) take(stats);
    run.rssLast = hostRssMegabytes();
    run.deviceLast = deviceMegabytes(device);
    run.after = device.liveObjects();
    return run;
}

nlohmann::json benchJson(const Device& device, const RenderOptions& options, const BenchOptions& bench,
                         const RenderRequest& request, const Scene& scene, const TimedRun& run) {
    const Measurements& measured = run.measured;
    nlohmann::json json;
    json["device"] = device.info().name;
    json["hostWait"] = options.spinWait ? "spin" : "sleep";
    json["frameThread"] = run.frameThread.json();
    json["driver"] = device.info().driver;
    json["width"] = request.width;
    json["height"] = request.height;
    json["frames"] = bench.frames;
    json["warmup"] = bench.warmup;
    json["camera"] = bench.camera;
    json["lightMotion"] = {{"degreesPerFrame", bench.lightMotion}, {"lights", run.turnedLights}};
    json["moveObjects"] = {{"fraction", bench.moveObjects}, {"moved", run.movedInstances}};
    json["scene"] = {{"source", options.scenePath.empty() ? "demo" : options.scenePath},
                     {"triangles", sceneTotals(scene).triangles},
                     {"instances", scene.instances.size()},
                     {"lights", scene.lights.size()}};
    json["passes"] = nlohmann::json::object();
    for (const auto& [name, series] : measured.passes)
        json["passes"][name] = {{"median_ms", series.median()}, {"p95_ms", series.p95()}, {"min_ms", series.minimum()}};
    json["cpu"] = nlohmann::json::object();
    for (const auto& [name, series] : measured.cpu)
        json["cpu"][name] = {{"median_ms", series.median()}, {"p95_ms", series.p95()}};
    json["frame"] = {{"median_ms", measured.frame.median()}, {"p95_ms", measured.frame.p95()}};
    json["gpuFrame"] = {{"median_ms", measured.gpuFrame.median()}, {"p95_ms", measured.gpuFrame.p95()}};
    json["gpuFramePeriod"] = {{"median_ms", measured.gpuPeriod.median()}, {"p95_ms", measured.gpuPeriod.p95()}};
    json["atlases"] = nlohmann::json::object();
    for (const AtlasDrawStats& atlas : measured.atlases)
        json["atlases"][atlas.pass] = {{"tiles", atlas.tiles}, {"draws", atlas.draws}, {"triangles", atlas.triangles}};
    json["memory"] = {{"host_rss_mb", {{"first", run.rssFirst}, {"last", run.rssLast}}},
                      {"device_mb", {{"first", run.deviceFirst}, {"last", run.deviceLast}}}};
    json["allocationsAfterWarmup"] = {{"gpuObjects", run.after.objectsCreated - run.before.objectsCreated},
                                      {"vkAllocateMemory", run.after.memoryAllocations - run.before.memoryAllocations}};
    json["validationMessages"] = device.validationMessageCount();
    json["tiles"] = {{"rendered", measured.tilesRendered.median()},
                     {"reused", measured.tilesReused.median()},
                     {"renderedMin", measured.tilesRendered.minimum()}};
    json["virtualPages"] = measured.pages.toJson("maps");
    json["virtualFacePages"] = measured.facePages.toJson("faces");
    json["shadowRaster"] = {{"used", measured.raster}, {"choice", measured.rasterChoice},
                            {"workItems", measured.rasterWork}, {"simplifiedItems", measured.rasterSimplified},
                            {"mediumPieces", measured.rasterMedium},
                            {"largePieces", measured.rasterLarge},
                            {"chunks", measured.rasterChunks},
                            {"dropped", measured.rasterDropped}};
    json["lightsPerCluster"] = {{"mean", measured.lightsPerClusterMean}, {"max", measured.lightsPerClusterMax}};
    json["mainView"] = {{"used", measured.mainView},
                        {"choice", measured.mainViewChoice},
                        {"instances", measured.viewInstances},
                        {"drawnEarly", measured.viewEarly.median()},
                        {"drawnLate", measured.viewLate.median()},
                        {"triangles", measured.viewTriangles.median()}};
    json["meshletsSkipped"] = {{"shadowOutside", measured.shadowMeshletsOutside.median()},
                               {"viewOutside", measured.viewMeshletsOutside.median()},
                               {"viewFacingAway", measured.viewMeshletsFacingAway.median()}};
    if (bench.varyPeriod > 0) json["vary"] = variationJson(bench.varyPeriod, run.samples);
    return json;
}

void printReport(const Device& device, const RenderOptions& options, const BenchOptions& bench,
                 const RenderRequest& request, const Scene& scene, const TimedRun& run) {
    const Measurements& measured = run.measured;
    std::printf("device: %s (%s), host wait: %s\n", device.info().name.c_str(), device.info().driver.c_str(),
                options.spinWait ? "spin" : "sleep");
    std::printf("scene: %s, %llu triangles, %zu instances, %zu lights; %ux%u, %u frames after %u warm-up, camera %s",
                options.scenePath.empty() ? "demo" : options.scenePath.c_str(),
                (unsigned long long)sceneTotals(scene).triangles, scene.instances.size(), scene.lights.size(),
                request.width, request.height, bench.frames, bench.warmup, bench.camera.c_str());
    if (bench.lightMotion > 0.0)
        std::printf(", light motion %g deg/frame (%u directional light%s)", bench.lightMotion, run.turnedLights,
                    run.turnedLights == 1 ? "" : "s");
    if (bench.moveObjects > 0.0)
        std::printf(", move objects %g (%u of %zu instances per frame)", bench.moveObjects, run.movedInstances,
                    scene.instances.size());
    std::printf("\n");
    std::printf("%-28s %10s %10s %10s\n", "", "median ms", "p95 ms", "min ms");
    double gpuTotal = 0.0;
    for (const auto& [name, series] : measured.passes) {
        if (name.find('/') == std::string::npos) gpuTotal += series.median();  // "pass/step" is inside "pass"
        std::printf("gpu %-24s %10.4f %10.4f %10.4f\n", name.c_str(), series.median(), series.p95(), series.minimum());
    }
    std::printf("gpu %-24s %10.4f\n", "sum of pass medians", gpuTotal);
    for (const auto& [name, series] : measured.cpu)
        std::printf("cpu %-24s %10.4f %10.4f\n", name.c_str(), series.median(), series.p95());
    std::printf("frame (submit to fence)      %10.4f %10.4f\n", measured.frame.median(), measured.frame.p95());
    std::printf("frame (GPU, first to last)   %10.4f %10.4f\n", measured.gpuFrame.median(), measured.gpuFrame.p95());
    std::printf("frame period (GPU end to end)%10.4f %10.4f\n", measured.gpuPeriod.median(), measured.gpuPeriod.p95());
    for (const AtlasDrawStats& atlas : measured.atlases)
        std::printf("%-20s %u tiles, %u draws, %llu triangles\n", atlas.pass.c_str(), atlas.tiles, atlas.draws,
                    (unsigned long long)atlas.triangles);
    std::printf("shadow raster: %s (%s), %llu work items (%llu simplified), %llu medium pieces, %llu large pieces in %llu chunks, %llu dropped\n",
                measured.raster.c_str(), measured.rasterChoice.c_str(), (unsigned long long)measured.rasterWork,
                (unsigned long long)measured.rasterSimplified,
                (unsigned long long)measured.rasterMedium, (unsigned long long)measured.rasterLarge,
                (unsigned long long)measured.rasterChunks, (unsigned long long)measured.rasterDropped);
    std::printf("main view: %s (%s)\n", measured.mainView.c_str(), measured.mainViewChoice.c_str());
    if (measured.mainView == "visibility")
        std::printf("main view culling (median): %.0f early + %.0f late of %u instances, %.0f triangles\n",
                    measured.viewEarly.median(), measured.viewLate.median(), measured.viewInstances,
                    measured.viewTriangles.median());
    std::printf("meshlets skipped (median): shadows %.0f outside their tile; main view %.0f outside, %.0f facing away\n",
                measured.shadowMeshletsOutside.median(), measured.viewMeshletsOutside.median(),
                measured.viewMeshletsFacingAway.median());
    std::printf("shadow tiles per frame (median): %.0f rendered, %.0f reused\n", measured.tilesRendered.median(),
                measured.tilesReused.median());
    measured.pages.print("virtual pages", "maps");
    measured.facePages.print("virtual face pages", "faces");
    std::printf("spot/point lights per cluster: %.2f mean, %u most\n", measured.lightsPerClusterMean,
                measured.lightsPerClusterMax);
    std::printf("host RSS %.1f -> %.1f MB, device memory %.1f -> %.1f MB\n", run.rssFirst, run.rssLast, run.deviceFirst,
                run.deviceLast);
    std::printf("%s\n", run.frameThread.summary().c_str());
    const uint64_t made = run.after.objectsCreated - run.before.objectsCreated;
    std::printf("after warm-up: %llu GPU objects made (%llu pipelines compiled, %llu reused; last \"%s\"), "
                "%llu vkAllocateMemory calls\n",
                (unsigned long long)made, (unsigned long long)(run.after.pipelinesCompiled - run.before.pipelinesCompiled),
                (unsigned long long)(run.after.pipelinesReused - run.before.pipelinesReused),
                made > 0 ? run.after.lastObjectName.data() : "",
                (unsigned long long)(run.after.memoryAllocations - run.before.memoryAllocations));
    if (bench.varyPeriod > 0 && !run.samples.empty()) {
        const nlohmann::json vary = variationJson(bench.varyPeriod, run.samples);
        std::printf("vary-settings: %zu periods of %u frames over %zu steps; host RSS %.1f first, %.1f last, %.1f max, "
                    "+%.1f growth MB; device %.1f first, %.1f last, %.1f max, +%.1f growth MB\n",
                    run.samples.size(), bench.varyPeriod, benchVariations().size(),
                    vary["host_rss_mb"]["first"].get<double>(), vary["host_rss_mb"]["last"].get<double>(),
                    vary["host_rss_mb"]["max"].get<double>(), vary["host_rss_mb"]["growth"].get<double>(),
                    vary["device_mb"]["first"].get<double>(), vary["device_mb"]["last"].get<double>(),
                    vary["device_mb"]["max"].get<double>(), vary["device_mb"]["growth"].get<double>());
    }
    std::printf("validation messages: %u\n", device.validationMessageCount());
}

// One row per timed frame, in order: what the medians and p95s summarize, for a plot of a run or a look
// at its slowest frames.
std::string frameTimesCsv(const Measurements& measured) {
    static const char* const kPhases[] = {"plan", "culling", "upload", "record", "submit", "readback", "total", "thread"};
    std::string csv = "frame,gpuFrameMs,submitToFenceMs";
    for (const char* phase : kPhases) csv += std::string(",cpu_") + phase + "Ms";
    csv += "\n";
    char cell[32];
    for (size_t i = 0; i < measured.gpuFrame.values.size(); ++i) {
        csv += std::to_string(i);
        std::snprintf(cell, sizeof(cell), ",%.4f,%.4f", measured.gpuFrame.values[i], measured.frame.values[i]);
        csv += cell;
        for (const char* phase : kPhases) {
            std::snprintf(cell, sizeof(cell), ",%.4f", measured.cpu.at(phase).values[i]);
            csv += cell;
        }
        csv += "\n";
    }
    return csv;
}

}  // namespace

int runBenchCommand(const RenderOptions& options, const BenchOptions& bench) {
    checkWritable(bench.jsonPath);
    if (bench.frameTimesPath != "-") checkWritable(bench.frameTimesPath);
    checkPinCpu(bench.pinCpu);
    const Settings userSettings = loadSettings(options);
    Device device = openDevice(options);
    // The warm-up frames build the pipelines that fixed settings need (on demand); --vary-settings
    // reaches every lit-pass variant, so on a GPU those are all built first, on the worker thread. A CPU
    // device builds on demand: its frames wait for their own variant anyway, and a background build
    // would take the cores that draw.
    const bool warmAllVariants = bench.varyPeriod > 0 && !device.info().isCpu;
    RendererOptions rendererOptions;
    rendererOptions.warmup = warmAllVariants ? PipelineWarmup::Background : PipelineWarmup::OnDemand;
    Renderer renderer(device, loadSceneFor(options), rendererOptions);
    const Scene& scene = renderer.scene();
    RenderRequest request = makeRenderRequest(options);
    request.readback = false;
    const CameraView start = resolveCameraView(scene, request.width, request.height);
    const Settings settings = withSceneDefaults(userSettings, scene, start);
    BenchMotion motion(scene, bench.lightMotion, bench.moveObjects);
    const FrameLoop loop{request, start, scene.wsBounds.valid() ? scene.wsBounds.center() : glm::vec3(0.0f), motion};

    uint64_t frame = 0;
    for (uint32_t i = 0; i < bench.warmup; ++i) submitBenchFrame(renderer, bench, loop, settings, frame++);
    if (warmAllVariants) {  // the timed frames use the specialized variants
        renderer.buildAllPipelines();
        renderer.waitIdle();
    }
    renderer.takeCompletedFrames();
    const TimedRun run = runTimedFrames(device, renderer, bench, loop, settings, frame);
    for (const std::string& warning : run.warnings) std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    printReport(device, options, bench, request, scene, run);
    if (!bench.jsonPath.empty()) {
        const std::string json = benchJson(device, options, bench, request, scene, run).dump(2);
        if (bench.jsonPath == "-") std::printf("%s\n", json.c_str());
        else writeTextFile(bench.jsonPath, json + "\n");
    }
    if (bench.frameTimesPath == "-") std::printf("%s", frameTimesCsv(run.measured).c_str());
    else if (!bench.frameTimesPath.empty()) writeTextFile(bench.frameTimesPath, frameTimesCsv(run.measured));
    if (options.validation && device.validationMessageCount() > 0)
        throw Error(std::to_string(device.validationMessageCount()) + " Vulkan validation messages (see above)");
    return 0;
}

}  // namespace penumbra

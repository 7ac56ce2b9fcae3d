#include "app/cli.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "penumbra/error.h"
#include "penumbra/version.h"

namespace penumbra {

namespace {

// The one line a failure prints, whatever the message holds (a path or a driver's text may contain
// a line break).
void printError(const std::string& prefix, const char* message) {
    std::string line = message;
    for (char& c : line)
        if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "penumbra: %s%s\n", prefix.c_str(), line.c_str());
}

constexpr const char* kGroundHelp = "add a grey ground plane under the scene (4x its width, at its lowest point)";

// Options every command that loads a scene shares: where its files may come from, what it may cost
// (docs/security.md).
void addSceneFileOptions(CLI::App& command, RenderOptions& options) {
    command.add_option("--asset-root", options.assetRoot,
                       "folder the scene's external buffers and images may come from (default: the scene file's folder)");
    command.add_option("--limit", options.limits,
                       "raise or lower a scene budget, NAME=VALUE with an optional K/M/G: fileBytes, imageBytes, "
                       "textureBytes, vertices, indices, nodes, nodeDepth, lights, jsonDepth (docs/security.md)");
}

// Options every command that renders shares.
void addRenderOptions(CLI::App& command, RenderOptions& options) {
    command.add_option("scene", options.scenePath,
                       "glTF 2.0 scene (.gltf or .glb), gen:field:N[:S[:P]] or gen:boxes:N[:P]; the built-in demo scene if omitted");
    command.add_option("--model", options.model, "the glTF that gen:field copies (default: assimp's 2CylinderEngine)");
    command.add_flag("--ground", options.ground, kGroundHelp);
    addSceneFileOptions(command, options);
    command.add_option("--width", options.width, "output width in pixels")->check(CLI::Range(1u, 16384u));
    command.add_option("--height", options.height, "output height in pixels")->check(CLI::Range(1u, 16384u));
    command.add_option("--settings", options.settingsPath, "settings JSON file (docs/settings.md lists the keys)");
    command.add_option("--set", options.overrides, "override one setting, e.g. shadows.directional.cascadeCount=2");
    command.add_option("--device", options.device, "Vulkan device: auto | gpu | cpu | N")->default_val("auto");
    command.add_option("--raster", options.raster, "shadow-map rasterizer: hw | compute | auto (= shadows.raster)")
        ->check(CLI::IsMember({"hw", "compute", "auto"}));
    command.add_option("--main-view", options.mainView,
                       "main view: forward | visibility (compute visibility buffer) | auto (= render.mainView)")
        ->check(CLI::IsMember({"forward", "visibility", "auto"}));
    command.add_flag("--validation", options.validation, "enable the Vulkan validation layers");
    command.add_option("--light", options.light, "light index (in the KHR_lights_punctual array) for AOVs and comparisons");
}

// A number from `low` to `high`, both included; CLI::Range lets "nan" through, this does not.
CLI::Validator numberIn(double low, double high) {
    char range[64];
    std::snprintf(range, sizeof range, "%g to %g", low, high);
    return CLI::Validator(
        [low, high, limits = std::string(range)](std::string& input) -> std::string {
            char* end = nullptr;
            const double value = std::strtod(input.c_str(), &end);
            if (!input.empty() && end == input.c_str() + input.size() && std::isfinite(value) && value >= low &&
                value <= high)
                return {};
            return input + " is not a number from " + limits;
        },
        std::string("NUMBER in ") + range);
}

}  // namespace

int runCli(int argc, char** argv) {
    CLI::App app{"penumbra: real-time shadow rendering (cascaded and spot-light shadow maps) on Vulkan"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("penumbra ") + PENUMBRA_VERSION_STRING, "print the version and exit");

    RenderOptions renderOptions;
    CLI::App* render = app.add_subcommand("render", "render a scene to a PNG (colour or a debug AOV)");
    addRenderOptions(*render, renderOptions);
    render->add_option("-o,--output", renderOptions.outputPath, "output PNG")->default_val("out.png");
    render->add_option("--aov", renderOptions.aov, "debug output instead of colour: shadow | cascades")
        ->check(CLI::IsMember({"shadow", "cascades"}));
    render->add_option("--dump-atlas", renderOptions.dumpAtlasPath, "write the shadow atlases' depth as a grayscale PNG");
    render->add_option("--stats", renderOptions.statsPath, "write stats JSON to FILE ('-' = stdout)");

    RenderOptions referenceOptions;
    CLI::App* reference = app.add_subcommand("reference", "ray-trace the exact shadow term of one light (Embree)");
    addRenderOptions(*reference, referenceOptions);
    reference->add_option("-o,--output", referenceOptions.outputPath, "output PNG (shadow AOV convention)")->default_val("reference.png");
    reference->add_option("--mask", referenceOptions.maskPath, "write the validity mask PNG");
    reference->add_option("--soft", referenceOptions.softSamples,
                          "trace the light as a disk of its shadowLightSize with N shadow rays per pixel (pcss truth)")
        ->check(CLI::Range(1u, 4096u));

    RenderOptions compareOptions;
    CLI::App* compare = app.add_subcommand("compare", "compare the rasterized shadow AOV with the ray-traced reference");
    addRenderOptions(*compare, compareOptions);
    compare->add_option("--diff", compareOptions.diffPath, "write a diff image: false shadow and false lit in two colours");
    compare->add_flag("--json", compareOptions.json, "print the metrics as JSON");
    compare->add_option("--soft", compareOptions.softSamples, "compare with the area-light reference of N rays per pixel")
        ->check(CLI::Range(1u, 4096u));
    compare->add_flag("--shimmer", compareOptions.shimmer,
                      "also render and trace with the camera 2 cm to its right: % of pixels that flip in ours only");

    RenderOptions benchOptions;
    BenchOptions benchSettings;
    CLI::App* bench = app.add_subcommand("bench", "render frames in flight; GPU ms per pass, CPU ms per phase, memory");
    addRenderOptions(*bench, benchOptions);
    bench->add_option("--frames", benchSettings.frames, "frames to time")->check(CLI::Range(1u, 1000000u));
    bench->add_option("--warmup", benchSettings.warmup, "frames before timing")->check(CLI::Range(0u, 100000u));
    bench->add_option("--camera", benchSettings.camera, "orbit (moves every frame) | static")
        ->check(CLI::IsMember({"orbit", "static"}));
    bench->add_option("--json", benchSettings.jsonPath, "write the results as JSON to FILE ('-' = stdout)");
    bench->add_option("--frame-times", benchSettings.frameTimesPath,
                      "write each timed frame's GPU frame and CPU phase milliseconds to FILE as CSV ('-' = stdout)");
    bench->add_flag("--vary-settings", benchSettings.vary,
                    "long run: change atlas sizes, cascades, filters and the shadowed lights every --vary-every frames");
    bench->add_option("--vary-every", benchSettings.varyEvery, "frames between changes of --vary-settings (default 100)")
        ->check(CLI::Range(1u, 1000000u));
    bench->add_option("--light-motion", benchSettings.lightMotion,
                      "turn every directional light by DEGREES per frame about +Y, 0..180 (default 0: still)")
        ->check(numberIn(0.0, 180.0));
    bench->add_option("--move-objects", benchSettings.moveObjects,
                      "move this fraction of the instances every frame, 0..1 (default 0: none)")
        ->check(numberIn(0.0, 1.0));
    bench->add_option("--pin-cpu", benchSettings.pinCpu,
                      "run the frame thread on logical CPU N while timed (no migrations between cores); default: any")
        ->check(CLI::Range(0, 4095));
    bench->add_flag("--spin-wait", benchOptions.spinWait,
                    "wait for the GPU by polling its fences instead of sleeping: steadier CPU phases, one core busy");

    RenderOptions exportOptions;
    CLI::App* exporter = app.add_subcommand("export", "write a scene (file, demo or gen:) as glTF 2.0 (.gltf or .glb)");
    exporter->add_option("scene", exportOptions.scenePath, "scene to write; the built-in demo scene if omitted");
    exporter->add_option("--model", exportOptions.model, "the glTF that gen:field copies");
    exporter->add_flag("--ground", exportOptions.ground, kGroundHelp);
    addSceneFileOptions(*exporter, exportOptions);
    exporter->add_option("-o,--output", exportOptions.outputPath, "output .gltf or .glb")->required();

    RenderOptions graphOptions;
    std::string graphFormat = "mermaid";
    uint32_t graphFrames = 1;
    CLI::App* graph = app.add_subcommand("graph", "print the frame graph of a rendered frame: passes, dependencies, barriers");
    addRenderOptions(*graph, graphOptions);
    graph->add_option("--format", graphFormat, "mermaid | dot (Graphviz)")->check(CLI::IsMember({"mermaid", "dot"}));
    graph->add_option("--frames", graphFrames, "frames to render; the last one's graph is printed (2: cached shadow tiles)")
        ->check(CLI::Range(1u, 100u));

    CLI::App* devices = app.add_subcommand("devices", "list the Vulkan devices Penumbra can use");

    std::string diffA, diffB;
    CLI::App* diff = app.add_subcommand("diff", "per-pixel difference of two PNGs (e.g. GPU vs lavapipe), as JSON");
    diff->add_option("a", diffA, "first PNG")->required();
    diff->add_option("b", diffB, "second PNG")->required();

    bool settingsMarkdown = false, settingsJson = false;
    CLI::App* settingsCommand =
        app.add_subcommand("settings", "print the settings reference (docs/settings.md) or the default settings");
    CLI::Option* markdownFlag =
        settingsCommand->add_flag("--markdown", settingsMarkdown, "every key, its range, default and meaning, as Markdown (the default)");
    settingsCommand->add_flag("--json", settingsJson, "every key's default, as a settings JSON file")->excludes(markdownFlag);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // A user error like any other: one line, exit code 1 (CLI11's own exit codes are not ours).
        printError("", (std::string(e.what()) + " (see penumbra --help)").c_str());
        return 1;
    }
    try {
        if (*render) return runRenderCommand(renderOptions);
        if (*reference) return runReferenceCommand(referenceOptions);
        if (*compare) return runCompareCommand(compareOptions);
        if (*bench) {
            benchSettings.varyPeriod = benchSettings.vary ? benchSettings.varyEvery : 0;
            return runBenchCommand(benchOptions, benchSettings);
        }
        if (*graph) return runGraphCommand(graphOptions, graphFormat, graphFrames);
        if (*devices) return runDevicesCommand();
        if (*exporter) return runExportCommand(exportOptions);
        if (*diff) return runDiffCommand(diffA, diffB);
        if (*settingsCommand) return runSettingsCommand(settingsJson);
    } catch (const Error& e) {
        printError("", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        printError("", "out of memory");
        return 1;
    } catch (const std::exception& e) {
        printError("unexpected error: ", e.what());
        return 1;
    }
    return 0;
}

}  // namespace penumbra

#pragma once
// What the viewer tests share: penumbra-viewer (PENUMBRA_VIEWER_PATH) run under xvfb-run on lavapipe
// with the validation layers on, scripted (--screenshot) or followed line by line on its stdout, and
// the images compared.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "cli_process.h"
#include "penumbra/image.h"

namespace penumbra::test {

namespace fs = std::filesystem;

inline const std::string kScenes = std::string(PENUMBRA_TEST_DATA_DIR) + "/scenes/";

inline fs::path tempPath(const std::string& name) {
    // One folder per test process: ctest runs tests in parallel, and two tests writing one file (two
    // viewers watching the same reloaded.gltf) fail each other.
    const fs::path dir = fs::temp_directory_path() / ("penumbra_viewer_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

#ifdef PENUMBRA_VIEWER_PATH
inline const char* const kViewer = PENUMBRA_VIEWER_PATH;
#else
inline const char* const kViewer = nullptr;
#endif

// The wrapper the viewer runs under. -noreset: by default Xvfb resets once its last client leaves and
// signals xvfb-run (SIGUSR1), and a signal that lands while xvfb-run's shell waits for a command spoils
// that command's exit status: a viewer that ended with 1 came back as "xvfb-run: error: problem while
// cleaning up temporary directory" and 5 (seen under ctest -j2, reproduced in 2-3 of 12 concurrent
// runs, none of 16 with -noreset). -n: `-a` takes the first free display from 99 on, and two test
// processes that look at once can take the same one; each process starts its search at its own number.
inline std::string xvfbRun() {
    return "xvfb-run -a -n " + std::to_string(100 + ::getpid() % 2000) + " -s '-screen 0 1280x1024x24 -noreset'";
}

inline bool canRunViewer() { return kViewer && std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

#define SKIP_WITHOUT_XVFB()                                                                           \
    if (!canRunViewer()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup.sh installs xvfb)"

// The scripted viewer's arguments: `frames` frames of `scene` at width x height, the last saved to `out`.
inline std::string scriptedArguments(const std::string& scene, const fs::path& out, const std::string& options,
                                     uint32_t width, uint32_t height, uint32_t frames) {
    return scene + " --device cpu --validation --width " + std::to_string(width) + " --height " + std::to_string(height) +
           " --frames " + std::to_string(frames) + " --screenshot " + out.string() + " " + options;
}

// The screenshot of a run; fails the test on a non-zero exit (a validation message included).
inline Image screenshotOf(const CliRun& run, const fs::path& out) {
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.err.find("validation"), std::string::npos) << run.err;
    if (run.exitCode != 0 || !fs::exists(out)) return Image{};
    return readPng(out.string());
}

// The viewer's screenshot after `frames` frames of `scene` at width x height.
inline Image viewerScreenshot(const std::string& scene, const std::string& name, const std::string& options,
                              uint32_t width = 320, uint32_t height = 180, uint32_t frames = 5) {
    const fs::path out = tempPath(name);
    fs::remove(out);
    return screenshotOf(runProgram(kViewer, scriptedArguments(scene, out, options, width, height, frames), xvfbRun()), out);
}

// Runs `command` (a shell command line), calling `onLine` with each line of its stdout as it comes;
// stderr is collected into the result.
inline CliRun followStdout(const std::string& command, const std::function<void(const std::string&)>& onLine) {
    static int counter = 0;
    const fs::path errPath = tempPath("follow_stderr_" + std::to_string(counter++) + ".txt");
    CliRun run;
    FILE* pipe = ::popen((command + " 2>" + errPath.string()).c_str(), "r");
    if (!pipe) return run;
    char line[4096];
    while (std::fgets(line, sizeof line, pipe)) {
        run.out += line;
        onLine(line);
    }
    const int status = ::pclose(pipe);
    if (WIFEXITED(status)) run.exitCode = WEXITSTATUS(status);
    std::stringstream err;
    err << std::ifstream(errPath).rdbuf();
    run.err = err.str();
    return run;
}

// Runs the viewer under Xvfb with `arguments`, following its stdout (it prints one line per scene it
// opens or reloads and per screenshot it saves, and flushes it).
inline CliRun runViewerFollowingStdout(const std::string& arguments, const std::function<void(const std::string&)>& onLine) {
    return followStdout(xvfbRun() + " " + std::string(kViewer) + " " + arguments, onLine);
}

inline double differingFraction(const Image& a, const Image& b) {
    size_t differ = 0;
    for (size_t p = 0; p < a.pixels.size(); p += 3)
        differ += a.pixels[p] != b.pixels[p] || a.pixels[p + 1] != b.pixels[p + 1] || a.pixels[p + 2] != b.pixels[p + 2];
    return double(differ) / double(a.pixels.size() / 3);
}

inline fs::path writeText(const std::string& name, const std::string& text) {
    const fs::path path = tempPath(name);
    std::ofstream(path) << text;
    return path;
}

// Sphere-fitted cascades and the hardware shadow raster: a frame's image depends on its camera and
// scene only, not on the frames before it (what a reload restarts).
inline const std::string kRepeatable =
    "--set shadows.directional.fit=sphere --set shadows.raster=hw --set render.toneMapping=aces";

}  // namespace penumbra::test

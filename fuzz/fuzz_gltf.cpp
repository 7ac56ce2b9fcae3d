// Fuzz target: a .gltf (JSON) or .glb (by its magic) held in memory, through the whole CPU side of a
// frame: loading (tinygltf, accessors, materials, lights, extras, images), the scene checks the
// renderer makes, the camera and the shadow plan.
//
// The input is loaded as if it lay in the folder `scene/` of a fixture made at start-up, with files
// beside it (beside.bin, beside.png, sub/inner.bin, sub/inner.png, inward -> sub) and escapes out of
// it (../outside.bin, ../outside.png, escape -> .., a FIFO, a link to /dev/zero). The loader's file
// observer aborts the process when it is about to open anything outside `scene/`: a reference that
// escapes the asset root is a finding, as a crash is.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "penumbra/camera.h"
#include "penumbra/error.h"
#include "penumbra/image.h"
#include "scene/asset_access.h"
#include "scene/gltf_loader.h"
#include "scene/scene_validation.h"
#include "shadows/shadow_planner.h"

namespace {

namespace fs = std::filesystem;

fs::path gFixture, gSceneFolder;

void writeBytes(const fs::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

void writeSmallPng(const fs::path& path) {
    penumbra::Image image(2, 2, 4);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = uint8_t(i * 37);
    penumbra::writePng(image, path.string());
}

void removeFixture() {
    std::error_code error;
    fs::remove_all(gFixture, error);
}

void makeFixture() {
    gFixture = fs::temp_directory_path() / ("penumbra_fuzz_gltf_" + std::to_string(::getpid()));
    fs::create_directories(gFixture / "scene" / "sub");
    gSceneFolder = fs::canonical(gFixture / "scene");
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};  // the buffer of fuzz/corpus/gltf/files-*.gltf
    const std::string bytes(reinterpret_cast<const char*>(triangle), sizeof triangle);
    writeBytes(gFixture / "outside.bin", bytes);
    writeSmallPng(gFixture / "outside.png");
    writeBytes(gSceneFolder / "beside.bin", bytes);
    writeSmallPng(gSceneFolder / "beside.png");
    writeBytes(gSceneFolder / "sub" / "inner.bin", bytes);
    writeSmallPng(gSceneFolder / "sub" / "inner.png");
    fs::create_directory_symlink("..", gSceneFolder / "escape");
    fs::create_directory_symlink("sub", gSceneFolder / "inward");
    fs::create_symlink("/dev/zero", gSceneFolder / "zero.bin");
    ::mkfifo((gSceneFolder / "fifo.bin").c_str(), 0600);
    std::atexit(removeFixture);
}

// Every file the loader opens must lie inside the scene's folder (the default asset root).
void checkOpen(const fs::path& path) {
    const auto [rootEnd, pathAt] = std::mismatch(gSceneFolder.begin(), gSceneFolder.end(), path.begin(), path.end());
    (void)pathAt;
    if (rootEnd != gSceneFolder.end()) {
        std::fprintf(stderr, "fuzz_gltf: the loader opened %s, outside the asset root %s\n", path.c_str(),
                     gSceneFolder.c_str());
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    makeFixture();
    penumbra::setFileOpenObserver(checkOpen);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    penumbra::Scene scene;
    try {
        penumbra::GltfLoadOptions options;
        options.limits.maxFileBytes = 64u << 20;  // the fuzzer's memory, not the defaults, bounds these
        options.limits.maxTextureBytes = 256u << 20;
        scene = penumbra::loadGltfSceneFromMemory(data, size, "fuzz.gltf", gSceneFolder.string(), options);
    } catch (const penumbra::Error&) {
        return 0;  // a clean one-line error is a correct answer to a bad file
    }
    // What the loader accepts, the renderer must accept too: validateScene must not throw here.
    penumbra::validateScene(scene);
    try {
        const penumbra::CameraView view = penumbra::resolveCameraView(scene, 64, 48);
        penumbra::ShadowSettings settings;
        (void)penumbra::ShadowPlanner::plan(scene, view, settings);
    } catch (const penumbra::Error&) {
        // The camera or the plan may still refuse a scene (e.g. a camera inside degenerate bounds).
    }
    return 0;
}

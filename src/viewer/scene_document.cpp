#include "viewer/scene_document.h"

#include <cstdio>
#include <filesystem>
#include <utility>

#include "penumbra/camera.h"
#include "penumbra/error.h"
#include "penumbra/scene_loading.h"
#include "penumbra/gltf_writer.h"

namespace penumbra::viewer {

namespace {

bool isFile(const std::string& source) {
    std::error_code error;
    return !source.empty() && std::filesystem::is_regular_file(source, error);
}

// The scene file to watch: none for the demo scene and gen: scenes.
FileWatcher watcherFor(const std::string& source, uint32_t pollMs) {
    return FileWatcher(isFile(source) ? source : std::string(), std::chrono::milliseconds(pollMs));
}

Scene loadSceneWithWarnings(const std::string& source, const SceneSourceOptions& loading) {
    Scene scene = loadScene(source, loading);
    for (const std::string& warning : scene.warnings) std::fprintf(stderr, "penumbra-viewer: warning: %s\n", warning.c_str());
    return scene;
}

std::string labelOf(const std::string& source) { return source.empty() ? "the demo scene" : source; }

}  // namespace

Camera startCamera(const Scene& scene) { return scene.camera ? *scene.camera : autoFramingCamera(scene.wsBounds); }

SceneDocument::SceneDocument(std::string source, uint32_t watchPollMs, SceneSourceOptions loading)
    : source_(std::move(source)), watchPollMs_(watchPollMs), loading_(std::move(loading)),
      watcher_(watcherFor(source_, watchPollMs)) {}

Scene SceneDocument::loadFirst() const { return loadSceneWithWarnings(source_, loading_); }

std::string SceneDocument::label() const { return labelOf(source_); }

std::string SceneDocument::defaultSavePath() const {
    if (!isFile(source_)) return "penumbra-scene.gltf";
    return std::filesystem::path(source_).replace_extension(".edited.gltf").string();
}

std::optional<SceneEvent> SceneDocument::update(FileWatcher::Clock::time_point now, const Scene& current,
                                                const InstallScene& install) {
    std::optional<SceneEvent> saved;
    if (!saveRequest_.empty()) saved = save(current, std::exchange(saveRequest_, std::string()));
    const std::string open = std::exchange(openRequest_, std::string());
    if (!open.empty()) return this->open(open, install);
    const bool changed = watcher_.poll(now);
    if (std::exchange(reloadRequest_, false) || changed) return this->open(source_, install);
    return saved;
}

SceneEvent SceneDocument::open(const std::string& source, const InstallScene& install) {
    const bool sameScene = source == source_;
    FileWatcher watcher = watcherFor(source, watchPollMs_);  // the stamp before the read
    SceneEvent event;
    std::optional<Camera> camera;
    try {
        Scene scene = loadSceneWithWarnings(source, loading_);
        if (!sameScene) camera = startCamera(scene);
        install(std::move(scene));
    } catch (const Error& error) {
        error_ = error.what();
        event.message = error_;
        std::fprintf(stderr, "penumbra-viewer: %s\n", error.what());
        return event;
    }
    watcher_ = std::move(watcher);
    source_ = source;
    error_.clear();
    event.opened = true;
    event.camera = camera;
    event.message = (sameScene ? "reloaded " : "opened ") + labelOf(source);
    return event;
}

SceneEvent SceneDocument::save(const Scene& scene, const std::string& path) {
    SceneEvent event;
    try {
        writeGltfScene(scene, path);
    } catch (const Error& error) {
        event.message = error.what();
        std::fprintf(stderr, "penumbra-viewer: %s\n", error.what());
        return event;
    }
    event.message = "saved the scene to " + path;
    std::error_code error;
    if (!watcher_.path().empty() && std::filesystem::equivalent(path, watcher_.path(), error))
        watcher_.markLoaded();  // our own write is what is loaded: no reload
    return event;
}

}  // namespace penumbra::viewer

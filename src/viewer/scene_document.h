#pragma once
// The viewer's scene file as a document, without a window: which file is open, File > Open and a
// dropped file (another scene, at its own camera), R, File > Reload and a change on disk (the same
// scene, the camera kept), File > Save scene (glTF with the edited shadow extras), and the error of
// the last open that failed (the old scene stays). The renderer stays with the caller: an opened
// scene is handed to an `InstallScene` function, which may refuse it by throwing penumbra::Error.
// The settings and the view are not the document's: opening or reloading leaves them alone.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "penumbra/scene.h"
#include "penumbra/scene_loading.h"
#include "viewer/file_watcher.h"

namespace penumbra::viewer {

// The camera a scene starts at: its own (docs/scene-format.md's choice), else an automatic framing.
Camera startCamera(const Scene& scene);

// What an update() or open() did.
struct SceneEvent {
    bool opened = false;            // a scene was installed (opened or reloaded)
    std::optional<Camera> camera;   // opened another scene: its start camera (a reload keeps the user's)
    std::string message;            // the status line: "opened ...", "reloaded ...", "saved ...", or an error
};

class SceneDocument {
public:
    using InstallScene = std::function<void(Scene&&)>;

    // `source`: a file, gen:..., or "" for the demo scene. The watcher takes the file's stamp now, before
    // the first read, so a write during it is seen. `loading` applies to every scene opened (--ground).
    SceneDocument(std::string source, uint32_t watchPollMs, SceneSourceOptions loading = {});

    // The first scene; throws penumbra::Error (the viewer ends with its one line).
    Scene loadFirst() const;

    const std::string& source() const { return source_; }
    std::string label() const;                            // the source, or "the demo scene"
    const std::string& error() const { return error_; }  // why the last open failed; "" once one succeeded
    // File > Save scene's default path: next to a scene file as NAME.edited.gltf, else penumbra-scene.gltf.
    std::string defaultSavePath() const;

    // Requests that the next update() acts on: File > Open and a dropped file; R and File > Reload; Save scene.
    void requestOpen(std::string source) { openRequest_ = std::move(source); }
    void requestReload() { reloadRequest_ = true; }
    void requestSave(std::string path) { saveRequest_ = std::move(path); }

    // Between frames: a requested save of `current` first, then a requested open, else a reload when
    // one was requested or the file changed on disk (FileWatcher's rule). Returns what happened, if anything.
    std::optional<SceneEvent> update(FileWatcher::Clock::time_point now, const Scene& current, const InstallScene& install);

    // Loads `source` and installs it. Reopening the open source is a reload. On failure (the file does
    // not load or install throws) the document keeps its source, the error is set and one line goes to stderr.
    SceneEvent open(const std::string& source, const InstallScene& install);
    // Writes `scene` as glTF (.gltf or .glb). A write over the watched file is not seen as a change.
    SceneEvent save(const Scene& scene, const std::string& path);

private:
    std::string source_;
    uint32_t watchPollMs_;
    SceneSourceOptions loading_;
    FileWatcher watcher_;
    std::string error_;
    std::string openRequest_, saveRequest_;
    bool reloadRequest_ = false;
};

}  // namespace penumbra::viewer

#pragma once
// The one way the scene loader reaches the file system (docs/security.md): the scene file itself, and
// the external buffers and images it references, each confined to the asset root and bounded by the
// fileBytes budget. Not part of the public API.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "penumbra/scene_limits.h"

namespace penumbra {

// Reads the regular file `path` whole, refusing (penumbra::Error "<shown>: <why>", one line) a missing
// file, a directory, a device, FIFO or socket, and a file of more than `maxBytes` (checked from its
// size before reading, and on the open file). Never blocks on a FIFO swapped in after the check; with
// `followLastLink` false (a canonical path), a symlink swapped in at the last component is refused.
// Every file the loader reads comes through here.
std::vector<uint8_t> readRegularFile(const std::filesystem::path& path, const std::string& shown, uint64_t maxBytes,
                                     const SceneLimits& limits, bool followLastLink = true);

// Where a scene's references may lead.
class AssetAccess {
public:
    // References resolve against `sceneFolder` and must stay inside `assetRoot` ("" = the scene folder).
    // Both are made canonical here; Error when either does not exist or is not a folder.
    AssetAccess(const std::string& sceneFolder, const std::string& assetRoot, const SceneLimits& limits);

    // The canonical path that `reference` (a URI, percent-decoded) names, or Error "<why>" (without the
    // scene's name) when a rule refuses it: empty, a NUL byte, a URI scheme, an absolute path, a path
    // that leaves the asset root, or no regular file.
    std::filesystem::path resolve(const std::string& reference) const;
    // resolve(), then readRegularFile() within the fileBytes budget.
    std::vector<uint8_t> read(const std::string& reference) const;

    const std::filesystem::path& root() const { return root_; }

private:
    std::filesystem::path folder_, root_;
    const SceneLimits& limits_;
};

// Tests and the fuzzer watch every file the loader opens: `observer` is called with the path just
// before it is opened (nullptr: none). Not thread-safe; set it before loading.
using FileOpenObserver = void (*)(const std::filesystem::path& path);
void setFileOpenObserver(FileOpenObserver observer);

}  // namespace penumbra

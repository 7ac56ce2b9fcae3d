#pragma once
// What loading one glTF scene may cost: the budgets a caller sets for input it does not trust. Each
// is checked before the memory it guards is allocated (an image's size from its header, a file's from
// the file system, vertex and index counts from the accessors) and refused with one penumbra::Error
// line naming the budget and how to raise it. The defaults load every real asset we know of and stop
// hostile ones; docs/security.md lists them with the threat model. The CLI and the viewer set them with
// `--limit NAME=VALUE` (NAME is the `name` of sceneLimitKeys(), e.g. `--limit fileBytes=64M`).
#include <cstdint>
#include <span>
#include <string>

namespace penumbra {

struct SceneLimits {
    uint64_t maxFileBytes = 1ull << 30;     // fileBytes: the scene file, and each file it references
    uint64_t maxImageBytes = 256ull << 20;  // imageBytes: one image decoded to RGBA8 (8192 x 8192 x 4)
    uint64_t maxTextureBytes = 2ull << 30;  // textureBytes: every image decoded to RGBA8, together
    uint64_t maxVertices = 50'000'000;      // vertices: of every mesh together (a shared accessor counts each use)
    uint64_t maxIndices = 150'000'000;      // indices: of every mesh together (3 per triangle)
    uint64_t maxNodes = 1'000'000;          // nodes: in the file
    uint64_t maxNodeDepth = 1024;           // nodeDepth: a root node is at depth 1
    uint64_t maxLights = 4096;              // lights: KHR_lights_punctual lights in the file
    uint64_t maxJsonDepth = 128;            // jsonDepth: nesting of arrays and objects in the glTF's JSON
};

// One budget: its --limit name, the SceneLimits member, and what it bounds.
struct SceneLimitKey {
    const char* name;
    const char* member;
    uint64_t SceneLimits::*field;
    const char* meaning;
};

// Every budget, in SceneLimits' order.
std::span<const SceneLimitKey> sceneLimitKeys();

// Sets one budget from "NAME=VALUE" (the CLI's --limit): VALUE is a whole number, optionally followed
// by K, M or G (times 2^10, 2^20, 2^30). Throws penumbra::Error naming the assignment for an unknown
// NAME or a bad VALUE.
void setSceneLimit(SceneLimits& limits, const std::string& assignment);

}  // namespace penumbra

#pragma once
// Builds small glTF files for the loader tests: a JSON document plus an external .bin buffer,
// written into a fresh temporary directory that is removed at the end of the test.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/gltf_loader.h"

namespace penumbra::testing {

class TempDir {
public:
    TempDir() {
        static int counter = 0;
        path_ = std::filesystem::temp_directory_path() /
                ("penumbra_scene_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

inline void writeFile(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

inline std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

class TestGltf {
public:
    nlohmann::json doc;
    std::vector<uint8_t> bin;

    TestGltf() {
        doc = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", nlohmann::json::array()}}}},
               {"nodes", nlohmann::json::array()}, {"meshes", nlohmann::json::array()},
               {"accessors", nlohmann::json::array()}, {"bufferViews", nlohmann::json::array()}};
    }

    int addAccessor(const void* data, size_t count, size_t elementSize, int componentType, const char* type) {
        while (bin.size() % 4) bin.push_back(0);
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", count * elementSize}});
        const auto* p = static_cast<const uint8_t*>(data);
        bin.insert(bin.end(), p, p + count * elementSize);
        doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                    {"componentType", componentType},
                                    {"count", count},
                                    {"type", type}});
        return int(doc["accessors"].size() - 1);
    }
    int addVec3(const std::vector<glm::vec3>& values) { return addAccessor(values.data(), values.size(), 12, 5126, "VEC3"); }
    int addIndices16(const std::vector<uint16_t>& values) { return addAccessor(values.data(), values.size(), 2, 5123, "SCALAR"); }

    // A mesh with one primitive; returns the mesh index.
    int addMesh(const nlohmann::json& primitive) {
        doc["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
        return int(doc["meshes"].size() - 1);
    }
    // A unit right triangle in the XY plane facing +Z (indexed, no normals).
    int addTriangleMesh() {
        const int positions = addVec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
        const int indices = addIndices16({0, 1, 2});
        return addMesh({{"attributes", {{"POSITION", positions}}}, {"indices", indices}});
    }
    int addNode(const nlohmann::json& node, bool root = true) {
        doc["nodes"].push_back(node);
        const int index = int(doc["nodes"].size() - 1);
        if (root) doc["scenes"][0]["nodes"].push_back(index);
        return index;
    }
    void addLight(const nlohmann::json& light) { doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(light); }

    // Writes <dir>/<name>.gltf and its <name>.bin; returns the .gltf path.
    std::string write(const TempDir& dir, const std::string& name) {
        nlohmann::json out = doc;
        if (!bin.empty()) {
            out["buffers"] = {{{"uri", name + ".bin"}, {"byteLength", bin.size()}}};
            writeFile(dir.file(name + ".bin"), std::string(bin.begin(), bin.end()));
        }
        const std::string path = dir.file(name + ".gltf");
        writeFile(path, out.dump(1));
        return path;
    }
};

// Loads `path` expecting an Error; checks it is one line naming the file and containing `detail`.
inline void expectLoadError(const std::string& path, const std::string& detail) {
    try {
        loadGltfScene(path);
        ADD_FAILURE() << "loading " << path << " succeeded";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_NE(message.find(detail), std::string::npos) << message;
    }
}

// True when some warning of `scene` contains `text`.
inline bool hasWarning(const Scene& scene, const std::string& text) {
    for (const std::string& warning : scene.warnings)
        if (warning.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace penumbra::testing

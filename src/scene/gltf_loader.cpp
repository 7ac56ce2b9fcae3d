// glTF file to Scene: parsing (tinygltf), then the node hierarchy flattened to world space.
#include "scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>

#include <glm/gtc/quaternion.hpp>

#include "core/error.h"
#include "scene/asset_access.h"
#include "scene/gltf_internal.h"
#include "scene/mesh_utils.h"
#include "scene/scene_validation.h"

namespace penumbra {
namespace gltf {

void LoadContext::fail(const std::string& what) const { throw Error(path + ": " + what); }

void LoadContext::warn(const std::string& what) const { scene.warnings.push_back(path + ": " + what); }

std::string describe(const char* kind, size_t index, const std::string& name) {
    std::string text = std::string(kind) + " " + std::to_string(index);
    if (!name.empty()) text += " '" + name + "'";
    return text;
}

}  // namespace gltf

namespace {

using gltf::LoadContext;

// glTF quaternions are (x, y, z, w) and must be unit length: a zero (or non-finite) one is an error,
// one off by more than rounding is normalized with a warning.
glm::quat nodeRotation(const LoadContext& ctx, size_t nodeIndex) {
    const tinygltf::Node& node = ctx.model.nodes[nodeIndex];
    const std::vector<double>& r = node.rotation;
    const glm::dvec4 xyzw(r[0], r[1], r[2], r[3]);
    const double length = glm::length(xyzw);
    const std::string object = gltf::describe("node", nodeIndex, node.name);
    if (!std::isfinite(length) || length < 1e-6)
        ctx.fail(object + ": rotation [" + std::to_string(r[0]) + ", " + std::to_string(r[1]) + ", " + std::to_string(r[2]) +
                 ", " + std::to_string(r[3]) + "] is not a unit quaternion");
    if (std::abs(length - 1.0) > 1e-3) ctx.warn(object + ": rotation has length " + std::to_string(length) + ", normalized");
    const glm::dvec4 unit = xyzw / length;
    return glm::quat(float(unit.w), float(unit.x), float(unit.y), float(unit.z));  // glm takes w first
}

glm::mat4 localFromNode(const LoadContext& ctx, size_t nodeIndex) {
    const tinygltf::Node& node = ctx.model.nodes[nodeIndex];
    glm::mat4 m(1.0f);
    if (node.matrix.size() == 16) {
        for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = float(node.matrix[size_t(i)]);  // column-major
    } else {
        glm::vec3 t(0.0f), s(1.0f);
        glm::quat r(1.0f, 0.0f, 0.0f, 0.0f);
        if (node.translation.size() == 3) t = glm::vec3(node.translation[0], node.translation[1], node.translation[2]);
        if (node.scale.size() == 3) s = glm::vec3(node.scale[0], node.scale[1], node.scale[2]);
        if (node.rotation.size() == 4) r = nodeRotation(ctx, nodeIndex);
        m = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
    }
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k)
            if (!std::isfinite(m[c][k])) ctx.fail(gltf::describe("node", nodeIndex, node.name) + ": transform is not finite");
    return m;
}

std::vector<int> rootNodes(const LoadContext& ctx) {
    const tinygltf::Model& model = ctx.model;
    if (!model.scenes.empty()) {
        size_t sceneIndex = 0;
        if (model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size()) sceneIndex = size_t(model.defaultScene);
        return model.scenes[sceneIndex].nodes;
    }
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes)
        for (int child : node.children)
            if (child >= 0 && size_t(child) < model.nodes.size()) isChild[size_t(child)] = true;
    std::vector<int> roots;
    for (size_t i = 0; i < model.nodes.size(); ++i)
        if (!isChild[i]) roots.push_back(int(i));
    return roots;
}

struct CameraCandidate {
    size_t nodeIndex = 0;
    glm::mat4 worldFromNode{1.0f};
};

class SceneFlattener {
public:
    explicit SceneFlattener(const LoadContext& ctx)
        : ctx_(ctx), meshCache_(ctx.model.meshes.size()), converted_(ctx.model.meshes.size(), false),
          visited_(ctx.model.nodes.size(), false), lightPlaced_(ctx.scene.lights.size(), false) {}

    void flatten() {
        struct Pending { int nodeIndex; glm::mat4 worldFromParent; uint64_t depth; };
        std::vector<Pending> stack;
        const std::vector<int> roots = rootNodes(ctx_);
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f), 1});
        while (!stack.empty()) {
            const Pending pending = stack.back();
            stack.pop_back();
            const size_t nodeIndex = checkedNode(pending.nodeIndex);
            if (pending.depth > ctx_.budget.limits().maxNodeDepth)
                ctx_.budget.check(pending.depth, &SceneLimits::maxNodeDepth,
                                  gltf::describe("node", nodeIndex, ctx_.model.nodes[nodeIndex].name) + "'s depth");
            const glm::mat4 worldFromNode = pending.worldFromParent * localFromNode(ctx_, nodeIndex);
            visitNode(nodeIndex, worldFromNode);
            const std::vector<int>& children = ctx_.model.nodes[nodeIndex].children;
            for (auto it = children.rbegin(); it != children.rend(); ++it)
                stack.push_back({*it, worldFromNode, pending.depth + 1});
        }
        chooseCamera();
    }

    bool usedDefaultMaterial() const { return usedDefaultMaterial_; }

private:
    size_t checkedNode(int nodeIndex) {
        if (nodeIndex < 0 || size_t(nodeIndex) >= ctx_.model.nodes.size())
            ctx_.fail("node " + std::to_string(nodeIndex) + " is out of range (the file has " +
                      std::to_string(ctx_.model.nodes.size()) + ")");
        if (visited_[size_t(nodeIndex)])
            ctx_.fail(gltf::describe("node", size_t(nodeIndex), ctx_.model.nodes[size_t(nodeIndex)].name) +
                      " is reached twice: the node hierarchy must be a tree");
        visited_[size_t(nodeIndex)] = true;
        return size_t(nodeIndex);
    }

    void visitNode(size_t nodeIndex, const glm::mat4& worldFromNode) {
        const tinygltf::Node& node = ctx_.model.nodes[nodeIndex];
        const std::string object = gltf::describe("node", nodeIndex, node.name);
        const bool castShadows = gltf::extraBool(ctx_, node.extras, object, "castShadows").value_or(true);
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= ctx_.model.meshes.size())
                ctx_.fail(object + ": mesh " + std::to_string(node.mesh) + " is out of range (the file has " +
                          std::to_string(ctx_.model.meshes.size()) + ")");
        }
        if (node.mesh >= 0 && glm::determinant(glm::mat3(worldFromNode)) == 0.0f) {
            // A zero scale (a common way to hide a node) leaves no volume and no defined normals.
            ctx_.warn(object + ": the world transform is singular (a zero scale), its mesh is not drawn");
        } else if (node.mesh >= 0) {
            for (uint32_t meshIndex : sceneMeshes(size_t(node.mesh))) {
                Instance instance;
                instance.meshIndex = meshIndex;
                instance.worldFromObject = worldFromNode;
                instance.castShadows = castShadows;
                instance.nodeName = node.name;
                ctx_.scene.instances.push_back(std::move(instance));
            }
        }
        if (node.camera >= 0) {
            if (size_t(node.camera) >= ctx_.model.cameras.size())
                ctx_.fail(object + ": camera " + std::to_string(node.camera) + " is out of range (the file has " +
                          std::to_string(ctx_.model.cameras.size()) + ")");
            if (ctx_.model.cameras[size_t(node.camera)].type == "perspective")
                cameras_.push_back({nodeIndex, worldFromNode});
            else
                ctx_.warn(object + ": camera " + std::to_string(node.camera) + " is not perspective, ignored");
        }
        const int lightIndex = gltf::nodeLightIndex(ctx_, nodeIndex);
        if (lightIndex >= 0) {
            if (lightPlaced_[size_t(lightIndex)]) {
                ctx_.warn(object + ": light " + std::to_string(lightIndex) + " is already placed by another node, ignored");
            } else {
                gltf::placeLight(ctx_, object, ctx_.scene.lights[size_t(lightIndex)], worldFromNode);
                lightPlaced_[size_t(lightIndex)] = true;
            }
        }
    }

    // The scene meshes of a glTF mesh (one per triangle primitive), converted once.
    const std::vector<uint32_t>& sceneMeshes(size_t gltfMesh) {
        if (!converted_[gltfMesh]) {
            converted_[gltfMesh] = true;
            const uint32_t defaultMaterial = uint32_t(ctx_.model.materials.size());
            for (size_t p = 0; p < ctx_.model.meshes[gltfMesh].primitives.size(); ++p) {
                std::optional<Mesh> mesh = gltf::convertPrimitive(ctx_, gltfMesh, p, defaultMaterial);
                if (!mesh) continue;
                usedDefaultMaterial_ |= mesh->materialIndex == defaultMaterial;
                meshCache_[gltfMesh].push_back(uint32_t(ctx_.scene.meshes.size()));
                ctx_.scene.meshes.push_back(std::move(*mesh));
            }
        }
        return meshCache_[gltfMesh];
    }

    // The Camera of a candidate node; with `failOnBadValues` a bad projection fails the load, else it
    // gives nullopt (cameras other than the chosen one are only offered to pick from).
    std::optional<Camera> cameraOf(const CameraCandidate& candidate, bool failOnBadValues) const {
        const tinygltf::Node& node = ctx_.model.nodes[candidate.nodeIndex];
        const tinygltf::PerspectiveCamera& p = ctx_.model.cameras[size_t(node.camera)].perspective;
        const std::string object = gltf::describe("camera", size_t(node.camera), ctx_.model.cameras[size_t(node.camera)].name);
        std::string problem;
        if (!(std::isfinite(p.yfov) && p.yfov > 0.0 && p.yfov < 3.14159)) problem = object + ": yfov must be in (0, pi)";
        else if (!(std::isfinite(p.znear) && p.znear > 0.0)) problem = object + ": znear must be > 0";
        else if (!(p.zfar == 0.0 || (std::isfinite(p.zfar) && p.zfar > p.znear)))
            problem = object + ": zfar must be greater than znear";
        Camera camera;
        camera.name = node.name;
        camera.worldFromView = candidate.worldFromNode;
        camera.yfov = float(p.yfov);
        camera.zNear = float(p.znear);
        camera.zFar = p.zfar == 0.0 ? INFINITY : float(p.zfar);
        if (problem.empty()) {
            try {
                validateCamera(camera, object + " (" + gltf::describe("node", candidate.nodeIndex, node.name) + ")");
            } catch (const Error& e) {
                problem = e.what();
            }
        }
        if (problem.empty()) return camera;
        if (failOnBadValues) ctx_.fail(problem);
        return std::nullopt;
    }

    void chooseCamera() {
        if (cameras_.empty()) return;
        const CameraCandidate* chosen = nullptr;
        for (const CameraCandidate& c : cameras_)
            if (ctx_.model.nodes[c.nodeIndex].name == "camera") chosen = &c;
        if (!chosen)
            for (const CameraCandidate& c : cameras_)
                if (!chosen || c.nodeIndex < chosen->nodeIndex) chosen = &c;
        ctx_.scene.camera = cameraOf(*chosen, true);
        std::vector<CameraCandidate> inNodeOrder = cameras_;
        std::sort(inNodeOrder.begin(), inNodeOrder.end(),
                  [](const CameraCandidate& a, const CameraCandidate& b) { return a.nodeIndex < b.nodeIndex; });
        for (const CameraCandidate& c : inNodeOrder)
            if (std::optional<Camera> camera = cameraOf(c, false)) ctx_.scene.cameras.push_back(*camera);
    }

    const LoadContext& ctx_;
    std::vector<std::vector<uint32_t>> meshCache_;
    std::vector<bool> converted_;
    std::vector<bool> visited_;
    std::vector<bool> lightPlaced_;
    std::vector<CameraCandidate> cameras_;
    bool usedDefaultMaterial_ = false;
};

}  // namespace

namespace {

// The counts the file states, against their budgets, before anything is converted.
void checkCounts(const tinygltf::Model& model, const LoadBudget& budget) {
    budget.check(model.nodes.size(), &SceneLimits::maxNodes, "the node count");
    budget.check(model.lights.size(), &SceneLimits::maxLights, "the light count");
}

Scene convertModel(const tinygltf::Model& model, const std::string& path, const std::string& parserWarnings,
                   LoadBudget& budget) {
    checkCounts(model, budget);
    Scene scene;
    scene.sourcePath = path;
    if (!parserWarnings.empty()) scene.warnings.push_back(path + ": " + parserWarnings);
    const LoadContext ctx{path, model, scene, budget};
    gltf::convertTextures(ctx);
    gltf::convertMaterials(ctx);
    gltf::convertLights(ctx);
    SceneFlattener flattener(ctx);
    flattener.flatten();
    if (flattener.usedDefaultMaterial() || scene.materials.empty()) {
        Material fallback;
        fallback.name = "default";  // glTF's default material: white, metallic 1, roughness 1
        scene.materials.push_back(fallback);
    }
    computeWorldBounds(scene);
    try {
        validateScene(scene);  // what the renderer will check: world bounds, light positions, ...
    } catch (const Error& e) {
        ctx.fail(e.what());
    }
    return scene;
}

Scene loadBytes(const uint8_t* data, size_t size, const std::string& name, const AssetAccess* access,
                const SceneLimits& limits) {
    LoadBudget budget(name, limits);
    std::string parserWarnings;
    const tinygltf::Model model = gltf::parseGltf(data, size, access, budget, parserWarnings);
    return convertModel(model, name, parserWarnings, budget);
}

std::string folderOf(const std::string& path) {
    const std::string folder = std::filesystem::path(path).parent_path().string();
    return folder.empty() ? std::string(".") : folder;
}

}  // namespace

Scene loadGltfScene(const std::string& path, const GltfLoadOptions& options) {
    const std::vector<uint8_t> bytes = readRegularFile(path, path, options.limits.maxFileBytes, options.limits);
    const AssetAccess access(folderOf(path), options.assetRoot, options.limits);
    return loadBytes(bytes.data(), bytes.size(), path, &access, options.limits);
}

Scene loadGltfSceneFromMemory(const uint8_t* data, size_t size, const std::string& name, const SceneLimits& limits) {
    return loadBytes(data, size, name, nullptr, limits);
}

Scene loadGltfSceneFromMemory(const uint8_t* data, size_t size, const std::string& name, const std::string& folder,
                              const GltfLoadOptions& options) {
    const AssetAccess access(folder, options.assetRoot, options.limits);
    return loadBytes(data, size, name, &access, options.limits);
}

}  // namespace penumbra

#include "penumbra/scene_loading.h"

#include "scene/default_light.h"
#include "scene/generated_scenes.h"
#include "scene/scene_validation.h"

namespace penumbra {

Scene loadScene(const std::string& source, const SceneSourceOptions& options) {
    const GltfLoadOptions files{options.assetRoot, options.limits};
    Scene scene;
    if (source.empty()) {
        scene = makeDemoScene();
    } else if (const auto spec = parseGeneratedSceneSpec(source)) {
        if (spec->kind == GeneratedSceneSpec::Kind::Field) {
            const Scene model = loadGltfScene(options.model, files);
            scene = makeFieldScene(model, spec->count, spec->spotLights, spec->pointLights);
            for (const std::string& warning : model.warnings) scene.warnings.push_back(options.model + ": " + warning);
        } else {
            scene = makeBoxesScene(spec->count, spec->pointLights);
        }
        scene.sourcePath = source;
    } else {
        scene = loadGltfScene(source, files);
    }
    if (options.addDefaultSun && addDefaultSunIfUnlit(scene))
        scene.warnings.push_back((source.empty() ? std::string("the scene") : source) +
                                 " has no lights; added a default sun as light 0");
    if (options.addGround) addGroundPlane(scene);
    validateScene(scene);
    return scene;
}

}  // namespace penumbra

// Each pass's declared set 0 and push constants (render/pass_layouts.h) against its shaders' SPIR-V
// (gpu/shader_interface.h): the real declarations pass, and each kind of disagreement is an Error that
// names the pass, the shader and the binding.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cull_structs.h"
#include "error_message.h"
#include "gpu/shader_interface.h"
#include "pass_bindings.h"
#include "render/pass_layouts.h"
#include "virtual_page_draw_structs.h"
#include "virtual_shadow_structs.h"
#include "visibility_structs.h"

namespace penumbra {
namespace {

using gpu::BindingDesc;
using gpu::PipelineStage;
using testing::errorMessage;

struct PassCase {
    std::string pass;
    std::vector<PipelineStage> stages;
    std::vector<BindingDesc> bindings;
    uint32_t pushConstantSize = 0;
    bool textureTable = false;
};

PipelineStage vertex(const char* shader) { return {gpu::kStageVertex, shader}; }
PipelineStage fragment(const char* shader) { return {gpu::kStageFragment, shader}; }
PipelineStage compute(const char* shader) { return {gpu::kStageCompute, shader}; }

// Every pipeline the renderer builds, with the declaration its pass gives it.
std::vector<PassCase> everyPass() {
    using namespace gpu_data;
    std::vector<PassCase> cases = {
        {"lit", {vertex("mesh.vert"), fragment("lit.frag")}, mainPassBindings("lit.frag"), 0, true},
        {"prepass", {vertex("mesh.vert"), fragment("normal_prepass.frag")}, mainPassBindings("normal_prepass.frag"), 0, true},
        {"background", {vertex("fullscreen.vert"), fragment("background.frag")}, backgroundBindings()},
        {"caster", {vertex("shadow_caster.vert")}, shadowCasterBindings(), sizeof(CasterConstants), true},
        {"caster alpha", {vertex("shadow_caster.vert"), fragment("shadow_caster.frag")}, shadowCasterBindings(),
         sizeof(CasterConstants), true},
        {"screen shadows", {vertex("fullscreen.vert"), fragment("screen_space_shadows.frag")}, screenSpaceShadowBindings(),
         sizeof(ScreenShadowConstants)},
        {"cull", {compute("shadow_cull.comp")}, shadowCullBindings(), sizeof(CullConstants)},
        {"draws", {compute("shadow_draws.comp")}, shadowDrawsBindings(), sizeof(CullConstants)},
        {"raster args", {compute("shadow_raster_args.comp")}, rasterArgsBindings(), sizeof(RasterArgsConstants)},
        {"resolve frag", {vertex("fullscreen.vert"), fragment("visibility_resolve.frag")},
         visibilityResolveBindings(gpu::kStageFragment), sizeof(VisibilityConstants), true},
        {"resolve comp", {compute("visibility_resolve.comp")}, visibilityResolveBindings(gpu::kStageCompute),
         sizeof(VisibilityConstants), true},
        {"pyramid", {compute("depth_pyramid.comp")}, depthPyramidBindings(), sizeof(PyramidConstants)},
        {"clusters", {compute("light_cluster.comp")}, lightClusterBindings()},
        {"visible bounds", {compute("visible_bounds.comp")}, visibleBoundsBindings()},
        {"virtual page mark", {compute("virtual_page_mark.comp")}, virtualPageMarkBindings()},
    };
    for (const char* shader : {"virtual_page_reset.comp", "virtual_page_invalidate.comp", "virtual_page_update.comp",
                               "virtual_page_plan.comp", "virtual_page_candidates.comp", "virtual_page_allocate.comp",
                               "virtual_page_finish.comp", "virtual_page_order.comp", "virtual_page_drawn.comp"})
        cases.push_back({shader, {compute(shader)}, virtualPageTableBindings(shader)});
    cases.push_back({"virtual page tiles", {compute("virtual_page_tiles.comp")}, virtualPageDrawBindings("virtual_page_tiles.comp"),
                     sizeof(VirtualPageTilesConstants)});
    cases.push_back({"virtual page copy", {compute("virtual_page_copy.comp")}, virtualPageDrawBindings("virtual_page_copy.comp"),
                     sizeof(VirtualPageCopyConstants)});
    cases.push_back({"virtual shadow probe", {compute("virtual_shadow_probe.comp")}, virtualShadowProbeBindings(),
                     sizeof(VirtualShadowProbeConstants)});
    for (const char* shader : {"shadow_raster_clear.comp", "shadow_raster.comp", "shadow_raster_bin.comp", "shadow_raster_chunks.comp"})
        cases.push_back({shader, {compute(shader)}, shadowRasterBindings(), sizeof(ShadowRasterConstants), true});
    for (const char* shader : {"visibility_raster.comp", "visibility_raster_bin.comp", "visibility_raster_chunks.comp"})
        cases.push_back({shader, {compute(shader)}, visibilityRasterBindings(), sizeof(VisibilityConstants), true});
    return cases;
}

std::string check(const PassCase& c) {
    return errorMessage([&] { gpu::checkPipelineInterface(c.pass, c.stages, c.bindings, c.pushConstantSize, c.textureTable); });
}

BindingDesc& declared(PassCase& c, uint32_t binding) {
    for (BindingDesc& b : c.bindings)
        if (b.binding == binding) return b;
    throw std::runtime_error("no such binding in the test's pass");
}

PassCase litPass() { return everyPass()[0]; }

TEST(ShaderInterfaceTest, EveryPassDeclaresWhatItsShadersUse) {
    for (const PassCase& c : everyPass()) EXPECT_EQ(check(c), "") << c.pass;
}

TEST(ShaderInterfaceTest, AWrongDescriptorTypeNamesPassShaderAndBinding) {
    PassCase c = litPass();
    declared(c, gpu_data::kSceneBindingMaterials).type = gpu::DescriptorType::UniformBuffer;
    EXPECT_EQ(check(c), "pass 'lit', shader 'lit.frag', binding 3 (MaterialBlock): declared as uniform buffer, "
                        "the shader has a storage buffer");
}

TEST(ShaderInterfaceTest, AStageMissingFromTheMaskIsAnError) {
    PassCase c = litPass();
    declared(c, gpu_data::kSceneBindingFrame).stages = gpu::kStageVertex;
    EXPECT_EQ(check(c), "pass 'lit', shader 'lit.frag', binding 0 (FrameBlock): used by the fragment stage but "
                        "declared for vertex");
}

TEST(ShaderInterfaceTest, AStageInTheMaskThatDoesNotUseTheBindingIsAnError) {
    PassCase c = litPass();
    declared(c, gpu_data::kSceneBindingMaterials).stages = gpu::kStageVertex | gpu::kStageFragment;
    EXPECT_EQ(check(c), "pass 'lit', shader 'mesh.vert', binding 3 (MaterialBlock): declared for the vertex stage, "
                        "which does not use it");
}

TEST(ShaderInterfaceTest, AnUndeclaredBindingIsAnError) {
    PassCase c = litPass();
    std::erase_if(c.bindings, [](const BindingDesc& b) { return b.binding == gpu_data::kLitBindingOtherAtlas; });
    EXPECT_EQ(check(c), "pass 'lit', shader 'lit.frag', binding " + std::to_string(gpu_data::kLitBindingOtherAtlas) +
                            " (otherShadowAtlas): used by the shader but not declared by the pass");
}

TEST(ShaderInterfaceTest, AnArrayDeclaredSmallerThanTheShadersIsAnError) {
    PassCase c = everyPass()[6];  // cull: its visible-instance lists are an array of buffers
    for (BindingDesc& b : c.bindings)
        if (b.binding == gpu_data::kCullBindingVisibleInstances) b.count = 1;
    EXPECT_EQ(check(c), "pass 'cull', shader 'shadow_cull.comp', binding 5 (VisibleBlock): an array of 4 in the shader, "
                        "1 declared");
}

TEST(ShaderInterfaceTest, AWrongPushConstantSizeIsAnError) {
    PassCase c = everyPass()[6];  // cull
    c.pushConstantSize = 32;
    EXPECT_EQ(check(c), "pass 'cull', shader 'shadow_cull.comp': push constants are 16 bytes in the shader, 32 declared");
}

TEST(ShaderInterfaceTest, TheTextureTableMustBeDeclaredWhenAShaderSamplesIt) {
    PassCase c = litPass();
    c.textureTable = false;
    EXPECT_EQ(check(c), "pass 'lit', shader 'lit.frag', binding 0 (baseColorTextures): set 1 is used but the pass "
                        "has no texture table");
}

TEST(ShaderInterfaceTest, ABindingDeclaredTwiceIsAnError) {
    PassCase c = litPass();
    c.bindings.push_back(c.bindings[0]);
    EXPECT_EQ(check(c), "pass 'lit', shader 'mesh.vert', binding 0 (FrameBlock): declared twice");
}

TEST(ShaderInterfaceTest, EachShaderIsReflectedOnce) {
    EXPECT_EQ(&gpu::embeddedShaderInterface("lit.frag"), &gpu::embeddedShaderInterface("lit.frag"));
}

}  // namespace
}  // namespace penumbra

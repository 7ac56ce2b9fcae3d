#pragma once
// Set 0 of every pass, declared once: each binding's GLSL name, number (shaders/shared/pass_bindings.h),
// descriptor type and exactly the stages that read it. Pipeline creation checks these against the
// shaders' SPIR-V (gpu/shader_interface.h); the passes write their descriptors with the same names.
#include <string>
#include <vector>

#include "gpu/types.h"

namespace penumbra {

// The forward main pass: mesh.vert with lit.frag, or with normal_prepass.frag (the depth + normal
// prepass); throws Error for another fragment shader.
std::vector<gpu::BindingDesc> mainPassBindings(const std::string& fragmentShader);
std::vector<gpu::BindingDesc> backgroundBindings();      // fullscreen.vert + background.frag
std::vector<gpu::BindingDesc> shadowCasterBindings();    // shadow_caster.vert (+ shadow_caster.frag)
std::vector<gpu::BindingDesc> screenSpaceShadowBindings();  // fullscreen.vert + screen_space_shadows.frag
std::vector<gpu::BindingDesc> shadowCullBindings();      // shadow_cull.comp
std::vector<gpu::BindingDesc> shadowDrawsBindings();     // shadow_draws.comp
std::vector<gpu::BindingDesc> atlasCopyBindings(const std::string& shader);  // shadow_atlas_{copy,resolve}.comp
std::vector<gpu::BindingDesc> shadowRasterBindings();    // shadow_raster{_clear,,_bin,_chunks}.comp
std::vector<gpu::BindingDesc> visibilityRasterBindings();  // visibility_raster{,_bin,_chunks}.comp
std::vector<gpu::BindingDesc> rasterArgsBindings();      // shadow_raster_args.comp
// The visibility resolve: visibility_resolve.frag (shading = kStageFragment, behind fullscreen.vert)
// or visibility_resolve.comp (kStageCompute, which also writes the resolved colour and depth).
std::vector<gpu::BindingDesc> visibilityResolveBindings(gpu::ShaderStage shading);
std::vector<gpu::BindingDesc> depthPyramidBindings();    // depth_pyramid.comp
std::vector<gpu::BindingDesc> lightClusterBindings();    // light_cluster.comp
std::vector<gpu::BindingDesc> visibleBoundsBindings();  // visible_bounds.comp
std::vector<gpu::BindingDesc> sceneScatterBindings();    // scene_scatter.comp
std::vector<gpu::BindingDesc> virtualPageMarkBindings();  // virtual_page_mark.comp
std::vector<gpu::BindingDesc> virtualPageMarkVisibilityBindings();  // virtual_page_mark_visibility.comp
// virtual_face_mark.comp, or virtual_face_mark_visibility.comp when `visibility`.
std::vector<gpu::BindingDesc> virtualFaceMarkBindings(bool visibility);
// The virtual page table's steps (virtual_page_{reset,invalidate,update,plan,candidates,allocate,finish,
// drawn}.comp): each reads its own subset of virtual_page_table.glsl's blocks; throws Error for another shader.
std::vector<gpu::BindingDesc> virtualPageTableBindings(const std::string& shader);
// Virtual page drawing (virtual_page_tiles.comp, virtual_page_copy[_r32f].comp); throws Error for another shader.
std::vector<gpu::BindingDesc> virtualPageDrawBindings(const std::string& shader);
std::vector<gpu::BindingDesc> virtualShadowProbeBindings(bool faces = false);  // virtual_shadow_probe.comp, or virtual_face_probe.comp (tests)

}  // namespace penumbra

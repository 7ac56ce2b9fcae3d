#include "render/visible_surface_pass.h"

#include "render/frame_data.h"

namespace penumbra {

VisibleSurfaces VisibleSurfacePass::render(const Scene& scene, const CameraView& view, gpu::BufferHandle frameBuffer,
                                           gpu::BufferHandle lightBuffer) {
    const gpu_data::FrameData frame = cameraFrameData(view);
    device_.writeBuffer(frameBuffer, &frame, sizeof(frame));

    // The screen-space path's prepass shader (alpha-tested like the lit pass); its normals are unused.
    const gpu::TextureHandle normals = device_.createTexture(
        {view.width, view.height, gpu::Format::RGBA16Float, gpu::kTextureColorTarget, 1, "visible normals"});
    const gpu::TextureHandle depth = device_.createTexture(
        {view.width, view.height, gpu::Format::D32Float, gpu::kTextureDepthTarget, 1, "visible depth"});
    MainPassInputs inputs;
    inputs.bindings = sceneBindings();
    inputs.writes = sceneDescriptorWrites(gpuScene_, frameBuffer, lightBuffer);
    MainPass::Target target;
    target.color = normals;
    target.colorFormat = gpu::Format::RGBA16Float;
    target.depth = depth;
    target.fragmentShader = "normal_prepass.frag";
    target.drawBlended = false;

    gpu::CommandList commands = device_.beginCommands();
    commands.transition(normals, gpu::TextureState::Undefined, gpu::TextureState::ColorTarget);
    commands.transition(depth, gpu::TextureState::Undefined, gpu::TextureState::DepthTarget);
    mainPass_.record(commands, scene, view, inputs, target);
    device_.submitAndWait(commands);
    const VisibleSurfaces visible =
        visibleSurfacesFromDepth(device_.readTexture(depth, gpu::TextureState::DepthTarget), view);
    device_.destroy(normals);
    device_.destroy(depth);
    return visible;
}

}  // namespace penumbra

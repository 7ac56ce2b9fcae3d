// Renders the built-in demo scene with the installed Penumbra library and writes a PNG.
//   penumbra_embed [OUT.png] [auto|gpu|cpu|N] [WIDTH HEIGHT] [key=value]...
// Uses only <penumbra/penumbra.h>: no Vulkan header is needed to render and read back.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <penumbra/penumbra.h>

#ifdef VK_VERSION_1_0
#error "rendering with read-back must not need the Vulkan headers"
#endif

int main(int argc, char** argv) {
    const std::string output = argc > 1 ? argv[1] : "embed.png";
    penumbra::DeviceOptions deviceOptions;
    deviceOptions.device = argc > 2 ? argv[2] : "auto";
    penumbra::RenderRequest request;
    if (argc > 4) {
        request.width = uint32_t(std::strtoul(argv[3], nullptr, 10));
        request.height = uint32_t(std::strtoul(argv[4], nullptr, 10));
    }
    // The headers compiled against and the library linked must be one version.
    if (std::strcmp(penumbra::version(), PENUMBRA_VERSION_STRING) != 0) {
        std::fprintf(stderr, "penumbra_embed: headers of penumbra %s, library %s\n", PENUMBRA_VERSION_STRING,
                     penumbra::version());
        return 1;
    }
    try {
        penumbra::Settings settings;
        for (int i = 5; i < argc; ++i) penumbra::applySettingOverride(settings, argv[i]);
        penumbra::Device device(deviceOptions);
        penumbra::Renderer renderer(device, penumbra::loadScene(""));
        const penumbra::RenderResult result = renderer.render(request, settings);
        penumbra::writePng(result.image, output);
        std::printf("penumbra_embed: penumbra %s, %ux%u on %s -> %s\n", penumbra::version(), result.image.width,
                    result.image.height, device.info().name.c_str(), output.c_str());
    } catch (const penumbra::Error& error) {
        std::fprintf(stderr, "penumbra_embed: %s\n", error.what());
        return 1;
    }
    return 0;
}

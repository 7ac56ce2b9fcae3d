// `penumbra graph`: renders frames of a scene and prints the frame graph of the last one (its passes,
// their dependencies and barriers) as Mermaid or Graphviz dot.
#include <cstdio>

#include "app/commands.h"
#include "penumbra/device.h"
#include "penumbra/error.h"
#include "penumbra/renderer.h"

namespace penumbra {

int runGraphCommand(const RenderOptions& options, const std::string& format, uint32_t frames) {
    ViewRender setup(options);
    Device& device = setup.device;
    device.recordFrameGraph(true);  // each frame keeps its own passes: the last one's are printed
    for (uint32_t frame = 0; frame < frames; ++frame) {
        const RenderResult result = setup.renderer.render(setup.request, setup.settings, setup.view);
        if (frame + 1 == frames)
            for (const std::string& warning : result.stats.warnings)
                std::fprintf(stderr, "penumbra: warning: %s\n", warning.c_str());
    }
    std::printf("%s", device.frameGraphText(format).c_str());
    if (options.validation && device.validationMessageCount() > 0)
        throw Error(std::to_string(device.validationMessageCount()) + " Vulkan validation messages (see above)");
    return 0;
}

}  // namespace penumbra

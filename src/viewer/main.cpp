// penumbra-viewer: the interactive window (see viewer_options.cpp for its options and controls).
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "penumbra/error.h"
#include "viewer/viewer_app.h"

namespace {

void printError(const std::string& message) {
    std::string line = message;
    for (char& c : line)
        if (c == '\n' || c == '\r') c = ' ';
    std::fprintf(stderr, "penumbra-viewer: %s\n", line.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const auto options = penumbra::viewer::parseViewerOptions(argc, argv);
        if (!options) return 0;
        penumbra::viewer::ViewerApp app(*options);
        return app.run();
    } catch (const penumbra::Error& error) {
        printError(error.what());
    } catch (const std::bad_alloc&) {
        printError("out of memory");
    } catch (const std::exception& error) {
        printError(std::string("unexpected error: ") + error.what());
    }
    return 1;
}

// Fuzz target: the settings parser. The whole input as a settings JSON document, then each line of
// it as a --set override (key=value) applied in turn to the defaults.
#include <cstddef>
#include <cstdint>
#include <string>

#include "penumbra/error.h"
#include "penumbra/settings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        penumbra::validateSettings(penumbra::parseSettingsJson(text, "fuzz.json"));
    } catch (const penumbra::Error&) {
    }
    penumbra::Settings settings;
    size_t begin = 0;
    while (begin <= text.size()) {
        size_t end = text.find('\n', begin);
        if (end == std::string::npos) end = text.size();
        try {
            penumbra::applySettingOverride(settings, text.substr(begin, end - begin));
        } catch (const penumbra::Error&) {
        }
        begin = end + 1;
    }
    penumbra::validateSettings(settings);  // overrides are validated as they apply: this must never throw
    return 0;
}

// `penumbra settings`: the settings reference and the defaults, both made from the key table.
#include <cstdio>

#include "app/commands.h"
#include "penumbra/settings.h"
#include "penumbra/settings_keys.h"

namespace penumbra {

int runSettingsCommand(bool json) {
    const std::string text = json ? settingsToJson(Settings{}) + "\n" : settingsReferenceMarkdown();
    std::fputs(text.c_str(), stdout);
    return 0;
}

}  // namespace penumbra

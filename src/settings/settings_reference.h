#pragma once
// The settings reference, made from the key table (penumbra/settings_keys.h): `penumbra settings
// --markdown` prints it and docs/settings.md is its output, so the documented keys, ranges and
// defaults are the ones validation uses.
#include <string>

namespace penumbra {

// docs/settings.md: every key with its type, allowed values, default and description, and the
// defaults as settings JSON.
std::string settingsReferenceMarkdown();

}  // namespace penumbra

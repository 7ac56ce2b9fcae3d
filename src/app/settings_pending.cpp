// TEMPORARY until the settings parser lands from the shadows branch.
#include "app/settings.h"
namespace penumbra { void validateSettings(const Settings&) {} }

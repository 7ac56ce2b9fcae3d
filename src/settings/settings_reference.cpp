#include "penumbra/settings_keys.h"

#include <cctype>
#include <sstream>

#include <nlohmann/json.hpp>

#include "penumbra/settings.h"

namespace penumbra {

namespace {

const char* typeName(SettingType type) {
    switch (type) {
        case SettingType::Number: return "number";
        case SettingType::Integer:
        case SettingType::PowerOfTwo: return "integer";
        case SettingType::Bool: return "bool";
        case SettingType::Choice: return "string";
        case SettingType::Ratios: return "3 numbers";
    }
    return "?";
}

std::string code(const std::string& text) { return "`" + text + "`"; }

// The allowed values as the reference shows them: each choice in code, a range as validation words it.
std::string allowedText(const SettingKey& key) {
    if (key.type != SettingType::Choice) return key.allowed;
    std::string text;
    for (const std::string& name : key.choices) text += (text.empty() ? "" : ", ") + code(name);
    return text;
}

// A key's value in `settings` as JSON text, read from settingsToJson so that the reference shows
// what a settings file holds ("log", 0.1, [0.1, 0.25, 0.5]).
std::string valueText(const nlohmann::json& settingsJson, const SettingKey& key) {
    const nlohmann::json* value = &settingsJson;
    std::stringstream path(key.key);
    for (std::string part; std::getline(path, part, '.');) value = &value->at(part);
    if (!value->is_array()) return value->dump();
    std::string text;
    for (const nlohmann::json& element : *value) text += (text.empty() ? "" : ", ") + element.dump();
    return "[" + text + "]";
}

// GitHub's anchor of a heading that is a dotted key: lower case, dots dropped.
std::string anchor(const std::string& key) {
    std::string text;
    for (char c : key)
        if (std::isalnum(static_cast<unsigned char>(c))) text += char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

std::string group(const std::string& key) { return key.substr(0, key.rfind('.')); }

}  // namespace

std::string settingsReferenceMarkdown() {
    const std::string defaultsJson = settingsToJson(Settings{});
    const nlohmann::json defaults = nlohmann::json::parse(defaultsJson);
    std::ostringstream out;
    out << "# Settings reference\n\n"
           "_Generated from the key table in `src/settings/settings_keys.cpp` by `penumbra settings --markdown > "
           "docs/settings.md`: edit the table, then run that command (a unit test fails while this file differs "
           "from its output)._\n\n"
           "These are the keys of the settings JSON that `--settings FILE` reads, that `--set key=value` overrides "
           "(in `penumbra` and `penumbra-viewer`) and that the viewer's settings inspector edits. Every key is "
           "optional; an unknown key, a value of the wrong type or out of range is an error that names the key "
           "and its allowed values. A dotted key is a path through nested objects: `shadows.directional.cascadeCount` "
           "is `{\"shadows\": {\"directional\": {\"cascadeCount\": 2}}}`. The file format is in "
           "[scene-format.md](scene-format.md#settings-json).\n\n"
           "| key | type | allowed | default |\n| --- | --- | --- | --- |\n";
    for (const SettingKey& key : settingKeys())
        out << "| [" << code(key.key) << "](#" << anchor(key.key) << ") | " << typeName(key.type) << " | "
            << allowedText(key) << " | " << code(valueText(defaults, key)) << " |\n";
    std::string currentGroup;
    for (const SettingKey& key : settingKeys()) {
        if (group(key.key) != currentGroup) {
            currentGroup = group(key.key);
            out << "\n## " << currentGroup << "\n";
        }
        out << "\n### " << key.key << "\n\n"
            << "Type: " << typeName(key.type) << ". Allowed: " << allowedText(key) << ". Default: "
            << code(valueText(defaults, key)) << ".\n\n"
            << key.description << "\n";
    }
    out << "\n## Defaults\n\n`penumbra settings --json` prints every key with its default, as a settings file:\n\n"
           "```json\n"
        << defaultsJson << "\n```\n";
    return out.str();
}

}  // namespace penumbra

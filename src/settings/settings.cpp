#include "penumbra/settings.h"

#include "penumbra/settings_keys.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/json_depth.h"
#include "penumbra/files.h"

namespace penumbra {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& message) { throw Error("settings: " + message); }

// Settings nest 3 levels at most; a deeper text is refused before anything recursive (a message's
// dump of the value) walks it: "[[[[..." a few hundred kilobytes deep would overflow the stack.
constexpr size_t kMaxJsonDepth = 16;

void checkDepth(const std::string& text, const std::string& origin) {
    if (jsonNestingDepth(text, kMaxJsonDepth) > kMaxJsonDepth)
        fail(origin + " nests arrays and objects more than " + std::to_string(kMaxJsonDepth) + " levels deep");
}

// A value as JSON text for messages; bytes that are not UTF-8 (a --set value is any text) become
// U+FFFD instead of an exception.
std::string show(const json& value) { return value.dump(-1, ' ', false, json::error_handler_t::replace); }

// Text from the user (a key, a --set argument) as it may appear in a one-line message: as typed when
// it is plain printable ASCII, else JSON-quoted with escapes (newlines, control and non-UTF-8 bytes).
std::string showText(const std::string& text) {
    const bool plain = std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7F; });
    return plain ? text : show(json(text));
}

[[noreturn]] void failType(const std::string& key, const json& value, const char* expected) {
    fail(showText(key) + " = " + show(value) + " has the wrong type (expected " + expected + ")");
}

float readFloat(const std::string& key, const json& value) {
    if (!value.is_number()) failType(key, value, "a number");
    return float(value.get<double>());  // too large for a float becomes inf: caught by validation
}

// Integers are range-checked here already, so that -1 or 2^40 never wrap into the uint32_t field.
uint32_t readUint(const std::string& key, const json& value, const char* allowed) {
    if (!value.is_number_integer()) failType(key, value, "an integer");
    const bool fits = value.is_number_unsigned() ? value.get<uint64_t>() <= UINT32_MAX : false;
    if (!fits) fail(key + " = " + show(value) + " is out of range (allowed " + allowed + ")");
    return uint32_t(value.get<uint64_t>());
}

bool readBool(const std::string& key, const json& value) {
    if (!value.is_boolean()) failType(key, value, "true or false");
    return value.get<bool>();
}

// A string setting that names one of `key.choices`: its index, or an error listing them.
double readChoice(const SettingKey& key, const json& value) {
    if (!value.is_string()) failType(key.key, value, "a string");
    for (size_t i = 0; i < key.choices.size(); ++i)
        if (value.get<std::string>() == key.choices[i]) return double(i);
    fail(std::string(key.key) + " = " + show(value) + " is out of range (allowed " + key.allowed + ")");
}

// One leaf of the settings JSON into its field, by the table's type (ranges: validateSettings).
void assignLeaf(Settings& settings, const SettingKey& key, const json& value) {
    const std::string name = key.key;
    switch (key.type) {
        case SettingType::Number: key.set(settings, 0, readFloat(name, value)); break;
        case SettingType::Integer:
        case SettingType::PowerOfTwo: key.set(settings, 0, readUint(name, value, key.allowed.c_str())); break;
        case SettingType::Bool: key.set(settings, 0, readBool(name, value)); break;
        case SettingType::Choice: key.set(settings, 0, readChoice(key, value)); break;
        case SettingType::Ratios: {
            if (!value.is_array() || value.size() != 3) failType(name, value, "an array of 3 numbers");
            for (size_t i = 0; i < 3; ++i) key.set(settings, i, readFloat(name + "[" + std::to_string(i) + "]", value[i]));
            break;
        }
    }
}

const char* const kObjectKeys[] = {"shadows", "shadows.directional", "shadows.spot", "shadows.virtual", "render"};

bool isObjectKey(const std::string& key) {
    for (const char* objectKey : kObjectKeys) {
        if (key == objectKey) return true;
    }
    return false;
}

void assignKey(Settings& settings, const std::string& key, const json& value);

void assignObject(Settings& settings, const std::string& prefix, const json& object) {
    for (const auto& [name, value] : object.items()) {
        assignKey(settings, prefix.empty() ? name : prefix + "." + name, value);
    }
}

void assignKey(Settings& settings, const std::string& key, const json& value) {
    if (const SettingKey* leaf = findSettingKey(key)) {
        assignLeaf(settings, *leaf, value);
        if (!settings.userSet(key)) settings.userKeys.push_back(key);
    } else if (isObjectKey(key)) {
        if (!value.is_object()) failType(key, value, "an object");
        assignObject(settings, key, value);
    } else {
        fail("unknown key " + showText(key));
    }
}

std::string trim(const std::string& text) {
    const size_t begin = text.find_first_not_of(" \t");
    if (begin == std::string::npos) return "";
    const size_t end = text.find_last_not_of(" \t");
    return text.substr(begin, end - begin + 1);
}

// nlohmann's parse error, e.g. "syntax error while parsing object - unexpected end of input; expected
// string literal" at "byte 12", made one line.
json parseJson(const std::string& jsonText, const std::string& origin) {
    checkDepth(jsonText, origin);
    try {
        return json::parse(jsonText);
    } catch (const json::parse_error& error) {
        std::string detail = error.what();
        const size_t colon = detail.find(": ");  // "[json.exception.parse_error.101] parse error at line 1, column 3: ..."
        if (colon != std::string::npos) detail = detail.substr(colon + 2);
        for (char& c : detail)
            if (c == '\n' || c == '\r') c = ' ';
        throw Error("settings: " + origin + " is not valid JSON (byte " + std::to_string(error.byte) + ": " + detail + ")");
    } catch (const json::exception& error) {  // out_of_range 406: a number too large for a double
        std::string detail = error.what();
        const size_t bracket = detail.find("] ");
        if (bracket != std::string::npos) detail = detail.substr(bracket + 2);
        throw Error("settings: " + origin + " is not valid JSON (" + showText(detail) + ")");
    }
}

}  // namespace

Settings parseSettingsJson(const std::string& jsonText, const std::string& origin) {
    const json root = parseJson(jsonText, origin);
    if (!root.is_object()) throw Error("settings: " + origin + " must hold a JSON object");
    Settings settings;
    try {
        assignObject(settings, "", root);
        validateSettings(settings);
    } catch (const Error& error) {
        throw Error(std::string(error.what()) + " (in " + origin + ")");
    }
    return settings;
}

Settings loadSettingsFile(const std::string& path) {
    std::string text;
    try {
        text = readTextFile(path);
    } catch (const Error& e) {
        throw Error(std::string("settings: ") + e.what());
    }
    return parseSettingsJson(text, path);
}

void applySettingOverride(Settings& settings, const std::string& assignment) {
    const size_t equals = assignment.find('=');
    if (equals == std::string::npos) fail("a setting override expects key=value, got '" + showText(assignment) + "'");
    const std::string key = trim(assignment.substr(0, equals));
    const std::string valueText = trim(assignment.substr(equals + 1));
    checkDepth(valueText, "the --set value");
    // JSON when it parses (numbers, true, [0.1,0.2,0.3], "quoted"), else the raw text as a string (PCF5x5).
    json value = json::parse(valueText, nullptr, /*allow_exceptions=*/false);
    if (value.is_discarded()) value = valueText;
    Settings updated = settings;
    assignKey(updated, key, value);
    validateSettings(updated);
    settings = updated;
}

bool Settings::userSet(const std::string& key) const {
    return std::find(userKeys.begin(), userKeys.end(), key) != userKeys.end();
}

}  // namespace penumbra

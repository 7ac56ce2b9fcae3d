// The table of every settings key (penumbra/settings_keys.h) and the viewer's inspector edits that it
// drives: every value an inspector widget offers survives Save settings (settingsToJson) and
// penumbra render --settings (parseSettingsJson), and what validation rejects the inspector rejects.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "penumbra/settings.h"
#include "penumbra/error.h"
#include "penumbra/settings_keys.h"
#include "viewer/settings_edit.h"

using namespace penumbra;

namespace {

void expectSameValues(const Settings& a, const Settings& b, const std::string& context) {
    for (const SettingKey& key : settingKeys())
        for (size_t i = 0; i < key.elements(); ++i)
            EXPECT_EQ(key.get(a, i), key.get(b, i)) << key.key << "[" << i << "] after " << context;
}

Settings roundTrip(const Settings& settings) { return parseSettingsJson(settingsToJson(settings), "saved.json"); }

}  // namespace

TEST(SettingsKeys, SavedJsonHoldsEveryKeyOfTheTable) {
    const nlohmann::json saved = nlohmann::json::parse(settingsToJson(Settings{}));
    for (const SettingKey& key : settingKeys()) {
        std::string pointer = std::string("/") + key.key;
        for (char& c : pointer)
            if (c == '.') c = '/';
        EXPECT_TRUE(saved.contains(nlohmann::json::json_pointer(pointer))) << key.key;
    }
    EXPECT_EQ(roundTrip(Settings{}).userKeys.size(), settingKeys().size());
}

TEST(SettingsKeys, DefaultsRoundTripThroughSavedJson) { expectSameValues(roundTrip(Settings{}), Settings{}, "defaults"); }

TEST(SettingsKeys, EveryValueTheInspectorOffersRoundTripsThroughSavedJson) {
    size_t edits = 0;
    for (const SettingKey& key : settingKeys()) {
        for (size_t i = 0; i < key.elements(); ++i) {
            for (double value : viewer::inspectorValues(key)) {
                Settings edited;
                const std::string error = viewer::applyInspectorEdit(edited, key, i, value);
                ASSERT_EQ(error, "") << key.key << " = " << value;
                EXPECT_EQ(key.get(edited, i), double(float(value))) << key.key;
                expectSameValues(roundTrip(edited), edited, std::string(key.key) + " = " + std::to_string(value));
                ++edits;
            }
        }
    }
    EXPECT_GT(edits, settingKeys().size() * 2);
}

TEST(SettingsKeys, InspectorRejectsWhatValidationRejects) {
    for (const SettingKey& key : settingKeys()) {
        if (key.type == SettingType::Bool || key.type == SettingType::Choice) {
            Settings settings;
            EXPECT_NE(viewer::applyInspectorEdit(settings, key, 0, key.max + 1.0), "") << key.key;
            continue;
        }
        const double below = key.min - (key.type == SettingType::Number || key.type == SettingType::Ratios ? 0.5 : 1.0);
        Settings settings;
        const std::string error = viewer::applyInspectorEdit(settings, key, 0, key.minExclusive ? key.min : below);
        EXPECT_NE(error.find(key.key), std::string::npos) << key.key << ": " << error;
        expectSameValues(settings, Settings{}, std::string("a rejected ") + key.key);
    }
}

TEST(SettingsKeys, ARatioPushesItsNeighboursInsteadOfCrossingThem) {
    Settings settings;
    const SettingKey& ratios = *findSettingKey("shadows.directional.cascadeRatios");
    ASSERT_EQ(viewer::applyInspectorEdit(settings, ratios, 0, 0.8), "");
    EXPECT_FLOAT_EQ(settings.shadows.directional.cascadeRatios[1], 0.8f);
    EXPECT_FLOAT_EQ(settings.shadows.directional.cascadeRatios[2], 0.8f);
    EXPECT_NO_THROW(validateSettings(settings));
}

TEST(SettingsKeys, TableRangesAreTheValidationRanges) {
    for (const SettingKey& key : settingKeys()) {
        if (key.type == SettingType::Choice || key.type == SettingType::Bool) continue;
        Settings settings;
        key.set(settings, 0, key.max * 2.0 + 1.0);
        EXPECT_THROW(validateSettings(settings), Error) << key.key;
        if (key.max < 1e30) {
            Settings atMax;
            key.set(atMax, 0, key.max);
            for (size_t i = 1; i < key.elements(); ++i) key.set(atMax, i, key.max);
            EXPECT_NO_THROW(validateSettings(atMax)) << key.key;
        }
    }
}

TEST(SaveSettingsFile, WritesJsonThatLoadSettingsFileReadsBackAsTheSameSettings) {
    Settings edited;
    const SettingKey* count = nullptr;
    for (const SettingKey& key : settingKeys())
        if (std::string(key.key) == "shadows.directional.cascadeCount") count = &key;
    ASSERT_NE(count, nullptr);
    ASSERT_EQ(viewer::applyInspectorEdit(edited, *count, 0, 2.0), "");
    edited.shadows.maxDistance = 37.5f;
    const std::string path = ::testing::TempDir() + "penumbra_saved_settings.json";
    ASSERT_EQ(viewer::saveSettingsFile(edited, path), "");
    const Settings loaded = loadSettingsFile(path);
    expectSameValues(loaded, edited, "saveSettingsFile and loadSettingsFile");
    EXPECT_EQ(loaded.shadows.directional.cascadeCount, 2u);
    EXPECT_EQ(loaded.shadows.maxDistance, 37.5f);
}

TEST(SaveSettingsFile, UnwritablePathIsOneError) {
    const std::string path = "/nonexistent-directory/settings.json";
    const std::string error = viewer::saveSettingsFile(Settings{}, path);
    EXPECT_NE(error.find(path), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

// The settings reference (docs/settings.md) is the generator's output, made from the key table, so
// the documented keys, ranges and defaults cannot drift from the ones validation uses.
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "penumbra/settings.h"
#include "penumbra/settings_keys.h"

using namespace penumbra;

namespace {

std::string readFile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

}  // namespace

TEST(SettingsReference, DocsFileIsTheGeneratorsOutput) {
    const std::string path = std::string(PENUMBRA_TEST_DATA_DIR) + "/../docs/settings.md";
    const std::string documented = readFile(path);
    ASSERT_FALSE(documented.empty()) << path << " is missing";
    EXPECT_TRUE(documented == settingsReferenceMarkdown())
        << path << " differs from the key table: run `./build/penumbra settings --markdown > docs/settings.md`";
}

TEST(SettingsReference, EveryKeyHasADescriptionAndASection) {
    const std::string reference = settingsReferenceMarkdown();
    for (const SettingKey& key : settingKeys()) {
        EXPECT_GT(key.description.size(), 20u) << key.key;
        EXPECT_EQ(key.description.find('|'), std::string::npos) << key.key << ": a '|' breaks the table";
        EXPECT_NE(reference.find("\n### " + std::string(key.key) + "\n"), std::string::npos) << key.key;
    }
}

TEST(SettingsReference, ShowsEachDefaultAsASettingsFileHoldsIt) {
    const std::string reference = settingsReferenceMarkdown();
    EXPECT_NE(reference.find("Default: `\"receiverPlane\"`."), std::string::npos);
    EXPECT_NE(reference.find("Default: `[0.1, 0.25, 0.5]`."), std::string::npos);
    EXPECT_NE(reference.find("Default: `1024`."), std::string::npos);
    EXPECT_NE(reference.find("Allowed: a power of two in 256..8192."), std::string::npos);
    // The JSON block at the end is `penumbra settings --json`, and it reads back as the defaults.
    EXPECT_NE(reference.find("```json\n" + settingsToJson(Settings{}) + "\n```\n"), std::string::npos);
    EXPECT_EQ(settingsToJson(parseSettingsJson(settingsToJson(Settings{}), "defaults")), settingsToJson(Settings{}));
}

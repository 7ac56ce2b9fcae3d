// `penumbra settings` as a user runs it: the Markdown is the settings reference (docs/settings.md's
// generator), the JSON is every default as a settings file.
#include <string>

#include <gtest/gtest.h>

#include "cli_process.h"
#include "penumbra/settings.h"
#include "penumbra/settings_keys.h"

using namespace penumbra;
using namespace penumbra::test;

TEST(CliSettings, MarkdownIsTheSettingsReference) {
    for (const char* arguments : {"settings", "settings --markdown"}) {
        const CliRun run = runPenumbra(arguments);
        EXPECT_EQ(run.exitCode, 0) << arguments << ": " << run.err;
        EXPECT_TRUE(run.out == settingsReferenceMarkdown()) << arguments;
        EXPECT_EQ(run.err, "") << arguments;
    }
}

TEST(CliSettings, JsonIsEveryDefaultAsASettingsFile) {
    const CliRun run = runPenumbra("settings --json");
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.out, settingsToJson(Settings{}) + "\n");
    const Settings read = parseSettingsJson(run.out, "penumbra settings --json");
    EXPECT_EQ(settingsToJson(read), settingsToJson(Settings{}));
    EXPECT_EQ(read.userKeys.size(), settingKeys().size()) << "every key is in the file";
}

TEST(CliSettings, MarkdownAndJsonTogetherIsOneLineError) {
    expectOneLineError(runPenumbra("settings --markdown --json"), "--json");
}

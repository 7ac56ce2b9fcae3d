// `penumbra --version` as a user runs it: the version of the headers and of the library.
#include <string>

#include <gtest/gtest.h>

#include "cli_process.h"
#include "penumbra/version.h"

using namespace penumbra;
using namespace penumbra::test;

TEST(CliVersion, PrintsTheVersionOfTheHeadersAndTheLibrary) {
    const CliRun run = runPenumbra("--version");
    EXPECT_EQ(run.exitCode, 0) << run.err;
    EXPECT_EQ(run.out, std::string("penumbra ") + PENUMBRA_VERSION_STRING + "\n");
    EXPECT_EQ(run.out, std::string("penumbra ") + version() + "\n");
    EXPECT_EQ(run.err, "");
}

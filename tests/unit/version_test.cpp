// The version: CMake's project version in the generated <penumbra/version.h>, and the library's.
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "penumbra/penumbra.h"

TEST(Version, LibraryVersionIsTheHeaders) { EXPECT_STREQ(penumbra::version(), PENUMBRA_VERSION_STRING); }

TEST(Version, StringIsMajorMinorPatch) {
    const std::string expected = std::to_string(PENUMBRA_VERSION_MAJOR) + "." + std::to_string(PENUMBRA_VERSION_MINOR) +
                                 "." + std::to_string(PENUMBRA_VERSION_PATCH);
    EXPECT_EQ(std::string(PENUMBRA_VERSION_STRING), expected);
    EXPECT_EQ(expected, PENUMBRA_PROJECT_VERSION);  // project(VERSION) in CMakeLists.txt, passed by tests/CMakeLists.txt
}

// The viewer's scene-file watcher (src/viewer/file_watcher.h): a fake file system and clock, so each
// rule is checked without waiting; one test on a real file.
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "gltf_test_files.h"
#include "viewer/file_watcher.h"

using namespace penumbra::viewer;
using namespace std::chrono_literals;
using Clock = FileWatcher::Clock;

namespace {

// A file system of stamps; a missing entry is a missing file. Counts the stats.
struct FakeFiles {
    std::map<std::string, FileStamp> stamps;
    int stats = 0;
    FileWatcher::StatFunction stat() {
        return [this](const std::filesystem::path& path) -> std::optional<FileStamp> {
            ++stats;
            const auto it = stamps.find(path.string());
            if (it == stamps.end()) return std::nullopt;
            return it->second;
        };
    }
    void write(const std::string& path, int64_t tick, uintmax_t size) {
        stamps[path] = FileStamp{std::filesystem::file_time_type(std::chrono::nanoseconds(tick)), size};
    }
};

// Polls at t0, t0 + step, ... and returns the index of each poll that reported a change.
struct Polls {
    FileWatcher& watcher;
    Clock::time_point now{};
    bool next(std::chrono::milliseconds step = 100ms) {
        now += step;
        return watcher.poll(now);
    }
};

}  // namespace

TEST(FileWatcher, UnchangedFileIsNeverReported) {
    FakeFiles files;
    files.write("scene.gltf", 1, 100);
    FileWatcher watcher("scene.gltf", 0ms, files.stat());
    Polls polls{watcher};
    for (int i = 0; i < 5; ++i) EXPECT_FALSE(polls.next()) << i;
}

TEST(FileWatcher, ChangeIsReportedOnceWhenItHeldForTwoPolls) {
    FakeFiles files;
    files.write("scene.gltf", 1, 100);
    FileWatcher watcher("scene.gltf", 0ms, files.stat());
    Polls polls{watcher};
    EXPECT_FALSE(polls.next());
    files.write("scene.gltf", 2, 100);  // same size, newer time
    EXPECT_FALSE(polls.next()) << "the first poll that sees the change waits for the file to settle";
    EXPECT_TRUE(polls.next());
    EXPECT_FALSE(polls.next()) << "a change is reported once";
    files.write("scene.gltf", 2, 120);  // same time, other size
    EXPECT_FALSE(polls.next());
    EXPECT_TRUE(polls.next());
}

TEST(FileWatcher, FileStillBeingWrittenIsReportedWhenItSettles) {
    FakeFiles files;
    files.write("scene.gltf", 1, 100);
    FileWatcher watcher("scene.gltf", 0ms, files.stat());
    Polls polls{watcher};
    for (int i = 2; i < 6; ++i) {
        files.write("scene.gltf", i, uintmax_t(100 * i));  // grows between every two polls
        EXPECT_FALSE(polls.next()) << i;
    }
    EXPECT_TRUE(polls.next());
}

TEST(FileWatcher, MissingFileIsNoChangeAndItsReturnIsOne) {
    FakeFiles files;
    files.write("scene.gltf", 1, 100);
    FileWatcher watcher("scene.gltf", 0ms, files.stat());
    Polls polls{watcher};
    files.stamps.clear();  // an editor's save: delete, then rename the new file into place
    EXPECT_FALSE(polls.next());
    EXPECT_FALSE(polls.next());
    files.write("scene.gltf", 1, 100);  // back as it was: nothing to reload
    EXPECT_FALSE(polls.next());
    EXPECT_FALSE(polls.next());
    files.stamps.clear();
    EXPECT_FALSE(polls.next());
    files.write("scene.gltf", 3, 100);
    EXPECT_FALSE(polls.next());
    EXPECT_TRUE(polls.next());
}

TEST(FileWatcher, StatsNoMoreOftenThanTheInterval) {
    FakeFiles files;
    files.write("scene.gltf", 1, 100);
    FileWatcher watcher("scene.gltf", 250ms, files.stat());
    EXPECT_EQ(files.stats, 1);  // the loaded version
    Polls polls{watcher};
    for (int i = 0; i < 10; ++i) polls.next(100ms);  // 1 s
    EXPECT_EQ(files.stats, 1 + 4) << "one stat per 250 ms (at 0.1, 0.4, 0.7, 1.0 s)";
    files.write("scene.gltf", 2, 100);
    int polled = 0;
    while (!polls.next(100ms)) ASSERT_LT(++polled, 10);
    EXPECT_GE(polled, 2) << "two stats 250 ms apart see the change";
}

TEST(FileWatcher, MarkLoadedTakesTheProgramsOwnWrite) {
    FakeFiles files;
    files.write("scene.gltf", 1, 100);
    FileWatcher watcher("scene.gltf", 0ms, files.stat());
    Polls polls{watcher};
    files.write("scene.gltf", 2, 140);  // the viewer saved the scene over its own file
    watcher.markLoaded();
    EXPECT_FALSE(polls.next());
    EXPECT_FALSE(polls.next());
}

TEST(FileWatcher, EmptyPathWatchesNothing) {
    FakeFiles files;
    FileWatcher watcher("", 0ms, files.stat());
    Polls polls{watcher};
    EXPECT_FALSE(polls.next());
    EXPECT_EQ(files.stats, 0);
}

TEST(FileWatcher, SeesARealFileGrow) {
    penumbra::testing::TempDir dir;
    const std::string path = dir.file("scene.gltf");
    penumbra::testing::writeFile(path, "{}");
    FileWatcher watcher(path, 0ms);
    Polls polls{watcher};
    EXPECT_FALSE(polls.next());
    penumbra::testing::writeFile(path, "{\"asset\": {\"version\": \"2.0\"}}");
    EXPECT_FALSE(polls.next());
    EXPECT_TRUE(polls.next());
    EXPECT_FALSE(statFile(dir.file("missing.gltf")).has_value());
}

#pragma once
// Watches one file for changes by polling its modification time and size (no inotify: it works the
// same on every file system, and a poll is one stat). A change is reported once the file has kept its
// new stamp for two polls in a row, so a file an editor or exporter is still writing is read when it
// is complete. The stat function and the clock are parameters, so the logic is unit-tested without a
// file system or waiting.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>

namespace penumbra::viewer {

struct FileStamp {
    std::filesystem::file_time_type modified{};
    uintmax_t size = 0;
    bool operator==(const FileStamp&) const = default;
};

// The stamp of a regular file, or nullopt when there is none (missing, being replaced, not a file).
std::optional<FileStamp> statFile(const std::filesystem::path& path);

class FileWatcher {
public:
    using Clock = std::chrono::steady_clock;
    using StatFunction = std::function<std::optional<FileStamp>(const std::filesystem::path&)>;

    FileWatcher() = default;  // watches nothing
    // `pollInterval`: the least time between two stats (0: every poll()). Takes the file's stamp now
    // as the loaded version.
    FileWatcher(std::filesystem::path path, std::chrono::milliseconds pollInterval, StatFunction stat = statFile);

    // True once per change of the file since the last markLoaded() (or the last change reported).
    bool poll(Clock::time_point now);
    // The file on disk is the version in memory (after the program loaded or wrote it itself).
    void markLoaded();
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
    std::chrono::milliseconds interval_{0};
    StatFunction stat_;
    std::optional<FileStamp> loaded_, candidate_;
    std::optional<Clock::time_point> lastPoll_;
};

}  // namespace penumbra::viewer

#include "viewer/file_watcher.h"

#include <utility>

namespace penumbra::viewer {

std::optional<FileStamp> statFile(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error) || error) return std::nullopt;
    FileStamp stamp;
    stamp.modified = std::filesystem::last_write_time(path, error);
    if (error) return std::nullopt;
    stamp.size = std::filesystem::file_size(path, error);
    if (error) return std::nullopt;
    return stamp;
}

FileWatcher::FileWatcher(std::filesystem::path path, std::chrono::milliseconds pollInterval, StatFunction stat)
    : path_(std::move(path)), interval_(pollInterval), stat_(std::move(stat)) {
    markLoaded();
}

void FileWatcher::markLoaded() {
    if (path_.empty() || !stat_) return;
    loaded_ = stat_(path_);
    candidate_.reset();
}

bool FileWatcher::poll(Clock::time_point now) {
    if (path_.empty() || !stat_) return false;
    if (lastPoll_ && now - *lastPoll_ < interval_) return false;
    lastPoll_ = now;
    const std::optional<FileStamp> stamp = stat_(path_);
    if (!stamp || stamp == loaded_) {  // missing (e.g. mid-replace) or unchanged
        candidate_.reset();
        return false;
    }
    if (candidate_ != stamp) {  // new, or still being written: wait for one more poll
        candidate_ = stamp;
        return false;
    }
    loaded_ = stamp;
    candidate_.reset();
    return true;
}

}  // namespace penumbra::viewer

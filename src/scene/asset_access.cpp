#include "scene/asset_access.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "scene/load_budget.h"

namespace penumbra {

namespace fs = std::filesystem;

namespace {

FileOpenObserver gObserver = nullptr;

constexpr const char* kAllowed = "only paths relative to the scene's folder and data: URIs are allowed";

// The reference as the message shows it: quoted, control characters as '?' so that it stays one line,
// a long one (a data: URI) cut short.
std::string quoted(const std::string& reference) {
    std::string text = "external file '";
    for (size_t i = 0; i < std::min<size_t>(reference.size(), 100); ++i)
        text += std::iscntrl(static_cast<unsigned char>(reference[i])) ? '?' : reference[i];
    return text + (reference.size() > 100 ? "...'" : "'");
}

// "file", "http", "data", ... for "scheme:rest" (RFC 3986: a letter, then letters, digits, + - .); "" for none.
std::string schemeOf(const std::string& reference) {
    const size_t colon = reference.find(':');
    if (colon == std::string::npos || colon == 0 || !std::isalpha(static_cast<unsigned char>(reference[0]))) return "";
    for (size_t i = 1; i < colon; ++i) {
        const char c = reference[i];
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return "";
    }
    return reference.substr(0, colon);
}

bool isInside(const fs::path& path, const fs::path& root) {
    const auto [rootEnd, pathAt] = std::mismatch(root.begin(), root.end(), path.begin(), path.end());
    (void)pathAt;
    return rootEnd == root.end();
}

// A folder made canonical; `what` names it in the error ("the asset root", "the scene folder").
fs::path canonicalFolder(const std::string& folder, const std::string& what) {
    std::error_code error;
    const fs::path path = fs::canonical(folder.empty() ? fs::path(".") : fs::path(folder), error);
    if (error) throw Error(what + " " + folder + " does not exist (" + error.message() + ")");
    if (!fs::is_directory(path, error)) throw Error(what + " " + folder + " is not a folder");
    return path;
}

// Why a path that exists is not a regular file, "" when it is one.
std::string notRegular(const struct stat& status) {
    if (S_ISREG(status.st_mode)) return "";
    if (S_ISDIR(status.st_mode)) return "it is a directory";
    return "not a regular file (a device, FIFO or socket)";
}

ssize_t readSome(int fd, uint8_t* data, size_t size) {
    ssize_t n = 0;
    do n = ::read(fd, data, size);
    while (n < 0 && errno == EINTR);
    return n;
}

// The `size` bytes fstat promised; a file that shrank gives what it holds, one that grew is refused.
std::vector<uint8_t> readOpenFile(int fd, const std::string& shown, uint64_t size) {
    std::vector<uint8_t> bytes(size);
    size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = readSome(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) throw Error(shown + ": reading failed (" + std::strerror(errno) + ")");
        if (n == 0) break;
        done += size_t(n);
    }
    bytes.resize(done);
    uint8_t probe = 0;
    if (readSome(fd, &probe, 1) != 0) throw Error(shown + ": the file changed while it was read");
    return bytes;
}

}  // namespace

void setFileOpenObserver(FileOpenObserver observer) { gObserver = observer; }

std::vector<uint8_t> readRegularFile(const fs::path& path, const std::string& shown, uint64_t maxBytes,
                                     const SceneLimits& limits, bool followLastLink) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) {
        if (errno == ENOENT) throw Error(shown + ": cannot open file (it does not exist)");
        throw Error(shown + ": cannot open file (" + std::strerror(errno) + ")");
    }
    if (const std::string why = notRegular(status); !why.empty()) throw Error(shown + ": cannot open file (" + why + ")");
    if (uint64_t(status.st_size) > maxBytes)
        throw Error(shown + " is " + std::to_string(status.st_size) + " bytes, " +
                    overBudget(limits, &SceneLimits::maxFileBytes));
    if (gObserver) gObserver(path);
    // O_NONBLOCK: a FIFO put in the file's place after the check does not block the open; fstat then refuses it.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | (followLastLink ? 0 : O_NOFOLLOW));
    if (fd < 0) throw Error(shown + ": cannot open file (" + std::strerror(errno) + ")");
    try {
        struct stat opened {};
        if (::fstat(fd, &opened) != 0) throw Error(shown + ": cannot open file (" + std::strerror(errno) + ")");
        if (const std::string why = notRegular(opened); !why.empty()) throw Error(shown + ": cannot open file (" + why + ")");
        if (uint64_t(opened.st_size) > maxBytes)
            throw Error(shown + " is " + std::to_string(opened.st_size) + " bytes, " +
                        overBudget(limits, &SceneLimits::maxFileBytes));
        std::vector<uint8_t> bytes = readOpenFile(fd, shown, uint64_t(opened.st_size));
        ::close(fd);
        return bytes;
    } catch (...) {
        ::close(fd);
        throw;
    }
}

AssetAccess::AssetAccess(const std::string& sceneFolder, const std::string& assetRoot, const SceneLimits& limits)
    : folder_(canonicalFolder(sceneFolder, "the scene folder")),
      root_(assetRoot.empty() ? folder_ : canonicalFolder(assetRoot, "the asset root")), limits_(limits) {}

fs::path AssetAccess::resolve(const std::string& reference) const {
    const std::string shown = quoted(reference);
    if (reference.empty()) throw Error("an external file reference is empty");
    if (reference.find('\0') != std::string::npos) throw Error(shown + " holds a NUL byte (%00)");
    if (const std::string scheme = schemeOf(reference); !scheme.empty()) {
        std::string lower = scheme;
        for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (lower == "data") throw Error(shown + " is a data: URI that is not base64 of a type glTF allows");
        throw Error(shown + " uses the URI scheme '" + scheme + ":': " + kAllowed);
    }
    if (reference[0] == '/' || reference[0] == '\\') throw Error(shown + " is an absolute path: " + kAllowed);
    std::error_code error;
    // weakly_canonical: every symlink of the existing part resolved, then "." and ".." of the rest.
    const fs::path path = fs::weakly_canonical(folder_ / reference, error);
    if (error) throw Error(shown + " cannot be resolved (" + error.message() + ")");
    if (!isInside(path, root_))
        throw Error(shown + " resolves to " + path.string() + ", outside the asset root " + root_.string() +
                    " (a caller who trusts the scene may widen it with --asset-root, or GltfLoadOptions::assetRoot)");
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) throw Error(shown + " does not exist (" + path.string() + ")");
    if (const std::string why = notRegular(status); !why.empty())
        throw Error(shown + " is refused: " + why + ", only regular files are read");
    return path;
}

std::vector<uint8_t> AssetAccess::read(const std::string& reference) const {
    return readRegularFile(resolve(reference), quoted(reference), limits_.maxFileBytes, limits_, false);
}

}  // namespace penumbra

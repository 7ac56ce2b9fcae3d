#include "penumbra/files.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

#include "core/error.h"

namespace penumbra {

namespace {

namespace fs = std::filesystem;

// A name beside `path` that no other process (nor an earlier write of this one) uses.
std::string temporaryNameFor(const std::string& path) {
    static unsigned counter = 0;
    return path + ".tmp" + std::to_string(::getpid()) + "." + std::to_string(counter++);
}

std::string folderOf(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

}  // namespace

void writeFileAtomically(const std::string& path, const void* data, size_t size) {
    std::error_code error;
    if (fs::is_directory(path, error)) throw Error("cannot write " + path + ": it is a directory");
    const std::string temporary = temporaryNameFor(path);
    FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) throw Error("cannot write " + path + ": " + std::strerror(errno));
    const bool written = std::fwrite(data, 1, size, file) == size;
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) {
        fs::remove(temporary, error);
        throw Error("cannot write " + path + ": writing failed (disk full?)");
    }
    fs::rename(temporary, path, error);
    if (error) {
        fs::remove(temporary, error);
        throw Error("cannot write " + path + ": " + error.message());
    }
}

void writeTextFile(const std::string& path, const std::string& text) { writeFileAtomically(path, text.data(), text.size()); }

void checkWritable(const std::string& path) {
    if (path.empty() || path == "-") return;
    std::error_code error;
    if (fs::is_directory(path, error)) throw Error("cannot write " + path + ": it is a directory");
    const std::string folder = folderOf(path);
    if (!fs::is_directory(folder, error)) throw Error("cannot write " + path + ": the folder " + folder + " does not exist");
    // The same test the real write makes: create a file beside the target, then remove it.
    const std::string probe = temporaryNameFor(path);
    FILE* file = std::fopen(probe.c_str(), "wb");
    if (!file) throw Error("cannot write " + path + ": " + std::strerror(errno));
    std::fclose(file);
    fs::remove(probe, error);
}

std::vector<uint8_t> readFileBytes(const std::string& path) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (status.type() == fs::file_type::not_found) throw Error(path + ": cannot open file (it does not exist)");
    if (status.type() == fs::file_type::directory) throw Error(path + ": cannot open file (it is a directory)");
    if (status.type() != fs::file_type::regular) throw Error(path + ": cannot open file (not a regular file)");
    FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) throw Error(path + ": cannot open file (" + std::strerror(errno) + ")");
    std::vector<uint8_t> bytes;
    uint8_t chunk[1 << 16];
    size_t n = 0;
    while ((n = std::fread(chunk, 1, sizeof chunk, file)) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed) throw Error(path + ": reading failed");
    return bytes;
}

std::string readTextFile(const std::string& path) {
    const std::vector<uint8_t> bytes = readFileBytes(path);
    return std::string(bytes.begin(), bytes.end());
}

}  // namespace penumbra

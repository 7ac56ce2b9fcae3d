#include "core/files.h"

#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "core/error.h"

namespace penumbra {

void writeFileAtomically(const std::string& path, const void* data, size_t size) {
    const std::string temporary = path + ".tmp" + std::to_string(::getpid());
    FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) throw Error("cannot write " + path + ": the file could not be created");
    const bool written = std::fwrite(data, 1, size, file) == size;
    const bool closed = std::fclose(file) == 0;
    std::error_code error;
    if (!written || !closed) {
        std::filesystem::remove(temporary, error);
        throw Error("cannot write " + path + ": writing failed (disk full?)");
    }
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw Error("cannot write " + path + ": " + error.message());
    }
}

void writeTextFile(const std::string& path, const std::string& text) { writeFileAtomically(path, text.data(), text.size()); }

}  // namespace penumbra

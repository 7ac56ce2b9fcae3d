#pragma once
// Output files are written whole or not at all: into a temporary name beside the target, then
// renamed over it, so an interrupted or failed write never leaves a half-written file.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

// Throws penumbra::Error naming the path when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);
void writeFileAtomically(const std::string& path, const void* data, size_t size);

// Fails early, before any long work, when `path` can't be written: it names a directory, its folder
// does not exist, or a file can't be created there. Creates nothing that stays behind ("" and "-"
// pass).
void checkWritable(const std::string& path);

// The whole content of a regular file. Throws Error "<path>: <why>" when it can't be opened, is a
// directory or a device, or can't be read whole.
std::vector<uint8_t> readFileBytes(const std::string& path);
std::string readTextFile(const std::string& path);

}  // namespace penumbra

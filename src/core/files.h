#pragma once
// Output files are written whole or not at all: into a temporary name beside the target, then
// renamed over it, so an interrupted or failed write never leaves a half-written file.
#include <string>

namespace penumbra {

// Throws penumbra::Error naming the path when it cannot be written.
void writeTextFile(const std::string& path, const std::string& text);
void writeFileAtomically(const std::string& path, const void* data, size_t size);

}  // namespace penumbra

// glTF bytes to a tinygltf::Model: the checks made before tinygltf sees the bytes (the GLB header, the
// JSON's nesting), every external file read through AssetAccess, every image decoded by our own
// decoder within the budgets.
#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/image_decode.h"
#include "core/json_depth.h"
#include "scene/asset_access.h"
#include "scene/gltf_internal.h"
#include "scene/load_budget.h"

namespace penumbra::gltf {
namespace {

// What tinygltf's callbacks see (their user data).
struct ParseState {
    const AssetAccess* access;  // nullptr: no external file is read
    LoadBudget& budget;
};

// tinygltf's messages span several lines; ours are one line.
std::string oneLine(const std::string& text) {
    std::string line;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            if (!line.empty() && line.back() != ' ') line += "; ";
        } else {
            line += c;
        }
    }
    while (!line.empty() && (line.back() == ' ' || line.back() == ';')) line.pop_back();
    return line;
}

// nlohmann's "[json.exception.parse_error.101] parse error at ..." without the tag.
std::string withoutJsonTags(std::string text) {
    for (size_t at = text.find("[json.exception."); at != std::string::npos; at = text.find("[json.exception.", at)) {
        const size_t end = text.find("] ", at);
        if (end == std::string::npos) break;
        text.erase(at, end + 2 - at);
    }
    return text;
}

// The size the image's header promises, checked against the budgets before anything is decoded: a
// PNG header claiming 60000x60000 is refused here. A bad header is the decoder's message (false).
bool chargeImage(const uint8_t* bytes, size_t size, const std::string& what, LoadBudget& budget, std::string* err) {
    ImageHeader header;
    try {
        header = readImageHeader(bytes, size, what);
    } catch (const Error& e) {
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
    const uint64_t decoded = uint64_t(header.width) * header.height * 4;
    const std::string image = what + " (" + std::to_string(header.width) + "x" + std::to_string(header.height) + ")";
    budget.check(decoded, &SceneLimits::maxImageBytes, image + " decoded to RGBA8");
    budget.charge(decoded, &SceneLimits::maxTextureBytes, image);
    return true;
}

// Decodes every image to RGBA8 with our own decoder so that a bad image is a clean error, and a
// problem the decoder recovered from is a warning.
bool decodeImage(tinygltf::Image* image, const int imageIndex, std::string* err, std::string* warn, int, int,
                 const unsigned char* bytes, int size, void* user) {
    const std::string what = "image " + std::to_string(imageIndex);
    const size_t length = size_t(std::max(size, 0));
    if (!chargeImage(bytes, length, what, static_cast<ParseState*>(user)->budget, err)) return false;
    try {
        std::vector<std::string> warnings;
        Image rgba = decodePngOrJpeg(bytes, length, 4, what, &warnings);
        for (const std::string& warning : warnings)
            if (warn) *warn += warning + "\n";
        image->width = int(rgba.width);
        image->height = int(rgba.height);
        image->component = 4;
        image->bits = 8;
        image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        image->image = std::move(rgba.pixels);
        return true;
    } catch (const Error& e) {
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
}

// tinygltf looks for an external file under its base folder, then under "."; given "" as the base
// folder and every file "existing", it asks readReferencedFile for the reference itself (percent-
// decoded), once. AssetAccess decides.
bool everyFileExists(const std::string&, void*) { return true; }

std::string expandNothing(const std::string& path, void*) { return path; }

bool readReferencedFile(std::vector<unsigned char>* out, std::string*, const std::string& reference, void* user) {
    const ParseState& state = *static_cast<ParseState*>(user);
    if (!state.access)
        throw Error(state.budget.name() + ": external file " + reference + " is not read (the glTF is held in memory)");
    try {
        *out = state.access->read(reference);
    } catch (const Error& e) {
        throw Error(state.budget.name() + ": " + e.what());
    }
    return true;
}

bool writeNothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is not supported\n";
    return false;
}

uint32_t readU32(const uint8_t* at) {
    uint32_t value = 0;
    std::memcpy(&value, at, 4);  // GLB is little-endian, as every target of Penumbra
    return value;
}

// The GLB header and chunk headers against the bytes there are, before tinygltf reads them; returns
// the JSON chunk. A header may claim any length: none is trusted past the file's end.
std::string_view glbJson(const uint8_t* data, size_t size, const LoadBudget& budget) {
    const std::string& name = budget.name();
    if (size < 20)
        throw Error(name + ": invalid glTF: the GLB is " + std::to_string(size) + " bytes, shorter than its 20-byte header");
    const uint64_t length = readU32(data + 8), jsonLength = readU32(data + 12);
    budget.check(length, &SceneLimits::maxFileBytes, "the GLB header's length");
    if (length > size)
        throw Error(name + ": invalid glTF: the GLB header claims " + std::to_string(length) + " bytes, the file holds " +
                    std::to_string(size));
    if (20 + jsonLength > length)
        throw Error(name + ": invalid glTF: the GLB's JSON chunk claims " + std::to_string(jsonLength) + " bytes, past the " +
                    std::to_string(length) + " the header gives");
    if (20 + jsonLength + 8 <= length) {
        const uint64_t binLength = readU32(data + 20 + jsonLength);
        if (20 + jsonLength + 8 + binLength > length)
            throw Error(name + ": invalid glTF: the GLB's BIN chunk claims " + std::to_string(binLength) +
                        " bytes, past the " + std::to_string(length) + " the header gives");
    }
    return {reinterpret_cast<const char*>(data + 20), size_t(jsonLength)};
}

uint64_t unsignedOr(const nlohmann::json& object, const char* key, uint64_t fallback) {
    const auto it = object.find(key);
    return it != object.end() && it->is_number_unsigned() ? it->get<uint64_t>() : fallback;
}

// The object at `index` of the document's array `name`, or nullptr.
const nlohmann::json* elementOf(const nlohmann::json& doc, const char* name, const nlohmann::json& index) {
    const auto array = doc.find(name);
    if (array == doc.end() || !array->is_array() || !index.is_number_integer()) return nullptr;
    const int64_t at = index.get<int64_t>();
    if (at < 0 || uint64_t(at) >= array->size() || !(*array)[size_t(at)].is_object()) return nullptr;
    return &(*array)[size_t(at)];
}

// tinygltf 2.7 hands the image loader &buffer.data[view.byteOffset] and view.byteLength without
// checking them against the buffer (a fuzz finding): an image in a bufferView past its buffer's end
// would be read out of bounds. Such a file is refused before tinygltf sees it. tinygltf makes every
// buffer's data exactly its byteLength (a data: URI, a file, the GLB chunk), and reads byteOffset as 0
// when it is not an unsigned integer, as here.
void checkImageBufferViews(std::string_view text, const std::string& name) {
    const nlohmann::json doc = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
    const auto images = doc.is_object() ? doc.find("images") : doc.end();
    if (!doc.is_object() || images == doc.end() || !images->is_array()) return;  // tinygltf says what is wrong
    for (size_t i = 0; i < images->size(); ++i) {
        const nlohmann::json& image = (*images)[i];
        const auto viewIndex = image.is_object() ? image.find("bufferView") : image.end();
        if (!image.is_object() || viewIndex == image.end()) continue;
        const nlohmann::json* view = elementOf(doc, "bufferViews", *viewIndex);
        const nlohmann::json* buffer = view && view->contains("buffer") ? elementOf(doc, "buffers", (*view)["buffer"]) : nullptr;
        if (!buffer) continue;  // tinygltf refuses a missing bufferView or buffer itself
        const unsigned __int128 end = (unsigned __int128)unsignedOr(*view, "byteOffset", 0) + unsignedOr(*view, "byteLength", 0);
        const uint64_t length = unsignedOr(*buffer, "byteLength", 0);
        if (end > length)
            throw Error(name + ": invalid glTF: image " + std::to_string(i) + ": bufferView " + viewIndex->dump() +
                        " ends at byte " + std::to_string(uint64_t(std::min<unsigned __int128>(end, UINT64_MAX))) +
                        ", past the end of its buffer (" + std::to_string(length) + " bytes)");
    }
}

void checkJsonDepth(std::string_view json, const LoadBudget& budget) {
    const uint64_t limit = budget.limits().maxJsonDepth;
    const size_t depth = jsonNestingDepth(json, size_t(std::min<uint64_t>(limit, SIZE_MAX - 1)));
    if (depth > limit)
        throw Error(budget.name() + ": the JSON nests more than " + std::to_string(limit) + " levels deep, " +
                    overBudget(budget.limits(), &SceneLimits::maxJsonDepth));
}

}  // namespace

tinygltf::Model parseGltf(const uint8_t* data, size_t size, const AssetAccess* access, LoadBudget& budget,
                          std::string& warnings) {
    const std::string& name = budget.name();
    budget.check(size, &SceneLimits::maxFileBytes, "the file's size");
    // tinygltf takes 32-bit sizes.
    if (size > 0xFFFFFFFFu) throw Error(name + ": the file is larger than 4 GiB, which glTF loading does not support");
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string_view json = binary ? glbJson(data, size, budget) : std::string_view(reinterpret_cast<const char*>(data), size);
    checkJsonDepth(json, budget);
    checkImageBufferViews(json, name);
    ParseState state{access, budget};
    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(decodeImage, &state);
    parser.SetFsCallbacks({everyFileExists, expandNothing, readReferencedFile, writeNothing, &state});
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        ok = binary ? parser.LoadBinaryFromMemory(&model, &err, &warn, data, unsigned(size), "")
                    : parser.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data), unsigned(size), "");
    } catch (const Error&) {
        throw;  // a refused file or a budget, already one line naming the scene
    } catch (const std::bad_alloc&) {
        throw Error(name + ": invalid glTF (out of memory while parsing)");
    } catch (const std::exception& e) {
        throw Error(name + ": invalid glTF (" + e.what() + ")");
    }
    if (!ok)
        throw Error(name + ": invalid glTF: " + (err.empty() ? std::string("unknown error") : withoutJsonTags(oneLine(err))));
    warnings = oneLine(warn);
    return model;
}

}  // namespace penumbra::gltf

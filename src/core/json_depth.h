#pragma once
// How deeply a JSON text nests arrays and objects, found without parsing it. Parsers that recurse
// per level (tinygltf's extras, nlohmann's dump) overflow the stack on a few hundred kilobytes of
// "[[[[...": callers refuse such a text before handing it on.
#include <cstddef>
#include <string_view>

namespace penumbra {

// The deepest nesting of `text` (0 for a scalar), counting no bracket inside a string; it stops
// counting at `stopAbove` + 1, so a caller learns only that the text is too deep.
size_t jsonNestingDepth(std::string_view text, size_t stopAbove);

}  // namespace penumbra

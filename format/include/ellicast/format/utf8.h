// UTF-8 checks for the text a stream carries: names, and the JSON patches of MATERIAL_EXTENSIONS.
// Follows spec/format.md sections 15 (Format 1.1 additions: scene, materials, textures: names are
// UTF-8, shown with U+FFFD where ill-formed) and 18.2 (MATERIAL_EXTENSIONS payload, rule 2).
#pragma once

#include <string>
#include <string_view>

namespace ellicast {

// Names in the stream are UTF-8 (spec 15). True when `text` is well-formed UTF-8 (no overlong
// forms, no surrogates, nothing above U+10FFFF).
bool is_valid_utf8(std::string_view text);

// `text` with every byte sequence that is not well-formed UTF-8 replaced by U+FFFD (one per
// maximal ill-formed subpart, as Unicode recommends): what a decoder shows of a name (spec 15.1).
std::string replace_invalid_utf8(std::string_view text);

}  // namespace ellicast

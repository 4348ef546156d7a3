// Material extensions (format 1.3): the JSON patch that a MATERIAL_EXTENSIONS packet carries for one
// material, its checks and its texture references. Follows spec/format.md section 18 (Format 1.3
// addition: material extensions): 18.2 MATERIAL_EXTENSIONS payload; 18.3 Texture references, in the
// order that counts. The MATERIAL flag (18.1) is Material::has_extensions, in scene.h.
#pragma once

#include "ellicast/format/error.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ellicast {

// Format 1.3 (spec 18.2): the JSON patch of one material.
struct MaterialExtensions {
    uint16_t index = 0;
    uint16_t material_count = 0;  // size of the whole material table
    std::string patch;            // the JSON text, as received
    bool operator==(const MaterialExtensions&) const = default;
};
inline constexpr size_t kMaterialExtensionsMinSize = 6;  // index, count, and the shortest patch "{}"

// A texture reference of a patch (spec 18.2, 18.3).
struct PatchTextureReference {
    std::string path;         // member names (array positions) from the top, joined by '/'
    uint16_t texture = 0;     // index into the stream's texture table
    size_t index_offset = 0;  // where the digits of its "index" stand in the patch text
    size_t index_length = 0;
};

// Checks a patch by spec 18.2 (rules 2..8: UTF-8, RFC 8259 grammar, surrogates, finite numbers,
// unique names, depth 32, shape and texture rules): Ok, with its texture references in document
// order when `references` is given, or MalformedPayload.
Error check_material_patch(std::string_view patch, std::vector<PatchTextureReference>* references = nullptr);
// The patch with the index of each of its texture references (as check_material_patch found them)
// replaced by map(index): a patch moved to another texture table.
std::string remap_patch_textures(std::string_view patch, const std::vector<PatchTextureReference>& references,
                                 const std::function<uint16_t(uint16_t)>& map);

std::vector<uint8_t> encode_material_extensions_payload(const MaterialExtensions& extensions);
Error decode_material_extensions_payload(std::span<const uint8_t> payload, MaterialExtensions& out);

}  // namespace ellicast

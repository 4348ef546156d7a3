// Internal to converters: a glTF material's extensions and texture transforms as the patch of
// format 1.3 (spec section 18), built from a tinygltf material at the sender (asset_input.cpp) and
// merged into the written material at the receiver (asset_output.cpp).
#pragma once

#include "ellicast/format.h"

#include <tiny_gltf.h>

#include <array>
#include <functional>
#include <set>
#include <string>
#include <vector>

namespace ellicast::material_patch {

// The five core texture infos, in the order of Material's references: base colour,
// metallic-roughness, normal, occlusion, emissive.
extern const std::array<const char*, 5> kCoreSlots;

// The patch of glTF material `material`: every KHR_materials_* extension, and the
// KHR_texture_transform of each core texture info whose texture is sent (`core_sent`) and of every
// texture reference inside those extensions. `texture(index, where)` maps a glTF texture index to
// the stream's texture table (kNone: the texture is not sent; it warns). A texture reference on
// another set than TEXCOORD_0, or whose texture is not sent, is left out of the patch. Empty when
// there is nothing to carry. What is not carried is named in `warnings`, with `where`.
std::string make(const tinygltf::Material& material, const std::array<bool, 5>& core_sent,
                 const std::function<uint16_t(int, const std::string&)>& texture, const std::string& where,
                 std::vector<std::string>& warnings);

// Merges a patch (spec 18.4) into `material`: its texture references mapped by `texture` (a glTF
// texture index, or -1 when that texture is not written: the merge fails with `why`), the
// extensions of a core texture info only where `material` has that texture, and the name of every
// extension it uses added to `used`.
bool apply(const std::string& patch, tinygltf::Material& material, const std::function<int(uint16_t)>& texture,
           std::set<std::string>& used, std::string& why);

// True when `material` (as written) needs a tangent space: a normal map, or an extension that
// uses one (KHR_materials_anisotropy, a *NormalTexture such as clearcoat's).
bool needs_tangents(const tinygltf::Material& material);

}  // namespace ellicast::material_patch

// MATERIAL_EXTENSIONS (format 1.3, spec section 18): the payload, and the strict check of its JSON
// patch (RFC 8259 grammar, the limits of spec 18.2, the patch's fixed shape, texture references).
//
// The checker parses the patch once into a small tree of values (objects keep their members in
// text order with the offset of each value), then walks the tree for the shape and the texture
// references. Everything is bounded by the patch's length (at most one packet) and a nesting depth
// of 32, so hostile text costs linear time and memory.
#include "bytes.h"
#include "json_text.h"
#include "ellicast/format.h"

#include <functional>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <set>

namespace ellicast {

using namespace detail;

namespace {

bool ends_with_texture(std::string_view name) {
    constexpr std::string_view kSuffix = "Texture";
    return name.size() >= kSuffix.size() && name.substr(name.size() - kSuffix.size()) == kSuffix;
}

// Rule 8, the shape: only the named members, each (and every extension object) an object.
bool extensions_ok(const JsonValue& v) {
    if (v.kind != JsonValue::Object) return false;
    for (const auto& [name, ext] : v.members)
        if (ext->kind != JsonValue::Object) return false;
    return true;
}

bool core_texture_info_ok(const JsonValue& v) {
    if (v.kind != JsonValue::Object) return false;
    for (const auto& [name, member] : v.members)
        if (name != "extensions" || !extensions_ok(*member)) return false;
    return true;
}

bool shape_ok(const JsonValue& patch) {
    if (patch.kind != JsonValue::Object) return false;
    for (const auto& [name, member] : patch.members) {
        if (name == "extensions") {
            if (!extensions_ok(*member)) return false;
        } else if (name == "normalTexture" || name == "occlusionTexture" || name == "emissiveTexture") {
            if (!core_texture_info_ok(*member)) return false;
        } else if (name == "pbrMetallicRoughness") {
            if (member->kind != JsonValue::Object) return false;
            for (const auto& [inner, value] : member->members) {
                if (inner == "extensions") {
                    if (!extensions_ok(*value)) return false;
                } else if (inner == "baseColorTexture" || inner == "metallicRoughnessTexture") {
                    if (!core_texture_info_ok(*value)) return false;
                } else {
                    return false;
                }
            }
        } else {
            return false;
        }
    }
    return true;
}

// The texture rules of spec 18.2 and the references in document order (spec 18.3). `name` is the
// member whose value `v` is (empty for an array element or the patch itself).
bool walk_references(const JsonValue& v, std::string_view name, const std::string& path,
                     std::vector<PatchTextureReference>* out) {
    if (v.kind == JsonValue::Object) {
        const JsonValue* index = v.member("index");
        const bool reference = index && ends_with_texture(name);
        const bool transform = name == "KHR_texture_transform";
        if (reference || transform) {
            if (const JsonValue* tc = v.member("texCoord"); tc && !(tc->kind == JsonValue::Number && tc->text == "0"))
                return false;
        }
        if (reference) {
            const std::string& digits = index->text;
            if (index->kind != JsonValue::Number || digits.empty() || digits.size() > 5 ||
                digits.find_first_not_of("0123456789") != std::string::npos || (digits.size() > 1 && digits[0] == '0'))
                return false;
            const unsigned long value = std::strtoul(digits.c_str(), nullptr, 10);
            if (value > 65534) return false;
            if (out) out->push_back({path, uint16_t(value), index->offset, index->length});
        }
        for (const auto& [member_name, member] : v.members)
            if (!walk_references(*member, member_name, path.empty() ? member_name : path + "/" + member_name, out))
                return false;
    } else if (v.kind == JsonValue::Array) {
        for (size_t k = 0; k < v.elements.size(); ++k)
            if (!walk_references(*v.elements[k], {}, path + "/" + std::to_string(k), out)) return false;
    }
    return true;
}

}  // namespace

Error check_material_patch(std::string_view patch, std::vector<PatchTextureReference>* references) {
    if (!is_valid_utf8(patch)) return Error::MalformedPayload;  // rule 2
    Parser parser(patch);
    std::unique_ptr<JsonValue> root = parser.document();  // rules 3..7
    if (!root || root->kind != JsonValue::Object || !shape_ok(*root)) return Error::MalformedPayload;
    std::vector<PatchTextureReference> found;
    if (!walk_references(*root, {}, {}, &found)) return Error::MalformedPayload;
    // Members are walked in text order, so the references come in the order of their '{'.
    if (references) *references = std::move(found);
    return Error::Ok;
}

std::string remap_patch_textures(std::string_view patch, const std::vector<PatchTextureReference>& references,
                                 const std::function<uint16_t(uint16_t)>& map) {
    std::string out;
    size_t at = 0;
    for (const auto& r : references) {  // document order is text order of the index digits too
        out.append(patch.substr(at, r.index_offset - at));
        out += std::to_string(map(r.texture));
        at = r.index_offset + r.index_length;
    }
    out.append(patch.substr(at));
    return out;
}

std::vector<uint8_t> encode_material_extensions_payload(const MaterialExtensions& m) {
    std::vector<uint8_t> out(4 + m.patch.size());
    out[0] = uint8_t(m.index), out[1] = uint8_t(m.index >> 8);
    out[2] = uint8_t(m.material_count), out[3] = uint8_t(m.material_count >> 8);
    std::copy(m.patch.begin(), m.patch.end(), out.begin() + 4);
    return out;
}

Error decode_material_extensions_payload(std::span<const uint8_t> payload, MaterialExtensions& out) {
    if (payload.size() < kMaterialExtensionsMinSize) return Error::MalformedPayload;
    MaterialExtensions m;
    m.index = uint16_t(payload[0] | (payload[1] << 8));
    m.material_count = uint16_t(payload[2] | (payload[3] << 8));
    if (m.index >= m.material_count) return Error::MalformedPayload;
    m.patch.assign(reinterpret_cast<const char*>(payload.data()) + 4, payload.size() - 4);
    if (check_material_patch(m.patch) != Error::Ok) return Error::MalformedPayload;
    out = std::move(m);
    return Error::Ok;
}

}  // namespace ellicast

// The patch of format 1.3 (spec section 18) to and from tinygltf materials. See material_extensions.h.
#include "material_extensions.h"

#include "json_value.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <cmath>

namespace ellicast::material_patch {

const std::array<const char*, 5> kCoreSlots = {"baseColorTexture", "metallicRoughnessTexture", "normalTexture",
                                               "occlusionTexture", "emissiveTexture"};

namespace {

using json = nlohmann::json;

using json_value::to_json;
using json_value::to_value;

bool ends_with_texture(const std::string& name) {
    return name.size() >= 7 && name.compare(name.size() - 7, 7, "Texture") == 0;
}

// A texCoord member that is not the number 0 (spec 18.2); an integral 0 is rewritten as the integer.
bool other_set(json& holder) {
    if (!holder.is_object() || !holder.contains("texCoord")) return false;
    json& tc = holder["texCoord"];
    if (!tc.is_number() || tc.get<double>() != 0) return true;
    tc = 0;
    return false;
}

// Maps the texture references inside an extension object to the stream's table, leaving out those
// that cannot travel (spec 18.2's texture rules).
void map_references(json& v, const std::string& where, const std::function<uint16_t(int, const std::string&)>& texture,
                    std::vector<std::string>& warnings) {
    if (v.is_array()) {
        for (json& e : v) map_references(e, where, texture, warnings);
        return;
    }
    if (!v.is_object()) return;
    for (auto it = v.begin(); it != v.end();) {
        json& member = it.value();
        const std::string name = it.key();
        const std::string here = where + "/" + name;
        if (ends_with_texture(name) && member.is_object() && member.contains("index")) {
            const json& index = member["index"];
            std::string problem;
            if (!index.is_number_integer() || index.get<int64_t>() < 0 || index.get<int64_t>() > INT_MAX)
                problem = "its index is not a texture index";
            else if (other_set(member))
                problem = "it uses another texture-coordinate set than TEXCOORD_0, which ellicast does not carry";
            else if (member.contains("extensions") && member["extensions"].is_object() &&
                     member["extensions"].contains("KHR_texture_transform") &&
                     other_set(member["extensions"]["KHR_texture_transform"]))
                problem = "its KHR_texture_transform selects another texture-coordinate set than TEXCOORD_0";
            if (problem.empty()) {
                const uint16_t mapped = texture(int(index.get<int64_t>()), here);
                if (mapped == kNone) problem = "its texture is not sent";
                else member["index"] = mapped;
            }
            if (!problem.empty()) {
                warnings.push_back(here + ": " + problem + "; this texture is left out of the extension");
                it = v.erase(it);
                continue;
            }
        }
        map_references(member, here, texture, warnings);
        ++it;
    }
}

// The extension names an "extensions" object anywhere in `v` holds.
void collect_used(const json& v, std::set<std::string>& used) {
    if (v.is_array()) {
        for (const json& e : v) collect_used(e, used);
    } else if (v.is_object()) {
        for (const auto& [key, member] : v.items()) {
            if (key == "extensions" && member.is_object())
                for (const auto& [name, ext] : member.items()) used.insert(name);
            collect_used(member, used);
        }
    }
}

// Rewrites the texture references of a received patch with glTF texture indices; false when one
// names a texture that is not written.
bool map_to_gltf(json& v, const std::string& name, const std::function<int(uint16_t)>& texture, std::string& why) {
    if (v.is_array()) {
        for (json& e : v)
            if (!map_to_gltf(e, {}, texture, why)) return false;
    } else if (v.is_object()) {
        if (ends_with_texture(name) && v.contains("index") && v["index"].is_number_unsigned()) {
            const uint64_t stream_index = v["index"].get<uint64_t>();
            const int out = stream_index < kNone ? texture(uint16_t(stream_index)) : -1;
            if (out < 0) {
                why = name + " refers to texture " + std::to_string(stream_index) + ", which is not written";
                return false;
            }
            v["index"] = out;
        }
        for (auto& [key, member] : v.items())
            if (!map_to_gltf(member, key, texture, why)) return false;
    }
    return true;
}

}  // namespace

std::string make(const tinygltf::Material& material, const std::array<bool, 5>& core_sent,
                 const std::function<uint16_t(int, const std::string&)>& texture, const std::string& where,
                 std::vector<std::string>& warnings) {
    json patch = json::object();
    for (const auto& [name, value] : material.extensions) {
        if (name.rfind("KHR_materials_", 0) != 0) {
            warnings.push_back(where + ": extension " + name + " is not sent (ellicast carries KHR_materials_* and "
                               "KHR_texture_transform)");
            continue;
        }
        json ext = to_json(value);
        if (!ext.is_object()) {
            warnings.push_back(where + ": extension " + name + " is not a JSON object; not sent");
            continue;
        }
        map_references(ext, where + " extensions/" + name, texture, warnings);
        patch["extensions"][name] = std::move(ext);
    }
    if (!material.pbrMetallicRoughness.extensions.empty())
        warnings.push_back(where + ": the extensions of pbrMetallicRoughness are not sent");
    const tinygltf::ExtensionMap* core[5] = {&material.pbrMetallicRoughness.baseColorTexture.extensions,
                                             &material.pbrMetallicRoughness.metallicRoughnessTexture.extensions,
                                             &material.normalTexture.extensions, &material.occlusionTexture.extensions,
                                             &material.emissiveTexture.extensions};
    for (size_t k = 0; k < 5; ++k) {
        if (!core_sent[k]) continue;
        auto it = core[k]->find("KHR_texture_transform");
        if (it == core[k]->end()) continue;
        json transform = to_json(it->second);
        other_set(transform);  // an integral texCoord 0 written as the integer (other sets were refused before)
        json& info = k < 2 ? patch["pbrMetallicRoughness"][kCoreSlots[k]] : patch[kCoreSlots[k]];
        info["extensions"]["KHR_texture_transform"] = std::move(transform);
    }
    if (patch.empty()) return {};
    std::string text = patch.dump();
    if (check_material_patch(text) != Error::Ok) {
        warnings.push_back(where + ": its extensions break the limits of a MATERIAL_EXTENSIONS patch (spec 18.2: "
                           "nesting over 32 deep, or a texture reference out of range); not sent");
        return {};
    }
    return text;
}

bool needs_tangents(const tinygltf::Material& material) {
    if (material.normalTexture.index >= 0) return true;
    for (const auto& [name, ext] : material.extensions) {
        if (name == "KHR_materials_anisotropy") return true;
        if (!ext.IsObject()) continue;
        for (const std::string& key : ext.Keys())
            if (key.size() > 13 && key.compare(key.size() - 13, 13, "NormalTexture") == 0) return true;
    }
    return false;
}

bool apply(const std::string& patch, tinygltf::Material& material, const std::function<int(uint16_t)>& texture,
           std::set<std::string>& used, std::string& why) {
    json j = json::parse(patch, nullptr, false);
    if (!j.is_object()) {
        why = "its extensions are not a JSON object";
        return false;
    }
    if (!map_to_gltf(j, {}, texture, why)) return false;
    auto extensions_of = [&](const json& holder, tinygltf::ExtensionMap& out) {
        if (!holder.is_object() || !holder.contains("extensions")) return;
        for (const auto& [name, ext] : holder["extensions"].items()) {
            out[name] = to_value(ext);
            used.insert(name);
            collect_used(ext, used);
        }
    };
    extensions_of(j, material.extensions);
    auto& pbr = material.pbrMetallicRoughness;
    tinygltf::ExtensionMap* core[5] = {&pbr.baseColorTexture.extensions, &pbr.metallicRoughnessTexture.extensions,
                                       &material.normalTexture.extensions, &material.occlusionTexture.extensions,
                                       &material.emissiveTexture.extensions};
    const int core_index[5] = {pbr.baseColorTexture.index, pbr.metallicRoughnessTexture.index,
                               material.normalTexture.index, material.occlusionTexture.index,
                               material.emissiveTexture.index};
    const json none;
    const json& pbr_patch = j.contains("pbrMetallicRoughness") ? j["pbrMetallicRoughness"] : none;
    extensions_of(pbr_patch, pbr.extensions);
    for (size_t k = 0; k < 5; ++k) {
        const json& holder = k < 2 ? pbr_patch : j;
        if (core_index[k] < 0 || !holder.is_object() || !holder.contains(kCoreSlots[k])) continue;
        extensions_of(holder[kCoreSlots[k]], *core[k]);  // only where the material has that texture (18.4)
    }
    return true;
}

}  // namespace ellicast::material_patch

// Writing an Asset as glTF 2.0 with its scene graph: nodes, meshes (one primitive per object),
// materials, textures (image bytes embedded as given), optionally with KHR_draco_mesh_compression
// or KHR_mesh_quantization. Whatever does not hold together is left out with a warning, so that the
// file is always valid glTF: a receiver writes whatever has arrived.
#include "ellicast/converters/asset.h"
#include "ellicast/converters/mesh_output.h"

#include "gltf_write.h"
#include "meshopt_output.h"
#include "skin_weights.h"
#include "material_extensions.h"
#include "tangents.h"
#include "ellicast/converters/image_file.h"

#include "ellicast/converters/draco_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <tuple>
#include <optional>
#include <set>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"  // false positive in string concatenation (GCC bug 105651)
#endif

namespace ellicast {

namespace {

using namespace gltf_write;

const char* const kDracoExtension = "KHR_draco_mesh_compression";
const char* const kQuantizationExtension = "KHR_mesh_quantization";

bool valid_filter(uint16_t f, bool min) {
    return f == 9728 || f == 9729 || (min && f >= 9984 && f <= 9987);
}
bool valid_wrap(uint16_t w) { return w == 33071 || w == 33648 || w == 10497; }

float clamp01(float v) { return std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f; }

// The uniform scale and offset that map a mesh's positions into [-1, 1]^3 (KHR_mesh_quantization).
struct Dequantization {
    std::array<double, 3> center{};
    double scale = 1;
};

// A copy of an object with what glTF cannot hold repaired, or nullopt when it cannot be written.
std::optional<Mesh> writable_object(const Mesh& in, const std::string& what, std::vector<std::string>& warnings) {
    for (const auto& p : in.positions)
        for (float c : p)
            if (!std::isfinite(c)) {
                warnings.push_back(what + " has a non-finite position; left out");
                return std::nullopt;
            }
    if (!valid_indices(in)) {
        warnings.push_back(what + " has a triangle index beyond its vertices; left out");
        return std::nullopt;
    }
    Mesh m = in;
    auto drop = [&](auto& attr, const char* name) {
        if (!attr.empty() && attr.size() != m.positions.size()) {
            warnings.push_back(what + ": its " + name + " count differs from its vertex count; " + name + " left out");
            attr.clear();
        }
    };
    drop(m.normals, "NORMAL");
    drop(m.texcoords, "TEXCOORD_0");
    drop(m.colors, "COLOR_0");
    for (auto& uv : m.texcoords)
        for (float& c : uv)
            if (!std::isfinite(c)) c = 0;
    // Further sets (format 1.14): complete ones after a TEXCOORD_0, up to the first that is not.
    if (!m.has_texcoords()) m.texcoord_sets.clear();
    for (size_t s = 0; s < m.texcoord_sets.size(); ++s) {
        if (m.texcoord_sets[s].size() == m.positions.size()) continue;
        warnings.push_back(what + ": its TEXCOORD_" + std::to_string(s + 1) +
                           " count differs from its vertex count; it and the sets after it left out");
        m.texcoord_sets.resize(s);
        break;
    }
    for (auto& set : m.texcoord_sets)
        for (auto& uv : set)
            for (float& c : uv)
                if (!std::isfinite(c)) c = 0;
    m.normals = unit_normals(m.normals);
    return m;
}

class AssetWriter {
public:
    AssetWriter(const std::string& path, const Asset& asset, const AssetWriteOptions& options,
                std::vector<std::string>& warnings)
        : path_(path), asset_(asset), options_(options), warnings_(warnings) {
        for (const SceneExtras& e : asset.scene.extras) extras_[{e.kind, e.index}] = &e.text;
    }

    tinygltf::Model build() {
        model_.asset.version = "2.0";
        model_.asset.generator = "ellicast";
        extras_at(ExtrasTarget::Asset, 0, "/asset");
        write_textures();
        write_materials();
        write_cameras_lights();
        if (asset_.scene.nodes.empty()) write_flat();
        else write_scene_graph();
        if (used_draco_) {
            model_.extensionsUsed.push_back(kDracoExtension);
            model_.extensionsRequired.push_back(kDracoExtension);
        }
        if (used_quantization_) {
            model_.extensionsUsed.push_back(kQuantizationExtension);
            model_.extensionsRequired.push_back(kQuantizationExtension);
        }
        for (const std::string& name : used_extensions_) model_.extensionsUsed.push_back(name);
        require_source_extensions();
        // tinygltf writes a node with no property at all (an unnamed leaf with the default transform,
        // as Khronos SimpleSkin has) as JSON null, which is invalid glTF: give it its identity
        // translation explicitly, which means the same.
        for (tinygltf::Node& node : model_.nodes)
            if (node.name.empty() && node.mesh < 0 && node.skin < 0 && node.camera < 0 && node.children.empty() &&
                node.matrix.empty() && node.translation.empty() && node.rotation.empty() && node.scale.empty() &&
                node.weights.empty() && node.extensions.empty())
                node.translation = {0, 0, 0};
        return std::move(model_);
    }
    // Format 1.12: what build() leaves for the serialized document (the elements' extras).
    const gltf_write::JsonPatches& patches() const { return extras_patches_; }

private:
    // Format 1.12 (spec 28.3): the extras of the asset's element `index` of the table of `kind` go
    // into the written document at `place` (a JSON pointer to the written element), set after
    // tinygltf has serialized the model (its values drop nulls).
    void extras_at(ExtrasTarget kind, size_t index, const std::string& place) {
        const auto it = extras_.find({kind, uint16_t(index)});
        if (index > 0xFFFF || it == extras_.end()) return;
        if (!acceptable_extras_text(*it->second)) {  // a receiver's texts were checked (spec 28.1)
            warnings_.push_back(path_ + ": the extras of " + extras_target_name(kind) + " " + std::to_string(index) +
                                " are not JSON; written without them");
            return;
        }
        extras_patches_.emplace_back(place + "/extras", *it->second);
    }

    bool object_present(size_t o) const { return o < asset_.objects.size() && !asset_.objects[o].positions.empty(); }

    // ---- textures: one glTF image per distinct image file, one sampler per distinct setting
    void write_textures() {
        const auto& textures = asset_.scene.textures;
        texture_out_.assign(textures.size(), -1);
        std::multimap<uint32_t, int> images_by_crc;          // CRC-32C of the file -> glTF image
        std::vector<const std::vector<uint8_t>*> image_bytes;  // per glTF image
        std::map<std::array<int, 4>, int> samplers;
        for (size_t t = 0; t < textures.size(); ++t) {
            const auto& tex = textures[t];
            const std::string what = path_ + ": texture " + std::to_string(t);
            if (tex.image.empty()) {
                warnings_.push_back(what + " has no image; left out");
                continue;
            }
            // The file is written as what its bytes are; one no viewer can open is left out (the
            // validator refuses an image cut off in its header), one cut off in its image data is kept.
            const image_file::Check check = image_file::check(tex.image);
            if (check.format == image_file::Format::Unknown) {
                warnings_.push_back(what + " is neither PNG nor JPEG; left out");
                continue;
            }
            const std::string kind = image_file::name(check.format);
            if (!check.readable) {
                warnings_.push_back(what + ": its " + kind + " file " + check.problem + "; no viewer can open it, left out");
                continue;
            }
            if (!check.problem.empty()) warnings_.push_back(what + ": its " + kind + " file " + check.problem + "; written as it is");
            const char* mime = image_file::mime_type(check.format);
            const bool jpeg = check.format == image_file::Format::Jpeg;
            if (jpeg != (tex.info.image_type == ImageType::Jpeg))
                warnings_.push_back(what + " is announced as " + (jpeg ? "PNG" : "JPEG") + " but its bytes are a " + kind +
                                    " file; written as " + mime);
            const uint32_t crc = crc32c(tex.image.data(), tex.image.size());
            int source = -1;
            for (auto [it, end] = images_by_crc.equal_range(crc); it != end; ++it)
                if (*image_bytes[size_t(it->second)] == tex.image) source = it->second;
            if (source < 0) {
                source = int(model_.images.size());
                tinygltf::Image image;
                image.mimeType = mime;
                image.bufferView = add_buffer_view(model_, tex.image.data(), tex.image.size(), 0);
                model_.images.push_back(std::move(image));
                image_bytes.push_back(&tex.image);
                images_by_crc.emplace(crc, source);
            }
            std::array<int, 4> s = {valid_filter(tex.info.mag_filter, false) ? tex.info.mag_filter : -1,
                                    valid_filter(tex.info.min_filter, true) ? tex.info.min_filter : -1,
                                    valid_wrap(tex.info.wrap_s) ? tex.info.wrap_s : 10497,
                                    valid_wrap(tex.info.wrap_t) ? tex.info.wrap_t : 10497};
            if ((tex.info.mag_filter && s[0] < 0) || (tex.info.min_filter && s[1] < 0) || s[2] != tex.info.wrap_s ||
                s[3] != tex.info.wrap_t)
                warnings_.push_back(what + ": sampler values that are not glTF's replaced by the defaults");
            auto [sit, new_sampler] = samplers.try_emplace(s, int(model_.samplers.size()));
            if (new_sampler) {
                tinygltf::Sampler sampler;
                sampler.magFilter = s[0];
                sampler.minFilter = s[1];
                sampler.wrapS = s[2];
                sampler.wrapT = s[3];
                model_.samplers.push_back(sampler);
            }
            tinygltf::Texture texture;
            texture.source = source;
            texture.sampler = sit->second;
            extras_at(ExtrasTarget::Texture, t, "/textures/" + std::to_string(model_.textures.size()));
            texture_out_[t] = int(model_.textures.size());
            model_.textures.push_back(texture);
        }
    }

    // ---- materials: material i is glTF material i; variants without textures are appended
    // A material whose TEXCOORD_0 texture cannot be written is kept in the table (indices stay) but
    // no primitive uses it: they get the default material, as at a receiver still waiting for it.
    void write_materials() {
        const auto& materials = asset_.scene.materials;
        for (size_t i = 0; i < materials.size(); ++i) {
            const Material& m = materials[i];
            bool whole = true;
            for (const TextureRef* ref : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                          &m.occlusion_texture, &m.emissive_texture})
                if (ref->texture != kNone && ref->texcoord <= kMaxTexcoordSets &&
                    (ref->texture >= texture_out_.size() || texture_out_[ref->texture] < 0))
                    whole = false;
            tinygltf::Material g = gltf_material(m, i, false);
            // Format 1.3: the material's extensions and texture transforms (spec 18.4).
            if (whole && !m.extensions.empty()) {
                std::string why;
                std::set<std::string> used;
                const bool applied = material_patch::apply(
                    m.extensions, g,
                    [&](uint16_t t) { return t < texture_out_.size() ? texture_out_[t] : -1; }, used, why);
                if (applied) {
                    used_extensions_.insert(used.begin(), used.end());
                } else {
                    warnings_.push_back(path_ + ": material " + std::to_string(i) + ": " + why +
                                        "; primitives using the material get the default material");
                    whole = false;
                }
            }
            material_whole_.push_back(whole);
            extras_at(ExtrasTarget::Material, i, "/materials/" + std::to_string(model_.materials.size()));
            model_.materials.push_back(std::move(g));
        }
    }

    // The glTF texture info of a reference, or index -1 when it cannot be shown (with a warning).
    int texture_index(const TextureRef& ref, const std::string& what) {
        if (ref.texture == kNone) return -1;
        if (ref.texture >= texture_out_.size() || texture_out_[ref.texture] < 0) {
            warnings_.push_back(what + ": texture " + std::to_string(ref.texture) +
                                " is not available; primitives using the material get the default material");
            return -1;
        }
        if (ref.texcoord > kMaxTexcoordSets) {
            warnings_.push_back(what + " uses TEXCOORD_" + std::to_string(ref.texcoord) +
                                ", which ellicast does not carry; the material is written without that texture");
            return -1;
        }
        return texture_out_[ref.texture];
    }

    tinygltf::Material gltf_material(const Material& m, size_t index, bool untextured) {
        const std::string what = path_ + ": material " + std::to_string(index) + (m.name.empty() ? "" : " (" + m.name + ")");
        tinygltf::Material g;
        g.name = untextured ? m.name + " (untextured)" : m.name;
        auto& pbr = g.pbrMetallicRoughness;
        pbr.baseColorFactor = {clamp01(m.base_color[0]), clamp01(m.base_color[1]), clamp01(m.base_color[2]),
                               clamp01(m.base_color[3])};
        pbr.metallicFactor = clamp01(m.metallic);
        pbr.roughnessFactor = clamp01(m.roughness);
        g.emissiveFactor = {clamp01(m.emissive[0]), clamp01(m.emissive[1]), clamp01(m.emissive[2])};
        switch (m.alpha_mode) {
            case AlphaMode::Mask: g.alphaMode = "MASK"; break;
            case AlphaMode::Blend: g.alphaMode = "BLEND"; break;
            default: g.alphaMode = "OPAQUE"; break;
        }
        // alphaCutoff only means something with MASK (the validator warns about it otherwise).
        g.alphaCutoff = m.alpha_mode == AlphaMode::Mask && std::isfinite(m.alpha_cutoff) && m.alpha_cutoff >= 0
                            ? m.alpha_cutoff : 0.5;
        g.doubleSided = m.double_sided;
        if (untextured) return g;
        pbr.baseColorTexture.index = texture_index(m.base_color_texture, what + " baseColorTexture");
        pbr.baseColorTexture.texCoord = m.base_color_texture.texcoord;
        pbr.metallicRoughnessTexture.index = texture_index(m.metallic_roughness_texture, what + " metallicRoughnessTexture");
        pbr.metallicRoughnessTexture.texCoord = m.metallic_roughness_texture.texcoord;
        g.normalTexture.index = texture_index(m.normal_texture, what + " normalTexture");
        g.normalTexture.texCoord = m.normal_texture.texcoord;
        g.normalTexture.scale = std::isfinite(m.normal_texture.scale) ? m.normal_texture.scale : 1.0;
        g.occlusionTexture.index = texture_index(m.occlusion_texture, what + " occlusionTexture");
        g.occlusionTexture.texCoord = m.occlusion_texture.texcoord;
        g.occlusionTexture.strength = clamp01(m.occlusion_texture.scale);
        g.emissiveTexture.index = texture_index(m.emissive_texture, what + " emissiveTexture");
        g.emissiveTexture.texCoord = m.emissive_texture.texcoord;
        return g;
    }

    bool has_texture(int material) const {
        const auto& g = model_.materials[size_t(material)];
        return g.pbrMetallicRoughness.baseColorTexture.index >= 0 ||
               g.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 || g.normalTexture.index >= 0 ||
               g.occlusionTexture.index >= 0 || g.emissiveTexture.index >= 0;
    }

    // The highest texture-coordinate set the written material's core textures use (0 without any).
    int highest_set(int material) const {
        const auto& g = model_.materials[size_t(material)];
        int set = 0;
        for (const auto* t : {&g.pbrMetallicRoughness.baseColorTexture, &g.pbrMetallicRoughness.metallicRoughnessTexture,
                              &g.emissiveTexture})
            if (t->index >= 0) set = std::max(set, t->texCoord);
        if (g.normalTexture.index >= 0) set = std::max(set, g.normalTexture.texCoord);
        if (g.occlusionTexture.index >= 0) set = std::max(set, g.occlusionTexture.texCoord);
        return set;
    }

    // The glTF material for a primitive of object `object` drawn with asset material `material`:
    // -1 (glTF's default material) when there is none; an untextured copy when the object has no
    // texture coordinates but the material has textures.
    int primitive_material(uint16_t material, const Mesh& object, const std::string& what) {
        if (material == kNone) return -1;
        if (material >= asset_.scene.materials.size()) {
            warnings_.push_back(what + ": material " + std::to_string(material) +
                                " is not available; drawn with the default material");
            return -1;
        }
        if (!material_whole_[material]) return -1;  // named by texture_index
        const int set = highest_set(material);
        if (!has_texture(material) || (object.has_texcoords() && int(object.texcoord_sets.size()) >= set))
            return material;
        auto it = untextured_.find(material);
        if (it == untextured_.end()) {
            warnings_.push_back(what + " has no TEXCOORD_" + std::to_string(object.has_texcoords() ? set : 0) +
                                " but material " + std::to_string(material) +
                                " has textures on it: drawn with an untextured copy of the material");
            extras_at(ExtrasTarget::Material, material, "/materials/" + std::to_string(model_.materials.size()));
            model_.materials.push_back(gltf_material(asset_.scene.materials[material], material, true));
            it = untextured_.emplace(material, int(model_.materials.size()) - 1).first;
        }
        return it->second;
    }

    // ---- geometry

    // The primitive (without material) of object `o`, written once per dequantization and need of
    // tangents (a normal-mapped material: TANGENT from tangents.cpp, for an object with normals and
    // texture coordinates; a point set's points get a unit vector perpendicular to their normal, as
    // a point has no surface to orient it along, so that the file declares its tangent space rather
    // than leaving a viewer to generate one).
    std::optional<tinygltf::Primitive> object_primitive(size_t o, const std::optional<Dequantization>& dq,
                                                        int dq_key, bool tangents, const std::string& what,
                                                        bool skinned = false, uint8_t targets = 0) {
        // A skinned object (format 1.5) keeps float positions: a dequantizing wrapper node would not move
        // with the skeleton; with Draco its joints and weights go into the Draco data, reordered with its
        // vertices. An object with morph targets (format 1.6) is written plain: its displacements are
        // per vertex, in its frame.
        const bool plain = (skinned && !options_.draco) || targets > 0;
        // (A skinned Draco primitive carries JOINTS_0 and WEIGHTS_0: another key than the object unskinned.)
        auto key = std::make_tuple(o, plain ? -2 - int(skinned) - 2 * int(targets) : skinned ? -1000 + dq_key : dq_key,
                                   tangents);
        if (auto it = primitives_.find(key); it != primitives_.end()) return it->second;
        std::optional<tinygltf::Primitive> result;
        if (std::optional<Mesh> mesh = writable_object(asset_.objects[o], what, warnings_)) {
            tangents = tangents && mesh->has_normals() && mesh->has_texcoords();
            if (skinned && targets == 0 && options_.quantize) {
                // Quantized but for its positions (no dequantizing node), weights as exact bytes where
                // they are multiples of 1/255; for meshopt in vertex-cache and fetch order, weights too.
                VertexWeights weights = asset_.weights[o];
                if (options_.meshopt) *mesh = meshopt_output::in_fetch_order(*mesh, &weights);
                result = quantized_primitive(*mesh, std::nullopt);
                if (tangents) add_quantized_tangents(*result, *mesh);
                add_weights(*result, weights, true);
            } else if (plain) {
                result = add_primitive(model_, *mesh);
                if (tangents)
                    result->attributes["TANGENT"] = add_float_attribute(model_, mesh_tangents(*mesh), TINYGLTF_TYPE_VEC4, false);
                if (skinned) add_weights(*result, asset_.weights[o]);
                if (targets > 0) add_targets(*result, *mesh, asset_.morphs[o]);
            } else if (skinned && (mesh->is_point_set || mesh->triangles.empty())) {
                result = add_primitive(model_, *mesh);  // Draco covers triangles only
                add_weights(*result, asset_.weights[o]);
            } else if (options_.draco && !mesh->is_point_set && !mesh->triangles.empty()) {
                result = draco_primitive(*mesh, what, tangents, skinned ? &asset_.weights[o] : nullptr);
            } else if (dq) {
                // meshopt output: vertex-cache and fetch order, which its codecs compress best.
                if (options_.meshopt) *mesh = meshopt_output::in_fetch_order(*mesh);
                result = quantized_primitive(*mesh, *dq);
                if (tangents) add_quantized_tangents(*result, *mesh);
            } else {
                result = add_primitive(model_, *mesh);
                if (tangents)
                    result->attributes["TANGENT"] = add_float_attribute(model_, mesh_tangents(*mesh), TINYGLTF_TYPE_VEC4, false);
            }
        }
        primitives_[key] = result;
        return result;
    }

    // A set of texture coordinates as KHR_mesh_quantization allows: in [0,1] as normalized uint16;
    // outside (repeating textures) kept as floats, which the extension allows.
    int quantized_texcoords(const std::vector<std::array<float, 2>>& values) {
        const size_t n = values.size();
        bool unit = true;
        for (const auto& uv : values) unit = unit && uv[0] >= 0 && uv[0] <= 1 && uv[1] >= 0 && uv[1] <= 1;
        if (!unit) return add_float_attribute(model_, values, TINYGLTF_TYPE_VEC2, false);
        std::vector<uint16_t> q(n * 2);
        for (size_t i = 0; i < n; ++i)
            for (int k = 0; k < 2; ++k) q[i * 2 + k] = uint16_t(std::lround(values[i][k] * 65535.0));
        int view = add_buffer_view(model_, q.data(), q.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
        return add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, n, {}, {}, true);
    }

    // KHR_mesh_quantization: positions as normalized int16 in the mesh's cube, normals as normalized
    // int8, texture coordinates in [0,1] as normalized uint16, colours as normalized uint16.
    // `dq` nullopt: positions as floats (a skinned mesh, which a dequantizing node would not move with
    // its skeleton), the other attributes quantized all the same.
    tinygltf::Primitive quantized_primitive(const Mesh& mesh, const std::optional<Dequantization>& dq) {
        used_quantization_ = true;
        tinygltf::Primitive prim;
        const size_t n = mesh.positions.size();
        if (!dq) {
            prim.attributes["POSITION"] = add_float_attribute(model_, mesh.positions, TINYGLTF_TYPE_VEC3, true);
        } else {
            std::vector<int16_t> q(n * 4, 0);  // padded to 8 bytes: vertex elements are 4-byte aligned
            std::vector<double> mn(3, 32767), mx(3, -32767);
            for (size_t i = 0; i < n; ++i)
                for (int k = 0; k < 3; ++k) {
                    double v = std::round((mesh.positions[i][k] - dq->center[k]) / dq->scale * 32767.0);
                    auto s = int16_t(std::clamp(v, -32767.0, 32767.0));
                    q[i * 4 + k] = s;
                    mn[k] = std::min(mn[k], double(s));
                    mx[k] = std::max(mx[k], double(s));
                }
            int view = add_buffer_view(model_, q.data(), q.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
            model_.bufferViews[size_t(view)].byteStride = 8;
            prim.attributes["POSITION"] =
                add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, n, mn, mx, true);
        }
        if (mesh.has_normals()) {
            std::vector<int8_t> q(n * 4, 0);
            for (size_t i = 0; i < n; ++i) {
                auto best = quantize_unit_int8(mesh.normals[i]);
                for (int k = 0; k < 3; ++k) q[i * 4 + k] = best[k];
            }
            int view = add_buffer_view(model_, q.data(), q.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
            model_.bufferViews[size_t(view)].byteStride = 4;
            prim.attributes["NORMAL"] = add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, n,
                                                     {}, {}, true);
        }
        if (mesh.has_texcoords()) {
            prim.attributes["TEXCOORD_0"] = quantized_texcoords(mesh.texcoords);
            for (size_t s = 0; s < mesh.texcoord_sets.size(); ++s)
                prim.attributes["TEXCOORD_" + std::to_string(s + 1)] = quantized_texcoords(mesh.texcoord_sets[s]);
        }
        if (mesh.has_colors()) {
            const int channels = mesh.colors_have_alpha ? 4 : 3;
            std::vector<float> c = clamped_colors(mesh);
            std::vector<uint16_t> q(n * 4, 0);
            for (size_t i = 0; i < n; ++i)
                for (int k = 0; k < channels; ++k) q[i * 4 + k] = uint16_t(std::lround(c[i * channels + k] * 65535.0));
            int view = add_buffer_view(model_, q.data(), q.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
            model_.bufferViews[size_t(view)].byteStride = 8;
            prim.attributes["COLOR_0"] =
                add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                             channels == 4 ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, n, {}, {}, true);
        }
        if (mesh.is_point_set || mesh.triangles.empty()) {
            prim.mode = TINYGLTF_MODE_POINTS;
        } else {
            prim.mode = TINYGLTF_MODE_TRIANGLES;
            prim.indices = add_indices(model_, mesh);
        }
        return prim;
    }

    // TANGENT under KHR_mesh_quantization: normalized int8 xyz (nearest unit-length direction) and w.
    void add_quantized_tangents(tinygltf::Primitive& prim, const Mesh& mesh) {
        const auto tangents = mesh_tangents(mesh);
        std::vector<int8_t> q(tangents.size() * 4);
        for (size_t i = 0; i < tangents.size(); ++i) {
            auto best = quantize_unit_int8({tangents[i][0], tangents[i][1], tangents[i][2]});
            for (int k = 0; k < 3; ++k) q[i * 4 + k] = best[k];
            q[i * 4 + 3] = tangents[i][3] < 0 ? int8_t(-127) : int8_t(127);
        }
        int view = add_buffer_view(model_, q.data(), q.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
        model_.bufferViews[size_t(view)].byteStride = 4;
        prim.attributes["TANGENT"] =
            add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, tangents.size(), {}, {}, true);
    }

    // The int8 vector nearest in direction to the unit vector `n` whose length is closest to 1
    // (a normalized int8 normal must still be unit length within the validator's tolerance).
    static std::array<int8_t, 3> quantize_unit_int8(const std::array<float, 3>& n) {
        std::array<int8_t, 3> best{0, 0, 127};
        double best_error = 1e9;
        int base[3];
        for (int k = 0; k < 3; ++k) base[k] = int(std::floor(double(n[k]) * 127.0));
        for (int dx = 0; dx <= 1; ++dx)
            for (int dy = 0; dy <= 1; ++dy)
                for (int dz = 0; dz <= 1; ++dz) {
                    int c[3] = {std::clamp(base[0] + dx, -127, 127), std::clamp(base[1] + dy, -127, 127),
                                std::clamp(base[2] + dz, -127, 127)};
                    double len = std::sqrt(double(c[0]) * c[0] + double(c[1]) * c[1] + double(c[2]) * c[2]) / 127.0;
                    if (len == 0) continue;
                    double dot = (c[0] * n[0] + c[1] * n[1] + c[2] * n[2]) / (127.0 * len);
                    double error = std::abs(len - 1) * 4 + (1 - dot);
                    if (error < best_error) {
                        best_error = error;
                        best = {int8_t(c[0]), int8_t(c[1]), int8_t(c[2])};
                    }
                }
        return best;
    }

    // KHR_draco_mesh_compression: the triangles and attributes go through Draco's encoder (the
    // baselines' codec); the accessors take count and bounds from a decode of the encoded data
    // (Edgebreaker reorders and may split vertices).
    std::optional<tinygltf::Primitive> draco_primitive(const Mesh& input, const std::string& what, bool tangents,
                                                       const VertexWeights* skin = nullptr) {
        Mesh mesh = input;
        if (mesh.has_colors()) {
            std::vector<float> c = clamped_colors(mesh);
            const int channels = mesh.colors_have_alpha ? 4 : 3;
            for (size_t i = 0; i < mesh.colors.size(); ++i)
                for (int k = 0; k < channels; ++k) mesh.colors[i][k] = c[i * channels + k];
        }
        DracoSettings settings;
        settings.position_bits = options_.draco_position_bits;
        settings.normal_bits = options_.draco_normal_bits;
        settings.texcoord_bits = options_.draco_texcoord_bits;
        settings.color_bits = options_.draco_color_bits;
        settings.encoding_speed = settings.decoding_speed = options_.draco_speed;
        DracoAttributeIds ids;
        std::vector<uint8_t> encoded;
        Mesh decoded;
        std::string problem;
        try {
            encoded = draco_encode(mesh, settings, &ids, skin ? DracoSkin{&skin->joints, &skin->weights} : DracoSkin{});
            if (!draco_decode(encoded, decoded, problem)) problem = "it cannot decode its own output: " + problem;
        } catch (const DracoError& e) {
            problem = e.what();
        }
        if (problem.empty() && (decoded.has_normals() != mesh.has_normals() ||
                                decoded.has_texcoords() != mesh.has_texcoords() ||
                                decoded.texcoord_sets.size() != mesh.texcoord_sets.size() ||
                                decoded.has_colors() != mesh.has_colors()))
            problem = "an attribute was lost";
        if (!problem.empty()) {
            warnings_.push_back(what + ": Draco: " + problem + "; written uncompressed");
            tinygltf::Primitive plain = add_primitive(model_, input);
            if (skin) add_weights(plain, *skin);
            if (tangents)
                plain.attributes["TANGENT"] = add_float_attribute(model_, mesh_tangents(input), TINYGLTF_TYPE_VEC4, false);
            return plain;
        }
        const size_t points = decoded.positions.size();
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        tinygltf::Value::Object attributes;
        auto declare = [&](const char* name, int id, int type, bool bounds, int component = TINYGLTF_COMPONENT_TYPE_FLOAT,
                           bool normalized = false) {
            std::vector<double> mn, mx;
            if (bounds) {
                mn.assign(3, std::numeric_limits<double>::max());
                mx.assign(3, -std::numeric_limits<double>::max());
                for (const auto& v : decoded.positions)
                    for (int k = 0; k < 3; ++k) mn[k] = std::min(mn[k], double(v[k])), mx[k] = std::max(mx[k], double(v[k]));
            }
            prim.attributes[name] = add_accessor(model_, -1, component, type, points, mn, mx, normalized);
            attributes[name] = tinygltf::Value(id);
        };
        declare("POSITION", ids.position, TINYGLTF_TYPE_VEC3, true);
        if (ids.normal >= 0) declare("NORMAL", ids.normal, TINYGLTF_TYPE_VEC3, false);
        if (ids.texcoord >= 0) declare("TEXCOORD_0", ids.texcoord, TINYGLTF_TYPE_VEC2, false);
        for (size_t s = 0; s < ids.texcoord_sets.size(); ++s)
            declare(("TEXCOORD_" + std::to_string(s + 1)).c_str(), ids.texcoord_sets[s], TINYGLTF_TYPE_VEC2, false);
        if (ids.joints >= 0) {  // a skinned object: its joints and weights in the Draco data too
            declare("JOINTS_0", ids.joints, TINYGLTF_TYPE_VEC4, false,
                    ids.joints_8bit ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE : TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
            declare("WEIGHTS_0", ids.weights, TINYGLTF_TYPE_VEC4, false,
                    ids.weights_8bit ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE : TINYGLTF_COMPONENT_TYPE_FLOAT,
                    ids.weights_8bit);
        }
        if (ids.color >= 0)
            declare("COLOR_0", ids.color, mesh.colors_have_alpha ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, false);
        prim.indices = add_accessor(model_, -1,
                                    points <= 0xFFFF ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                                     : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                    TINYGLTF_TYPE_SCALAR, decoded.triangles.size() * 3);
        // Tangents are not in the Draco data: an ordinary accessor in the decoded vertex order, which
        // KHR_draco_mesh_compression allows for attributes it does not list.
        if (tangents)
            prim.attributes["TANGENT"] = add_float_attribute(model_, mesh_tangents(decoded), TINYGLTF_TYPE_VEC4, false);
        tinygltf::Value::Object extension;
        extension["bufferView"] = tinygltf::Value(add_buffer_view(model_, encoded.data(), encoded.size(), 0));
        extension["attributes"] = tinygltf::Value(attributes);
        prim.extensions[kDracoExtension] = tinygltf::Value(extension);
        used_draco_ = true;
        return prim;
    }

    // The dequantization of asset mesh `m`: a cube around every present object of it.
    std::optional<Dequantization> mesh_dequantization(const SceneMesh& m) const {
        if (!options_.quantize) return std::nullopt;
        std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
        bool any = false;
        for (const auto& p : m.primitives) {
            if (!object_present(p.object)) continue;
            const Mesh& o = asset_.objects[p.object];
            if (options_.draco && !o.is_point_set && !o.triangles.empty()) continue;  // Draco quantizes itself
            for (const auto& v : o.positions)
                for (int k = 0; k < 3; ++k)
                    if (std::isfinite(v[k])) lo[k] = std::min(lo[k], double(v[k])), hi[k] = std::max(hi[k], double(v[k]));
            any = true;
        }
        if (!any) return std::nullopt;
        Dequantization dq;
        double half = 0;
        for (int k = 0; k < 3; ++k) {
            dq.center[k] = (lo[k] + hi[k]) / 2;
            half = std::max(half, (hi[k] - lo[k]) / 2);
        }
        dq.scale = half > 0 ? half : 1;
        return dq;
    }

    // The glTF mesh of asset mesh `mi` (-1 when none of its objects can be written).
    int gltf_mesh(size_t mi) {
        if (auto it = mesh_out_.find(mi); it != mesh_out_.end()) return it->second;
        const SceneMesh& m = asset_.scene.meshes[mi];
        const std::string label = path_ + ": mesh " + std::to_string(mi) + (m.name.empty() ? "" : " (" + m.name + ")");
        const bool skinned = skinned_meshes_.count(mi) > 0;
        const uint8_t targets = mesh_targets(mi, label);
        std::optional<Dequantization> dq = skinned || targets ? std::nullopt : mesh_dequantization(m);
        tinygltf::Mesh g;
        g.name = m.name;
        if (targets) g.weights.assign(m.weights.begin(), m.weights.end());
        for (size_t p = 0; p < m.primitives.size(); ++p) {
            const ScenePrimitive& sp = m.primitives[p];
            const std::string what = label + " primitive " + std::to_string(p) + " (object " + std::to_string(sp.object) + ")";
            if (!object_present(sp.object)) {
                warnings_.push_back(what + (sp.object < asset_.objects.size() ? " has not arrived" : " does not exist") +
                                    "; left out");
                continue;
            }
            const int material = primitive_material(sp.material, asset_.objects[sp.object], what);
            // A tangent space: for a normal map, also one in an extension, and for anisotropy.
            const bool normal_mapped = material >= 0 && material_patch::needs_tangents(model_.materials[size_t(material)]);
            auto prim = object_primitive(sp.object, dq, dq ? int(mi) : -1, normal_mapped, what, skinned, targets);
            if (!prim) continue;
            prim->material = material;
            g.primitives.push_back(std::move(*prim));
        }
        int index = -1;
        if (g.primitives.empty()) {
            warnings_.push_back(label + " has no object to show; nodes showing it are written without it");
        } else {
            index = int(model_.meshes.size());
            extras_at(ExtrasTarget::Mesh, mi, "/meshes/" + std::to_string(index));
            model_.meshes.push_back(std::move(g));
            if (dq) dequantization_[index] = *dq;
        }
        mesh_out_[mi] = index;
        mesh_targets_out_[index] = targets;
        return index;
    }

    // Format 1.6: the morph targets asset mesh `mi` is written with: its count when it has default
    // weights and every present object of it has as many targets per vertex; else 0, with a warning.
    uint8_t mesh_targets(size_t mi, const std::string& label) {
        const SceneMesh& m = asset_.scene.meshes[mi];
        if (m.weights.empty()) return 0;
        for (const ScenePrimitive& p : m.primitives) {
            if (!object_present(p.object)) continue;
            const Mesh& object = asset_.objects[p.object];
            const VertexMorph* morph = p.object < asset_.morphs.size() ? &asset_.morphs[p.object] : nullptr;
            if (!morph || morph->targets != m.weights.size() ||
                morph->values.size() != morph_record_values(morph->targets, morph->attributes) * object.positions.size()) {
                warnings_.push_back(label + ": object " + std::to_string(p.object) + " has no " +
                                    std::to_string(m.weights.size()) + " morph targets per vertex; the mesh is written "
                                    "without its morph targets");
                return 0;
            }
        }
        return uint8_t(m.weights.size());
    }

    // A primitive's morph targets (format 1.6): POSITION displacements (with their bounds, as glTF
    // requires) and NORMAL displacements where the object has them and the primitive has normals. A
    // target with neither gets zero POSITION displacements (a glTF target needs an attribute).
    void add_targets(tinygltf::Primitive& prim, const Mesh& mesh, const VertexMorph& morph) {
        const size_t per = morph_record_values(morph.targets, morph.attributes);
        const size_t n = mesh.positions.size();
        const bool position = morph.attributes & kMorphPosition, normal = morph.attributes & kMorphNormal;
        const bool write_normal = normal && prim.attributes.count("NORMAL");
        for (size_t t = 0; t < morph.targets; ++t) {
            std::map<std::string, int> target;
            std::vector<std::array<float, 3>> d(n, {0, 0, 0});
            if (position || !write_normal) {
                if (position) {
                    const size_t offset = morph_slot_offset(morph.attributes, t, kMorphPosition);
                    for (size_t v = 0; v < n; ++v)
                        for (size_t k = 0; k < 3; ++k) d[v][k] = morph.values[v * per + offset + k];
                }
                target["POSITION"] = add_displacements(model_, d, true);
            }
            if (write_normal) {
                const size_t offset = morph_slot_offset(morph.attributes, t, kMorphNormal);
                for (size_t v = 0; v < n; ++v)
                    for (size_t k = 0; k < 3; ++k) d[v][k] = morph.values[v * per + offset + k];
                target["NORMAL"] = add_displacements(model_, d, false);
            }
            prim.targets.push_back(std::move(target));
        }
    }

    // ---- cameras and lights (format 1.10, spec 26.4): every one of the asset, in order. Records that
    // break spec 26.2 / 26.3 cannot come from a stream; an Asset made otherwise has them left out.
    // Format 1.13 (spec 29.2): the source's required extensions that this output uses are required
    // again, after those its own storage requires; the others are named in one warning.
    void require_source_extensions() {
        std::vector<std::string> lacking;
        for (const std::string& name : asset_.scene.required_extensions) {
            auto& required = model_.extensionsRequired;
            if (std::find(required.begin(), required.end(), name) != required.end()) continue;
            const auto& used = model_.extensionsUsed;
            (std::find(used.begin(), used.end(), name) != used.end() ? required : lacking).push_back(name);
        }
        if (lacking.empty() || !options_.warn_unused_required) return;
        std::string names;
        for (const std::string& n : lacking) names += (names.empty() ? "" : ", ") + n;
        warnings_.push_back(path_ + ": the source required " + names +
                            ", which this output does not use (its content did not travel or has not arrived); the "
                            "output does not require " + (lacking.size() == 1 ? "it" : "them"));
    }

    void write_cameras_lights() {
        for (const SceneCamera& c : asset_.scene.cameras) {
            tinygltf::Camera g;
            g.name = c.name;
            extras_at(ExtrasTarget::Camera, model_.cameras.size(), "/cameras/" + std::to_string(model_.cameras.size()));
            if (!valid_camera(c)) {
                warnings_.push_back(path_ + ": camera " + std::to_string(model_.cameras.size()) +
                                    " has values glTF does not allow; written as a default perspective camera");
                g.type = "perspective";
                g.perspective.yfov = 0.8;
                g.perspective.znear = 0.01;
            } else if (c.projection == CameraProjection::Perspective) {
                g.type = "perspective";
                g.perspective.aspectRatio = c.a;  // 0: left out (tinygltf writes it only when above 0)
                g.perspective.yfov = c.b;
                g.perspective.znear = c.znear;
                g.perspective.zfar = c.zfar;      // 0: infinite, left out when saving (gltf_write)
            } else {
                g.type = "orthographic";
                g.orthographic.xmag = c.a;
                g.orthographic.ymag = c.b;
                g.orthographic.znear = c.znear;
                g.orthographic.zfar = c.zfar;
            }
            model_.cameras.push_back(std::move(g));
        }
        for (const SceneLight& l : asset_.scene.lights) {
            static const char* kTypes[] = {"directional", "point", "spot"};
            tinygltf::Light g;
            g.name = l.name;
            extras_at(ExtrasTarget::Light, model_.lights.size(),
                      "/extensions/KHR_lights_punctual/lights/" + std::to_string(model_.lights.size()));
            if (!valid_light(l)) {
                warnings_.push_back(path_ + ": light " + std::to_string(model_.lights.size()) +
                                    " has values KHR_lights_punctual does not allow; written as a white point light");
                g.type = "point";
                g.color = {1, 1, 1};
            } else {
                g.type = kTypes[size_t(l.type)];
                g.color = {l.color[0], l.color[1], l.color[2]};
                g.intensity = l.intensity;
                g.range = l.range;  // 0: left out (tinygltf writes it only when above 0)
                g.spot.innerConeAngle = l.inner_cone;
                g.spot.outerConeAngle = l.outer_cone;
            }
            model_.lights.push_back(std::move(g));
        }
        // Listed here rather than left to tinygltf (which adds it while serializing), so that the
        // extensions used are known before the document is written (require_source_extensions).
        if (!model_.lights.empty()) used_extensions_.insert("KHR_lights_punctual");
    }

    // ---- nodes

    void set_transform(tinygltf::Node& g, const SceneNode& n, const std::string& what) {
        bool finite = true;
        for (float v : n.matrix) finite = finite && std::isfinite(v);
        for (float v : n.translation) finite = finite && std::isfinite(v);
        for (float v : n.rotation) finite = finite && std::isfinite(v);
        for (float v : n.scale) finite = finite && std::isfinite(v);
        if (!finite) {
            warnings_.push_back(what + " has a non-finite transform; written without it");
            return;
        }
        if (n.has_matrix) {
            static const std::array<float, 16> identity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
            if (n.matrix != identity) g.matrix.assign(n.matrix.begin(), n.matrix.end());
            return;
        }
        if (n.translation != std::array<float, 3>{0, 0, 0}) g.translation.assign(n.translation.begin(), n.translation.end());
        if (n.rotation != std::array<float, 4>{0, 0, 0, 1}) {
            double len = 0;
            for (float v : n.rotation) len += double(v) * v;
            len = std::sqrt(len);
            if (len > 0) {
                for (float v : n.rotation) g.rotation.push_back(v / len);
            } else {
                warnings_.push_back(what + " has a zero rotation quaternion; written without rotation");
            }
        }
        if (n.scale != std::array<float, 3>{1, 1, 1}) g.scale.assign(n.scale.begin(), n.scale.end());
    }

    // Which nodes can be written: those whose parent chain ends at a root. A parent outside the
    // table makes a node a root; a cycle leaves its nodes out.
    std::vector<bool> writable_nodes() {
        const auto& nodes = asset_.scene.nodes;
        const size_t n = nodes.size();
        parent_.assign(n, -1);
        for (size_t i = 0; i < n; ++i) {
            uint16_t p = nodes[i].parent;
            if (p == kNone) continue;
            if (p >= n || p == i) {
                warnings_.push_back(path_ + ": node " + std::to_string(i) + " names parent " + std::to_string(p) +
                                    ", which is not in the scene; written as a root");
                continue;
            }
            parent_[i] = p;
        }
        std::vector<int> state(n, 0);  // 0 unknown, 1 reaches a root, 2 in or under a cycle
        std::vector<bool> ok(n, false);
        for (size_t i = 0; i < n; ++i) {
            std::vector<size_t> chain;
            size_t at = i;
            int result = 1;
            std::set<size_t> seen;
            while (true) {
                if (state[at] != 0) {
                    result = state[at];
                    break;
                }
                if (!seen.insert(at).second) {
                    result = 2;
                    break;
                }
                chain.push_back(at);
                if (parent_[at] < 0) {
                    result = 1;
                    break;
                }
                at = size_t(parent_[at]);
            }
            for (size_t c : chain) state[c] = result;
        }
        size_t cyclic = 0;
        for (size_t i = 0; i < n; ++i) {
            ok[i] = state[i] == 1;
            if (!ok[i]) ++cyclic;
        }
        if (cyclic)
            warnings_.push_back(path_ + ": " + std::to_string(cyclic) +
                                " node(s) in or under a parent cycle are left out");
        return ok;
    }

    void write_scene_graph() {
        const auto& nodes = asset_.scene.nodes;
        std::vector<bool> ok = writable_nodes();
        std::vector<int> out(nodes.size(), -1);
        for (size_t i = 0; i < nodes.size(); ++i)
            if (ok[i]) {
                out[i] = int(model_.nodes.size());
                model_.nodes.emplace_back();
            }
        plan_skins(ok, out);
        for (size_t i = 0; i < nodes.size(); ++i) {
            if (!ok[i]) continue;
            const SceneNode& n = nodes[i];
            const std::string what = path_ + ": node " + std::to_string(i) + (n.name.empty() ? "" : " (" + n.name + ")");
            tinygltf::Node g;
            g.name = n.name;
            extras_at(ExtrasTarget::Node, i, "/nodes/" + std::to_string(out[i]));
            set_transform(g, n, what);
            if (n.mesh != kNone) {
                if (n.mesh >= asset_.scene.meshes.size()) {
                    warnings_.push_back(what + " names mesh " + std::to_string(n.mesh) +
                                        ", which is not in the scene; written without it");
                } else if (int mesh = gltf_mesh(n.mesh); mesh >= 0) {
                    attach_mesh(g, mesh);
                    if (n.skin != kNone && skinned_meshes_.count(n.mesh)) g.skin = skin_out_.at(n.skin);
                }
            }
            // Format 1.10 (spec 26.4): the node's camera, and its light as KHR_lights_punctual says.
            if (n.camera != kNone) {
                if (n.camera < model_.cameras.size()) g.camera = int(n.camera);
                else warnings_.push_back(what + " names camera " + std::to_string(n.camera) + ", which is not in the scene; written without it");
            }
            if (n.light != kNone) {
                if (n.light < model_.lights.size()) {
                    tinygltf::Value::Object light;
                    light["light"] = tinygltf::Value(int(n.light));
                    g.extensions["KHR_lights_punctual"] = tinygltf::Value(std::move(light));
                } else {
                    warnings_.push_back(what + " names light " + std::to_string(n.light) + ", which is not in the scene; written without it");
                }
            }
            model_.nodes[size_t(out[i])] = std::move(g);
        }
        // Children in index order, as the format defines them.
        tinygltf::Scene scene;
        for (size_t i = 0; i < nodes.size(); ++i) {
            if (!ok[i]) continue;
            if (parent_[i] < 0) scene.nodes.push_back(out[i]);
            else model_.nodes[size_t(out[size_t(parent_[i])])].children.push_back(out[i]);
        }
        if (!scene.nodes.empty()) {  // tinygltf writes an empty scene as null
            extras_at(ExtrasTarget::Scene, 0, "/scenes/0");
            model_.scenes.push_back(std::move(scene));
            model_.defaultScene = 0;
        }
        write_animations(out);
    }

    // Animations (format 1.4) over the nodes written: node_out[i] is the glTF node of asset node i
    // (-1: not written). A track whose node is not written is left out, and an animation left without
    // track too, each with a warning.
    void write_animations(const std::vector<int>& node_out) {
        for (size_t a = 0; a < asset_.scene.animations.size(); ++a) {
            const SceneAnimation& animation = asset_.scene.animations[a];
            const std::string what = path_ + ": animation " + std::to_string(a) +
                                     (animation.name.empty() ? "" : " (" + animation.name + ")");
            tinygltf::Animation g;
            g.name = animation.name;
            std::set<std::pair<int, int>> targets;
            for (size_t t = 0; t < animation.tracks.size(); ++t) {
                const SceneAnimation::Track& track = animation.tracks[t];
                const int node = track.node < node_out.size() ? node_out[track.node] : -1;
                const size_t per_key = animation_values_per_key(track.path, track.interpolation, track.targets);
                const bool weights = track.path == AnimationPath::Weights;
                if (weights && (node < 0 || model_.nodes[size_t(node)].mesh < 0 ||
                                mesh_targets_out_[model_.nodes[size_t(node)].mesh] != track.targets || track.targets == 0)) {
                    warnings_.push_back(what + ": track " + std::to_string(t) + " moves morph target weights of a node "
                                        "whose mesh is not written with " + std::to_string(track.targets) +
                                        " morph targets; left out");
                    continue;
                }
                if (node < 0 || track.times.empty() || track.values.size() != track.times.size() * per_key ||
                    !targets.insert({node, int(track.path)}).second) {
                    warnings_.push_back(what + ": track " + std::to_string(t) +
                                        " moves a node that is not written (or one another track moves); left out");
                    continue;
                }
                // Tracks with the same key times share one input accessor (as glTF exporters write them:
                // the Fox's 63 tracks have 3 lists of times).
                int& input = animation_inputs_[track.times];
                if (input == 0) {
                    const auto [lo, hi] = std::minmax_element(track.times.begin(), track.times.end());
                    const int input_view = add_buffer_view(model_, track.times.data(), track.times.size() * 4, 0);
                    input = 1 + add_accessor(model_, input_view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                                             track.times.size(), {double(*lo)}, {double(*hi)});
                }
                const bool rotation = track.path == AnimationPath::Rotation;
                const size_t components = weights ? 1 : rotation ? 4 : 3;
                if (!std::all_of(track.values.begin(), track.values.end(), [](float v) { return std::isfinite(v); })) {
                    warnings_.push_back(what + ": track " + std::to_string(t) + " has a value that is not a finite number; left out");
                    continue;
                }
                // glTF wants unit rotations (the values; a cubic spline's tangents are free): each one
                // further than 1e-6 from unit length is normalized, and a zero one becomes the identity.
                std::vector<float> values = track.values;
                if (rotation) {
                    const bool cubic = track.interpolation == Interpolation::CubicSpline;
                    size_t zero = 0;
                    for (size_t q = cubic ? 4 : 0; q + 4 <= values.size(); q += cubic ? 12 : 4) {
                        double length = 0;
                        for (size_t k = 0; k < 4; ++k) length += double(values[q + k]) * values[q + k];
                        length = std::sqrt(length);
                        if (!(length > 1e-12) || !std::isfinite(length)) {
                            ++zero;
                            values[q] = values[q + 1] = values[q + 2] = 0, values[q + 3] = 1;
                        } else if (std::abs(length - 1) > 1e-6) {  // a unit one keeps its bits
                            for (size_t k = 0; k < 4; ++k) values[q + k] = float(values[q + k] / length);
                        }
                    }
                    if (zero)
                        warnings_.push_back(what + ": track " + std::to_string(t) + ": " + std::to_string(zero) +
                                            " zero rotation(s) written as the identity");
                }
                int output = -1;
                if (rotation && options_.quantize && track.interpolation != Interpolation::CubicSpline) {
                    // Quantized output (--quantize, --meshopt): unit quaternions as normalized int16, which
                    // glTF allows for rotations (within 1.6e-5 a component; a cubic spline's free tangents
                    // stay float).
                    std::vector<int16_t> q(values.size());
                    for (size_t k = 0; k < values.size(); ++k)
                        q[k] = int16_t(std::lround(std::clamp(values[k], -1.0f, 1.0f) * 32767.0));
                    const int output_view = add_buffer_view(model_, q.data(), q.size() * 2, 0);
                    output = add_accessor(model_, output_view, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4,
                                          values.size() / components, {}, {}, true);
                } else {
                    const int output_view = add_buffer_view(model_, values.data(), values.size() * 4, 0);
                    output = add_accessor(model_, output_view, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                          weights ? TINYGLTF_TYPE_SCALAR : rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3,
                                          values.size() / components);
                }
                tinygltf::AnimationSampler sampler;
                sampler.input = input - 1;
                sampler.output = output;
                sampler.interpolation = track.interpolation == Interpolation::Step          ? "STEP"
                                        : track.interpolation == Interpolation::CubicSpline ? "CUBICSPLINE"
                                                                                            : "LINEAR";
                tinygltf::AnimationChannel channel;
                channel.sampler = int(g.samplers.size());
                channel.target_node = node;
                channel.target_path = track.path == AnimationPath::Translation ? "translation"
                                      : rotation                               ? "rotation"
                                      : weights                                ? "weights"
                                                                               : "scale";
                g.samplers.push_back(std::move(sampler));
                g.channels.push_back(std::move(channel));
            }
            if (g.channels.empty()) {
                warnings_.push_back(what + ": no track of it can be written; left out");
                continue;
            }
            extras_at(ExtrasTarget::Animation, a, "/animations/" + std::to_string(model_.animations.size()));
            model_.animations.push_back(std::move(g));
        }
    }

    // Skins (format 1.5): which meshes are written skinned and the glTF skins, over the written nodes
    // (out[i]: the glTF node of asset node i, -1 when not written). A mesh is skinned when every
    // written node showing it names a skin that can be written (its joints and skeleton written)
    // and every present object of it has weights per vertex; a mesh shown both skinned and not, or
    // whose weights name joints past a skin, is written unskinned with a warning.
    void plan_skins(const std::vector<bool>& ok, const std::vector<int>& out) {
        const auto& nodes = asset_.scene.nodes;
        const auto& skins = asset_.scene.skins;
        std::vector<int> writable(skins.size(), 1);
        std::vector<std::string> unwritable(skins.size());  // why a skin cannot be written
        for (size_t s = 0; s < skins.size(); ++s) {
            unwritable[s] = skin_problem(skins[s], out);
            writable[s] = unwritable[s].empty();
        }
        std::map<size_t, std::vector<size_t>> users;  // asset mesh -> written nodes showing it
        for (size_t i = 0; i < nodes.size(); ++i)
            if (ok[i] && nodes[i].mesh != kNone && nodes[i].mesh < asset_.scene.meshes.size()) users[nodes[i].mesh].push_back(i);
        for (const auto& [mesh, shown_by] : users) {
            size_t with_skin = 0;
            uint16_t joints = 0xFFFF;
            std::string skin_why;
            for (size_t i : shown_by)
                if (nodes[i].skin != kNone) {
                    ++with_skin;
                    const bool can = nodes[i].skin < skins.size() && writable[nodes[i].skin];
                    joints = can ? std::min<uint16_t>(joints, uint16_t(skins[nodes[i].skin].joints.size())) : 0;
                    if (!can && skin_why.empty())
                        skin_why = "skin " + std::to_string(nodes[i].skin) +
                                   (nodes[i].skin < skins.size() ? ": " + unwritable[nodes[i].skin] : " does not exist");
                }
            if (with_skin == 0) continue;
            const std::string what = path_ + ": mesh " + std::to_string(mesh);
            std::string why;
            if (with_skin < shown_by.size()) why = "it is shown both by skinned nodes and by nodes without a skin";
            else if (joints == 0) why = skin_why;
            for (const auto& p : asset_.scene.meshes[mesh].primitives) {
                if (!why.empty() || !object_present(p.object)) continue;
                const VertexWeights* w = p.object < asset_.weights.size() ? &asset_.weights[p.object] : nullptr;
                if (!w || w->joints.size() != asset_.objects[p.object].positions.size() ||
                    w->weights.size() != w->joints.size()) {
                    why = "object " + std::to_string(p.object) + " has no weights per vertex";
                    continue;
                }
                for (size_t v = 0; v < w->joints.size() && why.empty(); ++v)
                    for (size_t k = 0; k < 4; ++k)
                        if (w->weights[v][k] > 0 && w->joints[v][k] >= joints) {
                            why = "the weights of object " + std::to_string(p.object) + " name joint " +
                                  std::to_string(w->joints[v][k]) + ", past its skin's " + std::to_string(joints);
                            break;
                        }
            }
            if (!why.empty()) {
                warnings_.push_back(what + " is written without skinning (its nodes in the bind pose): " + why);
                continue;
            }
            skinned_meshes_.insert(mesh);
            for (size_t i : shown_by) write_skin(nodes[i].skin, out);
        }
    }

    // The written root above asset node `i` (itself when it is written as a root).
    size_t written_root(size_t i) const {
        for (size_t steps = 0; parent_[i] >= 0 && steps < parent_.size(); ++steps) i = size_t(parent_[i]);
        return i;
    }
    // Whether asset node `ancestor` is `i` or above it in the written graph.
    bool written_at_or_above(size_t ancestor, size_t i) const {
        for (size_t steps = 0; steps <= parent_.size(); ++steps) {
            if (i == ancestor) return true;
            if (parent_[i] < 0) return false;
            i = size_t(parent_[i]);
        }
        return false;
    }

    // Why glTF cannot take `skin` over the written nodes (out[i] < 0: node i not written); empty when
    // it can. A stream may carry what glTF forbids: a joint twice, an inverse bind matrix that is
    // not an affine transform, joints without a common root.
    std::string skin_problem(const SceneSkin& skin, const std::vector<int>& out) const {
        const auto& nodes = asset_.scene.nodes;
        if (skin.joints.empty()) return "it has no joint";
        std::set<uint16_t> seen;
        for (size_t j = 0; j < skin.joints.size(); ++j) {
            const SkinJoint& joint = skin.joints[j];
            if (joint.node >= nodes.size() || out[joint.node] < 0)
                return "joint " + std::to_string(j) + " names node " + std::to_string(joint.node) + ", which is not written";
            if (!seen.insert(joint.node).second)
                return "node " + std::to_string(joint.node) + " is more than one of its joints (glTF joints are distinct)";
            const auto& m = joint.inverse_bind;
            const bool finite = std::all_of(m.begin(), m.end(), [](float v) { return std::isfinite(v); });
            auto near = [](float v, float to) { return std::abs(v - to) <= 1e-5f; };  // write_skin snaps these
            if (!finite || !near(m[3], 0) || !near(m[7], 0) || !near(m[11], 0) || !near(m[15], 1))
                return "the inverse bind matrix of joint " + std::to_string(j) + " is not an affine transform";
        }
        const size_t root = written_root(skin.joints.front().node);
        for (const SkinJoint& joint : skin.joints)
            if (written_root(joint.node) != root) return "its joints have no common root";
        if (skin.skeleton != kNone && (skin.skeleton >= nodes.size() || out[skin.skeleton] < 0))
            return "its skeleton names node " + std::to_string(skin.skeleton) + ", which is not written";
        return {};
    }

    // The glTF skin of asset skin `s` (written once).
    void write_skin(uint16_t s, const std::vector<int>& out) {
        if (skin_out_.count(s)) return;
        const SceneSkin& skin = asset_.scene.skins[s];
        tinygltf::Skin g;
        g.name = skin.name;
        extras_at(ExtrasTarget::Skin, s, "/skins/" + std::to_string(model_.skins.size()));
        std::vector<float> matrices;
        for (const SkinJoint& j : skin.joints) {
            g.joints.push_back(out[j.node]);
            matrices.insert(matrices.end(), j.inverse_bind.begin(), j.inverse_bind.end());
            // glTF wants the last row exactly (0, 0, 0, 1); skin_problem let only rounding differ.
            float* last = matrices.data() + matrices.size() - 16;
            last[3] = last[7] = last[11] = 0, last[15] = 1;
        }
        if (skin.skeleton != kNone) {
            // glTF's skeleton is the joints' common root: one that is not is left out (it is optional).
            const bool common = std::all_of(skin.joints.begin(), skin.joints.end(),
                                            [&](const SkinJoint& j) { return written_at_or_above(skin.skeleton, j.node); });
            if (common) g.skeleton = out[skin.skeleton];
            else
                warnings_.push_back(path_ + ": skin " + std::to_string(s) + (skin.name.empty() ? "" : " (" + skin.name + ")") +
                                    ": its skeleton, node " + std::to_string(skin.skeleton) +
                                    ", is not above every joint; written without it");
        }
        const int view = add_buffer_view(model_, matrices.data(), matrices.size() * sizeof(float), 0);
        g.inverseBindMatrices = add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, skin.joints.size());
        skin_out_[s] = int(model_.skins.size());
        model_.skins.push_back(std::move(g));
    }

    // JOINTS_0 (unsigned byte when every joint is below 256, else unsigned short) and WEIGHTS_0
    // (float) of a primitive.
    // `quantized`: weights that are all multiples of 1/255 (a stream's) as normalized bytes
    // (KHR_mesh_quantization), exactly; others as floats.
    void add_weights(tinygltf::Primitive& prim, const VertexWeights& w, bool quantized = false) {
        uint16_t top = 0;
        for (const auto& j : w.joints)
            for (uint16_t x : j) top = std::max(top, x);
        if (top < 256) {
            std::vector<uint8_t> bytes;
            for (const auto& j : w.joints)
                for (uint16_t x : j) bytes.push_back(uint8_t(x));
            const int view = add_buffer_view(model_, bytes.data(), bytes.size(), TINYGLTF_TARGET_ARRAY_BUFFER);
            prim.attributes["JOINTS_0"] =
                add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, w.joints.size());
        } else {
            const int view = add_buffer_view(model_, w.joints.data(), w.joints.size() * sizeof(w.joints[0]),
                                             TINYGLTF_TARGET_ARRAY_BUFFER);
            prim.attributes["JOINTS_0"] =
                add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, w.joints.size());
        }
        if (quantized && skin_weights::in_255ths(w.weights)) {
            const std::vector<std::array<uint8_t, 4>> q = skin_weights::as_bytes(w.weights);
            const int view = add_buffer_view(model_, q.data(), q.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER);
            prim.attributes["WEIGHTS_0"] = add_accessor(model_, view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                        TINYGLTF_TYPE_VEC4, w.weights.size(), {}, {}, true);
        } else {
            prim.attributes["WEIGHTS_0"] = add_float_attribute(model_, w.weights, TINYGLTF_TYPE_VEC4, false);
        }
    }

    // Shows glTF mesh `mesh` at node `g` (index `at`): directly, or through a child node holding
    // the dequantizing transform of a quantized mesh.
    void attach_mesh(tinygltf::Node& g, int mesh) {
        auto it = dequantization_.find(mesh);
        if (it == dequantization_.end()) {
            g.mesh = mesh;
            return;
        }
        tinygltf::Node wrapper;
        wrapper.name = (g.name.empty() ? "node" : g.name) + " (dequantization)";
        wrapper.mesh = mesh;
        wrapper.translation = {it->second.center[0], it->second.center[1], it->second.center[2]};
        wrapper.scale = {it->second.scale, it->second.scale, it->second.scale};
        g.children.push_back(int(model_.nodes.size()));
        model_.nodes.push_back(std::move(wrapper));
    }

    // No scene graph (a format 1.0 stream): one root node and one mesh per object.
    void write_flat() {
        tinygltf::Scene scene;
        for (size_t o = 0; o < asset_.objects.size(); ++o) {
            if (!object_present(o)) {
                warnings_.push_back(path_ + ": object " + std::to_string(o) + " has not arrived; left out");
                continue;
            }
            SceneMesh m;
            m.name = asset_.objects[o].name.empty() ? "object" + std::to_string(o) : asset_.objects[o].name;
            m.primitives.push_back({uint16_t(o), kNone});
            flat_meshes_.push_back(m);
        }
        for (size_t i = 0; i < flat_meshes_.size(); ++i) {
            const SceneMesh& m = flat_meshes_[i];
            std::optional<Dequantization> dq = mesh_dequantization(m);
            const uint16_t o = m.primitives[0].object;
            auto prim = object_primitive(o, dq, dq ? int(o) : -1, false, path_ + ": object " + std::to_string(o));
            if (!prim) continue;
            tinygltf::Mesh g;
            g.name = m.name;
            g.primitives.push_back(std::move(*prim));
            int mesh = int(model_.meshes.size());
            model_.meshes.push_back(std::move(g));
            if (dq) dequantization_[mesh] = *dq;
            tinygltf::Node node;
            node.name = m.name;
            int at = int(model_.nodes.size());
            model_.nodes.emplace_back();
            attach_mesh(node, mesh);
            model_.nodes[size_t(at)] = std::move(node);
            scene.nodes.push_back(at);
        }
        if (!scene.nodes.empty()) {  // tinygltf writes an empty scene as null
            model_.scenes.push_back(std::move(scene));
            model_.defaultScene = 0;
        }
    }

    const std::string& path_;
    const Asset& asset_;
    const AssetWriteOptions options_;  // a copy: the caller's may be a temporary
    std::vector<std::string>& warnings_;
    tinygltf::Model model_;
    std::map<std::pair<ExtrasTarget, uint16_t>, const std::string*> extras_;  // format 1.12: (kind, index) -> text
    gltf_write::JsonPatches extras_patches_;  // where the written elements' extras go
    std::vector<int> texture_out_;
    std::vector<bool> material_whole_;  // per asset material: every texture it uses was written
    std::set<std::string> used_extensions_;  // extensions the materials' patches use (spec 18), and lights'
    std::map<uint16_t, int> untextured_;
    std::map<std::tuple<size_t, int, bool>, std::optional<tinygltf::Primitive>> primitives_;
    std::set<size_t> skinned_meshes_;   // asset meshes written with JOINTS_0 / WEIGHTS_0
    std::map<uint16_t, int> skin_out_;  // asset skin -> glTF skin
    std::map<size_t, int> mesh_out_;
    std::map<int, uint8_t> mesh_targets_out_;  // glTF mesh -> its morph target count
    std::map<int, Dequantization> dequantization_;
    std::vector<int> parent_;
    std::vector<SceneMesh> flat_meshes_;
    bool used_draco_ = false;
    bool used_quantization_ = false;
    std::map<std::vector<float>, int> animation_inputs_;  // key times -> 1 + their accessor
};

}  // namespace

std::string check_asset_write_options(const AssetWriteOptions& o) {
    if (o.draco && o.quantize)
        return "--draco and --quantize cannot be combined (Draco quantizes the attributes itself)";
    if (o.draco && o.meshopt)
        return "--draco and --meshopt cannot be combined (each compresses the geometry its own way)";
    auto bits = [](int b, int lo, int hi) { return b >= lo && b <= hi; };
    if (!bits(o.draco_position_bits, 1, 30)) return "Draco position bits must be 1..30";
    if (!bits(o.draco_normal_bits, 1, 30)) return "Draco normal bits must be 1..30";
    if (!bits(o.draco_texcoord_bits, 1, 30)) return "Draco texture coordinate bits must be 1..30";
    if (!bits(o.draco_color_bits, 1, 30)) return "Draco colour bits must be 1..30";
    if (!bits(o.draco_speed, 0, 10)) return "Draco speed must be 0..10";
    return "";
}

namespace {
// What the writer builds: meshopt output is the quantized file, compressed afterwards.
AssetWriteOptions writer_options(AssetWriteOptions options) {
    if (options.meshopt) options.quantize = true;
    return options;
}
}  // namespace

bool write_asset(const std::string& path, const Asset& asset, const AssetWriteOptions& options,
                 std::vector<std::string>& warnings, std::string& error) {
    if (std::string bad = check_asset_write_options(options); !bad.empty()) {
        error = path + ": " + bad;
        return false;
    }
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".ply" || ext == ".obj") {
        if (options.draco || options.quantize || options.meshopt) {
            error = path + ": Draco, quantized and meshopt output are glTF features (write .glb or .gltf)";
            return false;
        }
        std::vector<Mesh> meshes = flatten_asset(asset);
        if (meshes.empty()) {
            error = path + ": no object to write";
            return false;
        }
        return write_meshes(path, meshes, error);
    }
    if (ext != ".glb" && ext != ".gltf") {
        error = path + ": unknown output type '" + ext + "' (expected .glb, .gltf, .ply or .obj)";
        return false;
    }
    AssetWriter writer(path, asset, writer_options(options), warnings);
    tinygltf::Model model = writer.build();
    gltf_write::JsonPatches patches = writer.patches();
    if (options.meshopt) meshopt_output::compress(model, patches);
    return save_model(path, model, ext == ".glb", error, patches);
}

bool write_asset_glb(const Asset& asset, const AssetWriteOptions& options, std::vector<uint8_t>& out,
                     std::vector<std::string>& warnings, std::string& error) {
    if (std::string bad = check_asset_write_options(options); !bad.empty()) {
        error = bad;
        return false;
    }
    AssetWriter writer("glb", asset, writer_options(options), warnings);
    tinygltf::Model model = writer.build();
    gltf_write::JsonPatches patches = writer.patches();
    if (options.meshopt) meshopt_output::compress(model, patches);
    return glb_bytes(model, out, error, patches);
}

}  // namespace ellicast

// Reading a model with its scene: glTF nodes, meshes, materials and textures as they are, each
// distinct primitive once in its mesh's own frame (instances share it). OBJ / PLY / OFF / STL
// become one node with one mesh. Accessor and primitive reading is shared with gltf_input.cpp.
#include "ellicast/converters/asset.h"

#include "gltf_read.h"
#include "json_value.h"
#include "material_extensions.h"
#include "ellicast/converters/image_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"  // false positive in string concatenation (GCC bug 105651)
#endif

namespace ellicast {

namespace {

using namespace gltf_read;

constexpr size_t kMaxTable = 0xFFFE;  // entries of a scene table (0xFFFF means "none")
constexpr size_t kMaxName = 255;       // bytes of a name on the wire

// The raw bytes of images that came from a URI (data: or external file), by image index. Images
// stored in a bufferView are read from it afterwards, with their bounds checked.
struct CapturedImages {
    std::map<int, std::vector<uint8_t>> bytes;
};

bool capture_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                   const unsigned char* bytes, int size, void* user) {
    if (image->bufferView >= 0) return true;  // tinygltf does not check the view's bounds: read it ourselves
    if (bytes && size > 0) static_cast<CapturedImages*>(user)->bytes[index].assign(bytes, bytes + size);
    return true;
}

// A name cut to the wire's 255 bytes without splitting a UTF-8 sequence.
std::string wire_name(const std::string& name, const std::string& what, std::vector<std::string>& warnings) {
    if (name.size() <= kMaxName) return name;
    size_t n = kMaxName;
    while (n > 0 && (uint8_t(name[n]) & 0xC0) == 0x80) --n;
    warnings.push_back(what + ": name longer than 255 bytes, shortened");
    return name.substr(0, n);
}

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
    return out;
}

// Checks a KHR_texture_transform object (it travels in the material's patch, spec 18); false with
// `why` when a receiver could not apply it.
bool check_uv_transform(const tinygltf::Value& value, std::string& why) {
    if (!value.IsObject()) return why = "is not an object", false;
    auto pair = [&](const char* name) {
        if (!value.Has(name)) return true;
        const tinygltf::Value& a = value.Get(name);
        if (!a.IsArray() || a.ArrayLen() != 2 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber()) return false;
        return std::isfinite(a.Get(0).GetNumberAsDouble()) && std::isfinite(a.Get(1).GetNumberAsDouble());
    };
    if (!pair("offset")) return why = "has an offset that is not two finite numbers", false;
    if (!pair("scale")) return why = "has a scale that is not two finite numbers", false;
    if (value.Has("rotation")) {
        const tinygltf::Value& r = value.Get("rotation");
        if (!r.IsNumber() || !std::isfinite(r.GetNumberAsDouble())) return why = "has a rotation that is not a finite number", false;
    }
    if (value.Has("texCoord")) {
        const tinygltf::Value& tc = value.Get("texCoord");
        if (!tc.IsNumber() || tc.GetNumberAsDouble() != 0)
            return why = "selects another texture-coordinate set than TEXCOORD_0, which ellicast does not carry", false;
    }
    return true;
}

// Everything of one glTF file while it becomes an Asset.
class GltfAssetReader {
public:
    GltfAssetReader(const std::string& path, const tinygltf::Model& model, const CapturedImages& images, Asset& asset)
        : path_(path), model_(model), images_(images), asset_(asset), warnings_(asset.warnings) {}

    void read() {
        warn_not_carried();
        std::vector<int> roots = scene_roots();
        for (int root : roots) visit(root, -1, 0);
        if (node_order_.size() > kMaxTable) throw InputError(path_ + ": more than 65534 nodes in the scene");
        // Node table in the file's order (indices stay as the asset had them when every node is shown).
        std::vector<int> order = node_order_;
        std::sort(order.begin(), order.end());
        for (size_t i = 0; i < order.size(); ++i) new_node_[order[i]] = uint16_t(i);
        read_materials();
        read_cameras_lights();
        for (int old : order) add_node(old);
        if (asset_.objects.empty()) throw InputError(path_ + ": the scene holds no triangle or point primitive to send");
        read_animations();
        // Format 1.12 (spec 28): the asset's and the default scene's extras.
        add_extras(ExtrasTarget::Asset, 0, model_.asset.extras_json_string, path_ + ": the asset");
        if (!model_.scenes.empty()) {
            const int scene = model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size() ? model_.defaultScene : 0;
            add_extras(ExtrasTarget::Scene, 0, model_.scenes[size_t(scene)].extras_json_string, path_ + ": scene " + std::to_string(scene));
        }
        warn_extras_not_carried();
        read_required_extensions();
    }

private:
    // Format 1.12 (spec 28): an element's extras, as JSON text (the reader keeps them as text, see
    // load_model), for the element `index` of the description's table of `kind`; none for an absent
    // or null value, a warning for one too large or not acceptable.
    void add_extras(ExtrasTarget kind, size_t index, const std::string& text, const std::string& where) {
        if (text.empty() || text == "null") return;
        if (!acceptable_extras_text(text)) {
            warnings_.push_back(where + ": its extras are not JSON ellicast can carry (not finite numbers, duplicate "
                                "member names, or nested deeper than 32); not sent");
            return;
        }
        if (text.size() > kMaxExtrasText) {
            warnings_.push_back(where + ": its extras (" + std::to_string(text.size()) + " bytes of JSON) are larger than " +
                                std::to_string(kMaxExtrasText) + " bytes; not sent");
            return;
        }
        asset_.scene.extras.push_back({kind, uint16_t(index), text});
    }

    // Format 1.13 (spec 29.3): the source's required extensions but those of how it stored geometry
    // (the receiver chooses its own storage and requires what it uses).
    void read_required_extensions() {
        static const std::set<std::string> storage = {"KHR_draco_mesh_compression", "KHR_mesh_quantization",
                                                      "EXT_meshopt_compression"};
        std::vector<std::string>& out = asset_.scene.required_extensions;
        for (const std::string& name : model_.extensionsRequired) {
            if (storage.count(name) || std::find(out.begin(), out.end(), name) != out.end()) continue;
            if (!is_extension_name(name)) {
                warnings_.push_back(path_ + ": required extension \"" + name +
                                    "\" is not an extension name ellicast can send (letters, digits and underscores, "
                                    "at most 64); the output will not require it");
                continue;
            }
            out.push_back(name);
        }
        if (out.size() > kMaxRequiredExtensions) {
            warnings_.push_back(path_ + ": " + std::to_string(out.size()) + " required extensions, more than the " +
                                std::to_string(kMaxRequiredExtensions) + " a stream can name; the output will require none");
            out.clear();
        }
    }

    // What has extras but no table in the stream (spec 28.4): said once, counting them.
    void warn_extras_not_carried() {
        std::map<std::string, size_t> found;
        auto count = [&](const std::string& v, const char* what) {
            if (!v.empty() && v != "null") ++found[what];
        };
        count(model_.extras_json_string, "the glTF root object");
        for (const auto& m : model_.meshes)
            for (const auto& p : m.primitives) count(p.extras_json_string, "primitive");
        for (const auto& a : model_.accessors) count(a.extras_json_string, "accessor");
        for (const auto& b : model_.bufferViews) count(b.extras_json_string, "buffer view");
        for (const auto& b : model_.buffers) count(b.extras_json_string, "buffer");
        for (const auto& i : model_.images) count(i.extras_json_string, "image");
        for (const auto& smp : model_.samplers) count(smp.extras_json_string, "sampler");
        // (Not animation samplers: tinygltf gives each the extras of its animation.)
        for (const auto& a : model_.animations)
            for (const auto& c : a.channels) count(c.extras_json_string, "animation channel");
        for (const auto& m : model_.materials) {
            count(m.normalTexture.extras_json_string, "texture info");
            count(m.occlusionTexture.extras_json_string, "texture info");
            count(m.emissiveTexture.extras_json_string, "texture info");
            count(m.pbrMetallicRoughness.baseColorTexture.extras_json_string, "texture info");
            count(m.pbrMetallicRoughness.metallicRoughnessTexture.extras_json_string, "texture info");
        }
        if (found.empty()) return;
        std::vector<std::string> items;
        for (const auto& [what, n] : found) items.push_back(std::to_string(n) + " " + what + (n == 1 ? "" : "s"));
        warnings_.push_back(path_ + ": extras of " + join(items) +
                            " not sent (ellicast carries the extras of the asset, its scene, nodes, meshes, materials, "
                            "textures, animations, skins, cameras and lights)");
    }

    // A glTF double as the f32 a CAMERA or LIGHT packet carries: the nearest, or the nearest on the
    // allowed side when rounding crosses `limit` (spec 26.5: a yfov just below pi, a cone angle of pi / 2).
    static float wire_float(double v, double limit = std::numeric_limits<double>::infinity()) {
        float f = float(v);
        if (v <= limit && double(f) > limit) f = std::nextafter(f, 0.0f);
        return f;
    }

    // Cameras and KHR_lights_punctual lights (format 1.10, spec 26): every one, in the asset's order;
    // one that breaks spec 26.2 / 26.3 as f32 values is not sent, with a warning.
    void read_cameras_lights() {
        constexpr double kPi = 3.14159265358979323846;
        for (size_t i = 0; i < model_.cameras.size(); ++i) {
            const tinygltf::Camera& g = model_.cameras[i];
            const std::string where = path_ + ": camera " + std::to_string(i) + (g.name.empty() ? "" : " (" + g.name + ")");
            SceneCamera c;
            c.name = wire_name(g.name, where, warnings_);
            bool known = true;
            if (g.type == "perspective") {
                c.projection = CameraProjection::Perspective;
                c.a = wire_float(g.perspective.aspectRatio);
                c.b = wire_float(g.perspective.yfov, kPi);
                c.znear = wire_float(g.perspective.znear);
                c.zfar = wire_float(g.perspective.zfar);
            } else if (g.type == "orthographic") {
                c.projection = CameraProjection::Orthographic;
                c.a = wire_float(g.orthographic.xmag);
                c.b = wire_float(g.orthographic.ymag);
                c.znear = wire_float(g.orthographic.znear);
                c.zfar = wire_float(g.orthographic.zfar);
            } else {
                known = false;
            }
            if (!known || !valid_camera(c) || asset_.scene.cameras.size() >= kMaxTable) {
                warnings_.push_back(where + ": " + (known ? "values glTF does not allow (or too many cameras)" : "unknown type \"" + g.type + "\"") +
                                    "; not sent, and the nodes naming it are sent without a camera");
                camera_map_.push_back(kNone);
                continue;
            }
            camera_map_.push_back(uint16_t(asset_.scene.cameras.size()));
            add_extras(ExtrasTarget::Camera, asset_.scene.cameras.size(), g.extras_json_string, where);
            asset_.scene.cameras.push_back(std::move(c));
        }
        for (size_t i = 0; i < model_.lights.size(); ++i) {
            const tinygltf::Light& g = model_.lights[i];
            const std::string where = path_ + ": light " + std::to_string(i) + (g.name.empty() ? "" : " (" + g.name + ")");
            SceneLight l;
            l.name = wire_name(g.name, where, warnings_);
            bool known = true;
            if (g.type == "directional") l.type = LightType::Directional;
            else if (g.type == "point") l.type = LightType::Point;
            else if (g.type == "spot") l.type = LightType::Spot;
            else known = false;
            if (g.color.size() == 3)
                for (size_t k = 0; k < 3; ++k) l.color[k] = wire_float(g.color[k], 1.0);
            else if (!g.color.empty()) known = false;
            l.intensity = wire_float(g.intensity);
            if (l.type != LightType::Directional) l.range = wire_float(g.range);
            if (l.type == LightType::Spot) {
                l.inner_cone = wire_float(g.spot.innerConeAngle, kPi / 2);
                l.outer_cone = wire_float(g.spot.outerConeAngle, kPi / 2);
            }
            if (!known || !valid_light(l) || asset_.scene.lights.size() >= kMaxTable) {
                warnings_.push_back(where + ": " + (known ? "values KHR_lights_punctual does not allow (or too many lights)" : "unknown type \"" + g.type + "\" or colour") +
                                    "; not sent, and the nodes naming it are sent without a light");
                light_map_.push_back(kNone);
                continue;
            }
            light_map_.push_back(uint16_t(asset_.scene.lights.size()));
            add_extras(ExtrasTarget::Light, asset_.scene.lights.size(), g.extras_json_string, where);
            asset_.scene.lights.push_back(std::move(l));
        }
    }

    // Roots of the default scene (or, with no scene at all, one made-up node per mesh).
    std::vector<int> scene_roots() {
        if (model_.scenes.empty()) {
            warnings_.push_back(path_ + ": no scene; every mesh is sent as a root node without transform");
            std::vector<int> roots;
            for (size_t m = 0; m < model_.meshes.size(); ++m) {
                tinygltf::Node node;
                node.mesh = int(m);
                node.name = model_.meshes[m].name;
                extra_nodes_.push_back(node);
                roots.push_back(int(model_.nodes.size() + extra_nodes_.size() - 1));
            }
            return roots;
        }
        int scene = model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size() ? model_.defaultScene : 0;
        if (model_.scenes.size() > 1)
            warnings_.push_back(path_ + ": " + std::to_string(model_.scenes.size() - 1) +
                                " scene(s) besides the default scene " + std::to_string(scene) + " are not sent");
        return model_.scenes[size_t(scene)].nodes;
    }

    const tinygltf::Node& node_at(int index) const {
        return size_t(index) < model_.nodes.size() ? model_.nodes[size_t(index)]
                                                   : extra_nodes_[size_t(index) - model_.nodes.size()];
    }

    // Depth-first over the default scene: records each node once with its parent.
    void visit(int index, int parent, int depth) {
        if (index < 0 || size_t(index) >= model_.nodes.size() + extra_nodes_.size())
            throw InputError(path_ + ": a scene refers to node " + std::to_string(index) + ", which does not exist");
        if (depth > 256) throw InputError(path_ + ": the node hierarchy is deeper than 256 (at node " +
                                          std::to_string(index) + "), or cyclic");
        if (parent_.count(index)) {
            warnings_.push_back(path_ + ": node " + std::to_string(index) +
                                " appears more than once in the scene (glTF forbids it); kept at its first place");
            return;
        }
        parent_[index] = parent;
        node_order_.push_back(index);
        for (int child : node_at(index).children) visit(child, index, depth + 1);
    }

    // The scene node of glTF node `old`; its mesh becomes the Asset mesh table entry.
    void add_node(int old) {
        const tinygltf::Node& node = node_at(old);
        const std::string where = path_ + ": node " + std::to_string(old) + (node.name.empty() ? "" : " (" + node.name + ")");
        SceneNode out;
        out.index = new_node_.at(old);
        int parent = parent_.at(old);
        out.parent = parent < 0 ? kNone : new_node_.at(parent);
        out.name = wire_name(node.name, where, warnings_);
        if (node.matrix.size() == 16) {
            out.has_matrix = true;
            for (int k = 0; k < 16; ++k) out.matrix[k] = float(node.matrix[k]);
        } else {
            if (node.translation.size() == 3)
                for (int k = 0; k < 3; ++k) out.translation[k] = float(node.translation[k]);
            if (node.rotation.size() == 4)
                for (int k = 0; k < 4; ++k) out.rotation[k] = float(node.rotation[k]);
            if (node.scale.size() == 3)
                for (int k = 0; k < 3; ++k) out.scale[k] = float(node.scale[k]);
        }
        for (float v : out.matrix)
            if (!std::isfinite(v)) throw InputError(where + ": its transform has a non-finite value");
        for (float v : out.translation)
            if (!std::isfinite(v)) throw InputError(where + ": its translation has a non-finite value");
        for (float v : out.rotation)
            if (!std::isfinite(v)) throw InputError(where + ": its rotation has a non-finite value");
        for (float v : out.scale)
            if (!std::isfinite(v)) throw InputError(where + ": its scale has a non-finite value");
        if (!node.weights.empty())
            warnings_.push_back(where + ": its own morph target weights (overriding its mesh's) are not sent; its mesh's "
                                "default weights are");
        for (const auto& [name, value] : node.extensions) {
            if (name == "KHR_lights_punctual") {  // format 1.10 (spec 26.1): the node's light
                const tinygltf::Value& light = value.Get("light");
                const int l = light.IsInt() ? light.Get<int>() : -1;
                if (l < 0 || size_t(l) >= light_map_.size())
                    warnings_.push_back(where + ": names light " + (light.IsInt() ? std::to_string(l) : std::string("(not a number)")) +
                                        ", which does not exist; sent without a light");
                else out.light = light_map_[size_t(l)];
                continue;
            }
            warnings_.push_back(where + ": extension " + name + " of the node is not sent");
        }
        if (node.camera >= 0) {  // format 1.10 (spec 26.1)
            if (size_t(node.camera) >= camera_map_.size())
                warnings_.push_back(where + ": names camera " + std::to_string(node.camera) + ", which does not exist; sent without a camera");
            else out.camera = camera_map_[size_t(node.camera)];
        }
        if (node.mesh >= 0) {
            if (size_t(node.mesh) >= model_.meshes.size())
                throw InputError(where + ": refers to mesh " + std::to_string(node.mesh) + ", which does not exist");
            out.mesh = mesh_index(node.mesh, where);
        }
        if (node.skin >= 0) {
            // Format 1.5 (spec 21): the skin travels when the node shows a mesh whose objects carry
            // weights, and its joints are nodes of the scene.
            if (out.mesh == kNone) {
                warnings_.push_back(where + ": skinned, but without a mesh ellicast sends; its skin is not sent");
            } else if (!mesh_weighted(out.mesh)) {
                warnings_.push_back(where + ": skinned, but its mesh's primitives have no JOINTS_0 and WEIGHTS_0 that "
                                    "ellicast can send; its skin is not sent (the mesh is sent in its bind pose)");
            } else {
                out.skin = skin_index(node.skin, where);
            }
        }
        if (size_t(old) < model_.nodes.size()) add_extras(ExtrasTarget::Node, out.index, node.extras_json_string, where);
        asset_.scene.nodes.push_back(std::move(out));
    }

    // The Asset mesh of glTF mesh `m` (read once, at its first use); kNone when it has no primitive to send.
    uint16_t mesh_index(int m, const std::string& where) {
        if (auto it = mesh_map_.find(m); it != mesh_map_.end()) return it->second;
        const tinygltf::Mesh& gmesh = model_.meshes[size_t(m)];
        const std::string label = gmesh.name.empty() ? "mesh " + std::to_string(m) : gmesh.name;
        SceneMesh out;
        out.name = wire_name(gmesh.name, path_ + ": mesh " + std::to_string(m), warnings_);
        for (size_t p = 0; p < gmesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = gmesh.primitives[p];
            const std::string pwhere = path_ + ": " + label + " primitive " + std::to_string(p);
            int object = object_index(prim, label + (gmesh.primitives.size() > 1 ? "#" + std::to_string(p) : ""), pwhere);
            if (object < 0) continue;
            ScenePrimitive sp;
            sp.object = uint16_t(object);
            if (prim.material >= 0) {
                if (size_t(prim.material) >= model_.materials.size())
                    warnings_.push_back(pwhere + ": refers to material " + std::to_string(prim.material) +
                                        ", which does not exist; drawn with the default material");
                else
                    sp.material = uint16_t(prim.material);
            }
            out.primitives.push_back(sp);
        }
        read_targets(gmesh, out, path_ + ": " + label);
        uint16_t index = kNone;
        if (out.primitives.empty()) {
            warnings_.push_back(where + ": its mesh " + label + " has no primitive ellicast can send; the node is sent "
                                "without it");
        } else {
            if (asset_.scene.meshes.size() >= kMaxTable) throw InputError(path_ + ": more than 65534 meshes");
            index = uint16_t(asset_.scene.meshes.size());
            out.index = index;
            add_extras(ExtrasTarget::Mesh, index, gmesh.extras_json_string, path_ + ": " + label);
            asset_.scene.meshes.push_back(std::move(out));
        }
        mesh_map_[m] = index;
        return index;
    }

    // Format 1.6 (spec 22): the mesh's targets travel when every object it sends carries as many
    // targets as the mesh has; then its default weights go into its record.
    void read_targets(const tinygltf::Mesh& gmesh, SceneMesh& out, const std::string& where) {
        size_t targets = 0;
        for (const auto& prim : gmesh.primitives) targets = std::max(targets, prim.targets.size());
        if (targets == 0 || out.primitives.empty()) return;
        std::string problem;
        if (targets > 255) problem = std::to_string(targets) + " morph targets (at most 255 can be sent)";
        for (const auto& p : out.primitives)
            if (problem.empty() && (p.object >= asset_.morphs.size() || asset_.morphs[p.object].targets != targets))
                problem = "a primitive without " + std::to_string(targets) + " morph targets that can be sent";
        if (!problem.empty()) {
            warnings_.push_back(where + ": " + problem + "; its morph targets are not sent (the base shape is)");
            for (const auto& p : out.primitives)
                if (p.object < asset_.morphs.size()) asset_.morphs[p.object] = {};
            return;
        }
        out.weights.assign(targets, 0.0f);
        if (!gmesh.weights.empty() && gmesh.weights.size() != targets)
            warnings_.push_back(where + ": " + std::to_string(gmesh.weights.size()) + " default weights for " +
                                std::to_string(targets) + " morph targets; sent as 0");
        else
            for (size_t t = 0; t < gmesh.weights.size(); ++t) {
                out.weights[t] = float(gmesh.weights[t]);
                if (!std::isfinite(out.weights[t])) {
                    warnings_.push_back(where + ": a default weight is not finite; sent as 0");
                    out.weights[t] = 0.0f;
                }
            }
    }

    // The morph targets of a primitive per vertex of `mesh` (as primitive_to_mesh made it): POSITION
    // and NORMAL displacements (0 where a target lacks one). Empty, with a warning, when one is not
    // usable. TANGENT displacements are not sent (named in a warning).
    VertexMorph read_morph(const tinygltf::Primitive& prim, const Mesh& mesh, const std::string& where) {
        VertexMorph out;
        if (prim.targets.empty()) return out;
        try {
            if (prim.targets.size() > 255)
                throw InputError(where + ": " + std::to_string(prim.targets.size()) + " morph targets (at most 255 can be sent)");
            if (mesh.is_point_set && prim.indices >= 0) throw InputError(where + ": an indexed point primitive's morph targets");
            bool tangents = false;
            for (const auto& target : prim.targets) {
                if (target.count("POSITION")) out.attributes |= kMorphPosition;
                if (target.count("NORMAL") && !mesh.normals.empty()) out.attributes |= kMorphNormal;
                tangents |= target.count("TANGENT") > 0;
            }
            if (tangents) warnings_.push_back(where + ": the TANGENT displacements of its morph targets are not sent");
            if (out.attributes == 0) out.attributes = kMorphPosition;  // only tangents: a target of zeros
            out.targets = uint8_t(prim.targets.size());
            const size_t n = mesh.positions.size();
            const size_t per = morph_record_values(out.targets, out.attributes);
            out.values.assign(per * n, 0.0f);
            for (size_t t = 0; t < prim.targets.size(); ++t) {
                for (const uint8_t bit : {kMorphPosition, kMorphNormal}) {
                    if (!(out.attributes & bit)) continue;
                    const size_t offset = morph_slot_offset(out.attributes, t, bit);
                    const char* name = bit == kMorphPosition ? "POSITION" : "NORMAL";
                    auto it = prim.targets[t].find(name);
                    if (it != prim.targets[t].end()) {
                        int components = 0;
                        const std::string what = where + " target " + std::to_string(t) + " " + name;
                        const std::vector<double> d = read_accessor(model_, it->second, what, components);
                        if (components != 3 || d.size() != 3 * n)
                            throw InputError(what + ": not a VEC3 of the vertex count");
                        for (size_t v = 0; v < n; ++v)
                            for (size_t k = 0; k < 3; ++k) {
                                const float x = float(d[3 * v + k]);
                                if (!std::isfinite(x)) throw InputError(what + ": a displacement is not finite");
                                out.values[v * per + offset + k] = x;
                            }
                    }
                }
            }
        } catch (const InputError& e) {
            warnings_.push_back(std::string(e.what()) + "; its morph targets are not sent");
            return {};
        }
        return out;
    }

    // Whether every object of asset mesh `m` carries weights.
    bool mesh_weighted(uint16_t m) const {
        for (const auto& p : asset_.scene.meshes[m].primitives)
            if (p.object >= asset_.weights.size() || asset_.weights[p.object].empty()) return false;
        return true;
    }

    // The asset skin of glTF skin `s` (read once, at its first use); kNone, with a warning, when it
    // cannot be sent.
    uint16_t skin_index(int s, const std::string& where) {
        if (auto it = skin_map_.find(s); it != skin_map_.end()) return it->second;
        uint16_t index = kNone;
        try {
            if (size_t(s) >= model_.skins.size())
                throw InputError(where + ": refers to skin " + std::to_string(s) + ", which does not exist");
            const tinygltf::Skin& skin = model_.skins[size_t(s)];
            const std::string what = path_ + ": skin " + std::to_string(s) + (skin.name.empty() ? "" : " (" + skin.name + ")");
            SceneSkin out;
            out.name = wire_name(skin.name, what, warnings_);
            if (skin.joints.empty() || skin.joints.size() > 0xFFFF)
                throw InputError(what + ": " + std::to_string(skin.joints.size()) + " joints (1 to 65535 can be sent)");
            std::vector<double> matrices;
            if (skin.inverseBindMatrices >= 0) {
                int components = 0;
                matrices = read_accessor(model_, skin.inverseBindMatrices, what + " inverseBindMatrices", components);
                if (components != 16 || matrices.size() != 16 * skin.joints.size())
                    throw InputError(what + ": its inverseBindMatrices accessor is not a MAT4 per joint");
            }
            for (size_t j = 0; j < skin.joints.size(); ++j) {
                auto node = new_node_.find(skin.joints[j]);
                if (node == new_node_.end())
                    throw InputError(what + ": joint " + std::to_string(j) + " (node " + std::to_string(skin.joints[j]) +
                                     ") is not a node of the scene");
                SkinJoint joint;
                joint.node = node->second;
                if (!matrices.empty())
                    for (size_t k = 0; k < 16; ++k) {
                        joint.inverse_bind[k] = float(matrices[16 * j + k]);
                        if (!std::isfinite(joint.inverse_bind[k]))
                            throw InputError(what + ": the inverse bind matrix of joint " + std::to_string(j) + " is not finite");
                    }
                out.joints.push_back(joint);
            }
            if (skin.skeleton >= 0) {
                if (auto node = new_node_.find(skin.skeleton); node != new_node_.end()) out.skeleton = node->second;
                else warnings_.push_back(what + ": its skeleton node " + std::to_string(skin.skeleton) +
                                         " is not in the scene; sent without it");
            }
            if (asset_.scene.skins.size() >= kMaxTable) throw InputError(path_ + ": more than 65534 skins");
            index = uint16_t(asset_.scene.skins.size());
            add_extras(ExtrasTarget::Skin, index, skin.extras_json_string, what);
            asset_.scene.skins.push_back(std::move(out));
        } catch (const InputError& e) {
            warnings_.push_back(std::string(e.what()) + "; the skin is not sent (its meshes are sent in their bind pose)");
        }
        skin_map_[s] = index;
        return index;
    }

    // JOINTS_n and WEIGHTS_n of a primitive (every set, in order), per vertex of `mesh` (as
    // primitive_to_mesh made it): each vertex's four largest influences (a record holds four, spec
    // 21.2; a receiver's weights sum to 1 again), with a warning counting the vertices that had more.
    // Empty, with a warning naming what is wrong, when a set is unusable.
    VertexWeights read_weights(const tinygltf::Primitive& prim, const Mesh& mesh, const std::string& where) {
        VertexWeights out;
        const size_t n = mesh.positions.size();
        std::vector<std::vector<std::pair<float, uint16_t>>> influences(n);  // (weight, joint) per vertex
        try {
            for (int set = 0;; ++set) {
                const std::string js = "JOINTS_" + std::to_string(set), ws = "WEIGHTS_" + std::to_string(set);
                auto j = prim.attributes.find(js), w = prim.attributes.find(ws);
                if (j == prim.attributes.end() && w == prim.attributes.end()) break;
                if (j == prim.attributes.end() || w == prim.attributes.end())
                    throw InputError(where + ": " + js + " without " + ws + " or the other way round");
                if (mesh.is_point_set && prim.indices >= 0) throw InputError(where + ": an indexed point primitive's weights");
                int jc = 0, wc = 0;
                const std::vector<double> joints = read_accessor(model_, j->second, where + " " + js, jc);
                const std::vector<double> weights = read_accessor(model_, w->second, where + " " + ws, wc);
                if (jc != 4 || wc != 4 || joints.size() != 4 * n || weights.size() != 4 * n)
                    throw InputError(where + ": " + js + " and " + ws + " are not VEC4 of the vertex count");
                for (size_t i = 0; i < n; ++i)
                    for (size_t k = 0; k < 4; ++k) {
                        const double jv = joints[4 * i + k], wv = weights[4 * i + k];
                        if (!(jv >= 0) || jv > 0xFFFF || jv != std::floor(jv))
                            throw InputError(where + ": " + js + " of vertex " + std::to_string(i) + " is not a joint index");
                        if (!std::isfinite(wv) || wv < 0)
                            throw InputError(where + ": " + ws + " of vertex " + std::to_string(i) + " is negative or not finite");
                        if (wv > 0) influences[i].emplace_back(float(wv), uint16_t(jv));
                    }
            }
        } catch (const InputError& e) {
            warnings_.push_back(std::string(e.what()) + "; the weights are not sent");
            return {};
        }
        if (!prim.attributes.count("JOINTS_0")) return out;
        out.joints.assign(n, {0, 0, 0, 0});
        out.weights.assign(n, {0, 0, 0, 0});
        size_t more = 0;
        for (size_t i = 0; i < n; ++i) {
            auto& list = influences[i];
            // The largest first (the earlier set and slot on a tie).
            std::stable_sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
            more += list.size() > 4;
            for (size_t k = 0; k < 4 && k < list.size(); ++k) {
                out.weights[i][k] = list[k].first;
                out.joints[i][k] = list[k].second;
            }
        }
        if (more) {  // said once for the asset (warn_attributes), naming the first primitive
            if (folded_.primitives++ == 0)  // `where` names the file first: keep what follows it
                folded_.first = where.rfind(path_ + ": ", 0) == 0 ? where.substr(path_.size() + 2) : where;
            folded_.vertices += more;
            folded_.of += n;
        }
        return out;
    }

    // The object of a primitive: primitives with the same accessors and mode are one object.
    int object_index(const tinygltf::Primitive& prim, const std::string& name, const std::string& where) {
        auto key = std::make_tuple(prim.attributes, prim.indices, prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode,
                                   prim.extensions.count("KHR_draco_mesh_compression") > 0, prim.targets);
        if (auto it = object_map_.find(key); it != object_map_.end()) return it->second;
        for (const auto& [attr, accessor] : prim.attributes) {
            (void)accessor;
            if (attr == "POSITION" || attr == "NORMAL" || attr == "COLOR_0" || texcoord_set_carried(attr) ||
                attr.rfind("JOINTS_", 0) == 0 || attr.rfind("WEIGHTS_", 0) == 0)  // read_weights takes every set
                continue;
            not_carried_attributes_[attr] = true;
        }
        Mesh mesh;
        mesh.name = name;
        int result = -1;
        if (primitive_to_mesh(model_, prim, Eigen::Matrix4d::Identity(), where, mesh, warnings_)) {
            check_and_repair_mesh(mesh, where, warnings_);
            if (mesh.positions.empty()) {
                warnings_.push_back(where + ": no vertices, skipped");
            } else if (!mesh.is_point_set && mesh.triangles.empty()) {
                warnings_.push_back(where + ": no usable triangles, skipped");
            } else {
                if (asset_.objects.size() >= kMaxObjects) throw InputError(path_ + ": more than 65535 objects");
                result = int(asset_.objects.size());
                asset_.weights.push_back(read_weights(prim, mesh, where));  // weights[i] belongs to objects[i]
                asset_.morphs.push_back(read_morph(prim, mesh, where));     // and morphs[i]
                asset_.objects.push_back(std::move(mesh));
            }
        }
        object_map_[key] = result;
        return result;
    }

    // TEXCOORD_0 .. TEXCOORD_7 travel (format 1.14, spec 30).
    static bool texcoord_set_carried(const std::string& attr) {
        return attr.size() == 10 && attr.rfind("TEXCOORD_", 0) == 0 && attr[9] >= '0' &&
               attr[9] <= char('0' + kMaxTexcoordSets);
    }

    // Format 1.14 (spec 30.3): a reference to set `set` of material `material` travels when every
    // primitive drawn with the material has the sets 0 .. set; otherwise the first that lacks one.
    std::string primitive_without_set(size_t material, int set) const {
        for (size_t m = 0; m < model_.meshes.size(); ++m)
            for (size_t p = 0; p < model_.meshes[m].primitives.size(); ++p) {
                const tinygltf::Primitive& prim = model_.meshes[m].primitives[p];
                if (prim.material != int(material)) continue;
                for (int s = 0; s <= set; ++s)
                    if (!prim.attributes.count("TEXCOORD_" + std::to_string(s)))
                        return "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + " has no TEXCOORD_" +
                               std::to_string(s);
            }
        return {};
    }

    void read_materials() {
        if (model_.materials.size() > kMaxTable) throw InputError(path_ + ": more than 65534 materials");
        for (size_t i = 0; i < model_.materials.size(); ++i) {
            current_material_ = i;
            const tinygltf::Material& gm = model_.materials[i];
            const std::string where =
                path_ + ": material " + std::to_string(i) + (gm.name.empty() ? "" : " (" + gm.name + ")");
            Material m;
            m.index = uint16_t(i);
            m.name = wire_name(gm.name, where, warnings_);
            const auto& pbr = gm.pbrMetallicRoughness;
            for (size_t k = 0; k < 4 && k < pbr.baseColorFactor.size(); ++k) m.base_color[k] = float(pbr.baseColorFactor[k]);
            m.metallic = float(pbr.metallicFactor);
            m.roughness = float(pbr.roughnessFactor);
            for (size_t k = 0; k < 3 && k < gm.emissiveFactor.size(); ++k) m.emissive[k] = float(gm.emissiveFactor[k]);
            if (gm.alphaMode == "MASK") m.alpha_mode = AlphaMode::Mask;
            else if (gm.alphaMode == "BLEND") m.alpha_mode = AlphaMode::Blend;
            else if (!gm.alphaMode.empty() && gm.alphaMode != "OPAQUE")
                warnings_.push_back(where + ": alphaMode \"" + gm.alphaMode + "\" is not a glTF mode; sent as OPAQUE");
            m.alpha_cutoff = float(gm.alphaCutoff);
            m.double_sided = gm.doubleSided;
            m.base_color_texture = texture_ref(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, 1,
                                               pbr.baseColorTexture.extensions, where + " baseColorTexture");
            m.metallic_roughness_texture = texture_ref(pbr.metallicRoughnessTexture.index,
                                                       pbr.metallicRoughnessTexture.texCoord, 1,
                                                       pbr.metallicRoughnessTexture.extensions,
                                                       where + " metallicRoughnessTexture");
            m.normal_texture = texture_ref(gm.normalTexture.index, gm.normalTexture.texCoord, gm.normalTexture.scale,
                                           gm.normalTexture.extensions, where + " normalTexture");
            m.occlusion_texture = texture_ref(gm.occlusionTexture.index, gm.occlusionTexture.texCoord,
                                              gm.occlusionTexture.strength, gm.occlusionTexture.extensions,
                                              where + " occlusionTexture");
            m.emissive_texture = texture_ref(gm.emissiveTexture.index, gm.emissiveTexture.texCoord, 1,
                                             gm.emissiveTexture.extensions, where + " emissiveTexture");
            // Format 1.3: KHR_materials_* and every KHR_texture_transform travel in the material's
            // patch (spec 18); the texture coordinates are sent as the asset has them.
            const std::array<bool, 5> core_sent = {
                m.base_color_texture.texture != kNone, m.metallic_roughness_texture.texture != kNone,
                m.normal_texture.texture != kNone, m.occlusion_texture.texture != kNone,
                m.emissive_texture.texture != kNone};
            m.extensions = material_patch::make(
                gm, core_sent, [&](int index, const std::string& at) { return texture_index(index, at); }, where,
                warnings_);
            add_extras(ExtrasTarget::Material, asset_.scene.materials.size(), gm.extras_json_string, where);
            asset_.scene.materials.push_back(std::move(m));
        }
    }

    // The Asset texture reference of a material's glTF texture info (its KHR_texture_transform is
    // checked here and travels in the material's patch). ellicast carries TEXCOORD_0 to TEXCOORD_7
    // (format 1.14): a reference to another set, to a set a primitive drawn with the material lacks,
    // or through the transform's texCoord to a set other than 0, is not sent (nor its image, unless
    // another reference uses it); the material keeps its factors and its other textures, and the
    // warning names the material and the slot.
    TextureRef texture_ref(int index, int texcoord, double scale, const tinygltf::ExtensionMap& extensions,
                           const std::string& where) {
        TextureRef ref;
        ref.scale = float(scale);
        if (index < 0) return ref;
        if (texcoord < 0 || texcoord > 255) {
            warnings_.push_back(where + ": texCoord " + std::to_string(texcoord) + " is out of range; texture not sent");
            return ref;
        }
        if (texcoord > int(kMaxTexcoordSets)) {
            warnings_.push_back(where + " uses TEXCOORD_" + std::to_string(texcoord) +
                                "; ellicast carries TEXCOORD_0 to TEXCOORD_7, so this texture is not sent (the material "
                                "keeps its factors and its other textures)");
            return ref;
        }
        if (texcoord > 0) {
            if (const std::string lacking = primitive_without_set(current_material_, texcoord); !lacking.empty()) {
                warnings_.push_back(where + " uses TEXCOORD_" + std::to_string(texcoord) + " but " + lacking +
                                    "; this texture is not sent (the material keeps its factors and its other textures)");
                return ref;
            }
        }
        for (const auto& [name, value] : extensions) {
            if (name == "KHR_texture_transform") {
                std::string why;
                if (!check_uv_transform(value, why)) {
                    warnings_.push_back(where + ": its KHR_texture_transform " + why +
                                        "; this texture is not sent (the material keeps its factors and its other "
                                        "textures)");
                    return ref;
                }
                continue;
            }
            warnings_.push_back(where + ": extension " + name + " of the texture reference not sent");
        }
        ref.texcoord = uint8_t(texcoord);
        ref.texture = texture_index(index, where);
        return ref;
    }

    uint16_t texture_index(int index, const std::string& where) {
        if (size_t(index) >= model_.textures.size()) {
            warnings_.push_back(where + ": refers to texture " + std::to_string(index) + ", which does not exist; not sent");
            return kNone;
        }
        const tinygltf::Texture& tex = model_.textures[size_t(index)];
        for (const auto& [name, value] : tex.extensions) {
            (void)value;
            warnings_.push_back(where + ": texture " + std::to_string(index) + " extension " + name + " not sent");
        }
        if (tex.source < 0 || size_t(tex.source) >= model_.images.size()) {
            warnings_.push_back(where + ": texture " + std::to_string(index) +
                                " has no core image source (PNG or JPEG); not sent");
            return kNone;
        }
        const std::vector<uint8_t>* bytes = image_bytes(tex.source);
        const std::string image_where = path_ + ": image " + std::to_string(tex.source);
        if (!bytes || bytes->empty()) {
            warnings_.push_back(image_where + " could not be read; its texture is not sent");
            return kNone;
        }
        SceneDescription::Texture out;
        const image_file::Format format = checked_image(tex.source, *bytes);
        if (format == image_file::Format::Unknown) return kNone;
        out.info.image_type = format == image_file::Format::Png ? ImageType::Png : ImageType::Jpeg;
        if (bytes->size() > 0xFFFFFFFFu) {
            warnings_.push_back(image_where + " is larger than 4 GiB; not sent");
            return kNone;
        }
        if (tex.sampler >= 0 && size_t(tex.sampler) < model_.samplers.size()) {
            const tinygltf::Sampler& s = model_.samplers[size_t(tex.sampler)];
            out.info.mag_filter = uint16_t(std::max(s.magFilter, 0));
            out.info.min_filter = uint16_t(std::max(s.minFilter, 0));
            out.info.wrap_s = uint16_t(std::max(s.wrapS, 0));
            out.info.wrap_t = uint16_t(std::max(s.wrapT, 0));
        }
        auto key = std::make_tuple(tex.source, out.info.mag_filter, out.info.min_filter, out.info.wrap_s, out.info.wrap_t);
        if (auto it = texture_map_.find(key); it != texture_map_.end()) return it->second;
        // The same bytes from another image index (a copy in the file) are sent once too.
        for (size_t t = 0; t < asset_.scene.textures.size(); ++t) {
            const auto& other = asset_.scene.textures[t];
            if (other.image == *bytes && other.info.mag_filter == out.info.mag_filter &&
                other.info.min_filter == out.info.min_filter && other.info.wrap_s == out.info.wrap_s &&
                other.info.wrap_t == out.info.wrap_t)
                return texture_map_[key] = uint16_t(t);
        }
        if (asset_.scene.textures.size() >= kMaxTable) throw InputError(path_ + ": more than 65534 textures");
        out.image = *bytes;
        out.info.index = uint16_t(asset_.scene.textures.size());
        add_extras(ExtrasTarget::Texture, out.info.index, tex.extras_json_string, path_ + ": texture " + std::to_string(index));
        asset_.scene.textures.push_back(std::move(out));
        return texture_map_[key] = uint16_t(asset_.scene.textures.size() - 1);
    }

    // The format of image `i` (`bytes` its file), Unknown when it is not sent: neither PNG nor JPEG,
    // or cut off before the header a viewer needs. Says once per image what is wrong with it: its
    // file is damaged (a file cut off in its image data is sent as it is: viewers show what they can
    // of it, as they do of the asset), or it is not what its mimeType or file name declares (it is sent
    // as what its bytes are; the receiver's glTF names it by them).
    image_file::Format checked_image(int i, const std::vector<uint8_t>& bytes) {
        if (auto it = image_formats_.find(i); it != image_formats_.end()) return it->second;
        const tinygltf::Image& image = model_.images[size_t(i)];
        const bool external = !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
        std::string declared = image.mimeType;  // from a bufferView image or a data: URI
        if (external) {  // tinygltf keeps no mimeType for an image given by URI
            if (!json_) json_ = read_json(path_);
            const nlohmann::json& doc = *json_;
            if (doc.is_object() && doc.contains("images") && doc["images"].is_array() && size_t(i) < doc["images"].size()) {
                const nlohmann::json& entry = doc["images"][size_t(i)];
                if (entry.is_object() && entry.contains("mimeType") && entry["mimeType"].is_string())
                    declared = entry["mimeType"].get<std::string>();
            }
        }
        const std::string where = path_ + ": image " + std::to_string(i) + (external ? " (" + (image.uri.size() <= 80 ? image.uri : quoted_input(image.uri)) + ")" : "");
        const image_file::Check check = image_file::check(bytes);
        image_file::Format format = check.format;
        const std::string what = image_file::name(format);
        if (format == image_file::Format::Unknown) {
            warnings_.push_back(where + " is neither PNG nor JPEG" + (declared.empty() ? "" : " (" + declared + ")") +
                                "; its texture is not sent");
        } else if (!check.readable) {
            warnings_.push_back(where + ": its " + what + " file " + check.problem +
                                "; no viewer can open it, so its texture is not sent");
            format = image_file::Format::Unknown;
        } else {
            if (!check.problem.empty())
                warnings_.push_back(where + ": its " + what + " file " + check.problem +
                                    "; sent as it is (viewers show what they can of it)");
            std::string extension = std::filesystem::path(image.uri).extension().string();
            std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
            const bool named_png = extension == ".png", named_jpeg = extension == ".jpg" || extension == ".jpeg";
            const std::string mime = image_file::mime_type(format);
            if (!declared.empty() && declared != mime)
                warnings_.push_back(where + " is declared " + declared + " but its bytes are a " + what +
                                    " file; sent as " + what + " (" + mime + ")");
            else if (declared.empty() && external &&
                     ((named_png && format != image_file::Format::Png) || (named_jpeg && format != image_file::Format::Jpeg)))
                warnings_.push_back(where + " is named like a " + (named_png ? "PNG" : "JPEG") + " file but its bytes are a " +
                                    what + " file; sent as " + what + " (" + mime + ")");
        }
        return image_formats_[i] = format;
    }

    // Animations (format 1.4, spec 20): every channel that moves a node of the scene sent, as a track
    // over its sampler's keys. Channels the format cannot carry are named in a warning.
    void read_animations() {
        if (model_.animations.size() > 0xFFFF)
            throw InputError(path_ + ": more than 65535 animations");
        for (size_t a = 0; a < model_.animations.size(); ++a) {
            const tinygltf::Animation& anim = model_.animations[a];
            const std::string where = path_ + ": animation " + std::to_string(a) + (anim.name.empty() ? "" : " (" + anim.name + ")");
            SceneAnimation out;
            out.name = wire_name(anim.name, where, warnings_);
            std::vector<std::string> dropped;
            for (size_t c = 0; c < anim.channels.size(); ++c) {
                const tinygltf::AnimationChannel& channel = anim.channels[c];
                const std::string what = where + " channel " + std::to_string(c);
                const auto node = new_node_.find(channel.target_node);
                if (channel.target_node < 0 || node == new_node_.end()) {
                    dropped.push_back("channel " + std::to_string(c) + " (no node of the scene)");
                    continue;
                }
                try {
                    SceneAnimation::Track track = read_track(anim, channel, node->second, what);
                    if (std::any_of(out.tracks.begin(), out.tracks.end(), [&](const SceneAnimation::Track& t) {
                            return t.node == track.node && t.path == track.path;
                        })) {
                        // glTF allows one channel per node and path; a receiver would leave it out (spec 20.2).
                        dropped.push_back("channel " + std::to_string(c) + " (a second channel on the same node and path)");
                        continue;
                    }
                    out.tracks.push_back(std::move(track));
                } catch (const InputError& e) {
                    // A broken channel costs that channel, not the model.
                    warnings_.push_back(std::string(e.what()) + "; the channel is not sent");
                }
            }
            if (!dropped.empty())
                warnings_.push_back(where + ": not sent: " + join(dropped));
            if (out.tracks.size() > 0xFFFF) throw InputError(where + ": more than 65535 channels");
            if (out.tracks.empty()) {
                warnings_.push_back(where + ": nothing of it can be sent; the animation is left out");
                continue;
            }
            add_extras(ExtrasTarget::Animation, asset_.scene.animations.size(), anim.extras_json_string, where);
            asset_.scene.animations.push_back(std::move(out));
        }
    }

    // One channel's track: its sampler's keys as f32. Throws InputError naming what is wrong.
    SceneAnimation::Track read_track(const tinygltf::Animation& anim, const tinygltf::AnimationChannel& channel,
                                     uint16_t node, const std::string& what) {
        SceneAnimation::Track track;
        track.node = node;
        if (channel.target_path == "translation") track.path = AnimationPath::Translation;
        else if (channel.target_path == "rotation") track.path = AnimationPath::Rotation;
        else if (channel.target_path == "scale") track.path = AnimationPath::Scale;
        else if (channel.target_path == "weights") track.path = AnimationPath::Weights;
        else throw InputError(what + ": path " + quoted_input(channel.target_path) + " is not glTF's");
        if (track.path == AnimationPath::Weights) {
            // Format 1.6 (spec 22.5): the node's mesh must carry its morph targets.
            const uint16_t mesh = asset_.scene.nodes[node].mesh;
            if (mesh == kNone || asset_.scene.meshes[mesh].weights.empty())
                throw InputError(what + ": it moves morph target weights of a node whose mesh's morph targets are not sent");
            track.targets = uint8_t(asset_.scene.meshes[mesh].weights.size());
        }
        if (channel.sampler < 0 || size_t(channel.sampler) >= anim.samplers.size())
            throw InputError(what + ": refers to sampler " + std::to_string(channel.sampler) + ", which does not exist");
        const tinygltf::AnimationSampler& sampler = anim.samplers[size_t(channel.sampler)];
        if (sampler.interpolation.empty() || sampler.interpolation == "LINEAR") track.interpolation = Interpolation::Linear;
        else if (sampler.interpolation == "STEP") track.interpolation = Interpolation::Step;
        else if (sampler.interpolation == "CUBICSPLINE") track.interpolation = Interpolation::CubicSpline;
        else throw InputError(what + ": interpolation " + quoted_input(sampler.interpolation) + " is not glTF's");
        int components = 0;
        const std::vector<double> times = read_accessor(model_, sampler.input, what + " input", components);
        if (components != 1) throw InputError(what + ": its input accessor is not SCALAR");
        int value_components = 0;
        const std::vector<double> values = read_accessor(model_, sampler.output, what + " output", value_components);
        const size_t want = track.path == AnimationPath::Weights ? track.targets : track.path == AnimationPath::Rotation ? 4 : 3;
        if (track.path == AnimationPath::Weights ? value_components != 1 : size_t(value_components) != want)
            throw InputError(what + ": its output accessor has " + std::to_string(value_components) +
                             " components, the path needs " + (track.path == AnimationPath::Weights ? std::string("1 (SCALAR)") : std::to_string(want)));
        const size_t per_key = animation_values_per_key(track.path, track.interpolation, track.targets);
        if (times.empty() || values.size() != times.size() * per_key)
            throw InputError(what + ": " + std::to_string(times.size()) + " keys but " +
                             std::to_string(values.size() / want) + " output elements (" +
                             std::to_string(per_key / want) + " per key needed)");
        if (track.interpolation == Interpolation::CubicSpline && times.size() < 2)
            throw InputError(what + ": a CUBICSPLINE sampler needs at least two keys");
        for (size_t k = 0; k < times.size(); ++k) {
            const float t = float(times[k]);
            if (!std::isfinite(t) || t < 0 || (k > 0 && !(t > track.times.back())))
                throw InputError(what + ": its key times are not finite, non-negative and strictly increasing (key " +
                                 std::to_string(k) + ")");
            track.times.push_back(t);
        }
        for (double v : values) {
            const float f = float(v);
            if (!std::isfinite(f)) throw InputError(what + ": an output value is not finite");
            track.values.push_back(f);
        }
        return track;
    }

    // The file bytes of image `i`: from its URI (captured while loading) or its bufferView.
    const std::vector<uint8_t>* image_bytes(int i) {
        if (auto it = view_images_.find(i); it != view_images_.end()) return &it->second;
        const tinygltf::Image& image = model_.images[size_t(i)];
        if (image.bufferView < 0) {
            auto it = images_.bytes.find(i);
            return it == images_.bytes.end() ? nullptr : &it->second;
        }
        const auto& views = model_.bufferViews;
        if (size_t(image.bufferView) >= views.size()) return nullptr;
        const tinygltf::BufferView& view = views[size_t(image.bufferView)];
        if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) return nullptr;
        const auto& data = model_.buffers[size_t(view.buffer)].data;
        if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
            warnings_.push_back(path_ + ": image " + std::to_string(i) + ": bufferView " +
                                std::to_string(image.bufferView) + " runs past the end of its buffer");
            return nullptr;
        }
        auto& bytes = view_images_[i];
        bytes.assign(data.begin() + long(view.byteOffset), data.begin() + long(view.byteOffset + view.byteLength));
        return &bytes;
    }

    // Whole-file things ellicast does not carry (cameras and lights travel from format 1.10 on).
    void warn_not_carried() {
        std::vector<std::string> unknown, required;
        auto listed = [](const std::vector<std::string>& list, const std::string& ext) {
            return std::find(list.begin(), list.end(), ext) != list.end();
        };
        std::vector<std::string> names = model_.extensionsUsed;
        for (const auto& ext : model_.extensionsRequired)
            if (!listed(names, ext)) names.push_back(ext);
        for (const auto& ext : names)  // material extensions: carried, or named per material
            if (!kGeometryExtensions.count(ext) && ext != "KHR_texture_transform" && ext != "KHR_lights_punctual" &&
                (ext.rfind("KHR_materials_", 0) != 0 || ext == "KHR_materials_variants")) {
                unknown.push_back(ext);
                if (listed(model_.extensionsRequired, ext)) required.push_back(ext);
            }
        if (!unknown.empty())
            warnings_.push_back(path_ + ": extension(s) " + join(unknown) + " not sent" +
                                (required.empty() ? "" : " (the input requires " + join(required) +
                                                             ": the output shows the asset without it)"));
    }

public:
    void warn_attributes() {
        if (folded_.primitives)
            warnings_.push_back(path_ + ": " + std::to_string(folded_.vertices) + " of " + std::to_string(folded_.of) +
                                " vertices have more than four joint influences (JOINTS_1 / WEIGHTS_1); their four "
                                "largest are sent (" + std::to_string(folded_.primitives) + " primitive" +
                                (folded_.primitives == 1 ? "" : "s") + ", the first " + folded_.first + ")");
        std::vector<std::string> names;
        for (const auto& [name, seen] : not_carried_attributes_) names.push_back(name);
        if (!names.empty())
            warnings_.push_back(path_ + ": vertex attribute(s) " + join(names) +
                                " not sent (ellicast carries POSITION, NORMAL, TEXCOORD_0 to TEXCOORD_7 and COLOR_0" +
                                (not_carried_attributes_.count("TANGENT")
                                     ? "; TANGENT is rebuilt on output for normal-mapped materials from the normals and "
                                       "texture coordinates)"
                                     : ")"));
    }

private:
    size_t current_material_ = 0;  // the material read_materials is at (texture_ref's sets)
    const std::string& path_;
    const tinygltf::Model& model_;
    const CapturedImages& images_;
    Asset& asset_;
    std::vector<std::string>& warnings_;
    std::vector<tinygltf::Node> extra_nodes_;
    std::map<int, int> parent_;
    std::vector<int> node_order_;
    std::map<int, uint16_t> new_node_;
    std::map<int, uint16_t> mesh_map_;
    std::vector<uint16_t> camera_map_, light_map_;  // glTF camera / light -> sent one, or kNone (format 1.10)
    std::map<int, uint16_t> skin_map_;
    std::map<std::tuple<std::map<std::string, int>, int, int, bool, std::vector<std::map<std::string, int>>>, int> object_map_;
    std::map<std::tuple<int, uint16_t, uint16_t, uint16_t, uint16_t>, uint16_t> texture_map_;
    std::map<int, std::vector<uint8_t>> view_images_;
    std::map<int, image_file::Format> image_formats_;  // checked_image's answers
    std::optional<nlohmann::json> json_;                // the file's JSON, read when checked_image needs it
    std::map<std::string, bool> not_carried_attributes_;
    struct {
        size_t primitives = 0, vertices = 0, of = 0;  // skinned vertices folded to four influences
        std::string first;                            // the first primitive that had any
    } folded_;
};

}  // namespace

bool is_gltf_file(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".gltf" || ext == ".glb") return true;
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    char magic[4] = {};
    bool glb = std::fread(magic, 1, 4, f) == 4 && std::memcmp(magic, "glTF", 4) == 0;
    std::fclose(f);
    return glb;
}

Asset load_asset(const std::string& path, const InputOptions& options) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
    if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, not a model file");
    Asset asset;
    if (!is_gltf_file(path)) {
        LoadResult loaded = load_meshes(path);  // OBJ / PLY / OFF / STL, with its checks
        asset.warnings = std::move(loaded.warnings);
        SceneMesh mesh;
        mesh.index = 0;
        for (size_t i = 0; i < loaded.meshes.size() && i < kMaxObjects; ++i)
            mesh.primitives.push_back({uint16_t(i), kNone});
        asset.objects = std::move(loaded.meshes);
        SceneNode node;
        node.index = 0;
        node.mesh = 0;
        node.name = wire_name(std::filesystem::path(path).stem().string(), path, asset.warnings);
        mesh.name = node.name;
        asset.scene.nodes.push_back(node);
        asset.scene.meshes.push_back(std::move(mesh));
        return asset;
    }
    if (std::filesystem::file_size(path, ec) == 0) throw InputError(path + ": the file is empty");
    tinygltf::Model model;
    CapturedImages images;
    // Material extensions and texture transforms travel (MATERIAL_EXTENSIONS, spec 18), lights too: a
    // required one is not "ignored" here; warn_not_carried names, once, every extension that is not sent
    // (KHR_materials_variants, EXT_texture_webp, ...), required or not.
    load_model(path, model, capture_image, &images, asset.warnings, options, [](const std::string&) { return true; });
    GltfAssetReader reader(path, model, images, asset);
    reader.read();
    reader.warn_attributes();
    for (const auto& ext : model.extensionsUsed) {
        asset.source_draco |= ext == "KHR_draco_mesh_compression";
        asset.source_quantized |= ext == "KHR_mesh_quantization";
        asset.source_meshopt |= ext == "EXT_meshopt_compression";
    }
    return asset;
}

}  // namespace ellicast

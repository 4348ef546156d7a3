// The Asset a receiver can write from what has arrived: the scene tables of a ReceivedStream, cut
// down to what holds together, with the decoded objects.
#include "ellicast/converters/asset.h"

#include "morph_targets.h"
#include "skin_weights.h"

#include <algorithm>
#include <map>
#include <set>

namespace ellicast {

namespace {

std::string texture_gap(const ReceivedStream::ReceivedTexture& t) {
    if (t.received_bytes >= t.info.image_size) return "all bytes arrived but the image checksum does not match";
    return std::to_string(t.received_bytes) + " of " + std::to_string(t.info.image_size) + " bytes arrived";
}

// Why texture `index` cannot be shown yet.
std::string texture_missing(const ReceivedStream& stream, uint16_t index) {
    auto t = stream.textures().find(index);
    return t == stream.textures().end() ? std::string("none of it arrived") : texture_gap(t->second);
}

// Animations (format 1.4, spec 20.2): each complete one with the tracks a receiver shows, over the
// nodes written (node_map: stream node -> written node). What is not shown yet is named.
void received_animations(const ReceivedStream& stream, const std::map<uint16_t, uint16_t>& node_map,
                         const std::function<unsigned(uint16_t)>& node_targets, Asset& asset,
                         std::vector<std::string>& warnings);
// Morph targets (format 1.6, spec 22.4): the meshes shown with their targets keep their default
// weights and their objects get per-vertex displacements; the others lose them with a warning.
// Returns the stream meshes shown with their targets.
std::set<uint16_t> received_morphs(const ReceivedStream& stream, const std::map<uint16_t, uint16_t>& mesh_map,
                                   Asset& asset, std::vector<std::string>& warnings);

// Skins (format 1.5, spec 21.3): the written nodes whose skin can be shown keep it (renumbered), the
// others lose it with a warning saying why; weighted objects get per-vertex weights.
void received_skins(const ReceivedStream& stream, const std::map<uint16_t, uint16_t>& node_map, Asset& asset,
                    std::vector<std::string>& warnings);

// Format 1.12 (spec 28.3): the extras of the stream's element (`wire`, `wire_index`) go to the
// written element `asset_index` of the same table (an animation's, MORPH_ANIMATION's included, to
// the asset's animation) once its text is complete.
void carry_extras(const ReceivedStream& stream, ExtrasTarget wire, uint16_t wire_index, size_t asset_index, Asset& asset) {
    const auto it = stream.extras().find({wire, wire_index});
    if (it == stream.extras().end() || !it->second.complete) return;
    const ExtrasTarget kind = wire == ExtrasTarget::MorphAnimation ? ExtrasTarget::Animation : wire;
    asset.scene.extras.push_back({kind, uint16_t(asset_index), it->second.text});
}

// Extras texts that are not complete yet (spec 28.3), said in one warning.
void warn_extras_waiting(const ReceivedStream& stream, std::vector<std::string>& warnings) {
    const auto count = stream.extras_count();
    if (!count) return;
    size_t complete = 0;
    std::string first;
    for (const auto& [key, e] : stream.extras()) {
        if (e.complete) {
            ++complete;
            continue;
        }
        if (first.empty())
            first = extras_target_label(key.first, key.second) + ", " + std::to_string(e.received_bytes) + " of " +
                    std::to_string(e.text_size) + " bytes";
    }
    if (complete == *count) return;
    warnings.push_back(std::to_string(*count - complete) + " of " + std::to_string(*count) +
                       " extras texts have not arrived whole; their elements are written without extras" +
                       (first.empty() ? "" : " (the first: " + first + ")"));
}

// Format 1.13 (spec 29.2): the source's required extensions held, in their order; the writer requires
// those its output uses. Names not held yet are said in one warning.
void carry_required_extensions(const ReceivedStream& stream, Asset& asset) {
    for (const auto& [index, name] : stream.required_extensions()) asset.scene.required_extensions.push_back(name);
    const auto count = stream.required_extension_count();
    if (count && stream.required_extensions().size() < *count)
        asset.warnings.push_back(std::to_string(*count - stream.required_extensions().size()) + " of the source's " +
                                 std::to_string(*count) +
                                 " required extensions have not arrived; the output does not require them");
}

// A name as it can be shown and written (glTF is UTF-8 JSON): ill-formed UTF-8 replaced by U+FFFD
// (spec 15.1), with a warning.
std::string shown_name(const std::string& name, const std::string& what, std::vector<std::string>& warnings) {
    if (is_valid_utf8(name)) return name;
    std::string shown = replace_invalid_utf8(name);
    warnings.push_back(what + ": its name is not valid UTF-8; shown as \"" + shown + "\"");
    return shown;
}

}  // namespace

Asset received_asset(const ReceivedStream& stream, std::vector<Mesh> objects) {
    Asset asset;
    asset.objects = std::move(objects);
    auto& warnings = asset.warnings;
    carry_required_extensions(stream, asset);
    // Cameras and lights (format 1.10, spec 26.4): every one that arrived, renumbered in index order,
    // whether or not a node names it (also with no SCENE packet at all).
    std::map<uint16_t, uint16_t> camera_map, light_map;
    for (const auto& [index, c] : stream.cameras()) {
        camera_map[index] = uint16_t(asset.scene.cameras.size());
        SceneCamera out = c;
        out.name = shown_name(c.name, "camera " + std::to_string(index), warnings);
        carry_extras(stream, ExtrasTarget::Camera, index, asset.scene.cameras.size(), asset);
        asset.scene.cameras.push_back(std::move(out));
    }
    for (const auto& [index, l] : stream.lights()) {
        light_map[index] = uint16_t(asset.scene.lights.size());
        SceneLight out = l;
        out.name = shown_name(l.name, "light " + std::to_string(index), warnings);
        carry_extras(stream, ExtrasTarget::Light, index, asset.scene.lights.size(), asset);
        asset.scene.lights.push_back(std::move(out));
    }
    if (const auto count = stream.camera_count(); count && stream.cameras().size() < *count)
        warnings.push_back(std::to_string(*count - stream.cameras().size()) + " of " + std::to_string(*count) +
                           " cameras did not arrive");
    if (const auto count = stream.light_count(); count && stream.lights().size() < *count)
        warnings.push_back(std::to_string(*count - stream.lights().size()) + " of " + std::to_string(*count) +
                           " lights did not arrive");
    if (!stream.has_scene()) {
        if (!stream.materials().empty() || !stream.textures().empty())
            warnings.push_back("no SCENE packet arrived: materials and textures cannot be placed; each object is "
                               "written as its own node");
        carry_extras(stream, ExtrasTarget::Asset, 0, 0, asset);
        warn_extras_waiting(stream, warnings);
        return asset;  // write_asset gives each object its own node and mesh
    }

    // Textures: only complete ones (every byte arrived, checksum matches), renumbered.
    std::map<uint16_t, uint16_t> texture_map;
    for (const auto& [index, t] : stream.textures()) {
        if (!t.complete) continue;
        texture_map[index] = uint16_t(asset.scene.textures.size());
        SceneDescription::Texture out;
        out.info = t.info;
        out.info.index = uint16_t(asset.scene.textures.size());
        out.image = t.image;
        carry_extras(stream, ExtrasTarget::Texture, index, out.info.index, asset);
        asset.scene.textures.push_back(std::move(out));
    }

    // Materials that arrived and whose textures are all complete, renumbered. A material still
    // waiting for a texture is not shown at all (its primitives get the default material, as if it
    // had not arrived): a textured material without its texture would show the wrong colours. A
    // reference to a further texture-coordinate set (format 1.14, spec 30.2) is shown when every
    // object drawn with the material shows that set, and then waits for its texture like set 0;
    // otherwise it is cleared and the material shown without that texture.
    std::map<uint16_t, size_t> material_sets;  // stream material -> sets every object drawn with it shows
    std::map<uint16_t, uint16_t> lacking_object;  // stream material -> an object that shows fewest
    for (const auto& [index, m] : stream.scene_meshes())
        for (const auto& p : m.primitives) {
            if (p.material == kNone || p.object >= asset.objects.size() || asset.objects[p.object].positions.empty())
                continue;
            const Mesh& object = asset.objects[p.object];
            const size_t sets = object.has_texcoords() ? object.texcoord_sets.size() : 0;
            auto [it, fresh] = material_sets.emplace(p.material, sets);
            if (fresh || sets < it->second) it->second = sets, lacking_object[p.material] = p.object;
        }
    std::map<uint16_t, uint16_t> material_map;
    std::set<uint16_t> waiting_materials;
    uint16_t material_count = 0;
    for (const auto& [index, m] : stream.materials()) {
        material_count = std::max(material_count, m.material_count);
        Material out = m;
        out.name = shown_name(m.name, "material " + std::to_string(index), warnings);
        const std::string what = "material " + std::to_string(index) + (out.name.empty() ? "" : " (" + out.name + ")");
        std::vector<std::string> waiting;
        const std::pair<TextureRef*, const char*> slots[] = {{&out.base_color_texture, "baseColorTexture"},
                                                             {&out.metallic_roughness_texture, "metallicRoughnessTexture"},
                                                             {&out.normal_texture, "normalTexture"},
                                                             {&out.occlusion_texture, "occlusionTexture"},
                                                             {&out.emissive_texture, "emissiveTexture"}};
        for (auto [ref, slot] : slots) {
            if (ref->texture == kNone) continue;
            if (ref->texcoord != 0) {
                const auto sets = material_sets.find(index);
                if (sets != material_sets.end() && ref->texcoord > sets->second) {
                    const uint16_t object = lacking_object.at(index);
                    warnings.push_back(what + " " + slot + " uses TEXCOORD_" + std::to_string(ref->texcoord) +
                                       ", which object " + std::to_string(object) +
                                       (ref->texcoord > kMaxTexcoordSets ? " cannot have (ellicast carries TEXCOORD_0 to TEXCOORD_7)"
                                                                          : " does not show (its TEXCOORDS packets have not arrived)") +
                                       "; the material is shown without that texture");
                    ref->texture = kNone;
                    continue;
                }
            }
            if (auto it = texture_map.find(ref->texture); it != texture_map.end()) {
                ref->texture = it->second;
                continue;
            }
            waiting.push_back(std::string(slot) + " texture " + std::to_string(ref->texture) + " (" +
                              texture_missing(stream, ref->texture) + ")");
        }
        // Format 1.3 (spec 18.4): the material waits for its patch when its flag says it has one,
        // and for every texture the patch refers to; shown, it carries the patch remapped to the
        // complete textures' numbering.
        out.extensions.clear();
        out.has_extensions = false;
        if (auto patch = stream.material_extensions().find(index); patch != stream.material_extensions().end()) {
            std::vector<PatchTextureReference> refs;
            check_material_patch(patch->second.patch, &refs);  // it passed at reception
            bool complete = true;
            for (const auto& r : refs) {
                if (texture_map.count(r.texture)) continue;
                complete = false;
                waiting.push_back(r.path + " texture " + std::to_string(r.texture) + " (" +
                                  texture_missing(stream, r.texture) + ")");
            }
            if (complete) {
                out.extensions = remap_patch_textures(patch->second.patch, refs,
                                                      [&](uint16_t t) { return texture_map.at(t); });
                out.has_extensions = true;
            }
        } else if (m.has_extensions) {
            waiting.push_back("extensions (its MATERIAL_EXTENSIONS packet has not arrived)");
        }
        if (!waiting.empty()) {
            std::string list;
            for (size_t i = 0; i < waiting.size(); ++i) list += (i ? ", " : "") + waiting[i];
            warnings.push_back(what + " is waiting for its " + list +
                               "; its primitives get the default material until it has arrived whole");
            waiting_materials.insert(index);
            continue;
        }
        material_map[index] = uint16_t(asset.scene.materials.size());
        out.index = uint16_t(asset.scene.materials.size());
        carry_extras(stream, ExtrasTarget::Material, index, out.index, asset);
        asset.scene.materials.push_back(std::move(out));
    }
    if (stream.materials().size() < material_count)
        warnings.push_back(std::to_string(material_count - stream.materials().size()) + " of " +
                           std::to_string(material_count) +
                           " materials did not arrive; their primitives get the default material");

    // Meshes that arrived, renumbered; references to materials that did not arrive cleared.
    std::map<uint16_t, uint16_t> mesh_map;
    std::set<uint16_t> missing_materials;
    for (const auto& [index, m] : stream.scene_meshes()) {
        mesh_map[index] = uint16_t(asset.scene.meshes.size());
        SceneMesh out = m;
        out.name = shown_name(m.name, "mesh " + std::to_string(out.index), warnings);
        out.index = uint16_t(asset.scene.meshes.size());
        for (auto& p : out.primitives) {
            if (p.material == kNone) continue;
            if (auto it = material_map.find(p.material); it != material_map.end()) {
                p.material = it->second;
            } else {
                if (!waiting_materials.count(p.material)) missing_materials.insert(p.material);
                p.material = kNone;
            }
        }
        carry_extras(stream, ExtrasTarget::Mesh, index, out.index, asset);
        asset.scene.meshes.push_back(std::move(out));
    }

    // Nodes whose whole parent chain arrived, renumbered in index order.
    const auto& nodes = stream.scene_nodes();
    std::map<uint16_t, bool> reaches_root;
    size_t cut_off = 0;
    for (const auto& [index, n] : nodes) {
        std::vector<uint16_t> chain;
        std::set<uint16_t> seen;
        uint16_t at = index;
        bool ok = false;
        while (true) {
            if (auto known = reaches_root.find(at); known != reaches_root.end()) {
                ok = known->second;
                break;
            }
            auto it = nodes.find(at);
            if (it == nodes.end() || !seen.insert(at).second) break;  // missing ancestor, or a cycle
            chain.push_back(at);
            if (it->second.parent == kNone) {
                ok = true;
                break;
            }
            at = it->second.parent;
        }
        for (uint16_t c : chain) reaches_root[c] = ok;
        if (!ok) ++cut_off;
    }
    std::map<uint16_t, uint16_t> node_map;
    for (const auto& [index, n] : nodes)
        if (reaches_root[index]) node_map[index] = uint16_t(node_map.size());
    std::set<uint16_t> missing_meshes;
    for (const auto& [index, n] : nodes) {
        if (!reaches_root[index]) continue;
        SceneNode out = n;
        out.name = shown_name(n.name, "node " + std::to_string(out.index), warnings);
        out.index = node_map[index];
        out.parent = n.parent == kNone ? kNone : node_map.at(n.parent);
        if (n.mesh != kNone) {
            if (auto it = mesh_map.find(n.mesh); it != mesh_map.end()) {
                out.mesh = it->second;
            } else {
                missing_meshes.insert(n.mesh);
                out.mesh = kNone;
            }
        }
        // Format 1.10 (spec 26.4): its camera and light once they have arrived. (The lambda names
        // copies: clang before 16 cannot capture structured bindings.)
        const uint16_t node_index = index;
        const bool unnamed = n.name.empty();
        const auto attach = [&](uint16_t& field, const std::map<uint16_t, uint16_t>& map, const char* what) {
            if (field == kNone) return;
            if (auto it = map.find(field); it != map.end()) {
                field = it->second;
                return;
            }
            warnings.push_back("node " + std::to_string(node_index) + (unnamed ? "" : " (" + out.name + ")") +
                               " is shown without its " + what + " " + std::to_string(field) + ", which has not arrived");
            field = kNone;
        };
        attach(out.camera, camera_map, "camera");
        attach(out.light, light_map, "light");
        carry_extras(stream, ExtrasTarget::Node, index, out.index, asset);
        asset.scene.nodes.push_back(std::move(out));
    }
    const std::set<uint16_t> morphed = received_morphs(stream, mesh_map, asset, warnings);
    const auto node_targets = [&](uint16_t node) -> unsigned {
        const auto n = nodes.find(node);
        if (n == nodes.end() || !morphed.count(n->second.mesh)) return 0;
        return unsigned(stream.scene_meshes().at(n->second.mesh).weights.size());
    };
    received_animations(stream, node_map, node_targets, asset, warnings);
    received_skins(stream, node_map, asset, warnings);
    // The asset and its scene are always written (spec 28.3).
    carry_extras(stream, ExtrasTarget::Asset, 0, 0, asset);
    carry_extras(stream, ExtrasTarget::Scene, 0, 0, asset);
    warn_extras_waiting(stream, warnings);
    const size_t node_count = stream.scene_node_count();
    if (nodes.size() < node_count || cut_off)
        warnings.push_back(std::to_string(node_count - nodes.size()) + " of " + std::to_string(node_count) +
                           " scene nodes did not arrive" +
                           (cut_off ? "; " + std::to_string(cut_off) + " node(s) below them are left out" : ""));
    if (!missing_meshes.empty())
        warnings.push_back(std::to_string(missing_meshes.size()) + " mesh record(s) did not arrive; their nodes are "
                           "written without a mesh");
    if (!missing_materials.empty())
        warnings.push_back(std::to_string(missing_materials.size()) +
                           " material(s) used by primitives did not arrive; those primitives get the default material");

    // Objects that no written node shows get a root node of their own, in their mesh's frame.
    std::set<size_t> shown;
    for (const auto& n : asset.scene.nodes)
        if (n.mesh != kNone)
            for (const auto& p : asset.scene.meshes[n.mesh].primitives) shown.insert(p.object);
    for (size_t o = 0; o < asset.objects.size(); ++o) {
        if (asset.objects[o].positions.empty() || shown.count(o)) continue;
        if (asset.scene.nodes.size() >= 0xFFFE || asset.scene.meshes.size() >= 0xFFFE) break;
        // Keep the material a received mesh gives the object, if any.
        uint16_t material = kNone;
        for (const auto& m : asset.scene.meshes)
            for (const auto& p : m.primitives)
                if (p.object == o && material == kNone) material = p.material;
        SceneMesh mesh;
        mesh.index = uint16_t(asset.scene.meshes.size());
        mesh.name = asset.objects[o].name.empty() ? "object" + std::to_string(o) : asset.objects[o].name;
        mesh.primitives.push_back({uint16_t(o), material});
        SceneNode node;
        node.index = uint16_t(asset.scene.nodes.size());
        node.mesh = mesh.index;
        node.name = mesh.name;
        warnings.push_back("object " + std::to_string(o) +
                           ": no node that shows it arrived; written as a root node in its own frame");
        asset.scene.meshes.push_back(std::move(mesh));
        asset.scene.nodes.push_back(std::move(node));
    }
    return asset;
}

namespace {
std::set<uint16_t> received_morphs(const ReceivedStream& stream, const std::map<uint16_t, uint16_t>& mesh_map,
                                   Asset& asset, std::vector<std::string>& warnings) {
    std::set<uint16_t> out;
    asset.morphs.assign(asset.objects.size(), {});
    const auto object_shown = [&](uint16_t o) { return o < asset.objects.size() && !asset.objects[o].positions.empty(); };
    for (const auto& [index, mesh] : stream.scene_meshes()) {
        if (mesh.weights.empty()) continue;
        SceneMesh& written = asset.scene.meshes[mesh_map.at(index)];
        if (!mesh_shows_targets(stream, mesh, object_shown)) {
            written.weights.clear();
            std::string why = "none of its objects has arrived";
            for (const auto& p : mesh.primitives) {
                if (!object_shown(p.object)) continue;
                const ReceivedObject& o = stream.objects()[p.object];
                if (o.morph.empty())
                    why = "no displacements of object " + std::to_string(p.object) + " have arrived";
                else if (!morphed(o))
                    why = "no point of object " + std::to_string(p.object) + " with its displacements has arrived";
                else if (o.morph_targets != mesh.weights.size())
                    why = "object " + std::to_string(p.object) + " has " + std::to_string(o.morph_targets) +
                          " morph targets, the mesh " + std::to_string(mesh.weights.size());
                else continue;
                break;
            }
            warnings.push_back("mesh " + std::to_string(index) + " is shown without its " +
                               std::to_string(mesh.weights.size()) + " morph targets (in its base shape): " + why);
            continue;
        }
        out.insert(index);
        for (const auto& p : mesh.primitives)
            if (object_shown(p.object) && asset.morphs[p.object].empty())
                asset.morphs[p.object] = morph_targets::vertex_morph(asset.objects[p.object], stream, p.object);
    }
    return out;
}

void received_animations(const ReceivedStream& stream, const std::map<uint16_t, uint16_t>& node_map,
                         const std::function<unsigned(uint16_t)>& node_targets, Asset& asset,
                         std::vector<std::string>& warnings) {
    const auto shown = shown_animations(stream, [&](uint16_t node) { return node_map.count(node) > 0; }, node_targets);
    std::set<uint16_t> shown_indices, shown_morphs;
    for (const ShownAnimation& s : shown) {
        const auto& received = s.morph_only ? stream.morph_animations().at(s.index) : stream.animations().at(s.index);
        const std::string what = (s.morph_only ? "morph animation " : "animation ") + std::to_string(s.index);
        SceneAnimation a;
        a.name = shown_name(received.name, what, warnings);
        for (uint16_t t : s.tracks) {
            const auto& track = received.tracks.at(t);
            a.tracks.push_back({node_map.at(track.info.node), track.info.path, track.info.interpolation, 0, track.times,
                                track.values});
        }
        size_t morph_declared = 0;
        for (const auto& [m, morph] : stream.morph_animations())
            if (s.morph_only ? m == s.index : morph.joins == s.index) {
                morph_declared += morph.track_count;
                shown_morphs.insert(m);
            }
        for (const auto& [m, t] : s.morph_tracks) {
            const auto& track = stream.morph_animations().at(m).tracks.at(t);
            a.tracks.push_back({node_map.at(track.info.node), AnimationPath::Weights, track.info.interpolation,
                                track.info.targets, track.times, track.values});
        }
        if (!s.morph_only) shown_indices.insert(s.index);
        const size_t declared = (s.morph_only ? 0 : received.track_count) + morph_declared;
        if (a.tracks.size() < declared)
            warnings.push_back(what + ": " + std::to_string(declared - a.tracks.size()) + " of its " +
                               std::to_string(declared) +
                               " tracks left out (a node not shown or without its morph targets, times that do not "
                               "increase, or a target moved twice)");
        carry_extras(stream, s.morph_only ? ExtrasTarget::MorphAnimation : ExtrasTarget::Animation, s.index,
                     asset.scene.animations.size(), asset);
        asset.scene.animations.push_back(std::move(a));
    }
    // Why an animation (or morph animation) that arrived in part or whole is not shown.
    const auto not_shown = [&](const std::string& what, const ReceivedStream::ReceivedAnimation& a,
                               const char* why_complete) {
        uint64_t held = 0;
        for (const auto& [t, track] : a.tracks) held += track.keys_held;
        warnings.push_back(what + " not shown: " +
                           (a.complete() ? std::string(why_complete)
                                         : std::to_string(a.tracks.size()) + " of its " + std::to_string(a.track_count) +
                                               " tracks and " + std::to_string(held) + " keys of those arrived so far"));
    };
    for (const auto& [m, morph] : stream.morph_animations())
        if (!shown_morphs.count(m))
            not_shown("morph animation " + std::to_string(m), morph,
                      "none of its tracks can be shown, or the animation it joins is not");
    if (const auto count = stream.morph_animation_count(); count && stream.morph_animations().size() < *count)
        warnings.push_back(std::to_string(*count - stream.morph_animations().size()) + " of " + std::to_string(*count) +
                           " morph animations did not arrive at all" +
                           (stream.animations().empty() ? "" : "; the animations wait for them"));
    for (const auto& [index, animation] : stream.animations())
        if (!shown_indices.count(index))
            not_shown("animation " + std::to_string(index), animation, "none of its tracks can be shown");
    if (const auto count = stream.animation_count(); count && stream.animations().size() < *count)
        warnings.push_back(std::to_string(*count - stream.animations().size()) + " of " + std::to_string(*count) +
                           " animations did not arrive at all");
}

void received_skins(const ReceivedStream& stream, const std::map<uint16_t, uint16_t>& node_map, Asset& asset,
                    std::vector<std::string>& warnings) {
    // Weighted objects (a held point with its record) and the largest joint index of their records.
    asset.weights.assign(asset.objects.size(), {});
    std::map<size_t, uint16_t> max_joint;
    for (size_t o = 0; o < asset.objects.size() && o < stream.objects().size(); ++o) {
        if (asset.objects[o].positions.empty()) continue;
        asset.weights[o] = skin_weights::vertex_weights(asset.objects[o], stream, o);
        if (asset.weights[o].empty()) continue;
        uint16_t m = 0;
        for (const auto& [i, r] : stream.objects()[o].weights)
            for (size_t k = 0; k < r->count; ++k) m = std::max(m, r->joints[k]);
        max_joint[o] = m;
    }
    std::map<uint16_t, uint16_t> skin_map;  // stream skin -> written skin
    for (SceneNode& node : asset.scene.nodes) {
        if (node.skin == kNone) continue;
        const uint16_t skin = node.skin;
        node.skin = kNone;
        const std::string what = "node " + std::to_string(node.index) + (node.name.empty() ? "" : " (" + node.name + ")");
        std::string why;
        auto s = stream.skins().find(skin);
        if (s == stream.skins().end()) {
            why = "its skin " + std::to_string(skin) + " has not arrived";
        } else if (!s->second.complete()) {
            why = "its skin " + std::to_string(skin) + " has " + std::to_string(s->second.joints.size()) + " of its " +
                  std::to_string(s->second.joint_count) + " joints";
        } else if (node.mesh == kNone) {
            why = "its mesh is not shown";
        } else {
            for (const auto& [j, joint] : s->second.joints)
                if (!node_map.count(joint.node)) {
                    why = "the node " + std::to_string(joint.node) + " of joint " + std::to_string(j) + " is not shown";
                    break;
                }
            if (why.empty() && s->second.skeleton != kNone && !node_map.count(s->second.skeleton))
                why = "its skeleton node " + std::to_string(s->second.skeleton) + " is not shown";
            bool any = false;
            for (const auto& p : asset.scene.meshes[node.mesh].primitives) {
                if (!why.empty()) break;
                if (p.object >= asset.objects.size() || asset.objects[p.object].positions.empty()) continue;
                any = true;
                if (asset.weights[p.object].empty())
                    why = "no weights of object " + std::to_string(p.object) + " have arrived";
                else if (max_joint[p.object] >= s->second.joint_count)
                    why = "the weights of object " + std::to_string(p.object) + " name joint " +
                          std::to_string(max_joint[p.object]) + ", past the skin's " +
                          std::to_string(s->second.joint_count) + " joints";
            }
            if (why.empty() && !any) why = "none of its mesh's objects has arrived";
        }
        if (!why.empty()) {
            warnings.push_back(what + " is shown without its skin (in the bind pose): " + why);
            continue;
        }
        auto [it, fresh] = skin_map.try_emplace(skin, uint16_t(asset.scene.skins.size()));
        if (fresh) {
            SceneSkin out;
            out.name = shown_name(s->second.name, "skin " + std::to_string(skin), warnings);
            out.skeleton = s->second.skeleton == kNone ? kNone : node_map.at(s->second.skeleton);
            for (const auto& [j, joint] : s->second.joints) out.joints.push_back({node_map.at(joint.node), joint.inverse_bind});
            carry_extras(stream, ExtrasTarget::Skin, skin, asset.scene.skins.size(), asset);
            asset.scene.skins.push_back(std::move(out));
        }
        node.skin = it->second;
    }
    if (const auto count = stream.skin_count(); count && stream.skins().size() < *count)
        warnings.push_back(std::to_string(*count - stream.skins().size()) + " of " + std::to_string(*count) +
                           " skins did not arrive at all");
}

}  // namespace

}  // namespace ellicast

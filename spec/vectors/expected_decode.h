// The expected decode of a conformance vector as JSON: what a format 1.9 decoder makes of a container
// file (spec/format.md sections 10 and 11). The vector generator (make_vectors.cpp) writes it next to
// each .ellc; tests/test_conformance.cpp recomputes it with the library and compares. The JSON layout
// is described in spec/vectors/README.md.
#pragma once

#include <ellicast/auth.h>
#include <ellicast/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace ellicast::conformance {

// Elements of one kind are listed one by one up to this many per object; the digest is always given.
inline constexpr size_t kMaxListedElements = 300;

// The reason names of spec section 11.3 (stable: the vectors use them; error_name() is for people).
inline const char* reason_name(Error e) {
    switch (e) {
    case Error::Ok: return "ok";
    case Error::TooShort: return "too short";
    case Error::BadMagic: return "bad magic";
    case Error::UnsupportedMajor: return "unsupported major version";
    case Error::InvalidType: return "invalid type";
    case Error::Oversized: return "oversized";
    case Error::Truncated: return "truncated";
    case Error::LengthMismatch: return "length mismatch";
    case Error::BadChecksum: return "bad checksum";
    case Error::UnknownCriticalType: return "unknown critical type";
    case Error::MalformedPayload: return "malformed payload";
    case Error::NoStreamInfo: return "no stream info";
    case Error::UnknownObject: return "unknown object";
    case Error::IndexOutOfRange: return "index out of range";
    case Error::StreamMismatch: return "stream mismatch";
    case Error::BadSignature: return "bad container signature";
    case Error::UnsupportedContainer: return "unsupported container version";
    case Error::IoError: return "i/o error";
    case Error::ManifestSignature: return "bad manifest signature";
    case Error::NotAuthenticated: return "not authenticated";
    }
    return "unknown";
}

// FNV-1a, 64 bits, over little-endian u32 words: the digest of a list of quantized elements.
class Digest {
public:
    void add(uint32_t v) {
        for (int i = 0; i < 4; ++i) {
            h_ ^= (v >> (8 * i)) & 0xFF;
            h_ *= 0x100000001B3ull;
        }
    }
    std::string hex() const {
        char buf[20];
        std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
        return buf;
    }

private:
    uint64_t h_ = 0xCBF29CE484222325ull;
};

// A float as the shortest decimal that reads back as the same float (JSON numbers are doubles).
inline double shortest(float f) {
    if (!std::isfinite(f)) return static_cast<double>(f);
    char buf[32];
    for (int digits = 6; digits <= 9; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, static_cast<double>(f));
        if (std::strtof(buf, nullptr) == f) break;
    }
    return std::strtod(buf, nullptr);
}

inline nlohmann::json floats(const float* v, size_t n) {
    nlohmann::json a = nlohmann::json::array();
    for (size_t i = 0; i < n; ++i) a.push_back(shortest(v[i]));
    return a;
}

inline std::vector<uint32_t> ellipsoid_integers(const QuantizedEllipsoid& q) {
    return {q.center[0], q.center[1], q.center[2], q.radii[0], q.radii[1], q.radii[2],
            q.largest,   q.rotation[0], q.rotation[1], q.rotation[2]};
}

inline std::vector<uint32_t> point_integers(const QuantizedPoint& q, const ObjectInfo& o) {
    std::vector<uint32_t> v(q.position.begin(), q.position.end());
    if (o.has(kAttrNormal)) v.insert(v.end(), q.normal.begin(), q.normal.end());
    if (o.has(kAttrTexcoord)) v.insert(v.end(), q.texcoord.begin(), q.texcoord.end());
    for (int i = 0; i < o.color_channels(); ++i) v.push_back(q.color[i]);
    return v;
}

inline nlohmann::json stream_info_json(const StreamInfo& s, size_t object_count) {
    return {{"packet_size", s.packet_size},
            {"position_bits", s.position_bits},
            {"normal_bits", s.normal_bits},
            {"texcoord_bits", s.texcoord_bits},
            {"color_bits", s.color_bits},
            {"ellipsoid_encoding", s.ellipsoid_encoding},
            {"content_id", s.content_id},
            {"object_count", object_count},
            {"grid_hint", s.grid_hint},
            {"coverage_target", shortest(s.coverage_target)},
            {"seed", s.seed}};
}

inline nlohmann::json object_info_json(const ObjectInfo& o) {
    nlohmann::json j = {{"frame_origin", floats(o.frame.origin.data(), 3)},
                        {"frame_scale", shortest(o.frame.scale)},
                        {"ellipsoid_count", o.ellipsoid_count},
                        {"point_count", o.point_count},
                        {"kind", o.kind == ObjectKind::Surface ? "surface" : "point set"},
                        {"attributes", o.attributes},
                        {"texcoord_origin", floats(o.texcoord_origin.data(), 2)},
                        {"texcoord_scale", floats(o.texcoord_scale.data(), 2)}};
    // Format 1.7 (spec 23.1): the map fields, listed only for a mapped object (map_level > 0), so that the
    // decodes of the streams without a map stay as they were.
    if (o.mapped()) {
        j["map_level"] = o.map_level;
        j["map_batch"] = o.map_batch;
    }
    return j;
}

// A point (or, format 1.11, a carried vertex): its index, integers and dequantized values.
inline nlohmann::json point_entry_json(const ReceivedStream& stream, const ObjectInfo& oi, uint32_t index,
                                       const QuantizedPoint& q) {
    SurfacePoint s = dequantize_point(q, *stream.info(), oi);
    nlohmann::json p = {{"index", index}, {"q", point_integers(q, oi)}, {"position", floats(s.position.data(), 3)}};
    if (oi.has(kAttrNormal)) p["normal"] = floats(s.normal.data(), 3);
    if (oi.has(kAttrTexcoord)) p["texcoord"] = floats(s.texcoord.data(), 2);
    if (oi.color_channels() > 0) p["color"] = floats(s.color.data(), oi.color_channels());
    return p;
}

// Format 1.3 (spec 19.1, 19.2, 19.5): an object's connectivity, held from the first CONNECTIVITY or
// CONNECTIVITY_REPAIR packet of it that passed the checks of spec 19.1 or 19.5 (also after its bytes
// were discarded for a wrong CRC-32C), and, once it is complete and every point of the object is
// held, its decode: the exact triangle list, or `unusable`.
inline nlohmann::json connectivity_json(const ReceivedStream& stream, size_t object) {
    const ReceivedObject& o = stream.objects()[object];
    const ReceivedConnectivity& c = *o.connectivity;
    nlohmann::json j = {{"triangle_count", c.triangle_count}};
    // Format 1.11 (spec 27): an exact layer in EXACT_MESH packets says so, with its carried count.
    if (c.mesh) {
        j["mesh"] = true;
        j["carried_count"] = c.carried_count;
    }
    j.update({{"coded_size", c.coded_size},
                        {"coded_crc", c.coded_crc},
                        {"received_bytes", c.complete ? uint64_t(c.coded_size) : c.received_bytes},
                        {"complete", c.complete}});
    // Format 1.3 repair packets (spec 19.5), listed once a CONNECTIVITY_REPAIR packet of the object
    // passed the checks (so that the decodes of the vectors without one stay as they were): the symbol
    // size they say, the rows held (in the order accepted; none once complete, or after the bytes were
    // discarded for a wrong CRC-32C), and whether the connectivity was completed by solving for missing
    // source symbols.
    if (c.symbol_size != 0) {
        nlohmann::json rows = nlohmann::json::array();
        for (uint8_t r : c.rows) rows.push_back(r);
        j["symbol_size"] = c.symbol_size;
        j["rows"] = rows;
        j["recovered"] = c.recovered;
    }
    if (c.complete && o.info && o.points.size() == o.info->point_count) {
        std::vector<Triangle> triangles;
        std::vector<QuantizedPoint> carried;
        std::string why;
        if (exact_layer(stream, object, triangles, carried, why) == Error::Ok) {
            nlohmann::json list = nlohmann::json::array();
            for (const Triangle& t : triangles) list.push_back({t[0], t[1], t[2]});
            j["triangles"] = list;
            if (c.mesh) {
                nlohmann::json vertices = nlohmann::json::array();
                for (size_t k = 0; k < carried.size(); ++k)
                    vertices.push_back(point_entry_json(stream, *o.info, uint32_t(o.info->point_count + k), carried[k]));
                j["carried"] = vertices;
            }
        } else {
            j["unusable"] = true;
        }
    }
    return j;
}

// Format 1.8 (spec 24.2, 24.3): the normal entries held for an object with surface normals, by point
// index ("sent" with its integers and its dequantized normal, or left to the surface), whether they are
// complete (an entry for every point 0 .. point_count - 1), and, once the object is exact (spec 19.4:
// every point held and the connectivity decoded), every point's surface normal over the exact triangle
// list (null where it is undefined: no triangle contributes, or the sum is 0); null while not exact.
inline nlohmann::json normals_json(const ReceivedStream& stream, size_t object) {
    using nlohmann::json;
    const ReceivedObject& o = stream.objects()[object];
    const int bits = stream.info()->normal_bits;
    json entries = json::array();
    for (const auto& [index, e] : o.normal_entries) {
        if (e.sent)
            entries.push_back({{"index", index},
                               {"sent", true},
                               {"q", {e.normal[0], e.normal[1]}},
                               {"normal", floats(decode_octahedral(e.normal, bits).data(), 3)}});
        else
            entries.push_back({{"index", index}, {"sent", false}});
    }
    json surface = nullptr;
    std::vector<Triangle> triangles;
    std::vector<QuantizedPoint> carried;
    std::string why;
    if (exact_layer(stream, object, triangles, carried, why) == Error::Ok) {
        // Every vertex of the exact triangle list: the points, then (format 1.11) the carried vertices.
        std::vector<std::array<uint32_t, 3>> positions;
        positions.reserve(o.points.size() + carried.size());
        for (const auto& [index, p] : o.points) positions.push_back(p.position);
        for (const QuantizedPoint& q : carried) positions.push_back(q.position);
        const SurfaceNormals normals = surface_normals(positions, triangles);
        surface = json::array();
        for (size_t i = 0; i < positions.size(); ++i) {
            const std::array<float, 3>& n = normals.normal[i];
            const bool defined = n[0] != 0 || n[1] != 0 || n[2] != 0;
            surface.push_back({{"index", i}, {"normal", defined ? floats(n.data(), 3) : json(nullptr)}});
        }
    }
    return {{"entries", entries}, {"complete", o.normals_complete()}, {"surface", surface}};
}

// The objects a receiver holds, as the JSON lists them.
inline nlohmann::json objects_json(const ReceivedStream& stream) {
    using nlohmann::json;
    json objects = json::array();
    for (size_t i = 0; i < stream.objects().size(); ++i) {
        const ReceivedObject& object = stream.objects()[i];
        json o;
        o["id"] = i;
        o["info"] = object.info ? object_info_json(*object.info) : json(nullptr);
        o["ellipsoids_received"] = object.ellipsoids.size();
        o["points_received"] = object.points.size();
        if (object.info) {
            const ObjectInfo& oi = *object.info;
            Digest ed, pd;
            json ellipsoids = json::array(), points = json::array();
            for (const auto& [index, held] : object.ellipsoids) {
                const QuantizedEllipsoid& q = *held;
                auto ints = ellipsoid_integers(q);
                ed.add(index);
                for (uint32_t v : ints) ed.add(v);
                if (object.ellipsoids.size() > kMaxListedElements) continue;
                Ellipsoid e = dequantize_ellipsoid(q, oi.frame);
                ellipsoids.push_back({{"index", index},
                                      {"q", ints},
                                      {"center", floats(e.center.data(), 3)},
                                      {"radii", floats(e.radii.data(), 3)},
                                      {"rotation", floats(e.rotation.data(), 4)}});
            }
            for (const auto& [index, q] : object.points) {
                auto ints = point_integers(q, oi);
                pd.add(index);
                for (uint32_t v : ints) pd.add(v);
                if (object.points.size() > kMaxListedElements) continue;
                points.push_back(point_entry_json(stream, oi, index, q));
            }
            o["ellipsoid_digest"] = ed.hex();
            o["point_digest"] = pd.hex();
            o["ellipsoids_listed"] = object.ellipsoids.size() <= kMaxListedElements;
            o["points_listed"] = object.points.size() <= kMaxListedElements;
            o["ellipsoids"] = ellipsoids;
            o["points"] = points;
            // Format 1.2 repair packets (spec 17.4): the points recovered, and every block of which a
            // POINTS_REPAIR packet passed the checks, in first_index order.
            o["points_recovered"] = object.points_recovered;
            json blocks = json::array();
            for (const auto& [first, b] : object.repair_blocks) {
                json rows = json::array();
                for (uint8_t r : b.rows_accepted) rows.push_back(r);
                blocks.push_back({{"first_index", b.block.first_index},
                                  {"batch", b.block.batch},
                                  {"source_count", b.block.source_count()},
                                  {"point_count", b.block.point_count},
                                  {"rows", rows},
                                  {"complete", b.complete},
                                  {"recovered", b.recovered},
                                  {"points_recovered", b.points_recovered}});
            }
            o["repair_blocks"] = blocks;
            // Format 1.3, the exact layer (spec 19): listed only for an object whose entry announces
            // one or that holds a connectivity, so that the decodes of streams without it stay as they were.
            if (oi.exact_layer || object.connectivity) o["exact_layer"] = oi.exact_layer;
            if (object.connectivity) o["connectivity"] = connectivity_json(stream, i);
            // Format 1.8, surface normals (spec 24): listed only for an object whose entry has the flag
            // (read from a STREAM_INFO that says 1.8 or later), so that the decodes of the streams without
            // it stay as they were.
            if (oi.surface_normals) {
                o["surface_normals"] = true;
                o["normals"] = normals_json(stream, i);
            }
            // Format 1.14 (spec 30): the further texture-coordinate sets, listed only for an object that
            // holds a TEXCOORDS packet, so that the decodes of streams without one stay as they were:
            // set_count, and per set (1 .. set_count) its range (null before a packet of the set was
            // accepted), whether every point's record is held, and the records by point index, each as
            // its integers and its dequantized coordinates.
            if (!object.texcoord_sets.empty()) {
                json sets = json::array();
                for (size_t s = 0; s < object.texcoord_sets.size(); ++s) {
                    const ReceivedTexcoordSet& set = object.texcoord_sets[s];
                    json records = json::array();
                    for (const auto& [index, r] : set.records)
                        records.push_back({{"index", index},
                                           {"q", {r[0], r[1]}},
                                           {"texcoord", floats(dequantize_texcoord({r[0], r[1]}, set.range).data(), 2)}});
                    json range = nullptr;
                    if (set.has_range)
                        range = {{"bits", set.range.bits},
                                 {"origin", floats(set.range.origin.data(), 2)},
                                 {"scale", floats(set.range.scale.data(), 2)}};
                    sets.push_back({{"set", s + 1},
                                    {"range", range},
                                    {"complete", set.records.size() == oi.point_count},
                                    {"records", records}});
                }
                o["texcoord_sets"] = {{"set_count", object.texcoord_sets.size()}, {"sets", sets}};
            }
            // Format 1.5 (spec 21.2): the influence records held, by point index; listed only for an
            // object that holds one, so that the decodes of streams without JOINT_WEIGHTS stay as they were.
            if (!object.weights.empty()) {
                json weights = json::array();
                for (const auto& [index, r] : object.weights) {
                    json joints = json::array(), w = json::array();
                    for (size_t k = 0; k < r->count; ++k) {
                        joints.push_back(r->joints[k]);
                        w.push_back(r->weights[k]);
                    }
                    weights.push_back({{"index", index}, {"joints", joints}, {"weights", w}});
                }
                o["weights"] = weights;
            }
            // Format 1.7 (spec 23): a mapped object's map: the fragments accepted (by first rank, each with its
            // cells of level map_level as [Morton code, count] in code order), the ranks they hold, whether
            // they hold every rank, and the records held but not placed (by index, each as its integers: the
            // offset inside its cell, then the attributes). Placed points are in `points`.
            if (oi.mapped()) {
                json fragments = json::array(), unplaced = json::array();
                for (const auto& [first, f] : object.map_fragments) {
                    json cells = json::array();
                    for (const MapCell& c : f.cells()) cells.push_back({c.code, c.count});
                    fragments.push_back({{"first_rank", first}, {"point_total", f.point_total()}, {"cells", cells}});
                }
                for (const auto& [index, q] : object.unplaced)
                    unplaced.push_back({{"index", index}, {"q", point_integers(q, oi)}});
                o["map"] = {{"fragments", fragments},
                            {"ranks", object.map_ranks},
                            {"complete", object.map_complete()},
                            {"unplaced", unplaced}};
            }
            // Format 1.6 (spec 22.1): the target count, attributes and scales kept for the object and the
            // displacement records held, by point index, each as its integers and as its dequantized
            // displacements; listed only for an object that holds one, so that the decodes of streams
            // without MORPH_DELTAS stay as they were.
            if (!object.morph.empty()) {
                const std::vector<float>& scales = object.morph_scales;
                json records = json::array();
                for (const auto& [index, values] : object.morph) {
                    // The library keeps a record dequantized (q * scale in f32); the integer of a component
                    // is the nearest to value / scale: the products of distinct i16 values and one f32 scale
                    // round to distinct f32 values, within 2^-9 of q * scale once divided by it (README).
                    json q = json::array();
                    for (size_t i = 0; i < object.morph.stride(); ++i) {
                        const double v = values[i], s = scales[i / 3];
                        q.push_back(std::isfinite(v) ? json(std::lround(v / s)) : json(nullptr));
                    }
                    records.push_back({{"index", index}, {"q", q}, {"values", floats(values, object.morph.stride())}});
                }
                o["morph"] = {{"target_count", object.morph_targets},
                              {"attributes", object.morph_attributes},
                              {"scales", floats(scales.data(), scales.size())},
                              {"records", records}};
            }
        }
        objects.push_back(o);
    }
    return objects;
}

inline nlohmann::json counters_json(const ReceiveCounters& c) {
    return {{"accepted", c.accepted}, {"duplicates", c.duplicates}, {"skipped", c.skipped},
            {"rejected", c.rejected}, {"held", c.pending}};
}

// ---- Format 1.1 scene (spec section 15) ----

// The scene types of format 1.1 (SCENE, MATERIAL, TEXTURE_FRAGMENT), 1.3 (MATERIAL_EXTENSIONS), 1.4
// (ANIMATION), 1.5 (SKIN; JOINT_WEIGHTS belongs to an object and is not one) and 1.6 (MORPH_ANIMATION;
// MORPH_DELTAS belongs to an object and is not one).
inline bool is_scene_type(uint8_t type) {
    return type == uint8_t(PacketType::Scene) || type == uint8_t(PacketType::Material) ||
           type == uint8_t(PacketType::TextureFragment) || type == uint8_t(PacketType::MaterialExtensions) ||
           type == uint8_t(PacketType::Animation) || type == uint8_t(PacketType::Skin) ||
           type == uint8_t(PacketType::MorphAnimation) || type == uint8_t(PacketType::Camera) ||
           type == uint8_t(PacketType::Light) || type == uint8_t(PacketType::Extras) ||
           type == uint8_t(PacketType::RequiredExtension);
}

inline nlohmann::json none_or(uint16_t v) { return v == kNone ? nlohmann::json(nullptr) : nlohmann::json(v); }

// FNV-1a 64 over the bytes of a complete texture image.
inline std::string bytes_digest(const std::vector<uint8_t>& bytes) {
    uint64_t h = 0xCBF29CE484222325ull;
    for (uint8_t b : bytes) {
        h ^= b;
        h *= 0x100000001B3ull;
    }
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

inline const char* kTextureSlots[5] = {"base_color", "metallic_roughness", "normal", "occlusion", "emissive"};

inline std::array<const TextureRef*, 5> texture_refs(const Material& m) {
    return {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture, &m.occlusion_texture,
            &m.emissive_texture};
}

// Format 1.10 (spec 26.2, 26.3): a camera and a light as received, the fields named as glTF names them.
inline nlohmann::json camera_json(const SceneCamera& c) {
    const bool perspective = c.projection == CameraProjection::Perspective;
    return {{"index", c.index},
            {"name", replace_invalid_utf8(c.name)},
            {"projection", perspective ? "perspective" : "orthographic"},
            {perspective ? "aspect_ratio" : "xmag", shortest(c.a)},
            {perspective ? "yfov" : "ymag", shortest(c.b)},
            {"znear", shortest(c.znear)},
            {"zfar", shortest(c.zfar)}};
}
inline nlohmann::json light_json(const SceneLight& l) {
    static const char* types[] = {"directional", "point", "spot"};
    return {{"index", l.index},
            {"name", replace_invalid_utf8(l.name)},
            {"type", types[static_cast<int>(l.type)]},
            {"color", floats(l.color.data(), 3)},
            {"intensity", shortest(l.intensity)},
            {"range", shortest(l.range)},
            {"inner_cone_angle", shortest(l.inner_cone)},
            {"outer_cone_angle", shortest(l.outer_cone)}};
}

// `viewed`: the file is one of format 1.10 (a CAMERA or LIGHT packet, or a SCENE packet that says 1.10
// or later): its nodes say their camera and light; before, the keys are left out.
inline nlohmann::json node_json(const SceneNode& n, bool viewed = false) {
    nlohmann::json j = {{"index", n.index}, {"parent", none_or(n.parent)}, {"mesh", none_or(n.mesh)}, {"name", replace_invalid_utf8(n.name)}};
    if (n.has_matrix) {
        j["matrix"] = floats(n.matrix.data(), 16);
    } else {
        j["translation"] = floats(n.translation.data(), 3);
        j["rotation"] = floats(n.rotation.data(), 4);
        j["scale"] = floats(n.scale.data(), 3);
    }
    j["skin"] = none_or(n.skin);  // format 1.5 (spec 21): null for a record without a skin or with 0xFFFF
    if (viewed) {  // format 1.10 (spec 26.1): null for a record without the field or with 0xFFFF
        j["camera"] = none_or(n.camera);
        j["light"] = none_or(n.light);
    }
    return j;
}

inline nlohmann::json material_json(const Material& m) {
    static const char* modes[] = {"OPAQUE", "MASK", "BLEND"};
    nlohmann::json textures;
    auto refs = texture_refs(m);
    for (size_t i = 0; i < refs.size(); ++i)
        textures[kTextureSlots[i]] = refs[i]->texture == kNone
                                         ? nlohmann::json(nullptr)
                                         : nlohmann::json{{"texture", refs[i]->texture},
                                                          {"texcoord", refs[i]->texcoord},
                                                          {"scale", shortest(refs[i]->scale)}};
    return {{"index", m.index},
            {"name", replace_invalid_utf8(m.name)},
            {"alpha_mode", modes[static_cast<int>(m.alpha_mode)]},
            {"alpha_cutoff", shortest(m.alpha_cutoff)},
            {"double_sided", m.double_sided},
            {"base_color", floats(m.base_color.data(), 4)},
            {"metallic", shortest(m.metallic)},
            {"roughness", shortest(m.roughness)},
            {"emissive", floats(m.emissive.data(), 3)},
            {"textures", textures},
            {"has_extensions", m.has_extensions}};
}

// Format 1.3 (spec 18.2, 18.3): the texture references of a received patch, in document order.
inline std::vector<PatchTextureReference> patch_references(const MaterialExtensions& e) {
    std::vector<PatchTextureReference> refs;
    if (check_material_patch(e.patch, &refs) != Error::Ok) refs.clear();  // a received patch passed the check
    return refs;
}

inline nlohmann::json material_extensions_json(const MaterialExtensions& e) {
    nlohmann::json refs = nlohmann::json::array();
    for (const PatchTextureReference& r : patch_references(e)) refs.push_back({{"path", r.path}, {"texture", r.texture}});
    return {{"index", e.index}, {"patch", e.patch}, {"references", refs}};
}

inline nlohmann::json texture_json(const ReceivedStream::ReceivedTexture& t) {
    const TextureInfo& i = t.info;
    nlohmann::json missing = nlohmann::json::array();
    if (!t.complete) {
        uint64_t cursor = 0;
        for (const auto& [offset, bytes] : t.pieces) {
            if (offset > cursor) missing.push_back({cursor, offset});
            cursor = uint64_t(offset) + bytes.size();
        }
        if (cursor < i.image_size) missing.push_back({cursor, i.image_size});
    }
    return {{"index", i.index},
            {"image_type", i.image_type == ImageType::Png ? "PNG" : "JPEG"},
            {"sampler", {i.mag_filter, i.min_filter, i.wrap_s, i.wrap_t}},
            {"image_size", i.image_size},
            {"image_crc", i.image_crc},
            {"received_bytes", t.complete ? uint64_t(i.image_size) : t.received_bytes},
            {"missing", missing},
            {"complete", t.complete},
            {"image_digest", t.complete ? nlohmann::json(bytes_digest(t.image)) : nlohmann::json(nullptr)}};
}

// Format 1.4 (spec 20.1, 20.2): an animation as received: its track count and name (of the first
// packet of it accepted), and per received track its description, the keys held (and the ranges of
// those missing), whether it is complete and usable, and, once complete, its keys: the times and the
// values (V per key, in key order, as the packets carry them). Format 1.6 (spec 22.2), `morph`: a
// morph animation, with the ANIMATION it joins (null when it stands alone) and, per track, its
// target count C instead of a path.
inline nlohmann::json animation_json(uint16_t index, const ReceivedStream::ReceivedAnimation& a, bool morph = false) {
    using nlohmann::json;
    static const char* paths[] = {"translation", "rotation", "scale"};
    static const char* interpolations[] = {"LINEAR", "STEP", "CUBICSPLINE"};
    json tracks = json::array();
    for (const auto& [t, track] : a.tracks) {
        json missing = json::array();
        if (!track.complete) {
            uint64_t cursor = 0;
            for (const auto& [first, run] : track.runs) {
                if (first > cursor) missing.push_back({cursor, first});
                cursor = uint64_t(first) + run.times.size();
            }
            if (cursor < track.info.key_count) missing.push_back({cursor, track.info.key_count});
        }
        json entry = {{"index", t},
                      {"node", track.info.node},
                      {"interpolation", interpolations[static_cast<int>(track.info.interpolation)]},
                      {"key_count", track.info.key_count},
                      {"keys_held", track.keys_held},
                      {"missing", missing},
                      {"complete", track.complete},
                      {"usable", track.usable},
                      {"times", track.complete ? floats(track.times.data(), track.times.size()) : json(nullptr)},
                      {"values", track.complete ? floats(track.values.data(), track.values.size()) : json(nullptr)}};
        if (morph) entry["target_count"] = track.info.targets;
        else entry["path"] = paths[static_cast<int>(track.info.path)];
        tracks.push_back(std::move(entry));
    }
    json out = {{"index", index},
                {"name", replace_invalid_utf8(a.name)},
                {"track_count", a.track_count},
                {"complete", a.complete()},
                {"tracks", tracks}};
    if (morph) out["joins"] = none_or(a.joins);
    return out;
}

// Format 1.5 (spec 21.1): a skin as received: its joint count, skeleton and name (of the first packet
// of it accepted), the joints held (and the ranges of those missing), whether it is complete, and every
// joint held, in joint order: its node and its inverse bind matrix (16 floats, column-major).
inline nlohmann::json skin_json(uint16_t index, const ReceivedStream::ReceivedSkin& k) {
    using nlohmann::json;
    json missing = json::array(), joints = json::array();
    uint32_t cursor = 0;
    for (const auto& [j, joint] : k.joints) {
        if (j > cursor) missing.push_back({cursor, j});
        cursor = uint32_t(j) + 1;
        joints.push_back({{"index", j}, {"node", joint.node}, {"matrix", floats(joint.inverse_bind.data(), 16)}});
    }
    if (cursor < k.joint_count) missing.push_back({cursor, k.joint_count});
    return {{"index", index},
            {"name", replace_invalid_utf8(k.name)},
            {"joint_count", k.joint_count},
            {"skeleton", none_or(k.skeleton)},
            {"joints_held", k.joints.size()},
            {"missing", missing},
            {"complete", k.complete()},
            {"joints", joints}};
}

// Format 1.5 (spec 21.3): whether an object has arrived (15.4: its entry and at least one element of
// it), and whether it is weighted (a point held together with that point's record).
inline bool object_arrived(const ReceivedStream& s, uint16_t object) {
    if (object >= s.objects().size()) return false;
    const ReceivedObject& o = s.objects()[object];
    return o.info && (!o.ellipsoids.empty() || !o.points.empty());
}
inline bool object_weighted(const ReceivedStream& s, uint16_t object) {
    const ReceivedObject& o = s.objects()[object];
    for (const auto& [index, r] : o.weights)
        if (o.points.contains(index)) return true;
    return false;
}
// Format 1.6 (spec 22.4): whether a mesh whose record arrived is shown with its targets: its record
// carries targets, at least one of its objects has arrived (15.4: the mesh is shown), and every arrived
// object of it is morphed (22.3: a point held with its record) with the mesh's target count.
inline bool mesh_shown_with_targets(const ReceivedStream& s, const SceneMesh& mesh) {
    return mesh_shows_targets(s, mesh, [&](uint16_t object) { return object_arrived(s, object); });
}

// What a receiver shows of the scene (spec 15.4, 18.4): complete textures; materials whose texture
// references on set 0 and whose patch's texture references are all complete, and whose patch arrived
// when their has_extensions bit says they have one (the others wait: for a texture, named by slot or
// patch path with how much of the texture arrived, or for their patch); references on other sets
// ignored; nodes whose parent chain reaches a root through arrived nodes, with their mesh when its
// record arrived.
inline nlohmann::json shown_json(const ReceivedStream& s, bool viewed = false) {
    using nlohmann::json;
    json textures = json::array(), materials = json::array(), waiting = json::array(), ignored = json::array(),
         nodes = json::array(), waiting_extensions = json::array();
    for (const auto& [index, t] : s.textures())
        if (t.complete) textures.push_back(index);
    for (const auto& [index, m] : s.materials()) {
        bool shown = true;
        auto refs = texture_refs(m);
        auto wait_for = [&](const std::string& slot, uint16_t texture) {
            auto t = s.textures().find(texture);
            if (t != s.textures().end() && t->second.complete) return;
            shown = false;
            waiting.push_back({{"material", index},
                               {"slot", slot},
                               {"texture", texture},
                               {"received_bytes", t == s.textures().end() ? 0 : t->second.received_bytes},
                               {"image_size", t == s.textures().end() ? json(nullptr) : json(t->second.info.image_size)}});
        };
        for (size_t k = 0; k < refs.size(); ++k) {
            const TextureRef& r = *refs[k];
            if (r.texture == kNone) continue;
            if (r.texcoord != 0) {
                ignored.push_back({{"material", index}, {"slot", kTextureSlots[k]}, {"texcoord", r.texcoord}});
                continue;
            }
            wait_for(kTextureSlots[k], r.texture);
        }
        // Format 1.3 (spec 18.4): the patch, when it arrived (also without the bit), its texture
        // references in document order, named by their path (spec 18.3); a material whose bit says
        // it has a patch that has not arrived waits for it.
        if (auto e = s.material_extensions().find(index); e != s.material_extensions().end()) {
            for (const PatchTextureReference& r : patch_references(e->second)) wait_for(r.path, r.texture);
        } else if (m.has_extensions) {
            shown = false;
            waiting_extensions.push_back(index);
        }
        if (shown) materials.push_back(index);
    }
    const auto& all = s.scene_nodes();
    std::vector<uint16_t> shown_nodes;
    for (const auto& [index, n] : all) {
        uint16_t at = index;
        bool reaches = false;
        for (size_t steps = 0; steps <= all.size(); ++steps) {
            auto it = all.find(at);
            if (it == all.end()) break;
            if (it->second.parent == kNone) {
                reaches = true;
                break;
            }
            at = it->second.parent;
        }
        if (!reaches) continue;
        const bool has_mesh = n.mesh != kNone && s.scene_meshes().count(n.mesh);
        nodes.push_back({{"index", index}, {"mesh", has_mesh ? json(n.mesh) : json(nullptr)}});
        shown_nodes.push_back(index);
    }
    // Format 1.4 (spec 20.2): the complete animations, each with the tracks it keeps over the nodes
    // shown above.
    json animations = json::array();
    const auto node_shown = [&](uint16_t node) {
        return std::find(shown_nodes.begin(), shown_nodes.end(), node) != shown_nodes.end();
    };
    // Format 1.6 (spec 22.4): the meshes shown with their targets, in index order; a morph track is kept
    // only on a shown node whose mesh is one of them with the track's target count.
    json morphed = json::array();
    for (const auto& [index, m] : s.scene_meshes())
        if (mesh_shown_with_targets(s, m)) morphed.push_back(index);
    const auto node_targets = [&](uint16_t node) -> unsigned {
        const auto n = all.find(node);
        if (n == all.end() || n->second.mesh == kNone) return 0;
        const auto m = s.scene_meshes().find(n->second.mesh);
        if (m == s.scene_meshes().end() || !mesh_shown_with_targets(s, m->second)) return 0;
        return unsigned(m->second.weights.size());
    };
    for (const ShownAnimation& a : shown_animations(s, node_shown, node_targets)) {
        json morph_tracks = json::array();
        for (const auto& [m, t] : a.morph_tracks) morph_tracks.push_back({m, t});
        animations.push_back(
            {{"index", a.index}, {"tracks", a.tracks}, {"morph_only", a.morph_only}, {"morph_tracks", morph_tracks}});
    }
    // Format 1.5 (spec 21.3): the nodes shown skinned, in node order: among the nodes shown above, those
    // whose record names a complete skin whose joints' nodes (and skeleton, when not 0xFFFF) are shown,
    // whose mesh record arrived and shows at least one arrived object, every arrived object of it
    // weighted, and every joint index of the records held for those objects below the skin's joint_count.
    json skinned = json::array();
    for (uint16_t index : shown_nodes) {
        const SceneNode& n = all.at(index);
        if (n.skin == kNone) continue;
        const auto skin = s.skins().find(n.skin);
        if (skin == s.skins().end() || !skin->second.complete()) continue;
        bool ok = skin->second.skeleton == kNone || node_shown(skin->second.skeleton);
        for (const auto& [j, joint] : skin->second.joints) ok = ok && node_shown(joint.node);
        const auto mesh = n.mesh == kNone ? s.scene_meshes().end() : s.scene_meshes().find(n.mesh);
        bool any = false;
        if (ok && mesh != s.scene_meshes().end()) {
            for (const ScenePrimitive& p : mesh->second.primitives) {
                if (!object_arrived(s, p.object)) continue;
                any = true;
                if (!object_weighted(s, p.object)) ok = false;
                for (const auto& [i, r] : s.objects()[p.object].weights)
                    for (size_t k = 0; k < r->count; ++k)
                        if (r->joints[k] >= skin->second.joint_count) ok = false;
            }
        }
        if (ok && any) skinned.push_back({{"node", index}, {"skin", n.skin}});
    }
    json out = {{"textures", textures}, {"materials", materials}, {"waiting", waiting},
                {"waiting_extensions", waiting_extensions}, {"ignored_references", ignored}, {"nodes", nodes},
                {"animations", animations}, {"skinned", skinned}, {"morphed", morphed}};
    if (viewed) {
        // Format 1.10 (spec 26.4): among the nodes shown above, in node order, those whose camera (light)
        // arrived, with it; and those whose record names one that has not arrived.
        json with_camera = json::array(), with_light = json::array(), waiting_view = json::array();
        for (uint16_t index : shown_nodes) {
            const SceneNode& n = all.at(index);
            if (n.camera != kNone) {
                if (s.cameras().count(n.camera)) with_camera.push_back({{"node", index}, {"camera", n.camera}});
                else waiting_view.push_back({{"node", index}, {"camera", n.camera}});
            }
            if (n.light != kNone) {
                if (s.lights().count(n.light)) with_light.push_back({{"node", index}, {"light", n.light}});
                else waiting_view.push_back({{"node", index}, {"light", n.light}});
            }
        }
        out["node_cameras"] = with_camera;
        out["node_lights"] = with_light;
        out["waiting_cameras_lights"] = waiting_view;
    }
    return out;
}

// Format 1.12 (spec 28): every target that took a fragment, in (kind, index) order: its description,
// the bytes held, and the text once complete.
inline nlohmann::json extras_json(const ReceivedStream& s) {
    nlohmann::json texts = nlohmann::json::array();
    for (const auto& [key, e] : s.extras())
        texts.push_back({{"kind", extras_target_name(key.first)},
                         {"index", key.second},
                         {"text_size", e.text_size},
                         {"text_crc", e.text_crc},
                         {"received_bytes", e.received_bytes},
                         {"complete", e.complete},
                         {"text", e.complete ? nlohmann::json(e.text) : nlohmann::json(nullptr)}});
    return texts;
}

// `with_extras`: the file holds an EXTRAS packet (format 1.12): the extras keys are there;
// `with_required`: a REQUIRED_EXTENSION packet (format 1.13): the required extensions' keys are there.
inline nlohmann::json scene_json(const ReceivedStream& s, bool viewed = false, bool with_extras = false,
                                 bool with_required = false) {
    using nlohmann::json;
    json nodes = json::array(), meshes = json::array(), materials = json::array(), textures = json::array(),
         extensions = json::array();
    for (const auto& [index, n] : s.scene_nodes()) nodes.push_back(node_json(n, viewed));
    for (const auto& [index, m] : s.scene_meshes()) {
        json prims = json::array();
        for (const auto& p : m.primitives) prims.push_back({{"object", p.object}, {"material", none_or(p.material)}});
        // Format 1.6 (spec 22): the default weights, one per target ([] for a mesh without targets).
        meshes.push_back({{"index", m.index},
                          {"name", replace_invalid_utf8(m.name)},
                          {"primitives", prims},
                          {"weights", floats(m.weights.data(), m.weights.size())}});
    }
    for (const auto& [index, m] : s.materials()) materials.push_back(material_json(m));
    for (const auto& [index, e] : s.material_extensions()) extensions.push_back(material_extensions_json(e));
    for (const auto& [index, t] : s.textures()) textures.push_back(texture_json(t));
    json animations = json::array();
    for (const auto& [index, a] : s.animations()) animations.push_back(animation_json(index, a));
    json skins = json::array();
    for (const auto& [index, k] : s.skins()) skins.push_back(skin_json(index, k));
    json morph_animations = json::array();
    for (const auto& [index, a] : s.morph_animations()) morph_animations.push_back(animation_json(index, a, true));
    const bool scene = s.has_scene() || !s.scene_nodes().empty() || !s.scene_meshes().empty();
    json out = {{"node_count", scene ? json(s.scene_node_count()) : json(nullptr)},
            {"mesh_count", scene ? json(s.scene_mesh_count()) : json(nullptr)},
            {"nodes", nodes},
            {"meshes", meshes},
            // That of the materials and (format 1.3) patches held: all agree (spec 15.2, 18.2).
            {"material_count", !s.materials().empty() ? json(s.materials().begin()->second.material_count)
                               : !s.material_extensions().empty()
                                   ? json(s.material_extensions().begin()->second.material_count)
                                   : json(nullptr)},
            {"materials", materials},
            {"material_extensions", extensions},
            {"texture_count",
             s.textures().empty() ? json(nullptr) : json(s.textures().begin()->second.info.texture_count)},
            {"textures", textures},
            // Format 1.4: that of the ANIMATION packets accepted (all agree, spec 20.1), null when none was.
            {"animation_count", s.animation_count() ? json(*s.animation_count()) : json(nullptr)},
            {"animations", animations},
            // Format 1.5: that of the SKIN packets accepted (all agree, spec 21.1), null when none was.
            {"skin_count", s.skin_count() ? json(*s.skin_count()) : json(nullptr)},
            {"skins", skins},
            // Format 1.6: that of the MORPH_ANIMATION packets accepted (all agree, spec 22.2), null when none was.
            {"morph_animation_count", s.morph_animation_count() ? json(*s.morph_animation_count()) : json(nullptr)},
            {"morph_animations", morph_animations},
            {"shown", shown_json(s, viewed)}};
    if (viewed) {
        // Format 1.10: the table sizes of the CAMERA and LIGHT packets accepted (null when none was), and
        // every camera and light held, in index order.
        json cameras = json::array(), lights = json::array();
        for (const auto& [index, c] : s.cameras()) cameras.push_back(camera_json(c));
        for (const auto& [index, l] : s.lights()) lights.push_back(light_json(l));
        out["camera_count"] = s.camera_count() ? json(*s.camera_count()) : json(nullptr);
        out["cameras"] = cameras;
        out["light_count"] = s.light_count() ? json(*s.light_count()) : json(nullptr);
        out["lights"] = lights;
    }
    if (with_extras) {
        // Format 1.12: the text_count of the EXTRAS packets accepted (null when none was), every text held.
        out["extras_count"] = s.extras_count() ? json(*s.extras_count()) : json(nullptr);
        out["extras"] = extras_json(s);
    }
    if (with_required) {
        // Format 1.13: the name_count of the REQUIRED_EXTENSION packets accepted (null when none was),
        // every name held, in index order.
        json names = json::array();
        for (const auto& [index, name] : s.required_extensions()) names.push_back({{"index", index}, {"name", name}});
        out["required_extension_count"] = s.required_extension_count() ? json(*s.required_extension_count()) : json(nullptr);
        out["required_extensions"] = names;
    }
    return out;
}

// The key every signed vector is checked with (spec/vectors/README.md): the Ed25519 key pair whose
// 32-byte seed is 00 01 02 .. 1F.
inline auth::KeyPair vectors_key() {
    auth::Seed seed;
    for (size_t i = 0; i < seed.size(); ++i) seed[i] = static_cast<uint8_t>(i);
    return auth::key_pair_from_seed(seed);
}

inline std::string hex(std::span<const uint8_t> bytes) { return auth::to_hex(bytes); }

// Format 1.2, present when the file holds any MANIFEST packet: the recording authenticated with
// vectors_key() as spec 16.3 says for recordings (every MANIFEST first, then the other packets in
// file order), and what a decoder makes of the packets that pass.
inline nlohmann::json signed_json(const ContainerContents& contents, const std::vector<uint8_t>& bytes) {
    using nlohmann::json;
    const auth::PublicKey key = vectors_key().public_key;
    const auth::RecordingAuthentication a = auth::authenticate_recording(contents.packets, bytes, key);
    auto bytes_of = [&](const ContainerPacket& p) {
        return std::span<const uint8_t>(bytes).subspan(p.offset, p.view.size);
    };
    json manifests = json::array(), packets = json::array();
    ReceivedStream passed;
    for (size_t i = 0; i < contents.packets.size(); ++i) {
        const ContainerPacket& p = contents.packets[i];
        const PacketDigest digest = packet_digest(bytes_of(p));
        std::string verdict;
        switch (a.verdicts[i]) {
        case auth::Authenticator::Verdict::Pass: verdict = "pass"; break;
        case auth::Authenticator::Verdict::Manifest: verdict = "manifest"; break;  // or "skipped", below
        case auth::Authenticator::Verdict::Repeat: verdict = "repeat"; break;
        default: verdict = reason_name(a.errors[i]); break;
        }
        packets.push_back({{"offset", p.offset}, {"digest", hex(digest)}, {"verdict", verdict}});
        if (a.verdicts[i] == auth::Authenticator::Verdict::Pass) passed.add_parsed(p.view, p.offset);
        if (p.view.header.type != static_cast<uint8_t>(PacketType::Manifest)) continue;
        ManifestPart part;
        json m = {{"offset", p.offset}};
        if (decode_manifest_payload(p.view.payload, part) != Error::Ok) {
            m["malformed"] = true;
        } else if (!is_known_manifest_scheme(part.scheme)) {
            m["malformed"] = false;
            m["scheme"] = part.scheme;
            packets.back()["verdict"] = "skipped";  // a later scheme's MANIFEST: skipped, verified or not
        } else {
            json digests = json::array();
            for (const PacketDigest& d : part.digests) digests.push_back(hex(d));
            const std::vector<uint8_t> message = manifest_signed_message(bytes_of(p));
            m["malformed"] = false;
            m["scheme"] = part.scheme;
            m["part"] = part.part;
            m["part_count"] = part.part_count;
            m["packet_count"] = part.packet_count;
            m["first"] = part.first;
            m["key_id"] = hex(part.key_id);
            if (part.scheme == kManifestSchemeBound) m["content_id"] = part.content_id;
            m["digests"] = digests;
            m["signed_message_sha256"] = hex(sha256(message));
            m["signature"] = hex(part.signature);
            m["verified"] = auth::verify_manifest(bytes_of(p), part, key);
        }
        manifests.push_back(m);
    }
    const auto& c = a.counters;
    return {{"key", hex(key)},
            {"key_id", hex(key_id_of(std::span<const uint8_t, 32>(key)))},
            {"manifests", manifests},
            {"packets", packets},
            {"counters",
             {{"passed", c.passed},
              {"manifests_verified", c.manifests_verified},
              {"manifests_repeated", c.manifests_repeated},
              {"manifests_failed", c.manifests_failed},
              {"malformed", c.malformed},
              {"unknown_scheme", c.unknown_scheme},
              {"not_authenticated", c.not_authenticated}}},
            {"authenticated",
             {{"counters", counters_json(passed.counters())},
              {"stream_info", passed.info() ? stream_info_json(*passed.info(), passed.objects().size()) : json(nullptr)},
              {"objects", objects_json(passed)}}}};
}

// Decodes a container held in memory the way spec/format.md describes and returns the result.
inline nlohmann::json expected_decode(const std::vector<uint8_t>& bytes) {
    using nlohmann::json;
    json out;
    out["file_size"] = bytes.size();
    ContainerContents contents = read_container(bytes);
    out["container_error"] = contents.header_error == Error::Ok ? json(nullptr) : json(reason_name(contents.header_error));

    ReceivedStream stream;
    // A format 1.0 decoder's view: the types of 1.1 and later are unknown to it (spec section 9).
    ReceivedStream as_1_0;
    bool any_scene_packet = false;
    bool viewed = false;  // format 1.10: a CAMERA or LIGHT packet, or a SCENE packet saying 1.10 or later
    bool with_extras = false;  // format 1.12: an EXTRAS packet
    bool with_required = false;  // format 1.13: a REQUIRED_EXTENSION packet
    json packets = json::array();
    for (const ContainerPacket& p : contents.packets) {
        const ReceiveCounters before = stream.counters();
        Error e = stream.add_parsed(p.view, p.offset);
        const ReceiveCounters& after = stream.counters();
        std::string result = reason_name(e);
        if (e == Error::Ok) {
            if (after.accepted > before.accepted) result = "accepted";
            else if (after.duplicates > before.duplicates) result = "duplicate";
            else if (after.skipped > before.skipped) result = "skipped";
            else result = "held";
        }
        const PacketHeader& h = p.view.header;
        PacketView old = p.view;
        if (is_scene_type(h.type)) any_scene_packet = true;
        if (h.type == uint8_t(PacketType::Camera) || h.type == uint8_t(PacketType::Light) ||
            (h.type == uint8_t(PacketType::Scene) && h.version_minor >= kCameraLightMinor))
            viewed = true;
        if (h.type == uint8_t(PacketType::Extras)) with_extras = true;
        if (h.type == uint8_t(PacketType::RequiredExtension)) with_required = true;
        if (h.type > uint8_t(PacketType::Points)) old.header.type = 0xFF;  // a type a 1.0 decoder does not know
        as_1_0.add_parsed(old, p.offset);
        char version[8];
        std::snprintf(version, sizeof version, "%u.%u", h.version_major, h.version_minor);
        packets.push_back({{"offset", p.offset},
                           {"size", p.view.size},
                           {"version", version},
                           {"type", packet_type_name(h.type)},
                           {"flags", h.flags},
                           {"stream_id", h.stream_id},
                           {"sequence", h.sequence},
                           {"object_id", h.object_id},
                           {"payload_length", h.payload_length},
                           {"result", result}});
    }
    out["packets"] = packets;

    json damaged = json::array();
    for (const DamagedRegion& d : contents.damaged)
        damaged.push_back({{"offset", d.offset}, {"length", d.length}, {"reason", reason_name(d.first_error)}});
    out["damaged"] = damaged;

    json rejections = json::array();
    for (const Rejection& r : stream.rejections())
        rejections.push_back({{"offset", r.where}, {"reason", reason_name(r.error)}, {"detail", r.detail}});
    out["rejections"] = rejections;

    out["counters"] = counters_json(stream.counters());
    out["stream_id"] = stream.has_stream_id() ? json(stream.stream_id()) : json(nullptr);
    out["newest_minor"] = stream.newest_minor();
    out["stream_info"] = stream.info() ? stream_info_json(*stream.info(), stream.objects().size()) : json(nullptr);
    out["objects"] = objects_json(stream);
    // Format 1.1: present when the file holds any SCENE, MATERIAL, TEXTURE_FRAGMENT, (format 1.3)
    // MATERIAL_EXTENSIONS, (format 1.4) ANIMATION, (format 1.5) SKIN or (format 1.6) MORPH_ANIMATION packet.
    out["scene"] = any_scene_packet ? scene_json(stream, viewed, with_extras, with_required) : json(nullptr);
    if (any_scene_packet) {
        json info_1_0 = as_1_0.info() ? stream_info_json(*as_1_0.info(), as_1_0.objects().size()) : json(nullptr);
        // The same objects but for their format 1.5 influence records, format 1.6 displacement records
        // and format 1.14 further texture-coordinate sets, which a 1.0 decoder skips.
        json geometry = out["objects"];
        for (json& o : geometry) {
            o.erase("weights");
            o.erase("morph");
            o.erase("texcoord_sets");
        }
        out["as_1_0"] = {{"counters", counters_json(as_1_0.counters())},
                         {"newest_minor", as_1_0.newest_minor()},
                         {"same_objects", info_1_0 == out["stream_info"] && objects_json(as_1_0) == geometry}};
    }
    // Format 1.2: present when the file holds any MANIFEST packet.
    const bool any_manifest = std::any_of(contents.packets.begin(), contents.packets.end(), [](const ContainerPacket& p) {
        return p.view.header.type == static_cast<uint8_t>(PacketType::Manifest);
    });
    out["signed"] = any_manifest ? signed_json(contents, bytes) : json(nullptr);
    return out;
}

// Keys that are for people only and not compared: rejection details and vector descriptions.
inline bool is_informative_key(const std::string& key) { return key == "detail" || key == "description"; }

// Compares an actual decode with the expected one: integers, strings, booleans and nulls exactly,
// floating-point values within 1e-6 relative error (surface normals, spec 24.3, within 1e-4). Appends one line
// per difference to `diffs`.
inline void compare_json(const nlohmann::json& expected, const nlohmann::json& actual, const std::string& path,
                         std::vector<std::string>& diffs) {
    if (diffs.size() > 20) return;
    if (expected.is_number() && actual.is_number()) {
        if (expected.is_number_float() || actual.is_number_float()) {
            double a = expected.get<double>(), b = actual.get<double>();
            double tol = 1e-6 * std::max({1.0, std::fabs(a), std::fabs(b)});
            // Surface normals (format 1.8, spec 24.3, 14): summed in any order, compared within 1e-4.
            if (path.find(".normals.surface[") != std::string::npos) tol = 1e-4;
            if (!(std::fabs(a - b) <= tol)) diffs.push_back(path + ": expected " + expected.dump() + ", got " + actual.dump());
        } else if (expected != actual) {
            diffs.push_back(path + ": expected " + expected.dump() + ", got " + actual.dump());
        }
        return;
    }
    if (expected.type() != actual.type()) {
        diffs.push_back(path + ": expected " + expected.dump().substr(0, 80) + ", got " + actual.dump().substr(0, 80));
        return;
    }
    if (expected.is_object()) {
        for (auto it = expected.begin(); it != expected.end(); ++it) {
            if (is_informative_key(it.key())) continue;
            if (!actual.contains(it.key())) diffs.push_back(path + "." + it.key() + ": missing");
            else compare_json(it.value(), actual[it.key()], path + "." + it.key(), diffs);
        }
        for (auto it = actual.begin(); it != actual.end(); ++it)
            if (!is_informative_key(it.key()) && !expected.contains(it.key()))
                diffs.push_back(path + "." + it.key() + ": not expected");
        return;
    }
    if (expected.is_array()) {
        if (expected.size() != actual.size()) {
            diffs.push_back(path + ": expected " + std::to_string(expected.size()) + " entries, got " +
                            std::to_string(actual.size()));
            return;
        }
        for (size_t i = 0; i < expected.size(); ++i)
            compare_json(expected[i], actual[i], path + "[" + std::to_string(i) + "]", diffs);
        return;
    }
    if (expected != actual) diffs.push_back(path + ": expected " + expected.dump() + ", got " + actual.dump());
}

// JSON as people read it: objects and arrays on several lines, short ones (a point, a rotation) inline.
inline void write_readable(const nlohmann::json& j, std::string& out, int indent = 0) {
    std::string compact = j.dump();
    if (!j.is_structured() || j.empty() || compact.size() + static_cast<size_t>(indent) <= 250) {
        out += compact;
        return;
    }
    const std::string pad(static_cast<size_t>(indent) + 2, ' ');
    out += j.is_object() ? "{\n" : "[\n";
    bool first = true;
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (!first) out += ",\n";
        first = false;
        out += pad;
        if (j.is_object()) out += nlohmann::json(it.key()).dump() + ": ";
        write_readable(it.value(), out, indent + 2);
    }
    out += "\n" + std::string(static_cast<size_t>(indent), ' ') + (j.is_object() ? "}" : "]");
}

}  // namespace ellicast::conformance

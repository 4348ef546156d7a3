// Payloads of SCENE, MATERIAL and TEXTURE_FRAGMENT packets (format 1.1), and cutting a scene
// description into packets.
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>
#include <cmath>

namespace ellicast {

using namespace detail;

namespace {

constexpr uint8_t kRecordNode = 1;
constexpr uint8_t kRecordMesh = 2;
constexpr size_t kSceneHeaderSize = 8;
constexpr size_t kMaterialFixedSize = 88;
constexpr size_t kMaxName = 255;

bool all_finite(std::span<const float> values) {
    return std::all_of(values.begin(), values.end(), [](float f) { return std::isfinite(f); });
}

// The longest prefix of `name` of at most `limit` bytes that does not cut a UTF-8 sequence.
std::string utf8_prefix(const std::string& name, size_t limit) {
    if (name.size() <= limit) return name;
    size_t n = limit;
    while (n > 0 && (static_cast<uint8_t>(name[n]) & 0xC0) == 0x80) --n;
    return name.substr(0, n);
}

void put_name(std::vector<uint8_t>& out, const std::string& name) {
    std::string n = utf8_prefix(name, kMaxName);
    put_u8(out, static_cast<uint8_t>(n.size()));
    out.insert(out.end(), n.begin(), n.end());
}

// Reads bounded fields from a payload; any read past the end sets `failed`.
class Reader {
public:
    explicit Reader(std::span<const uint8_t> in) : in_(in) {}
    bool failed = false;
    size_t left() const { return in_.size() - pos_; }
    size_t pos() const { return pos_; }
    void skip(size_t n) {
        if (n > left()) failed = true;
        else pos_ += n;
    }
    uint8_t u8() { return need(1) ? in_[pos_++] : 0; }
    uint16_t u16() {
        if (!need(2)) return 0;
        uint16_t v = get_u16(in_.data() + pos_);
        pos_ += 2;
        return v;
    }
    uint32_t u32() {
        if (!need(4)) return 0;
        uint32_t v = get_u32(in_.data() + pos_);
        pos_ += 4;
        return v;
    }
    float f32() {
        if (!need(4)) return 0;
        float v = get_f32(in_.data() + pos_);
        pos_ += 4;
        return v;
    }
    std::string name() {
        size_t n = u8();
        if (!need(n)) return {};
        std::string s(reinterpret_cast<const char*>(in_.data() + pos_), n);
        pos_ += n;
        return s;
    }

private:
    bool need(size_t n) {
        if (failed || n > left()) {
            failed = true;
            return false;
        }
        return true;
    }
    std::span<const uint8_t> in_;
    size_t pos_ = 0;
};

std::vector<uint8_t> node_record(const SceneNode& n) {
    std::vector<uint8_t> body;
    put_u16(body, n.index);
    put_u16(body, n.parent);
    put_u16(body, n.mesh);
    put_u8(body, n.has_matrix ? 1 : 0);
    put_name(body, n.name);
    if (n.has_matrix) {
        for (float f : n.matrix) put_f32(body, f);
    } else {
        for (float f : n.translation) put_f32(body, f);
        for (float f : n.rotation) put_f32(body, f);
        for (float f : n.scale) put_f32(body, f);
    }
    // Format 1.5 (spec 21): the skin only when the node has one, or (format 1.10, spec 26.1) when the
    // camera and light follow it, which they do only when the node has one of them.
    const bool camera_light = n.camera != kNone || n.light != kNone;
    if (n.skin != kNone || camera_light) put_u16(body, n.skin);
    if (camera_light) {
        put_u16(body, n.camera);
        put_u16(body, n.light);
    }
    return body;
}

std::vector<uint8_t> mesh_record(const SceneMesh& m) {
    std::vector<uint8_t> body;
    put_u16(body, m.index);
    put_name(body, m.name);
    put_u16(body, static_cast<uint16_t>(m.primitives.size()));
    for (const auto& p : m.primitives) {
        put_u16(body, p.object);
        put_u16(body, p.material);
    }
    if (!m.weights.empty()) {  // format 1.6 (spec 22): only when the mesh has targets
        put_u8(body, static_cast<uint8_t>(m.weights.size()));
        for (float w : m.weights) put_f32(body, w);
    }
    return body;
}

void put_record(std::vector<uint8_t>& out, uint8_t kind, const std::vector<uint8_t>& body) {
    put_u8(out, kind);
    put_u16(out, static_cast<uint16_t>(body.size()));
    out.insert(out.end(), body.begin(), body.end());
}

}  // namespace

// ------------------------------------------------------------------------------------------
// SCENE

std::vector<uint8_t> encode_scene_payload(const SceneBatch& batch) {
    std::vector<uint8_t> out;
    put_u16(out, batch.node_count);
    put_u16(out, batch.mesh_count);
    put_u16(out, static_cast<uint16_t>(batch.nodes.size() + batch.meshes.size()));
    put_u16(out, 0);
    for (const auto& n : batch.nodes) put_record(out, kRecordNode, node_record(n));
    for (const auto& m : batch.meshes) put_record(out, kRecordMesh, mesh_record(m));
    return out;
}

Error decode_scene_payload(std::span<const uint8_t> payload, SceneBatch& out, uint8_t version_minor) {
    Reader r(payload);
    SceneBatch batch;
    batch.node_count = r.u16();
    batch.mesh_count = r.u16();
    const size_t records = r.u16();
    r.u16();
    if (r.failed) return Error::MalformedPayload;
    for (size_t i = 0; i < records; ++i) {
        const uint8_t kind = r.u8();
        const size_t length = r.u16();
        if (r.failed || length > r.left()) return Error::MalformedPayload;
        Reader body(payload.subspan(r.pos(), length));
        r.skip(length);
        if (kind == kRecordNode) {
            SceneNode n;
            n.index = body.u16();
            n.parent = body.u16();
            n.mesh = body.u16();
            const uint8_t flags = body.u8();
            n.name = body.name();
            n.has_matrix = (flags & 1) != 0;
            if (n.has_matrix) {
                for (float& f : n.matrix) f = body.f32();
            } else {
                for (float& f : n.translation) f = body.f32();
                for (float& f : n.rotation) f = body.f32();
                for (float& f : n.scale) f = body.f32();
            }
            // Format 1.5 (spec 21): a skin when the packet says 1.5 or later and at least two bytes
            // follow the transform (in an older packet they are fields of a later version it knew not of).
            if (version_minor >= kSkinMinor && !body.failed && body.left() >= 2) n.skin = body.u16();
            // Format 1.10 (spec 26.1): a camera, then a light, each when two more bytes follow.
            if (version_minor >= kCameraLightMinor && !body.failed && body.left() >= 2) n.camera = body.u16();
            if (version_minor >= kCameraLightMinor && !body.failed && body.left() >= 2) n.light = body.u16();
            if (body.failed || n.index >= batch.node_count || n.parent == n.index ||
                (n.parent != kNone && n.parent >= batch.node_count) || (n.mesh != kNone && n.mesh >= batch.mesh_count) ||
                !all_finite(n.matrix) || !all_finite(n.translation) || !all_finite(n.rotation) || !all_finite(n.scale))
                return Error::MalformedPayload;
            batch.nodes.push_back(std::move(n));
        } else if (kind == kRecordMesh) {
            SceneMesh m;
            m.index = body.u16();
            m.name = body.name();
            const size_t count = body.u16();
            if (body.failed || count * 4 > body.left() || m.index >= batch.mesh_count) return Error::MalformedPayload;
            for (size_t k = 0; k < count; ++k) {
                ScenePrimitive p;
                p.object = body.u16();
                p.material = body.u16();
                m.primitives.push_back(p);
            }
            // Format 1.6 (spec 22): targets when the packet says 1.6 or later and a byte follows the
            // primitives; then every weight must follow, finite.
            if (version_minor >= kMorphMinor && !body.failed && body.left() >= 1) {
                const size_t targets = body.u8();
                if (targets * 4 > body.left()) return Error::MalformedPayload;
                m.weights.resize(targets);
                for (float& w : m.weights) w = body.f32();
                if (!all_finite(m.weights)) return Error::MalformedPayload;
            }
            if (body.failed) return Error::MalformedPayload;
            batch.meshes.push_back(std::move(m));
        }
        // Record kinds of a newer minor version are skipped: their length says how far.
    }
    if (r.left() != 0) return Error::MalformedPayload;
    out = std::move(batch);
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// MATERIAL

std::vector<uint8_t> encode_material_payload(const Material& m) {
    std::vector<uint8_t> out;
    std::string name = utf8_prefix(m.name, kMaxName);
    put_u16(out, m.index);
    put_u16(out, m.material_count);
    put_u8(out, static_cast<uint8_t>(m.alpha_mode));
    put_u8(out, m.double_sided ? 1 : 0);
    put_u8(out, static_cast<uint8_t>(name.size()));
    put_u8(out, m.has_extensions ? 1 : 0);  // flags (spec 18.1)
    for (float f : m.base_color) put_f32(out, f);
    put_f32(out, m.metallic);
    put_f32(out, m.roughness);
    for (float f : m.emissive) put_f32(out, f);
    put_f32(out, m.alpha_cutoff);
    for (const TextureRef* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                &m.occlusion_texture, &m.emissive_texture}) {
        put_u16(out, t->texture);
        put_u8(out, t->texcoord);
        put_u8(out, 0);
        put_f32(out, t->scale);
    }
    out.insert(out.end(), name.begin(), name.end());
    return out;
}

Error decode_material_payload(std::span<const uint8_t> payload, Material& out) {
    if (payload.size() < kMaterialFixedSize) return Error::MalformedPayload;
    Reader r(payload);
    Material m;
    m.index = r.u16();
    m.material_count = r.u16();
    const uint8_t alpha = r.u8();
    m.double_sided = r.u8() != 0;
    const size_t name_length = r.u8();
    m.has_extensions = (r.u8() & 1) != 0;  // flags bit 0 (spec 18.1); bits 1..7 reserved
    for (float& f : m.base_color) f = r.f32();
    m.metallic = r.f32();
    m.roughness = r.f32();
    for (float& f : m.emissive) f = r.f32();
    m.alpha_cutoff = r.f32();
    for (TextureRef* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                          &m.occlusion_texture, &m.emissive_texture}) {
        t->texture = r.u16();
        t->texcoord = r.u8();
        r.u8();
        t->scale = r.f32();
    }
    if (r.failed || payload.size() != kMaterialFixedSize + name_length) return Error::MalformedPayload;
    m.name.assign(reinterpret_cast<const char*>(payload.data() + kMaterialFixedSize), name_length);
    float scalars[] = {m.metallic, m.roughness, m.alpha_cutoff, m.base_color_texture.scale,
                       m.metallic_roughness_texture.scale, m.normal_texture.scale, m.occlusion_texture.scale,
                       m.emissive_texture.scale};
    if (m.index >= m.material_count || alpha > 2 || !all_finite(m.base_color) || !all_finite(m.emissive) ||
        !all_finite(scalars))
        return Error::MalformedPayload;
    m.alpha_mode = static_cast<AlphaMode>(alpha);
    out = std::move(m);
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// TEXTURE_FRAGMENT

std::vector<uint8_t> encode_texture_fragment_payload(const TextureFragment& f) {
    std::vector<uint8_t> out;
    out.reserve(kTextureFragmentHeaderSize + f.data.size());
    const TextureInfo& t = f.info;
    put_u16(out, t.index);
    put_u16(out, t.texture_count);
    put_u8(out, static_cast<uint8_t>(t.image_type));
    put_u8(out, 0);
    put_u16(out, t.mag_filter);
    put_u16(out, t.min_filter);
    put_u16(out, t.wrap_s);
    put_u16(out, t.wrap_t);
    put_u16(out, 0);
    put_u32(out, t.image_size);
    put_u32(out, t.image_crc);
    put_u32(out, f.offset);
    out.insert(out.end(), f.data.begin(), f.data.end());
    return out;
}

Error decode_texture_fragment_payload(std::span<const uint8_t> payload, TextureFragment& out) {
    if (payload.size() <= kTextureFragmentHeaderSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    TextureFragment f;
    TextureInfo& t = f.info;
    t.index = get_u16(p);
    t.texture_count = get_u16(p + 2);
    const uint8_t type = p[4];
    t.mag_filter = get_u16(p + 6);
    t.min_filter = get_u16(p + 8);
    t.wrap_s = get_u16(p + 10);
    t.wrap_t = get_u16(p + 12);
    t.image_size = get_u32(p + 16);
    t.image_crc = get_u32(p + 20);
    f.offset = get_u32(p + 24);
    const size_t length = payload.size() - kTextureFragmentHeaderSize;
    if (t.index >= t.texture_count || (type != 1 && type != 2) || uint64_t(f.offset) + length > t.image_size)
        return Error::MalformedPayload;
    t.image_type = static_cast<ImageType>(type);
    f.data.assign(payload.begin() + kTextureFragmentHeaderSize, payload.end());
    out = std::move(f);
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// Packetizing

namespace {

size_t weights_tracks(const SceneAnimation& animation) {
    return size_t(std::count_if(animation.tracks.begin(), animation.tracks.end(),
                                [](const auto& t) { return t.path == AnimationPath::Weights; }));
}

// Where each animation goes (spec 22.5): its tracks other than weights make an animation of the
// ANIMATION table, its weights tracks a morph animation of the MORPH_ANIMATION table.
struct AnimationTables {
    std::vector<uint16_t> animation_index, morph_index;  // kNone: not in that table
    size_t animation_count = 0, morph_count = 0;
};
AnimationTables animation_tables(const std::vector<SceneAnimation>& animations) {
    AnimationTables t;
    t.animation_index.assign(animations.size(), kNone);
    t.morph_index.assign(animations.size(), kNone);
    for (size_t i = 0; i < animations.size(); ++i) {
        const size_t weights = weights_tracks(animations[i]);
        if (weights < animations[i].tracks.size()) t.animation_index[i] = static_cast<uint16_t>(t.animation_count++);
        if (weights > 0) t.morph_index[i] = static_cast<uint16_t>(t.morph_count++);
    }
    return t;
}

// The size of the table a target of `kind` indexes (1 for the asset and the scene).
size_t extras_table_size(const SceneDescription& scene, ExtrasTarget kind) {
    switch (kind) {
    case ExtrasTarget::Asset:
    case ExtrasTarget::Scene: return 1;
    case ExtrasTarget::Node: return scene.nodes.size();
    case ExtrasTarget::Mesh: return scene.meshes.size();
    case ExtrasTarget::Material: return scene.materials.size();
    case ExtrasTarget::Texture: return scene.textures.size();
    case ExtrasTarget::Animation: return scene.animations.size();  // mapped to its table when sent
    case ExtrasTarget::Skin: return scene.skins.size();
    case ExtrasTarget::Camera: return scene.cameras.size();
    case ExtrasTarget::Light: return scene.lights.size();
    case ExtrasTarget::MorphAnimation: return 0;  // a description names every animation Animation
    }
    return 0;
}

}  // namespace

Error packetize_scene(const SceneDescription& scene, size_t packet_size, uint32_t stream_id, uint32_t first_sequence,
                      ScenePackets& out) {
    if (packet_size < kMinPacketSize || packet_size > kMaxPacketSize) return Error::MalformedPayload;
    if (scene.nodes.size() > 0xFFFE || scene.meshes.size() > 0xFFFE || scene.materials.size() > 0xFFFE ||
        scene.textures.size() > 0xFFFE)
        return Error::MalformedPayload;
    const size_t capacity = packet_size - kPacketOverhead;
    const auto node_count = static_cast<uint16_t>(scene.nodes.size());
    const auto mesh_count = static_cast<uint16_t>(scene.meshes.size());
    for (size_t i = 0; i < scene.nodes.size(); ++i) {
        const SceneNode& n = scene.nodes[i];
        if (n.index != i || n.parent == n.index || (n.parent != kNone && n.parent >= node_count) ||
            (n.mesh != kNone && n.mesh >= mesh_count) || (n.skin != kNone && (n.skin >= scene.skins.size() || n.mesh == kNone)) ||
            (n.camera != kNone && n.camera >= scene.cameras.size()) || (n.light != kNone && n.light >= scene.lights.size()))
            return Error::MalformedPayload;
    }
    if (scene.cameras.size() > 0xFFFE || scene.lights.size() > 0xFFFE) return Error::MalformedPayload;
    for (const SceneCamera& c : scene.cameras)
        if (!valid_camera(c)) return Error::MalformedPayload;
    for (const SceneLight& l : scene.lights)
        if (!valid_light(l)) return Error::MalformedPayload;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        if (scene.meshes[i].index != i || scene.meshes[i].weights.size() > 255 || !all_finite(scene.meshes[i].weights))
            return Error::MalformedPayload;
        for (const auto& p : scene.meshes[i].primitives)
            if (p.material != kNone && p.material >= scene.materials.size()) return Error::MalformedPayload;
    }

    ScenePackets packets;
    uint32_t sequence = first_sequence;
    auto emit = [&](PacketType type, const std::vector<uint8_t>& payload, uint8_t minor = kFormatMinor) {
        return write_packet(skippable_header(type, minor, stream_id, sequence++, kStreamObjectId), payload);
    };

    // SCENE: whole records, as many as fit each packet. A name is shortened when its record would
    // not fit a packet at all (only possible with the smallest packet sizes).
    SceneBatch batch{node_count, mesh_count, {}, {}};
    size_t used = kSceneHeaderSize;
    auto flush = [&]() {
        if (batch.nodes.empty() && batch.meshes.empty()) return;
        const bool skinned = std::any_of(batch.nodes.begin(), batch.nodes.end(), [](const SceneNode& n) { return n.skin != kNone; });
        const bool morphed = std::any_of(batch.meshes.begin(), batch.meshes.end(), [](const SceneMesh& m) { return !m.weights.empty(); });
        const bool viewed = std::any_of(batch.nodes.begin(), batch.nodes.end(),
                                        [](const SceneNode& n) { return n.camera != kNone || n.light != kNone; });
        packets.scene.push_back(emit(PacketType::Scene, encode_scene_payload(batch),
                                     viewed    ? kCameraLightMinor
                                     : morphed ? kMorphMinor
                                     : skinned ? kSkinMinor
                                               : kFormatMinor));
        batch.nodes.clear();
        batch.meshes.clear();
        used = kSceneHeaderSize;
    };
    auto fit_name = [&](std::string& name, size_t size_without_name) -> bool {
        if (kSceneHeaderSize + size_without_name > capacity) return false;
        name = utf8_prefix(name, std::min(kMaxName, capacity - kSceneHeaderSize - size_without_name));
        return true;
    };
    for (SceneNode n : scene.nodes) {
        const bool camera_light = n.camera != kNone || n.light != kNone;
        const size_t fixed = 3 + 7 + 1 + (n.has_matrix ? 64 : 40) + (n.skin != kNone || camera_light ? 2 : 0) + (camera_light ? 4 : 0);
        if (!fit_name(n.name, fixed)) return Error::MalformedPayload;
        const size_t size = fixed + n.name.size();
        if (used + size > capacity) flush();
        batch.nodes.push_back(std::move(n));
        used += size;
    }
    for (SceneMesh m : scene.meshes) {
        const size_t fixed = 3 + 2 + 1 + 2 + 4 * m.primitives.size() + (m.weights.empty() ? 0 : 1 + 4 * m.weights.size());
        if (!fit_name(m.name, fixed)) return Error::MalformedPayload;
        const size_t size = fixed + m.name.size();
        if (used + size > capacity) flush();
        batch.meshes.push_back(std::move(m));
        used += size;
    }
    flush();

    for (size_t i = 0; i < scene.materials.size(); ++i) {
        Material m = scene.materials[i];
        m.index = static_cast<uint16_t>(i);
        m.material_count = static_cast<uint16_t>(scene.materials.size());
        if (capacity < kMaterialFixedSize) return Error::MalformedPayload;
        m.name = utf8_prefix(m.name, std::min(kMaxName, capacity - kMaterialFixedSize));
        for (const TextureRef* t : {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture,
                                    &m.occlusion_texture, &m.emissive_texture})
            if (t->texture != kNone && t->texture >= scene.textures.size()) return Error::MalformedPayload;
        // Format 1.3: the patch in a MATERIAL_EXTENSIONS packet right after its material, when it fits one.
        MaterialExtensions patch{m.index, m.material_count, std::move(m.extensions)};
        m.extensions.clear();
        m.has_extensions = false;
        if (!patch.patch.empty()) {
            std::vector<PatchTextureReference> refs;
            if (check_material_patch(patch.patch, &refs) != Error::Ok) return Error::MalformedPayload;
            for (const auto& r : refs)
                if (r.texture >= scene.textures.size()) return Error::MalformedPayload;
            m.has_extensions = 4 + patch.patch.size() <= capacity;
            if (!m.has_extensions) packets.extensions_too_large.push_back(m.index);
        }
        packets.materials.push_back(emit(PacketType::Material, encode_material_payload(m)));
        if (m.has_extensions) {
            packets.materials.push_back(emit(PacketType::MaterialExtensions, encode_material_extensions_payload(patch),
                                             kMaterialExtensionsMinor));
        }
    }

    const size_t per_fragment = capacity - kTextureFragmentHeaderSize;
    for (size_t i = 0; i < scene.textures.size(); ++i) {
        const auto& texture = scene.textures[i];
        if (texture.image.empty() || texture.image.size() > 0xFFFFFFFFull) return Error::MalformedPayload;
        TextureFragment f;
        f.info = texture.info;
        f.info.index = static_cast<uint16_t>(i);
        f.info.texture_count = static_cast<uint16_t>(scene.textures.size());
        f.info.image_size = static_cast<uint32_t>(texture.image.size());
        f.info.image_crc = crc32c(texture.image.data(), texture.image.size());
        for (size_t offset = 0; offset < texture.image.size(); offset += per_fragment) {
            size_t n = std::min(per_fragment, texture.image.size() - offset);
            f.offset = static_cast<uint32_t>(offset);
            f.data.assign(texture.image.begin() + offset, texture.image.begin() + offset + n);
            packets.textures.push_back(emit(PacketType::TextureFragment, encode_texture_fragment_payload(f)));
        }
    }
    // ANIMATION (format 1.4): each track's keys in runs of as many as fit a packet. An animation's
    // weights tracks form a morph animation (format 1.6, spec 22.5), which joins the ANIMATION of its
    // other tracks or, when it has none, stands alone.
    if (scene.animations.size() > 0xFFFF) return Error::MalformedPayload;
    for (const auto& animation : scene.animations) {
        const auto& tracks = animation.tracks;
        const size_t weights = weights_tracks(animation);
        if (tracks.empty() || weights > 0xFFFF || tracks.size() - weights > 0xFFFF) return Error::MalformedPayload;
    }
    const AnimationTables tables = animation_tables(scene.animations);
    const std::vector<uint16_t>& animation_index = tables.animation_index;
    const std::vector<uint16_t>& morph_index = tables.morph_index;
    const size_t animation_count = tables.animation_count, morph_count = tables.morph_count;
    if (animation_count > 0xFFFF || morph_count > 0xFFFF) return Error::MalformedPayload;
    for (const bool morph : {false, true}) {  // every ANIMATION packet, then every MORPH_ANIMATION packet
        for (size_t i = 0; i < scene.animations.size(); ++i) {
            const SceneAnimation& animation = scene.animations[i];
            const uint16_t index = morph ? morph_index[i] : animation_index[i];
            if (index == kNone) continue;
            AnimationPiece piece;
            piece.animation = index;
            piece.animation_count = static_cast<uint16_t>(morph ? morph_count : animation_count);
            piece.joins = morph ? animation_index[i] : kNone;
            // A morph animation that joins one is written under that one's name (spec 22.2).
            piece.name = morph && piece.joins != kNone ? std::string() : utf8_prefix(animation.name, kMaxName);
            std::vector<const SceneAnimation::Track*> tracks;
            for (const auto& t : animation.tracks)
                if ((t.path == AnimationPath::Weights) == morph) tracks.push_back(&t);
            piece.track_count = static_cast<uint16_t>(tracks.size());
            const size_t header = morph ? kMorphAnimationHeaderSize : kAnimationHeaderSize;
            for (size_t t = 0; t < tracks.size(); ++t) {
                const SceneAnimation::Track& track = *tracks[t];
                if (morph && track.targets == 0) return Error::MalformedPayload;
                const size_t per_key = animation_values_per_key(track.path, track.interpolation, track.targets);
                const size_t keys = track.times.size();
                if (keys == 0 || keys > 0xFFFFFFFFull || track.values.size() != keys * per_key ||
                    (track.interpolation == Interpolation::CubicSpline && keys < 2) || track.node >= node_count ||
                    !all_finite(track.times) || !all_finite(track.values))
                    return Error::MalformedPayload;
                for (size_t k = 0; k < keys; ++k)
                    if (track.times[k] < 0 || (k > 0 && !(track.times[k] > track.times[k - 1]))) return Error::MalformedPayload;
                piece.track = static_cast<uint16_t>(t);
                piece.info = {track.node, track.path, track.interpolation, static_cast<uint32_t>(keys),
                              morph ? track.targets : uint8_t(0)};
                const size_t key_bytes = 4 * (1 + per_key);
                if (capacity < header + piece.name.size() + key_bytes) return Error::MalformedPayload;
                const size_t per_packet = std::min<size_t>(0xFFFF, (capacity - header - piece.name.size()) / key_bytes);
                for (size_t first = 0; first < keys; first += per_packet) {
                    const size_t n = std::min(per_packet, keys - first);
                    piece.first_key = static_cast<uint32_t>(first);
                    piece.times.assign(track.times.begin() + std::ptrdiff_t(first), track.times.begin() + std::ptrdiff_t(first + n));
                    piece.values.assign(track.values.begin() + std::ptrdiff_t(first * per_key),
                                        track.values.begin() + std::ptrdiff_t((first + n) * per_key));
                    packets.animations.push_back(
                        morph ? emit(PacketType::MorphAnimation, encode_morph_animation_payload(piece), kMorphMinor)
                              : emit(PacketType::Animation, encode_animation_payload(piece), kAnimationMinor));
                }
            }
        }
    }
    // SKIN (format 1.5): each skin's joints in runs of as many as fit a packet.
    if (scene.skins.size() > 0xFFFE) return Error::MalformedPayload;
    for (size_t i = 0; i < scene.skins.size(); ++i) {
        const SceneSkin& skin = scene.skins[i];
        if (skin.joints.empty() || skin.joints.size() > 0xFFFF || (skin.skeleton != kNone && skin.skeleton >= node_count))
            return Error::MalformedPayload;
        SkinPiece piece;
        piece.skin = static_cast<uint16_t>(i);
        piece.skin_count = static_cast<uint16_t>(scene.skins.size());
        piece.joint_count = static_cast<uint16_t>(skin.joints.size());
        piece.skeleton = skin.skeleton;
        piece.name = utf8_prefix(skin.name, kMaxName);
        for (const SkinJoint& j : skin.joints)
            if (j.node >= node_count || !all_finite(j.inverse_bind)) return Error::MalformedPayload;
        if (capacity < kSkinHeaderSize + piece.name.size() + kSkinJointSize) return Error::MalformedPayload;
        const size_t per_packet = (capacity - kSkinHeaderSize - piece.name.size()) / kSkinJointSize;
        for (size_t first = 0; first < skin.joints.size(); first += per_packet) {
            const size_t n = std::min(per_packet, skin.joints.size() - first);
            piece.first_joint = static_cast<uint16_t>(first);
            piece.joints.assign(skin.joints.begin() + std::ptrdiff_t(first), skin.joints.begin() + std::ptrdiff_t(first + n));
            packets.skins.push_back(emit(PacketType::Skin, encode_skin_payload(piece), kSkinMinor));
        }
    }
    // CAMERA and LIGHT (format 1.10, spec 26): one record a packet, a name cut to what fits.
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        SceneCamera c = scene.cameras[i];
        c.index = static_cast<uint16_t>(i);
        c.camera_count = static_cast<uint16_t>(scene.cameras.size());
        c.name = utf8_prefix(c.name, std::min(kMaxName, capacity - kCameraFixedSize));
        packets.cameras_lights.push_back(emit(PacketType::Camera, encode_camera_payload(c), kCameraLightMinor));
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        SceneLight l = scene.lights[i];
        l.index = static_cast<uint16_t>(i);
        l.light_count = static_cast<uint16_t>(scene.lights.size());
        l.name = utf8_prefix(l.name, std::min(kMaxName, capacity - kLightFixedSize));
        packets.cameras_lights.push_back(emit(PacketType::Light, encode_light_payload(l), kCameraLightMinor));
    }
    // EXTRAS (format 1.12, spec 28): every text in target order, in fragments that fill the packets.
    if (scene.extras.size() > 0xFFFF) return Error::MalformedPayload;
    // An animation's text goes to the table its animation is sent in (spec 28.1: kind 6, or 10 for
    // one of weights tracks only).
    std::vector<SceneExtras> texts;
    for (const SceneExtras& e : scene.extras) {
        if (static_cast<uint8_t>(e.kind) >= kExtrasTargetKinds || e.index >= extras_table_size(scene, e.kind) ||
            e.text.empty() || e.text.size() > kMaxExtrasText || !acceptable_extras_text(e.text))
            return Error::MalformedPayload;
        SceneExtras wire = e;
        if (e.kind == ExtrasTarget::Animation && animation_index[e.index] == kNone) {
            wire.kind = ExtrasTarget::MorphAnimation;
            wire.index = morph_index[e.index];
        } else if (e.kind == ExtrasTarget::Animation) {
            wire.index = animation_index[e.index];
        }
        texts.push_back(std::move(wire));
    }
    std::sort(texts.begin(), texts.end(), [](const SceneExtras& a, const SceneExtras& b) {
        return std::make_pair(a.kind, a.index) < std::make_pair(b.kind, b.index);
    });
    for (size_t i = 1; i < texts.size(); ++i)
        if (texts[i].kind == texts[i - 1].kind && texts[i].index == texts[i - 1].index) return Error::MalformedPayload;
    const size_t per_extras = capacity - kExtrasHeaderSize;
    for (const SceneExtras& e : texts) {
        ExtrasFragment f;
        f.kind = e.kind;
        f.index = e.index;
        f.text_count = static_cast<uint16_t>(texts.size());
        f.text_size = static_cast<uint32_t>(e.text.size());
        f.text_crc = crc32c(reinterpret_cast<const uint8_t*>(e.text.data()), e.text.size());
        for (size_t offset = 0; offset < e.text.size(); offset += per_extras) {
            const size_t n = std::min(per_extras, e.text.size() - offset);
            f.offset = static_cast<uint32_t>(offset);
            f.data.assign(e.text.begin() + std::ptrdiff_t(offset), e.text.begin() + std::ptrdiff_t(offset + n));
            packets.extras.push_back(emit(PacketType::Extras, encode_extras_payload(f), kExtrasMinor));
        }
    }
    // REQUIRED_EXTENSION (format 1.13, spec 29): one packet a name, in the list's order.
    const auto& required = scene.required_extensions;
    if (required.size() > kMaxRequiredExtensions) return Error::MalformedPayload;
    for (size_t i = 0; i < required.size(); ++i) {
        if (!is_extension_name(required[i]) || std::find(required.begin(), required.begin() + std::ptrdiff_t(i), required[i]) !=
                                                   required.begin() + std::ptrdiff_t(i))
            return Error::MalformedPayload;
        const RequiredExtension e{static_cast<uint8_t>(required.size()), static_cast<uint8_t>(i), required[i]};
        packets.required_extensions.push_back(
            emit(PacketType::RequiredExtension, encode_required_extension_payload(e), kRequiredExtensionMinor));
    }
    out = std::move(packets);
    return Error::Ok;
}

}  // namespace ellicast

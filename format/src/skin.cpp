// Skins (format 1.5, spec 21): SKIN and JOINT_WEIGHTS payloads, and what a receiver keeps of them.
#include "ellicast/format.h"

#include "bytes.h"
#include "point_runs.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ellicast {

using namespace detail;

// ------------------------------------------------------------------------------------------
// SKIN

std::vector<uint8_t> encode_skin_payload(const SkinPiece& s) {
    std::vector<uint8_t> out;
    const size_t name = std::min<size_t>(s.name.size(), 255);
    out.reserve(kSkinHeaderSize + name + kSkinJointSize * s.joints.size());
    put_u16(out, s.skin);
    put_u16(out, s.skin_count);
    put_u16(out, s.joint_count);
    put_u16(out, s.first_joint);
    put_u16(out, static_cast<uint16_t>(s.joints.size()));
    put_u16(out, s.skeleton);
    put_u8(out, static_cast<uint8_t>(name));
    put_u8(out, 0);
    out.insert(out.end(), s.name.begin(), s.name.begin() + static_cast<std::ptrdiff_t>(name));
    for (const SkinJoint& j : s.joints) {
        put_u16(out, j.node);
        for (float f : j.inverse_bind) put_f32(out, f);
    }
    return out;
}

Error decode_skin_payload(std::span<const uint8_t> payload, SkinPiece& out) {
    if (payload.size() < kSkinHeaderSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    SkinPiece s;
    s.skin = get_u16(p);
    s.skin_count = get_u16(p + 2);
    s.joint_count = get_u16(p + 4);
    s.first_joint = get_u16(p + 6);
    const uint16_t count = get_u16(p + 8);
    s.skeleton = get_u16(p + 10);
    const uint8_t name = p[12];
    if (payload.size() != kSkinHeaderSize + name + kSkinJointSize * size_t(count)) return Error::MalformedPayload;
    if (s.skin >= s.skin_count || s.joint_count == 0 || count == 0 || uint32_t(s.first_joint) + count > s.joint_count)
        return Error::MalformedPayload;
    s.name.assign(reinterpret_cast<const char*>(p + kSkinHeaderSize), name);
    const uint8_t* joint = p + kSkinHeaderSize + name;
    s.joints.resize(count);
    for (size_t k = 0; k < count; ++k, joint += kSkinJointSize) {
        s.joints[k].node = get_u16(joint);
        for (size_t v = 0; v < 16; ++v) {
            const float x = get_f32(joint + 2 + 4 * v);
            if (!std::isfinite(x)) return Error::MalformedPayload;
            s.joints[k].inverse_bind[v] = x;
        }
    }
    out = std::move(s);
    return Error::Ok;
}

Error ReceivedStream::take_skin(const PacketView& packet, uint64_t where) {
    SkinPiece s;
    if (decode_skin_payload(packet.payload, s) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "SKIN payload inconsistent or out of range (length, skin index, joint count or range, or a "
                      "matrix entry that is not finite)");
    const std::string what = "skin " + std::to_string(s.skin);
    // Comparisons (spec 21.1), in order: table size, skin, joints.
    if (skin_count_ && *skin_count_ != s.skin_count)
        return reject(where, Error::StreamMismatch,
                      "SKIN table size " + std::to_string(s.skin_count) + " contradicts the " +
                          std::to_string(*skin_count_) + " of earlier packets");
    auto held = skins_.find(s.skin);
    if (held != skins_.end() && (held->second.joint_count != s.joint_count || held->second.skeleton != s.skeleton ||
                                 held->second.name != s.name))
        return reject(where, Error::StreamMismatch, what + ": its joint count, skeleton or name contradicts earlier packets");
    size_t fresh = 0;
    for (size_t k = 0; k < s.joints.size(); ++k) {
        const uint16_t index = static_cast<uint16_t>(s.first_joint + k);
        if (held != skins_.end()) {
            auto j = held->second.joints.find(index);
            if (j != held->second.joints.end()) {
                // Matrix entries as numbers: +0 and -0 agree (== does so).
                if (!(j->second == s.joints[k]))
                    return reject(where, Error::StreamMismatch,
                                  what + ": joint " + std::to_string(index) + " differs from the one received before");
                continue;
            }
        }
        ++fresh;
    }
    if (fresh == 0) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    const uint64_t memory = 128 * uint64_t(fresh);
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      what + ": the stream's textures, animations and skins exceed this receiver's " +
                          std::to_string(limits_.max_texture_bytes) + "-byte memory limit for them");
    skin_count_ = s.skin_count;
    ReceivedSkin& skin = skins_[s.skin];
    if (skin.joints.empty()) {
        skin.joint_count = s.joint_count;
        skin.skeleton = s.skeleton;
        skin.name = s.name;
    }
    for (size_t k = 0; k < s.joints.size(); ++k) skin.joints.emplace(static_cast<uint16_t>(s.first_joint + k), s.joints[k]);
    texture_bytes_ += memory;
    ++counters_.accepted;
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// JOINT_WEIGHTS

bool valid_influences(const Influences& r) {
    if (r.count < 1 || r.count > 4) return false;
    unsigned sum = 0;
    for (size_t i = 0; i < 4; ++i) {
        if (i >= r.count) {
            if (r.joints[i] != 0 || r.weights[i] != 0) return false;
            continue;
        }
        if (r.weights[i] == 0) return false;
        sum += r.weights[i];
        for (size_t k = 0; k < i; ++k)
            if (r.joints[k] == r.joints[i]) return false;
    }
    return sum == 255;
}

Influences quantize_influences(std::span<const uint16_t> joints, std::span<const float> weights) {
    // Sum the weights of each joint (a joint may come twice, e.g. from a blend of corners).
    std::vector<std::pair<uint16_t, double>> items;
    for (size_t i = 0; i < joints.size() && i < weights.size(); ++i) {
        if (!(weights[i] > 0) || !std::isfinite(weights[i])) continue;
        auto it = std::find_if(items.begin(), items.end(), [&](const auto& x) { return x.first == joints[i]; });
        if (it == items.end()) items.emplace_back(joints[i], double(weights[i]));
        else it->second += double(weights[i]);
    }
    Influences r;
    if (items.empty()) return r;
    std::stable_sort(items.begin(), items.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    if (items.size() > 4) items.resize(4);
    double total = 0;
    for (const auto& it : items) total += it.second;
    // Largest remainders: floor each share of 255, then hand out what is left to the largest
    // fractional parts (the earlier on a tie).
    std::array<unsigned, 4> units{};
    std::array<double, 4> rest{};
    unsigned given = 0;
    for (size_t i = 0; i < items.size(); ++i) {
        const double exact = 255.0 * items[i].second / total;
        units[i] = unsigned(std::floor(exact));
        rest[i] = exact - units[i];
        given += units[i];
    }
    while (given < 255) {
        size_t best = 0;
        for (size_t i = 1; i < items.size(); ++i)
            if (rest[i] > rest[best]) best = i;
        ++units[best];
        rest[best] = -1;
        ++given;
    }
    for (size_t i = 0; i < items.size(); ++i) {
        if (units[i] == 0) continue;
        r.joints[r.count] = items[i].first;
        r.weights[r.count] = uint8_t(units[i]);
        ++r.count;
    }
    return r;
}

std::vector<uint8_t> encode_joint_weights_payload(const JointWeightsRun& run) {
    bool wide = false;
    for (const Influences& r : run.records)
        for (size_t i = 0; i < r.count; ++i) wide |= r.joints[i] > 0xFF;
    std::vector<uint8_t> out;
    out.reserve(kJointWeightsHeaderSize + run.records.size() * (wide ? 13 : 9));
    put_u32(out, run.first_index);
    put_u16(out, static_cast<uint16_t>(run.records.size()));
    put_u8(out, wide ? 2 : 1);
    put_u8(out, 0);
    for (const Influences& r : run.records) {
        put_u8(out, r.count);
        for (size_t i = 0; i < r.count; ++i) {
            if (wide) put_u16(out, r.joints[i]);
            else put_u8(out, static_cast<uint8_t>(r.joints[i]));
        }
        for (size_t i = 0; i < r.count; ++i) put_u8(out, r.weights[i]);
    }
    return out;
}

Error decode_joint_weights_payload(std::span<const uint8_t> payload, JointWeightsRun& out) {
    if (payload.size() < kJointWeightsHeaderSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    JointWeightsRun run;
    run.first_index = get_u32(p);
    const uint16_t count = get_u16(p + 4);
    const uint8_t joint_size = p[6];
    if (count == 0 || (joint_size != 1 && joint_size != 2) || uint64_t(run.first_index) + count > 0xFFFFFFFFull)
        return Error::MalformedPayload;
    size_t pos = kJointWeightsHeaderSize;
    run.records.resize(count);
    for (Influences& r : run.records) {
        if (pos >= payload.size()) return Error::MalformedPayload;
        const uint8_t n = p[pos++];
        if (n < 1 || n > 4 || payload.size() - pos < size_t(n) * (joint_size + 1u)) return Error::MalformedPayload;
        r.count = n;
        for (size_t i = 0; i < n; ++i, pos += joint_size) r.joints[i] = joint_size == 2 ? get_u16(p + pos) : p[pos];
        for (size_t i = 0; i < n; ++i) r.weights[i] = p[pos++];
        if (!valid_influences(r)) return Error::MalformedPayload;
    }
    if (pos != payload.size()) return Error::MalformedPayload;
    out = std::move(run);
    return Error::Ok;
}

Error packetize_joint_weights(const StreamInfo& info, uint16_t object_id, const std::vector<Influences>& records,
                              uint32_t stream_id, uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out) {
    if (object_id >= info.objects.size() || records.size() != info.objects[object_id].point_count || records.empty() ||
        info.packet_size < kMinPacketSize)
        return Error::MalformedPayload;
    for (const Influences& r : records)
        if (!valid_influences(r)) return Error::MalformedPayload;
    const size_t capacity = info.packet_size - kPacketOverhead - kJointWeightsHeaderSize;
    uint32_t sequence = first_sequence;
    size_t first = 0;
    while (first < records.size()) {
        // As many records as fit: a record takes 1 + count * (joint size + 1) bytes, and the joint
        // size of the run is 2 once any of its joints needs it.
        size_t n = 0, influences = 0;
        bool wide = false;
        while (first + n < records.size() && n < 0xFFFF) {
            const Influences& r = records[first + n];
            bool w = wide;
            for (size_t i = 0; i < r.count; ++i) w |= r.joints[i] > 0xFF;
            if ((n + 1) + (influences + r.count) * (w ? 3u : 2u) > capacity) break;
            wide = w;
            influences += r.count;
            ++n;
        }
        if (n == 0) return Error::MalformedPayload;  // a record does not fit a packet (cannot happen at 128 bytes)
        JointWeightsRun run;
        run.first_index = static_cast<uint32_t>(first);
        run.records.assign(records.begin() + std::ptrdiff_t(first), records.begin() + std::ptrdiff_t(first + n));
        out.push_back(write_packet(skippable_header(PacketType::JointWeights, kSkinMinor, stream_id, sequence++, object_id),
                                   encode_joint_weights_payload(run)));
        first += n;
    }
    return Error::Ok;
}

std::map<uint16_t, uint32_t> skinned_objects(const ReceivedStream& stream) {
    std::map<uint16_t, uint32_t> out;
    for (const auto& [index, node] : stream.scene_nodes()) {
        if (node.skin == kNone || node.mesh == kNone) continue;
        const auto mesh = stream.scene_meshes().find(node.mesh);
        if (mesh == stream.scene_meshes().end()) continue;
        const auto skin = stream.skins().find(node.skin);
        const uint32_t joints = skin == stream.skins().end() ? 0x10000u : skin->second.joint_count;
        for (const auto& p : mesh->second.primitives) {
            auto [it, fresh] = out.try_emplace(p.object, joints);
            if (!fresh) it->second = std::min(it->second, joints);
        }
    }
    return out;
}

Error ReceivedStream::take_joint_weights(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                         uint64_t where) {
    JointWeightsRun run;
    if (decode_joint_weights_payload(packet.payload, run) != Error::Ok)
        return reject(where, Error::MalformedPayload, name + ": its count, joint size or an influence record is malformed");
    const uint64_t end = uint64_t(run.first_index) + run.records.size();
    if (end > object.info->point_count)
        return reject(where, Error::IndexOutOfRange,
                      name + ": points " + std::to_string(run.first_index) + "+" + std::to_string(run.records.size()) +
                          " of " + std::to_string(object.info->point_count));
    bool news = false;
    if (auto differs = detail::compare_run(object.weights, run.first_index, run.records, news))
        return reject(where, Error::StreamMismatch,
                      name + ": the record of point " + std::to_string(*differs) + " differs from the one received before");
    if (!news) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    detail::keep_run(object.weights, run.first_index, run.records);
    ++counters_.accepted;
    return Error::Ok;
}

}  // namespace ellicast

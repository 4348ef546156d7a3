// Morph targets (format 1.6, spec 22): MORPH_DELTAS payloads, and what a receiver keeps of them.
// (MORPH_ANIMATION is in animation.cpp, beside ANIMATION; the mesh record's targets in scene.cpp.)
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace ellicast {

using namespace detail;

size_t morph_record_values(uint8_t target_count, uint8_t attributes) {
    return size_t(target_count) * 3 * size_t(std::popcount(static_cast<unsigned>(attributes & 3u)));
}

std::vector<uint8_t> encode_morph_deltas_payload(const MorphDeltasRun& run) {
    const size_t slots = morph_record_values(run.target_count, run.attributes) / 3, mask = (slots + 7) / 8;
    std::vector<uint8_t> out;
    out.reserve(kMorphDeltasHeaderSize + 4 * slots + run.count * (mask + 6 * slots));
    put_u32(out, run.first_index);
    put_u16(out, run.count);
    put_u8(out, run.target_count);
    put_u8(out, run.attributes);
    for (float f : run.scales) put_f32(out, f);
    for (size_t i = 0; i < run.count; ++i) {
        const int16_t* record = run.values.data() + i * slots * 3;
        const size_t at = out.size();
        out.resize(at + mask, 0);
        for (size_t k = 0; k < slots; ++k) {
            const int16_t* v = record + 3 * k;
            if (v[0] == 0 && v[1] == 0 && v[2] == 0) continue;  // the encoder leaves out exactly the zero vectors
            out[at + k / 8] |= uint8_t(1u << (k % 8));
            for (size_t c = 0; c < 3; ++c) put_u16(out, static_cast<uint16_t>(v[c]));
        }
    }
    return out;
}

Error decode_morph_deltas_payload(std::span<const uint8_t> payload, MorphDeltasRun& out) {
    if (payload.size() < kMorphDeltasHeaderSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    MorphDeltasRun run;
    run.first_index = get_u32(p);
    run.count = get_u16(p + 4);
    run.target_count = p[6];
    run.attributes = p[7];
    if (run.count == 0 || run.target_count == 0 || run.attributes == 0 || (run.attributes & ~3u) != 0)
        return Error::MalformedPayload;
    const size_t slots = morph_record_values(run.target_count, run.attributes) / 3, mask = (slots + 7) / 8;
    if (payload.size() < kMorphDeltasHeaderSize + 4 * slots) return Error::MalformedPayload;
    run.scales.resize(slots);
    for (size_t k = 0; k < slots; ++k) {
        const float s = get_f32(p + kMorphDeltasHeaderSize + 4 * k);
        // Below 2^113, every q * s is a finite f32 (spec 22.1).
        if (!std::isfinite(s) || !(s > 0) || s >= 0x1p113f) return Error::MalformedPayload;
        run.scales[k] = s;
    }
    size_t pos = kMorphDeltasHeaderSize + 4 * slots;
    run.values.assign(size_t(run.count) * slots * 3, 0);
    for (size_t i = 0; i < run.count; ++i) {
        if (payload.size() - pos < mask) return Error::MalformedPayload;
        const uint8_t* bits = p + pos;
        pos += mask;
        if (slots % 8 != 0 && (bits[mask - 1] >> (slots % 8)) != 0) return Error::MalformedPayload;  // bits past S
        for (size_t k = 0; k < slots; ++k) {
            if (!(bits[k / 8] >> (k % 8) & 1u)) continue;
            if (payload.size() - pos < 6) return Error::MalformedPayload;
            for (size_t c = 0; c < 3; ++c, pos += 2)
                run.values[(i * slots + k) * 3 + c] = static_cast<int16_t>(get_u16(p + pos));
        }
    }
    if (pos != payload.size() || uint64_t(run.first_index) + run.count > 0xFFFFFFFFull) return Error::MalformedPayload;
    out = std::move(run);
    return Error::Ok;
}

Error packetize_morph_deltas(const StreamInfo& info, uint16_t object_id, uint8_t target_count, uint8_t attributes,
                             const std::vector<float>& values, uint32_t stream_id, uint32_t first_sequence,
                             std::vector<std::vector<uint8_t>>& out) {
    if (object_id >= info.objects.size() || target_count == 0 || attributes == 0 || (attributes & ~3u) != 0 ||
        info.packet_size < kMinPacketSize)
        return Error::MalformedPayload;
    const size_t points = info.objects[object_id].point_count;
    const size_t per_point = morph_record_values(target_count, attributes), slots = per_point / 3, mask = (slots + 7) / 8;
    if (points == 0 || values.size() != points * per_point) return Error::MalformedPayload;
    for (float f : values)
        if (!std::isfinite(f)) return Error::MalformedPayload;
    // One scale per slot over the object's points (spec 22.1, informative): its largest component
    // maps to 32767.
    std::vector<float> scales(slots, 0.0f);
    for (size_t i = 0; i < points; ++i)
        for (size_t k = 0; k < per_point; ++k)
            scales[k / 3] = std::max(scales[k / 3], std::abs(values[i * per_point + k]));
    for (float& s : scales) s = s > 0 ? s / 32767.0f : 1.0f;
    for (float s : scales)
        if (!std::isfinite(s) || !(s > 0) || s >= 0x1p113f) return Error::MalformedPayload;  // a subnormal range underflows
    std::vector<int16_t> q(values.size());
    std::vector<uint16_t> present(points, 0);  // vectors a point's record carries
    for (size_t i = 0; i < points; ++i)
        for (size_t k = 0; k < slots; ++k) {
            bool any = false;
            for (size_t c = 0; c < 3; ++c) {
                const size_t at = i * per_point + 3 * k + c;
                const double x = std::round(double(values[at]) / double(scales[k]));
                q[at] = static_cast<int16_t>(std::clamp(x, -32767.0, 32767.0));
                any |= q[at] != 0;
            }
            present[i] += any;
        }
    const size_t capacity = info.packet_size - kPacketOverhead - kMorphDeltasHeaderSize - 4 * slots;
    if (info.packet_size < kPacketOverhead + kMorphDeltasHeaderSize + 4 * slots) return Error::MalformedPayload;
    uint32_t sequence = first_sequence;
    size_t first = 0;
    while (first < points) {
        size_t n = 0, bytes = 0;
        while (first + n < points && n < 0xFFFF && bytes + mask + 6 * present[first + n] <= capacity)
            bytes += mask + 6 * present[first + n++];
        if (n == 0) return Error::MalformedPayload;  // one point's record is larger than a packet
        MorphDeltasRun run;
        run.first_index = static_cast<uint32_t>(first);
        run.count = static_cast<uint16_t>(n);
        run.target_count = target_count;
        run.attributes = attributes;
        run.scales = scales;
        run.values.assign(q.begin() + std::ptrdiff_t(first * per_point), q.begin() + std::ptrdiff_t((first + n) * per_point));
        out.push_back(write_packet(skippable_header(PacketType::MorphDeltas, kMorphMinor, stream_id, sequence++, object_id),
                                   encode_morph_deltas_payload(run)));
        first += n;
    }
    return Error::Ok;
}

Error ReceivedStream::take_morph_deltas(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                        uint64_t where) {
    MorphDeltasRun run;
    if (decode_morph_deltas_payload(packet.payload, run) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      name + ": its count, target count, attributes, a scale, a record's mask or length is malformed");
    const uint64_t end = uint64_t(run.first_index) + run.count;
    if (end > object.info->point_count)
        return reject(where, Error::IndexOutOfRange,
                      name + ": points " + std::to_string(run.first_index) + "+" + std::to_string(run.count) + " of " +
                          std::to_string(object.info->point_count));
    // Comparisons (spec 22.1), in order: the object's target count, attributes and scales, then the records.
    if (object.morph_targets != 0 &&
        (object.morph_targets != run.target_count || object.morph_attributes != run.attributes ||
         object.morph_scales != run.scales))
        return reject(where, Error::StreamMismatch,
                      name + ": " + std::to_string(run.target_count) + " targets with attributes " +
                          std::to_string(run.attributes) + " and their scales contradict the " +
                          std::to_string(object.morph_targets) + " with attributes " +
                          std::to_string(object.morph_attributes) + " of earlier packets");
    const size_t per_point = morph_record_values(run.target_count, run.attributes);
    // Dequantized (spec 22.1): with the object's scales fixed, equal values are equal integers.
    std::vector<float> values(run.values.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = morph_dequantize(run.values[i], run.scales[(i % per_point) / 3]);
    uint64_t fresh = 0, runs = 0;
    bool in_run = false;
    for (size_t i = 0; i < run.count; ++i) {
        const float* held = object.morph.find(static_cast<uint32_t>(run.first_index + i));  // none before the first run
        if (!held) {
            ++fresh;
            if (!in_run) ++runs;
            in_run = true;
            continue;
        }
        in_run = false;
        // As numbers: +0 and -0 agree (== does so).
        if (!std::equal(held, held + per_point, values.begin() + std::ptrdiff_t(i * per_point)))
            return reject(where, Error::StreamMismatch,
                          name + ": the displacements of point " + std::to_string(run.first_index + i) +
                              " differ from those received before");
    }
    if (fresh == 0) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    // What the new records will cost as held (pages included), for the limit below.
    const uint64_t memory = fresh * 4 * per_point + runs * kHeldPacketCost;
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      name + ": the stream's textures, animations and morph targets exceed this receiver's " +
                          std::to_string(limits_.max_texture_bytes) + "-byte memory limit for them");
    object.morph_targets = run.target_count;
    object.morph_attributes = run.attributes;
    object.morph_scales = run.scales;
    object.morph.set_stride(per_point);
    for (size_t i = 0; i < run.count; ++i)
        object.morph.insert(static_cast<uint32_t>(run.first_index + i), values.data() + i * per_point);
    texture_bytes_ += memory;
    ++counters_.accepted;
    return Error::Ok;
}

std::map<uint16_t, uint8_t> morph_target_objects(const ReceivedStream& stream) {
    std::map<uint16_t, uint8_t> out;
    for (const auto& [index, mesh] : stream.scene_meshes()) {
        if (mesh.weights.empty()) continue;
        const auto targets = static_cast<uint8_t>(mesh.weights.size());
        for (const auto& p : mesh.primitives) {
            auto [it, fresh] = out.try_emplace(p.object, targets);
            if (!fresh) it->second = std::min(it->second, targets);
        }
    }
    return out;
}

bool morphed(const ReceivedObject& object) {
    for (const auto& [index, record] : object.morph)
        if (object.points.contains(index)) return true;
    return false;
}

bool mesh_shows_targets(const ReceivedStream& stream, const SceneMesh& mesh,
                        const std::function<bool(uint16_t object)>& object_shown) {
    if (mesh.weights.empty()) return false;
    bool any = false;
    for (const auto& p : mesh.primitives) {
        if (!object_shown(p.object)) continue;
        if (p.object >= stream.objects().size()) return false;
        const ReceivedObject& o = stream.objects()[p.object];
        if (o.morph_targets != mesh.weights.size() || !morphed(o)) return false;
        any = true;
    }
    return any;
}

}  // namespace ellicast

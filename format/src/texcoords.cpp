// Further texture-coordinate sets (format 1.14, spec 30): TEXCOORDS payloads, their packets, and
// what a receiver keeps of them.
#include "ellicast/format.h"

#include "bytes.h"
#include "point_runs.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ellicast {

using namespace detail;

namespace {
// Spec 30.1's rules for a range (step 11): bits 4..16, every component finite, scales not negative,
// ends finite in f32.
bool valid_range(const TexcoordRange& range) {
    if (range.bits < 4 || range.bits > 16) return false;
    for (int k = 0; k < 2; ++k) {
        const float o = range.origin[k], s = range.scale[k];
        if (!std::isfinite(o) || !std::isfinite(s) || s < 0 || !std::isfinite(static_cast<float>(double(o) + s)))
            return false;
    }
    return true;
}
}  // namespace

// ------------------------------------------------------------------------------------------
// TEXCOORDS payload (spec 30.1)

size_t texcoords_payload_size(size_t count, unsigned bits) {
    return kTexcoordsHeaderSize + (2 * size_t(bits) * count + 7) / 8;
}

std::vector<uint8_t> encode_texcoords_payload(const TexcoordsRun& run) {
    std::vector<uint8_t> out;
    out.reserve(texcoords_payload_size(run.records.size(), run.range.bits));
    put_u32(out, run.first_index);
    put_u16(out, static_cast<uint16_t>(run.records.size()));
    put_u8(out, run.set);
    put_u8(out, run.set_count);
    put_u8(out, run.range.bits);
    for (int k = 0; k < 3; ++k) put_u8(out, 0);
    for (float f : run.range.origin) put_f32(out, f);
    for (float f : run.range.scale) put_f32(out, f);
    BitWriter w(out);
    for (const auto& r : run.records)
        for (int k = 0; k < 2; ++k) w.put(r[k], int(run.range.bits));
    return out;
}

Error decode_texcoords_payload(std::span<const uint8_t> payload, TexcoordsRun& out) {
    if (payload.size() < kTexcoordsHeaderSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    TexcoordsRun run;
    run.first_index = get_u32(p);
    const uint16_t count = get_u16(p + 4);
    run.set = p[6];
    run.set_count = p[7];
    run.range.bits = p[8];
    for (int k = 0; k < 2; ++k) run.range.origin[k] = get_f32(p + 12 + 4 * k);
    for (int k = 0; k < 2; ++k) run.range.scale[k] = get_f32(p + 20 + 4 * k);
    if (count == 0 || run.set_count == 0 || run.set_count > kMaxTexcoordSets || run.set == 0 ||
        run.set > run.set_count || !valid_range(run.range) || uint64_t(run.first_index) + count > 0xFFFFFFFFull)
        return Error::MalformedPayload;
    if (payload.size() != texcoords_payload_size(count, run.range.bits)) return Error::MalformedPayload;
    run.records.resize(count);
    BitReader r(payload.subspan(kTexcoordsHeaderSize));
    for (auto& record : run.records)
        for (int k = 0; k < 2; ++k) record[k] = static_cast<uint16_t>(r.get(run.range.bits));
    out = std::move(run);
    return Error::Ok;
}

std::array<float, 2> dequantize_texcoord(const std::array<uint16_t, 2>& q, const TexcoordRange& range) {
    const double max = double((1u << range.bits) - 1u);
    std::array<float, 2> t{};
    for (int k = 0; k < 2; ++k)
        t[k] = static_cast<float>(double(range.origin[k]) + std::min<double>(q[k], max) / max * double(range.scale[k]));
    return t;
}

std::array<uint16_t, 2> quantize_texcoord(const std::array<float, 2>& t, const TexcoordRange& range) {
    const uint32_t max = (1u << range.bits) - 1u;
    std::array<uint16_t, 2> q{};
    for (int k = 0; k < 2; ++k) {
        const double s = range.scale[k];
        const double x = s > 0 ? (double(t[k]) - range.origin[k]) / s : 0.0;
        if (!(x > 0)) continue;  // NaN and below the range: 0
        const double v = std::round(x * max);
        q[k] = static_cast<uint16_t>(v >= max ? max : uint32_t(v));
    }
    return q;
}

TexcoordRange texcoord_range(const std::vector<std::array<float, 2>>& values, uint8_t bits) {
    TexcoordRange range;
    range.bits = bits;
    for (int k = 0; k < 2; ++k) {
        float lo = INFINITY, hi = -INFINITY;
        for (const auto& t : values)
            if (std::isfinite(t[k])) lo = std::min(lo, t[k]), hi = std::max(hi, t[k]);
        if (!(lo <= hi)) lo = hi = 0;
        range.origin[k] = lo;
        range.scale[k] = hi > lo ? hi - lo : 1.0f;
        // The end, rounded to f32, reaches the largest value (so that it quantizes to the top step).
        while (static_cast<float>(double(lo) + range.scale[k]) < hi)
            range.scale[k] = std::nextafter(range.scale[k], INFINITY);
    }
    return range;
}

std::vector<std::vector<uint8_t>> detail::texcoords_payloads(const std::vector<TexcoordSet>& sets, uint32_t point_count,
                                                             size_t packet_size) {
    std::vector<std::vector<uint8_t>> out;
    if (sets.empty() || sets.size() > kMaxTexcoordSets || point_count == 0 || packet_size < kMinPacketSize) return {};
    for (size_t s = 0; s < sets.size(); ++s) {
        const TexcoordSet& set = sets[s];
        if (set.records.size() != point_count || !valid_range(set.range)) return {};
        const size_t capacity = (std::min<size_t>(packet_size, kMaxPacketSize) - kPacketOverhead - kTexcoordsHeaderSize) *
                                8 / (2 * size_t(set.range.bits));
        const size_t per_packet = std::min<size_t>(capacity, 0xFFFF);
        for (size_t first = 0; first < point_count; first += per_packet) {
            TexcoordsRun run;
            run.first_index = static_cast<uint32_t>(first);
            run.set = static_cast<uint8_t>(s + 1);
            run.set_count = static_cast<uint8_t>(sets.size());
            run.range = set.range;
            const size_t n = std::min<size_t>(per_packet, point_count - first);
            run.records.assign(set.records.begin() + std::ptrdiff_t(first), set.records.begin() + std::ptrdiff_t(first + n));
            out.push_back(encode_texcoords_payload(run));
        }
    }
    return out;
}

Error packetize_texcoords(const StreamInfo& info, uint16_t object_id, const std::vector<TexcoordSet>& sets,
                          uint32_t stream_id, uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out) {
    if (object_id >= info.objects.size() || !info.objects[object_id].has(kAttrTexcoord)) return Error::MalformedPayload;
    const auto payloads = detail::texcoords_payloads(sets, info.objects[object_id].point_count, info.packet_size);
    if (payloads.empty()) return Error::MalformedPayload;
    uint32_t sequence = first_sequence;
    for (const auto& payload : payloads)
        out.push_back(write_packet(
            skippable_header(PacketType::Texcoords, kTexcoordsMinor, stream_id, sequence++, object_id), payload));
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// What a receiver keeps (spec 30.1, steps 13 to 15)

Error ReceivedStream::take_texcoords(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                     uint64_t where) {
    const ObjectInfo& oi = *object.info;
    if (!oi.has(kAttrTexcoord))
        return reject(where, Error::MalformedPayload,
                      name + ": the object carries no texture coordinates (its entry's attributes bit 1 is clear), "
                             "so it has no further set");
    TexcoordsRun run;
    if (decode_texcoords_payload(packet.payload, run) != Error::Ok)
        return reject(where, Error::MalformedPayload, name + ": its payload no longer parses");
    const uint64_t end = uint64_t(run.first_index) + run.records.size();
    if (end > oi.point_count)
        return reject(where, Error::IndexOutOfRange,
                      name + ": points " + std::to_string(run.first_index) + "+" + std::to_string(run.records.size()) +
                          " of " + std::to_string(oi.point_count));
    const std::string set_name = "TEXCOORD_" + std::to_string(run.set);
    if (!object.texcoord_sets.empty() && object.texcoord_sets.size() != run.set_count)
        return reject(where, Error::StreamMismatch,
                      name + ": set_count " + std::to_string(run.set_count) + ", the object's packets before said " +
                          std::to_string(object.texcoord_sets.size()));
    const ReceivedTexcoordSet* held = object.texcoord_sets.empty() ? nullptr : &object.texcoord_sets[run.set - 1];
    if (held && held->has_range && !(held->range == run.range))
        return reject(where, Error::StreamMismatch,
                      name + ": the bits, origin or scale of " + set_name + " differ from the first packet of the set");
    bool news = false;
    for (size_t k = 0; k < run.records.size(); ++k) {
        const uint32_t index = uint32_t(run.first_index + k);
        const uint16_t* r = held ? held->records.find(index) : nullptr;
        if (!r) news = true;
        else if (r[0] != run.records[k][0] || r[1] != run.records[k][1])
            return reject(where, Error::StreamMismatch,
                          name + ": the " + set_name + " record of point " + std::to_string(index) +
                              " differs from the one received before");
    }
    if (!news) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    if (object.texcoord_sets.empty()) object.texcoord_sets.resize(run.set_count);
    ReceivedTexcoordSet& set = object.texcoord_sets[run.set - 1];
    if (!set.has_range) set.has_range = true, set.range = run.range;
    for (size_t k = 0; k < run.records.size(); ++k) set.records.insert(uint32_t(run.first_index + k), run.records[k].data());
    ++counters_.accepted;
    return Error::Ok;
}

}  // namespace ellicast

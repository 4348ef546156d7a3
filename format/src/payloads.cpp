// Payloads of STREAM_INFO, ELLIPSOIDS and POINTS packets, and cutting a stream into packets.
#include "ellicast/format.h"

#include "bytes.h"
#include "point_runs.h"

#include <algorithm>
#include <cmath>

namespace ellicast {

using namespace detail;

namespace {

constexpr size_t kBatchHeaderSize = 8;  // u32 first_index, u16 count, u16 reserved

bool finite(float f) { return std::isfinite(f); }

size_t payload_capacity(size_t packet_size) {
    packet_size = std::min(packet_size, kMaxPacketSize);
    return packet_size > kPacketOverhead ? packet_size - kPacketOverhead : 0;
}

void put_batch_header(std::vector<uint8_t>& out, uint32_t first, size_t count) {
    put_u32(out, first);
    put_u16(out, static_cast<uint16_t>(count));
    put_u16(out, 0);
}

}  // namespace

unsigned record_position_bits(const StreamInfo& info, const ObjectInfo& object) {
    return object.mapped() && object.map_level < info.position_bits ? info.position_bits - object.map_level
                                                                    : info.position_bits;
}

size_t point_record_bits(const StreamInfo& info, const ObjectInfo& object) {
    size_t bits = 3u * record_position_bits(info, object);
    if (object.has(kAttrNormal)) bits += 2u * info.normal_bits;
    if (object.has(kAttrTexcoord)) bits += 2u * info.texcoord_bits;
    bits += static_cast<size_t>(object.color_channels()) * info.color_bits;
    return bits;
}

Error check_stream_info(const StreamInfo& info) {
    if (info.packet_size < kMinPacketSize || info.packet_size > kMaxPacketSize) return Error::MalformedPayload;
    if (info.position_bits < 8 || info.position_bits > 16) return Error::MalformedPayload;
    if (info.normal_bits < 4 || info.normal_bits > 16) return Error::MalformedPayload;
    if (info.texcoord_bits < 4 || info.texcoord_bits > 16) return Error::MalformedPayload;
    if (info.color_bits < 2 || info.color_bits > 16) return Error::MalformedPayload;
    if (info.ellipsoid_encoding != 0) return Error::MalformedPayload;
    if (!finite(info.coverage_target)) return Error::MalformedPayload;
    if (info.objects.size() > kMaxObjects) return Error::MalformedPayload;
    for (const ObjectInfo& o : info.objects) {
        if (!finite(o.frame.scale) || !(o.frame.scale > 0)) return Error::MalformedPayload;
        // The whole cube must be finite in f32, or dequantized positions overflow to infinity.
        for (float f : o.frame.origin)
            if (!finite(f) || !finite(static_cast<float>(double(f) + o.frame.scale))) return Error::MalformedPayload;
        if (o.kind != ObjectKind::Surface && o.kind != ObjectKind::PointSet) return Error::MalformedPayload;
        if (o.kind == ObjectKind::PointSet && o.ellipsoid_count != 0) return Error::MalformedPayload;
        if (o.attributes & ~kAttrKnownMask) return Error::MalformedPayload;
        if ((o.attributes & kAttrColorAlpha) && !(o.attributes & kAttrColor)) return Error::MalformedPayload;
        // Format 1.7 (spec 23.1): a level below the position depth, and a batch exactly when mapped.
        if (o.map_level >= info.position_bits || (o.map_level == 0) != (o.map_batch == 0)) return Error::MalformedPayload;
        // Format 1.8 (spec 24.1): surface normals only on a surface with an exact layer and no normal in its records.
        if (o.surface_normals && (o.kind != ObjectKind::Surface || !o.exact_layer || o.has(kAttrNormal)))
            return Error::MalformedPayload;
        for (int i = 0; i < 2; ++i)
            if (!finite(o.texcoord_origin[i]) || !finite(o.texcoord_scale[i]) || o.texcoord_scale[i] < 0 ||
                !finite(static_cast<float>(double(o.texcoord_origin[i]) + o.texcoord_scale[i])))
                return Error::MalformedPayload;
    }
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// STREAM_INFO

std::vector<uint8_t> encode_stream_info_payload(const StreamInfo& info, uint16_t first_object, uint16_t count) {
    std::vector<uint8_t> out;
    const size_t entry_size = stream_info_entry_size(info);
    out.reserve(kStreamInfoFixedSize + count * entry_size);
    put_u16(out, static_cast<uint16_t>(kStreamInfoFixedSize));
    put_u16(out, static_cast<uint16_t>(entry_size));
    put_u16(out, info.packet_size);
    put_u8(out, info.position_bits);
    put_u8(out, info.normal_bits);
    put_u8(out, info.texcoord_bits);
    put_u8(out, info.color_bits);
    put_u8(out, info.ellipsoid_encoding);
    put_u8(out, 0);
    put_u32(out, info.content_id);
    put_u16(out, static_cast<uint16_t>(info.objects.size()));
    put_u16(out, first_object);
    put_u16(out, count);
    put_u16(out, info.grid_hint);
    put_f32(out, info.coverage_target);
    put_u32(out, info.seed);
    for (size_t i = first_object; i < size_t(first_object) + count && i < info.objects.size(); ++i) {
        const ObjectInfo& o = info.objects[i];
        for (float f : o.frame.origin) put_f32(out, f);
        put_f32(out, o.frame.scale);
        put_u32(out, o.ellipsoid_count);
        put_u32(out, o.point_count);
        put_u8(out, static_cast<uint8_t>(o.kind));
        put_u8(out, o.attributes);
        // flags (spec 19.1, 24.1); the other bits reserved
        put_u16(out, uint16_t((o.exact_layer ? kEntryExactLayer : 0) | (o.surface_normals ? kEntrySurfaceNormals : 0)));
        for (float f : o.texcoord_origin) put_f32(out, f);
        for (float f : o.texcoord_scale) put_f32(out, f);
        if (entry_size == kMappedEntrySize) {  // format 1.7 (spec 23.1)
            put_u8(out, o.map_level);
            put_u8(out, 0);
            put_u16(out, o.map_batch);
        }
    }
    return out;
}

size_t stream_info_entry_size(const StreamInfo& info) {
    for (const ObjectInfo& o : info.objects)
        if (o.mapped()) return kMappedEntrySize;
    return kObjectEntrySize;
}

std::optional<uint32_t> stream_info_content_id(uint8_t type, std::span<const uint8_t> payload) {
    if (type != static_cast<uint8_t>(PacketType::StreamInfo) || payload.size() < 16) return std::nullopt;
    return get_u32(payload.data() + 12);
}

Error decode_stream_info_payload(std::span<const uint8_t> payload, StreamInfoPart& out, uint8_t version_minor) {
    if (payload.size() < kStreamInfoFixedSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    const size_t info_size = get_u16(p);
    const size_t entry_size = get_u16(p + 2);
    if (info_size < kStreamInfoFixedSize || entry_size < kObjectEntrySize) return Error::MalformedPayload;
    StreamInfoPart part;
    StreamInfo& info = part.info;
    info.packet_size = get_u16(p + 4);
    info.position_bits = p[6];
    info.normal_bits = p[7];
    info.texcoord_bits = p[8];
    info.color_bits = p[9];
    info.ellipsoid_encoding = p[10];
    info.content_id = get_u32(p + 12);
    part.object_count = get_u16(p + 16);
    part.first_object = get_u16(p + 18);
    const size_t entry_count = get_u16(p + 20);
    info.grid_hint = get_u16(p + 22);
    info.coverage_target = get_f32(p + 24);
    info.seed = get_u32(p + 28);
    if (payload.size() != info_size + entry_count * entry_size) return Error::MalformedPayload;
    if (size_t(part.first_object) + entry_count > part.object_count) return Error::MalformedPayload;
    info.objects.resize(entry_count);
    for (size_t i = 0; i < entry_count; ++i) {
        const uint8_t* e = p + info_size + i * entry_size;
        ObjectInfo& o = info.objects[i];
        for (int k = 0; k < 3; ++k) o.frame.origin[k] = get_f32(e + 4 * k);
        o.frame.scale = get_f32(e + 12);
        o.ellipsoid_count = get_u32(e + 16);
        o.point_count = get_u32(e + 20);
        o.kind = static_cast<ObjectKind>(e[24]);
        o.attributes = e[25];
        o.exact_layer = (get_u16(e + 26) & kEntryExactLayer) != 0 && o.kind != ObjectKind::PointSet;
        o.surface_normals = version_minor >= kSurfaceNormalsMinor && (get_u16(e + 26) & kEntrySurfaceNormals) != 0;
        for (int k = 0; k < 2; ++k) o.texcoord_origin[k] = get_f32(e + 28 + 4 * k);
        for (int k = 0; k < 2; ++k) o.texcoord_scale[k] = get_f32(e + 36 + 4 * k);
        if (version_minor >= kMapMinor && entry_size >= kMappedEntrySize) {  // spec 23.1
            o.map_level = e[44];
            o.map_batch = get_u16(e + 46);
        }
    }
    if (check_stream_info(info) != Error::Ok) return Error::MalformedPayload;
    out = std::move(part);
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// ELLIPSOIDS

std::vector<uint8_t> encode_ellipsoids_payload(const EllipsoidBatch& batch) {
    std::vector<uint8_t> out;
    out.reserve(kBatchHeaderSize + batch.ellipsoids.size() * kEllipsoidBytes);
    put_batch_header(out, batch.first_index, batch.ellipsoids.size());
    for (const auto& q : batch.ellipsoids) {
        uint8_t bytes[kEllipsoidBytes];
        pack_ellipsoid(q, bytes);
        out.insert(out.end(), bytes, bytes + kEllipsoidBytes);
    }
    return out;
}

Error decode_ellipsoids_payload(std::span<const uint8_t> payload, EllipsoidBatch& out) {
    if (payload.size() < kBatchHeaderSize) return Error::MalformedPayload;
    const uint32_t first = get_u32(payload.data());
    const size_t count = get_u16(payload.data() + 4);
    if (payload.size() != kBatchHeaderSize + count * kEllipsoidBytes) return Error::MalformedPayload;
    if (uint64_t(first) + count > 0xFFFFFFFFull) return Error::MalformedPayload;
    EllipsoidBatch batch;
    batch.first_index = first;
    batch.ellipsoids.reserve(count);
    for (size_t i = 0; i < count; ++i)
        batch.ellipsoids.push_back(unpack_ellipsoid(payload.data() + kBatchHeaderSize + i * kEllipsoidBytes));
    out = std::move(batch);
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// POINTS

std::vector<uint8_t> encode_points_payload(const PointBatch& batch, const StreamInfo& info, const ObjectInfo& object) {
    std::vector<uint8_t> out;
    const size_t bits = point_record_bits(info, object);
    out.reserve(kBatchHeaderSize + (batch.points.size() * bits + 7) / 8);
    put_batch_header(out, batch.first_index, batch.points.size());
    BitWriter w(out);
    const int channels = object.color_channels();
    // A mapped record (spec 23.4) keeps the low bits of each coordinate: the offset in its cell.
    const int position_bits = int(record_position_bits(info, object));
    for (const QuantizedPoint& q : batch.points) {
        for (int i = 0; i < 3; ++i) w.put(q.position[i], position_bits);
        if (object.has(kAttrNormal))
            for (int i = 0; i < 2; ++i) w.put(q.normal[i], info.normal_bits);
        if (object.has(kAttrTexcoord))
            for (int i = 0; i < 2; ++i) w.put(q.texcoord[i], info.texcoord_bits);
        for (int i = 0; i < channels; ++i) w.put(q.color[i], info.color_bits);
    }
    return out;
}

Error decode_points_payload(std::span<const uint8_t> payload, const StreamInfo& info, const ObjectInfo& object,
                            PointBatch& out) {
    if (payload.size() < kBatchHeaderSize) return Error::MalformedPayload;
    const uint32_t first = get_u32(payload.data());
    const size_t count = get_u16(payload.data() + 4);
    const size_t bits = point_record_bits(info, object);
    if (payload.size() != kBatchHeaderSize + (count * bits + 7) / 8) return Error::MalformedPayload;
    if (uint64_t(first) + count > 0xFFFFFFFFull) return Error::MalformedPayload;
    PointBatch batch;
    batch.first_index = first;
    batch.points.resize(count);
    BitReader r(payload.subspan(kBatchHeaderSize));
    const int channels = object.color_channels();
    const int position_bits = int(record_position_bits(info, object));
    for (QuantizedPoint& q : batch.points) {
        for (int i = 0; i < 3; ++i) q.position[i] = r.get(position_bits);
        if (object.has(kAttrNormal))
            for (int i = 0; i < 2; ++i) q.normal[i] = r.get(info.normal_bits);
        if (object.has(kAttrTexcoord))
            for (int i = 0; i < 2; ++i) q.texcoord[i] = r.get(info.texcoord_bits);
        for (int i = 0; i < channels; ++i) q.color[i] = r.get(info.color_bits);
    }
    out = std::move(batch);
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// Capacities

size_t ellipsoids_per_packet(size_t packet_size) {
    size_t cap = payload_capacity(packet_size);
    return cap > kBatchHeaderSize ? std::min<size_t>((cap - kBatchHeaderSize) / kEllipsoidBytes, 0xFFFF) : 0;
}

size_t points_per_packet(size_t packet_size, const StreamInfo& info, const ObjectInfo& object) {
    size_t cap = payload_capacity(packet_size);
    size_t bits = point_record_bits(info, object);
    return cap > kBatchHeaderSize && bits > 0 ? std::min<size_t>((cap - kBatchHeaderSize) * 8 / bits, 0xFFFF) : 0;
}

size_t point_batch_size(const StreamInfo& info, const ObjectInfo& object) {
    const size_t fit = points_per_packet(info.packet_size, info, object);
    return object.mapped() ? std::min<size_t>(fit, object.map_batch) : fit;
}

size_t objects_per_stream_info_packet(size_t packet_size, size_t entry_size) {
    size_t cap = payload_capacity(packet_size);
    return cap > kStreamInfoFixedSize ? std::min<size_t>((cap - kStreamInfoFixedSize) / entry_size, 0xFFFF) : 0;
}

// ------------------------------------------------------------------------------------------
// Packetizing

namespace {

struct PendingBatch {
    uint16_t object = 0;
    std::vector<uint8_t> payload;
    double position = 0;  // where in the stream this batch falls, as a fraction of its object's points
};

}  // namespace

Error packetize_stream(const StreamInfo& info_in, const std::vector<ObjectContent>& contents, uint32_t stream_id,
                       StreamPackets& out) {
    if (check_stream_info(info_in) != Error::Ok) return Error::MalformedPayload;
    if (contents.size() != info_in.objects.size()) return Error::MalformedPayload;
    for (size_t i = 0; i < contents.size(); ++i) {
        const ObjectInfo& o = info_in.objects[i];
        if (contents[i].ellipsoids.size() != o.ellipsoid_count || contents[i].points.size() != o.point_count)
            return Error::MalformedPayload;
    }
    const size_t per_info = objects_per_stream_info_packet(info_in.packet_size, stream_info_entry_size(info_in));
    const size_t per_ellipsoids = ellipsoids_per_packet(info_in.packet_size);
    if (per_info == 0 || per_ellipsoids == 0) return Error::MalformedPayload;

    // Object payloads first: the content id is a checksum over them unless the caller chose one.
    std::vector<std::pair<uint16_t, std::vector<uint8_t>>> ellipsoid_payloads;
    std::vector<PendingBatch> point_batches;
    std::vector<std::pair<uint16_t, std::vector<uint8_t>>> map_payloads;  // format 1.7 (spec 23.3)
    std::vector<std::pair<uint16_t, std::vector<uint8_t>>> normals_payloads;  // format 1.8 (spec 24.2)
    std::vector<std::pair<uint16_t, std::vector<uint8_t>>> texcoords_payloads;  // format 1.14 (spec 30.1)
    for (size_t i = 0; i < contents.size(); ++i) {
        const auto& content = contents[i];
        const ObjectInfo& object = info_in.objects[i];
        if (object.mapped()) {
            std::vector<MapCell> cells;
            if (!point_map_cells(content.points, info_in, object, cells)) return Error::MalformedPayload;
            for (const PointMapFragment& f : plan_point_map(cells, object.map_level, info_in.packet_size))
                map_payloads.emplace_back(static_cast<uint16_t>(i), encode_point_map_payload(f, object.map_level));
        }
        for (size_t first = 0; first < content.ellipsoids.size(); first += per_ellipsoids) {
            EllipsoidBatch batch;
            batch.first_index = static_cast<uint32_t>(first);
            size_t n = std::min(per_ellipsoids, content.ellipsoids.size() - first);
            batch.ellipsoids.assign(content.ellipsoids.begin() + first, content.ellipsoids.begin() + first + n);
            ellipsoid_payloads.emplace_back(static_cast<uint16_t>(i), encode_ellipsoids_payload(batch));
        }
        if (object.surface_normals != !content.normals.empty()) return Error::MalformedPayload;
        if (object.surface_normals) {
            auto payloads = detail::normals_payloads(content.normals, info_in.packet_size, info_in.normal_bits);
            if (payloads.empty()) return Error::MalformedPayload;
            for (auto& payload : payloads) normals_payloads.emplace_back(static_cast<uint16_t>(i), std::move(payload));
        }
        if (!content.texcoord_sets.empty()) {  // format 1.14 (spec 30.3)
            if (!object.has(kAttrTexcoord)) return Error::MalformedPayload;
            auto payloads = detail::texcoords_payloads(content.texcoord_sets, uint32_t(content.points.size()),
                                                       info_in.packet_size);
            if (payloads.empty()) return Error::MalformedPayload;
            for (auto& payload : payloads) texcoords_payloads.emplace_back(static_cast<uint16_t>(i), std::move(payload));
        }
        const size_t per_points = point_batch_size(info_in, object);
        if (per_points == 0) return Error::MalformedPayload;
        const size_t batches = (content.points.size() + per_points - 1) / per_points;
        for (size_t b = 0; b < batches; ++b) {
            PointBatch batch;
            size_t first = b * per_points;
            batch.first_index = static_cast<uint32_t>(first);
            size_t n = std::min(per_points, content.points.size() - first);
            batch.points.assign(content.points.begin() + first, content.points.begin() + first + n);
            point_batches.push_back({static_cast<uint16_t>(i),
                                     encode_points_payload(batch, info_in, info_in.objects[i]),
                                     (b + 0.5) / static_cast<double>(batches)});
        }
    }
    // Every object refines at the same pace: interleave point batches by their relative position.
    std::stable_sort(point_batches.begin(), point_batches.end(),
                     [](const PendingBatch& a, const PendingBatch& b) { return a.position < b.position; });

    StreamInfo info = info_in;
    if (info.content_id == 0) {
        uint32_t crc = 0;
        for (const auto& [object, payload] : ellipsoid_payloads) crc = crc32c(payload.data(), payload.size(), crc);
        for (const auto& batch : point_batches) crc = crc32c(batch.payload.data(), batch.payload.size(), crc);
        for (const auto& [object, payload] : map_payloads) crc = crc32c(payload.data(), payload.size(), crc);
        for (const auto& [object, payload] : normals_payloads) crc = crc32c(payload.data(), payload.size(), crc);
        for (const auto& [object, payload] : texcoords_payloads) crc = crc32c(payload.data(), payload.size(), crc);
        info.content_id = crc == 0 ? 1 : crc;
    }

    StreamPackets packets;
    uint32_t sequence = 0;
    const bool mapped = stream_info_entry_size(info) == kMappedEntrySize;
    const bool surface_normals = std::any_of(info.objects.begin(), info.objects.end(),
                                             [](const ObjectInfo& o) { return o.surface_normals; });
    auto header = [&](PacketType type, uint16_t object) {
        PacketHeader h;
        h.type = static_cast<uint8_t>(type);
        // Format 1.7 types, and STREAM_INFO with the entries' map fields, say 1.7 (spec 23).
        if (type == PacketType::MappedPoints || type == PacketType::PointMap || (type == PacketType::StreamInfo && mapped))
            h.version_minor = kMapMinor;
        // Format 1.8: NORMALS, and STREAM_INFO with an entry's surface-normals flag (spec 24).
        if (type == PacketType::Normals || (type == PacketType::StreamInfo && surface_normals))
            h.version_minor = kSurfaceNormalsMinor;
        if (type == PacketType::Normals) h.flags |= kFlagSkippable;
        if (type == PacketType::Texcoords) h.version_minor = kTexcoordsMinor, h.flags |= kFlagSkippable;  // spec 30
        h.stream_id = stream_id;
        h.sequence = sequence++;
        h.object_id = object;
        return h;
    };
    size_t first = 0;
    do {
        size_t n = std::min(per_info, info.objects.size() - first);
        auto payload = encode_stream_info_payload(info, static_cast<uint16_t>(first), static_cast<uint16_t>(n));
        packets.stream_info.push_back(write_packet(header(PacketType::StreamInfo, kStreamObjectId), payload));
        first += n;
    } while (first < info.objects.size());
    for (const auto& [object, payload] : ellipsoid_payloads)
        packets.ellipsoids.push_back(write_packet(header(PacketType::Ellipsoids, object), payload));
    for (const auto& [object, payload] : map_payloads)
        packets.maps.push_back(write_packet(header(PacketType::PointMap, object), payload));
    for (const auto& batch : point_batches)
        packets.points.push_back(write_packet(
            header(info.objects[batch.object].mapped() ? PacketType::MappedPoints : PacketType::Points, batch.object),
            batch.payload));
    for (const auto& [object, payload] : normals_payloads)
        packets.normals.push_back(write_packet(header(PacketType::Normals, object), payload));
    for (const auto& [object, payload] : texcoords_payloads)
        packets.texcoords.push_back(write_packet(header(PacketType::Texcoords, object), payload));
    out = std::move(packets);
    return Error::Ok;
}

}  // namespace ellicast

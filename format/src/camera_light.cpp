// Cameras and punctual lights (format 1.10, spec 26): CAMERA and LIGHT payloads, their checks, and
// what a receiver keeps of them.
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>
#include <cmath>

namespace ellicast {

using namespace detail;

namespace {

// The real numbers pi and pi / 2 in double precision: a float is compared with them exactly (every
// f32 is a double, and no f32 lies between the double nearest pi and pi itself).
constexpr double kPi = 3.14159265358979323846;

bool finite(std::initializer_list<float> values) {
    return std::all_of(values.begin(), values.end(), [](float f) { return std::isfinite(f); });
}

std::string cut_name(const std::string& name) {
    if (name.size() <= 255) return name;
    size_t n = 255;
    while (n > 0 && (static_cast<uint8_t>(name[n]) & 0xC0) == 0x80) --n;
    return name.substr(0, n);
}

}  // namespace

bool valid_camera(const SceneCamera& c) {
    if (c.projection != CameraProjection::Perspective && c.projection != CameraProjection::Orthographic) return false;
    if (!finite({c.a, c.b, c.znear, c.zfar})) return false;
    if (c.projection == CameraProjection::Perspective)
        return !(c.a < 0) && c.b > 0 && double(c.b) < kPi && c.znear > 0 && !(c.zfar < 0) &&
               (c.zfar == 0 || c.zfar > c.znear);
    return c.a > 0 && c.b > 0 && !(c.znear < 0) && c.zfar > c.znear;
}

bool valid_light(const SceneLight& l) {
    if (static_cast<uint8_t>(l.type) > 2) return false;
    if (!finite({l.color[0], l.color[1], l.color[2], l.intensity, l.range, l.inner_cone, l.outer_cone})) return false;
    for (float c : l.color)
        if (c < 0 || c > 1) return false;
    if (l.intensity < 0 || l.range < 0) return false;
    if (l.type == LightType::Directional && l.range != 0) return false;
    if (l.type != LightType::Spot) return l.inner_cone == 0 && l.outer_cone == 0;
    return !(l.inner_cone < 0) && l.outer_cone > l.inner_cone && double(l.outer_cone) <= kPi / 2;
}

std::vector<uint8_t> encode_camera_payload(const SceneCamera& c) {
    const std::string name = cut_name(c.name);
    std::vector<uint8_t> out;
    out.reserve(kCameraFixedSize + name.size());
    put_u16(out, c.index);
    put_u16(out, c.camera_count);
    put_u8(out, static_cast<uint8_t>(c.projection));
    put_u8(out, static_cast<uint8_t>(name.size()));
    put_u16(out, 0);
    for (float f : {c.a, c.b, c.znear, c.zfar}) put_f32(out, f);
    out.insert(out.end(), name.begin(), name.end());
    return out;
}

Error decode_camera_payload(std::span<const uint8_t> payload, SceneCamera& out) {
    // Spec 26.2, rules 1..6 in order (one reason for all).
    if (payload.size() < kCameraFixedSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    if (payload.size() != kCameraFixedSize + p[5]) return Error::MalformedPayload;
    SceneCamera c;
    c.index = get_u16(p);
    c.camera_count = get_u16(p + 2);
    if (c.index >= c.camera_count || p[4] > 1) return Error::MalformedPayload;
    c.projection = static_cast<CameraProjection>(p[4]);
    c.a = get_f32(p + 8);
    c.b = get_f32(p + 12);
    c.znear = get_f32(p + 16);
    c.zfar = get_f32(p + 20);
    if (!valid_camera(c)) return Error::MalformedPayload;
    c.name.assign(reinterpret_cast<const char*>(p + kCameraFixedSize), p[5]);
    out = std::move(c);
    return Error::Ok;
}

std::vector<uint8_t> encode_light_payload(const SceneLight& l) {
    const std::string name = cut_name(l.name);
    std::vector<uint8_t> out;
    out.reserve(kLightFixedSize + name.size());
    put_u16(out, l.index);
    put_u16(out, l.light_count);
    put_u8(out, static_cast<uint8_t>(l.type));
    put_u8(out, static_cast<uint8_t>(name.size()));
    put_u16(out, 0);
    for (float f : {l.color[0], l.color[1], l.color[2], l.intensity, l.range, l.inner_cone, l.outer_cone}) put_f32(out, f);
    out.insert(out.end(), name.begin(), name.end());
    return out;
}

Error decode_light_payload(std::span<const uint8_t> payload, SceneLight& out) {
    // Spec 26.3, rules 1..7 in order (one reason for all).
    if (payload.size() < kLightFixedSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    if (payload.size() != kLightFixedSize + p[5]) return Error::MalformedPayload;
    SceneLight l;
    l.index = get_u16(p);
    l.light_count = get_u16(p + 2);
    if (l.index >= l.light_count || p[4] > 2) return Error::MalformedPayload;
    l.type = static_cast<LightType>(p[4]);
    for (size_t k = 0; k < 3; ++k) l.color[k] = get_f32(p + 8 + 4 * k);
    l.intensity = get_f32(p + 20);
    l.range = get_f32(p + 24);
    l.inner_cone = get_f32(p + 28);
    l.outer_cone = get_f32(p + 32);
    if (!valid_light(l)) return Error::MalformedPayload;
    l.name.assign(reinterpret_cast<const char*>(p + kLightFixedSize), p[5]);
    out = std::move(l);
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// What a receiver keeps (spec 26.2, 26.3: table size, then the record; the memory cap last).

namespace {

template <class Record>
Error take_record(const Record& r, uint16_t count, std::optional<uint16_t>& table_count,
                  std::map<uint16_t, Record>& table, const char* type, size_t& budget_used, size_t budget,
                  ReceiveCounters& counters, const std::function<Error(Error, std::string)>& reject) {
    const std::string what = std::string(type) + " " + std::to_string(r.index);
    if (table_count && *table_count != count)
        return reject(Error::StreamMismatch, std::string(type) + " table size " + std::to_string(count) +
                                                 " contradicts the " + std::to_string(*table_count) + " of earlier packets");
    if (auto it = table.find(r.index); it != table.end()) {
        if (!(it->second == r)) return reject(Error::StreamMismatch, what + " contradicts the one received before");
        ++counters.duplicates;
        return Error::Ok;
    }
    const size_t memory = kHeldPacketCost + r.name.size();
    if (budget_used + memory > budget)
        return reject(Error::MalformedPayload, what + ": the stream's scene data exceed this receiver's " +
                                                   std::to_string(budget) + "-byte memory limit for them");
    budget_used += memory;
    table_count = count;
    table.emplace(r.index, r);
    ++counters.accepted;
    return Error::Ok;
}

}  // namespace

Error ReceivedStream::take_camera(const PacketView& packet, uint64_t where) {
    SceneCamera c;
    if (decode_camera_payload(packet.payload, c) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "CAMERA payload inconsistent or out of range (length, index, projection, or a value glTF does "
                      "not allow: not finite, yfov not in (0, pi), znear, zfar, aspect ratio or magnification)");
    return take_record(c, c.camera_count, camera_count_, cameras_, "CAMERA", texture_bytes_, limits_.max_texture_bytes,
                       counters_, [&](Error e, std::string why) { return reject(where, e, std::move(why)); });
}

Error ReceivedStream::take_light(const PacketView& packet, uint64_t where) {
    SceneLight l;
    if (decode_light_payload(packet.payload, l) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "LIGHT payload inconsistent or out of range (length, index, light type, or a value "
                      "KHR_lights_punctual does not allow: not finite, colour outside [0, 1], negative intensity or "
                      "range, a range or cone on a light without one, cone angles out of order or above pi/2)");
    return take_record(l, l.light_count, light_count_, lights_, "LIGHT", texture_bytes_, limits_.max_texture_bytes,
                       counters_, [&](Error e, std::string why) { return reject(where, e, std::move(why)); });
}

}  // namespace ellicast

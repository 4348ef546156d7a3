// Surface normals (format 1.8, spec 24): NORMALS payloads, the surface normal of a point over the
// exact layer, and what a receiver keeps of NORMALS packets.
#include "ellicast/format.h"

#include "bytes.h"
#include "point_runs.h"

#include <algorithm>
#include <cmath>

namespace ellicast {

using namespace detail;

// ------------------------------------------------------------------------------------------
// The entries a receiver holds

namespace {
constexpr uint64_t kPageCost = sizeof(NormalPage) + 64;  // the page and its map node
constexpr uint64_t kSentCost = sizeof(std::pair<uint16_t, std::array<uint16_t, 2>>);
bool bit(const std::array<uint64_t, NormalEntries::kPagePoints / 64>& bits, uint32_t i) {
    return (bits[i / 64] >> (i % 64)) & 1u;
}
}  // namespace

bool NormalEntries::contains(uint32_t index) const {
    auto page = pages_.find(index / kPagePoints);
    return page != pages_.end() && bit(page->second.held, index % kPagePoints);
}

namespace {
// The entry of the point at offset `i` of a page that holds it.
NormalEntry entry_of(const NormalPage& page, uint32_t i) {
    NormalEntry e;
    if (bit(page.sent, i)) {
        auto it = std::lower_bound(page.normals.begin(), page.normals.end(), i,
                                   [](const auto& n, uint32_t offset) { return n.first < offset; });
        e.sent = true;
        e.normal = {it->second[0], it->second[1]};
    }
    return e;
}
}  // namespace

std::optional<NormalEntry> NormalEntries::find(uint32_t index) const {
    auto page = pages_.find(index / kPagePoints);
    const uint32_t i = index % kPagePoints;
    if (page == pages_.end() || !bit(page->second.held, i)) return std::nullopt;
    return entry_of(page->second, i);
}

bool NormalEntries::insert(uint32_t index, const NormalEntry& entry) {
    auto [page_it, made] = pages_.try_emplace(index / kPagePoints);
    if (made) memory_ += kPageCost;
    NormalPage& page = page_it->second;
    const uint32_t i = index % kPagePoints;
    if (bit(page.held, i)) return false;
    page.held[i / 64] |= uint64_t(1) << (i % 64);
    ++size_;
    if (entry.sent) {
        page.sent[i / 64] |= uint64_t(1) << (i % 64);
        auto at = std::lower_bound(page.normals.begin(), page.normals.end(), i,
                                   [](const auto& n, uint32_t offset) { return n.first < offset; });
        page.normals.insert(at, {uint16_t(i), {uint16_t(entry.normal[0]), uint16_t(entry.normal[1])}});
        memory_ += kSentCost;
    }
    return true;
}

NormalEntries::const_iterator::value_type NormalEntries::const_iterator::operator*() const {
    return {page_->first * kPagePoints + bit_, entry_of(page_->second, bit_)};
}

void NormalEntries::const_iterator::settle() {
    while (page_ != owner_->pages_.end()) {
        for (; bit_ < kPagePoints; ++bit_)
            if (bit(page_->second.held, bit_)) return;
        ++page_;
        bit_ = 0;
    }
    bit_ = 0;
}

NormalEntries::const_iterator& NormalEntries::const_iterator::operator++() {
    ++bit_;
    settle();
    return *this;
}

NormalEntries::const_iterator NormalEntries::begin() const {
    const_iterator it(this, pages_.begin(), 0);
    it.settle();
    return it;
}

NormalEntries::const_iterator NormalEntries::end() const { return const_iterator(this, pages_.end(), 0); }

// ------------------------------------------------------------------------------------------
// NORMALS payload (spec 24.2)

size_t normals_payload_size(size_t count, size_t sent, unsigned normal_bits) {
    return kNormalsHeaderSize + (count + 2 * size_t(normal_bits) * sent + 7) / 8;
}

std::vector<uint8_t> encode_normals_payload(const NormalsRun& run, unsigned normal_bits) {
    size_t sent = 0;
    for (const NormalEntry& e : run.entries) sent += e.sent;
    std::vector<uint8_t> out;
    out.reserve(normals_payload_size(run.entries.size(), sent, normal_bits));
    put_u32(out, run.first_index);
    put_u16(out, static_cast<uint16_t>(run.entries.size()));
    put_u16(out, static_cast<uint16_t>(sent));
    BitWriter w(out);
    for (const NormalEntry& e : run.entries) w.put(e.sent ? 1u : 0u, 1);
    for (const NormalEntry& e : run.entries)
        if (e.sent)
            for (int k = 0; k < 2; ++k) w.put(e.normal[k], int(normal_bits));
    return out;
}

Error check_normals_header(std::span<const uint8_t> payload) {
    if (payload.size() < kNormalsHeaderSize) return Error::MalformedPayload;
    const uint32_t first = get_u32(payload.data());
    const uint16_t count = get_u16(payload.data() + 4);
    const uint16_t sent = get_u16(payload.data() + 6);
    if (count == 0 || sent > count || uint64_t(first) + count > 0xFFFFFFFFull) return Error::MalformedPayload;
    return Error::Ok;
}

Error decode_normals_payload(std::span<const uint8_t> payload, unsigned normal_bits, NormalsRun& out) {
    if (check_normals_header(payload) != Error::Ok) return Error::MalformedPayload;
    const uint16_t count = get_u16(payload.data() + 4);
    const uint16_t sent = get_u16(payload.data() + 6);
    if (payload.size() != normals_payload_size(count, sent, normal_bits)) return Error::MalformedPayload;
    NormalsRun run;
    run.first_index = get_u32(payload.data());
    run.entries.resize(count);
    BitReader r(payload.subspan(kNormalsHeaderSize));
    size_t flagged = 0;
    for (NormalEntry& e : run.entries) {
        e.sent = r.get(1) != 0;
        flagged += e.sent;
    }
    if (flagged != sent) return Error::MalformedPayload;
    for (NormalEntry& e : run.entries)
        if (e.sent)
            for (int k = 0; k < 2; ++k) e.normal[k] = r.get(int(normal_bits));
    out = std::move(run);
    return Error::Ok;
}

std::vector<std::vector<uint8_t>> detail::normals_payloads(const std::vector<NormalEntry>& entries,
                                                           size_t packet_size, unsigned normal_bits) {
    std::vector<std::vector<uint8_t>> out;
    const size_t capacity_bits = (packet_size - kPacketOverhead - kNormalsHeaderSize) * 8;
    size_t first = 0;
    while (first < entries.size()) {
        // As many entries as fit: one flag bit each, and 2N bits more for each normal sent.
        size_t n = 0, bits = 0;
        while (first + n < entries.size() && n < 0xFFFF) {
            const size_t more = 1 + (entries[first + n].sent ? 2 * size_t(normal_bits) : 0);
            if (bits + more > capacity_bits) break;
            bits += more;
            ++n;
        }
        if (n == 0) return {};
        NormalsRun run;
        run.first_index = static_cast<uint32_t>(first);
        run.entries.assign(entries.begin() + std::ptrdiff_t(first), entries.begin() + std::ptrdiff_t(first + n));
        out.push_back(encode_normals_payload(run, normal_bits));
        first += n;
    }
    return out;
}

Error packetize_normals(const StreamInfo& info, uint16_t object_id, const std::vector<NormalEntry>& entries,
                        uint32_t stream_id, uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out) {
    if (object_id >= info.objects.size() || !info.objects[object_id].surface_normals ||
        entries.size() != info.objects[object_id].point_count || entries.empty() || info.packet_size < kMinPacketSize)
        return Error::MalformedPayload;
    const auto payloads = normals_payloads(entries, info.packet_size, info.normal_bits);
    if (payloads.empty()) return Error::MalformedPayload;
    uint32_t sequence = first_sequence;
    for (const auto& payload : payloads)
        out.push_back(write_packet(
            skippable_header(PacketType::Normals, kSurfaceNormalsMinor, stream_id, sequence++, object_id), payload));
    return Error::Ok;
}

// ------------------------------------------------------------------------------------------
// The surface normal of a point (spec 24.3)

namespace {

using I3 = std::array<int64_t, 3>;

I3 difference(const std::array<uint32_t, 3>& a, const std::array<uint32_t, 3>& b) {
    return {int64_t(a[0]) - int64_t(b[0]), int64_t(a[1]) - int64_t(b[1]), int64_t(a[2]) - int64_t(b[2])};
}

I3 cross(const I3& a, const I3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

bool zero(const I3& v) { return v[0] == 0 && v[1] == 0 && v[2] == 0; }

// Calls f(corner, e1, e2, m) for each corner of each triangle whose indices are all valid.
template <class F>
void for_each_corner(const std::vector<std::array<uint32_t, 3>>& positions,
                     std::span<const std::array<uint32_t, 3>> triangles, F&& f) {
    for (const auto& t : triangles) {
        if (t[0] >= positions.size() || t[1] >= positions.size() || t[2] >= positions.size()) continue;
        for (int c = 0; c < 3; ++c) {
            const uint32_t i = t[c], j = t[(c + 1) % 3], k = t[(c + 2) % 3];
            const I3 e1 = difference(positions[j], positions[i]);
            const I3 e2 = difference(positions[k], positions[i]);
            f(i, e1, e2, cross(e1, e2));
        }
    }
}

}  // namespace

SurfaceNormals surface_normals(const std::vector<std::array<uint32_t, 3>>& positions,
                               std::span<const std::array<uint32_t, 3>> triangles) {
    std::vector<std::array<double, 3>> sum(positions.size(), {0, 0, 0});
    std::vector<double> angles(positions.size(), 0);
    for_each_corner(positions, triangles, [&](uint32_t i, const I3& e1, const I3& e2, const I3& m) {
        if (zero(m)) return;
        const double l1 = std::sqrt(double(e1[0]) * e1[0] + double(e1[1]) * e1[1] + double(e1[2]) * e1[2]);
        const double l2 = std::sqrt(double(e2[0]) * e2[0] + double(e2[1]) * e2[1] + double(e2[2]) * e2[2]);
        const double lm = std::sqrt(double(m[0]) * m[0] + double(m[1]) * m[1] + double(m[2]) * m[2]);
        const double dot = double(e1[0]) * e2[0] + double(e1[1]) * e2[1] + double(e1[2]) * e2[2];
        const double theta = std::acos(std::clamp(dot / (l1 * l2), -1.0, 1.0));
        for (int k = 0; k < 3; ++k) sum[i][k] += theta * double(m[k]) / lm;
        angles[i] += theta;
    });
    SurfaceNormals out;
    out.normal.assign(positions.size(), {0, 0, 0});
    out.condition.assign(positions.size(), 0);
    for (size_t i = 0; i < positions.size(); ++i) {
        const double l = std::sqrt(sum[i][0] * sum[i][0] + sum[i][1] * sum[i][1] + sum[i][2] * sum[i][2]);
        if (!(l > 0) || !(angles[i] > 0)) continue;
        for (int k = 0; k < 3; ++k) out.normal[i][k] = float(sum[i][k] / l);
        out.condition[i] = float(l / angles[i]);
    }
    return out;
}

std::vector<char> surface_normal_defined(const std::vector<std::array<uint32_t, 3>>& positions,
                                         std::span<const std::array<uint32_t, 3>> triangles) {
    std::vector<char> defined(positions.size(), 0);
    for_each_corner(positions, triangles, [&](uint32_t i, const I3&, const I3&, const I3& m) {
        if (!zero(m)) defined[i] = 1;
    });
    return defined;
}

// ------------------------------------------------------------------------------------------
// What a receiver keeps (spec 24.2, steps 13 to 15)

Error ReceivedStream::take_normals(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                   uint64_t where) {
    const ObjectInfo& oi = *object.info;
    if (!oi.surface_normals)
        return reject(where, Error::MalformedPayload,
                      name + ": the object has no surface normals (its entry's flags bit 9 is clear)");
    NormalsRun run;
    if (decode_normals_payload(packet.payload, info_->normal_bits, run) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      name + ": its length does not match its count, sent count and the " +
                          std::to_string(info_->normal_bits) + "-bit normals, or its flags do not add up to its sent count");
    const uint64_t end = uint64_t(run.first_index) + run.entries.size();
    if (end > oi.point_count)
        return reject(where, Error::IndexOutOfRange,
                      name + ": points " + std::to_string(run.first_index) + "+" + std::to_string(run.entries.size()) +
                          " of " + std::to_string(oi.point_count));
    bool news = false;
    for (size_t k = 0; k < run.entries.size(); ++k) {
        const uint32_t index = uint32_t(run.first_index + k);
        const std::optional<NormalEntry> held = object.normal_entries.find(index);
        if (!held) news = true;
        else if (!(*held == run.entries[k]))
            return reject(where, Error::StreamMismatch,
                          name + ": the normal entry of point " + std::to_string(index) +
                              " differs from the one received before");
    }
    if (!news) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    for (size_t k = 0; k < run.entries.size(); ++k)
        object.normal_entries.insert(uint32_t(run.first_index + k), run.entries[k]);
    ++counters_.accepted;
    return Error::Ok;
}

}  // namespace ellicast

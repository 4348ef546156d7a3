// Shared by the fuzz targets: a receiver with small limits (so that the fuzzer's memory limit catches
// allocations out of proportion to the input, not the receiver's legitimate caps), and a pass over
// everything it holds, so that dequantization runs on whatever got in.
#pragma once

#include <ellicast/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace ellicast::fuzz {

inline ReceivedStream::Limits small_limits() {
    ReceivedStream::Limits limits;
    limits.max_pending_bytes = 1u << 20;
    limits.max_elements = 1u << 20;
    limits.max_rejections_kept = 64;
    limits.max_texture_bytes = 1u << 20;
    return limits;
}

// Dequantizes everything received; checks the invariants the receiver promises.
inline void touch_everything(const ReceivedStream& stream) {
    for (size_t i = 0; i < stream.objects().size(); ++i) {
        const ReceivedObject& o = stream.objects()[i];
        if (!o.info) continue;
        if (o.ellipsoids.size() > o.info->ellipsoid_count || o.points.size() > o.info->point_count) std::abort();
        for (const auto& [index, e] : o.ellipsoids)
            if (index >= o.info->ellipsoid_count) std::abort();
        for (const auto& [index, p] : o.points)
            if (index >= o.info->point_count) std::abort();
        for (const Ellipsoid& e : stream.ellipsoids(i))
            for (float r : e.radii)
                if (!(r >= 0)) std::abort();  // never negative, never NaN
        for (const SurfacePoint& p : stream.points(i))
            for (float c : p.position)
                if (std::isnan(c)) std::abort();
    }
    if (stream.rejections().size() > 64) std::abort();
}

// Cuts the input after its mode byte into datagrams (packets back to back, each cut at the length its
// own header declares, or what is left) and calls take(datagram) for each, a vector of exactly its
// bytes so that ASan sees any overread. Mode bit 0: reseal each datagram's CRC-32C first, so that
// mutated fields reach the payload decoders. Mode bit 1: give each datagram one byte more than its
// packet (the datagram length check).
template <class Take>
void for_each_datagram(uint8_t mode, const uint8_t* p, size_t left, Take take) {
    while (left > 0) {
        size_t n = left;
        if (left >= kHeaderSize) n = std::min(left, kPacketOverhead + (p[18] | (p[19] << 8)));
        const bool extra = (mode & 2) && n < left;
        if (extra) ++n;
        std::vector<uint8_t> datagram(p, p + n);
        if ((mode & 1) && n >= kPacketOverhead + (extra ? 1 : 0)) {
            const size_t body = n - kChecksumSize - (extra ? 1 : 0);
            const uint32_t crc = crc32c(datagram.data(), body);
            std::memcpy(datagram.data() + body, &crc, 4);
        }
        take(datagram);
        p += n;
        left -= n;
    }
}

}  // namespace ellicast::fuzz

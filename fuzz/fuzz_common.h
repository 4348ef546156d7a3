// Shared by the fuzz targets: a receiver with small limits (so that the fuzzer's memory limit catches
// allocations out of proportion to the input, not the receiver's legitimate caps), and a pass over
// everything it holds, so that dequantization runs on whatever got in.
#pragma once

#include <ellicast/format.h>

#include <cmath>
#include <cstdlib>

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
        if (!o.ellipsoids.empty() && o.ellipsoids.rbegin()->first >= o.info->ellipsoid_count) std::abort();
        if (!o.points.empty() && o.points.rbegin()->first >= o.info->point_count) std::abort();
        for (const Ellipsoid& e : stream.ellipsoids(i))
            for (float r : e.radii)
                if (!(r >= 0)) std::abort();  // never negative, never NaN
        for (const SurfacePoint& p : stream.points(i))
            for (float c : p.position)
                if (std::isnan(c)) std::abort();
    }
    if (stream.rejections().size() > 64) std::abort();
}

}  // namespace ellicast::fuzz

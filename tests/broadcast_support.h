// Synthetic streams for the broadcast tests: real packets made by the format library from
// random geometry, so that carousel, channel and UDP tests do not depend on the encoder.
#pragma once

#include <doctest/doctest.h>
#include <ellicast/format.h>

#include <cstdint>
#include <random>
#include <vector>

namespace ellicast::test {

// A one-object surface stream with `ellipsoids` ellipsoids and `points` points (with normals),
// cut into packets of `packet_size` bytes: STREAM_INFO, ELLIPSOIDS..., POINTS...
inline std::vector<std::vector<uint8_t>> synthetic_stream(uint32_t ellipsoids, uint32_t points,
                                                          uint32_t stream_id = 0x5EED, uint16_t packet_size = 1200,
                                                          uint32_t seed = 7) {
    StreamInfo info;
    info.packet_size = packet_size;
    ObjectInfo object;
    object.frame.origin = {-1, -1, -1};
    object.frame.scale = 2;
    object.ellipsoid_count = ellipsoids;
    object.point_count = points;
    object.attributes = kAttrNormal;
    info.objects.push_back(object);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    ObjectContent content;
    for (uint32_t i = 0; i < ellipsoids; ++i) {
        Ellipsoid e;
        e.center = {u(rng), u(rng), u(rng)};
        e.radii = {0.2f + 0.1f * u(rng), 0.2f + 0.1f * u(rng), 0.2f + 0.1f * u(rng)};
        content.ellipsoids.push_back(quantize_ellipsoid(e, object.frame));
    }
    for (uint32_t i = 0; i < points; ++i) {
        SurfacePoint p;
        p.position = {u(rng), u(rng), u(rng)};
        p.normal = {0, 0, 1};
        content.points.push_back(quantize_point(p, info, object));
    }
    StreamPackets sp;
    Error e = packetize_stream(info, {content}, stream_id, sp);
    REQUIRE(e == Error::Ok);
    std::vector<std::vector<uint8_t>> all;
    for (auto* part : {&sp.stream_info, &sp.ellipsoids, &sp.points})
        for (auto& p : *part) all.push_back(p);
    return all;
}

}  // namespace ellicast::test

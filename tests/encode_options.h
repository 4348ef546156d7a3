// Encoder settings and stream plumbing shared by the tests that encode (not part of the format-only
// test build).
#pragma once

#include "ellicast/codec/encoder.h"
#include "ellicast/format.h"

#include <doctest/doctest.h>

namespace ellicast::test {

// Coarse settings that keep the suite fast; the benchmarks run the defaults.
inline EncodeOptions fast_options() {
    EncodeOptions o;
    o.max_ellipsoids = 40;
    o.candidates = 200;
    o.grid = 32;
    return o;
}

// The scene tests' settings: fast_options' base ellipsoid budget at 80% coverage and no repair
// packets, so that every packet of a kind can be counted and lost on purpose.
inline EncodeOptions coarse_options() {
    EncodeOptions o;
    o.max_ellipsoids = 40;
    o.coverage = 0.8;
    o.repair_ratio = 0;
    return o;
}

// The tests of the points-only reconstruction and of the base (creases, sheets, samples, coverage):
// surface samples wherever the spacing asks and ellipsoids up to max_ellipsoids, as `ellicast encode
// --sample-budget -1 --base-ratio 0` makes them. The defaults size both by the object's bytes, which
// leaves a box with no samples and 13 ellipsoids: its exact layer brings it back, but a reconstruction
// from points alone has nothing on its faces.
inline EncodeOptions unbudgeted(EncodeOptions o = {}) {
    o.sample_budget = -1;
    o.base_ratio = 0;
    return o;
}

// Every packet of `encoded`, in transmission order, taken by a receiver.
inline ReceivedStream receive_every_packet(const EncodeResult& encoded) {
    StreamPackets packets;
    REQUIRE(packetize_stream(encoded.info, encoded.contents, 1, packets) == Error::Ok);
    ReceivedStream stream;
    size_t where = 0;
    for (auto* group : {&packets.stream_info, &packets.ellipsoids, &packets.maps, &packets.points, &packets.normals})
        for (const auto& p : *group) REQUIRE(stream.add_packet(p, where++) == Error::Ok);
    return stream;
}

}  // namespace ellicast::test

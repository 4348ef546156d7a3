// ellicast itself as a scheme of the comparison: the mesh encoded (codec/encoder.h), cut into
// packets (format.h), scheduled by the carousel (broadcast/carousel.h: b d1 b d2 ... b dn), and
// rebuilt from whatever packets arrived by the decoder (codec/decoder.h).
#pragma once

#include "ellicast/codec/encoder.h"
#include "ellicast/compare/schemes.h"

#include <functional>
#include <string>
#include <memory>

namespace ellicast::compare {

struct EllicastSettings {
    EncodeOptions encode;           // ellipsoid count, bit depths, packet size, seed
    double base_share = 0.15;       // carousel: share of the cycle's bytes spent on the base
    size_t chunk_packets = 0;       // carousel: POINTS packets per chunk (0: from base_share)
    int grid_resolution = 0;        // decoder grid (0: the stream's hint, else the decoder default)
    // Repair packets (format 1.2, spec 17) per POINTS packet of a block, interleaved by the carousel;
    // 0: none, the carousel repeats the POINTS packets (the schedule of format 1.1).
    double repair_ratio = 1.0;
    std::string name = "ellicast";  // the scheme's name in the report
};

class EllicastScheme : public Scheme {
public:
    // Encodes `mesh` and builds its carousel. Throws CompareError when encoding or scheduling fails.
    EllicastScheme(const Mesh& mesh, const EllicastSettings& settings);
    ~EllicastScheme() override;

    std::string name() const override;
    std::string describe() const override;
    uint64_t period() const override;
    uint32_t packet_at(uint64_t slot) const override;
    // Feeds the held packets to a ReceivedStream and decodes it: true when the decoder builds a
    // surface (it needs the stream info and at least one ellipsoid).
    bool reconstruct(const std::vector<uint32_t>& held, Mesh& out) const override;
    // The decoder shows a surface as soon as it holds the stream info and one ellipsoid packet: true
    // exactly then, without decoding.
    bool can_show(const std::vector<uint32_t>& held) const override;
    // Share of the surface points that the held packets carry, or that a receiver recovers from
    // them (a block of which any k packets are held).
    double data_fraction(const std::vector<uint32_t>& held) const override;
    // Every point held: every block has k of its packets, every other packet is held.
    bool complete(const std::vector<uint32_t>& held) const override;
    // Bytes of one carousel cycle (b d1 .. b dn): the comparison's unit of time. With repair packets
    // the schedule's period is several cycles.
    double cycle_bytes() const;

    // period_bytes(): the bytes of one carousel cycle, the channel cycle of the comparison.
    // Extra bytes the carousel spends repeating the base, relative to the stream sent once
    // ((n - 1) B / (B + D)): the redundancy the erasure-coded baseline gets.
    double repetition_overhead() const;
    // Share of the cycle's bytes that are base.
    double base_share() const;
    size_t base_packets() const;
    size_t point_packets() const;
    size_t ellipsoids() const { return ellipsoids_; }
    size_t points() const { return points_; }

private:
    struct State;
    std::unique_ptr<State> state_;
    size_t ellipsoids_ = 0, points_ = 0;
};

}  // namespace ellicast::compare

// The ways of sending one mesh through a lossy slotted channel that `ellicast compare` puts side by
// side. A scheme is a set of distinct packets (each a real packet of at most the packet size, with
// the ellicast header and CRC-32C) and a schedule saying which of them goes out in each slot; a
// receiver keeps every distinct packet that arrives, across cycles, and the scheme says what it can
// show from the packets held.
//
//   draco_whole.cpp     the Draco file cut into packets, repeated; decodable once every packet is held
//   draco_erasure.cpp   the same bytes plus Reed-Solomon parity (ISA-L); decodable from any k of each block:
//                       draco-rs-repeat (a little parity, repeated) and draco-mds (every slot a new symbol)
//   draco_clusters.cpp  spatial clusters that each compress into one packet and decode alone
//   ellicast_scheme.cpp ellicast's stream, scheduled by its carousel, rebuilt by its decoder
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/compare/compare_error.h"
#include "ellicast/converters/draco_mesh.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace ellicast::compare {

// Packet types of the baselines: experimental types of format 1.0, marked skippable so that an
// ellicast receiver that meets one ignores it.
inline constexpr uint8_t kDracoFragmentType = 0x80;  // a piece of a Draco file
inline constexpr uint8_t kDracoShardType = 0x81;     // a Reed-Solomon shard of a Draco file
inline constexpr uint8_t kDracoClusterType = 0x82;   // one cluster's whole Draco file
inline constexpr uint32_t kBaselineStreamId = 0xD7AC0;

class Scheme {
public:
    virtual ~Scheme() = default;

    // Short name used in the CSV and the plots ("ellicast", "draco-whole", ...).
    virtual std::string name() const = 0;
    // One sentence: what the scheme sends and how it is scheduled.
    virtual std::string describe() const = 0;

    // The distinct packets the scheme sends.
    const std::vector<std::vector<uint8_t>>& packets() const { return packets_; }
    // Transmissions after which the schedule repeats (the scheme's own period).
    virtual uint64_t period() const { return packets_.size(); }
    // Index into packets() of the packet of transmission `n` (counted from the sender's start).
    virtual uint32_t packet_at(uint64_t n) const { return static_cast<uint32_t>(n % packets_.size()); }

    // What a receiver holding the packets `held` (distinct indices into packets(), ascending) can
    // show: true with the mesh when it has a surface to show, false (out empty) when it has none.
    // Parses the real packet bytes: a damaged packet would be rejected by its CRC.
    virtual bool reconstruct(const std::vector<uint32_t>& held, Mesh& out) const = 0;

    // Share (0..1) of the model's data in the packets `held`: for ellicast the share of surface
    // points received; by default the share of distinct packets.
    virtual double data_fraction(const std::vector<uint32_t>& held) const {
        return packets_.empty() ? 0 : double(held.size()) / double(packets_.size());
    }

    // A key of what `held` shows: two held sets with the same key show the same thing and measure
    // the same (the experiment measures once per key). By default the set itself.
    virtual std::vector<uint32_t> outcome_key(const std::vector<uint32_t>& held) const { return held; }
    // Whether `held` gives something to show, at less cost than reconstruct() where a scheme can
    // tell (it must agree with reconstruct()). By default reconstruct() itself.
    virtual bool can_show(const std::vector<uint32_t>& held) const {
        Mesh mesh;
        return reconstruct(held, mesh);
    }
    // True when outcome_key() takes only a couple of values, so that measuring the scheme on the time
    // grid costs next to nothing: the experiment then does it in every trial, not only the curve trials.
    virtual bool few_outcomes() const { return false; }
    // Whether `held` gives the scheme's full quality: every packet (the default), the exact model
    // for the erasure-coded schemes.
    virtual bool complete(const std::vector<uint32_t>& held) const { return held.size() == packets_.size(); }

    // Bytes of one period of the schedule.
    uint64_t period_bytes() const;

protected:
    std::vector<std::vector<uint8_t>> packets_;
};

// Wraps `payload` in a packet of `type` (skippable) with the baseline stream id and `sequence`.
std::vector<uint8_t> baseline_packet(uint8_t type, uint32_t sequence, std::span<const uint8_t> payload);
// The payload of a baseline packet of `type`; empty when the bytes are not an intact packet of that
// type (bad CRC, other type, other stream).
std::span<const uint8_t> baseline_payload(std::span<const uint8_t> packet, uint8_t type);
// Largest payload of a packet of `packet_size` bytes.
size_t payload_capacity(size_t packet_size);

// ---------------------------------------------------------------------------------------------
// Draco whole mesh: the Draco file cut into packets of the packet size, sent round robin; the receiver
// can decode only once it holds every packet.
class DracoWhole : public Scheme {
public:
    DracoWhole(const Mesh& mesh, const DracoSettings& settings, size_t packet_size);
    std::string name() const override { return "draco-whole"; }
    std::string describe() const override;
    bool reconstruct(const std::vector<uint32_t>& held, Mesh& out) const override;
    // Decodable exactly when every packet is held: the key is that one bit.
    std::vector<uint32_t> outcome_key(const std::vector<uint32_t>& held) const override {
        return {complete(held) ? 1u : 0u};
    }
    bool can_show(const std::vector<uint32_t>& held) const override { return complete(held); }
    bool few_outcomes() const override { return true; }
    const std::vector<uint8_t>& draco_bytes() const { return draco_; }

private:
    std::vector<uint8_t> draco_;
};

// Cuts `bytes` into fragments that each fit a payload of `capacity` bytes after an 8-byte fragment
// header (file size, fragment count, fragment index): the payloads of DracoWhole's packets.
std::vector<std::vector<uint8_t>> fragment_payloads(std::span<const uint8_t> bytes, size_t capacity);

// ---------------------------------------------------------------------------------------------
// Draco + erasure code: the Draco file in k data shards of one packet each (the systematic source
// symbols), plus Reed-Solomon parity shards (ISA-L), in blocks of at most 255 shards, interleaved in
// time block by block: shard 0 of every block, then shard 1 of every block, ... A receiver decodes a
// block from any k of its shards and the file once every block is decoded. The two schemes below
// differ only in how many parity shards each block gets.
class DracoErasure : public Scheme {
public:
    struct Block {
        int data = 0;    // k
        int parity = 0;  // m
    };
    bool reconstruct(const std::vector<uint32_t>& held, Mesh& out) const override;
    // Decodable exactly when every block holds k distinct shards: the key is that one bit.
    std::vector<uint32_t> outcome_key(const std::vector<uint32_t>& held) const override;
    bool can_show(const std::vector<uint32_t>& held) const override { return decodable(held); }
    bool complete(const std::vector<uint32_t>& held) const override { return decodable(held); }
    bool few_outcomes() const override { return true; }

    // True when every block holds at least k distinct shards (read from the packets' headers).
    bool decodable(const std::vector<uint32_t>& held) const;
    const std::vector<Block>& blocks() const { return blocks_; }
    size_t data_shards() const;
    size_t parity_shards() const;
    const std::vector<uint8_t>& draco_bytes() const { return draco_; }
    // The block and the shard index inside it of packet `packet`.
    std::pair<int, int> shard_of(uint32_t packet) const;

protected:
    // Encodes `mesh` and cuts it into data shards; `plan` gives the blocks for k_total data shards
    // (each k + m <= 255, the k summing to k_total).
    DracoErasure(const Mesh& mesh, const DracoSettings& settings, size_t packet_size,
                 const std::function<std::vector<Block>(size_t k_total)>& plan);
    std::string layout() const;  // "82 data + 13 parity packets in 1 block"

    std::vector<uint8_t> draco_;
    size_t shard_bytes_ = 0;
    std::vector<Block> blocks_;
};

// The Draco file with m = ceil(k * redundancy) parity shards per block, its k + m packets repeated
// round robin: a receiver that misses more than m shards of a block waits for their repetition.
class DracoRsRepeat : public DracoErasure {
public:
    DracoRsRepeat(const Mesh& mesh, const DracoSettings& settings, size_t packet_size, double redundancy);
    std::string name() const override { return "draco-rs-repeat"; }
    std::string describe() const override;
    double redundancy() const { return redundancy_; }

private:
    double redundancy_;
};

// The strongest Draco carousel: a maximum-distance-separable code with every block as long as the
// field allows (k data + 255 - k parity shards, k <= max_block_data), so that every slot of a cycle
// carries a symbol not sent before (no symbol goes out twice before every symbol of its block has
// gone out once). With no loss a receiver decodes after exactly k_total slots (plus the interleaving
// of unequal blocks), whenever it tunes in.
class DracoMds : public DracoErasure {
public:
    static constexpr int kDefaultBlockData = 85;  // code rate 1/3: a block survives 2/3 loss in one period
    DracoMds(const Mesh& mesh, const DracoSettings& settings, size_t packet_size, int max_block_data = kDefaultBlockData);
    std::string name() const override { return "draco-mds"; }
    std::string describe() const override;
    int max_block_data() const { return max_block_data_; }

private:
    int max_block_data_;
};

// ---------------------------------------------------------------------------------------------
// Draco per cluster: the triangles cut into spatially compact clusters (recursive bisection of
// triangle centroids along the longest axis) until each cluster's own Draco file fits one packet;
// every cluster decodes alone, on one position grid shared by all (no cracks between clusters), and
// a lost packet is a hole.
class DracoClusters : public Scheme {
public:
    DracoClusters(const Mesh& mesh, const DracoSettings& settings, size_t packet_size);
    std::string name() const override { return "draco-clusters"; }
    std::string describe() const override;
    bool reconstruct(const std::vector<uint32_t>& held, Mesh& out) const override;

    size_t cluster_count() const { return packets_.size(); }
    // The triangles (indices into the input mesh) of each cluster, in packet order.
    const std::vector<std::vector<uint32_t>>& cluster_triangles() const { return clusters_; }
    // Mean fill of the packets (payload bytes / capacity).
    double mean_fill() const { return mean_fill_; }

private:
    std::vector<std::vector<uint32_t>> clusters_;
    double mean_fill_ = 0;
};

// The sub-mesh of `mesh` made of the triangles `triangles` (vertices renumbered, attributes kept).
Mesh submesh(const Mesh& mesh, std::span<const uint32_t> triangles);

// Concatenates meshes (vertices are not welded).
Mesh concatenate(const std::vector<Mesh>& parts);

}  // namespace ellicast::compare

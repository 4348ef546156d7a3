// The carousel schedule b d1 b d2 ... b dn and its figures (overhead, waits without and with loss).
#include <ellicast/broadcast/carousel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <tuple>
#include <random>
#include <set>

namespace ellicast::broadcast {

// The base is what a receiver needs to show a model: stream info, ellipsoids, scene, materials.
// Points, normals (format 1.8), further texture coordinates (1.14), skin weights, morph targets, texture fragments, animations and the exact layer (connectivity, or format 1.11's coded mesh) are detail: sent once per
// cycle, spread over the chunks, so that a large texture does not ride along with every repetition of
// the base.
bool is_base_packet(const PacketHeader& header) {
    return !is_points_type(header.type) &&
           header.type != static_cast<uint8_t>(PacketType::TextureFragment) &&
           header.type != static_cast<uint8_t>(PacketType::Animation) &&
           header.type != static_cast<uint8_t>(PacketType::Normals) &&
           header.type != static_cast<uint8_t>(PacketType::Texcoords) &&
           header.type != static_cast<uint8_t>(PacketType::JointWeights) &&
           header.type != static_cast<uint8_t>(PacketType::MorphDeltas) &&
           header.type != static_cast<uint8_t>(PacketType::MorphAnimation) &&
           !is_exact_layer_type(header.type) && !is_exact_layer_repair_type(header.type);
}

uint64_t Carousel::bytes_before(uint64_t slot) const {
    if (cycle.empty()) return 0;
    return (slot / cycle.size()) * cycle_bytes + cycle_offsets[slot % cycle.size()];
}

namespace {

// Number of chunks n that brings n B / (n B + D) closest to `share`.
size_t chunks_for_share(uint64_t base_bytes, uint64_t data_bytes, size_t data_packets, double share) {
    if (data_packets == 0 || base_bytes == 0) return 1;
    double n = share * static_cast<double>(data_bytes) / ((1.0 - share) * static_cast<double>(base_bytes));
    size_t best = 1;
    double best_error = std::numeric_limits<double>::infinity();
    // The achieved share is monotone in n: look at the two integers around the real solution.
    for (double candidate : {std::floor(n), std::ceil(n)}) {
        size_t c = static_cast<size_t>(std::clamp(candidate, 1.0, static_cast<double>(data_packets)));
        double achieved = double(c) * double(base_bytes) / (double(c) * double(base_bytes) + double(data_bytes));
        if (std::abs(achieved - share) < best_error) {
            best_error = std::abs(achieved - share);
            best = c;
        }
    }
    return best;
}

}  // namespace

bool build_carousel(const std::vector<std::vector<uint8_t>>& packets, const CarouselOptions& options, Carousel& out,
                    std::string& error) {
    out = Carousel{};
    out.restamp_sequence = options.restamp_sequence;
    if (packets.empty()) {
        error = "the stream holds no packet";
        return false;
    }
    if (packets.size() > std::numeric_limits<uint32_t>::max()) {
        error = "the stream holds more packets than a carousel can index";
        return false;
    }
    if (options.chunk_packets == 0 && !(options.base_share > 0 && options.base_share < 1)) {
        error = "the base share must lie strictly between 0 and 1 (got " + std::to_string(options.base_share) + ")";
        return false;
    }
    std::vector<uint32_t> manifests, repairs;
    for (size_t i = 0; i < packets.size(); ++i) {
        PacketView view;
        Error e = parse_packet(packets[i], view);
        if (e != Error::Ok) {
            error = "packet " + std::to_string(i) + " is not a valid ellicast packet: " + error_name(e);
            return false;
        }
        out.sizes.push_back(static_cast<uint32_t>(packets[i].size()));
        if (view.header.type == static_cast<uint8_t>(PacketType::Manifest)) {
            manifests.push_back(static_cast<uint32_t>(i));
            continue;
        }
        if (view.header.type == static_cast<uint8_t>(PacketType::PointsRepair)) {
            repairs.push_back(static_cast<uint32_t>(i));
            continue;
        }
        if (view.header.type == static_cast<uint8_t>(PacketType::PointMap)) {
            out.maps.push_back(static_cast<uint32_t>(i));
            out.map_bytes += packets[i].size();
            continue;
        }
        if (is_base_packet(view.header)) {
            out.base.push_back(static_cast<uint32_t>(i));
            if (view.header.type == static_cast<uint8_t>(PacketType::StreamInfo))
                out.stream_info.push_back(static_cast<uint32_t>(i));
            out.base_bytes += packets[i].size();
        } else {
            out.data.push_back(static_cast<uint32_t>(i));
            out.data_bytes += packets[i].size();
        }
    }

    // Repair blocks (spec 17.5): the POINTS packets a block's range holds are its sources; each
    // cycle gives a block as many data slots as it has sources, filled with its source and repair
    // packets evenly interleaved, each sent once before any is sent again.
    std::vector<std::vector<size_t>> block_positions;  // per block: positions in out.data of its sources
    std::vector<std::vector<uint32_t>> block_sequence;  // per block: one pass over its symbols
    if (!repairs.empty()) {
        struct Pending {
            RepairBlock block;
            std::vector<std::pair<uint8_t, uint32_t>> rows;  // (row, input index)
        };
        std::map<std::pair<uint16_t, uint32_t>, Pending> blocks;  // (object, first_index)
        for (uint32_t r : repairs) {
            PacketView view;
            parse_packet(packets[r], view);
            RepairPacket repair;
            if (decode_repair_payload(view.payload, repair) != Error::Ok) {
                error = "packet " + std::to_string(r) + ": a malformed POINTS_REPAIR packet";
                return false;
            }
            Pending& b = blocks[{view.header.object_id, repair.block.first_index}];
            if (b.rows.empty()) b.block = repair.block;
            if (!b.block.same_block(repair.block)) {
                error = "packet " + std::to_string(r) + ": a POINTS_REPAIR packet whose block contradicts another's";
                return false;
            }
            b.rows.push_back({repair.row, r});
        }
        std::map<std::pair<uint16_t, uint32_t>, std::vector<size_t>> sources;
        for (size_t k = 0; k < out.data.size(); ++k) {
            PacketView view;
            parse_packet(packets[out.data[k]], view);
            if (!is_points_type(view.header.type) || view.payload.size() < 4) continue;
            const uint32_t first = uint32_t(view.payload[0]) | uint32_t(view.payload[1]) << 8 |
                                   uint32_t(view.payload[2]) << 16 | uint32_t(view.payload[3]) << 24;
            auto it = blocks.upper_bound({view.header.object_id, first});
            if (it == blocks.begin()) continue;
            --it;
            if (it->first.first != view.header.object_id ||
                first >= uint64_t{it->second.block.first_index} + it->second.block.point_count)
                continue;
            sources[it->first].push_back(k);
        }
        for (auto& [key, b] : blocks) {
            auto s = sources.find(key);
            if (s == sources.end()) continue;  // no POINTS packet to interleave with: not scheduled
            std::sort(b.rows.begin(), b.rows.end());
            b.rows.erase(std::unique(b.rows.begin(), b.rows.end(),
                                     [](const auto& x, const auto& y) { return x.first == y.first; }),
                         b.rows.end());
            // How many repair rows to send: the ratio asked for (all by default), as near as a period
            // of at most 16 cycles allows: with k slots a cycle, k + R symbols repeat after
            // (k + R) / gcd(k + R, k) cycles.
            const size_t k = s->second.size();
            const double target = options.repair_ratio >= 0 ? options.repair_ratio * double(k) : double(b.rows.size());
            size_t best = 0;
            for (size_t r = 0; r <= b.rows.size(); ++r) {
                if ((k + r) / std::gcd(k + r, k) > 16) continue;
                if (std::abs(double(r) - target) <= std::abs(double(best) - target) + 1e-9) best = r;
            }
            b.rows.resize(best);
            if (b.rows.empty()) continue;  // sent as plain POINTS packets
            CarouselBlock cb;
            cb.needed = b.block.source_count();
            for (size_t pos : s->second) cb.symbols.push_back(out.data[pos]);
            for (const auto& [row, index] : b.rows) cb.symbols.push_back(index);
            cb.sources = s->second.size();
            block_positions.push_back(s->second);
            out.blocks.push_back(std::move(cb));
        }
        // The period: every block's pass of n symbols over its k slots a cycle repeats after
        // n / gcd(n, k) cycles. Kept at most 64 cycles by sending whole multiples of k repairs.
        auto period_of = [&](const std::vector<CarouselBlock>& bs) {
            uint64_t period = 1;
            for (const CarouselBlock& b : bs) {
                const uint64_t n = b.symbols.size(), k = b.sources;
                period = std::lcm(period, n / std::gcd(n, k));
                if (period > 64) return period;
            }
            return period;
        };
        if (period_of(out.blocks) > 64)
            for (CarouselBlock& b : out.blocks) b.symbols.resize(b.sources * (b.symbols.size() / b.sources));
        if (period_of(out.blocks) > 64)
            for (CarouselBlock& b : out.blocks) b.symbols.resize(b.sources);
        out.period_cycles = static_cast<size_t>(period_of(out.blocks));
        // Spread each block's slots over the whole cycle: the slots the blocks own, in cycle order,
        // go to the blocks in the order of (j + 1/2) / k_b, so that a receiver short of a few symbols
        // of a block gets its next slots soon wherever it is in the cycle (with the blocks one after
        // the other, the last block's next slots came half a cycle later: 1.26 instead of 1.1 cycles
        // to every point at 10% loss).
        std::vector<size_t> owned;
        std::vector<std::tuple<double, size_t, size_t>> order;  // (fraction, block, j)
        for (size_t b = 0; b < block_positions.size(); ++b)
            for (size_t j = 0; j < block_positions[b].size(); ++j) {
                owned.push_back(block_positions[b][j]);
                order.emplace_back((double(j) + 0.5) / double(block_positions[b].size()), b, j);
            }
        std::sort(owned.begin(), owned.end());
        std::sort(order.begin(), order.end());
        for (size_t r = 0; r < order.size(); ++r) block_positions[std::get<1>(order[r])][std::get<2>(order[r])] = owned[r];
        for (CarouselBlock& b : out.blocks) {
            // Sources and repairs evenly interleaved (symbol t is a source when floor((t+1)k/n) grows).
            const size_t n = b.symbols.size(), k = b.sources;
            std::vector<uint32_t> pass;
            size_t next_source = 0, next_repair = k;
            for (size_t t = 0; t < n; ++t)
                pass.push_back((t + 1) * k / n > t * k / n ? b.symbols[next_source++] : b.symbols[next_repair++]);
            block_sequence.push_back(std::move(pass));
            for (size_t i = k; i < n; ++i) out.repairs.push_back(b.symbols[i]);
        }
    }
    // The data sent in each cycle of the period, position by position.
    std::vector<std::vector<uint32_t>> cycle_data(out.period_cycles, out.data);
    for (size_t c = 0; c < out.period_cycles; ++c)
        for (size_t b = 0; b < out.blocks.size(); ++b) {
            const size_t k = out.blocks[b].sources, n = block_sequence[b].size();
            for (size_t j = 0; j < k; ++j) cycle_data[c][block_positions[b][j]] = block_sequence[b][(c * k + j) % n];
        }

    // MANIFEST parts (signed streams, spec 16.4): a part that lists only detail packets (POINTS,
    // POINTS_REPAIR, TEXTURE_FRAGMENT) goes just before the first of them in each cycle and again
    // half-way through them; any other part (it lists base packets, or none of this stream's) goes
    // with the base.
    std::vector<std::vector<PacketDigest>> detail_listed;  // per detail manifest: its digests
    // The parts that list a STREAM_INFO or an ELLIPSOIDS packet (what a first picture needs): one of
    // them, in turn, after every repeat of the stream info inside a chunk, since a receiver with a key
    // can use those packets only once their part has verified, and the base alone comes too rarely.
    std::vector<uint32_t> first_picture_manifests;
    if (!manifests.empty()) {
        std::set<PacketDigest> detail_digests, base_digests, first_picture;
        for (uint32_t d : out.data) detail_digests.insert(packet_digest(packets[d]));
        for (uint32_t r : repairs) detail_digests.insert(packet_digest(packets[r]));
        for (uint32_t b : out.base) {
            base_digests.insert(packet_digest(packets[b]));
            if (packets[b][6] == static_cast<uint8_t>(PacketType::StreamInfo) ||
                packets[b][6] == static_cast<uint8_t>(PacketType::Ellipsoids))
                first_picture.insert(packet_digest(packets[b]));
        }
        std::vector<uint32_t> base_manifests;
        for (uint32_t m : manifests) {
            PacketView view;
            ManifestPart part;
            parse_packet(packets[m], view);
            std::vector<PacketDigest> listed;
            bool lists_base = false, lists_first_picture = false;
            if (decode_manifest_payload(view.payload, part) == Error::Ok)
                for (const PacketDigest& d : part.digests) {
                    if (detail_digests.count(d)) listed.push_back(d);
                    else if (base_digests.count(d)) lists_base = true;
                    lists_first_picture |= first_picture.count(d) > 0;
                }
            if (lists_first_picture) first_picture_manifests.push_back(m);
            if (lists_base || listed.empty()) {
                base_manifests.push_back(m);
                continue;
            }
            out.detail_manifests.push_back(m);
            detail_listed.push_back(std::move(listed));
        }
        // Base order: the input order, MANIFEST parts included.
        for (uint32_t m : base_manifests) {
            out.base.push_back(m);
            out.base_bytes += packets[m].size();
        }
        std::sort(out.base.begin(), out.base.end());
    }
    // Format 1.7: a map no larger than the rest of the base goes whole with every repetition of the
    // base and after every stream info repeat; a larger one `map_rounds` times a cycle.
    const bool small_map = out.map_bytes <= out.base_bytes;
    const size_t map_rounds = std::max<size_t>(1, options.map_rounds);
    size_t chunks;
    if (options.chunk_packets > 0) {
        chunks = out.data.empty() ? 1 : (out.data.size() + options.chunk_packets - 1) / options.chunk_packets;
    } else {
        // A large map's rounds count as data: the chunks are those the base alone asks for.
        chunks = small_map
                     ? chunks_for_share(out.base_bytes + out.map_bytes, out.data_bytes, out.data.size(), options.base_share)
                     : chunks_for_share(out.base_bytes, out.data_bytes + map_rounds * out.map_bytes, out.data.size(),
                                        options.base_share);
        chunks = std::max(chunks, std::min(options.min_base_repetitions, std::max<size_t>(out.data.size(), 1)));
    }
    chunks = std::max<size_t>(chunks, 1);
    // Spread the points packets evenly over the chunks (sizes differ by at most one packet).
    out.chunk_count = chunks;
    out.chunk_packets = out.data.empty() ? 0 : (out.data.size() + chunks - 1) / chunks;
    // Map fragments sent with the bases in a cycle, in turn (at least one with every base).
    const size_t map_sends = out.maps.empty() ? 0
                             : small_map     ? chunks * out.maps.size()
                                             : std::max(map_rounds * out.maps.size(), chunks);
    size_t next_info = 0, next_manifest = 0, next_map = 0;
    for (size_t period = 0; period < out.period_cycles; ++period) {
        const std::vector<uint32_t>& data = cycle_data[period];
        // This cycle's detail MANIFEST parts: before the first packet each lists, and half-way.
        std::vector<std::vector<uint32_t>> manifests_before(data.size());
        if (!detail_listed.empty()) {
            std::map<PacketDigest, size_t> position;
            for (size_t k = 0; k < data.size(); ++k) position.emplace(packet_digest(packets[data[k]]), k);
            for (size_t m = 0; m < detail_listed.size(); ++m) {
                std::vector<size_t> listed;
                for (const PacketDigest& d : detail_listed[m])
                    if (auto it = position.find(d); it != position.end()) listed.push_back(it->second);
                if (listed.empty()) continue;
                std::sort(listed.begin(), listed.end());
                manifests_before[listed.front()].push_back(out.detail_manifests[m]);
                if (listed.size() > 1) manifests_before[listed[listed.size() / 2]].push_back(out.detail_manifests[m]);
            }
        }
        size_t next = 0;
        for (size_t c = 0; c < chunks; ++c) {
            for (uint32_t b : out.base) out.cycle.push_back({b, true, false, static_cast<uint32_t>(c)});
            // This repetition's share of the map's fragments.
            for (size_t k = c * map_sends / chunks; k < (c + 1) * map_sends / chunks; ++k)
                out.cycle.push_back({out.maps[k % out.maps.size()], true, false, static_cast<uint32_t>(c)});
            size_t end = data.size() * (c + 1) / chunks;
            uint64_t chunk_bytes = 0;
            for (size_t in_chunk = 1; next < end; ++next, ++in_chunk) {
                for (uint32_t m : manifests_before[next]) {
                    out.cycle.push_back({m, false, false, static_cast<uint32_t>(c)});
                    chunk_bytes += packets[m].size();
                    out.repeat_bytes += packets[m].size();
                }
                out.cycle.push_back({data[next], false, false, static_cast<uint32_t>(c)});
                chunk_bytes += packets[data[next]].size();
                // A stream info part after every k-th packet, unless the base comes next anyway.
                if (options.stream_info_every > 0 && !out.stream_info.empty() && in_chunk % options.stream_info_every == 0 &&
                    next + 1 < end) {
                    const uint32_t info = out.stream_info[next_info++ % out.stream_info.size()];
                    out.cycle.push_back({info, true, true, static_cast<uint32_t>(c)});
                    chunk_bytes += packets[info].size();
                    out.repeat_bytes += packets[info].size();
                    // Format 1.7: a small map's next fragment in turn, so that a small object's one
                    // fragment is not lost with every base of a cycle (points cannot be placed without
                    // it). A large map comes often enough with the bases: more copies of the bunny's
                    // lengthened the cycle 4% and the wait for every point with it.
                    if (small_map && !out.maps.empty()) {
                        const uint32_t map = out.maps[next_map++ % out.maps.size()];
                        out.cycle.push_back({map, true, true, static_cast<uint32_t>(c)});
                        chunk_bytes += packets[map].size();
                        out.repeat_bytes += packets[map].size();
                    }
                    if (!first_picture_manifests.empty()) {
                        const uint32_t m = first_picture_manifests[next_manifest++ % first_picture_manifests.size()];
                        out.cycle.push_back({m, true, true, static_cast<uint32_t>(c)});
                        chunk_bytes += packets[m].size();
                        out.repeat_bytes += packets[m].size();
                    }
                }
            }
            out.max_chunk_bytes = std::max(out.max_chunk_bytes, chunk_bytes);
        }
    }
    out.cycle_offsets.reserve(out.cycle.size() + 1);
    uint64_t offset = 0;
    for (const auto& entry : out.cycle) {
        out.cycle_offsets.push_back(offset);
        offset += out.sizes[entry.packet];
    }
    out.cycle_offsets.push_back(offset);
    out.cycle_bytes = offset;
    return true;
}

std::vector<uint8_t> carousel_packet(const Carousel& carousel, const std::vector<std::vector<uint8_t>>& packets,
                                     uint64_t slot) {
    std::vector<uint8_t> bytes = packets[carousel.packet_at(slot)];
    if (carousel.restamp_sequence) restamp_packet(bytes, static_cast<uint32_t>(slot));  // valid: checked when built
    return bytes;
}

namespace {

// What a receiver waits for: single packets, and (repair) any `needed` distinct symbols of a block.
struct Needs {
    std::vector<bool> single;           // by input index
    std::vector<int32_t> block_of;      // by input index: its block, or -1
    std::vector<size_t> block_needed;   // per block
    size_t total = 0;                   // singles + the sum of block_needed
};

Needs needs_of(const Carousel& c, WaitFor what) {
    Needs n;
    n.single.assign(c.sizes.size(), false);
    n.block_of.assign(c.sizes.size(), -1);
    for (uint32_t b : c.base) n.single[b] = true, ++n.total;
    if (what != WaitFor::Everything) return n;
    for (uint32_t m : c.maps) n.single[m] = true, ++n.total;  // format 1.7: points are placed by the map
    for (size_t b = 0; b < c.blocks.size(); ++b) {
        for (uint32_t p : c.blocks[b].symbols) n.block_of[p] = static_cast<int32_t>(b);
        n.block_needed.push_back(std::min(c.blocks[b].needed, c.blocks[b].symbols.size()));
        n.total += n.block_needed.back();
    }
    for (uint32_t d : c.data)
        if (n.block_of[d] < 0) n.single[d] = true, ++n.total;
    return n;
}

// The mean over tune-in slots of a wait: tuning in as a slot starts weighs every slot alike; at a
// random moment, slot j (lost to the receiver) weighs its size and adds its remaining half.
struct TuneInAverage {
    bool at_slot_start;
    double total = 0, weight = 0;
    void add(double expected_from_next, double size_j) {
        if (at_slot_start) {
            total += expected_from_next;
            weight += 1;
        } else {
            total += size_j * (expected_from_next + size_j / 2.0);
            weight += size_j;
        }
    }
    double mean() const { return total / weight; }
};

// Follows the reception of the packets of `needs` one received packet at a time.
struct Progress {
    const Needs& needs;
    std::vector<bool> have;
    std::vector<size_t> block_have;
    size_t missing;
    explicit Progress(const Needs& n)
        : needs(n), have(n.single.size(), false), block_have(n.block_needed.size(), 0), missing(n.total) {}
    void take(uint32_t p) {
        if (have[p]) return;
        have[p] = true;
        if (needs.single[p]) --missing;
        else if (const int32_t b = needs.block_of[p]; b >= 0 && block_have[size_t(b)] < needs.block_needed[size_t(b)])
            ++block_have[size_t(b)], --missing;
    }
    bool done() const { return missing == 0; }
};

// For every tune-in slot j of one cycle (the receiver gets slots j, j+1, ...), the bytes from the
// start of slot j to the end of the slot that completes `what`, without loss. Two passes over a
// doubled cycle suffice because every packet appears in every cycle.
std::vector<uint64_t> lossless_waits(const Carousel& c, WaitFor what) {
    const size_t n = c.cycle.size();
    std::vector<uint64_t> waits(n, 0);
    if (what == WaitFor::Everything && !c.blocks.empty()) {
        // Repair blocks: any k symbols of a block will do, so follow each tune-in slot forward
        // (at most two periods: every symbol comes once a period).
        const Needs needs = needs_of(c, what);
        for (size_t j = 0; j < n; ++j) {
            Progress progress(needs);
            uint64_t slot = j;
            for (; slot < j + 2 * n; ++slot) {
                progress.take(c.packet_at(slot));
                if (progress.done()) break;
            }
            waits[j] = c.bytes_before(slot + 1) - c.bytes_before(j);
        }
        return waits;
    }
    // The completion slot for start j is the latest, over needed packets p, of p's first occurrence
    // at or after j. Sweep j backwards over a doubled cycle keeping each packet's next occurrence in
    // a max segment tree over slots.
    std::vector<int64_t> next_occurrence(c.sizes.size(), -1);
    std::vector<bool> needed(c.sizes.size(), false);
    for (uint32_t b : c.base) needed[b] = true;
    if (what == WaitFor::Everything) {
        for (uint32_t d : c.data) needed[d] = true;
        for (uint32_t m : c.maps) needed[m] = true;
    }
    const size_t span = 2 * n;
    size_t size = 1;
    while (size < span) size <<= 1;
    std::vector<int64_t> tree(2 * size, -1);  // max of "slot s is the next occurrence of a needed packet"
    auto set = [&](size_t pos, int64_t value) {
        pos += size;
        tree[pos] = value;
        for (pos >>= 1; pos >= 1; pos >>= 1) tree[pos] = std::max(tree[2 * pos], tree[2 * pos + 1]);
    };
    for (int64_t j = static_cast<int64_t>(span) - 1; j >= 0; --j) {
        uint32_t p = c.cycle[static_cast<size_t>(j) % n].packet;
        if (needed[p]) {
            if (next_occurrence[p] >= 0) set(static_cast<size_t>(next_occurrence[p]), -1);
            next_occurrence[p] = j;
            set(static_cast<size_t>(j), j);
        }
        if (j < static_cast<int64_t>(n)) {
            int64_t last = tree[1];
            uint64_t end = (static_cast<uint64_t>(last) / n) * c.cycle_bytes + c.cycle_offsets[last % n + 1];
            waits[static_cast<size_t>(j)] = end - c.cycle_offsets[static_cast<size_t>(j)];
        }
    }
    return waits;
}

}  // namespace

CarouselStats carousel_stats(const Carousel& c) {
    CarouselStats s;
    s.base_packets = c.base.size();
    s.data_packets = c.data.size();
    s.cycle_packets = c.cycle.size();
    s.base_bytes = c.base_bytes;
    s.data_bytes = c.data_bytes;
    s.cycle_bytes = c.cycle_bytes;
    if (c.cycle.empty()) return s;
    double once = double(c.base_bytes + c.data_bytes);
    s.repetition_overhead = c.bytes_per_cycle() / once - 1.0;
    s.base_share = double(c.period_cycles * c.chunk_count * c.base_bytes + c.repeat_bytes) / double(c.cycle_bytes);
    const size_t n = c.cycle.size();
    for (WaitFor what : {WaitFor::Base, WaitFor::Everything}) {
        auto waits = lossless_waits(c, what);
        // Tuning in during slot j (at offset u into it) loses slot j: the wait is the remaining
        // (size_j - u) plus the wait from slot j + 1.
        uint64_t worst = 0;
        double mean = 0;
        for (size_t j = 0; j < n; ++j) {
            uint64_t size = c.sizes[c.cycle[j].packet];
            uint64_t from_next = waits[(j + 1) % n];
            worst = std::max(worst, size + from_next);
            mean += double(size) * (double(from_next) + double(size) / 2.0);
        }
        mean /= double(c.cycle_bytes);
        if (what == WaitFor::Base) {
            s.worst_base_wait_bytes = worst;
            s.mean_base_wait_bytes = mean;
        } else {
            s.worst_full_wait_bytes = worst;
            s.mean_full_wait_bytes = mean;
        }
    }
    return s;
}

double expected_wait_bytes(const Carousel& c, WaitFor what, double loss, size_t tune_in_samples, bool at_slot_start) {
    const size_t n = c.cycle.size();
    if (n == 0) return 0;
    if (!(loss >= 0) || loss >= 1) return std::numeric_limits<double>::infinity();
    if (what == WaitFor::Everything && !c.blocks.empty()) {
        // Repair blocks: "any k of a block" has no product form; estimated from 256 simulated
        // receptions per tune-in slot (a fixed seed: the same carousel gives the same figure).
        const Needs needs = needs_of(c, what);
        const size_t samples = tune_in_samples == 0 ? n : std::min(n, tune_in_samples);
        std::mt19937_64 rng(12345);
        std::uniform_real_distribution<double> uniform(0, 1);
        TuneInAverage average{at_slot_start};
        for (size_t s = 0; s < samples; ++s) {
            const size_t j = samples == n ? s : (s * n) / samples;
            const double size_j = c.sizes[c.cycle[j].packet];
            const uint64_t first = at_slot_start ? j : j + 1;
            double sum = 0;
            for (int trial = 0; trial < 256; ++trial) {
                Progress progress(needs);
                uint64_t slot = first;
                for (; slot < first + uint64_t(n) * 2000; ++slot) {
                    if (uniform(rng) >= loss) progress.take(c.packet_at(slot));
                    if (progress.done()) break;
                }
                sum += double(c.bytes_before(slot + 1) - c.bytes_before(first));
            }
            average.add(sum / 256, size_j);
        }
        return average.mean();
    }
    std::vector<bool> needed(c.sizes.size(), false);
    size_t needed_count = 0;
    for (uint32_t b : c.base) needed[b] = true, ++needed_count;
    if (what == WaitFor::Everything) {
        for (uint32_t d : c.data) needed[d] = true, ++needed_count;
        for (uint32_t m : c.maps) needed[m] = true, ++needed_count;
    }
    size_t samples = tune_in_samples == 0 ? n : std::min(n, tune_in_samples);
    const double log_loss = loss > 0 ? std::log(loss) : -std::numeric_limits<double>::infinity();
    // Stop once the chance of not being done is negligible, or after a bounded horizon.
    const double epsilon = 1e-12;
    const uint64_t max_slots = static_cast<uint64_t>(n) * 2000;
    std::vector<uint32_t> seen(c.sizes.size());
    TuneInAverage average{at_slot_start};
    for (size_t s = 0; s < samples; ++s) {
        size_t j = samples == n ? s : (s * n) / samples;
        // Tune in during slot j: slot j is missed, reception starts at slot j + 1 (or at j itself
        // when tuning in as it starts).
        double size_j = c.sizes[c.cycle[j].packet];
        const uint64_t first = at_slot_start ? j : j + 1;
        std::fill(seen.begin(), seen.end(), 0);
        size_t missing = needed_count;
        double log_done = 0;  // sum over needed p of log(1 - loss^seen[p]) over seen packets
        double expected = 0;
        for (uint64_t k = 0; k < max_slots; ++k) {
            uint64_t slot = first + k;
            uint32_t p = c.cycle[slot % n].packet;
            double size = c.sizes[p];
            double p_done_before = missing == 0 ? std::exp(log_done) : 0.0;
            expected += size * (1.0 - p_done_before);
            if (needed[p]) {
                if (seen[p] == 0) {
                    --missing;
                } else {
                    log_done -= std::log1p(-std::exp(log_loss * seen[p]));
                }
                ++seen[p];
                log_done += loss > 0 ? std::log1p(-std::exp(log_loss * seen[p])) : 0.0;
            }
            if (missing == 0 && 1.0 - std::exp(log_done) < epsilon) break;
        }
        average.add(expected, size_j);
    }
    return average.mean();
}

int64_t completion_slot(const Carousel& c, WaitFor what, uint64_t first_slot, const std::vector<bool>& received) {
    if (c.cycle.empty()) return -1;
    const Needs needs = needs_of(c, what);
    Progress progress(needs);
    if (progress.done()) return -1;
    for (size_t k = 0; k < received.size(); ++k) {
        if (!received[k]) continue;
        progress.take(c.packet_at(first_slot + k));
        if (progress.done()) return static_cast<int64_t>(k);
    }
    return -1;
}

}  // namespace ellicast::broadcast

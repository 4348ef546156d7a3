// ellicast as a scheme: encoder -> packets -> carousel; ReceivedStream -> decoder.
#include "ellicast/compare/ellicast_scheme.h"

#include "ellicast/broadcast/carousel.h"
#include "ellicast/codec/decoder.h"
#include "ellicast/format.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ellicast::compare {

struct EllicastScheme::State {
    broadcast::Carousel carousel;
    broadcast::CarouselStats stats;
    EllicastSettings settings;
    std::vector<uint32_t> points_in_packet;  // surface points each packet carries (0 for the base and repairs)
    // Repair blocks: per packet its block (-1: none); per block its k and its points.
    std::vector<int32_t> block_of;
    std::vector<size_t> block_needed;
    std::vector<uint64_t> block_points;
    size_t singles_needed = 0;  // packets in no block: each one is needed
    size_t info_packets = 0, ellipsoid_packets = 0, map_packets = 0;  // packets_ starts with these, in that order
    bool exact_layer = false;  // the object has one (spec 19)
};

EllicastScheme::EllicastScheme(const Mesh& mesh, const EllicastSettings& settings) : state_(std::make_unique<State>()) {
    state_->settings = settings;
    if (std::string why = check_encode_options(settings.encode); !why.empty())
        throw CompareError("ellicast encoder options: " + why);
    EncodeResult encoded;
    try {
        encoded = encode_meshes({mesh}, settings.encode);
    } catch (const std::exception& e) {
        throw CompareError(std::string("ellicast encoder: ") + e.what());
    }
    StreamPackets stream;
    if (Error e = packetize_stream(encoded.info, encoded.contents, 1, stream); e != Error::Ok)
        throw CompareError(std::string("ellicast packetizer: ") + error_name(e));
    state_->info_packets = stream.stream_info.size();
    state_->ellipsoid_packets = stream.ellipsoids.size();
    state_->map_packets = stream.maps.size();  // format 1.7: POINT_MAP, base like the ellipsoids
    for (auto* group : {&stream.stream_info, &stream.ellipsoids, &stream.maps})
        for (auto& p : *group) {
            packets_.push_back(std::move(p));
            state_->points_in_packet.push_back(0);
        }
    const ObjectInfo& object = encoded.info.objects.at(0);
    for (auto& p : stream.points) {
        // Count the points each packet really carries, from its own payload.
        PacketView view;
        PointBatch batch;
        if (parse_packet(p, view) != Error::Ok ||
            decode_points_payload(view.payload, encoded.info, object, batch) != Error::Ok)
            throw CompareError("ellicast packetizer wrote a POINTS packet that does not parse");
        state_->points_in_packet.push_back(static_cast<uint32_t>(batch.points.size()));
        packets_.push_back(std::move(p));
    }
    // Format 1.8: NORMALS packets (an object with normals and an exact layer), detail after the points.
    for (auto& p : stream.normals) {
        state_->points_in_packet.push_back(0);
        packets_.push_back(std::move(p));
    }
    for (auto& p : stream.texcoords) {  // format 1.14: further texture-coordinate sets, detail too
        state_->points_in_packet.push_back(0);
        packets_.push_back(std::move(p));
    }
    ellipsoids_ = object.ellipsoid_count;
    points_ = object.point_count;
    state_->block_of.assign(packets_.size(), -1);
    if (settings.repair_ratio > 0) {
        // The encoder's blocks (spec 17.5): POINTS packets k at a time, ceil(ratio * k) repairs each.
        const size_t batch = point_batch_size(encoded.info, object);
        const size_t max_sources = std::max<size_t>(1, size_t(255.0 / (1.0 + settings.repair_ratio)));
        const size_t first_points_packet = state_->info_packets + state_->ellipsoid_packets + state_->map_packets;
        for (const RepairBlock& block : plan_repair_blocks(object.point_count, uint16_t(batch), max_sources)) {
            std::vector<std::vector<uint8_t>> repairs;
            const size_t count = size_t(std::ceil(settings.repair_ratio * block.source_count() - 1e-9));
            if (Error e = packetize_repairs(encoded.info, 0, encoded.contents[0].points, {block}, count, 1, 0, repairs);
                e != Error::Ok)
                throw CompareError(std::string("ellicast repair packets: ") + error_name(e));
            const int32_t id = static_cast<int32_t>(state_->block_needed.size());
            state_->block_needed.push_back(block.source_count());
            state_->block_points.push_back(block.point_count);
            const size_t first_batch = block.first_index / batch;
            for (size_t i = 0; i < block.source_count(); ++i) state_->block_of[first_points_packet + first_batch + i] = id;
            for (auto& r : repairs) {
                packets_.push_back(std::move(r));
                state_->points_in_packet.push_back(0);
                state_->block_of.push_back(id);
            }
        }
    }

    // Format 1.3: the exact layer (spec 19; 1.11's coded mesh, spec 27), as encode_asset sends it: its
    // pieces, and with repair its repair symbols, any k of which give it back. Complete then means the
    // exact model.
    if (const ObjectContent& content = encoded.contents[0]; !content.connectivity.empty()) {
        state_->exact_layer = true;
        std::vector<std::vector<uint8_t>> pieces, repairs;
        // Format 1.11: with carried vertices, EXACT_MESH pieces and repair symbols (spec 27).
        const uint32_t carried = uint32_t(content.carried.size());
        if (Error e = packetize_connectivity(encoded.info, 0, content.triangle_count, content.connectivity, 1, 0, pieces,
                                             carried);
            e != Error::Ok)
            throw CompareError(std::string("ellicast exact layer: ") + error_name(e));
        const size_t k = pieces.size();
        int32_t id = -1;
        if (settings.repair_ratio > 0 && k <= 127) {
            const size_t count = std::min(size_t(std::ceil(settings.repair_ratio * double(k) - 1e-9)), 255 - k);
            if (Error e = packetize_connectivity_repairs(encoded.info, 0, content.triangle_count, content.connectivity,
                                                         count, 1, 0, repairs, carried);
                e != Error::Ok)
                throw CompareError(std::string("ellicast exact layer repair: ") + error_name(e));
            id = static_cast<int32_t>(state_->block_needed.size());
            state_->block_needed.push_back(k);
            state_->block_points.push_back(0);
        }
        for (auto* group : {&pieces, &repairs})
            for (auto& p : *group) {
                packets_.push_back(std::move(p));
                state_->points_in_packet.push_back(0);
                state_->block_of.push_back(id);
            }
    }
    for (int32_t b : state_->block_of) state_->singles_needed += b < 0;
    broadcast::CarouselOptions options;
    options.base_share = settings.base_share;
    options.chunk_packets = settings.chunk_packets;
    options.restamp_sequence = false;
    std::string error;
    if (!broadcast::build_carousel(packets_, options, state_->carousel, error))
        throw CompareError("ellicast carousel: " + error);
    state_->stats = broadcast::carousel_stats(state_->carousel);
}

EllicastScheme::~EllicastScheme() = default;

uint64_t EllicastScheme::period() const { return state_->carousel.cycle.size(); }

uint32_t EllicastScheme::packet_at(uint64_t slot) const { return state_->carousel.packet_at(slot); }

double EllicastScheme::repetition_overhead() const { return state_->stats.repetition_overhead; }
double EllicastScheme::base_share() const { return state_->stats.base_share; }
size_t EllicastScheme::base_packets() const { return state_->stats.base_packets; }
size_t EllicastScheme::point_packets() const { return state_->stats.data_packets; }

std::string EllicastScheme::describe() const {
    std::ostringstream s;
    s << ellipsoids_ << " ellipsoids and " << points_ << " points in " << base_packets() << " base + "
      << point_packets() << " point packets; carousel b d1 ... b d" << state_->carousel.chunk_count << " (base "
      << std::lround(100 * base_share()) << "% of the cycle, repetition overhead "
      << std::lround(100 * repetition_overhead()) << "%); decodable from any subset holding the stream info and an ellipsoid";
    if (!state_->block_needed.empty())
        s << "; " << state_->carousel.repairs.size() << " repair packets in " << state_->block_needed.size()
          << " blocks, sent in turn with the point packets (any k of a block give all its points)";
    else
        s << "; the point packets repeat every cycle (no repair packets)";
    return s.str();
}

bool EllicastScheme::reconstruct(const std::vector<uint32_t>& held, Mesh& out) const {
    out = Mesh{};
    ReceivedStream received;
    for (uint32_t i : held)
        if (i < packets_.size()) received.add_packet(packets_[i], i);
    if (!received.info()) return false;
    DecodeOptions options;
    options.grid_resolution = state_->settings.grid_resolution;
    options.threads = 1;  // the trials run side by side already
    std::vector<Mesh> meshes;
    StreamDecodeReport report;
    std::string error;
    if (!decode_stream(received, options, meshes, report, error)) return false;
    for (size_t i = 0; i < meshes.size(); ++i)
        if (i < report.objects.size() && report.objects[i].has_surface && !meshes[i].triangles.empty()) {
            out = std::move(meshes[i]);
            return true;
        }
    return false;
}

bool EllicastScheme::can_show(const std::vector<uint32_t>& held) const {
    bool info = false, ellipsoids = false;
    for (uint32_t i : held) {
        if (i < state_->info_packets) info = true;
        else if (i < state_->info_packets + state_->ellipsoid_packets) ellipsoids = true;
    }
    if (info && ellipsoids) return true;
    // Without an ellipsoid, every point and the exact layer still show the original mesh (spec
    // 19.4): everything but the base's ellipsoids, held. Stream info parts are also singles.
    if (!info || !state_->exact_layer) return false;
    std::vector<uint32_t> with_base = held;
    for (uint32_t i = 0; i < state_->info_packets + state_->ellipsoid_packets; ++i) with_base.push_back(i);
    std::sort(with_base.begin(), with_base.end());
    with_base.erase(std::unique(with_base.begin(), with_base.end()), with_base.end());
    return complete(with_base);
}

double EllicastScheme::data_fraction(const std::vector<uint32_t>& held) const {
    if (points_ == 0) return 0;
    std::vector<size_t> symbols(state_->block_needed.size(), 0);
    std::vector<uint64_t> block_points_held(state_->block_needed.size(), 0);
    uint64_t n = 0;
    for (uint32_t i : held) {
        if (i >= state_->points_in_packet.size()) continue;
        const int32_t b = state_->block_of[i];
        if (b < 0) {
            n += state_->points_in_packet[i];
            continue;
        }
        ++symbols[size_t(b)];
        block_points_held[size_t(b)] += state_->points_in_packet[i];
    }
    for (size_t b = 0; b < symbols.size(); ++b)
        n += symbols[b] >= state_->block_needed[b] ? state_->block_points[b] : block_points_held[b];
    return double(n) / double(points_);
}

bool EllicastScheme::complete(const std::vector<uint32_t>& held) const {
    std::vector<size_t> symbols(state_->block_needed.size(), 0);
    size_t singles = 0;
    for (uint32_t i : held) {
        if (i >= packets_.size()) continue;
        if (state_->block_of[i] < 0) ++singles;
        else ++symbols[size_t(state_->block_of[i])];
    }
    if (singles < state_->singles_needed) return false;
    for (size_t b = 0; b < symbols.size(); ++b)
        if (symbols[b] < state_->block_needed[b]) return false;
    return true;
}

double EllicastScheme::cycle_bytes() const { return state_->carousel.bytes_per_cycle(); }

std::string EllicastScheme::name() const { return state_->settings.name; }

}  // namespace ellicast::compare

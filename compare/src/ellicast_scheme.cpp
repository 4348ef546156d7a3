// ellicast as a scheme: encoder -> packets -> carousel; ReceivedStream -> decoder.
#include "ellicast/compare/ellicast_scheme.h"

#include "ellicast/broadcast/carousel.h"
#include "ellicast/codec/decoder.h"
#include "ellicast/format.h"

#include <sstream>

namespace ellicast::compare {

struct EllicastScheme::State {
    broadcast::Carousel carousel;
    broadcast::CarouselStats stats;
    EllicastSettings settings;
    std::vector<uint32_t> points_in_packet;  // surface points each packet carries (0 for the base)
    size_t info_packets = 0, ellipsoid_packets = 0;  // packets_ starts with these, in that order
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
    for (auto* group : {&stream.stream_info, &stream.ellipsoids})
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
    ellipsoids_ = object.ellipsoid_count;
    points_ = object.point_count;

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
    return info && ellipsoids;
}

double EllicastScheme::data_fraction(const std::vector<uint32_t>& held) const {
    if (points_ == 0) return 0;
    size_t n = 0;
    for (uint32_t i : held)
        if (i < state_->points_in_packet.size()) n += state_->points_in_packet[i];
    return double(n) / double(points_);
}

}  // namespace ellicast::compare

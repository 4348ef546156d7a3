// Receiving datagrams safely: classification of what is dropped, loss estimation, completeness.
#include <ellicast/broadcast/reception.h>

#include <algorithm>

namespace ellicast::broadcast {

LossEstimator::LossEstimator(uint32_t window) : window_(std::max<uint32_t>(64, window)), bits_((window_ + 63) / 64, 0) {}

void LossEstimator::add(uint32_t sequence) {
    auto test_and_set = [&](uint64_t s) {
        uint64_t i = s % window_;
        uint64_t mask = 1ull << (i % 64);
        bool was = (bits_[i / 64] & mask) != 0;
        bits_[i / 64] |= mask;
        return was;
    };
    auto clear = [&](uint64_t s) { bits_[(s % window_) / 64] &= ~(1ull << ((s % window_) % 64)); };
    if (!started_) {
        started_ = true;
        // Start in the middle of the 64-bit range so that a sequence before the first one unwraps.
        first_ = highest_ = (1ull << 40) + sequence;
        test_and_set(first_);
        received_ = 1;
        return;
    }
    int64_t delta = static_cast<int32_t>(sequence - static_cast<uint32_t>(highest_));
    uint64_t unwrapped = static_cast<uint64_t>(static_cast<int64_t>(highest_) + delta);
    if (delta > 0) {
        uint64_t steps = static_cast<uint64_t>(delta);
        if (steps >= window_) {
            std::fill(bits_.begin(), bits_.end(), 0);
        } else {
            for (uint64_t s = highest_ + 1; s <= unwrapped; ++s) clear(s);
        }
        highest_ = unwrapped;
        test_and_set(unwrapped);
        ++received_;
        return;
    }
    // At or behind the highest: a duplicate or a late (reordered) packet, if still in the window.
    if (highest_ - unwrapped >= window_) return;
    if (unwrapped < first_) {
        // Arrived before the first one seen: extend the span back (bits there are clear: they
        // were never set since the window only covers what came after the start).
        for (uint64_t s = unwrapped; s < first_; ++s) clear(s);
        first_ = unwrapped;
    }
    if (!test_and_set(unwrapped)) ++received_;
}

uint64_t LossEstimator::expected() const { return started_ ? highest_ - first_ + 1 : 0; }

double LossEstimator::loss() const {
    uint64_t e = expected();
    if (e == 0 || received_ >= e) return 0;
    return 1.0 - static_cast<double>(received_) / static_cast<double>(e);
}

Reception::Reception() : Reception(Options{}) {}

Reception::Reception(Options options) : options_(options), stream_(options.limits) {}

Error Reception::take(std::span<const uint8_t> datagram, bool truncated) {
    ++counters_.datagrams;
    counters_.bytes += datagram.size();
    if (truncated || datagram.size() > kMaxPacketSize) {
        ++counters_.oversized;
        return Error::Oversized;
    }
    PacketView view;
    Error e = parse_packet(datagram, view);
    if (e == Error::Ok && options_.stream_id && view.header.stream_id != *options_.stream_id) e = Error::StreamMismatch;
    if (e == Error::Ok) {
        uint64_t before_accepted = stream_.counters().accepted;
        e = stream_.add_parsed(view, counters_.datagrams - 1);
        if (e == Error::Ok) {
            if (stream_.counters().accepted > before_accepted)
                ++counters_.accepted;
            else
                ++counters_.duplicates;
            loss_.add(view.header.sequence);
            return Error::Ok;
        }
    }
    switch (e) {
        case Error::TooShort:
        case Error::BadMagic: ++counters_.not_ellicast; break;
        case Error::BadChecksum:
        case Error::Truncated:
        case Error::LengthMismatch: ++counters_.damaged; break;
        case Error::Oversized: ++counters_.oversized; break;
        case Error::StreamMismatch: ++counters_.other_stream; break;
        default: ++counters_.invalid; break;
    }
    return e;
}

bool Reception::base_complete() const {
    if (!stream_.info()) return false;
    const auto& objects = stream_.objects();
    for (const auto& object : objects) {
        if (!object.info) return false;
        if (object.info->kind == ObjectKind::Surface && object.ellipsoids.size() < object.info->ellipsoid_count)
            return false;
    }
    // Format 1.1: the scene tables and the materials travel with the base.
    if (stream_.has_scene()) {
        if (stream_.scene_nodes().size() < stream_.scene_node_count()) return false;
        if (stream_.scene_meshes().size() < stream_.scene_mesh_count()) return false;
    }
    const auto& materials = stream_.materials();
    if (!materials.empty() && materials.size() < materials.begin()->second.material_count) return false;
    return true;
}

bool Reception::complete() const {
    if (!base_complete()) return false;
    for (const auto& object : stream_.objects())
        if (object.points.size() < object.info->point_count) return false;
    const auto& textures = stream_.textures();
    if (!textures.empty() && textures.size() < textures.begin()->second.info.texture_count) return false;
    for (const auto& [index, texture] : textures)
        if (!texture.complete) return false;
    return true;
}

uint64_t Reception::points_received() const {
    uint64_t n = 0;
    for (const auto& object : stream_.objects()) n += object.points.size();
    return n;
}

uint64_t Reception::points_declared() const {
    uint64_t n = 0;
    for (const auto& object : stream_.objects())
        if (object.info) n += object.info->point_count;
    return n;
}

uint64_t Reception::ellipsoids_received() const {
    uint64_t n = 0;
    for (const auto& object : stream_.objects()) n += object.ellipsoids.size();
    return n;
}

uint64_t Reception::ellipsoids_declared() const {
    uint64_t n = 0;
    for (const auto& object : stream_.objects())
        if (object.info) n += object.info->ellipsoid_count;
    return n;
}

}  // namespace ellicast::broadcast

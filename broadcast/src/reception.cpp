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

Reception::Reception(Options options) : options_(options) {
    options_.max_candidates = std::clamp<size_t>(options_.max_candidates, 1, 64);
    budget_ = std::make_shared<SharedMemoryBudget>();
    budget_->base = options_.limits.memory_base;
    budget_->per_byte = options_.limits.memory_per_byte;
    if (options_.key) authenticator_.emplace(*options_.key, options_.auth_limits);
}

const ReceivedStream& Reception::stream() const {
    return chosen_ < candidates_.size() ? candidates_[chosen_].stream : empty_;
}

ReceptionCounters Reception::counters() const {
    ReceptionCounters c = counters_;
    if (authenticator_) {
        const auth::Authenticator::Counters& a = authenticator_->counters();
        c.unauthenticated = a.not_authenticated + a.manifests_failed + a.malformed;
        c.awaiting_manifest = a.held;
    }
    if (chosen_ >= candidates_.size()) return c;
    const Candidate& k = candidates_[chosen_];
    c.accepted = k.accepted;
    c.duplicates = k.duplicates;
    c.invalid += k.invalid;
    c.other_stream += valid_ - k.routed;
    return c;
}

Error Reception::take(std::span<const uint8_t> datagram, bool truncated) {
    ++counters_.datagrams;
    counters_.bytes += datagram.size();
    last_accepted_by_ = 0;
    last_evicted_ = 0;
    released_accepted_.clear();
    if (truncated || datagram.size() > kMaxPacketSize) {
        ++counters_.oversized;
        return Error::Oversized;
    }
    const uint64_t where = counters_.datagrams - 1;
    PacketView view;
    Error e = parse_packet(datagram, view);
    if (e == Error::Ok && options_.stream_id && view.header.stream_id != *options_.stream_id) e = Error::StreamMismatch;
    if (e == Error::Ok && authenticator_) {
        // Signed stream: only packets a verified MANIFEST lists reach the candidates (spec 16.3).
        const auth::Authenticator::Verdict v = authenticator_->take(view, datagram, where);
        Error result = Error::Ok;
        if (v == auth::Authenticator::Verdict::Rejected) result = authenticator_->last_error();
        else if (v != auth::Authenticator::Verdict::Held) {
            std::optional<Error> r = route(view, where);
            if (!r) ++counters_.other_stream;
            result = r.value_or(Error::StreamMismatch);
        }
        // Packets held until this MANIFEST verified: taken now, in the order they arrived. Those that
        // brought something new are kept for the caller (a recording of what was received).
        const uint64_t own = last_accepted_by_;
        for (auth::Authenticator::Released& held : authenticator_->take_released()) {
            PacketView released;
            last_accepted_by_ = 0;
            if (parse_packet(held.bytes, released) == Error::Ok && !route(released, held.where)) ++counters_.other_stream;
            if (last_accepted_by_) released_accepted_.push_back({last_accepted_by_, std::move(held.bytes)});
        }
        last_accepted_by_ = own;
        return result;
    }
    if (e == Error::Ok) {
        if (std::optional<Error> r = route(view, where)) return *r;
        e = Error::StreamMismatch;  // no room for another stream: counted as another stream's
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

size_t Reception::place_for_new_candidate(uint32_t id) {
    if (candidates_.size() < options_.max_candidates) {
        candidates_.emplace_back(id, options_.limits, next_serial_++);
        candidates_.back().stream.share_memory_budget(budget_);
        return candidates_.size() - 1;
    }
    size_t victim = SIZE_MAX;
    for (size_t i = 0; i < candidates_.size(); ++i) {
        if (i == chosen_) continue;
        const Candidate& k = candidates_[i];
        if (victim == SIZE_MAX || k.accepted < candidates_[victim].accepted ||
            (k.accepted == candidates_[victim].accepted && k.last_accepted_at < candidates_[victim].last_accepted_at))
            victim = i;
    }
    if (victim == SIZE_MAX) return SIZE_MAX;
    candidates_[victim].stream.share_memory_budget(nullptr);  // gives back what it held
    candidates_[victim] = Candidate(id, options_.limits, next_serial_++);
    candidates_[victim].stream.share_memory_budget(budget_);
    last_evicted_ |= uint64_t(1) << victim;
    ++evictions_;
    return victim;
}

std::optional<Error> Reception::route(const PacketView& view, uint64_t where) {
    const uint32_t id = view.header.stream_id;
    budget_->bytes += view.size;  // intact, once however many candidates take it (spec 11.2)
    bool any = false, taken = false, contradicted = true;
    uint64_t ok = 0;  // bit i: candidate i took the packet, new or not (at most 64 candidates)
    Error first_error = Error::Ok;
    for (size_t i = 0; i < candidates_.size(); ++i) {
        Candidate& k = candidates_[i];
        if (k.stream_id != id) continue;
        any = true;
        ++k.routed;
        const uint64_t before = k.stream.counters().accepted;
        const Error r = k.stream.add_parsed(view, where);
        if (r == Error::Ok) {
            taken = true;
            ok |= uint64_t(1) << i;
            contradicted = false;
            if (k.stream.counters().accepted > before) {
                ++k.accepted;
                k.last_accepted_at = valid_;
                last_accepted_by_ |= uint64_t(1) << i;
            } else {
                ++k.duplicates;
            }
        } else {
            ++k.invalid;
            if (first_error == Error::Ok) first_error = r;
            if (!(r == Error::StreamMismatch && view.header.type == static_cast<uint8_t>(PacketType::StreamInfo))) contradicted = false;
        }
    }
    // A stream id not heard before, or a STREAM_INFO every candidate of its id contradicts:
    // a new candidate, in a free place or in the weakest one's.
    if (!any || (!taken && contradicted)) {
        if (const size_t place = place_for_new_candidate(id); place != SIZE_MAX) {
            Candidate& k = candidates_[place];
            ++k.routed;
            const Error r = k.stream.add_parsed(view, where);
            if (r == Error::Ok) {
                taken = true;
                ok |= uint64_t(1) << place;
                if (k.stream.counters().accepted > 0) {
                    ++k.accepted;
                    k.last_accepted_at = valid_;
                    last_accepted_by_ |= uint64_t(1) << place;
                } else {
                    ++k.duplicates;
                }
            } else {
                ++k.invalid;
                if (first_error == Error::Ok) first_error = r;
            }
            any = true;
        } else if (!any) {
            return std::nullopt;
        }
    }
    ++valid_;
    // The candidate with the most packets accepted; the first on a tie.
    size_t best = 0;
    for (size_t i = 1; i < candidates_.size(); ++i)
        if (candidates_[i].accepted > candidates_[best].accepted) best = i;
    chosen_ = best;
    if (taken) {
        if (ok >> chosen_ & 1) loss_.add(view.header.sequence);
        return Error::Ok;
    }
    return first_error;
}

namespace {

bool stream_base_complete(const ReceivedStream& stream) {
    if (!stream.info()) return false;
    for (const auto& object : stream.objects()) {
        if (!object.info) return false;
        if (object.info->kind == ObjectKind::Surface && object.ellipsoids.size() < object.info->ellipsoid_count)
            return false;
        if (object.info->mapped() && !object.map_complete()) return false;  // format 1.7: the map is base
    }
    // Format 1.1: the scene tables and the materials travel with the base.
    if (stream.has_scene()) {
        if (stream.scene_nodes().size() < stream.scene_node_count()) return false;
        if (stream.scene_meshes().size() < stream.scene_mesh_count()) return false;
    }
    const auto& materials = stream.materials();
    if (!materials.empty() && materials.size() < materials.begin()->second.material_count) return false;
    return true;
}

bool stream_complete(const ReceivedStream& stream) {
    if (!stream_base_complete(stream)) return false;
    for (const auto& object : stream.objects()) {
        if (object.points.size() < object.info->point_count) return false;
        // Format 1.3: an object with an exact layer is complete with its connectivity (spec 19.1).
        if (object.info->exact_layer && !(object.connectivity && object.connectivity->complete)) return false;
        // Format 1.8 (spec 24.4): every normal entry; format 1.14 (spec 30.2): every further set's records.
        if (object.info->surface_normals && !object.normals_complete()) return false;
        if (!object.texcoords_complete()) return false;
    }
    const auto& textures = stream.textures();
    if (!textures.empty() && textures.size() < textures.begin()->second.info.texture_count) return false;
    for (const auto& [index, texture] : textures)
        if (!texture.complete) return false;
    // Format 1.4: every animation whole (spec 20.2).
    if (const auto count = stream.animation_count(); count && stream.animations().size() < *count) return false;
    for (const auto& [index, animation] : stream.animations())
        if (!animation.complete()) return false;
    // Format 1.5 (spec 21.3): every skin whole, and a record for every point of the objects a skinned
    // node shows.
    if (const auto count = stream.skin_count(); count && stream.skins().size() < *count) return false;
    for (const auto& [index, skin] : stream.skins())
        if (!skin.complete()) return false;
    for (const auto& [o, joints] : skinned_objects(stream))
        if (o < stream.objects().size() && stream.objects()[o].weights.size() < stream.objects()[o].info->point_count)
            return false;
    // Format 1.6 (spec 22.4): every morph animation whole, and displacements for every point of the
    // objects a mesh with targets shows.
    if (const auto count = stream.morph_animation_count(); count && stream.morph_animations().size() < *count)
        return false;
    for (const auto& [index, animation] : stream.morph_animations())
        if (!animation.complete()) return false;
    for (const auto& [o, targets] : morph_target_objects(stream))
        if (o < stream.objects().size() && stream.objects()[o].morph.size() < stream.objects()[o].info->point_count)
            return false;
    return true;
}

}  // namespace

bool Reception::base_complete() const { return stream_base_complete(stream()); }

bool Reception::complete() const { return stream_complete(stream()); }

bool Reception::every_candidate_complete() const {
    if (candidates_.empty()) return false;
    for (const Candidate& k : candidates_)
        if (!stream_complete(k.stream)) return false;
    return true;
}

uint64_t Reception::points_received() const {
    uint64_t n = 0;
    for (const auto& object : stream().objects()) n += object.points.size();
    return n;
}

uint64_t Reception::points_declared() const {
    uint64_t n = 0;
    for (const auto& object : stream().objects())
        if (object.info) n += object.info->point_count;
    return n;
}

uint64_t Reception::ellipsoids_received() const {
    uint64_t n = 0;
    for (const auto& object : stream().objects()) n += object.ellipsoids.size();
    return n;
}

uint64_t Reception::ellipsoids_declared() const {
    uint64_t n = 0;
    for (const auto& object : stream().objects())
        if (object.info) n += object.info->ellipsoid_count;
    return n;
}

}  // namespace ellicast::broadcast

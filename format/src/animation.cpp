// ANIMATION packets (format 1.4, spec 20): the payload, and what a receiver keeps of them.
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>
#include <cmath>

namespace ellicast {

using namespace detail;

namespace {
bool read_keys(const uint8_t* key, size_t count, size_t per_key, AnimationPiece& a);

// The name, then each key's time and values (spec 20.1, 22.2).
void put_name_and_keys(std::vector<uint8_t>& out, const AnimationPiece& a, size_t name, size_t per_key) {
    out.insert(out.end(), a.name.begin(), a.name.begin() + static_cast<std::ptrdiff_t>(name));
    for (size_t k = 0; k < a.times.size(); ++k) {
        put_f32(out, a.times[k]);
        for (size_t v = 0; v < per_key; ++v) put_f32(out, a.values[k * per_key + v]);
    }
}

// The index and key-range rules shared by ANIMATION and MORPH_ANIMATION (spec 20.1, 22.2).
bool valid_ranges(const AnimationPiece& a, uint16_t count) {
    return a.animation < a.animation_count && a.track < a.track_count && count != 0 && a.info.key_count != 0 &&
           !(a.info.interpolation == Interpolation::CubicSpline && a.info.key_count < 2) &&
           uint64_t(a.first_key) + count <= a.info.key_count;
}
}  // namespace

size_t animation_values_per_key(AnimationPath path, Interpolation interpolation, size_t targets) {
    const size_t components = path == AnimationPath::Weights ? targets : path == AnimationPath::Rotation ? 4 : 3;
    return interpolation == Interpolation::CubicSpline ? 3 * components : components;
}

std::vector<uint8_t> encode_animation_payload(const AnimationPiece& a) {
    std::vector<uint8_t> out;
    const size_t name = std::min<size_t>(a.name.size(), 255);
    out.reserve(kAnimationHeaderSize + name + 4 * (a.times.size() + a.values.size()));
    put_u16(out, a.animation);
    put_u16(out, a.animation_count);
    put_u16(out, a.track);
    put_u16(out, a.track_count);
    put_u16(out, a.info.node);
    put_u8(out, static_cast<uint8_t>(a.info.path));
    put_u8(out, static_cast<uint8_t>(a.info.interpolation));
    put_u32(out, a.info.key_count);
    put_u32(out, a.first_key);
    put_u16(out, static_cast<uint16_t>(a.times.size()));
    put_u8(out, static_cast<uint8_t>(name));
    put_u8(out, 0);
    put_name_and_keys(out, a, name, animation_values_per_key(a.info.path, a.info.interpolation));
    return out;
}

Error decode_animation_payload(std::span<const uint8_t> payload, AnimationPiece& out) {
    if (payload.size() < kAnimationHeaderSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    AnimationPiece a;
    a.animation = get_u16(p);
    a.animation_count = get_u16(p + 2);
    a.track = get_u16(p + 4);
    a.track_count = get_u16(p + 6);
    a.info.node = get_u16(p + 8);
    const uint8_t path = p[10], interpolation = p[11];
    a.info.key_count = get_u32(p + 12);
    a.first_key = get_u32(p + 16);
    const uint16_t count = get_u16(p + 20);
    const uint8_t name = p[22];
    if (path > 2 || interpolation > 2) return Error::MalformedPayload;
    a.info.path = static_cast<AnimationPath>(path);
    a.info.interpolation = static_cast<Interpolation>(interpolation);
    const size_t per_key = animation_values_per_key(a.info.path, a.info.interpolation);
    if (payload.size() != kAnimationHeaderSize + name + size_t(count) * 4 * (1 + per_key)) return Error::MalformedPayload;
    if (!valid_ranges(a, count)) return Error::MalformedPayload;
    a.name.assign(reinterpret_cast<const char*>(p + kAnimationHeaderSize), name);
    if (!read_keys(p + kAnimationHeaderSize + name, count, per_key, a)) return Error::MalformedPayload;
    out = std::move(a);
    return Error::Ok;
}

namespace {

// `count` keys of `per_key` values from `key` on (spec 20.1, 22.2): finite, times not negative and
// strictly increasing.
bool read_keys(const uint8_t* key, size_t count, size_t per_key, AnimationPiece& a) {
    a.times.resize(count);
    a.values.resize(size_t(count) * per_key);
    for (size_t k = 0; k < count; ++k, key += 4 * (1 + per_key)) {
        const float t = get_f32(key);
        if (!std::isfinite(t) || t < 0 || (k > 0 && !(t > a.times[k - 1]))) return false;
        a.times[k] = t;
        for (size_t v = 0; v < per_key; ++v) {
            const float x = get_f32(key + 4 + 4 * v);
            if (!std::isfinite(x)) return false;
            a.values[k * per_key + v] = x;
        }
    }
    return true;
}

}  // namespace

std::vector<uint8_t> encode_morph_animation_payload(const AnimationPiece& a) {
    std::vector<uint8_t> out;
    const size_t name = std::min<size_t>(a.name.size(), 255);
    out.reserve(kMorphAnimationHeaderSize + name + 4 * (a.times.size() + a.values.size()));
    put_u16(out, a.animation);
    put_u16(out, a.animation_count);
    put_u16(out, a.track);
    put_u16(out, a.track_count);
    put_u16(out, a.info.node);
    put_u16(out, a.joins);
    put_u8(out, a.info.targets);
    put_u8(out, static_cast<uint8_t>(a.info.interpolation));
    put_u16(out, static_cast<uint16_t>(a.times.size()));
    put_u32(out, a.info.key_count);
    put_u32(out, a.first_key);
    put_u8(out, static_cast<uint8_t>(name));
    put_u8(out, 0);
    put_name_and_keys(out, a, name, animation_values_per_key(AnimationPath::Weights, a.info.interpolation, a.info.targets));
    return out;
}

Error decode_morph_animation_payload(std::span<const uint8_t> payload, AnimationPiece& out) {
    if (payload.size() < kMorphAnimationHeaderSize) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    AnimationPiece a;
    a.animation = get_u16(p);
    a.animation_count = get_u16(p + 2);
    a.track = get_u16(p + 4);
    a.track_count = get_u16(p + 6);
    a.info.node = get_u16(p + 8);
    a.joins = get_u16(p + 10);
    a.info.path = AnimationPath::Weights;
    a.info.targets = p[12];
    const uint8_t interpolation = p[13];
    const uint16_t count = get_u16(p + 14);
    a.info.key_count = get_u32(p + 16);
    a.first_key = get_u32(p + 20);
    const uint8_t name = p[24];
    if (a.info.targets == 0 || interpolation > 2) return Error::MalformedPayload;
    a.info.interpolation = static_cast<Interpolation>(interpolation);
    const size_t per_key = animation_values_per_key(AnimationPath::Weights, a.info.interpolation, a.info.targets);
    if (payload.size() != kMorphAnimationHeaderSize + name + size_t(count) * 4 * (1 + per_key)) return Error::MalformedPayload;
    if (!valid_ranges(a, count)) return Error::MalformedPayload;
    a.name.assign(reinterpret_cast<const char*>(p + kMorphAnimationHeaderSize), name);
    if (!read_keys(p + kMorphAnimationHeaderSize + name, count, per_key, a)) return Error::MalformedPayload;
    out = std::move(a);
    return Error::Ok;
}

bool ReceivedStream::ReceivedAnimation::complete() const {
    if (tracks.size() != track_count) return false;
    return std::all_of(tracks.begin(), tracks.end(), [](const auto& t) { return t.second.complete; });
}

Error ReceivedStream::take_animation(const PacketView& packet, uint64_t where) {
    AnimationPiece a;
    if (decode_animation_payload(packet.payload, a) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "ANIMATION payload inconsistent or out of range (length, indices, path, interpolation, key "
                      "range, or a time or value that is not finite, negative or increasing)");
    return take_keys(a, animation_count_, animations_, "ANIMATION", where);
}

Error ReceivedStream::take_morph_animation(const PacketView& packet, uint64_t where) {
    AnimationPiece a;
    if (decode_morph_animation_payload(packet.payload, a) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "MORPH_ANIMATION payload inconsistent or out of range (length, indices, target count, "
                      "interpolation, key range, or a time or weight that is not finite, negative or increasing)");
    return take_keys(a, morph_animation_count_, morph_animations_, "MORPH_ANIMATION", where);
}

Error ReceivedStream::take_keys(const AnimationPiece& a, std::optional<uint16_t>& table_count,
                                std::map<uint16_t, ReceivedAnimation>& table, const char* type, uint64_t where) {
    const bool morph = a.info.path == AnimationPath::Weights;
    const std::string animation_name = std::string(morph ? "morph animation " : "animation ") + std::to_string(a.animation);
    const std::string what = animation_name + " track " + std::to_string(a.track);
    // Comparisons (spec 20.1, 22.2), in order: table size, animation, track, keys.
    if (table_count && *table_count != a.animation_count)
        return reject(where, Error::StreamMismatch,
                      std::string(type) + " table size " + std::to_string(a.animation_count) + " contradicts the " +
                          std::to_string(*table_count) + " of earlier packets");
    auto anim = table.find(a.animation);
    if (anim != table.end() &&
        (anim->second.track_count != a.track_count || anim->second.name != a.name || anim->second.joins != a.joins))
        return reject(where, Error::StreamMismatch,
                      animation_name + (morph ? ": its track count, joined animation or name contradicts earlier packets"
                                              : ": its track count or name contradicts earlier packets"));
    const ReceivedAnimation::Track* held = nullptr;
    if (anim != table.end()) {
        auto t = anim->second.tracks.find(a.track);
        if (t != anim->second.tracks.end()) held = &t->second;
    }
    if (held && !(held->info == a.info))
        return reject(where, Error::StreamMismatch,
                      what + (morph ? ": its node, target count, interpolation or key count contradicts earlier packets"
                                    : ": its node, path, interpolation or key count contradicts earlier packets"));
    const size_t per_key = animation_values_per_key(a.info.path, a.info.interpolation, a.info.targets);
    const uint32_t begin = a.first_key, end = static_cast<uint32_t>(a.first_key + a.times.size());
    // Keys held before: each must agree; the rest are the gaps this packet fills.
    std::vector<std::pair<uint32_t, uint32_t>> gaps;
    uint32_t cursor = begin;
    if (held) {
        auto run = held->runs.upper_bound(begin);
        if (run != held->runs.begin()) --run;
        for (; run != held->runs.end() && run->first < end; ++run) {
            const uint32_t run_begin = run->first;
            const uint32_t run_end = static_cast<uint32_t>(run_begin + run->second.times.size());
            if (run_end <= cursor) continue;
            if (run_begin > cursor) gaps.emplace_back(cursor, run_begin);
            for (uint32_t k = std::max(run_begin, begin); k < std::min(run_end, end); ++k) {
                bool same = run->second.times[k - run_begin] == a.times[k - begin];
                for (size_t v = 0; v < per_key && same; ++v)
                    same = run->second.values[(k - run_begin) * per_key + v] == a.values[(k - begin) * per_key + v];
                if (!same)
                    return reject(where, Error::StreamMismatch,
                                  what + ": key " + std::to_string(k) + " differs from the one received before");
            }
            cursor = std::max(cursor, run_end);
        }
        if (held->complete) {
            // Keys are kept whole once complete: compare with them.
            for (uint32_t k = begin; k < end; ++k) {
                bool same = held->times[k] == a.times[k - begin];
                for (size_t v = 0; v < per_key && same; ++v)
                    same = held->values[size_t(k) * per_key + v] == a.values[(k - begin) * per_key + v];
                if (!same)
                    return reject(where, Error::StreamMismatch,
                                  what + ": key " + std::to_string(k) + " differs from the one received before");
            }
            cursor = end;
        }
    }
    if (cursor < end) gaps.emplace_back(cursor, end);
    uint64_t fresh = 0;
    for (auto [x, y] : gaps) fresh += y - x;
    if (fresh == 0) {  // every key held already (so its animation and track were accepted before)
        ++counters_.duplicates;
        return Error::Ok;
    }
    const uint64_t memory = fresh * 4 * (1 + per_key) + gaps.size() * kHeldPacketCost;
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      what + ": the stream's textures and animations exceed this receiver's " +
                          std::to_string(limits_.max_texture_bytes) + "-byte memory limit for them");
    table_count = a.animation_count;
    ReceivedAnimation& animation = table[a.animation];
    if (animation.tracks.empty() && animation.track_count == 0) {
        animation.track_count = a.track_count;
        animation.name = a.name;
        animation.joins = a.joins;
    }
    auto [it, fresh_track] = animation.tracks.try_emplace(a.track);
    ReceivedAnimation::Track& track = it->second;
    if (fresh_track) track.info = a.info;
    for (auto [x, y] : gaps) {
        ReceivedAnimation::Track::Run run;
        run.times.assign(a.times.begin() + (x - begin), a.times.begin() + (y - begin));
        run.values.assign(a.values.begin() + std::ptrdiff_t((x - begin) * per_key),
                          a.values.begin() + std::ptrdiff_t((y - begin) * per_key));
        track.runs.emplace(x, std::move(run));
    }
    track.keys_held += static_cast<uint32_t>(fresh);
    track.memory += memory;
    texture_bytes_ += memory;
    if (track.keys_held == track.info.key_count) {
        // Every key: join the runs (in key order, they are disjoint and cover the track).
        track.times.reserve(track.info.key_count);
        track.values.reserve(size_t(track.info.key_count) * per_key);
        for (auto& [first, run] : track.runs) {
            track.times.insert(track.times.end(), run.times.begin(), run.times.end());
            track.values.insert(track.values.end(), run.values.begin(), run.values.end());
        }
        track.runs.clear();
        track.complete = true;
        track.usable = std::adjacent_find(track.times.begin(), track.times.end(),
                                          [](float x, float y) { return !(y > x); }) == track.times.end();
    }
    ++counters_.accepted;
    return Error::Ok;
}

namespace {

// The morph tracks of `animation` (morph index `m`) kept into a written animation whose weights
// targets so far are `nodes` (spec 22.4).
void keep_morph_tracks(uint16_t m, const ReceivedStream::ReceivedAnimation& animation,
                       const std::function<bool(uint16_t)>& node_shown, const std::function<unsigned(uint16_t)>& node_targets,
                       std::vector<uint16_t>& nodes, std::vector<std::pair<uint16_t, uint16_t>>& out) {
    for (const auto& [t, track] : animation.tracks) {
        if (!track.usable || !node_targets || !node_shown(track.info.node) ||
            node_targets(track.info.node) != track.info.targets)
            continue;
        if (std::find(nodes.begin(), nodes.end(), track.info.node) != nodes.end()) continue;
        nodes.push_back(track.info.node);
        out.emplace_back(m, t);
    }
}

}  // namespace

std::vector<ShownAnimation> shown_animations(const ReceivedStream& stream,
                                             const std::function<bool(uint16_t node)>& node_shown,
                                             const std::function<unsigned(uint16_t node)>& node_targets) {
    std::vector<ShownAnimation> out;
    // Format 1.6 (spec 22.4): once a MORPH_ANIMATION packet has been taken, an ANIMATION waits for
    // every morph animation to have taken a packet, and for those joining it to be complete.
    const auto& morphs = stream.morph_animations();
    const bool morph_table_known =
        !stream.morph_animation_count() || morphs.size() == *stream.morph_animation_count();
    for (const auto& [index, animation] : stream.animations()) {
        if (!animation.complete() || !morph_table_known) continue;
        bool joined_complete = true;
        for (const auto& [m, morph] : morphs)
            if (morph.joins == index && !morph.complete()) joined_complete = false;
        if (!joined_complete) continue;
        ShownAnimation shown{index, false, {}, {}};
        std::vector<std::pair<uint16_t, AnimationPath>> targets;
        for (const auto& [t, track] : animation.tracks) {
            if (!track.usable || !node_shown(track.info.node)) continue;
            const std::pair<uint16_t, AnimationPath> target{track.info.node, track.info.path};
            if (std::find(targets.begin(), targets.end(), target) != targets.end()) continue;
            targets.push_back(target);
            shown.tracks.push_back(t);
        }
        std::vector<uint16_t> weight_nodes;
        for (const auto& [m, morph] : morphs)
            if (morph.joins == index) keep_morph_tracks(m, morph, node_shown, node_targets, weight_nodes, shown.morph_tracks);
        if (!shown.tracks.empty() || !shown.morph_tracks.empty()) out.push_back(std::move(shown));
    }
    for (const auto& [m, morph] : morphs) {
        if (morph.joins != kNone || !morph.complete()) continue;
        ShownAnimation shown{m, true, {}, {}};
        std::vector<uint16_t> weight_nodes;
        keep_morph_tracks(m, morph, node_shown, node_targets, weight_nodes, shown.morph_tracks);
        if (!shown.morph_tracks.empty()) out.push_back(std::move(shown));
    }
    return out;
}

}  // namespace ellicast

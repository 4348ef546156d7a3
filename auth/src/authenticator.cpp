// The receiver's filter for signed streams (spec 16.3).
#include "ellicast/auth.h"

#include <algorithm>
#include <cstdio>

namespace ellicast::auth {

namespace {
constexpr size_t kMaxRejectionsKept = 10'000;
}

Authenticator::Authenticator(const PublicKey& key) : Authenticator(key, Limits{}) {}

Authenticator::Authenticator(const PublicKey& key, Limits limits)
    : key_(key), key_id_(key_id_of(std::span<const uint8_t, 32>(key))), limits_(limits),
      verify_budget_(limits.verify_burst) {}

Authenticator::Verdict Authenticator::reject(uint64_t where, Error e, std::string detail) {
    last_error_ = e;
    if (e == Error::NotAuthenticated) ++counters_.not_authenticated;
    if (rejections_.size() < kMaxRejectionsKept) rejections_.push_back({where, e, std::move(detail)});
    return Verdict::Rejected;
}

namespace {
std::string hex32(uint32_t v) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%08X", v);
    return text;
}

std::string type_of(const std::vector<uint8_t>& bytes) {
    return bytes.size() > 6 ? packet_type_name(bytes[6]) : std::string("?");
}
}  // namespace

Authenticator::Judgement Authenticator::judge(const PacketDigest& digest, uint32_t stream_id,
                                              std::optional<uint32_t> info_content) const {
    auto it = listed_.find(digest);
    if (it == listed_.end()) return Judgement::Unlisted;
    const Binding& b = it->second;
    if (b.unbound) return Judgement::Pass;                                     // rule 1
    auto c = content_.find(stream_id);
    if (info_content)  // rule 2: a STREAM_INFO of its own content, and of the stream's when it has one
        return b.binds(*info_content) && (c == content_.end() || c->second == *info_content) ? Judgement::Pass
                                                                                             : Judgement::OtherContent;
    if (c == content_.end()) return Judgement::AwaitContent;                   // rule 4
    return b.binds(c->second) ? Judgement::Pass : Judgement::OtherContent;     // rule 3
}

bool Authenticator::passed(uint32_t stream_id, std::optional<uint32_t> info_content) {
    ++counters_.passed;
    return info_content && content_.emplace(stream_id, *info_content).second;
}

std::string Authenticator::other_content_detail(uint8_t type, uint32_t stream_id) const {
    auto c = content_.find(stream_id);
    if (c == content_.end())
        return packet_type_name(type) + " packet that verified MANIFEST parts list only for another content than "
                                        "its own content id";
    return packet_type_name(type) + " packet that verified MANIFEST parts list only for another content than " +
           hex32(c->second) + ", the one stream " + std::to_string(stream_id) + " shows (spliced from another stream?)";
}

Authenticator::Verdict Authenticator::take(const PacketView& packet, std::span<const uint8_t> bytes, uint64_t where) {
    last_error_ = Error::Ok;
    bytes = bytes.first(std::min(bytes.size(), packet.size));
    if (limits_.packets_per_verification > 0 && ++packets_toward_budget_ >= limits_.packets_per_verification) {
        packets_toward_budget_ = 0;
        verify_budget_ = std::min(verify_budget_ + 1, limits_.verify_burst);
    }
    if (packet.header.type == static_cast<uint8_t>(PacketType::Manifest)) return take_manifest(packet, bytes, where);
    const PacketDigest digest = packet_digest(bytes);
    const uint32_t stream_id = packet.header.stream_id;
    const std::optional<uint32_t> info_content = stream_info_content_id(packet.header.type, packet.payload);
    switch (judge(digest, stream_id, info_content)) {
    case Judgement::Pass:
        // A STREAM_INFO that gives its stream a content releases what waited for it, after itself.
        if (passed(stream_id, info_content)) settle();
        return Verdict::Pass;
    case Judgement::OtherContent:
        return reject(where, Error::NotAuthenticated, other_content_detail(packet.header.type, stream_id));
    case Judgement::AwaitContent:
        break;
    case Judgement::Unlisted:
        if (complete_streams_.count(stream_id))
            return reject(where, Error::NotAuthenticated,
                          packet_type_name(packet.header.type) + " packet that the verified manifest of stream " +
                              std::to_string(stream_id) + " does not list");
        break;
    }
    const size_t cost = bytes.size() + kHeldPacketCost;
    if (limits_.max_held_packets == 0 || cost > limits_.max_held_bytes) {
        if (listed_.count(digest))
            return reject(where, Error::NotAuthenticated,
                          packet_type_name(packet.header.type) + " packet listed only for a content that stream " +
                              std::to_string(stream_id) + " never showed (no STREAM_INFO of it was authenticated)");
        return reject(where, Error::NotAuthenticated,
                      packet_type_name(packet.header.type) + " packet that no verified MANIFEST lists");
    }
    hold(digest, stream_id, info_content, bytes, where);
    return Verdict::Held;
}

void Authenticator::hold(const PacketDigest& digest, uint32_t stream_id, std::optional<uint32_t> info_content,
                         std::span<const uint8_t> bytes, uint64_t where) {
    const size_t cost = bytes.size() + kHeldPacketCost;
    while (!held_.empty() &&
           (held_.size() + 1 > limits_.max_held_packets || held_bytes_ + cost > limits_.max_held_bytes))
        drop_oldest();
    held_.push_back({digest, stream_id, info_content, std::vector<uint8_t>(bytes.begin(), bytes.end()), where});
    held_bytes_ += cost;
    counters_.held = held_.size();
}

void Authenticator::settle() {
    // Until nothing changes: a released STREAM_INFO can give a stream the content others wait for.
    for (bool changed = true; changed;) {
        changed = false;
        std::deque<Held> keep;
        for (Held& h : held_) {
            const Judgement j = judge(h.digest, h.stream_id, h.info_content);
            if (j == Judgement::Unlisted || j == Judgement::AwaitContent) {
                keep.push_back(std::move(h));
                continue;
            }
            held_bytes_ -= h.bytes.size() + kHeldPacketCost;
            if (j == Judgement::OtherContent) {
                reject(h.where, Error::NotAuthenticated, other_content_detail(h.bytes[6], h.stream_id));
                continue;
            }
            if (passed(h.stream_id, h.info_content)) changed = true;
            ++counters_.released;
            released_.push_back({std::move(h.bytes), h.where});
        }
        held_.swap(keep);
    }
    counters_.held = held_.size();
}

void Authenticator::drop_oldest() {
    Held& h = held_.front();
    held_bytes_ -= h.bytes.size() + kHeldPacketCost;
    const uint64_t where = h.where;
    const std::string type = type_of(h.bytes);
    const bool listed = listed_.count(h.digest) > 0;
    held_.pop_front();
    counters_.held = held_.size();
    reject(where, Error::NotAuthenticated,
           type + (listed ? " packet held for its stream's STREAM_INFO, which did not come before the hold was full"
                          : " packet held for a MANIFEST that did not come before the hold was full"));
}

void Authenticator::reject_unlisted(uint32_t stream_id) {
    std::deque<Held> keep;
    for (Held& h : held_) {
        if (h.stream_id != stream_id || listed_.count(h.digest)) {
            keep.push_back(std::move(h));
            continue;
        }
        held_bytes_ -= h.bytes.size() + kHeldPacketCost;
        reject(h.where, Error::NotAuthenticated,
               type_of(h.bytes) + " packet that the verified manifest of stream " + std::to_string(stream_id) +
                   " does not list");
    }
    held_.swap(keep);
    counters_.held = held_.size();
}

Authenticator::Verdict Authenticator::take_manifest(const PacketView& packet, std::span<const uint8_t> bytes,
                                                    uint64_t where) {
    ManifestPart part;
    if (decode_manifest_payload(packet.payload, part) != Error::Ok) {
        ++counters_.malformed;
        return reject(where, Error::MalformedPayload, "MANIFEST whose length, part or digest range is inconsistent");
    }
    if (!is_known_manifest_scheme(part.scheme)) {
        ++counters_.unknown_scheme;
        return Verdict::Manifest;
    }
    const PacketDigest self = packet_digest(bytes);
    if (verified_manifests_.count(self)) {
        ++counters_.manifests_repeated;
        return Verdict::Repeat;
    }
    if (part.key_id != key_id_) {
        ++counters_.manifests_failed;
        std::string detail = "MANIFEST signed by key id " + to_hex(part.key_id) + ", not " + to_hex(key_id_) +
                             " (the key given)";
        if (first_failure_.empty()) first_failure_ = detail;
        return reject(where, Error::ManifestSignature, std::move(detail));
    }
    if (limits_.verify_burst > 0) {
        if (verify_budget_ == 0) {
            ++counters_.manifests_unchecked;
            return Verdict::Manifest;  // not rejected: it may be the real one, which comes again
        }
        --verify_budget_;
    }
    if (!verify_manifest(bytes, part, key_)) {
        ++counters_.manifests_failed;
        std::string detail = "MANIFEST part " + std::to_string(part.part) + " of stream " +
                             std::to_string(packet.header.stream_id) +
                             ": its signature does not verify with the key given (forged or altered)";
        if (first_failure_.empty()) first_failure_ = detail;
        return reject(where, Error::ManifestSignature, std::move(detail));
    }
    if (listed_.size() + part.digests.size() > limits_.max_digests) {
        // Verified, but more than this receiver keeps: count it as verified, list nothing more.
        ++counters_.manifests_verified;
        return Verdict::Manifest;
    }
    verified_manifests_.insert(self);
    ++counters_.manifests_verified;
    const bool bound = part.scheme == kManifestSchemeBound;
    for (const PacketDigest& d : part.digests) {
        Binding& b = listed_[d];
        if (!bound) b.unbound = true;
        else if (!b.binds(part.content_id)) b.contents.push_back(part.content_id);
    }
    // Release what this part authenticates, in arrival order (or reject what it lists for another content).
    settle();
    // Once every part of one manifest of this stream verified, unlisted packets cannot be listed.
    const uint32_t stream_id = packet.header.stream_id;
    std::set<uint16_t>& parts =
        parts_[stream_id][{bound ? std::optional<uint32_t>(part.content_id) : std::nullopt, part.part_count,
                           part.packet_count}];
    parts.insert(part.part);
    if (parts.size() == part.part_count && complete_streams_.insert(stream_id).second) reject_unlisted(stream_id);
    return Verdict::Manifest;
}

std::vector<Authenticator::Released> Authenticator::take_released() {
    std::vector<Released> out;
    out.swap(released_);
    return out;
}

std::string Authenticator::problem() const {
    if (counters_.manifests_verified > 0) return "";
    std::string s = "no MANIFEST verified with key id " + to_hex(key_id_);
    if (counters_.manifests_failed + counters_.malformed + counters_.unknown_scheme == 0)
        return s + ": no MANIFEST packet arrived (is the stream signed?)";
    s += ": " + std::to_string(counters_.manifests_failed) + " failed verification";
    if (counters_.malformed) s += ", " + std::to_string(counters_.malformed) + " malformed";
    if (counters_.unknown_scheme) s += ", " + std::to_string(counters_.unknown_scheme) + " of an unknown scheme";
    if (!first_failure_.empty()) s += " (first: " + first_failure_ + ")";
    return s;
}

RecordingAuthentication authenticate_recording(const std::vector<ContainerPacket>& packets,
                                               std::span<const uint8_t> file_bytes, const PublicKey& key) {
    // Nothing is held: every MANIFEST is verified first, then every other packet is listed or not.
    Authenticator::Limits limits;
    limits.max_held_packets = 0;
    limits.max_digests = SIZE_MAX;
    limits.verify_burst = 0;  // a file is read once: every MANIFEST in it is checked
    Authenticator a(key, limits);
    RecordingAuthentication out;
    out.verdicts.assign(packets.size(), Authenticator::Verdict::Rejected);
    out.errors.assign(packets.size(), Error::Ok);
    auto bytes_of = [&](const ContainerPacket& p) { return file_bytes.subspan(p.offset, p.view.size); };
    // Pass 0: every MANIFEST; pass 1: the STREAM_INFO packets that can give a stream its content, in
    // file order (the first that passes gives it, spec 25.2); pass 2: every other packet.
    auto pass_of = [](const PacketView& v) {
        if (v.header.type == static_cast<uint8_t>(PacketType::Manifest)) return 0;
        if (v.header.type == static_cast<uint8_t>(PacketType::StreamInfo) && v.payload.size() >= 16) return 1;
        return 2;
    };
    for (int pass = 0; pass < 3; ++pass)
        for (size_t i = 0; i < packets.size(); ++i) {
            if (pass_of(packets[i].view) != pass) continue;
            out.verdicts[i] = a.take(packets[i].view, bytes_of(packets[i]), packets[i].offset);
            if (out.verdicts[i] == Authenticator::Verdict::Rejected) out.errors[i] = a.last_error();
        }
    out.counters = a.counters();
    out.rejections = a.rejections();
    std::stable_sort(out.rejections.begin(), out.rejections.end(),
                     [](const Rejection& x, const Rejection& y) { return x.where < y.where; });
    out.problem = a.problem();
    return out;
}

}  // namespace ellicast::auth

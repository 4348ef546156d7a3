// The receiver's filter for signed streams (spec 16.3).
#include "ellicast/auth.h"

#include <algorithm>

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

Authenticator::Verdict Authenticator::take(const PacketView& packet, std::span<const uint8_t> bytes, uint64_t where) {
    last_error_ = Error::Ok;
    bytes = bytes.first(std::min(bytes.size(), packet.size));
    if (limits_.packets_per_verification > 0 && ++packets_toward_budget_ >= limits_.packets_per_verification) {
        packets_toward_budget_ = 0;
        verify_budget_ = std::min(verify_budget_ + 1, limits_.verify_burst);
    }
    if (packet.header.type == static_cast<uint8_t>(PacketType::Manifest)) return take_manifest(packet, bytes, where);
    const PacketDigest digest = packet_digest(bytes);
    if (listed_.count(digest)) {
        ++counters_.passed;
        return Verdict::Pass;
    }
    const uint32_t stream_id = packet.header.stream_id;
    if (complete_streams_.count(stream_id))
        return reject(where, Error::NotAuthenticated,
                      packet_type_name(packet.header.type) + " packet that the verified manifest of stream " +
                          std::to_string(stream_id) + " does not list");
    const size_t cost = bytes.size() + kHeldPacketCost;
    if (limits_.max_held_packets == 0 || cost > limits_.max_held_bytes)
        return reject(where, Error::NotAuthenticated,
                      packet_type_name(packet.header.type) + " packet that no verified MANIFEST lists");
    while (!held_.empty() &&
           (held_.size() + 1 > limits_.max_held_packets || held_bytes_ + cost > limits_.max_held_bytes))
        drop_oldest();
    held_.push_back({digest, stream_id, std::vector<uint8_t>(bytes.begin(), bytes.end()), where});
    held_bytes_ += cost;
    counters_.held = held_.size();
    return Verdict::Held;
}

void Authenticator::drop_oldest() {
    Held& h = held_.front();
    held_bytes_ -= h.bytes.size() + kHeldPacketCost;
    const uint64_t where = h.where;
    const std::string type = h.bytes.size() > 6 ? packet_type_name(h.bytes[6]) : "?";
    held_.pop_front();
    counters_.held = held_.size();
    reject(where, Error::NotAuthenticated,
           type + " packet held for a MANIFEST that did not come before the hold was full");
}

void Authenticator::reject_unlisted(uint32_t stream_id) {
    std::deque<Held> keep;
    for (Held& h : held_) {
        if (h.stream_id != stream_id) {
            keep.push_back(std::move(h));
            continue;
        }
        held_bytes_ -= h.bytes.size() + kHeldPacketCost;
        reject(h.where, Error::NotAuthenticated,
               (h.bytes.size() > 6 ? packet_type_name(h.bytes[6]) : std::string("?")) +
                   " packet that the verified manifest of stream " + std::to_string(stream_id) + " does not list");
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
    if (part.scheme != kManifestSchemeEd25519) {
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
    std::unordered_set<PacketDigest, DigestHash> fresh(part.digests.begin(), part.digests.end());
    listed_.insert(part.digests.begin(), part.digests.end());
    // Release what this part lists, in arrival order.
    std::deque<Held> keep;
    for (Held& h : held_) {
        if (fresh.count(h.digest)) {
            held_bytes_ -= h.bytes.size() + kHeldPacketCost;
            released_.push_back({std::move(h.bytes), h.where});
            ++counters_.released;
            ++counters_.passed;
        } else {
            keep.push_back(std::move(h));
        }
    }
    held_.swap(keep);
    counters_.held = held_.size();
    // Once every part of one manifest of this stream verified, unlisted packets cannot be listed.
    const uint32_t stream_id = packet.header.stream_id;
    std::set<uint16_t>& parts = parts_[stream_id][{part.part_count, part.packet_count}];
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
    for (int pass = 0; pass < 2; ++pass)
        for (size_t i = 0; i < packets.size(); ++i) {
            const bool manifest = packets[i].view.header.type == static_cast<uint8_t>(PacketType::Manifest);
            if (manifest != (pass == 0)) continue;
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

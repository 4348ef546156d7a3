// Signing a stream: its MANIFEST packets (spec 16.2), and checking one.
#include "ellicast/auth.h"

#include <sodium.h>

#include <algorithm>
#include <optional>
#include <set>

namespace ellicast::auth {

bool is_detail_type(uint8_t type) {
    return is_points_type(type) || type == static_cast<uint8_t>(PacketType::PointsRepair) ||
           type == static_cast<uint8_t>(PacketType::TextureFragment);
}

namespace {
// Parts never mix these: what a first picture needs (STREAM_INFO and ELLIPSOIDS: a carousel repeats
// their part with every STREAM_INFO repeat, so it is kept apart), the rest of the base, the detail.
int part_class(uint8_t type) {
    if (type == static_cast<uint8_t>(PacketType::StreamInfo) || type == static_cast<uint8_t>(PacketType::Ellipsoids))
        return 0;
    return is_detail_type(type) ? 2 : 1;
}
}  // namespace

Error sign_packets(const std::vector<std::vector<uint8_t>>& packets, const KeyPair& key, size_t packet_size,
                   uint32_t first_sequence, std::vector<std::vector<uint8_t>>& manifests, std::string& error,
                   uint8_t scheme) {
    manifests.clear();
    if (!is_known_manifest_scheme(scheme)) {
        error = "MANIFEST scheme " + std::to_string(scheme) + " is not one this library writes (1 or 2)";
        return Error::MalformedPayload;
    }
    if (!available()) {
        error = "libsodium cannot be initialized";
        return Error::IoError;
    }
    const size_t capacity = digests_per_manifest_packet(packet_size, scheme);
    if (capacity == 0) {
        error = "a MANIFEST packet of " + std::to_string(packet_size) + " bytes has no room for a digest (at least " +
                std::to_string(kPacketOverhead + manifest_fixed_size(scheme) + kManifestSignatureSize + kPacketDigestSize) +
                " bytes)";
        return Error::MalformedPayload;
    }
    if (packets.size() > 0xFFFFFFFFu) {
        error = "more than 2^32 packets to sign";
        return Error::MalformedPayload;
    }
    // Parts: runs of at most `capacity` packets of one class (base or detail).
    std::vector<std::pair<size_t, size_t>> runs;  // [begin, end)
    uint32_t stream_id = 0;
    std::optional<uint32_t> content_id;  // of the STREAM_INFO packets: what scheme 2 binds the parts to
    for (size_t i = 0; i < packets.size(); ++i) {
        PacketView view;
        if (parse_packet(packets[i], view) != Error::Ok) {
            error = "packet " + std::to_string(i) + " is not a valid packet";
            return Error::MalformedPayload;
        }
        if (view.header.type == static_cast<uint8_t>(PacketType::Manifest)) {
            error = "packet " + std::to_string(i) + " is a MANIFEST: a manifest does not list MANIFEST packets";
            return Error::MalformedPayload;
        }
        if (i == 0) stream_id = view.header.stream_id;
        if (view.header.stream_id != stream_id) {
            error = "packet " + std::to_string(i) + " has stream id " + std::to_string(view.header.stream_id) +
                    ", the first had " + std::to_string(stream_id) + ": a manifest signs one stream";
            return Error::MalformedPayload;
        }
        // The content id a receiver binds with (spec 25.2).
        if (const auto id = stream_info_content_id(view.header.type, view.payload)) {
            if (content_id && *content_id != *id) {
                error = "packet " + std::to_string(i) + " is a STREAM_INFO of content id " + std::to_string(*id) +
                        ", an earlier one said " + std::to_string(*content_id) + ": a manifest signs one content";
                return Error::MalformedPayload;
            }
            content_id = id;
        }
        const int kind = part_class(view.header.type);
        const bool same_class = !runs.empty() && part_class(packets[runs.back().first][6]) == kind;
        if (same_class && runs.back().second - runs.back().first < capacity) runs.back().second = i + 1;
        else runs.push_back({i, i + 1});
    }
    if (runs.empty()) runs.push_back({0, 0});  // an empty stream still gets a (signed, empty) manifest
    if (runs.size() > 0xFFFF) {
        error = std::to_string(runs.size()) + " MANIFEST parts needed, at most 65535 (use larger packets)";
        return Error::MalformedPayload;
    }
    PublicKey derived{};
    std::vector<uint8_t> secret(crypto_sign_SECRETKEYBYTES);
    crypto_sign_seed_keypair(derived.data(), secret.data(), key.seed.data());
    sodium_memzero(secret.data(), secret.size());
    if (derived != key.public_key) {
        error = "the key pair is inconsistent: its public key is not the one its seed derives";
        return Error::MalformedPayload;
    }
    const auto key_id = key_id_of(std::span<const uint8_t, 32>(key.public_key));
    for (size_t r = 0; r < runs.size(); ++r) {
        ManifestPart part;
        part.scheme = scheme;
        part.content_id = scheme == kManifestSchemeBound ? content_id.value_or(0) : 0;
        part.part = static_cast<uint16_t>(r);
        part.part_count = static_cast<uint16_t>(runs.size());
        part.packet_count = static_cast<uint32_t>(packets.size());
        part.first = static_cast<uint32_t>(runs[r].first);
        part.key_id = key_id;
        for (size_t i = runs[r].first; i < runs[r].second; ++i) part.digests.push_back(packet_digest(packets[i]));
        PacketHeader h;
        h.version_minor = scheme == kManifestSchemeBound ? kBoundManifestMinor : kManifestMinor;
        h.stream_id = stream_id;
        h.sequence = first_sequence + static_cast<uint32_t>(r);
        manifests.push_back(signed_manifest_packet(h, std::move(part), key));
    }
    return Error::Ok;
}

std::vector<uint8_t> signed_manifest_packet(PacketHeader header, ManifestPart part, const KeyPair& key) {
    header.type = static_cast<uint8_t>(PacketType::Manifest);
    header.flags = kFlagSkippable;
    header.object_id = kStreamObjectId;
    std::vector<uint8_t> secret(crypto_sign_SECRETKEYBYTES);
    PublicKey derived{};
    crypto_sign_seed_keypair(derived.data(), secret.data(), key.seed.data());
    std::vector<uint8_t> packet = write_packet(header, encode_manifest_payload(part));
    const std::vector<uint8_t> message = manifest_signed_message(packet);
    crypto_sign_detached(part.signature.data(), nullptr, message.data(), message.size(), secret.data());
    sodium_memzero(secret.data(), secret.size());
    return write_packet(header, encode_manifest_payload(part));
}

bool verify_manifest(std::span<const uint8_t> packet, const ManifestPart& part, const PublicKey& key) {
    if (!available()) return false;
    if (part.key_id != key_id_of(std::span<const uint8_t, 32>(key))) return false;
    const std::vector<uint8_t> message = manifest_signed_message(packet);
    if (message.empty()) return false;
    return crypto_sign_verify_detached(part.signature.data(), message.data(), message.size(), key.data()) == 0;
}

}  // namespace ellicast::auth

namespace ellicast::auth {

Error sign_stream(std::vector<std::vector<uint8_t>>& packets, const KeyPair& key, size_t& manifest_count,
                  std::string& error) {
    // Distinct packets, MANIFESTs dropped (re-signing replaces them), first copy kept.
    std::vector<std::vector<uint8_t>> listed;
    std::set<PacketDigest> seen;
    size_t packet_size = kDefaultPacketSize;
    bool have_info = false;
    for (size_t i = 0; i < packets.size(); ++i) {
        PacketView view;
        if (parse_packet(packets[i], view) != Error::Ok) {
            error = "packet " + std::to_string(i) + " is not a valid packet";
            return Error::MalformedPayload;
        }
        if (view.header.type == static_cast<uint8_t>(PacketType::Manifest)) continue;
        if (!have_info && view.header.type == static_cast<uint8_t>(PacketType::StreamInfo)) {
            StreamInfoPart part;
            if (decode_stream_info_payload(view.payload, part) == Error::Ok) {
                packet_size = part.info.packet_size;
                have_info = true;
            }
        }
        if (seen.insert(packet_digest(packets[i])).second) listed.push_back(std::move(packets[i]));
    }
    std::vector<std::vector<uint8_t>> manifests;
    if (Error e = sign_packets(listed, key, packet_size, 0, manifests, error); e != Error::Ok) return e;
    manifest_count = manifests.size();
    packets = std::move(manifests);
    packets.insert(packets.end(), std::make_move_iterator(listed.begin()), std::make_move_iterator(listed.end()));
    for (size_t i = 0; i < packets.size(); ++i) restamp_packet(packets[i], static_cast<uint32_t>(i));
    return Error::Ok;
}

}  // namespace ellicast::auth

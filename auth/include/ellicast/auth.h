// Signed streams (format 1.2, spec section 16): Ed25519 keys, signing a stream (its MANIFEST
// packets), and the filter a receiver with the sender's public key puts in front of its decoder.
//
// Depends on the format library and libsodium only. Nothing here trusts its input: a MANIFEST is
// parsed by the format library and verified before anything it says is used, and everything a
// receiver holds while it waits for a MANIFEST is bounded by Authenticator::Limits.
#pragma once

#include <ellicast/format.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace ellicast::auth {

using PublicKey = std::array<uint8_t, 32>;
using Seed = std::array<uint8_t, 32>;

struct KeyPair {
    PublicKey public_key{};
    Seed seed{};  // the secret: Ed25519's 32-byte private key (RFC 8032), from which the key pair derives
};

// False when libsodium cannot be initialized (then nothing below works).
bool available();
KeyPair generate_key_pair();               // from the system's random source
KeyPair key_pair_from_seed(const Seed& seed);  // deterministic (conformance vectors, tests)

// Key files hold one line of text:
//   public: "ellicast-ed25519-public-key <64 hex digits>"
//   secret: "ellicast-ed25519-secret-key <64 hex digits of the seed>"
std::string public_key_text(const PublicKey& key);
std::string secret_key_text(const KeyPair& key);
std::string to_hex(std::span<const uint8_t> bytes);
// A public key from a key file, or given directly as 64 hex digits. On failure `error` says what
// was wrong (a missing file, a secret key given where a public one is wanted, a bad line).
bool read_public_key(const std::string& file_or_hex, PublicKey& out, std::string& error);
bool read_secret_key(const std::string& path, KeyPair& out, std::string& error);
// Writes the secret key (mode 0600) and the public key files. Refuses to replace an existing file.
bool write_key_pair(const std::string& secret_path, const std::string& public_path, const KeyPair& key,
                    std::string& error);

// Signs a stream: the MANIFEST packets listing every packet of `packets` (whole packets of one stream
// id, none of them a MANIFEST) in the given order, at most `packet_size` bytes each, numbered from
// `first_sequence`. A new part starts where the listed packets change between what a first picture
// needs (STREAM_INFO, ELLIPSOIDS), the rest of the base and detail (POINTS and TEXTURE_FRAGMENT), so
// that a carousel can send each part with the packets it lists (spec 16.4). Scheme 2 (format 1.9, the
// default) binds every part to the content id of the STREAM_INFO packets listed (spec 25.1; 0 when
// there is none); scheme 1 (format 1.2) writes the unbound parts of older signers. MalformedPayload
// (with `error`) when the packets are not such a list, their STREAM_INFO packets name two contents,
// there are more than 65535 parts, or the packet size leaves no room for a digest.
Error sign_packets(const std::vector<std::vector<uint8_t>>& packets, const KeyPair& key, size_t packet_size,
                   uint32_t first_sequence, std::vector<std::vector<uint8_t>>& manifests, std::string& error,
                   uint8_t scheme = kManifestSchemeBound);

// One MANIFEST packet: `part` (its fields as given, signature aside) under `header` (type, flags and
// object id are set here), signed with `key`. sign_packets makes its parts with it; a test or a
// conformance vector can make a part sign_packets would not (another content id, say).
std::vector<uint8_t> signed_manifest_packet(PacketHeader header, ManifestPart part, const KeyPair& key);

// Signs a recorded or freshly encoded stream in place: its distinct packets (the first copy of each;
// MANIFEST packets already there are dropped, so signing again replaces the signature) preceded by
// their MANIFEST parts, at the packet size its STREAM_INFO declares, every packet renumbered from 0.
// `manifest_count` receives the number of parts. Errors as sign_packets.
Error sign_stream(std::vector<std::vector<uint8_t>>& packets, const KeyPair& key, size_t& manifest_count,
                  std::string& error);

// True when the whole MANIFEST packet `packet` (parsed into `part`) carries `key`'s key id and a
// signature that verifies with it (spec 16.2, 16.3 step 2).
bool verify_manifest(std::span<const uint8_t> packet, const ManifestPart& part, const PublicKey& key);

// Whether a packet is detail (POINTS, TEXTURE_FRAGMENT) rather than base, for the manifest's parts.
bool is_detail_type(uint8_t type);

struct DigestHash {
    size_t operator()(const PacketDigest& d) const noexcept {
        size_t h = 0;
        for (size_t i = 0; i < sizeof(size_t); ++i) h |= size_t{d[i]} << (8 * i);
        return h;
    }
};

// A receiver's filter with the sender's public key (spec 16.3, 25.2). Every intact packet goes through
// take(); a packet comes out to the decoder only once a verified MANIFEST lists its digest for the
// content its stream shows (the content id of the first STREAM_INFO passed; a scheme-1 part lists
// for any content): at once (Pass), or later from take_released() when the MANIFEST that lists it,
// or the STREAM_INFO that gives its stream a content, arrives after it.
class Authenticator {
public:
    struct Limits {
        // Packets waiting for the MANIFEST that lists them: each counts its size plus
        // kHeldPacketCost. When one does not fit, those held longest are dropped until it does.
        size_t max_held_packets = 4096;
        size_t max_held_bytes = 8u << 20;
        // Digests kept from verified MANIFESTs (about 50 bytes each): a sender's streams together.
        size_t max_digests = 1u << 21;
        // Ed25519 verifications a forger can make a receiver do (spec 16.3 lets a receiver bound
        // them): a budget of verify_burst checks, and one more for every packets_per_verification
        // packets that go through take(). A MANIFEST that is not a repeat and finds the budget empty
        // is dropped unchecked (counted in manifests_unchecked); the carousel sends it again. The
        // real sender needs one check per distinct MANIFEST part (a few per stream), so only a flood
        // of forged MANIFESTs meets the bound, and it then costs at most one check per 16 packets.
        // 0 = unbounded (recordings: every MANIFEST is checked).
        size_t verify_burst = 64;
        size_t packets_per_verification = 16;
    };
    enum class Verdict {
        Pass,       // listed by a verified MANIFEST: give it to the decoder
        Manifest,   // a MANIFEST that verified now (or an unknown scheme, skipped): nothing to decode
        Repeat,     // a copy of a MANIFEST verified before
        Held,       // kept until a MANIFEST lists it, or its stream has a content
        Rejected,   // see last_error(): bad manifest signature, not authenticated, malformed payload
    };
    struct Counters {
        uint64_t passed = 0;              // packets given to the decoder, released ones included
        uint64_t released = 0;            // of those, held first
        uint64_t manifests_verified = 0;  // distinct MANIFEST packets whose signature verified
        uint64_t manifests_repeated = 0;  // copies of those
        uint64_t manifests_failed = 0;    // bad manifest signature (another key id, or a forgery)
        uint64_t manifests_unchecked = 0; // dropped unchecked: the verification budget was spent
        uint64_t malformed = 0;           // malformed MANIFEST payloads
        uint64_t unknown_scheme = 0;      // MANIFESTs of a later scheme, skipped
        uint64_t not_authenticated = 0;   // rejected: listed by no verified MANIFEST for the content shown
        uint64_t held = 0;                // currently held
    };
    struct Released {
        std::vector<uint8_t> bytes;
        uint64_t where = 0;
    };

    explicit Authenticator(const PublicKey& key);
    Authenticator(const PublicKey& key, Limits limits);

    // `packet` is an intact packet (parse_packet or parse_packet_prefix passed) and `bytes` its whole
    // bytes; `where` is reported with a rejection.
    Verdict take(const PacketView& packet, std::span<const uint8_t> bytes, uint64_t where);
    // The reason of the last Rejected verdict.
    Error last_error() const { return last_error_; }
    // Packets that became authenticated since the last call (released by a MANIFEST), in the order
    // they arrived. Moved out.
    std::vector<Released> take_released();
    // Rejected packets (held ones dropped later included), the first 10,000.
    const std::vector<Rejection>& rejections() const { return rejections_; }
    const Counters& counters() const { return counters_; }
    // Whether every part of a manifest of `stream_id` has verified (then unlisted packets of that
    // stream are rejected at once instead of held).
    bool manifest_complete(uint32_t stream_id) const { return complete_streams_.count(stream_id) > 0; }
    // The content a stream shows: the content id of its first STREAM_INFO passed (spec 25.2).
    std::optional<uint32_t> content(uint32_t stream_id) const {
        auto it = content_.find(stream_id);
        return it == content_.end() ? std::nullopt : std::optional<uint32_t>(it->second);
    }
    // Why nothing is authenticated, for a message: "" once a MANIFEST verified.
    std::string problem() const;
    const PublicKey& key() const { return key_; }

private:
    // What verified MANIFEST parts say of one digest (spec 25.2): listed by a scheme-1 part
    // (unbound: for any content), and the content ids of the scheme-2 parts that list it.
    struct Binding {
        bool unbound = false;
        std::vector<uint32_t> contents;
        bool binds(uint32_t content) const {
            return unbound || std::find(contents.begin(), contents.end(), content) != contents.end();
        }
    };
    enum class Judgement { Pass, OtherContent, AwaitContent, Unlisted };
    struct Held {
        PacketDigest digest;
        uint32_t stream_id;
        std::optional<uint32_t> info_content;  // a STREAM_INFO's own content id
        std::vector<uint8_t> bytes;
        uint64_t where;
    };
    Verdict take_manifest(const PacketView& packet, std::span<const uint8_t> bytes, uint64_t where);
    Verdict reject(uint64_t where, Error e, std::string detail);
    Judgement judge(const PacketDigest& digest, uint32_t stream_id, std::optional<uint32_t> info_content) const;
    // A packet judged Pass: counts it, and a STREAM_INFO sets its stream's content when it has none.
    // Returns whether it set one.
    bool passed(uint32_t stream_id, std::optional<uint32_t> info_content);
    // Held packets judged again (after a MANIFEST verified, or a stream got its content): those that
    // pass are released in arrival order, those bound to another content rejected.
    void settle();
    std::string other_content_detail(uint8_t type, uint32_t stream_id) const;
    void hold(const PacketDigest& digest, uint32_t stream_id, std::optional<uint32_t> info_content,
              std::span<const uint8_t> bytes, uint64_t where);
    void drop_oldest();
    void reject_unlisted(uint32_t stream_id);

    PublicKey key_;
    std::array<uint8_t, kKeyIdSize> key_id_;
    Limits limits_;
    std::unordered_map<PacketDigest, Binding, DigestHash> listed_;
    std::unordered_set<PacketDigest, DigestHash> verified_manifests_;
    // stream id -> (scheme-2 content id or none, part_count, packet_count) -> parts verified
    std::map<uint32_t, std::map<std::tuple<std::optional<uint32_t>, uint16_t, uint32_t>, std::set<uint16_t>>> parts_;
    std::set<uint32_t> complete_streams_;
    // stream id -> the content it shows: that of the first STREAM_INFO passed (spec 25.2)
    std::map<uint32_t, uint32_t> content_;
    std::deque<Held> held_;
    size_t held_bytes_ = 0;
    // Verifications left in the budget, and packets counted toward the next one (Limits).
    size_t verify_budget_ = 0;
    size_t packets_toward_budget_ = 0;
    std::vector<Released> released_;
    std::vector<Rejection> rejections_;
    Counters counters_;
    Error last_error_ = Error::Ok;
    std::string first_failure_;
};

// Authenticates a recording (spec 16.3, last paragraph): verifies every MANIFEST of the file first,
// then judges every other packet in file order, so nothing is held. verdicts[i] is the verdict on
// packets[i] (Pass, Manifest, Repeat or Rejected).
struct RecordingAuthentication {
    std::vector<Authenticator::Verdict> verdicts;
    std::vector<Error> errors;  // per packet: the reason when Rejected, else Ok
    Authenticator::Counters counters;
    std::vector<Rejection> rejections;
    std::string problem;
};
RecordingAuthentication authenticate_recording(const std::vector<ContainerPacket>& packets,
                                               std::span<const uint8_t> file_bytes, const PublicKey& key);

}  // namespace ellicast::auth

namespace ellicast::auth {

// The conformance of a signed recording (spec 16.4): the scheme-1 MANIFEST parts of each stream id form
// one manifest, and it lists every other packet of the file once and nothing else. With `key`, every
// MANIFEST's signature is checked too. A recording without scheme-1 MANIFEST packets gives no problem
// and is_signed = false (MANIFESTs of a later scheme are skipped, as a decoder skips them).
struct SignedRecordingProblem {
    std::optional<uint64_t> offset;  // absent for the manifest as a whole
    std::string message;
};
struct SignedRecordingCheck {
    bool is_signed = false;
    size_t manifest_packets = 0;       // well-formed scheme-1 MANIFEST packets, copies included
    size_t parts = 0;                  // distinct parts
    std::string key_id;                // hex, of the first well-formed part
    bool signatures_checked = false;   // a key was given
    size_t signatures_failed = 0;
    std::vector<SignedRecordingProblem> problems;
};
SignedRecordingCheck check_signed_recording(const std::vector<ContainerPacket>& packets,
                                            std::span<const uint8_t> file_bytes, const PublicKey* key);

}  // namespace ellicast::auth

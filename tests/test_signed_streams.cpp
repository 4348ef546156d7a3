// Signed streams (format 1.2, spec 16): signing, the receiver's filter with the sender's key, the
// carousel of a signed stream, key files, the conformance check of a signed recording, and the
// command line (keygen, encode --sign, sign, validate/decode --key).
#include "broadcast_support.h"

#include <ellicast/auth.h>
#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/reception.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <set>

using namespace ellicast;
using namespace ellicast::broadcast;
using Packets = std::vector<std::vector<uint8_t>>;

namespace {

auth::KeyPair key_from(uint8_t first) {
    auth::Seed seed;
    for (size_t i = 0; i < seed.size(); ++i) seed[i] = static_cast<uint8_t>(first + i);
    return auth::key_pair_from_seed(seed);
}

// A signed stream: MANIFEST parts first, then the packets (sign_stream's layout).
Packets signed_stream(const auth::KeyPair& key, uint32_t stream_id = 0x5EED, uint32_t points = 3000) {
    Packets packets = test::synthetic_stream(40, points, stream_id);
    size_t parts = 0;
    std::string error;
    REQUIRE(auth::sign_stream(packets, key, parts, error) == Error::Ok);
    REQUIRE(parts >= 2);
    return packets;
}

bool is_manifest(const std::vector<uint8_t>& p) { return p[6] == static_cast<uint8_t>(PacketType::Manifest); }

// A copy of `p` with payload bytes changed and the checksum recomputed: a forger's packet.
std::vector<uint8_t> forge(std::vector<uint8_t> p, size_t at = kHeaderSize + 10) {
    p[at] ^= 0x55;
    return test::resealed(std::move(p));
}

PacketView view_of(const std::vector<uint8_t>& p) {
    PacketView v;
    REQUIRE(parse_packet(p, v) == Error::Ok);
    return v;
}

}  // namespace

TEST_CASE("signing lists every packet once, in parts that are base or detail, each verifying alone") {
    const auth::KeyPair key = key_from(1);
    const Packets unsigned_packets = test::synthetic_stream(40, 3000);
    const Packets packets = signed_stream(key);
    std::vector<PacketDigest> listed;
    std::set<uint16_t> parts;
    for (const auto& p : packets) {
        if (!is_manifest(p)) continue;
        ManifestPart part;
        REQUIRE(decode_manifest_payload(view_of(p).payload, part) == Error::Ok);
        CHECK(auth::verify_manifest(p, part, key.public_key));
        CHECK_FALSE(auth::verify_manifest(p, part, key_from(2).public_key));
        CHECK(part.first == listed.size());
        parts.insert(part.part);
        // A part lists base packets only or detail (POINTS) packets only.
        std::set<bool> classes;
        for (size_t i = 0; i < part.digests.size(); ++i)
            classes.insert(auth::is_detail_type(unsigned_packets[part.first + i][6]));
        CHECK(classes.size() == 1);
        listed.insert(listed.end(), part.digests.begin(), part.digests.end());
        CHECK(p.size() <= 1200);
    }
    REQUIRE(listed.size() == unsigned_packets.size());
    for (size_t i = 0; i < listed.size(); ++i) CHECK(listed[i] == packet_digest(unsigned_packets[i]));
    CHECK(parts.size() == packets.size() - unsigned_packets.size());
    // Renumbered from 0; the digest ignores the sequence number.
    for (size_t i = 0; i < packets.size(); ++i) CHECK(view_of(packets[i]).header.sequence == i);
    // A decoder without a key skips the MANIFESTs and takes everything else.
    ReceivedStream stream;
    for (size_t i = 0; i < packets.size(); ++i) CHECK(stream.add_packet(packets[i], i) == Error::Ok);
    CHECK(stream.counters().skipped == parts.size());
    CHECK(stream.counters().accepted == unsigned_packets.size());
    CHECK(stream.points(0).size() == 3000);
}

TEST_CASE("with the key, a forged packet never reaches the decoder, whether it comes before or after the MANIFEST") {
    const auth::KeyPair key = key_from(1);
    const Packets packets = signed_stream(key);
    const size_t last = packets.size() - 1;  // a POINTS packet
    for (bool forged_first : {true, false}) {
        CAPTURE(forged_first);
        auth::Authenticator a(key.public_key);
        size_t passed = 0;
        auto take = [&](const std::vector<uint8_t>& p, uint64_t where) {
            auth::Authenticator::Verdict v = a.take(view_of(p), p, where);
            if (v == auth::Authenticator::Verdict::Pass) ++passed;
            passed += a.take_released().size();
            return v;
        };
        if (forged_first) CHECK(take(forge(packets[last]), 999) == auth::Authenticator::Verdict::Held);
        for (size_t i = 0; i < packets.size(); ++i) take(packets[i], i);
        if (!forged_first)
            CHECK(take(forge(packets[last]), 999) == auth::Authenticator::Verdict::Rejected);
        CHECK(passed == packets.size() - a.counters().manifests_verified);
        CHECK(a.counters().not_authenticated == 1);
        CHECK(a.counters().held == 0);
        REQUIRE_FALSE(a.rejections().empty());
        CHECK(a.rejections().back().where == 999);
        CHECK(a.rejections().back().error == Error::NotAuthenticated);
        CHECK(a.problem().empty());
    }
}

TEST_CASE("packets that arrive before their MANIFEST are held, then released in arrival order") {
    const auth::KeyPair key = key_from(1);
    const Packets packets = signed_stream(key);
    auth::Authenticator a(key.public_key);
    std::vector<uint64_t> released;
    for (size_t i = 0; i < packets.size(); ++i)
        if (!is_manifest(packets[i])) CHECK(a.take(view_of(packets[i]), packets[i], i) == auth::Authenticator::Verdict::Held);
    const size_t others = size_t(std::count_if(packets.begin(), packets.end(), [](const auto& p) { return !is_manifest(p); }));
    CHECK(a.counters().held == others);
    for (size_t i = 0; i < packets.size(); ++i)
        if (is_manifest(packets[i])) {
            CHECK(a.take(view_of(packets[i]), packets[i], i) == auth::Authenticator::Verdict::Manifest);
            for (const auto& r : a.take_released()) released.push_back(r.where);
        }
    CHECK(a.counters().held == 0);
    CHECK(a.counters().not_authenticated == 0);
    CHECK(released.size() == others);
    // sign_stream lists the packets in file order and each part a run of them: released in arrival order.
    CHECK(std::is_sorted(released.begin(), released.end()));
    CHECK(released.size() == a.counters().released);
    CHECK(a.counters().released == a.counters().passed);
    // A repeated MANIFEST is recognised without a second verification.
    CHECK(a.take(view_of(packets[0]), packets[0], 0) == auth::Authenticator::Verdict::Repeat);
}

TEST_CASE("the hold is bounded: a flood of unlisted packets pushes out the oldest, never grows past the limit") {
    const auth::KeyPair key = key_from(1);
    const Packets packets = signed_stream(key);
    auth::Authenticator::Limits limits;
    limits.max_held_packets = 100;
    limits.max_held_bytes = 1 << 20;
    auth::Authenticator a(key.public_key, limits);
    std::mt19937 rng(3);
    for (uint64_t i = 0; i < 20000; ++i) {
        const auto p = forge(packets[packets.size() - 1 - rng() % 20], kHeaderSize + 4 + rng() % 200);
        a.take(view_of(p), p, i);
        CHECK(a.counters().held <= 100);
    }
    CHECK(a.counters().held == 100);
    CHECK(a.counters().not_authenticated == 20000 - 100);
    // The real stream still gets through afterwards.
    size_t passed = 0;
    for (size_t i = 0; i < packets.size(); ++i) {
        if (a.take(view_of(packets[i]), packets[i], 20000 + i) == auth::Authenticator::Verdict::Pass) ++passed;
        passed += a.take_released().size();
    }
    CHECK(passed == packets.size() - a.counters().manifests_verified);
    // Once every part of the manifest verified, the forged packets still held are rejected.
    CHECK(a.manifest_complete(0x5EED));
    CHECK(a.counters().held == 0);
}

TEST_CASE("a MANIFEST signed with another key, altered, or malformed is rejected with its reason") {
    const auth::KeyPair key = key_from(1);
    const Packets theirs = signed_stream(key_from(9));
    const Packets ours = signed_stream(key);
    auth::Authenticator a(key.public_key);
    CHECK(a.take(view_of(theirs[0]), theirs[0], 0) == auth::Authenticator::Verdict::Rejected);
    CHECK(a.last_error() == Error::ManifestSignature);
    const auto altered = forge(ours[0], kHeaderSize + kManifestFixedSize + 3);  // a digest byte
    CHECK(a.take(view_of(altered), altered, 1) == auth::Authenticator::Verdict::Rejected);
    CHECK(a.last_error() == Error::ManifestSignature);
    auto malformed = ours[0];
    malformed[kHeaderSize + 4] = 0;  // part_count 0
    malformed = forge(malformed, kHeaderSize + 1);  // reserved byte: reseal
    CHECK(a.take(view_of(malformed), malformed, 2) == auth::Authenticator::Verdict::Rejected);
    CHECK(a.last_error() == Error::MalformedPayload);
    CHECK(a.counters().manifests_failed == 2);
    CHECK(a.counters().malformed == 1);
    const std::string problem = a.problem();
    CHECK(problem.find("2 failed verification") != std::string::npos);
    CHECK(problem.find("1 malformed") != std::string::npos);
    // Without any MANIFEST: the receiver says the stream does not look signed.
    auth::Authenticator none(key.public_key);
    CHECK(none.problem().find("no MANIFEST packet arrived") != std::string::npos);
}

TEST_CASE("a receiver with the key keeps the real stream against a forger that sends more, with the same stream id") {
    const auth::KeyPair key = key_from(1);
    const Packets real = signed_stream(key, 0xAAAA);
    // The forger: a stream of its own under the same stream id, unsigned, sent three times.
    const Packets forger = test::synthetic_stream(7, 9000, 0xAAAA, 1200, 99);
    for (bool with_key : {false, true}) {
        CAPTURE(with_key);
        Reception::Options options;
        if (with_key) options.key = key.public_key;
        Reception reception(options);
        for (int round = 0; round < 3; ++round)
            for (const auto& p : forger) reception.take(p);
        for (const auto& p : real) reception.take(p);
        REQUIRE(reception.stream().info());
        if (with_key) {
            // Nothing of the forger's got through: the shown stream is the signed one, complete.
            CHECK(reception.stream().info()->objects[0].ellipsoid_count == 40);
            CHECK(reception.complete());
            CHECK(reception.candidate_count() == 1);
            CHECK(reception.counters().unauthenticated > 0);
        } else {
            // Without a key, the one who sends more wins (spec 11.4): why the key exists.
            CHECK(reception.stream().info()->objects[0].ellipsoid_count == 7);
        }
    }
}

TEST_CASE("the carousel of a signed stream sends base parts with the base and detail parts before their points") {
    const auth::KeyPair key = key_from(1);
    const Packets packets = signed_stream(key, 0x5EED, 20000);
    CarouselOptions options;
    options.chunk_packets = 20;  // room for STREAM_INFO repeats inside a chunk
    Carousel carousel;
    std::string error;
    REQUIRE(build_carousel(packets, options, carousel, error));
    REQUIRE_FALSE(carousel.detail_manifests.empty());
    std::set<uint32_t> base(carousel.base.begin(), carousel.base.end());
    for (uint32_t m : carousel.detail_manifests) CHECK_FALSE(base.count(m));
    // Every detail part comes before the first packet it lists in the cycle, and twice a cycle.
    for (uint32_t m : carousel.detail_manifests) {
        ManifestPart part;
        REQUIRE(decode_manifest_payload(view_of(packets[m]).payload, part) == Error::Ok);
        std::set<PacketDigest> listed(part.digests.begin(), part.digests.end());
        size_t first_manifest = SIZE_MAX, first_listed = SIZE_MAX, copies = 0;
        for (size_t slot = 0; slot < carousel.cycle.size(); ++slot) {
            const uint32_t k = carousel.cycle[slot].packet;
            if (k == m) {
                ++copies;
                first_manifest = std::min(first_manifest, slot);
            }
            if (listed.count(packet_digest(packets[k]))) first_listed = std::min(first_listed, slot);
        }
        CHECK(first_manifest < first_listed);
        CHECK(copies == (part.digests.size() > 1 ? 2 : 1));
    }
    // Every STREAM_INFO repeat inside a chunk is followed by the part that lists it and the ELLIPSOIDS
    // packets (a part of their own), so that a receiver with the key can show a model early.
    size_t info_repeats = 0;
    for (size_t slot = 0; slot + 1 < carousel.cycle.size(); ++slot) {
        const CarouselEntry& e = carousel.cycle[slot];
        if (!e.stream_info_repeat || packets[e.packet][6] != uint8_t(PacketType::StreamInfo)) continue;
        ++info_repeats;
        const auto& next = packets[carousel.cycle[slot + 1].packet];
        REQUIRE(is_manifest(next));
        ManifestPart part;
        REQUIRE(decode_manifest_payload(view_of(next).payload, part) == Error::Ok);
        const std::set<PacketDigest> listed(part.digests.begin(), part.digests.end());
        CHECK(listed.count(packet_digest(packets[e.packet])));
        for (const PacketDigest& d : part.digests) {
            const auto it = std::find_if(packets.begin(), packets.end(), [&](const auto& p) { return packet_digest(p) == d; });
            REQUIRE(it != packets.end());
            CHECK(((*it)[6] == uint8_t(PacketType::StreamInfo) || (*it)[6] == uint8_t(PacketType::Ellipsoids)));
        }
    }
    CHECK(info_repeats > 0);
    // A receiver with the key that tunes in anywhere authenticates every packet within two cycles.
    for (uint64_t tune_in : {uint64_t(0), uint64_t(carousel.cycle.size() / 3), uint64_t(carousel.cycle.size() - 1)}) {
        CAPTURE(tune_in);
        Reception::Options ro;
        ro.key = key.public_key;
        Reception reception(ro);
        for (uint64_t slot = tune_in; slot < tune_in + 2 * carousel.cycle.size() && !reception.complete(); ++slot)
            reception.take(carousel_packet(carousel, packets, slot));
        CHECK(reception.complete());
        CHECK(reception.counters().unauthenticated == 0);
    }
}

TEST_CASE("a signed recording: the manifest's structure is checked, and the signatures with a key") {
    const auth::KeyPair key = key_from(1);
    auto check = [](const Packets& packets, const auth::PublicKey* k) {
        const std::vector<uint8_t> file = write_container(packets);
        const ContainerContents contents = read_container(file);
        return auth::check_signed_recording(contents.packets, file, k);
    };
    const Packets good = signed_stream(key);
    auth::SignedRecordingCheck c = check(good, nullptr);
    CHECK(c.is_signed);
    CHECK(c.problems.empty());
    CHECK_FALSE(c.signatures_checked);
    c = check(good, &key.public_key);
    CHECK(c.problems.empty());
    const auth::PublicKey other = key_from(2).public_key;
    c = check(good, &other);
    CHECK(c.signatures_failed == c.parts);
    // A missing part; a packet the manifest does not list.
    Packets missing_part(good.begin() + 1, good.end());
    c = check(missing_part, &key.public_key);
    REQUIRE_FALSE(c.problems.empty());
    CHECK(c.problems[0].message.find("parts present") != std::string::npos);
    Packets extra = good;
    extra.push_back(forge(good.back()));
    c = check(extra, &key.public_key);
    REQUIRE(c.problems.size() == 1);
    CHECK(c.problems[0].message.find("not listed") != std::string::npos);
    // An unsigned stream is not signed and has no problem.
    c = check(test::synthetic_stream(4, 100), nullptr);
    CHECK_FALSE(c.is_signed);
    CHECK(c.problems.empty());
}

TEST_CASE("key files: written once, secret kept private, the wrong kind of key refused with a message") {
    const auto dir = test::scratch_dir("signed_keys");
    const std::string secret = (dir / "k.key").string(), pub = (dir / "k.pub").string();
    const auth::KeyPair key = auth::generate_key_pair();
    std::string error;
    REQUIRE(auth::write_key_pair(secret, pub, key, error));
    struct stat st {};
    REQUIRE(stat(secret.c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == 0600);
    CHECK_FALSE(auth::write_key_pair(secret, pub, key, error));
    CHECK(error.find("exists") != std::string::npos);
    auth::KeyPair read_back;
    REQUIRE(auth::read_secret_key(secret, read_back, error));
    CHECK(read_back.public_key == key.public_key);
    auth::PublicKey p;
    REQUIRE(auth::read_public_key(pub, p, error));
    CHECK(p == key.public_key);
    REQUIRE(auth::read_public_key(auth::to_hex(key.public_key), p, error));  // 64 hex digits
    CHECK(p == key.public_key);
    CHECK_FALSE(auth::read_public_key(secret, p, error));
    CHECK(error.find("secret key") != std::string::npos);
    CHECK_FALSE(auth::read_secret_key(pub, read_back, error));
    CHECK(error.find("public key") != std::string::npos);
    CHECK_FALSE(auth::read_public_key((dir / "absent.pub").string(), p, error));
    CHECK(error.find("cannot open") != std::string::npos);
    std::ofstream((dir / "junk.pub").string()) << "ellicast-ed25519-public-key 12zz\n";
    CHECK_FALSE(auth::read_public_key((dir / "junk.pub").string(), p, error));
}

TEST_CASE("command line: keygen, encode --sign, validate and decode --key, sign") {
    const auto dir = test::scratch_dir("signed_cli");
    const std::string exe = test::shell_quoted(test::ellicast_exe().string());
    const std::string sample = (test::source_dir() / "samples" / "trefoil.obj").string();
    int status = 0;
    auto run = [&](const std::string& args) { return test::run_command(exe + " " + args, status); };
    const std::string k = (dir / "alice").string(), other = (dir / "bob").string();
    run("keygen '" + k + "'");
    REQUIRE(status == 0);
    run("keygen '" + k + "'");
    CHECK(status != 0);  // never replaces a key
    run("keygen '" + other + "'");
    const std::string stream = (dir / "t.ellc").string();
    std::string out = run("encode -q '" + sample + "' -o '" + stream + "' --sign '" + k + ".key'");
    REQUIRE(status == 0);
    CHECK(out.find("signed: ") != std::string::npos);
    out = run("validate '" + stream + "' --key '" + k + ".pub'");
    CHECK(status == 0);
    CHECK(out.find("every signature verified") != std::string::npos);
    out = run("validate '" + stream + "' --key '" + other + ".pub'");
    CHECK(status == 1);
    CHECK(out.find("not the key given") != std::string::npos);
    out = run("decode -q '" + stream + "' --key '" + k + ".pub' -o '" + (dir / "t.ply").string() + "'");
    CHECK(status == 0);
    out = run("decode -q '" + stream + "' --key '" + other + ".pub' -o '" + (dir / "u.ply").string() + "'");
    CHECK(status == 1);
    CHECK(out.find("no MANIFEST verified") != std::string::npos);
    // A secret key where a public one is wanted, and the other way round.
    out = run("validate '" + stream + "' --key '" + k + ".key'");
    CHECK(status == 2);
    out = run("sign '" + stream + "' --key '" + k + ".pub' -o '" + (dir / "s.ellc").string() + "'");
    CHECK(status == 2);
    // Re-signing with another key replaces the signature.
    out = run("sign '" + stream + "' --key '" + other + ".key' -o '" + (dir / "s.ellc").string() + "'");
    REQUIRE(status == 0);
    run("validate '" + (dir / "s.ellc").string() + "' --key '" + other + ".pub'");
    CHECK(status == 0);
    run("validate '" + (dir / "s.ellc").string() + "' --key '" + k + ".pub'");
    CHECK(status == 1);
    // An unsigned stream with --key: not signed.
    const std::string plain = (dir / "p.ellc").string();
    run("encode -q '" + sample + "' -o '" + plain + "'");
    out = run("validate '" + plain + "' --key '" + k + ".pub'");
    CHECK(status == 1);
    CHECK(out.find("not signed") != std::string::npos);
}

TEST_CASE("ellicast receive --key takes the signed stream over UDP while a forger floods the same stream id") {
    const auto dir = test::scratch_dir("receive-key");
    const auth::KeyPair key = key_from(1);
    const Packets real = signed_stream(key, 0xABCD, 3000);
    test::write_stream_file(dir / "real.ellc", real);
    // The forger: its own stream under the same stream id, unsigned, many more packets, faster.
    test::write_stream_file(dir / "forger.ellc", test::synthetic_stream(7, 9000, 0xABCD, 1200, 99));
    std::ofstream(dir / "k.pub") << auth::public_key_text(key.public_key);
    std::ofstream(dir / "other.pub") << auth::public_key_text(key_from(2).public_key);
    const std::string group = "239.255.61.9:" + std::to_string(41000 + (getpid() % 2000) * 8 + 6);
    test::Child receive({"receive", "--from", group, "--interface", "lo", "-o", (dir / "out.ellc").string(), "--key",
                         (dir / "k.pub").string(), "--until", "20"},
                        dir / "receive.log");
    test::Child wrong_key({"receive", "--from", group, "--interface", "lo", "-o", (dir / "wrong.ellc").string(), "--key",
                           (dir / "other.pub").string(), "--until", "3"},
                          dir / "wrong.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // let them join
    test::Child forger({"serve", (dir / "forger.ellc").string(), "--to", group, "--interface", "lo", "--ttl", "0", "--rate",
                        "16000000", "--cycles", "40"},
                       dir / "forger.log");
    test::Child serve({"serve", (dir / "real.ellc").string(), "--to", group, "--interface", "lo", "--ttl", "0", "--rate",
                       "4000000", "--cycles", "30", "--loss", "0.1", "--seed", "5"},
                      dir / "serve.log");
    const int code = receive.wait(std::chrono::seconds(25));
    const std::string log = test::read_text(dir / "receive.log");
    INFO(log);
    REQUIRE(code == 0);
    CHECK(log.find("everything complete after") != std::string::npos);
    CHECK(log.find("signed stream: ") != std::string::npos);
    // What it wrote is the signed stream, every packet authenticated, nothing of the forger's.
    Reception::Options options;
    options.key = key.public_key;
    Reception check(options);
    for (const auto& p : test::read_stream_file(dir / "out.ellc")) check.take(p);
    CHECK(check.complete());
    REQUIRE(check.stream().info());
    CHECK(check.stream().info()->objects[0].ellipsoid_count == 40);
    // With another sender's key nothing is authenticated: it says so and writes nothing.
    const int wrong_code = wrong_key.wait(std::chrono::seconds(10));
    const std::string wrong_log = test::read_text(dir / "wrong.log");
    INFO(wrong_log);
    CHECK(wrong_code != 0);
    CHECK(wrong_log.find("no MANIFEST verified") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "wrong.ellc"));
}

TEST_CASE("a flood of forged MANIFESTs with the right key id costs a bounded number of signature checks, and the real stream still gets through") {
    const auth::KeyPair key = key_from(1);
    const Packets real = signed_stream(key, 0xAAAA);
    std::vector<std::vector<uint8_t>> forged;  // the real MANIFESTs with a digest byte changed: right key id, bad signature
    for (const auto& p : real)
        if (is_manifest(p)) forged.push_back(forge(p, kHeaderSize + kManifestFixedSize + 3));
    REQUIRE(!forged.empty());
    Reception::Options options;
    options.key = key.public_key;
    Reception reception(options);
    // Each real packet is sent among 20 forged MANIFESTs, and the carousel repeats the real stream.
    size_t taken = 0;
    for (int cycle = 0; cycle < 4 && !reception.complete(); ++cycle)
        for (const auto& p : real) {
            for (int i = 0; i < 20; ++i, ++taken) reception.take(forged[(taken + i) % forged.size()]);
            reception.take(p);
            ++taken;
        }
    const auth::Authenticator::Counters& c = reception.authenticator()->counters();
    const auth::Authenticator::Limits limits;
    // Every check is a forged or a real MANIFEST: no more than the budget allows.
    CHECK(c.manifests_failed + c.manifests_verified <= limits.verify_burst + taken / limits.packets_per_verification);
    CHECK(c.manifests_unchecked > 0);
    CHECK(c.manifests_failed + c.manifests_unchecked + c.manifests_verified + c.manifests_repeated >= taken * 20 / 21);
    CHECK(reception.complete());
}

// ------------------------------------------------------------------------------------------------
// Format 1.9: parts bound to a content (spec 25). Row 4 of the hostile streams: two contents signed
// with one key under one stream id, spliced.

namespace {

struct Split {
    Packets manifests, info, ellipsoids, points;
};
Split split(const Packets& packets) {
    Split s;
    for (const auto& p : packets) {
        const uint8_t type = p[6];
        if (type == static_cast<uint8_t>(PacketType::Manifest)) s.manifests.push_back(p);
        else if (type == static_cast<uint8_t>(PacketType::StreamInfo)) s.info.push_back(p);
        else if (type == static_cast<uint8_t>(PacketType::Ellipsoids)) s.ellipsoids.push_back(p);
        else s.points.push_back(p);
    }
    return s;
}

std::set<PacketDigest> listed_by(const Packets& manifests) {
    std::set<PacketDigest> out;
    for (const auto& m : manifests) {
        ManifestPart part;
        REQUIRE(decode_manifest_payload(view_of(m).payload, part) == Error::Ok);
        out.insert(part.digests.begin(), part.digests.end());
    }
    return out;
}

}  // namespace

TEST_CASE("signing binds every part to the content id of its STREAM_INFO, and writes scheme 1 on request") {
    const auth::KeyPair key = key_from(1);
    const Packets packets = test::synthetic_stream(40, 3000);
    StreamInfoPart info;
    REQUIRE(decode_stream_info_payload(view_of(packets[0]).payload, info) == Error::Ok);
    for (uint8_t scheme : {kManifestSchemeBound, kManifestSchemeEd25519}) {
        CAPTURE(int(scheme));
        Packets manifests;
        std::string error;
        REQUIRE(auth::sign_packets(packets, key, 1200, 0, manifests, error, scheme) == Error::Ok);
        for (const auto& m : manifests) {
            const PacketView v = view_of(m);
            CHECK(v.header.version_minor == (scheme == kManifestSchemeBound ? 9 : 2));
            ManifestPart part;
            REQUIRE(decode_manifest_payload(v.payload, part) == Error::Ok);
            CHECK(part.scheme == scheme);
            CHECK(part.content_id == (scheme == kManifestSchemeBound ? info.info.content_id : 0u));
            CHECK(auth::verify_manifest(m, part, key.public_key));
            // The content id is signed: changing it breaks the signature.
            if (scheme == kManifestSchemeBound) {
                auto altered = forge(m, kHeaderSize + 24);
                ManifestPart p2;
                REQUIRE(decode_manifest_payload(view_of(altered).payload, p2) == Error::Ok);
                CHECK_FALSE(auth::verify_manifest(altered, p2, key.public_key));
            }
        }
    }
    // Two contents in one list cannot be signed as one.
    Packets mixed = packets;
    mixed.push_back(test::synthetic_stream(40, 2000)[0]);
    Packets manifests;
    std::string error;
    CHECK(auth::sign_packets(mixed, key, 1200, 0, manifests, error) == Error::MalformedPayload);
    CHECK(error.find("one content") != std::string::npos);
}

TEST_CASE("a receiver with the key never mixes two contents signed with it under one stream id") {
    const auth::KeyPair key = key_from(1);
    // Two contents under the same stream id, both signed (scheme 2) with the same key.
    const Split a = split(signed_stream(key, 0x5EED, 3000));
    const Split b = split(signed_stream(key, 0x5EED, 2000));
    REQUIRE(!a.info.empty());
    REQUIRE(!b.points.empty());
    const std::set<PacketDigest> listed_a = listed_by(a.manifests);

    SUBCASE("live: the other content's points come first, are held, and are rejected once the stream shows its "
            "content; its STREAM_INFO later cannot switch it") {
        auth::Authenticator filter(key.public_key);
        ReceivedStream decoder;
        uint64_t where = 0;
        auto feed = [&](const Packets& packets) {
            for (const auto& p : packets) {
                const auto verdict = filter.take(view_of(p), p, where);
                if (verdict == auth::Authenticator::Verdict::Pass) decoder.add_packet(p, where);
                for (auto& r : filter.take_released()) decoder.add_packet(r.bytes, r.where);
                ++where;
            }
        };
        feed(a.manifests);
        feed(b.manifests);
        feed(b.points);  // authenticated (for content b) but the stream shows no content yet: held
        CHECK(filter.counters().held == b.points.size());
        CHECK(decoder.counters().accepted == 0);
        feed(a.info);  // the stream shows content a: b's points are rejected, not released
        feed(a.ellipsoids);
        feed(b.info);  // another content's STREAM_INFO: rejected, the stream keeps its content
        CHECK(filter.content(0x5EED) == decoder.info()->content_id);
        CHECK(filter.counters().held == 0);
        size_t rejected_points = 0;
        for (const auto& p : b.points) rejected_points += !listed_a.count(packet_digest(p));
        CHECK(rejected_points > 0);
        CHECK(filter.counters().not_authenticated == rejected_points + b.info.size());
        // What reached the decoder: content a's STREAM_INFO, its ellipsoids, and no point of b that a's
        // manifest does not list.
        REQUIRE(decoder.objects().size() == 1);
        const size_t before = decoder.objects()[0].points.size();
        feed(a.points);
        CHECK(decoder.objects()[0].points.size() == 3000);
        CHECK(before < 3000);
        CHECK(decoder.info()->objects[0].point_count == 3000);
    }
    SUBCASE("live: a content's own points before its STREAM_INFO are released after it, in arrival order") {
        auth::Authenticator filter(key.public_key);
        uint64_t where = 0;
        for (const auto& p : a.manifests) filter.take(view_of(p), p, where++);
        for (const auto& p : a.points) CHECK(filter.take(view_of(p), p, where++) == auth::Authenticator::Verdict::Held);
        CHECK(filter.take(view_of(a.info[0]), a.info[0], where++) == auth::Authenticator::Verdict::Pass);
        const auto released = filter.take_released();
        REQUIRE(released.size() == a.points.size());
        for (size_t i = 0; i < released.size(); ++i) CHECK(released[i].bytes == a.points[i]);
        CHECK(filter.counters().not_authenticated == 0);
    }
    SUBCASE("a recording: the spliced file decodes to the first content alone") {
        Packets file = a.manifests;
        file.insert(file.end(), b.manifests.begin(), b.manifests.end());
        file.insert(file.end(), b.points.begin(), b.points.end());
        file.insert(file.end(), a.info.begin(), a.info.end());
        file.insert(file.end(), a.ellipsoids.begin(), a.ellipsoids.end());
        const std::vector<uint8_t> bytes = write_container(file);
        const ContainerContents contents = read_container(bytes);
        const auth::RecordingAuthentication r = auth::authenticate_recording(contents.packets, bytes, key.public_key);
        for (size_t i = 0; i < contents.packets.size(); ++i) {
            const ContainerPacket& p = contents.packets[i];
            if (p.view.header.type != static_cast<uint8_t>(PacketType::Points)) continue;
            const bool ours = listed_a.count(packet_digest(std::span<const uint8_t>(bytes).subspan(p.offset, p.view.size)));
            CHECK((r.verdicts[i] == auth::Authenticator::Verdict::Pass) == ours);
        }
        // And the conformance check names the two contents under one stream id.
        const auth::SignedRecordingCheck check = auth::check_signed_recording(contents.packets, bytes, &key.public_key);
        bool named = false;
        for (const auto& problem : check.problems) named |= problem.message.find("content_id") != std::string::npos;
        CHECK(named);
    }
}

TEST_CASE("command line: encode --sign gives each content its own stream id unless --stream-id is given") {
    const auto dir = test::scratch_dir("signed_stream_ids");
    const std::string exe = test::shell_quoted(test::ellicast_exe().string());
    int status = 0;
    auto run = [&](const std::string& args) { return test::run_command(exe + " " + args, status); };
    const std::string k = (dir / "alice").string();
    run("keygen '" + k + "'");
    REQUIRE(status == 0);
    auto stream_id_of = [](const std::filesystem::path& file) {
        const ContainerContents c = read_container(test::read_bytes(file));
        REQUIRE(!c.packets.empty());
        std::set<uint32_t> ids;
        for (const auto& p : c.packets) ids.insert(p.view.header.stream_id);
        REQUIRE(ids.size() == 1);
        return *ids.begin();
    };
    const std::string trefoil = (test::source_dir() / "samples" / "trefoil.obj").string();
    run("encode -q '" + trefoil + "' -o '" + (dir / "a.ellc").string() + "' --sign '" + k + ".key'");
    REQUIRE(status == 0);
    // Another content of the same model: other surface samples.
    run("encode -q '" + trefoil + "' -o '" + (dir / "b.ellc").string() + "' --sign '" + k + ".key' --sample-budget 0");
    REQUIRE(status == 0);
    run("encode -q '" + trefoil + "' -o '" + (dir / "c.ellc").string() + "' --sign '" + k + ".key' --stream-id 7");
    REQUIRE(status == 0);
    run("encode -q '" + trefoil + "' -o '" + (dir / "d.ellc").string() + "'");
    REQUIRE(status == 0);
    CHECK(stream_id_of(dir / "a.ellc") != stream_id_of(dir / "b.ellc"));
    CHECK(stream_id_of(dir / "a.ellc") != 1u);
    CHECK(stream_id_of(dir / "c.ellc") == 7u);
    CHECK(stream_id_of(dir / "d.ellc") == 1u);  // unsigned: the default as before
    run("validate '" + (dir / "a.ellc").string() + "' --key '" + k + ".pub'");
    CHECK(status == 0);
}

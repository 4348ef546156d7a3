// Reading a recorded stream for decoding, authenticated when a key is given (spec 16.3).
#include "commands.h"

#include <ellicast/auth.h>

#include <cstdio>

namespace ellicast::cli {

int read_recording(const std::string& path, const std::string& key_text, RecordingPackets& out) {
    std::string message;
    if (read_file(path, out.bytes, message) != Error::Ok) return fail(kExitFailure, message);
    out.contents = read_container(out.bytes);
    if (out.contents.header_error != Error::Ok)
        return fail(kExitInvalid, path + ": not an ellicast container (" + error_name(out.contents.header_error) + ")");
    if (key_text.empty()) return kExitOk;
    auth::PublicKey key;
    if (!auth::read_public_key(key_text, key, message)) return fail(kExitUsage, "--key: " + message);
    const auth::RecordingAuthentication a = auth::authenticate_recording(out.contents.packets, out.bytes, key);
    std::vector<ContainerPacket> kept;
    for (size_t i = 0; i < out.contents.packets.size(); ++i)
        if (a.verdicts[i] == auth::Authenticator::Verdict::Pass) kept.push_back(out.contents.packets[i]);
    if (!a.problem.empty()) return fail(kExitInvalid, path + ": " + a.problem);
    std::fprintf(stderr,
                 "signed stream: %llu MANIFEST part(s) verified with key id %s; %zu packet(s) authenticated, %llu "
                 "rejected as not authenticated\n",
                 (unsigned long long)a.counters.manifests_verified,
                 auth::to_hex(key_id_of(std::span<const uint8_t, 32>(key))).c_str(), kept.size(),
                 (unsigned long long)a.counters.not_authenticated);
    if (a.counters.manifests_failed)
        std::fprintf(stderr, "ellicast: warning: %llu MANIFEST part(s) failed verification (forged, altered or another key)\n",
                     (unsigned long long)a.counters.manifests_failed);
    out.contents.packets = std::move(kept);
    return kExitOk;
}

}  // namespace ellicast::cli

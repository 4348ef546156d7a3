// The conformance of a signed recording (spec 16.4, 25.3), for `validate` and `inspect`.
#include "ellicast/auth.h"

#include <algorithm>
#include <map>

namespace ellicast::auth {

SignedRecordingCheck check_signed_recording(const std::vector<ContainerPacket>& packets,
                                            std::span<const uint8_t> file_bytes, const PublicKey* key) {
    SignedRecordingCheck out;
    out.signatures_checked = key != nullptr;
    auto bytes_of = [&](const ContainerPacket& p) { return file_bytes.subspan(p.offset, p.view.size); };
    auto is_manifest = [](const ContainerPacket& p) {
        return p.view.header.type == static_cast<uint8_t>(PacketType::Manifest);
    };
    struct Part {
        ManifestPart part;
        uint64_t offset;
    };
    // Distinct parts by digest, per stream id; the digests of every other packet, per stream id.
    std::map<uint32_t, std::map<PacketDigest, Part>> parts;
    std::map<uint32_t, std::map<PacketDigest, uint64_t>> others;  // digest -> first offset
    // stream id -> (offset, content id) of its STREAM_INFO packets, for scheme 2 (spec 25.3)
    std::map<uint32_t, std::vector<std::pair<uint64_t, uint32_t>>> infos;
    for (const ContainerPacket& p : packets) {
        const PacketDigest digest = packet_digest(bytes_of(p));
        if (!is_manifest(p)) {
            others[p.view.header.stream_id].emplace(digest, p.offset);
            if (const auto content = stream_info_content_id(p.view.header.type, p.view.payload))
                infos[p.view.header.stream_id].push_back({p.offset, *content});
            continue;
        }
        ManifestPart part;
        if (decode_manifest_payload(p.view.payload, part) != Error::Ok) continue;  // the decoder rejects it
        if (!is_known_manifest_scheme(part.scheme)) continue;  // a later scheme's: skipped, as decoders do
        ++out.manifest_packets;
        out.is_signed = true;
        if (out.key_id.empty()) out.key_id = to_hex(part.key_id);
        auto& of_stream = parts[p.view.header.stream_id];
        if (of_stream.count(digest)) continue;  // a copy
        if (key && !verify_manifest(bytes_of(p), part, *key)) {
            ++out.signatures_failed;
            out.problems.push_back(
                {p.offset, "MANIFEST part " + std::to_string(part.part) + ": " +
                               (part.key_id != key_id_of(std::span<const uint8_t, 32>(*key))
                                    ? "signed by key id " + to_hex(part.key_id) + ", not the key given"
                                    : std::string("its signature does not verify with the key given"))});
        }
        of_stream.emplace(digest, Part{std::move(part), p.offset});
    }
    for (auto& [stream_id, of_stream] : parts) {
        out.parts += of_stream.size();
        const std::string stream = of_stream.size() && parts.size() > 1 ? " of stream " + std::to_string(stream_id) : "";
        const ManifestPart& first = of_stream.begin()->second.part;
        std::map<uint16_t, const Part*> by_index;
        bool consistent = true;
        for (const auto& [digest, p] : of_stream) {
            const ManifestPart& m = p.part;
            if (m.part_count != first.part_count || m.packet_count != first.packet_count || m.key_id != first.key_id ||
                m.scheme != first.scheme || m.content_id != first.content_id) {
                out.problems.push_back({p.offset, "MANIFEST part " + std::to_string(m.part) +
                                                      " disagrees with the others on part_count, packet_count, "
                                                      "key_id, scheme or content_id (one stream id, one content)"});
                consistent = false;
                continue;
            }
            if (!by_index.emplace(m.part, &p).second) {
                out.problems.push_back({p.offset, "MANIFEST part " + std::to_string(m.part) +
                                                      " comes twice with different contents"});
                consistent = false;
            }
        }
        if (!consistent) continue;
        if (first.scheme == kManifestSchemeBound)
            for (const auto& [offset, content] : infos[stream_id])
                if (content != first.content_id)
                    out.problems.push_back({offset, "STREAM_INFO of content id " + std::to_string(content) +
                                                        ", but the manifest" + stream + " is bound to content id " +
                                                        std::to_string(first.content_id)});
        if (by_index.size() != first.part_count) {
            out.problems.push_back({std::nullopt, "manifest" + stream + ": " + std::to_string(by_index.size()) + " of " +
                                                      std::to_string(first.part_count) + " parts present"});
            continue;
        }
        // The parts' ranges must tile 0 .. packet_count - 1.
        std::vector<const Part*> ordered;
        for (const auto& [index, p] : by_index) ordered.push_back(p);
        std::sort(ordered.begin(), ordered.end(), [](const Part* a, const Part* b) { return a->part.first < b->part.first; });
        uint64_t next = 0;
        bool tiled = true;
        for (const Part* p : ordered) {
            if (p->part.first != next) tiled = false;
            next = uint64_t{p->part.first} + p->part.digests.size();
        }
        if (!tiled || next != first.packet_count) {
            out.problems.push_back({std::nullopt, "manifest" + stream + ": its parts' digest ranges do not cover 0.." +
                                                      std::to_string(first.packet_count) + " exactly once"});
            continue;
        }
        // It lists every other packet of the stream once and nothing else.
        std::map<PacketDigest, int> listed;
        for (const Part* p : ordered)
            for (const PacketDigest& d : p->part.digests) ++listed[d];
        size_t twice = 0, absent = 0;
        for (const auto& [d, n] : listed) {
            if (n > 1) ++twice;
            if (!others[stream_id].count(d)) ++absent;
        }
        if (twice) out.problems.push_back({std::nullopt, "manifest" + stream + ": " + std::to_string(twice) +
                                                             " digest(s) listed more than once"});
        if (absent)
            out.problems.push_back({std::nullopt, "manifest" + stream + ": lists " + std::to_string(absent) +
                                                      " packet(s) the file does not hold"});
        size_t unlisted = 0;
        for (const auto& [d, offset] : others[stream_id])
            if (!listed.count(d) && ++unlisted <= 50)
                out.problems.push_back({offset, "packet not listed by the stream's manifest"});
        if (unlisted > 50)
            out.problems.push_back({std::nullopt, "manifest" + stream + ": " + std::to_string(unlisted) +
                                                      " packets not listed in all (the first 50 are named)"});
    }
    for (const auto& [stream_id, of_stream] : others)
        if (out.is_signed && !parts.count(stream_id))
            out.problems.push_back({std::nullopt, "stream " + std::to_string(stream_id) + " has no MANIFEST"});
    std::stable_sort(out.problems.begin(), out.problems.end(), [](const auto& a, const auto& b) {
        if (a.offset.has_value() != b.offset.has_value()) return a.offset.has_value();
        return a.offset.value_or(0) < b.offset.value_or(0);
    });
    return out;
}

}  // namespace ellicast::auth

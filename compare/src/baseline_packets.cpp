// Framing of the baselines' packets (the ellicast header and CRC-32C, experimental types), and the
// mesh helpers the baselines share.
#include "ellicast/compare/schemes.h"

#include "ellicast/format.h"

namespace ellicast::compare {

uint64_t Scheme::period_bytes() const {
    uint64_t total = 0;
    for (uint64_t n = 0; n < period(); ++n) total += packets_[packet_at(n)].size();
    return total;
}

std::vector<uint8_t> baseline_packet(uint8_t type, uint32_t sequence, std::span<const uint8_t> payload) {
    PacketHeader header;
    header.type = type;
    header.flags = kFlagSkippable;
    header.stream_id = kBaselineStreamId;
    header.sequence = sequence;
    header.object_id = 0;
    return write_packet(header, payload);
}

std::span<const uint8_t> baseline_payload(std::span<const uint8_t> packet, uint8_t type) {
    PacketView view;
    if (parse_packet(packet, view) != Error::Ok) return {};
    if (view.header.type != type || view.header.stream_id != kBaselineStreamId) return {};
    return view.payload;
}

size_t payload_capacity(size_t packet_size) {
    if (packet_size < kMinPacketSize || packet_size > kMaxPacketSize)
        throw CompareError("packet size " + std::to_string(packet_size) + " is outside [" +
                           std::to_string(kMinPacketSize) + ", " + std::to_string(kMaxPacketSize) + "]");
    return packet_size - kPacketOverhead;
}

Mesh submesh(const Mesh& mesh, std::span<const uint32_t> triangles) {
    Mesh out;
    out.name = mesh.name;
    out.colors_have_alpha = mesh.colors_have_alpha;
    std::vector<uint32_t> remap(mesh.positions.size(), UINT32_MAX);
    out.triangles.reserve(triangles.size());
    for (uint32_t t : triangles) {
        std::array<uint32_t, 3> tri{};
        for (int c = 0; c < 3; ++c) {
            uint32_t v = mesh.triangles[t][c];
            if (remap[v] == UINT32_MAX) {
                remap[v] = static_cast<uint32_t>(out.positions.size());
                out.positions.push_back(mesh.positions[v]);
                if (mesh.has_normals()) out.normals.push_back(mesh.normals[v]);
                if (mesh.has_texcoords()) out.texcoords.push_back(mesh.texcoords[v]);
                if (mesh.has_colors()) out.colors.push_back(mesh.colors[v]);
            }
            tri[c] = remap[v];
        }
        out.triangles.push_back(tri);
    }
    return out;
}

Mesh concatenate(const std::vector<Mesh>& parts) {
    Mesh out;
    if (parts.empty()) return out;
    out.name = parts[0].name;
    out.colors_have_alpha = parts[0].colors_have_alpha;
    bool normals = true, texcoords = true, colors = true;
    for (const auto& p : parts) {
        normals = normals && p.has_normals();
        texcoords = texcoords && p.has_texcoords();
        colors = colors && p.has_colors();
    }
    for (const auto& p : parts) {
        const auto base = static_cast<uint32_t>(out.positions.size());
        out.positions.insert(out.positions.end(), p.positions.begin(), p.positions.end());
        if (normals) out.normals.insert(out.normals.end(), p.normals.begin(), p.normals.end());
        if (texcoords) out.texcoords.insert(out.texcoords.end(), p.texcoords.begin(), p.texcoords.end());
        if (colors) out.colors.insert(out.colors.end(), p.colors.begin(), p.colors.end());
        for (const auto& t : p.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
    }
    return out;
}

}  // namespace ellicast::compare

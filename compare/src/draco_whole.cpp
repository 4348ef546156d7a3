// Baseline 1: the whole mesh as one Draco file, cut into packets and repeated; nothing can be shown
// until every packet has been received (across cycles).
#include "ellicast/compare/schemes.h"

#include <cstring>
#include <sstream>

namespace ellicast::compare {

namespace {

constexpr size_t kFragmentHeader = 8;  // u32 file size, u16 fragment count, u16 fragment index

void put_u16(uint8_t* p, uint32_t v) {
    p[0] = uint8_t(v);
    p[1] = uint8_t(v >> 8);
}
void put_u32(uint8_t* p, uint32_t v) {
    for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}
uint32_t get_u16(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8; }
uint32_t get_u32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

}  // namespace

std::vector<std::vector<uint8_t>> fragment_payloads(std::span<const uint8_t> bytes, size_t capacity) {
    if (capacity <= kFragmentHeader) throw CompareError("packets too small to carry Draco fragments");
    const size_t per = capacity - kFragmentHeader;
    const size_t count = std::max<size_t>(1, (bytes.size() + per - 1) / per);
    if (count > 0xFFFF || bytes.size() > 0xFFFFFFFFu)
        throw CompareError("Draco file of " + std::to_string(bytes.size()) + " bytes needs more than 65535 packets");
    std::vector<std::vector<uint8_t>> out(count);
    for (size_t i = 0; i < count; ++i) {
        const size_t first = i * per;
        const size_t n = std::min(per, bytes.size() - std::min(first, bytes.size()));
        out[i].resize(kFragmentHeader + n);
        put_u32(out[i].data(), static_cast<uint32_t>(bytes.size()));
        put_u16(out[i].data() + 4, static_cast<uint32_t>(count));
        put_u16(out[i].data() + 6, static_cast<uint32_t>(i));
        if (n) std::memcpy(out[i].data() + kFragmentHeader, bytes.data() + first, n);
    }
    return out;
}

DracoWhole::DracoWhole(const Mesh& mesh, const DracoSettings& settings, size_t packet_size) {
    draco_ = draco_encode(mesh, settings);
    auto payloads = fragment_payloads(draco_, payload_capacity(packet_size));
    for (size_t i = 0; i < payloads.size(); ++i)
        packets_.push_back(baseline_packet(kDracoFragmentType, static_cast<uint32_t>(i), payloads[i]));
}

std::string DracoWhole::describe() const {
    std::ostringstream s;
    s << "Draco file of " << draco_.size() << " bytes in " << packets_.size()
      << " packets sent round robin; decodable once all are held";
    return s.str();
}

bool DracoWhole::reconstruct(const std::vector<uint32_t>& held, Mesh& out) const {
    out = Mesh{};
    // Reassemble from the packets' own headers, as a receiver would.
    std::vector<uint8_t> file;
    std::vector<bool> have;
    size_t total = 0, count = 0;
    for (uint32_t index : held) {
        if (index >= packets_.size()) continue;
        auto payload = baseline_payload(packets_[index], kDracoFragmentType);
        if (payload.size() < kFragmentHeader) continue;
        const size_t size = get_u32(payload.data()), n = get_u16(payload.data() + 4), i = get_u16(payload.data() + 6);
        if (have.empty()) {
            total = size;
            count = n;
            if (count == 0) return false;
            have.assign(count, false);
            file.assign(total, 0);
        }
        if (size != total || n != count || i >= count) continue;
        const size_t len = payload.size() - kFragmentHeader;
        if (have[i]) continue;
        // Every fragment but the last is full, so a fragment's place follows from its index and length.
        const size_t first = (i + 1 < count) ? i * len : total - std::min(len, total);
        if (first + len > total) continue;
        std::memcpy(file.data() + first, payload.data() + kFragmentHeader, len);
        have[i] = true;
    }
    if (have.empty()) return false;
    for (bool h : have)
        if (!h) return false;
    std::string error;
    return draco_decode(file, out, error) && !out.triangles.empty();
}

}  // namespace ellicast::compare

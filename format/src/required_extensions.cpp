// Required extensions (format 1.13, spec 29): REQUIRED_EXTENSION payloads and what a receiver keeps of
// them (take_required_extension: the comparisons of spec 29.1).
#include "ellicast/format.h"

#include "bytes.h"

namespace ellicast {

using namespace detail;

bool is_extension_name(std::string_view name) {
    if (name.empty() || name.size() > kMaxExtensionName) return false;
    for (const char c : name)
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return true;
}

std::vector<uint8_t> encode_required_extension_payload(const RequiredExtension& e) {
    std::vector<uint8_t> out;
    out.reserve(kRequiredExtensionHeaderSize + e.name.size());
    put_u8(out, e.name_count);
    put_u8(out, e.name_index);
    put_u16(out, 0);
    out.insert(out.end(), e.name.begin(), e.name.end());
    return out;
}

Error decode_required_extension_payload(std::span<const uint8_t> payload, RequiredExtension& out) {
    // Spec 29.1, rules 1..3 in order.
    if (payload.size() < kRequiredExtensionHeaderSize + 1 || payload.size() > kRequiredExtensionHeaderSize + kMaxExtensionName)
        return Error::MalformedPayload;
    RequiredExtension e;
    e.name_count = payload[0];
    e.name_index = payload[1];
    if (e.name_count == 0 || e.name_index >= e.name_count) return Error::MalformedPayload;
    e.name.assign(payload.begin() + kRequiredExtensionHeaderSize, payload.end());
    if (!is_extension_name(e.name)) return Error::MalformedPayload;
    out = std::move(e);
    return Error::Ok;
}

Error ReceivedStream::take_required_extension(const PacketView& packet, uint64_t where) {
    RequiredExtension e;
    if (decode_required_extension_payload(packet.payload, e) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "REQUIRED_EXTENSION payload inconsistent or out of range (no name or one longer than 64 bytes, "
                      "name count 0, an index not below the count, or a byte of the name not a letter, digit or "
                      "underscore)");
    // 1: the name count.
    if (required_extension_count_ && *required_extension_count_ != e.name_count)
        return reject(where, Error::StreamMismatch,
                      "REQUIRED_EXTENSION name count " + std::to_string(e.name_count) + " contradicts the " +
                          std::to_string(*required_extension_count_) + " of earlier packets");
    // 2: the name held at this index, 3: the same name at another.
    const std::string what = "required extension " + std::to_string(e.name_index) + " '" + e.name + "'";
    if (const auto it = required_extensions_.find(e.name_index); it != required_extensions_.end()) {
        if (it->second != e.name)
            return reject(where, Error::StreamMismatch, what + " contradicts the name '" + it->second + "' received before");
        ++counters_.duplicates;
        return Error::Ok;
    }
    for (const auto& [index, name] : required_extensions_)
        if (name == e.name)
            return reject(where, Error::StreamMismatch, what + ": the name is listed at index " + std::to_string(index) + " already");
    required_extension_count_ = e.name_count;
    required_extensions_.emplace(e.name_index, std::move(e.name));
    ++counters_.accepted;
    return Error::Ok;
}

}  // namespace ellicast

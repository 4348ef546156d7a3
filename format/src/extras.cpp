// Extras (format 1.12, spec 28): EXTRAS payloads, the check of a whole text, and what a receiver
// keeps of them (take_extras: the comparisons, the memory cap and the completion of spec 28.1).
#include "ellicast/format.h"

#include "bytes.h"
#include "fragments.h"
#include "json_text.h"

namespace ellicast {

using namespace detail;

const char* extras_target_name(ExtrasTarget kind) {
    static const char* names[kExtrasTargetKinds] = {"asset", "scene",     "node", "mesh",   "material",       "texture",
                                                    "animation", "skin", "camera", "light", "morph animation"};
    const auto k = static_cast<uint8_t>(kind);
    return k < kExtrasTargetKinds ? names[k] : "unknown";
}

std::string extras_target_label(ExtrasTarget kind, uint16_t index) {
    const bool whole = kind == ExtrasTarget::Asset || kind == ExtrasTarget::Scene;
    return std::string(extras_target_name(kind)) + (whole ? "" : " " + std::to_string(index));
}

std::vector<uint8_t> encode_extras_payload(const ExtrasFragment& f) {
    std::vector<uint8_t> out;
    out.reserve(kExtrasHeaderSize + f.data.size());
    put_u8(out, static_cast<uint8_t>(f.kind));
    put_u8(out, 0);
    put_u16(out, f.index);
    put_u16(out, f.text_count);
    put_u16(out, 0);
    put_u32(out, f.text_size);
    put_u32(out, f.text_crc);
    put_u32(out, f.offset);
    out.insert(out.end(), f.data.begin(), f.data.end());
    return out;
}

Error decode_extras_payload(std::span<const uint8_t> payload, ExtrasFragment& out) {
    // Spec 28.1, rules 1..5 in order.
    if (payload.size() < kExtrasHeaderSize + 1) return Error::MalformedPayload;
    const uint8_t* p = payload.data();
    ExtrasFragment f;
    if (p[0] >= kExtrasTargetKinds) return Error::MalformedPayload;
    f.kind = static_cast<ExtrasTarget>(p[0]);
    f.index = get_u16(p + 2);
    if ((f.kind == ExtrasTarget::Asset || f.kind == ExtrasTarget::Scene) && f.index != 0) return Error::MalformedPayload;
    f.text_count = get_u16(p + 4);
    f.text_size = get_u32(p + 8);
    f.text_crc = get_u32(p + 12);
    f.offset = get_u32(p + 16);
    if (f.text_count == 0 || f.text_size == 0 || f.text_size > kMaxExtrasText) return Error::MalformedPayload;
    const uint64_t length = payload.size() - kExtrasHeaderSize;
    if (uint64_t(f.offset) + length > f.text_size) return Error::MalformedPayload;
    f.data.assign(payload.begin() + kExtrasHeaderSize, payload.end());
    out = std::move(f);
    return Error::Ok;
}

bool acceptable_extras_text(std::string_view text) {
    if (!is_valid_utf8(text)) return false;
    Parser parser(text);
    return parser.document() != nullptr;
}

Error ReceivedStream::take_extras(const PacketView& packet, uint64_t where) {
    ExtrasFragment f;
    if (decode_extras_payload(packet.payload, f) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "EXTRAS payload inconsistent or out of range (shorter than 21 bytes, target kind above 10, an "
                      "asset or scene text with an index, text count 0, text size 0 or above 65536, or a fragment "
                      "past the text)");
    const std::string what = "extras of " + extras_target_label(f.kind, f.index);
    // 1, 2: the text count, then the description (or room for another target).
    if (extras_count_ && *extras_count_ != f.text_count)
        return reject(where, Error::StreamMismatch, "EXTRAS text count " + std::to_string(f.text_count) +
                                                        " contradicts the " + std::to_string(*extras_count_) + " of earlier packets");
    const ExtrasKey key{f.kind, f.index};
    auto it = extras_.find(key);
    if (it != extras_.end()) {
        if (it->second.text_size != f.text_size || it->second.text_crc != f.text_crc)
            return reject(where, Error::StreamMismatch, what + ": text size or CRC contradicts earlier fragments");
    } else if (extras_.size() >= f.text_count) {
        return reject(where, Error::StreamMismatch, what + ": the stream announced " + std::to_string(f.text_count) +
                                                        " texts, and this would be one more");
    }
    // 3: a duplicate.
    if (it != extras_.end() && it->second.complete) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    const uint32_t begin = f.offset, end = static_cast<uint32_t>(f.offset + f.data.size());
    const auto gaps = it == extras_.end() ? std::vector<std::pair<uint32_t, uint32_t>>{{begin, end}}
                                          : missing_runs(it->second.pieces, begin, end);
    uint64_t fresh = 0;
    for (auto [a, b] : gaps) fresh += b - a;
    if (fresh == 0) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    // 4: the memory cap, shared with textures: each run its bytes plus its bookkeeping, and a new
    // description its own. A complete text keeps counting what its runs counted.
    const uint64_t memory = fresh + gaps.size() * kHeldPacketCost + (it == extras_.end() ? kHeldPacketCost : 0);
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      what + ": the stream's textures and texts exceed this receiver's " +
                          std::to_string(limits_.max_texture_bytes) + "-byte memory limit for them");
    if (it == extras_.end()) {
        ReceivedExtras e;
        e.text_size = f.text_size;
        e.text_crc = f.text_crc;
        it = extras_.emplace(key, std::move(e)).first;
        extras_count_ = f.text_count;
    }
    ReceivedExtras& e = it->second;
    for (auto [a, b] : gaps)
        e.pieces.emplace(a, std::vector<uint8_t>(f.data.begin() + (a - begin), f.data.begin() + (b - begin)));
    e.received_bytes += fresh;
    e.memory += fresh + gaps.size() * kHeldPacketCost;
    texture_bytes_ += memory;
    if (e.received_bytes == e.text_size) {
        // 5, 6: the whole text's CRC-32C, then its JSON; either failing discards its bytes (the
        // description stays, and so does what it counts).
        std::vector<uint8_t> bytes = join_runs(e.pieces);
        e.pieces.clear();
        e.received_bytes = 0;
        auto discard = [&](Error error, const std::string& why) {
            texture_bytes_ -= e.memory;
            e.memory = 0;
            return reject(where, error, what + why);
        };
        if (crc32c(bytes.data(), bytes.size()) != e.text_crc)
            return discard(Error::StreamMismatch, " is complete but its CRC-32C does not match");
        std::string text(bytes.begin(), bytes.end());
        if (!acceptable_extras_text(text))
            return discard(Error::MalformedPayload, " is complete but is not one JSON text (RFC 8259, UTF-8, unique "
                                                    "member names, finite numbers, at most 32 deep)");
        e.text = std::move(text);
        e.received_bytes = e.text_size;
        e.complete = true;
    }
    ++counters_.accepted;  // after the checks of the whole text: a completing fragment that fails one is rejected only
    return Error::Ok;
}

}  // namespace ellicast

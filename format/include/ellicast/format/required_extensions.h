// Required extensions (format 1.13): the names of the glTF extensions the source asset required
// (its `extensionsRequired`), one REQUIRED_EXTENSION packet a name. Follows spec/format.md section 29
// (Format 1.13 addition: required extensions): 29.1 the payload and its checks; what a receiver keeps
// of them is in received_stream.h.
#pragma once

#include "ellicast/format/error.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ellicast {

inline constexpr size_t kRequiredExtensionHeaderSize = 4;
inline constexpr size_t kMaxExtensionName = 64;        // bytes of one name (spec 29.1)
inline constexpr size_t kMaxRequiredExtensions = 255;  // names in one stream (name_count is a u8)

// One REQUIRED_EXTENSION payload.
struct RequiredExtension {
    uint8_t name_count = 0;  // names in the whole stream
    uint8_t name_index = 0;  // this name's place in the list
    std::string name;
};

// A name as spec 29.1 defines it: 1 to 64 ASCII letters, digits and underscores.
bool is_extension_name(std::string_view name);

std::vector<uint8_t> encode_required_extension_payload(const RequiredExtension& extension);
// Spec 29.1, rules 1..3 (one reason for all): Ok or MalformedPayload.
Error decode_required_extension_payload(std::span<const uint8_t> payload, RequiredExtension& out);

}  // namespace ellicast

// The error codes of the format library: every parse and decode function returns one, and each names a
// reason for which a receiver rejects a packet or a container file. Follows spec/format.md sections
// 11.1 (Checking one packet) and 11.3 (Reasons); IoError is this library's own, for files.
#pragma once

#include <cstdint>

namespace ellicast {

enum class Error : uint8_t {
    Ok = 0,
    TooShort,             // fewer bytes than a packet header and checksum
    BadMagic,             // the first four bytes are not E1 4C 43 53
    UnsupportedMajor,     // major version other than 1
    InvalidType,          // packet type 0
    Oversized,            // header declares a packet larger than kMaxPacketSize
    Truncated,            // the declared payload runs past the bytes available
    LengthMismatch,       // a datagram holds bytes after the packet
    BadChecksum,          // CRC-32C does not match: the packet is damaged
    UnknownCriticalType,  // a type this decoder does not know, not marked skippable
    MalformedPayload,     // payload length or fields inconsistent with the packet type
    NoStreamInfo,         // payload needs the stream info of its object, which has not arrived
    UnknownObject,        // object id beyond the stream's object table
    IndexOutOfRange,      // an ellipsoid or point index beyond the object's declared count
    StreamMismatch,       // a packet of another stream id, or stream info contradicting earlier info
    BadSignature,         // a container file that does not start with the ellicast signature
    UnsupportedContainer, // container version other than 1
    IoError,              // a file could not be read or written
    ManifestSignature,    // with a key: a MANIFEST whose key id or Ed25519 signature does not match it
    NotAuthenticated,     // with a key: a packet that no verified MANIFEST lists
};

// A short readable name for an error ("bad checksum", ...).
const char* error_name(Error e);

}  // namespace ellicast

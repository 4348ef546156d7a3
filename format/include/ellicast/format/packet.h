// One packet on the wire: its 20-byte header and its CRC-32C checksum, and the functions that write,
// parse and restamp a whole packet without looking inside its payload. Follows spec/format.md
// sections 3 (Packet structure: 3.1 Header, 3.2 Checksum, 3.3 Sequence numbers, 3.4 Packet size) and
// 11.1 (Checking one packet, steps 1 to 8).
#pragma once

#include "ellicast/format/constants.h"
#include "ellicast/format/error.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace ellicast {

// ---------------------------------------------------------------------------------------------
// Checksum

// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78, init and final xor 0xFFFFFFFF).
// Pass the previous result as `crc` to continue over more data. crc32c("123456789") == 0xE3069283.
uint32_t crc32c(const uint8_t* data, size_t size, uint32_t crc = 0);

// ---------------------------------------------------------------------------------------------
// Packets

struct PacketHeader {
    uint8_t version_major = kFormatMajor;
    uint8_t version_minor = kFormatMinor;
    uint8_t type = 0;
    uint8_t flags = 0;
    uint32_t stream_id = 0;
    uint32_t sequence = 0;
    uint16_t object_id = kStreamObjectId;
    uint16_t payload_length = 0;

    bool skippable() const { return (flags & kFlagSkippable) != 0; }
    size_t packet_size() const { return kPacketOverhead + payload_length; }
};

// A packet as parsed in place: the header and a view of its payload inside the caller's bytes.
struct PacketView {
    PacketHeader header;
    std::span<const uint8_t> payload;
    size_t size = 0;  // whole packet: header + payload + checksum
};

// Serializes a packet: header (payload_length taken from payload.size()), payload, CRC-32C.
// Requires payload.size() <= kMaxPacketSize - kPacketOverhead.
std::vector<uint8_t> write_packet(PacketHeader header, std::span<const uint8_t> payload);
// The header of a skippable packet of a type a later minor version added (every type but
// STREAM_INFO, ELLIPSOIDS and POINTS), saying version 1.`minor`.
PacketHeader skippable_header(PacketType type, uint8_t minor, uint32_t stream_id, uint32_t sequence,
                              uint16_t object_id);

// Parses the packet at the start of `bytes`, which may continue with other data (a container).
// Checks magic, major version, type, declared length against kMaxPacketSize and against the bytes
// available, then the checksum. Does not look inside the payload.
Error parse_packet_prefix(std::span<const uint8_t> bytes, PacketView& out);

// Parses a datagram that must hold exactly one packet (LengthMismatch if bytes follow it).
Error parse_packet(std::span<const uint8_t> bytes, PacketView& out);

// Sets the sequence number of a serialized packet and recomputes its checksum. The sequence number
// counts transmissions (a carousel's repeats get new numbers); receivers estimate loss from its gaps
// and never use it to identify content. Returns false if `packet` is not a valid packet.
bool restamp_packet(std::vector<uint8_t>& packet, uint32_t sequence);
// Sets the stream id of a serialized packet and recomputes its checksum (a signer that gives each
// content its own stream id, spec 25.3). Returns false if `packet` is not a valid packet.
bool set_packet_stream_id(std::vector<uint8_t>& packet, uint32_t stream_id);

}  // namespace ellicast

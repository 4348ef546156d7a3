// Container files (.ellc): a recorded stream. The file's signature and header, writing and reading a
// container (keeping every intact packet after damage), and reading and writing whole files. Follows
// spec/format.md section 10 (Container file (.ellc)).
#pragma once

#include "ellicast/format/error.h"
#include "ellicast/format/packet.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ellicast {

// Container file: an 8-byte signature, a 4-byte file header, then packets back to back.
inline constexpr std::array<uint8_t, 8> kContainerSignature = {0x89, 'E', 'L', 'C', 0x0D, 0x0A, 0x1A, 0x0A};
inline constexpr size_t kContainerHeaderSize = 12;
inline constexpr uint8_t kContainerVersion = 1;

// The container header followed by the packets in the given order.
std::vector<uint8_t> write_container(const std::vector<std::vector<uint8_t>>& packets);

// A contiguous run of bytes of a container that holds no valid packet.
struct DamagedRegion {
    uint64_t offset = 0;
    uint64_t length = 0;
    Error first_error = Error::Ok;  // why the first packet expected at `offset` did not parse
};

struct ContainerPacket {
    uint64_t offset = 0;  // byte offset of the packet in the file
    PacketView view;      // points into the bytes given to read_container
};

struct ContainerContents {
    Error header_error = Error::Ok;  // BadSignature / UnsupportedContainer / TooShort: nothing read
    std::vector<ContainerPacket> packets;
    std::vector<DamagedRegion> damaged;
};

// Reads every intact packet of a container held in memory. After damage it resynchronizes on the
// next offset where a whole packet with a valid checksum starts, so every intact packet after a
// damaged region is kept. The returned views point into `bytes`.
ContainerContents read_container(std::span<const uint8_t> bytes);

// Reads a whole file into memory. Returns IoError (with the reason in `message`) when it cannot.
Error read_file(const std::string& path, std::vector<uint8_t>& out, std::string& message);
// Writes a file through a temporary file and a rename, so a failed write leaves no partial file.
// The temporary is created in the output's folder under an unpredictable name (".NAME.XXXXXXXXXXXX
// .partial"), exclusively and without following a symlink planted there; the rename replaces
// `path` itself (a symlink at `path` is replaced, its target is not written).
Error write_file(const std::string& path, std::span<const uint8_t> bytes, std::string& message);

}  // namespace ellicast

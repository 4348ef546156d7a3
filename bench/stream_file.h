// A stream file (.ellc) read into whole packets, for the benchmarks.
#pragma once

#include <ellicast/format.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace ellicast::bench {

// The intact packets of the container at `path`, in file order; false when it is not one.
inline bool read_stream_packets(const std::string& path, std::vector<std::vector<uint8_t>>& packets) {
    std::ifstream in(path, std::ios::binary);
    std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
    ContainerContents contents = read_container(bytes);
    if (contents.header_error != Error::Ok || contents.packets.empty()) return false;
    packets.clear();
    for (const auto& p : contents.packets)
        packets.emplace_back(bytes.data() + p.offset, bytes.data() + p.offset + p.view.size);
    return true;
}

}  // namespace ellicast::bench

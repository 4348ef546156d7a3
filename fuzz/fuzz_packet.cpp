// Fuzzes the packet parser and the receiver (ReceivedStream) with a sequence of datagrams.
//
// Input: one mode byte, then packets back to back (a container without its header: the seeds are the
// conformance vectors). Each datagram is cut at the length its own header declares (or what is left).
// Mode bit 0: recompute each datagram's CRC-32C first, so that mutated headers and payloads get past
// the checksum and reach the payload decoders and the receiver's state. Mode bit 1: give each datagram
// one byte more than its packet (the datagram length check).
#include "fuzz_common.h"

#include <cstdint>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace ellicast;
    if (size < 1) return 0;
    const uint8_t mode = data[0];
    ReceivedStream stream(fuzz::small_limits());
    uint64_t ordinal = 0;
    fuzz::for_each_datagram(mode, data + 1, size - 1, [&](const std::vector<uint8_t>& datagram) {
        PacketView view;
        Error e = parse_packet(datagram, view);
        if (e == Error::Ok && (view.size != datagram.size() || view.payload.size() != view.header.payload_length))
            std::abort();
        stream.add_packet(datagram, ordinal++);
    });
    fuzz::touch_everything(stream);
    return 0;
}

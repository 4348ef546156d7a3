// Fuzzes the container reader (resynchronization after damage) and the receiver fed from it.
// Input: a whole .ellc file (the seeds are the conformance vectors).
#include "fuzz_common.h"

#include <cstdint>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace ellicast;
    std::vector<uint8_t> bytes(data, data + size);  // exactly `size` bytes: ASan sees any overread
    ContainerContents c = read_container(bytes);
    // Invariants: packets and damaged regions tile the file after the header, in order.
    if (c.header_error == Error::Ok) {
        uint64_t covered = kContainerHeaderSize;
        size_t pi = 0, di = 0;
        while (pi < c.packets.size() || di < c.damaged.size()) {
            if (pi < c.packets.size() && c.packets[pi].offset == covered) {
                covered += c.packets[pi++].view.size;
            } else if (di < c.damaged.size() && c.damaged[di].offset == covered && c.damaged[di].length > 0) {
                covered += c.damaged[di++].length;
            } else {
                std::abort();
            }
        }
        if (covered != size) std::abort();
    } else if (!c.packets.empty() || !c.damaged.empty()) {
        std::abort();
    }
    ReceivedStream stream(fuzz::small_limits());
    for (const auto& p : c.packets) stream.add_parsed(p.view, p.offset);
    fuzz::touch_everything(stream);
    return 0;
}

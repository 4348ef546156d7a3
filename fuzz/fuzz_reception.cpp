// Fuzzes a network receiver's candidate handling (broadcast::Reception, spec 11.4): a sequence of
// datagrams from several senders, forged STREAM_INFO packets among them, reaching the candidate
// streams, the eviction of the weakest candidate when every place is taken, the choice of the
// stream shown, and the byte budget the candidates share.
//
// Input: one mode byte, then packets back to back (the seeds are the conformance vectors without their
// container header). Mode bits 0 and 1 as fuzz_packet (reseal checksums; one byte more). Mode bit 2:
// each datagram's stream id is rewritten to one of four (from its own first payload byte) and its
// checksum resealed, so that one input plays several senders with the same packets. Mode bits 3..4:
// the candidate places, 1 to 4.
#include "fuzz_common.h"

#include <ellicast/broadcast/reception.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace ellicast;
    if (size < 1) return 0;
    const uint8_t mode = data[0];
    broadcast::Reception::Options options;
    options.limits = fuzz::small_limits();
    options.max_candidates = 1 + ((mode >> 3) & 3);
    broadcast::Reception reception(options);
    uint64_t taken = 0;
    fuzz::for_each_datagram(mode, data + 1, size - 1, [&](std::vector<uint8_t> datagram) {
        if ((mode & 4) && datagram.size() >= kPacketOverhead) {
            const uint32_t id = 0xE1100000u + (datagram.size() > kHeaderSize ? datagram[kHeaderSize] & 3 : 0);
            std::memcpy(datagram.data() + 8, &id, 4);  // stream_id: bytes 8..11 of the header (spec 3.1)
            const size_t body = datagram.size() - kChecksumSize;
            const uint32_t crc = crc32c(datagram.data(), body);
            std::memcpy(datagram.data() + body, &crc, 4);
        }
        const bool had = reception.chosen() < reception.candidate_count();
        const uint64_t shown = had ? reception.candidate_serial(reception.chosen()) : 0;
        reception.take(datagram);
        ++taken;
        // The promises: bounded candidates, the stream shown is one of them, and the one shown before
        // this datagram was not evicted to make room.
        if (reception.candidate_count() > options.max_candidates) std::abort();
        if (reception.candidate_count() > 0 && reception.chosen() >= reception.candidate_count()) std::abort();
        // One byte budget for every candidate (spec 11.2): what it counts is what they hold.
        uint64_t held = 0;
        for (size_t i = 0; i < reception.candidate_count(); ++i) held += reception.candidate(i).held_memory();
        if (held != reception.memory().held) std::abort();
        if (had) {
            bool kept = false;
            for (size_t i = 0; i < reception.candidate_count(); ++i) kept |= reception.candidate_serial(i) == shown;
            if (!kept) std::abort();
        }
    });
    const broadcast::ReceptionCounters c = reception.counters();
    if (c.datagrams != taken) std::abort();
    for (size_t i = 0; i < reception.candidate_count(); ++i) fuzz::touch_everything(reception.candidate(i));
    (void)reception.complete();
    (void)reception.every_candidate_complete();
    (void)reception.points_received();
    return 0;
}

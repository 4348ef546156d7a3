// A receiver that hears more than one sender: no first packet and no early forged STREAM_INFO may
// take the stream from the real sender (issue 15, "the receiver must not be hijacked").
#include "broadcast_support.h"

#include <ellicast/broadcast/reception.h>

using namespace ellicast;
using namespace ellicast::broadcast;

namespace {

// Two cycles of a carousel-like repetition: every packet of the stream, twice.
void take_twice(Reception& reception, const std::vector<std::vector<uint8_t>>& packets) {
    for (int cycle = 0; cycle < 2; ++cycle)
        for (const auto& p : packets) reception.take(p);
}

}  // namespace

TEST_CASE("a second sender heard first does not take the receiver: the stream with the most packets is kept") {
    const auto real = test::synthetic_stream(40, 3000, 0xAAAA);
    const auto stranger = test::synthetic_stream(5, 100, 0xBBBB, 1200, 99);
    Reception reception;
    for (const auto& p : stranger) reception.take(p);  // the stranger's whole stream first
    CHECK(reception.stream().stream_id() == 0xBBBB);  // all there is so far
    take_twice(reception, real);
    CHECK(reception.candidate_count() == 2);
    CHECK(reception.stream().stream_id() == 0xAAAA);
    CHECK(reception.complete());
    const auto c = reception.counters();
    CHECK(c.accepted == real.size());
    CHECK(c.duplicates == real.size());
    CHECK(c.other_stream == stranger.size());
    REQUIRE(reception.stream().info());
    CHECK(reception.stream().info()->objects[0].point_count == 3000);
}

TEST_CASE("one early forged STREAM_INFO with the real stream id does not lock the real stream out") {
    const auto real = test::synthetic_stream(40, 3000, 0xAAAA);
    // A forger's STREAM_INFO for the same stream id, declaring another object (CRC valid).
    const auto forged = test::synthetic_stream(7, 50, 0xAAAA, 1200, 3);
    for (bool with_id : {false, true}) {
        CAPTURE(with_id);
        Reception::Options options;
        if (with_id) options.stream_id = 0xAAAA;
        Reception reception(options);
        CHECK(reception.take(forged[0]) == Error::Ok);
        REQUIRE(reception.stream().info());
        CHECK(reception.stream().info()->objects[0].ellipsoid_count == 7);
        take_twice(reception, real);
        CHECK(reception.candidate_count() == 2);
        REQUIRE(reception.stream().info());
        CHECK(reception.stream().info()->objects[0].ellipsoid_count == 40);
        CHECK(reception.complete());
        CHECK(reception.points_received() == 3000);
        // The forged candidate took only what fits its own stream info; the real one took everything.
        CHECK(reception.candidate(0).counters().accepted < reception.candidate(1).counters().accepted);
    }
}

TEST_CASE("the candidates are bounded: a stream heard once every place is taken takes the weakest one's place") {
    Reception::Options options;
    options.max_candidates = 3;
    Reception reception(options);
    for (uint32_t id = 1; id <= 10; ++id)
        for (const auto& p : test::synthetic_stream(2, 20, id, 1200, id)) reception.take(p);
    CHECK(reception.candidate_count() == 3);  // memory: at most three streams at a time
    CHECK(reception.evictions() == 7);
    const auto real = test::synthetic_stream(40, 3000, 0xAAAA);
    take_twice(reception, real);
    CHECK(reception.candidate_count() == 3);
    CHECK(reception.stream().stream_id() == 0xAAAA);
    CHECK(reception.complete());
    CHECK(reception.points_received() == 3000);
    // With the stream id given, only that stream is heard at all.
    Reception::Options only;
    only.stream_id = 0xAAAA;
    only.max_candidates = 3;
    Reception chosen(only);
    for (uint32_t id = 1; id <= 10; ++id)
        for (const auto& p : test::synthetic_stream(2, 20, id, 1200, id)) chosen.take(p);
    take_twice(chosen, real);
    CHECK(chosen.candidate_count() == 1);
    CHECK(chosen.complete());
}

TEST_CASE("four forged STREAM_INFO datagrams of four stream ids sent before the real sender do not lock it out") {
    // Issue 29, row 1: every candidate place was taken for good and the real stream never considered.
    const auto real = test::synthetic_stream(40, 3000, 0xAAAA);
    Reception reception;  // the default: four candidates
    for (uint32_t id = 1; id <= 4; ++id) CHECK(reception.take(test::synthetic_stream(7, 50, id, 1200, id)[0]) == Error::Ok);
    CHECK(reception.candidate_count() == 4);
    CHECK(reception.take(real[0]) == Error::Ok);  // takes a forger's place
    CHECK(reception.last_evicted() != 0);
    CHECK(reception.evictions() == 1);
    take_twice(reception, real);
    CHECK(reception.stream().stream_id() == 0xAAAA);
    CHECK(reception.complete());
    CHECK(reception.points_received() == 3000);
}

TEST_CASE("a flood of new stream ids never takes the place of the stream shown") {
    const auto real = test::synthetic_stream(40, 3000, 0xAAAA);
    Reception reception;
    const size_t half = real.size() / 2;
    for (size_t i = 0; i < half; ++i) reception.take(real[i]);
    REQUIRE(reception.stream().stream_id() == 0xAAAA);
    const uint64_t serial = reception.candidate_serial(reception.chosen());
    for (uint32_t id = 1; id <= 200; ++id) {
        reception.take(test::synthetic_stream(7, 50, id, 1200, id)[0]);
        CHECK((reception.last_evicted() >> reception.chosen() & 1) == 0);
    }
    CHECK(reception.candidate_count() == 4);
    CHECK(reception.evictions() == 197);
    CHECK(reception.candidate_serial(reception.chosen()) == serial);  // still the same candidate
    for (size_t i = half; i < real.size(); ++i) reception.take(real[i]);
    CHECK(reception.stream().stream_id() == 0xAAAA);
    CHECK(reception.complete());
}

TEST_CASE("a small stream that completes first does not end a receiver that heard another one still arriving") {
    const auto small = test::synthetic_stream(2, 30, 0xBBBB, 1200, 5);
    const auto real = test::synthetic_stream(40, 3000, 0xAAAA);
    Reception reception;
    for (const auto& p : small) reception.take(p);
    reception.take(real[0]);  // the real sender's stream info: a second candidate, far from complete
    CHECK(reception.stream().stream_id() == 0xBBBB);
    CHECK(reception.complete());  // the stream shown is complete...
    CHECK_FALSE(reception.every_candidate_complete());  // ...but the other is not: `receive` keeps going
    for (const auto& p : real) reception.take(p);
    CHECK(reception.stream().stream_id() == 0xAAAA);
    CHECK(reception.every_candidate_complete());
}

TEST_CASE("the candidate streams share one byte budget: a datagram that reaches two candidates is not paid for twice") {
    const auto real = test::synthetic_stream(40, 3000, 0xAAAA);
    // A STREAM_INFO for the same stream id that contradicts the real one (another packet size) but
    // declares the same object: every packet of the real stream reaches both candidates.
    const auto contradicting = test::synthetic_stream(40, 3000, 0xAAAA, 1400);
    auto held_together = [](const Reception& r) {
        uint64_t sum = 0;
        for (size_t i = 0; i < r.candidate_count(); ++i) sum += r.candidate(i).held_memory();
        return sum;
    };
    // With the default budget, both take everything: each holds the whole object.
    Reception roomy;
    roomy.take(contradicting[0]);
    take_twice(roomy, real);
    REQUIRE(roomy.candidate_count() == 2);
    CHECK(roomy.complete());
    const uint64_t one = roomy.candidate(1).held_memory();
    CHECK(roomy.candidate(0).held_memory() == one);
    CHECK(roomy.memory().held == 2 * one);
    uint64_t bytes = 0;
    for (const auto& p : real) bytes += 2 * p.size();
    CHECK(roomy.memory().bytes == bytes + contradicting[0].size());

    // A budget that one candidate's object fits but two do not: 8 KiB plus 1x the bytes taken, the
    // stream heard once. Budgets of their own would have let each candidate hold about `one`.
    Reception::Options options;
    options.limits.memory_base = 8u << 10;
    options.limits.memory_per_byte = 1;
    Reception tight(options);
    tight.take(contradicting[0]);
    for (const auto& p : real) tight.take(p);
    REQUIRE(tight.candidate_count() == 2);
    const SharedMemoryBudget& b = tight.memory();
    CHECK(b.held == held_together(tight));
    MESSAGE("two candidates of one object: " << b.held << " bytes held together for a budget of " << b.budget()
                                             << " (each alone would hold " << one << ")");
    CHECK(b.budget() < 2 * one);
    CHECK(b.held < 3 * one / 2);
    CHECK(b.held <= b.budget() + 2 * 1200 * 8);  // at most one packet's records over, for each candidate
    bool said = false;
    for (size_t i = 0; i < 2; ++i)
        for (const Rejection& r : tight.candidate(i).rejections())
            said |= r.detail.find("candidate streams hold") != std::string::npos;
    CHECK(said);

    // A candidate dropped to make room gives back what it held.
    Reception::Options two = options;
    two.max_candidates = 2;
    Reception evicting(two);
    evicting.take(contradicting[0]);
    for (const auto& p : real) evicting.take(p);
    REQUIRE(evicting.candidate_count() == 2);
    const uint64_t before = evicting.memory().held;
    for (const auto& p : test::synthetic_stream(2, 20, 0xBBBB, 1200, 5)) evicting.take(p);
    CHECK(evicting.evictions() >= 1);
    CHECK(evicting.memory().held == held_together(evicting));
    CHECK(evicting.memory().held < before);
}

// Loss traces as text files, so that the same losses can be applied again, elsewhere, later.
#include <ellicast/broadcast/channel.h>
#include <ellicast/format.h>

#include <charconv>
#include <fstream>
#include <sstream>

namespace ellicast::broadcast {

namespace {

constexpr const char* kTraceMagic = "ellicast-loss-trace 1";
constexpr size_t kMaxLineLength = 4096;

template <typename T>
bool parse_number(const std::string& text, T& value) {
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

bool write_trace(const std::string& path, const LossTrace& trace, std::string& error) {
    std::ostringstream out;
    {
        out << kTraceMagic << "\n";
        out << "slots " << trace.slots() << "\n";
        out << "packet_bytes " << trace.packet_bytes() << "\n";
        out << "model " << trace.description() << "\n";
        out << "# one line per slot not delivered intact: <slot> lost | [delay N] [dup] [flip b1,b2,...]\n";
        for (uint64_t k = 0; k < trace.slots(); ++k) {
            SlotFate f = trace.fate(k);
            if (!f.lost && !f.duplicated && f.delay == 0 && f.flipped_bits.empty()) continue;
            out << k;
            if (f.lost) {
                out << " lost\n";
                continue;
            }
            if (f.delay) out << " delay " << f.delay;
            if (f.duplicated) out << " dup";
            if (!f.flipped_bits.empty()) {
                out << " flip ";
                for (size_t i = 0; i < f.flipped_bits.size(); ++i) out << (i ? "," : "") << f.flipped_bits[i];
            }
            out << "\n";
        }
    }
    const std::string text = out.str();
    std::string message;
    if (write_file(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()), message) !=
        Error::Ok) {
        error = "cannot write the trace: " + message;
        return false;
    }
    return true;
}

bool read_trace(const std::string& path, LossTrace& out, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open the trace " + path;
        return false;
    }
    std::string line;
    uint64_t line_number = 0;
    auto fail = [&](const std::string& what) {
        error = path + ":" + std::to_string(line_number) + ": " + what;
        return false;
    };
    auto next_line = [&]() -> bool {
        if (!std::getline(in, line)) return false;
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        return true;
    };
    if (!next_line() || line != kTraceMagic) return fail("not an ellicast loss trace (expected \"" + std::string(kTraceMagic) + "\")");
    uint64_t slots = 0;
    size_t packet_bytes = 0;
    std::string model;
    bool have_slots = false, have_size = false;
    LossTrace trace;
    int64_t previous = -1;
    while (next_line()) {
        if (line.size() > kMaxLineLength) return fail("line too long");
        if (line.empty() || line[0] == '#') continue;
        const bool slot_line = line[0] >= '0' && line[0] <= '9';
        if (!slot_line) {
            // Header lines, before the first slot.
            if (previous >= 0) return fail("header line \"" + line.substr(0, 40) + "\" after the slots");
            if (line.rfind("slots ", 0) == 0) {
                if (!parse_number(line.substr(6), slots)) return fail("bad slot count");
                if (slots > kMaxTraceSlots) return fail("a trace of " + line.substr(6) + " slots exceeds the cap");
                have_slots = true;
            } else if (line.rfind("packet_bytes ", 0) == 0) {
                if (!parse_number(line.substr(13), packet_bytes) || packet_bytes == 0 || packet_bytes > 1'000'000)
                    return fail("bad packet size");
                have_size = true;
            } else if (line.rfind("model ", 0) == 0) {
                model = line.substr(6);
            } else {
                return fail("unexpected header line \"" + line.substr(0, 80) + "\"");
            }
            continue;
        }
        if (!(have_slots && have_size)) return fail("a slot before the \"slots\" and \"packet_bytes\" lines");
        if (previous < 0) trace = LossTrace(slots, packet_bytes, model);  // the first slot line
        std::istringstream words(line);
        std::string word;
        words >> word;
        uint64_t slot = 0;
        if (!parse_number(word, slot)) return fail("expected a slot number, got \"" + word + "\"");
        if (slot >= slots) return fail("slot " + word + " is beyond the trace's " + std::to_string(slots) + " slots");
        if (static_cast<int64_t>(slot) <= previous) return fail("slots must be listed in increasing order");
        previous = static_cast<int64_t>(slot);
        SlotFate f;
        bool any = false;
        while (words >> word) {
            any = true;
            if (word == "lost") {
                f.lost = true;
            } else if (word == "dup") {
                f.duplicated = true;
            } else if (word == "delay") {
                std::string value;
                words >> value;
                if (!parse_number(value, f.delay) || f.delay == 0 || f.delay > 1'000'000)
                    return fail("bad delay \"" + value + "\"");
            } else if (word == "flip") {
                std::string list;
                words >> list;
                std::istringstream items(list);
                std::string item;
                while (std::getline(items, item, ',')) {
                    uint32_t bit = 0;
                    if (!parse_number(item, bit)) return fail("bad bit position \"" + item + "\"");
                    if (f.flipped_bits.size() >= 1024) return fail("too many flipped bits in one slot");
                    f.flipped_bits.push_back(bit);
                }
                if (f.flipped_bits.empty()) return fail("\"flip\" needs bit positions");
            } else {
                return fail("unknown fate \"" + word + "\"");
            }
        }
        if (!any) return fail("slot " + std::to_string(slot) + " has no fate");
        if (f.lost && (f.duplicated || f.delay || !f.flipped_bits.empty()))
            return fail("a lost slot cannot also be delayed, duplicated or corrupted");
        trace.set_fate(slot, f);
    }
    if (!(have_slots && have_size)) return fail("the header ends before \"slots\" and \"packet_bytes\"");
    if (previous < 0) trace = LossTrace(slots, packet_bytes, model);  // no slot line: every slot delivered intact
    out = std::move(trace);
    return true;
}

}  // namespace ellicast::broadcast

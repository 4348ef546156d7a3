// UTF-8 well-formedness (Unicode 15, table 3-7) and replacement of ill-formed sequences by U+FFFD.
#include "ellicast/format.h"

namespace ellicast {

namespace {

// Length of the well-formed sequence starting at text[i], or 0 when none starts there; `bad` is
// then the length of the maximal ill-formed subpart (at least 1) to replace by one U+FFFD.
size_t sequence_at(std::string_view text, size_t i, size_t& bad) {
    const auto byte = [&](size_t k) { return i + k < text.size() ? uint8_t(text[i + k]) : uint8_t(0); };
    const uint8_t b0 = byte(0);
    bad = 1;
    if (b0 < 0x80) return 1;
    size_t need;
    uint8_t lo = 0x80, hi = 0xBF;  // the range of the second byte
    if (b0 >= 0xC2 && b0 <= 0xDF) need = 2;
    else if (b0 == 0xE0) need = 3, lo = 0xA0;
    else if ((b0 >= 0xE1 && b0 <= 0xEC) || b0 == 0xEE || b0 == 0xEF) need = 3;
    else if (b0 == 0xED) need = 3, hi = 0x9F;
    else if (b0 == 0xF0) need = 4, lo = 0x90;
    else if (b0 >= 0xF1 && b0 <= 0xF3) need = 4;
    else if (b0 == 0xF4) need = 4, hi = 0x8F;
    else return 0;
    for (size_t k = 1; k < need; ++k) {
        const uint8_t b = byte(k);
        const bool ok = i + k < text.size() && (k == 1 ? (b >= lo && b <= hi) : (b >= 0x80 && b <= 0xBF));
        if (!ok) {
            bad = k;
            return 0;
        }
    }
    return need;
}

}  // namespace

bool is_valid_utf8(std::string_view text) {
    for (size_t i = 0; i < text.size();) {
        size_t bad;
        const size_t n = sequence_at(text, i, bad);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

std::string replace_invalid_utf8(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        size_t bad;
        const size_t n = sequence_at(text, i, bad);
        if (n > 0) {
            out.append(text.substr(i, n));
            i += n;
        } else {
            out += "\xEF\xBF\xBD";
            i += bad;
        }
    }
    return out;
}

}  // namespace ellicast

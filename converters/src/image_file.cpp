// The structure of PNG and JPEG files (see image_file.h): chunks or markers, never the pixels.
#include "ellicast/converters/image_file.h"

#include <cstring>
#include <map>
#include <set>
#include <utility>

namespace ellicast::image_file {

namespace {

uint32_t be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }
uint16_t be16(const uint8_t* p) { return uint16_t(p[0] << 8 | p[1]); }

std::string at(size_t offset) { return " at byte " + std::to_string(offset); }

// PNG (ISO/IEC 15948): the signature, then chunks of length, type, data, CRC; IHDR first, IEND last.
Check check_png(std::span<const uint8_t> b) {
    Check c;
    c.format = Format::Png;
    size_t pos = 8;
    for (size_t chunk = 0;; ++chunk) {
        if (pos + 8 > b.size()) {
            c.problem = pos == b.size() ? "ends" + at(pos) + " without its IEND chunk"
                                        : "is truncated" + at(b.size()) + " in the header of the chunk" + at(pos);
            return c;
        }
        const uint32_t length = be32(&b[pos]);
        const std::string type(reinterpret_cast<const char*>(&b[pos + 4]), 4);
        if (chunk == 0 && (type != "IHDR" || length != 13)) {
            c.problem = "does not start with its 13-byte IHDR chunk";
            return c;
        }
        if (length > 0x7FFFFFFFu || uint64_t(pos) + 12 + length > b.size()) {
            c.problem = "is truncated" + at(b.size()) + " in its " + type + " chunk (" + std::to_string(length) +
                        " bytes from byte " + std::to_string(pos + 8) + ")";
            return c;
        }
        if (chunk == 0) c.readable = true;
        pos += 12 + size_t(length);
        if (type == "IEND") return c;
    }
}

bool is_frame_header(uint8_t m) {
    return (m >= 0xC0 && m <= 0xCF) && m != 0xC4 && m != 0xC8 && m != 0xCC;  // SOF0..SOF15 but DHT, JPG, DAC
}

// JPEG (ITU-T T.81): SOI, marker segments (FF, marker, big-endian length counting itself), one frame
// header, scans (SOS then entropy-coded data, in which FF is followed by 00 or a restart marker), EOI.
Check check_jpeg(std::span<const uint8_t> b) {
    Check c;
    c.format = Format::Jpeg;
    size_t pos = 2;
    uint8_t frame = 0;                     // the frame header's marker, 0 before it
    std::map<uint8_t, uint8_t> components;  // the frame's component ids -> their quantization table
    std::set<uint8_t> quant;                // defined quantization tables
    std::set<std::pair<int, int>> huffman;  // (class 0 DC / 1 AC, id) of defined Huffman tables
    int scans = 0;
    auto fail = [&](std::string problem) {
        c.problem = std::move(problem);
        return c;
    };
    while (true) {
        if (pos >= b.size()) return fail(scans ? "ends" + at(pos) + " without its EOI marker (truncated)"
                                               : "is truncated" + at(pos) + " before its first scan");
        if (b[pos] != 0xFF) return fail("has no marker" + at(pos));
        const size_t marker_at = pos;
        while (pos < b.size() && b[pos] == 0xFF) ++pos;  // fill bytes
        if (pos >= b.size()) return fail("is truncated" + at(pos));
        const uint8_t m = b[pos++];
        if (m == 0xD9) {  // EOI
            if (!scans) return fail("has its EOI marker" + at(marker_at) + " before any scan");
            return c;
        }
        if (m == 0x00 || m == 0x01 || (m >= 0xD0 && m <= 0xD8))
            return fail("has the stand-alone marker FF" + std::string(1, "0123456789ABCDEF"[m >> 4]) +
                        "0123456789ABCDEF"[m & 15] + at(marker_at) + " outside a scan");
        if (pos + 2 > b.size()) return fail("is truncated" + at(b.size()) + " in the segment" + at(marker_at));
        const size_t length = be16(&b[pos]);
        if (length < 2 || pos + length > b.size())
            return fail("is truncated" + at(b.size()) + " in the segment" + at(marker_at) + " (" + std::to_string(length) +
                        " bytes)");
        const uint8_t* body = &b[pos + 2];
        const size_t n = length - 2;
        pos += length;
        if (is_frame_header(m)) {
            if (frame) return fail("has a second frame header" + at(marker_at));
            if (n < 6 || n != 6 + 3 * size_t(body[5])) return fail("has a frame header of the wrong length" + at(marker_at));
            const unsigned height = be16(body + 1), width = be16(body + 3), count = body[5];
            if (!width || !height || count < 1 || count > 4)
                return fail("has a frame of " + std::to_string(width) + " x " + std::to_string(height) + " with " +
                            std::to_string(count) + " components" + at(marker_at));
            for (unsigned i = 0; i < count; ++i) components[body[6 + 3 * i]] = body[8 + 3 * i] & 15;
            frame = m;
        } else if (m == 0xDB) {  // DQT: (precision, id), then 64 values of 1 or 2 bytes; repeated
            size_t k = 0;
            while (k < n) {
                quant.insert(body[k] & 15);
                k += 1 + 64 * ((body[k] >> 4) ? 2 : 1);
            }
            if (k != n) return fail("has a quantization table segment of the wrong length" + at(marker_at));
        } else if (m == 0xC4) {  // DHT: (class, id), 16 code counts, the values; repeated
            size_t k = 0;
            while (k + 17 <= n) {
                huffman.insert({body[k] >> 4, body[k] & 15});
                size_t values = 0;
                for (int i = 1; i <= 16; ++i) values += body[k + i];
                k += 17 + values;
            }
            if (k != n) return fail("has a Huffman table segment of the wrong length" + at(marker_at));
        } else if (m == 0xDA) {  // SOS, then the scan's entropy-coded data
            if (!frame) return fail("has a scan before its frame header" + at(marker_at));
            if (n < 4 || n != 4 + 2 * size_t(body[0])) return fail("has a scan header of the wrong length" + at(marker_at));
            const unsigned count = body[0], spectral_start = body[1 + 2 * count], high_bit = body[3 + 2 * count] >> 4;
            // SOFn: n & 3 is 0/1 sequential, 2 progressive, 3 lossless; n >= 9 arithmetic coding.
            const bool arithmetic = frame >= 0xC9, progressive = (frame & 3) == 2, lossless = (frame & 3) == 3;
            for (unsigned i = 0; i < count; ++i) {
                const auto component = components.find(body[1 + 2 * i]);
                if (component == components.end())
                    return fail("has a scan naming a component not in its frame" + at(marker_at));
                if (!lossless && !quant.count(component->second))
                    return fail("has a scan using an undefined quantization table" + at(marker_at));
                const std::pair<int, int> dc = {0, body[2 + 2 * i] >> 4}, ac = {1, body[2 + 2 * i] & 15};
                bool ok = true;  // arithmetic coding needs no tables
                if (!arithmetic && lossless) ok = huffman.count(dc);
                else if (!arithmetic && !progressive) ok = huffman.count(dc) && huffman.count(ac);
                else if (!arithmetic && spectral_start > 0) ok = huffman.count(ac);    // an AC scan
                else if (!arithmetic && high_bit == 0) ok = huffman.count(dc);         // a first DC scan
                if (!ok) return fail("has a scan using an undefined Huffman table" + at(marker_at));
            }
            ++scans;
            c.readable = true;
            while (true) {  // up to the next marker that is not a restart marker
                if (pos + 1 >= b.size())
                    return fail("is truncated" + at(b.size()) + " in the data of scan " + std::to_string(scans) +
                                " (no EOI marker)");
                if (b[pos] == 0xFF && b[pos + 1] != 0x00 && !(b[pos + 1] >= 0xD0 && b[pos + 1] <= 0xD7)) break;
                pos += b[pos] == 0xFF ? 2 : 1;
            }
        }
        // APPn, COM, DRI, DNL, DAC and other segments: skipped by their length.
    }
}

}  // namespace

Check check(std::span<const uint8_t> bytes) {
    static const uint8_t png[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), png, 8) == 0) return check_png(bytes);
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return check_jpeg(bytes);
    return {};
}

const char* name(Format format) {
    return format == Format::Png ? "PNG" : format == Format::Jpeg ? "JPEG" : "unknown";
}

const char* mime_type(Format format) {
    return format == Format::Png ? "image/png" : format == Format::Jpeg ? "image/jpeg" : "";
}

}  // namespace ellicast::image_file

// What the bytes of a texture image file are (used by the converters and by `ellicast validate`). ellicast carries images as
// the asset had them and never decodes them, but it must know a PNG from a JPEG (the stream's
// image_type, the glTF mimeType) and must not pass on a file that no viewer can open (the glTF
// validator rejects an image whose header is cut off). Only the file's structure is read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace ellicast::image_file {

enum class Format { Unknown, Png, Jpeg };

struct Check {
    Format format = Format::Unknown;  // from the signature alone
    bool readable = false;            // the header a viewer needs is complete (PNG: IHDR; JPEG: the
                                      // frame header and what precedes the first scan's data)
    std::string problem;              // empty when the whole file is well formed; else what is wrong,
                                      // with the byte offset ("is truncated at byte 300 in the data of scan 1")
};

// Reads the structure of a PNG (signature, chunk lengths, IHDR first, IEND last) or JPEG file
// (markers from SOI: one frame header, segment lengths, the tables each scan uses defined before
// it, entropy-coded data, EOI). Bytes after IEND or EOI are allowed (some writers append data).
Check check(std::span<const uint8_t> bytes);

// "PNG" / "JPEG" / "unknown", and the media type glTF names the format by ("image/png",
// "image/jpeg"; "" for Unknown).
const char* name(Format format);
const char* mime_type(Format format);

}  // namespace ellicast::image_file

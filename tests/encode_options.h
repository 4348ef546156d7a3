// Encoder settings shared by the tests that encode (not part of the format-only test build).
#pragma once

#include "ellicast/codec/encoder.h"

namespace ellicast::test {

// Coarse settings that keep the suite fast; the benchmarks run the defaults.
inline EncodeOptions fast_options() {
    EncodeOptions o;
    o.max_ellipsoids = 40;
    o.candidates = 200;
    o.grid = 32;
    return o;
}

}  // namespace ellicast::test

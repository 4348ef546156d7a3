// Geometry as the format carries it: ellipsoids and surface points, dequantized, and their quantized
// forms, with the functions that quantize and dequantize them, the 16-byte layout of an ellipsoid and
// its error bound. Follows spec/format.md sections 6.1 (Ellipsoid encoding), 7.1 (Point record) and 8
// (Quantization and error bounds: 8.1 Ellipsoids; 8.2 Point positions, texture coordinates, colours;
// 8.3 Normals (octahedral); 8.4 Arithmetic).
#pragma once

#include "ellicast/format/stream_info.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace ellicast {

// ---------------------------------------------------------------------------------------------
// Geometry values (dequantized)

// An ellipsoid: the points x with |diag(1/radii) * R^T (x - center)|^2 <= 1, where R is the rotation
// of the unit quaternion `rotation` = (w, x, y, z); column i of R is the direction of semi-axis i.
// As an implicit quadric: x'Ax + 2b'x + c <= 0 with A = R diag(1/r^2) R^T, b = -A center,
// c = center' A center - 1 (the paper normalizes c to 1).
struct Ellipsoid {
    std::array<float, 3> center{};
    std::array<float, 3> radii{};
    std::array<float, 4> rotation{1, 0, 0, 0};
};

// A surface sample: an original vertex with the attributes its object carries.
struct SurfacePoint {
    std::array<float, 3> position{};
    std::array<float, 3> normal{};      // unit length, when the object has normals
    std::array<float, 2> texcoord{};    // when the object has TEXCOORD_0
    std::array<float, 4> color{0, 0, 0, 1};  // linear RGBA in [0,1], when the object has COLOR_0
};

// ---------------------------------------------------------------------------------------------
// Quantization (section "Quantization" of the spec states every error bound)

inline constexpr size_t kEllipsoidBytes = 16;                   // one quantized ellipsoid

// A quantized ellipsoid, 16 bytes: centre 3 x 15 bits, radii 3 x 13 bits, rotation as the
// "smallest three" of its quaternion (2-bit index + 3 x 14 bits).
struct QuantizedEllipsoid {
    std::array<uint16_t, 3> center{};   // 0..32767 across the frame
    std::array<uint16_t, 3> radii{};    // 0..8191, radius = q * scale / 8191
    uint8_t largest = 0;                // index (0=w,1=x,2=y,3=z) of the dropped quaternion component
    std::array<uint16_t, 3> rotation{}; // 0..16383, the other three components in order
};

QuantizedEllipsoid quantize_ellipsoid(const Ellipsoid& e, const Frame& frame);
Ellipsoid dequantize_ellipsoid(const QuantizedEllipsoid& q, const Frame& frame);
void pack_ellipsoid(const QuantizedEllipsoid& q, uint8_t out[kEllipsoidBytes]);
QuantizedEllipsoid unpack_ellipsoid(const uint8_t in[kEllipsoidBytes]);

// Largest distance between a point of the true ellipsoid surface and its image on the
// dequantized ellipsoid (the bound of spec section "Quantization"), for radii up to max_radius.
double ellipsoid_error_bound(const Frame& frame, double max_radius);

// A point record as integers, before bit packing.
struct QuantizedPoint {
    std::array<uint32_t, 3> position{};
    std::array<uint32_t, 2> normal{};
    std::array<uint32_t, 2> texcoord{};
    std::array<uint32_t, 4> color{};
};

QuantizedPoint quantize_point(const SurfacePoint& p, const StreamInfo& info, const ObjectInfo& object);
SurfacePoint dequantize_point(const QuantizedPoint& q, const StreamInfo& info, const ObjectInfo& object);

// Octahedral normal encoding at `bits` per component (the unit vector n -> two integers).
std::array<uint32_t, 2> encode_octahedral(const std::array<float, 3>& n, int bits);
std::array<float, 3> decode_octahedral(const std::array<uint32_t, 2>& q, int bits);

}  // namespace ellicast

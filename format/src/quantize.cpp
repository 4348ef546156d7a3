// Quantization of ellipsoids and points, and the error bounds the spec states for them.
#include "ellicast/format.h"

#include "bytes.h"

#include <algorithm>
#include <cmath>

namespace ellicast {

using namespace detail;

namespace {

constexpr int kCenterBits = 15;
constexpr int kRadiusBits = 13;
constexpr int kRotationBits = 14;
constexpr uint32_t kCenterMax = (1u << kCenterBits) - 1;      // 32767
constexpr uint32_t kRadiusMax = (1u << kRadiusBits) - 1;      // 8191
constexpr uint32_t kRotationMax = (1u << kRotationBits) - 1;  // 16383
constexpr double kSqrtHalf = 0.70710678118654752440;

uint32_t max_value(int bits) { return bits >= 32 ? 0xFFFFFFFFu : (1u << bits) - 1u; }

// Nearest integer of x in [0, max]; NaN goes to 0.
uint32_t quantize_unit(double x, uint32_t max) {
    if (!(x > 0)) return 0;
    double v = std::round(x * max);
    return v >= max ? max : static_cast<uint32_t>(v);
}

double octahedral_sign(double v) { return v < 0 ? -1.0 : 1.0; }

// The point of the octahedral square [-1,1]^2 for a unit vector.
void octahedral_square(const std::array<float, 3>& n, double& u, double& v) {
    double x = n[0], y = n[1], z = n[2];
    double l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
    if (!(l1 > 0) || !std::isfinite(l1)) {
        u = 0, v = 0;  // no direction: encode +Z
        return;
    }
    x /= l1, y /= l1, z /= l1;
    if (z < 0) {
        double ox = x;
        x = (1 - std::fabs(y)) * octahedral_sign(ox);
        y = (1 - std::fabs(ox)) * octahedral_sign(y);
    }
    u = x, v = y;
}

// The decoded unit vector of an octahedral grid point, in double precision (decode_octahedral
// rounds it to float; the encoder compares candidates before that rounding, which at 12 bits and
// more is as large as the differences it compares).
void octahedral_unit(const std::array<uint32_t, 2>& q, int bits, double out[3]) {
    const double max = max_value(bits);
    double x = std::min<double>(q[0], max) / max * 2 - 1;
    double y = std::min<double>(q[1], max) / max * 2 - 1;
    double z = 1 - std::fabs(x) - std::fabs(y);
    if (z < 0) {
        double ox = x;
        x = (1 - std::fabs(y)) * octahedral_sign(ox);
        y = (1 - std::fabs(ox)) * octahedral_sign(y);
    }
    double len = std::sqrt(x * x + y * y + z * z);
    out[0] = x / len, out[1] = y / len, out[2] = z / len;
}

}  // namespace

// ------------------------------------------------------------------------------------------
// Ellipsoids

QuantizedEllipsoid quantize_ellipsoid(const Ellipsoid& e, const Frame& frame) {
    QuantizedEllipsoid q;
    const double s = frame.scale;
    for (int i = 0; i < 3; ++i) {
        q.center[i] = static_cast<uint16_t>(quantize_unit((e.center[i] - frame.origin[i]) / s, kCenterMax));
        q.radii[i] = static_cast<uint16_t>(quantize_unit(e.radii[i] / s, kRadiusMax));
    }
    double c[4] = {e.rotation[0], e.rotation[1], e.rotation[2], e.rotation[3]};
    double norm = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
    if (!(norm > 0) || !std::isfinite(norm)) c[0] = 1, c[1] = c[2] = c[3] = 0, norm = 1;
    int largest = 0;
    for (int i = 1; i < 4; ++i)
        if (std::fabs(c[i]) > std::fabs(c[largest])) largest = i;
    // q and -q are the same rotation: make the dropped component positive.
    double sign = c[largest] < 0 ? -1.0 : 1.0;
    q.largest = static_cast<uint8_t>(largest);
    for (int i = 0, k = 0; i < 4; ++i) {
        if (i == largest) continue;
        double v = sign * c[i] / norm;  // in [-1/sqrt2, 1/sqrt2]
        q.rotation[k++] = static_cast<uint16_t>(quantize_unit((v / kSqrtHalf + 1) * 0.5, kRotationMax));
    }
    return q;
}

Ellipsoid dequantize_ellipsoid(const QuantizedEllipsoid& q, const Frame& frame) {
    Ellipsoid e;
    const double s = frame.scale;
    for (int i = 0; i < 3; ++i) {
        e.center[i] = static_cast<float>(frame.origin[i] + (q.center[i] & kCenterMax) * s / kCenterMax);
        e.radii[i] = static_cast<float>((q.radii[i] & kRadiusMax) * s / kRadiusMax);
    }
    double c[4];
    double sum = 0;
    int largest = q.largest & 3;
    for (int i = 0, k = 0; i < 4; ++i) {
        if (i == largest) continue;
        double v = ((q.rotation[k++] & kRotationMax) * 2.0 / kRotationMax - 1.0) * kSqrtHalf;
        c[i] = v;
        sum += v * v;
    }
    c[largest] = std::sqrt(std::max(0.0, 1.0 - sum));
    double norm = std::sqrt(sum + c[largest] * c[largest]);  // 1 unless the three were not a valid encoding
    for (int i = 0; i < 4; ++i) e.rotation[i] = static_cast<float>(c[i] / norm);
    return e;
}

void pack_ellipsoid(const QuantizedEllipsoid& q, uint8_t out[kEllipsoidBytes]) {
    std::vector<uint8_t> bytes;
    bytes.reserve(kEllipsoidBytes);
    BitWriter w(bytes);
    for (int i = 0; i < 3; ++i) w.put(q.center[i], kCenterBits);
    for (int i = 0; i < 3; ++i) w.put(q.radii[i], kRadiusBits);
    w.put(q.largest, 2);
    for (int i = 0; i < 3; ++i) w.put(q.rotation[i], kRotationBits);
    std::copy(bytes.begin(), bytes.end(), out);
}

QuantizedEllipsoid unpack_ellipsoid(const uint8_t in[kEllipsoidBytes]) {
    BitReader r({in, kEllipsoidBytes});
    QuantizedEllipsoid q;
    for (int i = 0; i < 3; ++i) q.center[i] = static_cast<uint16_t>(r.get(kCenterBits));
    for (int i = 0; i < 3; ++i) q.radii[i] = static_cast<uint16_t>(r.get(kRadiusBits));
    q.largest = static_cast<uint8_t>(r.get(2));
    for (int i = 0; i < 3; ++i) q.rotation[i] = static_cast<uint16_t>(r.get(kRotationBits));
    return q;
}

double ellipsoid_error_bound(const Frame& frame, double max_radius) {
    // |p - p'| <= |dc| + max|dr| + ||R - R'|| * (r + dr), for p = c + R diag(r) u, |u| = 1.
    const double s = frame.scale;
    const double center = std::sqrt(3.0) * s / (2.0 * kCenterMax);
    const double radius = s / (2.0 * kRadiusMax);
    // Each stored quaternion component is off by at most e; the recomputed largest one (>= 1/2) by
    // at most 3e; so |q - q'| <= sqrt(12) e, and ||R - R'|| <= 2 |q - q'| (plus rounding slack).
    const double e = 0.5 * (2.0 * kSqrtHalf) / kRotationMax;
    const double rotation = 2.0 * std::sqrt(12.0) * e * 1.001;
    return center + radius + rotation * (max_radius + radius);
}

// ------------------------------------------------------------------------------------------
// Points

std::array<uint32_t, 2> encode_octahedral(const std::array<float, 3>& n, int bits) {
    const uint32_t max = max_value(bits);
    double u, v;
    octahedral_square(n, u, v);
    // Of the four grid points around (u, v), keep the one that decodes closest to n.
    double fu = (u + 1) * 0.5 * max, fv = (v + 1) * 0.5 * max;
    std::array<uint32_t, 2> best{quantize_unit((u + 1) * 0.5, max), quantize_unit((v + 1) * 0.5, max)};
    double len = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    if (!(len > 0) || !std::isfinite(len)) return best;
    const double nx = n[0] / len, ny = n[1] / len, nz = n[2] / len;
    double best_distance = 5;
    for (int du = 0; du < 2; ++du)
        for (int dv = 0; dv < 2; ++dv) {
            double cu = std::clamp(std::floor(fu) + du, 0.0, double(max));
            double cv = std::clamp(std::floor(fv) + dv, 0.0, double(max));
            std::array<uint32_t, 2> cand{static_cast<uint32_t>(cu), static_cast<uint32_t>(cv)};
            double d[3];
            octahedral_unit(cand, bits, d);
            double distance = (d[0] - nx) * (d[0] - nx) + (d[1] - ny) * (d[1] - ny) + (d[2] - nz) * (d[2] - nz);
            if (distance < best_distance) best_distance = distance, best = cand;
        }
    return best;
}

std::array<float, 3> decode_octahedral(const std::array<uint32_t, 2>& q, int bits) {
    double d[3];
    octahedral_unit(q, bits, d);
    return {static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2])};
}

QuantizedPoint quantize_point(const SurfacePoint& p, const StreamInfo& info, const ObjectInfo& object) {
    QuantizedPoint q;
    const uint32_t pmax = max_value(info.position_bits);
    for (int i = 0; i < 3; ++i)
        q.position[i] = quantize_unit((p.position[i] - object.frame.origin[i]) / object.frame.scale, pmax);
    if (object.has(kAttrNormal)) q.normal = encode_octahedral(p.normal, info.normal_bits);
    if (object.has(kAttrTexcoord)) {
        const uint32_t tmax = max_value(info.texcoord_bits);
        for (int i = 0; i < 2; ++i) {
            double s = object.texcoord_scale[i];
            q.texcoord[i] = s > 0 ? quantize_unit((p.texcoord[i] - object.texcoord_origin[i]) / s, tmax) : 0;
        }
    }
    const int channels = object.color_channels();
    const uint32_t cmax = max_value(info.color_bits);
    for (int i = 0; i < channels; ++i) q.color[i] = quantize_unit(p.color[i], cmax);
    return q;
}

SurfacePoint dequantize_point(const QuantizedPoint& q, const StreamInfo& info, const ObjectInfo& object) {
    SurfacePoint p;
    const double pmax = max_value(info.position_bits);
    for (int i = 0; i < 3; ++i)
        p.position[i] = static_cast<float>(object.frame.origin[i] +
                                           std::min<double>(q.position[i], pmax) / pmax * object.frame.scale);
    if (object.has(kAttrNormal)) p.normal = decode_octahedral(q.normal, info.normal_bits);
    if (object.has(kAttrTexcoord)) {
        const double tmax = max_value(info.texcoord_bits);
        for (int i = 0; i < 2; ++i)
            p.texcoord[i] = static_cast<float>(object.texcoord_origin[i] +
                                               std::min<double>(q.texcoord[i], tmax) / tmax * object.texcoord_scale[i]);
    }
    const int channels = object.color_channels();
    const double cmax = max_value(info.color_bits);
    for (int i = 0; i < channels; ++i) p.color[i] = static_cast<float>(std::min<double>(q.color[i], cmax) / cmax);
    if (channels == 3) p.color[3] = 1;
    return p;
}

}  // namespace ellicast

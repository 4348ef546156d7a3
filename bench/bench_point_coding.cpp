// Issue 14, measurement only: how many bytes per point would candidate codings of the POINTS
// payload need, each packet coded on its own (it may use the stream info, and what we count as
// added to it)? Nothing here changes the format: the stream is made exactly as `ellicast encode`
// makes it (load_asset + encode_asset, default EncodeOptions, repair_ratio = 0), its POINTS packets
// are parsed back, and their quantized points are coded again by the candidates below. Every coder
// is decoded back and compared with its input (abort on any difference).
//
//   (a) today's bit packing: the POINTS packets as they are (24 bytes header/CRC + 8 bytes batch header)
//   (b) points sorted in Morton order, a per-packet octree from the full 14-bit cube down to the
//       points, coded with an adaptive binary range coder (LZMA-style, integer arithmetic): 8
//       occupancy bits per node (contexts: depth, occupied children so far), a "single position"
//       flag per node after which the remaining bits are sent directly, a duplicate count per leaf
//   (c) (b) plus a coarse occupancy map (the occupied cells of a 2^L grid, L = 4..7) sent once in the
//       stream info: the octree's top L levels only consider children the map says are occupied,
//       and the first two direct levels below L use the map's face neighbours as context
//   (c+) (c) with the initial probability of every context trained on the whole object and sent in
//       the stream info (1 byte per context, counted with the map)
//   (c++) (c+) with the direct bits below L coded in contexts from the map's local plane (least
//       squares through the occupied cells within 2 cells): how much nearer the plane each half is
//   (d) normals (10-bit octahedral): residual against a prediction, coded adaptively. Predictions:
//       nn   = the nearest point already decoded in the packet;
//       pca  = plane through the map's occupied cells around the point (sign from the nearest
//              decoded normal, else away from the map's centroid, plus an adaptive flip bit);
//       cell = the mean normal of the point's map cell, sent in the stream info (12 bits per cell, counted)
//
// Two packings are reported for every coding: "same" = the packets' own batches (222 points at
// 14 bits), "fill" = consecutive points in stream order, as many as fit a 1,200-byte packet once
// coded (what a real format would do). Bytes per point always include 24 + 8 framing bytes per packet.
// For (b) and the best (c) variant it also prints where the bits go (information per point by
// syntax element, from the adaptive models), and (b) over the whole object as one payload (not a
// packet: what independence costs). Decode times are of the decoder alone, over every packet.
//
//   bench_point_coding [--samples DIR] [--only NAME] [--no-draco] [--no-computed-normals]
//
// With --mapped it measures instead what format 1.7 made of issue 14 (spec 23): the POINT_MAP +
// MAPPED_POINTS packets of every sample against its POINTS packets and Draco (bench/results/mapped_points.txt).
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/format.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

using namespace ellicast;
using Clock = std::chrono::steady_clock;

namespace {

#define CHECK(cond)                                                                          \
    do {                                                                                     \
        if (!(cond)) {                                                                       \
            std::fprintf(stderr, "bench_point_coding: check failed at line %d: %s\n", __LINE__, #cond); \
            std::abort();                                                                    \
        }                                                                                    \
    } while (0)

constexpr int kBits = 14;            // position bits (the default)
constexpr int kNormalBits = 10;      // normal bits (the default)
constexpr size_t kFraming = kPacketOverhead + 8;  // header + CRC + batch header (first_index, count, reserved)
constexpr size_t kPacket = kDefaultPacketSize;

// ---------------------------------------------------------------------------------------------
// Binary range coder (LZMA style, 32-bit range, carry propagation through a cached byte) with
// adaptive 15-bit probabilities whose adaptation rate slows down as a context is used.

constexpr int kProbBits = 15;
constexpr uint32_t kProbOne = 1u << kProbBits;
constexpr uint32_t kTop = 1u << 24;

struct BitModel {
    uint16_t p = kProbOne / 2;  // probability of a 0
    uint8_t n = 0;              // observations so far (saturating)
    void update(int bit) {
        static constexpr uint8_t kRate[] = {1, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5};
        int rate = n < sizeof(kRate) ? kRate[n] : (n < 40 ? 5 : 6);
        if (bit == 0)
            p = uint16_t(p + ((kProbOne - p) >> rate));
        else
            p = uint16_t(p - (p >> rate));
        p = uint16_t(std::clamp<uint32_t>(p, 31, kProbOne - 31));
        if (n < 255) ++n;
    }
};

class RangeEncoder {
public:
    void encode(uint32_t p0, int bit) {  // p0: probability of 0 in [1, kProbOne)
        uint32_t bound = (range_ >> kProbBits) * p0;
        if (bit == 0) {
            range_ = bound;
        } else {
            low_ += bound;
            range_ -= bound;
        }
        while (range_ < kTop) {
            range_ <<= 8;
            shift_low();
        }
    }
    void bit(BitModel& m, int bit) {
        encode(m.p, bit);
        m.update(bit);
    }
    // v uniform in [0, k): a chain of static binary decisions "v == j" with P = 1 / (k - j).
    void uniform(uint32_t v, uint32_t k) {
        for (uint32_t j = 0; j + 1 < k; ++j) {
            uint32_t p_is = std::max<uint32_t>(1, kProbOne / (k - j));  // probability of "v == j" = bit 0
            encode(p_is, v == j ? 0 : 1);
            if (v == j) return;
        }
    }
    void bypass(uint32_t value, int bits) {
        for (int i = bits - 1; i >= 0; --i) encode(kProbOne / 2, (value >> i) & 1);
    }
    // Ends the stream with the fewest bytes: low moves to the value of [low, low + range) with the
    // most trailing zero bits; trailing zero bytes are dropped (the decoder reads zeros past the end).
    std::vector<uint8_t> finish() {
        for (int k = 32; k >= 0; --k) {
            uint64_t m = (uint64_t(1) << k) - 1;
            uint64_t v = (low_ + m) & ~m;
            if (v <= low_ + range_ - 1) {
                low_ = v;
                break;
            }
        }
        for (int i = 0; i < 5; ++i) shift_low();
        CHECK(!out_.empty() && out_[0] == 0);  // the first byte is always 0: not sent
        out_.erase(out_.begin());
        while (!out_.empty() && out_.back() == 0) out_.pop_back();
        return std::move(out_);
    }

private:
    void shift_low() {
        if (uint32_t(low_) < 0xFF000000u || (low_ >> 32) != 0) {
            uint8_t carry = uint8_t(low_ >> 32);
            uint8_t temp = cache_;
            do {
                out_.push_back(uint8_t(temp + carry));
                temp = 0xFF;
            } while (--cache_size_ != 0);
            cache_ = uint8_t(low_ >> 24);
        }
        ++cache_size_;
        low_ = (low_ & 0x00FFFFFFu) << 8;
    }
    uint64_t low_ = 0;
    uint32_t range_ = 0xFFFFFFFFu;
    uint8_t cache_ = 0;
    uint64_t cache_size_ = 1;
    std::vector<uint8_t> out_;
};

class RangeDecoder {
public:
    RangeDecoder(const uint8_t* data, size_t size) : data_(data), size_(size) {
        for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | next();
    }
    int decode(uint32_t p0) {
        uint32_t bound = (range_ >> kProbBits) * p0;
        int bit;
        if (code_ < bound) {
            range_ = bound;
            bit = 0;
        } else {
            code_ -= bound;
            range_ -= bound;
            bit = 1;
        }
        while (range_ < kTop) {
            range_ <<= 8;
            code_ = (code_ << 8) | next();
        }
        return bit;
    }
    int bit(BitModel& m) {
        int b = decode(m.p);
        m.update(b);
        return b;
    }
    uint32_t uniform(uint32_t k) {
        for (uint32_t j = 0; j + 1 < k; ++j) {
            uint32_t p_is = std::max<uint32_t>(1, kProbOne / (k - j));
            if (decode(p_is) == 0) return j;
        }
        return k - 1;
    }
    uint32_t bypass(int bits) {
        uint32_t v = 0;
        for (int i = 0; i < bits; ++i) v = (v << 1) | uint32_t(decode(kProbOne / 2));
        return v;
    }

private:
    uint8_t next() { return pos_ < size_ ? data_[pos_++] : 0; }
    const uint8_t* data_;
    size_t size_, pos_ = 0;
    uint32_t code_ = 0, range_ = 0xFFFFFFFFu;
};

// ---------------------------------------------------------------------------------------------
// Contexts: one flat table, so that a trained initial probability can be given to each.

namespace ctx {
constexpr int kOcc = 0;                           // [depth 0..13][occupied so far 0..2]
constexpr int kSingle = kOcc + 14 * 3;            // [depth 0..13]
constexpr int kDirect = kSingle + 14;             // [remaining levels 0..13][axis]
constexpr int kNbr1 = kDirect + 14 * 3;           // [axis][minus neighbour][plus neighbour]
constexpr int kNbr2 = kNbr1 + 12;                 // [axis][minus][plus][bit one level up]
constexpr int kDup = kNbr2 + 24;                  // [min(j, 2)]
constexpr int kNormFirst = kDup + 3;              // normals from here
constexpr int kNz = kNormFirst;                   // [component][u class 0..3]
constexpr int kSign = kNz + 8;                    // [component]
constexpr int kClass = kSign + 2;                 // [component][u class 0..3][class bit 0..9]
constexpr int kFlip = kClass + 2 * 4 * 10;        // [oriented by a neighbour]
constexpr int kPlane = kFlip + 2;                 // [levels below L 0..5][distance bin 0..7]
constexpr int kCount = kPlane + 6 * 8;
}  // namespace ctx

struct Models {
    std::vector<BitModel> m;
    explicit Models(const std::vector<uint16_t>* priors) : m(ctx::kCount) {
        if (priors)
            for (int i = 0; i < ctx::kCount; ++i)
                if ((*priors)[i] != 0) {
                    m[i].p = (*priors)[i];
                    m[i].n = 8;  // start as if 8 bits had been seen: rate 4
                }
    }
};

using Stats = std::vector<std::array<uint64_t, 2>>;

std::vector<double>* g_cost = nullptr;  // when set: information (bits) spent per context

struct Enc {
    static constexpr bool kEnc = true;
    RangeEncoder rc;
    Models models;
    Stats* stats;
    Enc(const std::vector<uint16_t>* priors, Stats* s) : models(priors), stats(s) {}
    int bit(int c, int b) {
        if (stats) ++(*stats)[c][b];
        if (g_cost) {
            double p0 = double(models.m[c].p) / kProbOne;
            (*g_cost)[c] += -std::log2(b ? 1 - p0 : p0);
        }
        rc.bit(models.m[c], b);
        return b;
    }
    uint32_t uniform(uint32_t v, uint32_t k) {
        rc.uniform(v, k);
        return v;
    }
    uint32_t bypass(uint32_t v, int bits) {
        rc.bypass(v, bits);
        return v;
    }
};

struct Dec {
    static constexpr bool kEnc = false;
    RangeDecoder rc;
    Models models;
    Dec(const std::vector<uint8_t>& bytes, const std::vector<uint16_t>* priors)
        : rc(bytes.data(), bytes.size()), models(priors) {}
    int bit(int c, int) { return rc.bit(models.m[c]); }
    uint32_t uniform(uint32_t, uint32_t k) { return rc.uniform(k); }
    uint32_t bypass(uint32_t, int bits) { return rc.bypass(bits); }
};

// ---------------------------------------------------------------------------------------------
// Morton codes: child index at depth d is (x bit, y bit, z bit) of bit 13 - d.

uint64_t morton(const std::array<uint32_t, 3>& p) {
    uint64_t code = 0;
    for (int d = 0; d < kBits; ++d) {
        int b = kBits - 1 - d;
        code = (code << 3) | (((p[0] >> b) & 1) << 2) | (((p[1] >> b) & 1) << 1) | ((p[2] >> b) & 1);
    }
    return code;
}

std::array<uint32_t, 3> unmorton(uint64_t code, int levels) {
    std::array<uint32_t, 3> p{0, 0, 0};
    for (int d = 0; d < levels; ++d) {
        int shift = 3 * (levels - 1 - d);
        p[0] = (p[0] << 1) | uint32_t((code >> (shift + 2)) & 1);
        p[1] = (p[1] << 1) | uint32_t((code >> (shift + 1)) & 1);
        p[2] = (p[2] << 1) | uint32_t((code >> shift) & 1);
    }
    return p;
}

uint64_t morton_levels(const std::array<int64_t, 3>& p, int levels) {
    uint64_t code = 0;
    for (int d = 0; d < levels; ++d) {
        int b = levels - 1 - d;
        code = (code << 3) | (((p[0] >> b) & 1) << 2) | (((p[1] >> b) & 1) << 1) | ((p[2] >> b) & 1);
    }
    return code;
}

// ---------------------------------------------------------------------------------------------
// The coarse occupancy map (stream info): occupied cells of the 2^L grid, as Morton codes of L levels.

struct CoarseMap {
    int L = 0;  // 0: no map
    std::vector<std::unordered_set<uint64_t>> by_depth;  // [d]: occupied cells at depth d (1..L)
    std::unordered_map<uint64_t, std::array<uint32_t, 2>> cell_normal;  // level-L cell -> octahedral normal
    int cell_normal_bits = 6;
    std::array<double, 3> centroid{};
    size_t bytes = 0;         // the map, coded
    size_t normal_bytes = 0;  // the cell normals, if sent

    bool has(int d, uint64_t cell) const { return by_depth[d].count(cell) != 0; }
    bool has_xyz(int64_t x, int64_t y, int64_t z) const {
        const int64_t n = int64_t(1) << L;
        if (x < 0 || y < 0 || z < 0 || x >= n || y >= n || z >= n) return false;
        return has(L, morton_levels({x, y, z}, L));
    }
};

// Octree coding of the map's cells (depth 0 .. L), the same occupancy contexts as the packets.
template <class IO>
void code_map_node(IO& io, const CoarseMap& map, int d, uint64_t prefix, std::vector<uint64_t>& out) {
    if (d == map.L) {
        out.push_back(prefix);
        return;
    }
    int occupied = 0;
    for (int i = 0; i < 8; ++i) {
        uint64_t child = (prefix << 3) | uint64_t(i);
        int o;
        if (i == 7 && occupied == 0)
            o = 1;
        else
            o = io.bit(ctx::kOcc + d * 3 + std::min(occupied, 2), IO::kEnc ? int(map.has(d + 1, child)) : 0);
        if (o) {
            ++occupied;
            code_map_node(io, map, d + 1, child, out);
        }
    }
}

CoarseMap build_map(const std::vector<QuantizedPoint>& points, int L, bool with_normals) {
    CoarseMap map;
    map.L = L;
    map.by_depth.resize(L + 1);
    std::unordered_map<uint64_t, std::array<double, 3>> normal_sum;
    std::vector<uint64_t> cells;
    std::array<double, 3> sum{};
    for (const auto& p : points) {
        uint64_t c = morton(p.position) >> (3 * (kBits - L));
        if (map.by_depth[L].insert(c).second) cells.push_back(c);
        if (with_normals) {
            auto n = decode_octahedral(p.normal, kNormalBits);
            auto& s = normal_sum[c];
            for (int k = 0; k < 3; ++k) s[k] += n[k];
        }
    }
    for (int d = L - 1; d >= 1; --d)
        for (uint64_t c : map.by_depth[d + 1]) map.by_depth[d].insert(c >> 3);
    for (uint64_t c : cells) {
        auto xyz = unmorton(c, L);
        for (int k = 0; k < 3; ++k) sum[k] += xyz[k] + 0.5;
    }
    for (int k = 0; k < 3; ++k) map.centroid[k] = sum[k] / double(cells.size());
    // Code the map and check it decodes.
    Enc enc(nullptr, nullptr);
    std::vector<uint64_t> dummy;
    code_map_node(enc, map, 0, 0, dummy);
    std::vector<uint8_t> bytes = enc.rc.finish();
    map.bytes = bytes.size() + 2;  // + L and a version byte
    Dec dec(bytes, nullptr);
    std::vector<uint64_t> decoded;
    code_map_node(dec, map, 0, 0, decoded);  // map.has is not consulted when decoding
    std::sort(decoded.begin(), decoded.end());
    std::sort(cells.begin(), cells.end());
    CHECK(decoded == cells);
    if (with_normals) {
        for (auto& [c, s] : normal_sum) {
            double len = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
            std::array<float, 3> n{0, 0, 1};
            if (len > 1e-9) n = {float(s[0] / len), float(s[1] / len), float(s[2] / len)};
            map.cell_normal[c] = encode_octahedral(n, map.cell_normal_bits);
        }
        map.normal_bytes = (cells.size() * 2 * map.cell_normal_bits + 7) / 8;  // raw, in map order
    }
    return map;
}

// ---------------------------------------------------------------------------------------------
// A packet's points, coded

enum class NormalPredictor { None, Nearest, Pca, Cell };

struct Config {
    const CoarseMap* map = nullptr;  // null: (b)
    const std::vector<uint16_t>* priors = nullptr;
    NormalPredictor normals = NormalPredictor::None;
    bool plane_ctx = false;  // (c++): direct bits below L take their context from the map's local plane
};

// The plane through the occupied map cells within 2 cells of a cell (least squares), in 14-bit units.
struct Plane {
    bool valid = false;
    std::array<double, 3> point{}, normal{0, 0, 1};
    double distance(const std::array<double, 3>& q) const {
        return (q[0] - point[0]) * normal[0] + (q[1] - point[1]) * normal[1] + (q[2] - point[2]) * normal[2];
    }
};

Plane map_plane(const CoarseMap& map, const std::array<int64_t, 3>& c) {
    Plane pl;
    const double cell = double(1 << (kBits - map.L));
    Eigen::Vector3d mean(0, 0, 0);
    Eigen::Vector3d qs[125];
    int n = 0;
    for (int dz = -2; dz <= 2; ++dz)
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx)
                if (map.has_xyz(c[0] + dx, c[1] + dy, c[2] + dz)) {
                    qs[n] = Eigen::Vector3d(c[0] + dx + 0.5, c[1] + dy + 0.5, c[2] + dz + 0.5);
                    mean += qs[n++];
                }
    if (n < 3) return pl;
    mean /= double(n);
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (int i = 0; i < n; ++i) cov += (qs[i] - mean) * (qs[i] - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    Eigen::Vector3d nn = es.eigenvectors().col(0);
    if (!(nn.norm() > 0.5)) return pl;
    nn.normalize();
    pl.valid = true;
    for (int k = 0; k < 3; ++k) {
        pl.point[k] = mean[k] * cell;
        pl.normal[k] = nn[k];
    }
    return pl;
}

// A point of a packet as the coder sees it: Morton code of its position, its normal.
struct Item {
    uint64_t code = 0;
    std::array<uint32_t, 2> normal{};
    bool operator<(const Item& o) const {
        return code != o.code ? code < o.code : normal < o.normal;
    }
    bool operator==(const Item& o) const = default;
};

template <class IO>
struct PacketCoder {
    IO& io;
    const Config& cfg;
    std::vector<uint64_t> out;  // decoded codes (decoder), in Morton order; also filled by the encoder
    int L() const { return cfg.map ? cfg.map->L : 0; }

    void leaf(uint64_t code, size_t n) {
        // n copies of one position: "one more?" bits
        size_t k = 1;
        for (;;) {
            int more = io.bit(ctx::kDup + int(std::min<size_t>(k - 1, 2)), IO::kEnc ? int(k < n) : 0);
            if (!more) break;
            ++k;
        }
        for (size_t i = 0; i < k; ++i) out.push_back(code);
    }

    // The remaining 3 * (14 - d) bits of one position (the encoder's `code`; the decoder passes 0
    // and gets the decoded code back). `prefix` is the node's path, known to both sides.
    uint64_t direct(int d, uint64_t prefix, uint64_t code) {
        std::array<int, 3> nm{0, 0, 0}, np{0, 0, 0};
        const int l = L();
        Plane plane;
        if (l > 0 && d >= l) {
            uint64_t cell_code = prefix >> (3 * (d - l));
            auto c = unmorton(cell_code, l);
            if (cfg.plane_ctx) {
                plane = map_plane(*cfg.map, {int64_t(c[0]), int64_t(c[1]), int64_t(c[2])});
            } else {
                for (int a = 0; a < 3; ++a) {
                    std::array<int64_t, 3> lo{c[0], c[1], c[2]}, hi{c[0], c[1], c[2]};
                    lo[a] -= 1;
                    hi[a] += 1;
                    nm[a] = cfg.map->has_xyz(lo[0], lo[1], lo[2]);
                    np[a] = cfg.map->has_xyz(hi[0], hi[1], hi[2]);
                }
            }
        }
        // the box still possible, in 14-bit units: [lo, lo + size) per axis
        auto xyz = unmorton(prefix, d);
        std::array<double, 3> lo;
        std::array<double, 3> size;
        for (int a = 0; a < 3; ++a) {
            size[a] = double(1 << (kBits - d));
            lo[a] = double(xyz[a]) * size[a];
        }
        std::array<int, 3> prev{0, 0, 0};
        for (int lv = d; lv < kBits; ++lv) {
            int child = 0;
            for (int a = 0; a < 3; ++a) {
                int shift = 3 * (kBits - 1 - lv) + (2 - a);
                int b = IO::kEnc ? int((code >> shift) & 1) : 0;
                int c;
                if (l > 0 && cfg.plane_ctx) {
                    // distances to the map's local plane of the centres of the two halves along a
                    std::array<double, 3> c0, c1;
                    for (int k = 0; k < 3; ++k) c0[k] = c1[k] = lo[k] + size[k] / 2;
                    c0[a] = lo[a] + size[a] / 4;
                    c1[a] = lo[a] + 3 * size[a] / 4;
                    double f0 = std::fabs(plane.distance(c0)), f1 = std::fabs(plane.distance(c1));
                    double t = (f1 - f0) / size[a];  // > 0: the lower half is nearer the plane
                    int bin = t < -0.6 ? 0 : t < -0.3 ? 1 : t < -0.1 ? 2 : t <= 0.1 ? 3 : t <= 0.3 ? 4 : t <= 0.6 ? 5 : 6;
                    if (!plane.valid) bin = 7;
                    c = ctx::kPlane + std::min(lv - l, 5) * 8 + bin;
                } else if (l > 0 && lv == l)
                    c = ctx::kNbr1 + a * 4 + nm[a] * 2 + np[a];
                else if (l > 0 && lv == l + 1)
                    c = ctx::kNbr2 + a * 8 + nm[a] * 4 + np[a] * 2 + prev[a];
                else
                    c = ctx::kDirect + (kBits - 1 - lv) * 3 + a;
                b = io.bit(c, b);
                prev[a] = b;
                child |= b << (2 - a);
                size[a] /= 2;
                if (b) lo[a] += size[a];
            }
            prefix = (prefix << 3) | uint64_t(child);
        }
        return prefix;
    }

    // p[0..n): sorted codes with this prefix (encoder); n unused by the decoder.
    void node(int d, uint64_t prefix, const uint64_t* p, size_t n) {
        if (d == kBits) {
            leaf(prefix, n);
            return;
        }
        const int l = L();
        if (d >= l) {
            int single = io.bit(ctx::kSingle + d, IO::kEnc ? int(p[0] == p[n - 1]) : 0);
            if (single) {
                uint64_t full = direct(d, prefix, IO::kEnc ? p[0] : 0);
                if (IO::kEnc) CHECK(full == p[0]);
                leaf(full, n);
                return;
            }
        }
        std::array<int, 8> candidates;
        int nc = 0;
        for (int i = 0; i < 8; ++i) {
            uint64_t child = (prefix << 3) | uint64_t(i);
            if (d < l && !cfg.map->has(d + 1, child)) continue;
            candidates[nc++] = i;
        }
        int occupied = 0;
        size_t start = 0;
        const int shift = 3 * (kBits - 1 - d);
        for (int ci = 0; ci < nc; ++ci) {
            int i = candidates[ci];
            size_t end = start;
            if (IO::kEnc)
                while (end < n && int((p[end] >> shift) & 7) == i) ++end;
            if (IO::kEnc) CHECK(end == start || int((p[start] >> shift) & 7) == i);
            int o;
            if (ci == nc - 1 && occupied == 0)
                o = 1;
            else
                o = io.bit(ctx::kOcc + d * 3 + std::min(occupied, 2), IO::kEnc ? int(end > start) : 0);
            if (o) {
                ++occupied;
                node(d + 1, (prefix << 3) | uint64_t(i), IO::kEnc ? p + start : nullptr, end - start);
            }
            start = end;
        }
        if (IO::kEnc) CHECK(start == n);  // every point fell in a candidate (the map covers them)
    }
};

// ---- normals

std::array<double, 3> to_xyz(uint64_t code) {
    auto p = unmorton(code, kBits);
    return {double(p[0]), double(p[1]), double(p[2])};
}

double dist2(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
    return s;
}

int wrap(int r) {  // into [-512, 511] for 10-bit components
    const int m = 1 << kNormalBits;
    r = ((r % m) + m) % m;
    return r >= m / 2 ? r - m : r;
}

int u_class(int r) {
    int a = std::abs(r);
    return a == 0 ? 0 : a <= 2 ? 1 : a <= 8 ? 2 : 3;
}

template <class IO>
int code_residual(IO& io, int comp, int r, int uc) {
    int nz = io.bit(ctx::kNz + comp * 4 + uc, IO::kEnc ? int(r != 0) : 0);
    if (!nz) return 0;
    int neg = io.bit(ctx::kSign + comp, IO::kEnc ? int(r < 0) : 0);
    uint32_t m = IO::kEnc ? uint32_t(std::abs(r) - 1) : 0;  // 0..511
    int k = 0;
    if (IO::kEnc) {
        while ((m + 1) >> (k + 1)) ++k;
    }
    int cls = 0;
    for (;;) {
        if (cls == 9) break;
        int more = io.bit(ctx::kClass + (comp * 4 + uc) * 10 + cls, IO::kEnc ? int(cls < k) : 0);
        if (!more) break;
        ++cls;
    }
    uint32_t mant = io.bypass(IO::kEnc ? (m + 1) - (1u << cls) : 0, cls);
    int mag = int((1u << cls) + mant);  // = m + 1
    return neg ? -mag : mag;
}

// The prediction of normal i from the decoded positions, the normals decoded before it and the map.
// Returns false when there is none (the first point with the nearest-neighbour predictor).
bool predict_normal(const Config& cfg, const std::vector<std::array<double, 3>>& pos,
                    const std::vector<std::array<uint32_t, 2>>& normals, size_t i, std::array<float, 3>& pred,
                    int& flip_ctx, bool& needs_flip_bit) {
    needs_flip_bit = false;
    // nearest decoded point
    size_t best = SIZE_MAX;
    double bd = 1e300;
    for (size_t j = 0; j < i; ++j) {
        double dd = dist2(pos[i], pos[j]);
        if (dd < bd) bd = dd, best = j;
    }
    std::array<float, 3> nn{0, 0, 1};
    if (best != SIZE_MAX) nn = decode_octahedral(normals[best], kNormalBits);
    if (cfg.normals == NormalPredictor::Nearest) {
        pred = nn;
        return best != SIZE_MAX;
    }
    const CoarseMap& map = *cfg.map;
    const int L = map.L;
    const double cell = double(1 << (kBits - L));
    std::array<int64_t, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = int64_t(pos[i][k] / cell);
    if (cfg.normals == NormalPredictor::Cell) {
        auto it = map.cell_normal.find(morton_levels(c, L));
        CHECK(it != map.cell_normal.end());
        pred = decode_octahedral(it->second, map.cell_normal_bits);
        return true;
    }
    // PCA of the occupied cells within 2 cells
    Eigen::Vector3d mean(0, 0, 0);
    std::vector<Eigen::Vector3d> pts;
    for (int dz = -2; dz <= 2; ++dz)
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx)
                if (map.has_xyz(c[0] + dx, c[1] + dy, c[2] + dz)) {
                    Eigen::Vector3d q(c[0] + dx + 0.5, c[1] + dy + 0.5, c[2] + dz + 0.5);
                    pts.push_back(q);
                    mean += q;
                }
    mean /= double(pts.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (auto& q : pts) cov += (q - mean) * (q - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    Eigen::Vector3d n = es.eigenvectors().col(0);
    if (!(n.norm() > 0.5)) n = Eigen::Vector3d(0, 0, 1);
    n.normalize();
    double sgn;
    if (best != SIZE_MAX) {
        sgn = n.dot(Eigen::Vector3d(nn[0], nn[1], nn[2]));
        flip_ctx = 1;
    } else {
        Eigen::Vector3d out(c[0] + 0.5 - map.centroid[0], c[1] + 0.5 - map.centroid[1], c[2] + 0.5 - map.centroid[2]);
        sgn = n.dot(out);
        flip_ctx = 0;
    }
    if (sgn < 0) n = -n;
    pred = {float(n[0]), float(n[1]), float(n[2])};
    needs_flip_bit = true;
    return true;
}

template <class IO>
void code_normals(IO& io, const Config& cfg, const std::vector<uint64_t>& codes, std::vector<std::array<uint32_t, 2>>& normals) {
    std::vector<std::array<double, 3>> pos(codes.size());
    for (size_t i = 0; i < codes.size(); ++i) pos[i] = to_xyz(codes[i]);
    const uint32_t mask = (1u << kNormalBits) - 1;
    for (size_t i = 0; i < codes.size(); ++i) {
        std::array<float, 3> pred;
        int flip_ctx = 0;
        bool flip_bit = false;
        if (!predict_normal(cfg, pos, normals, i, pred, flip_ctx, flip_bit)) {
            uint32_t u = io.bypass(IO::kEnc ? normals[i][0] : 0, kNormalBits);
            uint32_t v = io.bypass(IO::kEnc ? normals[i][1] : 0, kNormalBits);
            normals[i] = {u, v};
            continue;
        }
        if (flip_bit) {
            int flip = 0;
            if (IO::kEnc) {
                auto n = decode_octahedral(normals[i], kNormalBits);
                flip = n[0] * pred[0] + n[1] * pred[1] + n[2] * pred[2] < 0;
            }
            flip = io.bit(ctx::kFlip + flip_ctx, flip);
            if (flip) pred = {-pred[0], -pred[1], -pred[2]};
        }
        auto pq = encode_octahedral(pred, kNormalBits);
        int ru = IO::kEnc ? wrap(int(normals[i][0]) - int(pq[0])) : 0;
        int rv = IO::kEnc ? wrap(int(normals[i][1]) - int(pq[1])) : 0;
        ru = code_residual(io, 0, ru, 0);
        rv = code_residual(io, 1, rv, u_class(ru));
        normals[i] = {uint32_t(int(pq[0]) + ru) & mask, uint32_t(int(pq[1]) + rv) & mask};
    }
}

// Codes one packet's items; returns the payload (without framing).
std::vector<uint8_t> encode_packet(const Config& cfg, std::vector<Item> items, Stats* stats = nullptr) {
    std::sort(items.begin(), items.end());
    std::vector<uint64_t> codes(items.size());
    for (size_t i = 0; i < items.size(); ++i) codes[i] = items[i].code;
    Enc enc(cfg.priors, stats);
    PacketCoder<Enc> pc{enc, cfg, {}};
    pc.node(0, 0, codes.data(), codes.size());
    CHECK(pc.out == codes);
    if (cfg.normals != NormalPredictor::None) {
        std::vector<std::array<uint32_t, 2>> normals(items.size());
        for (size_t i = 0; i < items.size(); ++i) normals[i] = items[i].normal;
        code_normals(enc, cfg, codes, normals);
    }
    return enc.rc.finish();
}

std::vector<Item> decode_packet(const Config& cfg, const std::vector<uint8_t>& bytes) {
    Dec dec(bytes, cfg.priors);
    PacketCoder<Dec> pc{dec, cfg, {}};
    pc.node(0, 0, nullptr, 0);
    std::vector<Item> items(pc.out.size());
    for (size_t i = 0; i < items.size(); ++i) items[i].code = pc.out[i];
    if (cfg.normals != NormalPredictor::None) {
        std::vector<std::array<uint32_t, 2>> normals(items.size());
        code_normals(dec, cfg, pc.out, normals);
        for (size_t i = 0; i < items.size(); ++i) items[i].normal = normals[i];
    }
    return items;
}

// ---------------------------------------------------------------------------------------------
// Packings

struct Packing {
    size_t packets = 0;
    size_t bytes = 0;   // all framing included
    size_t points = 0;
    double bpp() const { return points ? double(bytes) / double(points) : 0; }
};

struct CodedPacket {
    std::vector<uint8_t> payload;
    std::vector<Item> items;
};

// Codes every batch as it is and checks the round trip.
Packing code_same(const Config& cfg, const std::vector<std::vector<Item>>& batches, std::vector<CodedPacket>* keep,
                  Stats* stats = nullptr) {
    Packing r;
    for (const auto& b0 : batches) {
        std::vector<Item> b = b0;
        if (cfg.normals == NormalPredictor::None)
            for (auto& it : b) it.normal = {0, 0};
        std::vector<uint8_t> payload = encode_packet(cfg, b, stats);
        std::vector<Item> back = decode_packet(cfg, payload);
        std::vector<Item> sorted = b;
        std::sort(sorted.begin(), sorted.end());
        if (back != sorted) {
            std::fprintf(stderr, "round trip: %zu items back of %zu\n", back.size(), sorted.size());
            for (size_t i = 0; i < std::min(back.size(), sorted.size()); ++i)
                if (!(back[i] == sorted[i])) {
                    std::fprintf(stderr, "first difference at %zu: code %llx/%llx normal %u,%u / %u,%u\n", i,
                                 (unsigned long long)back[i].code, (unsigned long long)sorted[i].code, back[i].normal[0],
                                 back[i].normal[1], sorted[i].normal[0], sorted[i].normal[1]);
                    break;
                }
        }
        CHECK(back == sorted);
        r.packets += 1;
        r.points += b.size();
        r.bytes += kFraming + payload.size();
        if (keep) keep->push_back({std::move(payload), std::move(sorted)});
    }
    return r;
}

// Consecutive items in stream order, as many as fit `packet` bytes once coded.
Packing code_fill(const Config& cfg, const std::vector<Item>& stream0, std::vector<CodedPacket>* keep) {
    Packing r;
    std::vector<Item> stream = stream0;
    if (cfg.normals == NormalPredictor::None)
        for (auto& it : stream) it.normal = {0, 0};
    const size_t budget = kPacket - kFraming;
    size_t at = 0;
    while (at < stream.size()) {
        auto fits = [&](size_t n, std::vector<uint8_t>* payload) {
            std::vector<Item> items(stream.begin() + at, stream.begin() + at + n);
            std::vector<uint8_t> p = encode_packet(cfg, std::move(items));
            bool ok = p.size() <= budget;
            if (payload) *payload = std::move(p);
            return ok;
        };
        size_t lo = 1, hi = std::min<size_t>(stream.size() - at, 0xFFFF);
        CHECK(fits(1, nullptr));
        if (!fits(hi, nullptr)) {
            // largest n in [lo, hi) that fits: grow then bisect
            size_t step = 256;
            while (lo + step < hi && fits(lo + step, nullptr)) lo += step, step *= 2;
            hi = std::min(hi, lo + step);
            while (hi - lo > 1) {
                size_t mid = (lo + hi) / 2;
                if (fits(mid, nullptr))
                    lo = mid;
                else
                    hi = mid;
            }
        } else {
            lo = hi;
        }
        std::vector<uint8_t> payload;
        CHECK(fits(lo, &payload));
        std::vector<Item> sorted(stream.begin() + at, stream.begin() + at + lo);
        std::sort(sorted.begin(), sorted.end());
        CHECK(decode_packet(cfg, payload) == sorted);
        r.packets += 1;
        r.points += lo;
        r.bytes += kFraming + payload.size();
        if (keep) keep->push_back({std::move(payload), std::move(sorted)});
        at += lo;
    }
    return r;
}

// Trained initial probabilities (8 bits each, sent in the stream info): from a first pass.
std::vector<uint16_t> train_priors(const Config& cfg, const std::vector<std::vector<Item>>& batches, size_t& bytes) {
    Stats stats(ctx::kCount, {0, 0});
    code_same(cfg, batches, nullptr, &stats);
    std::vector<uint16_t> priors(ctx::kCount, 0);
    bytes = 0;
    for (int i = 0; i < ctx::kCount; ++i) {
        uint64_t n0 = stats[i][0], n1 = stats[i][1];
        if (n0 + n1 == 0) continue;
        uint32_t q = uint32_t(std::clamp<double>(std::round(256.0 * (n0 + 0.5) / (n0 + n1 + 1.0)), 1, 255));
        priors[i] = uint16_t(q << (kProbBits - 8));
        ++bytes;
    }
    bytes += (ctx::kCount + 7) / 8;  // which contexts have a prior
    return priors;
}

double time_decode(const Config& cfg, const std::vector<CodedPacket>& packets, int repeats) {
    size_t sink = 0;
    auto t0 = Clock::now();
    for (int r = 0; r < repeats; ++r)
        for (const auto& p : packets) sink += decode_packet(cfg, p.payload).size();
    double s = std::chrono::duration<double>(Clock::now() - t0).count();
    CHECK(sink > 0);
    return s / double(repeats * packets.size());
}

// Where the bits of the coded packets go, per point.
void print_breakdown(const Config& cfg, const std::vector<CodedPacket>& kept) {
    std::vector<double> cost(ctx::kCount, 0.0);
    g_cost = &cost;
    size_t points = 0, bytes = 0;
    for (const auto& p : kept) {
        std::vector<uint8_t> again = encode_packet(cfg, p.items);
        CHECK(again == p.payload);
        points += p.items.size();
        bytes += p.payload.size();
    }
    g_cost = nullptr;
    const int L = cfg.map ? cfg.map->L : 0;
    double top = 0, occ_below = 0, single = 0, direct = 0, dup = 0, normals = 0;
    for (int c = 0; c < ctx::kCount; ++c) {
        if (c >= ctx::kOcc && c < ctx::kSingle)
            ((c - ctx::kOcc) / 3 < L ? top : occ_below) += cost[c];
        else if (c >= ctx::kSingle && c < ctx::kDirect)
            single += cost[c];
        else if ((c >= ctx::kDirect && c < ctx::kDup) || (c >= ctx::kPlane && c < ctx::kPlane + 48))
            direct += cost[c];
        else if (c >= ctx::kDup && c < ctx::kNormFirst)
            dup += cost[c];
        else
            normals += cost[c];
    }
    const double n = double(points);
    std::printf("    bits per point: octree above L %.2f, occupancy below L %.2f, single flags %.2f, direct bits %.2f,\n"
                "                    duplicates %.2f; payload %.2f bits/pt (%.2f coded + %.2f coder end/rounding); framing %.2f\n",
                top / n, occ_below / n, single / n, direct / n, dup / n, 8.0 * bytes / n,
                (top + occ_below + single + direct + dup + normals) / n,
                8.0 * bytes / n - (top + occ_below + single + direct + dup + normals) / n,
                8.0 * kFraming * kept.size() / n);
}

// ---------------------------------------------------------------------------------------------
// Models and Draco

Mesh weld_positions(const Mesh& in) {
    Mesh m;
    m.name = in.name;
    std::map<std::array<float, 3>, uint32_t> index;
    std::vector<uint32_t> remap(in.positions.size());
    for (size_t i = 0; i < in.positions.size(); ++i) {
        auto [it, fresh] = index.emplace(in.positions[i], uint32_t(m.positions.size()));
        if (fresh) m.positions.push_back(in.positions[i]);
        remap[i] = it->second;
    }
    for (auto t : in.triangles) {
        std::array<uint32_t, 3> r{remap[t[0]], remap[t[1]], remap[t[2]]};
        if (r[0] != r[1] && r[1] != r[2] && r[0] != r[2]) m.triangles.push_back(r);
    }
    m.is_point_set = in.is_point_set;
    return m;
}

// Area-weighted vertex normals (for models without normals: what (d) would cost if they had them).
void compute_normals(Mesh& m) {
    std::vector<std::array<double, 3>> acc(m.positions.size(), {0, 0, 0});
    for (auto t : m.triangles) {
        auto& a = m.positions[t[0]];
        auto& b = m.positions[t[1]];
        auto& c = m.positions[t[2]];
        double e1[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
        double e2[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; ++k)
            for (int v = 0; v < 3; ++v) acc[t[v]][k] += n[k];
    }
    m.normals.resize(m.positions.size());
    for (size_t i = 0; i < acc.size(); ++i) {
        double l = std::sqrt(acc[i][0] * acc[i][0] + acc[i][1] * acc[i][1] + acc[i][2] * acc[i][2]);
        m.normals[i] = l > 0 ? std::array<float, 3>{float(acc[i][0] / l), float(acc[i][1] / l), float(acc[i][2] / l)}
                             : std::array<float, 3>{0, 0, 1};
    }
}

void write_ply(const std::string& path, const Mesh& m, bool normals) {
    FILE* f = std::fopen(path.c_str(), "w");
    CHECK(f);
    std::fprintf(f, "ply\nformat ascii 1.0\nelement vertex %zu\nproperty float x\nproperty float y\nproperty float z\n",
                 m.positions.size());
    if (normals) std::fprintf(f, "property float nx\nproperty float ny\nproperty float nz\n");
    std::fprintf(f, "element face %zu\nproperty list uchar int vertex_indices\nend_header\n", m.triangles.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        std::fprintf(f, "%.9g %.9g %.9g", m.positions[i][0], m.positions[i][1], m.positions[i][2]);
        if (normals) std::fprintf(f, " %.9g %.9g %.9g", m.normals[i][0], m.normals[i][1], m.normals[i][2]);
        std::fprintf(f, "\n");
    }
    for (auto t : m.triangles) std::fprintf(f, "3 %u %u %u\n", t[0], t[1], t[2]);
    std::fclose(f);
}

long draco_bytes(const std::string& ply, bool point_cloud, bool normals) {
    std::string out = ply + (point_cloud ? ".pc" : ".mesh") + ".drc";
    std::string cmd = "draco_encoder -i '" + ply + "' -o '" + out + "' -qp 14 -cl 7" + (normals ? " -qn 10" : "") +
                      (point_cloud ? " -point_cloud" : "") + " >/dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) return -1;
    std::error_code ec;
    auto size = std::filesystem::file_size(out, ec);
    std::filesystem::remove(out, ec);
    return ec ? -1 : long(size);
}

// ---------------------------------------------------------------------------------------------
// One model

struct StreamPoints {
    StreamInfo info;
    std::vector<std::vector<Item>> batches;  // the POINTS packets' points, object by object (one object here)
    std::vector<Item> stream;                // all points in stream (index) order
    std::vector<QuantizedPoint> quantized;
    size_t point_bytes = 0, point_packets = 0;
    bool normals = false;
    double encode_seconds = 0;
};

StreamPoints encode_model(const Mesh& mesh) {
    Asset asset;
    asset.objects.push_back(mesh);
    EncodeOptions options;
    options.repair_ratio = 0;
    options.point_map = false;  // the POINTS packets of format 1.0, which the candidates re-code
    EncodedAsset out;
    std::string error;
    auto t0 = Clock::now();
    CHECK(encode_asset(asset, options, 1, false, out, error));
    StreamPoints s;
    s.encode_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    s.info = out.encoded.info;
    CHECK(s.info.objects.size() == 1 && s.info.position_bits == kBits && s.info.normal_bits == kNormalBits);
    const ObjectInfo& object = s.info.objects[0];
    s.normals = object.has(kAttrNormal);
    std::map<uint32_t, PointBatch> batches;
    for (const auto& bytes : out.packets) {
        PacketView v;
        CHECK(parse_packet(bytes, v) == Error::Ok);
        if (v.header.type != uint8_t(PacketType::Points)) continue;
        PointBatch batch;
        CHECK(decode_points_payload(v.payload, s.info, object, batch) == Error::Ok);
        s.point_bytes += v.size;
        s.point_packets += 1;
        batches[batch.first_index] = std::move(batch);
    }
    CHECK(s.point_bytes == out.point_bytes);
    for (auto& [first, batch] : batches) {
        std::vector<Item> items;
        for (const auto& q : batch.points) {
            Item it;
            it.code = morton(q.position);
            if (s.normals) it.normal = q.normal;
            items.push_back(it);
            s.stream.push_back(it);
            s.quantized.push_back(q);
        }
        s.batches.push_back(std::move(items));
    }
    CHECK(s.stream.size() == object.point_count);
    return s;
}

struct Result {
    std::string name;
    size_t vertices = 0, points = 0, packets_a = 0;
    double a = 0;
    Packing b_same, b_fill;
    std::map<int, Packing> c_same, c_fill, cp_same, cp_fill, cpp_same, cpp_fill;
    std::map<int, size_t> prior_bytes_pp;
    bool best_plane = false;
    std::map<int, size_t> map_bytes, prior_bytes;
    double decode_us_best = 0, decode_us_b = 0, decode_us_a = 0, decode_us_cplus = 0, decode_us_cpp = 0;
    int best_L_cplus = 0, best_L_cpp = 0;
    double best_cplus = 1e9, best_cpp = 1e9;
    int best_L = 0;
    double best_total = 1e9;
    long draco_mesh = -1, draco_pc = -1;
};

// ---------------------------------------------------------------------------------------------
// --mapped: what format 1.7's mapped points (spec 23) cost, against POINTS and Draco

struct MappedBytes {
    size_t points = 0, plain = 0, mapped = 0, map = 0, map_packets = 0;
    size_t normals = 0, normals_sent = 0;  // format 1.8: NORMALS packets' bytes (in `mapped`), normals they send
    bool surface_normals = false;          // some object has surface normals (the encoder found they pay)
    std::string levels;
    double plain_us = 0, mapped_us = 0;  // receiving every packet (parse, check, place), per point, best of 5
};

// Microseconds per point to take every packet of `packets` into a receiver, best of 5 runs.
double receive_us(const std::vector<std::vector<uint8_t>>& packets, size_t points) {
    double best = 1e30;
    for (int run = 0; run < 5; ++run) {
        const auto t0 = Clock::now();
        ReceivedStream rx;
        for (const auto& p : packets) rx.add_packet(p, 0);
        best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    return points ? best * 1e6 / double(points) : 0;
}

// The asset encoded twice as `ellicast encode` does (no repair): POINTS packets, and POINT_MAP +
// MAPPED_POINTS packets. Each mapped stream is received whole and checked to give back every point.
// `normal_tolerance`: EncodeOptions::normal_tolerance of the mapped stream (format 1.8's surface
// normals; 0: every normal in the records, as format 1.7); the POINTS stream sends every normal.
MappedBytes mapped_bytes(const Asset& asset, double normal_tolerance = EncodeOptions{}.normal_tolerance) {
    MappedBytes r;
    for (bool point_map : {false, true}) {
        EncodeOptions options;
        options.repair_ratio = 0;
        options.point_map = point_map;
        options.normal_tolerance = point_map ? normal_tolerance : 0;
        EncodedAsset out;
        std::string error;
        CHECK(encode_asset(asset, options, 1, false, out, error));
        if (!point_map) {
            r.plain = out.point_bytes;
            for (const auto& o : out.encoded.info.objects) r.points += o.point_count;
            r.plain_us = receive_us(out.packets, r.points);
            continue;
        }
        r.mapped_us = receive_us(out.packets, r.points);
        r.mapped = out.point_bytes + out.map_bytes + out.normal_bytes;
        r.normals = out.normal_bytes;
        for (const ObjectReport& o : out.encoded.reports) r.normals_sent += o.normals_sent, r.surface_normals |= o.surface_normals;
        r.map = out.map_bytes;
        r.map_packets = out.map_packets;
        for (const ObjectReport& o : out.encoded.reports)
            r.levels += (r.levels.empty() ? "" : ",") + std::to_string(int(o.map_level));
        ReceivedStream rx;
        for (const auto& p : out.packets) CHECK(rx.add_packet(p, 0) == Error::Ok);
        for (size_t i = 0; i < rx.objects().size(); ++i) {
            const auto& o = rx.objects()[i];
            CHECK(o.points.size() == o.info->point_count);
            for (const auto& [index, q] : o.points) CHECK(q.position == out.encoded.contents[i].points[index].position);
        }
    }
    return r;
}

int run_mapped(const std::string& samples, const std::string& tmp, bool draco) {
    std::printf("bench_point_coding --mapped: bytes per point of format 1.7's mapped points (POINT_MAP + MAPPED_POINTS\n");
    std::printf("packets, spec 23) against format 1.0's POINTS packets, both with all framing (24 bytes header + CRC and\n");
    std::printf("8 bytes batch header a packet; the map's packets counted once), as `ellicast encode` makes them (default\n");
    std::printf("options, 14-bit positions, %zu-byte packets, no repair). Every mapped stream is received and checked\n", kPacket);
    std::printf("to give back every point. Draco: draco_encoder -qp 14 -cl 7 (-qn 10 with normals), per input vertex.\n\n");
    std::printf("Positions only (attributes dropped, positions welded):\n");
    std::printf("%-14s %7s %6s %10s %10s %8s %6s %11s %11s\n", "model", "points", "level", "POINTS", "mapped", "change",
                "map", "Draco mesh", "Draco pc");
    const std::vector<std::string> names = {"bunny.ply", "fandisk.obj", "spot.obj", "suzanne.obj", "teapot.obj", "woody.obj"};
    struct Row {
        std::string name;
        double positions = 0;
        size_t vertices = 0;
    };
    std::vector<Row> rows;
    std::vector<std::tuple<std::string, double, double>> receive_times;
    for (const auto& name : names) {
        const std::string path = samples + "/meshes/" + name;
        if (!std::filesystem::exists(path)) continue;
        Asset asset = load_asset(path);
        Asset welded;
        welded.objects.push_back(weld_positions(asset.objects[0]));
        const MappedBytes m = mapped_bytes(welded);
        long mesh = -1, pc = -1;
        if (draco) {
            const std::string ply = tmp + "/" + name + ".ply";
            write_ply(ply, welded.objects[0], false);
            mesh = draco_bytes(ply, false, false);
            pc = draco_bytes(ply, true, false);
        }
        const double v = double(welded.objects[0].positions.size()), n = double(m.points);
        std::printf("%-14s %7zu %6s %6.2f B/pt %6.2f B/pt %+7.0f%% %6.2f %6.2f B/vx %6.2f B/vx\n", name.c_str(), m.points,
                    m.levels.c_str(), double(m.plain) / n, double(m.mapped) / n, 100.0 * (double(m.mapped) / double(m.plain) - 1),
                    double(m.map) / n, mesh < 0 ? 0.0 : double(mesh) / v, pc < 0 ? 0.0 : double(pc) / v);
        rows.push_back({name, double(m.mapped) / n, size_t(v)});
        receive_times.push_back({name, m.plain_us, m.mapped_us});
    }
    std::printf("('map' = the POINT_MAP packets' share of 'mapped'. Points = vertices + surface samples.)\n\n");
    std::printf("Receiving a whole stream (parse, check, place every point; also the stream info, ellipsoids and exact\n");
    std::printf("layer), microseconds per point, best of 5; inserting a point into the surface costs 16 to 18 us\n");
    std::printf("(bench/results/decode.txt):\n");
    for (const auto& [name, plain_us, mapped_us] : receive_times)
        std::printf("%-14s POINTS %.2f us, mapped %.2f us\n", name.c_str(), plain_us, mapped_us);
    std::printf("\n");
    std::printf("With normals (the model's own for suzanne, area-weighted computed ones for the others), %d-bit octahedral:\n",
                kNormalBits);
    std::printf("Format 1.7 sends every normal in the records; format 1.8 (spec 24) sends only those further than the\n");
    std::printf("tolerance from the surface normal over the exact layer (angle-weighted), in NORMALS packets (counted).\n");
    // The share of points whose normal is sent, or "off" where the encoder kept the normals in the
    // records (surface normals would not have saved bytes).
    auto sent_share = [](const MappedBytes& b) {
        char text[16];
        if (!b.surface_normals) return std::string("off");
        std::snprintf(text, sizeof text, "%.1f%%", 100.0 * double(b.normals_sent) / double(b.points));
        return std::string(text);
    };
    std::printf("%-14s %10s %10s %14s %14s %9s %14s %9s %16s\n", "model", "POINTS", "1.7 mapped", "normals cost",
                "1.8, 2 deg", "sent", "1.8, 1 deg", "sent", "Draco normals");
    for (const Row& row : rows) {
        Asset asset = load_asset(samples + "/meshes/" + row.name);
        Mesh m = asset.objects[0];
        if (!m.has_normals()) {
            m = weld_positions(m);
            compute_normals(m);
        }
        m.texcoords.clear();
        m.colors.clear();
        Asset with;
        with.objects.push_back(m);
        const MappedBytes b = mapped_bytes(with, 0);
        const MappedBytes b2 = mapped_bytes(with, 2);
        const MappedBytes b1 = mapped_bytes(with, 1);
        long mesh = -1, mesh_normals = -1;
        if (draco) {
            Mesh welded = weld_positions(m);
            compute_normals(welded);
            const std::string ply = tmp + "/" + row.name + ".n.ply";
            write_ply(ply, welded, true);
            mesh_normals = draco_bytes(ply, false, true);
            write_ply(ply, welded, false);
            mesh = draco_bytes(ply, false, false);
        }
        const double n = double(b.points);
        std::printf("%-14s %6.2f B/pt %6.2f B/pt %+8.2f B/pt %+8.2f B/pt %9s %+8.2f B/pt %9s %+10.2f B/vx\n",
                    row.name.c_str(), double(b.plain) / n, double(b.mapped) / n, double(b.mapped) / n - row.positions,
                    double(b2.mapped) / n - row.positions, sent_share(b2).c_str(),
                    double(b1.mapped) / n - row.positions, sent_share(b1).c_str(),
                    mesh < 0 ? 0.0 : double(mesh_normals - mesh) / double(row.vertices));
    }
    std::printf("('normals cost' and the 1.8 columns = mapped B/pt with normals minus positions only: the points differ\n");
    std::printf(" where a vertex splits at a crease; 'sent' = the share of points whose normal a NORMALS packet sends:\n");
    std::printf(" surface samples' always are (teapot 12,729 of its 15,962 points, woody 3,279 of 3,973, suzanne most).\n");
    std::printf(" Draco normals: its mesh with normals minus without, per vertex.)\n\n");
    std::printf("glTF samples as they are (every attribute they carry):\n");
    std::printf("%-24s %-34s %7s %8s %10s %10s %8s %10s %8s %7s\n", "asset", "attributes", "points", "levels", "POINTS",
                "1.7 mapped", "change", "1.8", "change", "sent");
    std::vector<std::filesystem::path> assets;
    for (const auto& dir : std::filesystem::directory_iterator(samples + "/gltf"))
        for (const auto& f : std::filesystem::directory_iterator(dir.path()))
            if (f.path().extension() == ".gltf" || f.path().extension() == ".glb") assets.push_back(f.path());
    std::sort(assets.begin(), assets.end());
    for (const auto& path : assets) {
        Asset asset = load_asset(path.string());
        std::set<std::string> attributes;
        for (const Mesh& m : asset.objects) {
            if (m.has_normals()) attributes.insert("normals");
            if (m.has_texcoords()) attributes.insert("texcoords");
            if (m.has_colors()) attributes.insert("colours");
        }
        std::string a;
        for (const auto& s : attributes) a += (a.empty() ? "" : "+") + s;
        const MappedBytes m = mapped_bytes(asset, 0);
        const MappedBytes m8 = mapped_bytes(asset);
        const double n = double(m.points);
        std::printf("%-24s %-34s %7zu %8s %6.2f B/pt %6.2f B/pt %+7.0f%% %6.2f B/pt %+7.0f%% %7s\n",
                    (path.parent_path().filename() / path.filename()).string().substr(0, 24).c_str(),
                    (a.empty() ? "-" : a).c_str(), m.points, m.levels.substr(0, 8).c_str(), double(m.plain) / n,
                    double(m.mapped) / n, 100.0 * (double(m.mapped) / double(m.plain) - 1), double(m8.mapped) / n,
                    100.0 * (double(m8.mapped) / double(m.plain) - 1), sent_share(m8).c_str());
    }
    std::printf("(levels: the map level of each object, 0 = sent as POINTS because mapping would not pay. 1.8: with\n");
    std::printf(" surface normals at the default 2-degree tolerance; sent = share of points whose normal is sent, off =\n");
    std::printf(" the encoder kept every normal in the records: samples' and creases' normals are always sent, and\n");
    std::printf(" there were too few others to pay for a bit a point.)\n");
    return 0;
}

void print_packing(const char* label, const Packing& p, size_t points, size_t extra, double base) {
    double amort = p.bpp() + double(extra) / double(points);
    std::printf("  %-34s %5zu packets  %7.1f pts/packet  %5.2f B/pt  %5.2f B/pt with stream-info model  (%+.0f%%)\n",
                label, p.packets, double(p.points) / double(std::max<size_t>(1, p.packets)), p.bpp(), amort,
                100.0 * (amort / base - 1));
}

}  // namespace

int main(int argc, char** argv) {
    std::string samples = "../shared/samples";
    std::string only;
    bool draco = true, computed_normals = true, mapped = false;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--samples" && i + 1 < argc)
            samples = argv[++i];
        else if (a == "--only" && i + 1 < argc)
            only = argv[++i];
        else if (a == "--no-draco")
            draco = false;
        else if (a == "--no-computed-normals")
            computed_normals = false;
        else if (a == "--mapped")
            mapped = true;
        else {
            std::fprintf(stderr, "usage: bench_point_coding [--samples DIR] [--only NAME] [--no-draco] [--no-computed-normals] [--mapped]\n");
            return 2;
        }
    }
    const std::vector<std::string> names = {"bunny.ply", "fandisk.obj", "spot.obj", "suzanne.obj", "teapot.obj", "woody.obj"};
    const std::vector<int> levels = {4, 5, 6, 7};
    const std::string tmp = (std::filesystem::temp_directory_path() / "bench_point_coding").string();
    std::filesystem::create_directories(tmp);
    if (mapped) return run_mapped(samples, tmp, draco);

    std::printf("bench_point_coding: bytes per point of POINTS payloads, 14-bit positions, %zu-byte packets,\n", kPacket);
    std::printf("framing included (%zu bytes per packet: 20 header + 4 CRC + 8 batch header). Every coding is decoded\n", kFraming);
    std::printf("back and compared with its input. Models encoded as `ellicast encode` does (default options, no repair).\n");
    std::printf("'same' = the packets' own batches; 'fill' = consecutive stream-order points, as many as fit %zu bytes coded.\n", kPacket);
    std::printf("'with stream-info model' adds the map (and trained priors) once, amortized over the object's points.\n\n");

    std::vector<Result> results;
    struct NormalRow {
        std::string name;
        bool computed = false;
        size_t points = 0;
        double raw = 0;  // today's extra bytes per point for normals (2 x 10 bits, bit-packed)
        std::map<std::string, double> extra;       // coding -> extra B/pt (fill packing, positions = c+ at best L)
        std::map<std::string, double> extra_same;  // same batches
        std::map<std::string, size_t> model_bytes;
        long draco_mesh = -1, draco_mesh_pos = -1;
        size_t vertices = 0;
    };
    std::vector<NormalRow> normal_rows;

    for (const auto& name : names) {
        if (!only.empty() && name.find(only) == std::string::npos) continue;
        const std::string path = samples + "/meshes/" + name;
        Asset asset = load_asset(path);
        CHECK(asset.objects.size() == 1);
        const Mesh& original = asset.objects[0];
        Mesh positions = weld_positions(original);

        Result res;
        res.name = name;
        res.vertices = positions.positions.size();
        StreamPoints s = encode_model(positions);
        res.points = s.stream.size();
        res.packets_a = s.point_packets;
        res.a = double(s.point_bytes) / double(res.points);
        std::printf("== %s: %zu vertices (positions welded, no attributes), %zu points, encoded in %.1f s\n", name.c_str(),
                    res.vertices, res.points, s.encode_seconds);
        std::printf("  %-34s %5zu packets  %7.1f pts/packet  %5.2f B/pt\n", "(a) bit packing (today)", res.packets_a,
                    double(res.points) / double(res.packets_a), res.a);

        // baseline decode time: today's payload parse
        {
            const ObjectInfo& object = s.info.objects[0];
            std::vector<std::vector<uint8_t>> payloads;
            for (const auto& b : s.batches) {
                PointBatch pb;
                pb.first_index = 0;
                for (const auto& it : b) {
                    QuantizedPoint q;
                    q.position = unmorton(it.code, kBits);
                    pb.points.push_back(q);
                }
                payloads.push_back(encode_points_payload(pb, s.info, object));
            }
            size_t sink = 0;
            const int rep = 50;
            auto t0 = Clock::now();
            for (int r = 0; r < rep; ++r)
                for (const auto& p : payloads) {
                    PointBatch out;
                    CHECK(decode_points_payload(p, s.info, object, out) == Error::Ok);
                    sink += out.points.size();
                }
            res.decode_us_a = 1e6 * std::chrono::duration<double>(Clock::now() - t0).count() / double(rep * payloads.size());
            CHECK(sink > 0);
        }

        Config cb;
        std::vector<CodedPacket> kept_b;
        res.b_same = code_same(cb, s.batches, nullptr);
        res.b_fill = code_fill(cb, s.stream, &kept_b);
        res.decode_us_b = 1e6 * time_decode(cb, kept_b, 5);
        print_packing("(b) octree, adaptive, same", res.b_same, res.points, 0, res.a);
        print_packing("(b) octree, adaptive, fill", res.b_fill, res.points, 0, res.a);

        std::map<int, CoarseMap> maps;
        for (int L : levels) {
            maps[L] = build_map(s.quantized, L, false);
            const CoarseMap& map = maps[L];
            res.map_bytes[L] = map.bytes;
            Config cc;
            cc.map = &map;
            res.c_same[L] = code_same(cc, s.batches, nullptr);
            res.c_fill[L] = code_fill(cc, s.stream, nullptr);
            size_t pb = 0;
            std::vector<uint16_t> priors = train_priors(cc, s.batches, pb);
            res.prior_bytes[L] = pb;
            Config cp = cc;
            cp.priors = &priors;
            std::vector<CodedPacket> kept;
            res.cp_same[L] = code_same(cp, s.batches, nullptr);
            res.cp_fill[L] = code_fill(cp, s.stream, &kept);
            char label[96];
            std::printf("  L=%d: map of %zu cells, %zu bytes coded (%.3f B/pt amortized); priors %zu bytes\n", L,
                        map.by_depth[L].size(), map.bytes, double(map.bytes) / double(res.points), pb);
            std::snprintf(label, sizeof label, "(c) + map L=%d, same", L);
            print_packing(label, res.c_same[L], res.points, map.bytes, res.a);
            std::snprintf(label, sizeof label, "(c) + map L=%d, fill", L);
            print_packing(label, res.c_fill[L], res.points, map.bytes, res.a);
            std::snprintf(label, sizeof label, "(c+) + map L=%d + priors, same", L);
            print_packing(label, res.cp_same[L], res.points, map.bytes + pb, res.a);
            std::snprintf(label, sizeof label, "(c+) + map L=%d + priors, fill", L);
            print_packing(label, res.cp_fill[L], res.points, map.bytes + pb, res.a);
            double total = res.cp_fill[L].bpp() + double(map.bytes + pb) / double(res.points);
            if (total < res.best_cplus) {
                res.best_cplus = total;
                res.best_L_cplus = L;
                res.decode_us_cplus = 1e6 * time_decode(cp, kept, 5);
            }
            if (total < res.best_total) {
                res.best_total = total;
                res.best_L = L;
                res.best_plane = false;
                res.decode_us_best = 1e6 * time_decode(cp, kept, 5);
            }
            // (c++): the same with plane contexts for the direct bits
            Config cq;
            cq.map = &map;
            cq.plane_ctx = true;
            size_t pbq = 0;
            std::vector<uint16_t> priors_q = train_priors(cq, s.batches, pbq);
            res.prior_bytes_pp[L] = pbq;
            cq.priors = &priors_q;
            std::vector<CodedPacket> kept_q;
            res.cpp_same[L] = code_same(cq, s.batches, nullptr);
            res.cpp_fill[L] = code_fill(cq, s.stream, &kept_q);
            std::snprintf(label, sizeof label, "(c++) + plane contexts L=%d, same", L);
            print_packing(label, res.cpp_same[L], res.points, map.bytes + pbq, res.a);
            std::snprintf(label, sizeof label, "(c++) + plane contexts L=%d, fill", L);
            print_packing(label, res.cpp_fill[L], res.points, map.bytes + pbq, res.a);
            total = res.cpp_fill[L].bpp() + double(map.bytes + pbq) / double(res.points);
            if (total < res.best_cpp) {
                res.best_cpp = total;
                res.best_L_cpp = L;
                res.decode_us_cpp = 1e6 * time_decode(cq, kept_q, 5);
            }
            if (total < res.best_total) {
                res.best_total = total;
                res.best_L = L;
                res.best_plane = true;
                res.decode_us_best = 1e6 * time_decode(cq, kept_q, 5);
            }
        }
        {
            // the best coding again, for its bit breakdown; and (b) on the whole object as ONE payload
            Config cb2;
            std::printf("  where the bits go, (b) fill:\n");
            print_breakdown(cb2, kept_b);
            Config cbest;
            cbest.map = &maps[res.best_L];
            cbest.plane_ctx = res.best_plane;
            size_t pbb = 0;
            std::vector<uint16_t> pr = train_priors(cbest, s.batches, pbb);
            cbest.priors = &pr;
            std::vector<CodedPacket> kb;
            code_fill(cbest, s.stream, &kb);
            std::printf("  where the bits go, best (%s, L=%d) fill:\n", res.best_plane ? "c++" : "c+", res.best_L);
            print_breakdown(cbest, kb);
            std::vector<std::vector<Item>> whole = {s.stream};
            Packing one = code_same(Config{}, whole, nullptr);
            std::printf("  reference, not a packet: (b) over the whole object as one payload: %.2f B/pt (%zu bytes)\n",
                        double(one.bytes - kFraming) / double(res.points), one.bytes - kFraming);
        }
        std::printf("  decode time per packet (fill): (a) %.1f us, (b) %.1f us, best (%s, L=%d) %.1f us\n", res.decode_us_a,
                    res.decode_us_b, res.best_plane ? "c++" : "c+", res.best_L, res.decode_us_best);

        if (draco) {
            std::string ply = tmp + "/" + name + ".pos.ply";
            write_ply(ply, positions, false);
            res.draco_mesh = draco_bytes(ply, false, false);
            res.draco_pc = draco_bytes(ply, true, false);
            std::printf("  Draco -qp 14 -cl 7: mesh %ld bytes (%.2f B/vertex), point cloud %ld bytes (%.2f B/vertex)\n",
                        res.draco_mesh, double(res.draco_mesh) / double(res.vertices), res.draco_pc,
                        double(res.draco_pc) / double(res.vertices));
        }
        results.push_back(res);

        // ---- normals
        const bool has = original.has_normals();
        if (has || computed_normals) {
            Mesh withn = positions;
            if (has) {
                // keep the model's normals (positions and normals welded together)
                Mesh m;
                std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, uint32_t> index;
                std::vector<uint32_t> remap(original.positions.size());
                for (size_t i = 0; i < original.positions.size(); ++i) {
                    auto [it, fresh] = index.emplace(std::make_pair(original.positions[i], original.normals[i]),
                                                     uint32_t(m.positions.size()));
                    if (fresh) {
                        m.positions.push_back(original.positions[i]);
                        m.normals.push_back(original.normals[i]);
                    }
                    remap[i] = it->second;
                }
                for (auto t : original.triangles) {
                    std::array<uint32_t, 3> r{remap[t[0]], remap[t[1]], remap[t[2]]};
                    if (r[0] != r[1] && r[1] != r[2] && r[0] != r[2]) m.triangles.push_back(r);
                }
                m.name = original.name;
                withn = m;
            } else {
                compute_normals(withn);
            }
            StreamPoints sn = encode_model(withn);
            CHECK(sn.normals);
            NormalRow row;
            row.name = name;
            row.computed = !has;
            row.points = sn.stream.size();
            row.vertices = withn.positions.size();
            row.raw = 2.0 * kNormalBits / 8.0;
            const int L = res.best_L;
            CoarseMap map = build_map(sn.quantized, L, true);
            std::printf("  normals (%s, 10-bit octahedral): %zu points, today %.2f B/pt (%.2f of it normals)\n",
                        has ? "the model's" : "computed, area-weighted", row.points,
                        double(sn.point_bytes) / double(row.points), row.raw);
            // positions alone with these points: c+ at L
            Config cpos;
            cpos.map = &map;
            cpos.plane_ctx = res.best_plane;
            size_t pb = 0;
            std::vector<uint16_t> ppos = train_priors(cpos, sn.batches, pb);
            cpos.priors = &ppos;
            Packing pos_fill = code_fill(cpos, sn.stream, nullptr);
            Packing pos_same = code_same(cpos, sn.batches, nullptr);
            for (auto [label, pred] : {std::pair<const char*, NormalPredictor>{"nn", NormalPredictor::Nearest},
                                       {"pca", NormalPredictor::Pca}, {"cell", NormalPredictor::Cell}}) {
                Config cn;
                cn.map = &map;
                cn.plane_ctx = res.best_plane;
                cn.normals = pred;
                size_t pbn = 0;
                std::vector<uint16_t> pn = train_priors(cn, sn.batches, pbn);
                cn.priors = &pn;
                Packing fill = code_fill(cn, sn.stream, nullptr);
                Packing same = code_same(cn, sn.batches, nullptr);
                size_t model = (pbn > pb ? pbn - pb : 0) + (pred == NormalPredictor::Cell ? map.normal_bytes : 0);
                row.model_bytes[label] = model;
                row.extra[label] = fill.bpp() - pos_fill.bpp() + double(model) / double(row.points);
                row.extra_same[label] = same.bpp() - pos_same.bpp() + double(model) / double(row.points);
                std::printf("    normals predicted by %-4s: +%.2f B/pt (fill), +%.2f B/pt (same batches), stream-info model %zu bytes\n",
                            label, row.extra[label], row.extra_same[label], model);
            }
            if (draco) {
                std::string ply = tmp + "/" + name + ".nrm.ply";
                write_ply(ply, withn, true);
                row.draco_mesh = draco_bytes(ply, false, true);
                std::string plyp = tmp + "/" + name + ".nrmpos.ply";
                write_ply(plyp, withn, false);
                row.draco_mesh_pos = draco_bytes(plyp, false, false);
                std::printf("    Draco mesh -qn 10: %ld bytes with normals, %ld without (+%.2f B/vertex for normals)\n",
                            row.draco_mesh, row.draco_mesh_pos,
                            double(row.draco_mesh - row.draco_mesh_pos) / double(row.vertices));
            }
            normal_rows.push_back(row);
        }
        std::printf("\n");
        std::fflush(stdout);
    }

    // ---- summary table
    std::printf("== Summary: bytes per point, positions only, 14 bits, %zu-byte packets, framing included\n", kPacket);
    std::printf("   (b) and (c) with packets filled to %zu bytes; (c) at its best L, map (+ priors) amortized once over the stream\n\n", kPacket);
    std::printf("%-12s %7s %7s %5s %6s %6s %6s %6s %7s %12s %9s %9s\n", "model", "points", "packets", "(a)", "(b)",
                "(c)", "(c+)", "(c++)", "best L", "map+priors", "Draco mesh", "Draco pc");
    for (const auto& r : results) {
        int L = r.best_L;
        auto best_of = [&](const std::map<int, Packing>& m, const std::map<int, size_t>* priors) {
            double v = 1e9;
            for (auto& [l, p] : m)
                v = std::min(v, p.bpp() + double(r.map_bytes.at(l) + (priors ? priors->at(l) : 0)) / double(r.points));
            return v;
        };
        const Packing& bp = r.best_plane ? r.cpp_fill.at(L) : r.cp_fill.at(L);
        std::printf("%-12s %7zu %3zu/%-3zu %5.2f %6.2f %6.2f %6.2f %6.2f %7d %6zu+%-5zu %9.2f %9.2f\n", r.name.c_str(), r.points,
                    r.packets_a, bp.packets, r.a, r.b_fill.bpp(), best_of(r.c_fill, nullptr), best_of(r.cp_fill, &r.prior_bytes),
                    best_of(r.cpp_fill, &r.prior_bytes_pp), L, r.map_bytes.at(L),
                    r.best_plane ? r.prior_bytes_pp.at(L) : r.prior_bytes.at(L),
                    r.draco_mesh > 0 ? double(r.draco_mesh) / double(r.vertices) : 0.0,
                    r.draco_pc > 0 ? double(r.draco_pc) / double(r.vertices) : 0.0);
    }
    std::printf("\n(packets: (a)'s / (c+)'s at best L. Draco per input vertex (welded positions); ellicast points = vertices +\n");
    std::printf(" surface samples, so the per-point figures of small low-poly models are not per-vertex figures.)\n\n");
    std::printf("%-12s %s\n", "model", "(b) | (c+) | (c++) with the packets' own batches (222 points), at the best L, framing + model included");
    for (const auto& r : results) {
        int L = r.best_L;
        std::printf("%-12s %5.2f | %5.2f | %5.2f\n", r.name.c_str(), r.b_same.bpp(),
                    r.cp_same.at(L).bpp() + double(r.map_bytes.at(L) + r.prior_bytes.at(L)) / double(r.points),
                    r.cpp_same.at(L).bpp() + double(r.map_bytes.at(L) + r.prior_bytes_pp.at(L)) / double(r.points));
    }
    std::printf("\nDecode time per packet (fill packing; this machine, another benchmark running on the other core):\n");
    for (const auto& r : results)
        std::printf("%-12s (a) %6.1f us   (b) %6.1f us   (c+ L=%d) %6.1f us = %.2f us/point   (c++ L=%d) %7.1f us = %.2f us/point\n",
                    r.name.c_str(), r.decode_us_a, r.decode_us_b, r.best_L_cplus, r.decode_us_cplus,
                    r.decode_us_cplus * double(r.cp_fill.at(r.best_L_cplus).packets) / double(r.points), r.best_L_cpp,
                    r.decode_us_cpp, r.decode_us_cpp * double(r.cpp_fill.at(r.best_L_cpp).packets) / double(r.points));
    std::printf("\n== (d) Normals: extra bytes per point over positions (best of c+/c++), 10-bit octahedral, lossless; fill packing\n");
    std::printf("%-12s %-9s %7s %6s %6s %6s %6s %11s\n", "model", "normals", "points", "today", "nn", "pca", "cell",
                "Draco mesh");
    for (const auto& r : normal_rows)
        std::printf("%-12s %-9s %7zu %6.2f %6.2f %6.2f %6.2f %11.2f\n", r.name.c_str(), r.computed ? "computed" : "model's",
                    r.points, r.raw, r.extra.at("nn"), r.extra.at("pca"), r.extra.at("cell"),
                    r.draco_mesh > 0 ? double(r.draco_mesh - r.draco_mesh_pos) / double(r.vertices) : 0.0);
    return 0;
}

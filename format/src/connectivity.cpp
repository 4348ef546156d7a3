// The exact layer (format 1.3, spec section 19): an object's original triangles as a range-coded
// gate traversal over its points. Each new corner is named by its rank among the points nearest to
// the parallelogram prediction (a k-d tree finds them), so a triangle costs a few adaptive bits and
// the order of the points (chosen for spreading, section 7.2) costs nothing.
//
// Both directions run the same loop (spec 19.2): the encoder decides at each gate what the decoder
// will read there. Work is linear in the triangles (at most 4 * triangle_count steps, each a k-nearest
// query), memory in the triangles and points.
#include "ellicast/format.h"
#include "ellicast/format/key_set.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <span>
#include <utility>

namespace ellicast {

namespace {

constexpr int kRanks = 16;
constexpr uint32_t kTop = 1u << 24;

// ---- LZMA's binary range coder (spec 19.3)

constexpr int kListMax = 16;
constexpr int kLengths = 18;   // a displacement's bit length, 0 .. 17

struct Contexts {
    uint16_t none = 1024;
    std::array<uint16_t, kRanks> rank;
    // Format 1.11 (spec 27.2).
    uint16_t sign = 1024;
    std::array<uint16_t, 3> fresh;  // by the gate's local candidates: none, one, more (seeds: none)
    // A displacement's bit length, by axis and the bit length of the axis before (x: set 0; y, z:
    // 1 + min(c, 8)).
    std::array<std::array<uint16_t, kLengths>, 10> length;
    // A carried vertex's texture coordinates, coded as its position is (their own sets and sign).
    uint16_t uv_sign = 1024;
    std::array<std::array<uint16_t, kLengths>, 10> uv_length;
    Contexts() {
        rank.fill(1024);
        fresh.fill(1024);
        for (auto& set : length) set.fill(1024);
        for (auto& set : uv_length) set.fill(1024);
    }
};

class RangeEncoder {
public:
    void bit(uint16_t& p, int b) {
        const uint32_t bound = (range_ >> 11) * p;
        if (b == 0) {
            range_ = bound;
            p = uint16_t(p + ((2048 - p) >> 5));
        } else {
            low_ += bound;
            range_ -= bound;
            p = uint16_t(p - (p >> 5));
        }
        normalize();
    }
    void direct(uint32_t value, int bits) {
        for (int k = bits - 1; k >= 0; --k) {
            range_ >>= 1;
            if ((value >> k) & 1) low_ += range_;
            normalize();
        }
    }
    std::vector<uint8_t> finish() {
        for (int i = 0; i < 5; ++i) shift_low();
        return std::move(out_);
    }

private:
    void normalize() {
        while (range_ < kTop) {
            range_ <<= 8;
            shift_low();
        }
    }
    void shift_low() {
        if (uint32_t(low_) < 0xFF000000u || (low_ >> 32) != 0) {
            uint8_t temp = cache_;
            do {
                out_.push_back(uint8_t(temp + uint8_t(low_ >> 32)));
                temp = 0xFF;
            } while (--cache_size_ != 0);
            cache_ = uint8_t(uint32_t(low_) >> 24);
        }
        ++cache_size_;
        low_ = uint64_t(uint32_t(low_) << 8);
    }
    uint64_t low_ = 0;
    uint32_t range_ = 0xFFFFFFFFu;
    uint8_t cache_ = 0;
    uint64_t cache_size_ = 1;
    std::vector<uint8_t> out_;
};

class RangeDecoder {
public:
    explicit RangeDecoder(std::span<const uint8_t> in) : in_(in) {
        for (int i = 0; i < 5; ++i) code_ = (code_ << 8) | next();
    }
    int bit(uint16_t& p) {
        const uint32_t bound = (range_ >> 11) * p;
        int b;
        if (code_ < bound) {
            range_ = bound;
            p = uint16_t(p + ((2048 - p) >> 5));
            b = 0;
        } else {
            range_ -= bound;
            code_ -= bound;
            p = uint16_t(p - (p >> 5));
            b = 1;
        }
        normalize();
        return b;
    }
    uint32_t direct(int bits) {
        uint32_t v = 0;
        for (int k = 0; k < bits; ++k) {
            range_ >>= 1;
            int b = 0;
            if (code_ >= range_) {
                code_ -= range_;
                b = 1;
            }
            normalize();
            v = (v << 1) | uint32_t(b);
        }
        return v;
    }

private:
    uint8_t next() { return pos_ < in_.size() ? in_[pos_++] : (++pos_, uint8_t(0)); }
    void normalize() {
        if (range_ < kTop) {
            range_ <<= 8;
            code_ = (code_ << 8) | next();
        }
    }
    std::span<const uint8_t> in_;
    size_t pos_ = 0;
    uint32_t range_ = 0xFFFFFFFFu;
    uint32_t code_ = 0;
};

// ---- the k points nearest to a prediction, ties by index (spec 19.2's candidates)

// Squared distance from a point to a prediction (spec 19.2's order of candidates).
uint64_t dist2(const std::array<uint32_t, 3>& p, const std::array<int64_t, 3>& q) {
    uint64_t d = 0;
    for (int k = 0; k < 3; ++k) {
        const int64_t e = int64_t(p[k]) - q[k];
        d += uint64_t(e * e);
    }
    return d;
}

// Ties matter: a stream may put every point at one position, and a search that visits every point
// at equal distance made each step linear and a whole decode quadratic (issue 29). Points with equal
// coordinates along a split are ordered by index, ties go to the lower indices first, and a subtree
// is skipped when it cannot hold a point nearer than the k-th, or as near with a lower index.
class KdTree {
    static constexpr size_t kLeaf = 8;  // most points in a leaf (a range scanned whole)
public:
    explicit KdTree(const std::vector<std::array<uint32_t, 3>>& p) : at_(p.size()), min_index_(p.size()) {
        for (size_t j = 0; j < p.size(); ++j) at_[j] = {p[j], uint32_t(j)};
        build(0, at_.size(), 0);
    }

    size_t size() const { return at_.size(); }

    // The `k` points nearest to `q` other than a and b, by (squared distance, index), nearest first
    // (k <= kRanks). `bound`: a squared distance the k-th nearest is known not to exceed (that of k
    // points other than a and b), or UINT64_MAX; farther points and subtrees are not looked at.
    void nearest(const std::array<int64_t, 3>& q, uint32_t a, uint32_t b, size_t k,
                 std::vector<std::pair<uint64_t, uint32_t>>& best, uint64_t bound = UINT64_MAX) const {
        Query query(q, a, b, std::min<size_t>(k, kRanks));
        query.worst = bound;
        if (query.k > 0) search(query);
        best.clear();
        for (size_t j = 0; j < query.n; ++j) best.emplace_back(query.items[j].d, query.items[j].i);
    }

    // How many points other than a and b come before (d, x) in the order of nearest(): nearer to `q`
    // than squared distance d, or as near with an index below x; counting stops at `limit`. The
    // rank of x among the nearest points is one more (the encoder's question, answered without
    // finding all kRanks nearest).
    size_t count_before(const std::array<int64_t, 3>& q, uint32_t a, uint32_t b, uint64_t d, uint32_t x,
                        size_t limit) const {
        struct Range {
            uint32_t lo, hi;
            int axis;
        };
        std::array<Range, 40> stack;  // a level halves the range (at most 33 for 2^32 points)
        size_t depth = 0, count = 0;
        stack[depth++] = {0, uint32_t(at_.size()), 0};
        auto take = [&](const Entry& e) {
            if (e.index == a || e.index == b) return;
            const uint64_t de = dist2(e.p, q);
            count += de < d || (de == d && e.index < x);
        };
        while (depth > 0 && count < limit) {
            const Range r = stack[--depth];
            if (r.hi - r.lo <= kLeaf) {
                for (uint32_t j = r.lo; j < r.hi; ++j) take(at_[j]);
                continue;
            }
            const uint32_t mid = (r.lo + r.hi) / 2;
            const int64_t gap = q[r.axis] - int64_t(at_[mid].p[r.axis]);
            const uint64_t along = uint64_t(gap * gap);
            const int next = r.axis == 2 ? 0 : r.axis + 1;
            // The side of the split away from q, and the split point, lie at least |gap| away.
            if (along <= d) {
                take(at_[mid]);
                stack[depth++] = gap < 0 ? Range{mid + 1, r.hi, next} : Range{r.lo, mid, next};
            }
            stack[depth++] = gap < 0 ? Range{r.lo, mid, next} : Range{mid + 1, r.hi, next};
        }
        return std::min(count, limit);
    }

private:
    // Builds the subtree over at_[lo, hi) and returns the lowest point index in it (kept by mid).
    uint32_t build(size_t lo, size_t hi, int axis) {
        if (hi - lo <= kLeaf) return lowest_in_leaf(lo, hi);
        const size_t mid = (lo + hi) / 2;
        std::nth_element(at_.begin() + lo, at_.begin() + mid, at_.begin() + hi, [&](const Entry& x, const Entry& y) {
            return x.p[axis] < y.p[axis] || (x.p[axis] == y.p[axis] && x.index < y.index);
        });
        const uint32_t left = build(lo, mid, (axis + 1) % 3), right = build(mid + 1, hi, (axis + 1) % 3);
        return min_index_[mid] = std::min({left, right, at_[mid].index});
    }
    uint32_t lowest_in_leaf(size_t lo, size_t hi) const {
        uint32_t m = UINT32_MAX;
        for (size_t j = lo; j < hi; ++j) m = std::min(m, at_[j].index);
        return m;
    }
    uint32_t lowest(size_t lo, size_t hi) const {
        if (hi <= lo) return UINT32_MAX;
        return hi - lo <= kLeaf ? lowest_in_leaf(lo, hi) : min_index_[(lo + hi) / 2];
    }
    // The point at position j of the tree order, and its index.
    struct Entry {
        std::array<uint32_t, 3> p;
        uint32_t index;
    };
    // One search: the prediction, the gate's two vertices (never candidates), k, and the k best so far
    // in order with the last one's (distance, index) beside them.
    struct Query {
        Query(const std::array<int64_t, 3>& q_, uint32_t a_, uint32_t b_, size_t k_) : q(q_), a(a_), b(b_), k(k_) {}
        const std::array<int64_t, 3>& q;
        uint32_t a, b;
        size_t k;
        struct Item {
            uint64_t d;
            uint32_t i;
        };
        std::array<Item, kRanks> items;  // the first n are set (not zeroed for every search)
        size_t n = 0;
        // The k-th's distance and index once there are k; before, the bound given (no point farther
        // is taken) with the index UINT32_MAX.
        uint64_t worst = UINT64_MAX;
        uint32_t worst_index = UINT32_MAX;
        bool full() const { return n == k; }
        // Whether points at least sqrt(box) away may still be taken (the bound of a split point, or
        // of a side with the index test below).
        bool within(uint64_t box) const { return box <= worst; }
    };
    static void consider(const Entry& e, Query& s) {
        const uint32_t i = e.index;
        if (i == s.a || i == s.b) return;
        const uint64_t d = dist2(e.p, s.q);
        if (d > s.worst || (d == s.worst && i > s.worst_index)) return;
        // Insertion into the sorted items (at most kRanks): shift the larger ones up.
        size_t j = s.full() ? s.n - 1 : s.n++;
        while (j > 0 && (s.items[j - 1].d > d || (s.items[j - 1].d == d && s.items[j - 1].i > i))) {
            s.items[j] = s.items[j - 1];
            --j;
        }
        s.items[j] = {d, i};
        if (s.full()) s.worst = s.items[s.n - 1].d, s.worst_index = s.items[s.n - 1].i;
    }
    // Searches the tree. A subtree over at_[lo, hi) lies at least sqrt(box) from q, where `off` holds
    // the squared distance from q to its box along each axis and `box` their sum (Arya & Mount's
    // incremental distance), a lower bound on the distance of every point in it. The search goes down
    // the nearer side of each split to a leaf, leaving the split point and the farther side on a stack
    // with their bound, and takes them back, last first, while they can hold a point nearer than the
    // k-th, or as near with a lower index. The answer does not depend on the order points are
    // considered in.
    void search(Query& s) const {
        struct Pending {
            uint32_t lo, hi, mid;  // the farther side at_[lo, hi) of the split point at_[mid]
            int axis;              // the axis below the split
            uint64_t box;          // the farther side's bound (and the split point's)
            std::array<uint64_t, 3> off;
        };
        // Depth: one entry a level, a level halving the range (at most 33 for 2^32 points).
        std::array<Pending, 40> stack;
        size_t depth = 0;
        size_t lo = 0, hi = at_.size();
        int axis = 0;
        uint64_t box = 0;
        std::array<uint64_t, 3> off{};
        for (;;) {
            while (hi - lo > kLeaf) {
                const size_t mid = (lo + hi) / 2;
                const int64_t split = at_[mid].p[axis];
                const bool left_first = s.q[axis] <= split;  // on the split: the lower indices first
                const int next = axis == 2 ? 0 : axis + 1;
                // The split point and the other side lie |q - split| away along this axis at least
                // (ties included), and as far as the box along the others.
                const int64_t gap = s.q[axis] - split;
                const uint64_t along = uint64_t(gap * gap);
                const uint64_t far_box = box - off[axis] + along;
                if (s.within(far_box)) {  // else neither can matter, now or later (the bound only tightens)
                    Pending& far = stack[depth++];
                    far.lo = uint32_t(left_first ? mid + 1 : lo);
                    far.hi = uint32_t(left_first ? hi : mid);
                    far.mid = uint32_t(mid);
                    far.axis = next;
                    far.off = off;
                    far.off[axis] = along;
                    far.box = far_box;
                }
                if (!left_first) lo = mid + 1;
                else hi = mid;
                axis = next;
            }
            for (size_t j = lo; j < hi; ++j) consider(at_[j], s);
            // Back up to the first pending side that can still matter.
            for (;;) {
                if (depth == 0) return;
                const Pending& far = stack[--depth];
                if (!s.within(far.box)) continue;
                consider(at_[far.mid], s);
                if (!s.full() || far.box < s.worst || (far.box == s.worst && lowest(far.lo, far.hi) < s.worst_index)) {
                    lo = far.lo, hi = far.hi, axis = far.axis, box = far.box, off = far.off;
                    break;
                }
            }
        }
    }
    // The points in tree order (each subtree a range, its split point at the middle), next to their
    // indices: a search reads them in sequence.
    std::vector<Entry> at_;
    std::vector<uint32_t> min_index_;  // by a subtree's mid: the lowest point index in it
};

// A candidate of a gate as the decoder finds it: its squared distance to the prediction, its number
// in the stream (which orders candidates as far apart: spec 19.2) and its number in the decoder's
// traversal (decode_exact_mesh numbers the points along a Morton curve).
struct Candidate {
    uint64_t d;
    uint32_t order;  // the stream's number
    uint32_t v;      // the traversal's number
    bool operator<(const Candidate& o) const { return d < o.d || (d == o.d && order < o.order); }
};

// The points in the cells of a uniform grid (a cell's points side by side, cells in x, y, z order), for
// the k points nearest to a prediction, by (squared distance, the stream's number) as KdTree::nearest:
// the cell holding it and those around it first, then every cell the ball through the k-th found
// reaches. On a surface sampled about evenly this reads a few cells of a few points each; the grid
// gives up (returns false) where it would read many (points piled in a few cells, a prediction far
// from every point), and the k-d tree answers then.
class PointGrid {
public:
    // Over points p (numbered as the traversal numbers them), where point i is point order[i] of the
    // stream.
    PointGrid(std::span<const std::array<uint32_t, 3>> p, const std::vector<uint32_t>& order) : order_(order) {
        if (p.empty()) return;
        std::array<uint32_t, 3> lo = p[0], hi = p[0];
        for (const auto& q : p)
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
        // The smallest power-of-two cell for which the grid has at most 8 cells a point.
        const uint64_t most = 8 * uint64_t(p.size()) + 64;
        for (shift_ = 0;; ++shift_) {
            uint64_t cells = 1;
            for (int k = 0; k < 3; ++k) n_[k] = int64_t((hi[k] - lo[k]) >> shift_) + 1, cells *= uint64_t(n_[k]);
            if (cells <= most) break;
        }
        for (int k = 0; k < 3; ++k) origin_[k] = lo[k];
        start_.assign(size_t(n_[0] * n_[1] * n_[2]) + 1, 0);
        for (const auto& q : p) ++start_[cell_of(q) + 1];
        for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
        at_.resize(p.size());
        std::vector<uint32_t> next(start_.begin(), start_.end() - 1);
        for (uint32_t i = 0; i < p.size(); ++i) at_[next[cell_of(p[i])]++] = {p[i], i};
    }

    // The k (1..kRanks) points nearest to q other than a and b (the traversal's numbers), nearest
    // first by (squared distance, the stream's number), of those at most sqrt(bound) away
    // (UINT64_MAX: any); false when the grid gives up.
    bool nearest(const std::array<int64_t, 3>& q, uint32_t a, uint32_t b, size_t k, uint64_t bound,
                 std::vector<Candidate>& best) const {
        using Key = Candidate;
        best.clear();
        if (at_.empty() || k == 0 || k > size_t(kRanks)) return false;
        // The k best so far in order; the worst key still taken: the k-th's once there are k, before
        // that the bound.
        std::array<Key, kRanks> items;
        size_t held = 0;
        Key worst{bound, UINT32_MAX, UINT32_MAX};
        size_t read = 0;
        auto scan = [&](int64_t x, int64_t y, int64_t z) {
            const size_t c = index(x, y, z);
            const uint32_t from = start_[c], to = start_[c + 1];
            if (from == to) return true;
            if (read + (to - from) > kMostRead) return false;
            read += to - from;
            // A cell whose box lies farther than the worst key's distance holds nothing to take.
            if (worst.d != UINT64_MAX) {
                uint64_t box = 0;
                const std::array<int64_t, 3> cell{x, y, z};
                for (int i = 0; i < 3; ++i) {
                    const int64_t lo = origin_[i] + (cell[i] << shift_), hi = lo + (int64_t(1) << shift_) - 1;
                    const int64_t g = q[i] < lo ? lo - q[i] : q[i] > hi ? q[i] - hi : 0;
                    box += uint64_t(g * g);
                }
                if (box > worst.d) return true;
            }
            for (uint32_t j = from; j < to; ++j) {
                const Entry& e = at_[j];
                if (e.index == a || e.index == b) continue;
                const uint64_t d = dist2(e.p, q);
                if (d > worst.d) continue;
                const Key key{d, order_[e.index], e.index};  // the stream's number read only here
                if (!(key < worst)) continue;
                if (k == 1) {  // the common case, without the insertion
                    items[0] = worst = key;
                    held = 1;
                    continue;
                }
                size_t at = held < k ? held++ : k - 1;
                for (; at > 0 && key < items[at - 1]; --at) items[at] = items[at - 1];
                items[at] = key;
                if (held == k) worst = items[k - 1];
            }
            return true;
        };
        // q's own cell (when q lies in the grid), then, while fewer than k points are known and no
        // bound is, the cells around it; then every other cell the ball through the worst key reaches.
        std::array<int64_t, 3> cq{}, c0{}, c1{};
        bool inside = true;
        for (int i = 0; i < 3; ++i) {
            cq[i] = (q[i] - origin_[i]) >> shift_;  // floor
            inside = inside && cq[i] >= 0 && cq[i] < n_[i];
            const int64_t c = std::clamp<int64_t>(cq[i], 0, n_[i] - 1);
            c0[i] = std::max<int64_t>(c - 1, 0), c1[i] = std::min<int64_t>(c + 1, n_[i] - 1);
        }
        if (inside && !scan(cq[0], cq[1], cq[2])) return false;
        auto in = [](int64_t x, int64_t y, int64_t z, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& hi) {
            return x >= lo[0] && x <= hi[0] && y >= lo[1] && y <= hi[1] && z >= lo[2] && z <= hi[2];
        };
        const bool block = worst.d == UINT64_MAX;
        if (block)
            for (int64_t z = c0[2]; z <= c1[2]; ++z)
                for (int64_t y = c0[1]; y <= c1[1]; ++y)
                    for (int64_t x = c0[0]; x <= c1[0]; ++x)
                        if (!(inside && x == cq[0] && y == cq[1] && z == cq[2]) && !scan(x, y, z)) return false;
        const uint64_t r2 = worst.d;
        if (r2 == UINT64_MAX) return false;  // fewer than k around q, and no bound: the tree
        // Above the exact radius whatever the rounding (r2 < 2^64; the cells clamp what lies beyond).
        const int64_t r = int64_t(std::min(std::sqrt(double(r2)), 1e15)) + 2;
        std::array<int64_t, 3> r0{}, r1{};
        uint64_t count = 1;
        for (int i = 0; i < 3; ++i) {
            r0[i] = std::clamp<int64_t>((q[i] - origin_[i] - r) >> shift_, 0, n_[i] - 1);  // floor
            r1[i] = std::clamp<int64_t>((q[i] - origin_[i] + r) >> shift_, 0, n_[i] - 1);
            count *= uint64_t(r1[i] - r0[i] + 1);
        }
        if (count > kMostCells) return false;
        for (int64_t z = r0[2]; z <= r1[2]; ++z)
            for (int64_t y = r0[1]; y <= r1[1]; ++y)
                for (int64_t x = r0[0]; x <= r1[0]; ++x) {
                    if ((inside && x == cq[0] && y == cq[1] && z == cq[2]) || (block && in(x, y, z, c0, c1))) continue;
                    if (!scan(x, y, z)) return false;
                }
        if (held < k) return false;
        best.assign(items.begin(), items.begin() + std::ptrdiff_t(k));
        return true;
    }

private:
    static constexpr size_t kMostRead = 512;     // points read by one search before giving up
    static constexpr uint64_t kMostCells = 343;  // cells one search may visit (7 x 7 x 7)
    struct Entry {
        std::array<uint32_t, 3> p;
        uint32_t index;
    };
    size_t index(int64_t x, int64_t y, int64_t z) const { return size_t((z * n_[1] + y) * n_[0] + x); }
    size_t cell_of(const std::array<uint32_t, 3>& p) const {
        return index((p[0] - origin_[0]) >> shift_, (p[1] - origin_[1]) >> shift_, (p[2] - origin_[2]) >> shift_);
    }
    int shift_ = 0;
    std::array<int64_t, 3> origin_{}, n_{};
    std::vector<uint32_t> start_;
    std::vector<Entry> at_;
    const std::vector<uint32_t>& order_;
};

// A k-d tree over the points in the stream's numbering, built when first asked for (a decode the
// grid serves alone builds none).
class LazyKdTree {
public:
    explicit LazyKdTree(const std::vector<QuantizedPoint>& p) : points_(p) {}
    const KdTree& get() const {
        if (!tree_) {
            std::vector<std::array<uint32_t, 3>> positions(points_.size());
            for (size_t i = 0; i < points_.size(); ++i) positions[i] = points_[i].position;
            tree_.emplace(positions);
        }
        return *tree_;
    }

private:
    const std::vector<QuantizedPoint>& points_;
    mutable std::optional<KdTree> tree_;
};

int index_bits(size_t n) {
    int w = 1;
    while (w < 32 && (uint64_t(1) << w) < n) ++w;
    return w;
}

uint64_t edge_key(uint32_t u, uint32_t v) { return (uint64_t(u) << 32) | v; }

struct Gate {
    uint32_t a, b, o;
};

std::array<int64_t, 3> prediction(const std::vector<std::array<uint32_t, 3>>& p, const Gate& g) {
    std::array<int64_t, 3> r;
    for (int k = 0; k < 3; ++k) r[k] = int64_t(p[g.a][k]) + int64_t(p[g.b][k]) - int64_t(p[g.o][k]);
    return r;
}

// The decoder's state, shared by both directions: T, D and Q of spec 19.2.
// The directed edges taken so far, by their first vertex: up to kInPlace of them in place (a closed
// mesh's vertices start about 6 on average), the rest, and any vertex beyond `vertices`, in a
// KeySet. Looking an edge up then reads the memory of its vertex, near that of the vertices the
// traversal has just taken, where a hash of every edge would read anywhere.
class EdgeSet {
public:
    void reset(size_t vertices) {
        lists_.assign(vertices, {});
        overflow_ = KeySet();
    }
    // An edge already held may be inserted again (a non-manifold input): it then takes a second
    // place in the list or goes to the overflow set, and contains() answers the same.
    void insert(uint32_t a, uint32_t b) {
        if (a < lists_.size()) {
            auto& list = lists_[a];
            if (list[0] < kInPlace) {
                list[++list[0]] = b;
                return;
            }
        }
        overflow_.insert(edge_key(a, b));
    }
    bool contains(uint32_t a, uint32_t b) const {
        if (a < lists_.size()) {
            const auto& list = lists_[a];
            for (uint32_t k = 1; k <= list[0]; ++k)
                if (list[k] == b) return true;
            if (list[0] < kInPlace) return false;
        }
        return overflow_.contains(edge_key(a, b));
    }

private:
    static constexpr uint32_t kInPlace = 7;
    std::vector<std::array<uint32_t, kInPlace + 1>> lists_;  // [0]: how many follow
    KeySet overflow_;
};

// The gates waiting, first in first out: a vector read from `head_`, its read part dropped once it is
// half of the vector (each gate moved at most once on average; the vector at most twice the queue).
class GateQueue {
public:
    bool empty() const { return head_ == items_.size(); }
    void push_back(const Gate& g) { items_.push_back(g); }
    Gate pop_front() {
        const Gate g = items_[head_++];
        if (head_ == items_.size()) {
            items_.clear();
            head_ = 0;
        } else if (head_ >= 1024 && 2 * head_ >= items_.size()) {
            items_.erase(items_.begin(), items_.begin() + std::ptrdiff_t(head_));
            head_ = 0;
        }
        return g;
    }

private:
    std::vector<Gate> items_;
    size_t head_ = 0;
};

struct Traversal {
    std::vector<Triangle> triangles;
    EdgeSet edges;
    GateQueue gates;
    void take(uint32_t a, uint32_t b, uint32_t c) {
        triangles.push_back({a, b, c});
        edges.insert(a, b);
        edges.insert(b, c);
        edges.insert(c, a);
        gates.push_back({a, b, c});
        gates.push_back({b, c, a});
        gates.push_back({c, a, b});
    }
};

void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
}
// The header of an exact-layer packet (skippable, per object, version 1.3).
PacketHeader layer_header(PacketType type, uint32_t stream_id, uint32_t sequence, uint16_t object_id) {
    const bool mesh = type == PacketType::ExactMesh || type == PacketType::ExactMeshRepair;
    return skippable_header(type, mesh ? kExactMeshMinor : kConnectivityMinor, stream_id, sequence, object_id);
}

uint32_t get32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

// Pieces and repair symbols of one size (spec 19.6): as few pieces as fit the packets, all as long
// as each other (the last shorter by at most one byte a piece). A repair symbol is then no longer than
// the coded connectivity (a box's 60 bytes had a 1,160-byte symbol), and a lost piece is one source
// symbol lost, never parts of two.
size_t connectivity_piece_size(size_t coded_size, size_t packet_size, bool mesh) {
    const size_t capacity = packet_size - kPacketOverhead - (mesh ? kExactMeshHeaderSize : kConnectivityHeaderSize);
    const size_t k = (coded_size + capacity - 1) / capacity;
    return k == 0 ? capacity : (coded_size + k - 1) / k;
}

}  // namespace

std::vector<uint8_t> encode_connectivity_payload(const ConnectivityPiece& piece, bool mesh) {
    std::vector<uint8_t> out;
    out.reserve(kExactMeshHeaderSize + piece.data.size());
    put32(out, piece.triangle_count);
    if (mesh) put32(out, piece.carried_count);
    put32(out, piece.coded_size);
    put32(out, piece.coded_crc);
    put32(out, piece.offset);
    out.insert(out.end(), piece.data.begin(), piece.data.end());
    return out;
}

Error decode_connectivity_payload(std::span<const uint8_t> payload, ConnectivityPiece& out, bool mesh) {
    const size_t header = mesh ? kExactMeshHeaderSize : kConnectivityHeaderSize;
    if (payload.size() <= header) return Error::MalformedPayload;
    ConnectivityPiece c;
    const uint8_t* p = payload.data();
    c.triangle_count = get32(p);
    if (mesh) c.carried_count = get32(p += 4);
    c.coded_size = get32(p + 4);
    c.coded_crc = get32(p + 8);
    c.offset = get32(p + 12);
    const uint64_t length = payload.size() - header;
    if (c.triangle_count == 0 || uint64_t(c.offset) + length > c.coded_size) return Error::MalformedPayload;
    if (mesh ? c.carried_count == 0 || c.carried_count > kMaxCarriedVertices
             : uint64_t(c.coded_size) > 16 * uint64_t(c.triangle_count) + 64)
        return Error::MalformedPayload;
    c.data.assign(payload.begin() + header, payload.end());
    out = std::move(c);
    return Error::Ok;
}

bool exact_layer_fits(const StreamInfo& info, const ObjectInfo& object, uint32_t triangle_count, uint32_t carried_count,
                      uint32_t coded_size, bool mesh) {
    if (object.kind == ObjectKind::PointSet) return false;
    if (!mesh) return uint64_t(triangle_count) <= 8 * uint64_t(object.point_count);
    const uint64_t vertices = uint64_t(object.point_count) + carried_count;
    // B of spec 7.1, a POINTS record's bits, also for a mapped object.
    uint64_t bits = 3 * uint64_t(info.position_bits);
    if (object.has(kAttrNormal)) bits += 2 * uint64_t(info.normal_bits);
    if (object.has(kAttrTexcoord)) bits += 2 * uint64_t(info.texcoord_bits);
    if (object.has(kAttrColor)) bits += (object.has(kAttrColorAlpha) ? 4 : 3) * uint64_t(info.color_bits);
    const uint64_t record_bytes = (bits + 7) / 8;
    return uint64_t(triangle_count) <= 8 * vertices &&
           uint64_t(coded_size) <= 16 * uint64_t(triangle_count) + (16 + record_bytes) * carried_count + 64;
}

Error packetize_connectivity(const StreamInfo& info, uint16_t object_id, uint32_t triangle_count,
                             const std::vector<uint8_t>& coded, uint32_t stream_id, uint32_t first_sequence,
                             std::vector<std::vector<uint8_t>>& out, uint32_t carried_count) {
    const bool mesh = carried_count > 0;
    if (coded.empty() || (!mesh && coded.size() > 16 * uint64_t(triangle_count) + 64) ||
        info.packet_size <= kPacketOverhead + kExactMeshHeaderSize)
        return Error::MalformedPayload;
    const size_t per_packet = connectivity_piece_size(coded.size(), info.packet_size, mesh);
    ConnectivityPiece piece;
    piece.triangle_count = triangle_count;
    piece.carried_count = carried_count;
    piece.coded_size = uint32_t(coded.size());
    piece.coded_crc = crc32c(coded.data(), coded.size());
    uint32_t sequence = first_sequence;
    for (size_t offset = 0; offset < coded.size(); offset += per_packet) {
        piece.offset = uint32_t(offset);
        piece.data.assign(coded.begin() + offset, coded.begin() + std::min(coded.size(), offset + per_packet));
        out.push_back(write_packet(layer_header(mesh ? PacketType::ExactMesh : PacketType::Connectivity, stream_id,
                                                sequence++, object_id),
                                   encode_connectivity_payload(piece, mesh)));
    }
    return Error::Ok;
}

std::vector<uint8_t> encode_connectivity_repair_payload(const ConnectivityRepair& r, bool mesh) {
    std::vector<uint8_t> out;
    out.reserve(20 + r.symbol.size());
    put32(out, r.triangle_count);
    if (mesh) put32(out, r.carried_count);
    put32(out, r.coded_size);
    put32(out, r.coded_crc);
    out.push_back(uint8_t(r.symbol_size));
    out.push_back(uint8_t(r.symbol_size >> 8));
    out.push_back(r.row);
    out.push_back(0);
    out.insert(out.end(), r.symbol.begin(), r.symbol.end());
    return out;
}

Error decode_connectivity_repair_payload(std::span<const uint8_t> payload, ConnectivityRepair& out, bool mesh) {
    const size_t header = mesh ? kExactMeshHeaderSize : kConnectivityHeaderSize;
    if (payload.size() < header) return Error::MalformedPayload;
    ConnectivityRepair r;
    const uint8_t* p = payload.data();
    r.triangle_count = get32(p);
    if (mesh) r.carried_count = get32(p += 4);
    r.coded_size = get32(p + 4);
    r.coded_crc = get32(p + 8);
    r.symbol_size = uint16_t(p[12] | (p[13] << 8));
    r.row = p[14];
    if (r.triangle_count == 0 || r.coded_size == 0 || r.symbol_size == 0 || payload.size() != header + size_t(r.symbol_size))
        return Error::MalformedPayload;
    if (mesh ? r.carried_count == 0 || r.carried_count > kMaxCarriedVertices
             : uint64_t(r.coded_size) > 16 * uint64_t(r.triangle_count) + 64)
        return Error::MalformedPayload;
    const uint64_t k = (uint64_t(r.coded_size) + r.symbol_size - 1) / r.symbol_size;
    if (k > 254 || r.row < k) return Error::MalformedPayload;
    r.symbol.assign(payload.begin() + header, payload.end());
    out = std::move(r);
    return Error::Ok;
}

// The source symbols of spec 19.5: the coded connectivity cut into `size`-byte symbols, the last padded.
std::vector<std::vector<uint8_t>> connectivity_symbols(const std::vector<uint8_t>& coded, size_t size) {
    std::vector<std::vector<uint8_t>> out;
    for (size_t at = 0; at < coded.size(); at += size) {
        std::vector<uint8_t> s(coded.begin() + at, coded.begin() + std::min(coded.size(), at + size));
        s.resize(size, 0);
        out.push_back(std::move(s));
    }
    return out;
}

Error packetize_connectivity_repairs(const StreamInfo& info, uint16_t object_id, uint32_t triangle_count,
                                     const std::vector<uint8_t>& coded, size_t count, uint32_t stream_id,
                                     uint32_t first_sequence, std::vector<std::vector<uint8_t>>& out,
                                     uint32_t carried_count) {
    const bool mesh = carried_count > 0;
    if (coded.empty() || info.packet_size <= kPacketOverhead + kExactMeshHeaderSize) return Error::MalformedPayload;
    const size_t size = connectivity_piece_size(coded.size(), info.packet_size, mesh);
    const auto sources = connectivity_symbols(coded, size);
    const size_t k = sources.size();
    if (k > 127 || k + count > 255) return Error::MalformedPayload;
    ConnectivityRepair r;
    r.triangle_count = triangle_count;
    r.carried_count = carried_count;
    r.coded_size = uint32_t(coded.size());
    r.coded_crc = crc32c(coded.data(), coded.size());
    r.symbol_size = uint16_t(size);
    uint32_t sequence = first_sequence;
    for (size_t row = k; row < k + count; ++row) {
        r.row = uint8_t(row);
        r.symbol = repair_symbol(sources, unsigned(row));
        out.push_back(write_packet(layer_header(mesh ? PacketType::ExactMeshRepair : PacketType::ConnectivityRepair,
                                                stream_id, sequence++, object_id),
                                   encode_connectivity_repair_payload(r, mesh)));
    }
    return Error::Ok;
}

Error check_connectivity_repair_packet(const ReceivedStream& stream, const PacketView& packet, std::string& why) {
    return ConnectivityRepairChecker(stream).check(packet, why);
}

Error ConnectivityRepairChecker::check(const PacketView& packet, std::string& why) {
    ConnectivityRepair r;
    const bool mesh = packet.header.type == static_cast<uint8_t>(PacketType::ExactMeshRepair);
    if (decode_connectivity_repair_payload(packet.payload, r, mesh) != Error::Ok) return Error::MalformedPayload;
    const uint16_t id = packet.header.object_id;
    if (id >= stream_.objects().size()) return Error::MalformedPayload;
    const auto& c = stream_.objects()[id].connectivity;
    if (!c || !c->complete || c->coded_size != r.coded_size || c->coded_crc != r.coded_crc) return Error::Ok;
    auto [it, fresh] = objects_.try_emplace(id);
    ObjectState& state = it->second;
    if (fresh) {
        state.symbol_size = r.symbol_size;
        state.sources = connectivity_symbols(c->coded, r.symbol_size);
    }
    if (r.symbol_size != state.symbol_size) {  // spec 19.5: one symbol size, the pieces'
        why = "object " + std::to_string(id) + ": a symbol size of " + std::to_string(r.symbol_size) +
              " bytes where its first CONNECTIVITY_REPAIR packet has " + std::to_string(state.symbol_size);
        return Error::StreamMismatch;
    }
    auto row = state.rows.find(r.row);
    if (row == state.rows.end()) row = state.rows.emplace(r.row, repair_symbol(state.sources, r.row)).first;
    if (row->second == r.symbol) return Error::Ok;
    why = "object " + std::to_string(id) + ": the symbol of row " + std::to_string(r.row) +
          " is not that row of the code over its connectivity";
    return Error::StreamMismatch;
}

Error exact_layer(const ReceivedStream& stream, size_t object, std::vector<Triangle>& out,
                  std::vector<QuantizedPoint>& carried, std::string& why) {
    if (object >= stream.objects().size()) {
        why = "no such object";
        return Error::UnknownObject;
    }
    const ReceivedObject& o = stream.objects()[object];
    if (!o.info || !o.connectivity || !o.connectivity->complete) {
        why = "its exact layer has not all arrived";
        return Error::Truncated;
    }
    if (o.points.size() != o.info->point_count) {
        why = std::to_string(o.points.size()) + " of its " + std::to_string(o.info->point_count) + " points arrived";
        return Error::Truncated;
    }
    carried.clear();
    if (!o.connectivity->mesh) {
        std::vector<std::array<uint32_t, 3>> positions;
        positions.reserve(o.points.size());
        for (const auto& [index, p] : o.points) positions.push_back(p.position);
        return decode_connectivity(o.connectivity->coded, o.connectivity->triangle_count, positions, out, why);
    }
    std::vector<QuantizedPoint> points;
    points.reserve(o.points.size());
    for (const auto& [index, p] : o.points) points.push_back(p);
    return decode_exact_mesh(o.connectivity->coded, o.connectivity->triangle_count, o.connectivity->carried_count,
                             points, *stream.info(), *o.info, out, carried, why);
}

Error exact_triangles(const ReceivedStream& stream, size_t object, std::vector<Triangle>& out, std::string& why) {
    std::vector<QuantizedPoint> carried;
    return exact_layer(stream, object, out, carried, why);
}

namespace {

// The direct fields of a carried vertex (spec 27.2): its normal, then its colour; its texture
// coordinates, between them in a POINTS record, travel as a displacement.
std::vector<int> direct_widths(const StreamInfo& info, const ObjectInfo& object, bool normal) {
    std::vector<int> w;
    if (normal && object.has(kAttrNormal)) w.insert(w.end(), 2, info.normal_bits);
    if (!normal && object.has(kAttrColor)) w.insert(w.end(), object.has(kAttrColorAlpha) ? 4 : 3, info.color_bits);
    return w;
}
uint32_t* direct_fields(QuantizedPoint& q, bool normal) { return normal ? q.normal.data() : q.color.data(); }

// The neighbour lists C(v) of spec 27.2: per vertex, at most 16 carried vertices joined to it.
class CarriedNeighbours {
public:
    CarriedNeighbours(size_t vertices, size_t n) : lists_(n == vertices ? 0 : vertices), n_(n) {}
    void join(uint32_t u, uint32_t v) {
        if (lists_.empty()) return;  // no carried vertex: every list stays empty
        add(u, v);
        add(v, u);
    }
    // Spec 27.2, step 4: C(a) then C(b), each once, without a and b, by (squared distance to r, index).
    void local(uint32_t a, uint32_t b, const std::array<int64_t, 3>& r, const std::vector<std::array<uint32_t, 3>>& p,
               std::vector<std::pair<uint64_t, uint32_t>>& out) const {
        out.clear();
        if (lists_.empty()) return;
        for (uint32_t from : {a, b})
            for (uint32_t v : lists_[from]) {
                if (v == a || v == b) continue;
                bool seen = false;
                for (const auto& e : out) seen |= e.second == v;
                if (seen) continue;
                out.emplace_back(dist2(p[v], r), v);
            }
        std::sort(out.begin(), out.end());
    }

private:
    void add(uint32_t u, uint32_t v) {
        if (v < n_) return;
        auto& list = lists_[u];
        if (list.size() >= size_t(kListMax) || std::find(list.begin(), list.end(), v) != list.end()) return;
        list.push_back(v);
    }
    std::vector<std::vector<uint32_t>> lists_;
    size_t n_;
};

// Taking a triangle (spec 19.2, and 27.2's neighbour lists).
void take_triangle(Traversal& tr, CarriedNeighbours& lists, uint32_t a, uint32_t b, uint32_t c) {
    tr.take(a, b, c);
    lists.join(a, b);
    lists.join(b, c);
    lists.join(c, a);
}

// Spec 27.2: the context of a gate's bit fresh, by the number k of its local candidates.
size_t fresh_context(size_t k) { return std::min<size_t>(k, 2); }

// The decoder's two numberings of an object's vertices: the stream's, and the traversal's (the
// points along a Morton curve of their positions). Point i of the traversal is point stream_of[i] of
// the stream, point j of the stream is point inside[j] of the traversal; a carried vertex (numbered
// from the point count on) keeps its number in both.
struct Numbering {
    std::vector<uint32_t> stream_of, inside;
    uint32_t to_stream(uint32_t v) const { return v < stream_of.size() ? stream_of[v] : v; }
    uint32_t to_inside(uint32_t v) const { return v < inside.size() ? inside[v] : v; }
};

// Spec 27.2 (19.2 when nothing is carried): the first `k` candidates of a gate, the points nearest
// to the prediction and its local candidates (carried vertices) together, by (squared distance,
// the stream's number). `a`, `b`: the gate's corners in the traversal's numbering; `bound` as
// KdTree::nearest's.
void candidates(const LazyKdTree& tree, const PointGrid& grid, const Numbering& numbers,
                const std::array<int64_t, 3>& r, uint32_t a, uint32_t b, uint64_t bound, size_t k,
                const std::vector<std::pair<uint64_t, uint32_t>>& local, std::vector<Candidate>& out) {
    if (!grid.nearest(r, a, b, k, bound, out)) {
        std::vector<std::pair<uint64_t, uint32_t>> found;  // a rare path: 17 of the bunny's 69,436 searches
        tree.get().nearest(r, numbers.to_stream(a), numbers.to_stream(b), k, found, bound);
        out.clear();
        for (const auto& [d, j] : found) out.push_back({d, j, numbers.to_inside(j)});
    }
    if (local.empty()) return;
    for (const auto& [d, v] : local) out.push_back({d, v, v});
    std::sort(out.begin(), out.end());
    if (out.size() > k) out.resize(k);
}

// The rank (1..kRanks) of vertex x among the candidates() of a gate, 0 when it is not one of
// them: one more than the candidates that come before it, counted rather than listed.
int candidate_rank(const KdTree& tree, const std::array<int64_t, 3>& r, const Gate& g,
                   const std::vector<std::pair<uint64_t, uint32_t>>& local,
                   const std::vector<std::array<uint32_t, 3>>& positions, uint32_t x) {
    if (x == g.a || x == g.b) return 0;
    const uint64_t d = dist2(positions[x], r);
    const std::pair<uint64_t, uint32_t> key(d, x);
    // x is a point (in the tree) or a carried vertex, a candidate only from its gate's local list.
    bool listed = x < tree.size();
    size_t before = 0;
    for (const auto& item : local) {
        listed = listed || item.second == x;
        before += item < key;
    }
    if (!listed) return 0;
    before += tree.count_before(r, g.a, g.b, d, x, kRanks);
    return before < size_t(kRanks) ? int(before) + 1 : 0;
}

int bit_length(uint64_t u) {
    int c = 0;
    while (u >> c) ++c;
    return c;
}

using LengthSets = std::array<std::array<uint16_t, kLengths>, 10>;

// Spec 27.2: `dims` values as displacements from `r`, with the length sets and sign given.
void encode_displacement(RangeEncoder& rc, LengthSets& lengths, uint16_t& sign, const uint32_t* q, const int64_t* r,
                         int dims) {
    size_t set = 0;
    for (int k = 0; k < dims; ++k) {
        const int64_t d = int64_t(q[k]) - r[k];
        const uint64_t u = uint64_t(d < 0 ? -d : d);
        const int c = bit_length(u);  // < 18: |d| < 2^17 (spec 27.2)
        auto& length = lengths[set];
        for (int i = 0; i < c; ++i) rc.bit(length[i], 0);
        rc.bit(length[c], 1);
        set = 1 + std::min(c, 8);
        if (c == 0) continue;
        rc.bit(sign, d < 0 ? 1 : 0);
        if (c > 1) rc.direct(uint32_t(u - (uint64_t(1) << (c - 1))), c - 1);
    }
}
bool decode_displacement(RangeDecoder& rc, LengthSets& lengths, uint16_t& sign, uint32_t* q, const int64_t* r, int dims,
                         int bits) {
    size_t set = 0;
    for (int k = 0; k < dims; ++k) {
        int c = -1;
        for (int i = 0; i < kLengths && c < 0; ++i)
            if (rc.bit(lengths[set][i])) c = i;
        if (c < 0) return false;
        set = 1 + size_t(std::min(c, 8));
        int64_t d = 0;
        if (c > 0) {
            const bool negative = rc.bit(sign) != 0;
            const int64_t u = (int64_t(1) << (c - 1)) + int64_t(c > 1 ? rc.direct(c - 1) : 0);
            d = negative ? -u : u;
        }
        const int64_t v = r[k] + d;
        if (v < 0 || v >= (int64_t(1) << bits)) return false;
        q[k] = uint32_t(v);
    }
    return true;
}

// A fresh vertex's predictions (spec 27.2): position and texture coordinates.
struct Prediction {
    std::array<int64_t, 3> position{};
    std::array<int64_t, 2> texcoord{};
};

// Spec 27.2: a fresh vertex's position and attributes; false when unusable (outside the frame or the
// texture-coordinate range).
bool decode_fresh(RangeDecoder& rc, Contexts& ctx, const Prediction& r, const StreamInfo& info, const ObjectInfo& object,
                  QuantizedPoint& q) {
    q = QuantizedPoint{};
    if (!decode_displacement(rc, ctx.length, ctx.sign, q.position.data(), r.position.data(), 3, info.position_bits))
        return false;
    for (const bool normal : {true, false}) {
        const std::vector<int> widths = direct_widths(info, object, normal);
        for (size_t f = 0; f < widths.size(); ++f) direct_fields(q, normal)[f] = rc.direct(widths[f]);
        if (normal && object.has(kAttrTexcoord) &&
            !decode_displacement(rc, ctx.uv_length, ctx.uv_sign, q.texcoord.data(), r.texcoord.data(), 2,
                                 info.texcoord_bits))
            return false;
    }
    return true;
}

// The prediction at a gate (a, b, o) and at a seed's corner (spec 27.2).
// `position`: the gate's prediction(), computed once for its candidates too.
Prediction gate_prediction(const std::array<int64_t, 3>& position, const std::vector<std::array<uint32_t, 2>>& uv,
                           const Gate& g) {
    Prediction r;
    r.position = position;
    for (int k = 0; k < 2; ++k) r.texcoord[k] = int64_t(uv[g.a][k]) + int64_t(uv[g.b][k]) - int64_t(uv[g.o][k]);
    return r;
}
Prediction seed_prediction(const StreamInfo& info, const std::vector<std::array<uint32_t, 3>>& p,
                           const std::vector<std::array<uint32_t, 2>>& uv, int corner, uint32_t previous) {
    Prediction r;
    for (int k = 0; k < 3; ++k)
        r.position[k] = corner == 0 ? int64_t(1) << (info.position_bits - 1) : int64_t(p[previous][k]);
    for (int k = 0; k < 2; ++k)
        r.texcoord[k] = corner == 0 ? int64_t(1) << (info.texcoord_bits - 1) : int64_t(uv[previous][k]);
    return r;
}

}  // namespace

Error encode_exact_mesh(const std::vector<QuantizedPoint>& vertices, size_t n, const std::vector<Triangle>& input,
                        const StreamInfo& info, const ObjectInfo& object, std::vector<uint8_t>& coded,
                        std::vector<Triangle>& sent, std::vector<uint32_t>& carried_order) {
    const size_t total = vertices.size();
    if (n > total || total > n + kMaxCarriedVertices) return Error::MalformedPayload;
    for (const Triangle& t : input)
        if (t[0] >= total || t[1] >= total || t[2] >= total || t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            return Error::MalformedPayload;
    if (input.empty() || total < 3) return Error::MalformedPayload;
    const uint32_t carried = uint32_t(total - n);
    // The input's triangles, by their directed edges (a triangle is found by any of its three,
    // rotated so that edge comes first): (edge key, triangle) sorted, so that the triangles of one
    // edge are together and in input order.
    std::vector<std::pair<uint64_t, uint32_t>> by_edge;
    by_edge.reserve(input.size() * 3);
    for (uint32_t t = 0; t < input.size(); ++t)
        for (int k = 0; k < 3; ++k) by_edge.emplace_back(edge_key(input[t][k], input[t][(k + 1) % 3]), t);
    std::sort(by_edge.begin(), by_edge.end());
    std::vector<bool> done(input.size(), false);
    size_t next_seed = 0;
    const int w = index_bits(total);
    // Decoder numbering: points keep theirs, carried vertices n, n + 1, ... as introduced.
    std::vector<uint32_t> id(total, UINT32_MAX);
    for (uint32_t i = 0; i < n; ++i) id[i] = i;
    std::vector<std::array<uint32_t, 3>> positions(total);
    std::vector<std::array<uint32_t, 2>> texcoords(total);
    for (size_t i = 0; i < n; ++i) {
        positions[i] = vertices[i].position;
        texcoords[i] = vertices[i].texcoord;
    }
    const std::vector<std::array<uint32_t, 3>> point_positions(positions.begin(), positions.begin() + long(n));
    const KdTree tree(point_positions);
    CarriedNeighbours lists(total, n);
    RangeEncoder rc;
    Contexts ctx;
    Traversal tr;
    tr.edges.reset(total);
    std::vector<std::pair<uint64_t, uint32_t>> near;
    carried_order.clear();
    uint32_t m = 0;
    // A carried vertex not yet introduced: the bit fresh 1, its displacement and attributes.
    auto introduce = [&](uint32_t v, const Prediction& r, size_t fresh_context) {
        rc.bit(ctx.fresh[fresh_context], 1);
        QuantizedPoint q = vertices[v];
        encode_displacement(rc, ctx.length, ctx.sign, q.position.data(), r.position.data(), 3);
        for (const bool normal : {true, false}) {
            const std::vector<int> widths = direct_widths(info, object, normal);
            for (size_t f = 0; f < widths.size(); ++f) rc.direct(direct_fields(q, normal)[f], widths[f]);
            if (normal && object.has(kAttrTexcoord))
                encode_displacement(rc, ctx.uv_length, ctx.uv_sign, q.texcoord.data(), r.texcoord.data(), 2);
        }
        id[v] = uint32_t(n) + m++;
        positions[id[v]] = q.position;
        texcoords[id[v]] = q.texcoord;
        carried_order.push_back(v);
    };
    while (tr.triangles.size() < input.size()) {
        if (tr.gates.empty()) {
            while (done[next_seed]) ++next_seed;
            const Triangle& t = input[next_seed];
            std::array<uint32_t, 3> corner{};
            for (int k = 0; k < 3; ++k) {
                const uint32_t v = t[k];
                if (id[v] == UINT32_MAX) {
                    introduce(v, seed_prediction(info, positions, texcoords, k, k > 0 ? corner[k - 1] : 0), 0);
                } else {
                    if (m < carried) rc.bit(ctx.fresh[0], 0);
                    rc.direct(id[v], w);
                }
                corner[k] = id[v];
            }
            done[next_seed] = true;
            take_triangle(tr, lists, corner[0], corner[1], corner[2]);
            continue;
        }
        const Gate g = tr.gates.pop_front();
        if (tr.edges.contains(g.b, g.a)) continue;
        // The first input triangle not yet coded with the directed edge b->a (in decoder numbering;
        // a and b are known, so their input indices are found through carried_order).
        const uint32_t in_a = g.a < n ? g.a : carried_order[g.a - n], in_b = g.b < n ? g.b : carried_order[g.b - n];
        int64_t found = -1;
        uint32_t x = 0;
        const uint64_t wanted = edge_key(in_b, in_a);
        for (auto it = std::lower_bound(by_edge.begin(), by_edge.end(), std::make_pair(wanted, uint32_t(0)));
             it != by_edge.end() && it->first == wanted; ++it)
            if (const uint32_t t = it->second; !done[t]) {
                    found = t;
                    for (int k = 0; k < 3; ++k)
                        if (input[t][k] == in_b && input[t][(k + 1) % 3] == in_a) x = input[t][(k + 2) % 3];
                    break;
                }
        rc.bit(ctx.none, found < 0 ? 1 : 0);
        if (found < 0) continue;
        done[size_t(found)] = true;
        const std::array<int64_t, 3> r = prediction(positions, g);
        lists.local(g.a, g.b, r, positions, near);
        const size_t context = fresh_context(near.size());
        if (id[x] == UINT32_MAX) {
            introduce(x, gate_prediction(r, texcoords, g), context);
            take_triangle(tr, lists, g.b, g.a, id[x]);
            continue;
        }
        if (m < carried) rc.bit(ctx.fresh[context], 0);
        const uint32_t xv = id[x];
        const int rank = candidate_rank(tree, r, g, near, positions, xv);
        for (int k = 1; k <= kRanks; ++k) {
            rc.bit(ctx.rank[k - 1], k == rank ? 1 : 0);
            if (k == rank) break;
        }
        if (rank == 0) rc.direct(xv, w);
        take_triangle(tr, lists, g.b, g.a, xv);
    }
    if (m != carried) return Error::MalformedPayload;  // a carried vertex no triangle uses
    coded = rc.finish();
    sent = std::move(tr.triangles);
    return Error::Ok;
}

Error decode_exact_mesh(std::span<const uint8_t> coded, uint32_t triangle_count, uint32_t carried_count,
                        const std::vector<QuantizedPoint>& points, const StreamInfo& info, const ObjectInfo& object,
                        std::vector<Triangle>& out, std::vector<QuantizedPoint>& carried, std::string& why) {
    const size_t n = points.size();
    const size_t total = n + carried_count;
    if (total < 3 || triangle_count == 0 || triangle_count > 8 * uint64_t(total) || carried_count > kMaxCarriedVertices) {
        why = "the triangle count does not fit the object's vertices";
        return Error::MalformedPayload;
    }
    const int w = index_bits(total);
    // The traversal numbers the points along a Morton curve of their positions (Numbering), so that a
    // gate's vertices, which are neighbours on the surface, lie near each other in memory (the
    // stream's order spreads them over the surface). Every number read, the candidates' order and the
    // triangles given back stay in the stream's numbering.
    Numbering numbers{std::vector<uint32_t>(n), std::vector<uint32_t>(n)};
    {
        // By (code, stream number): a least-significant-digit radix sort of the codes (3
        // position_bits bits, at most 48), stable, from the stream's order.
        std::vector<std::pair<uint64_t, uint32_t>> curve(n), scratch(n);
        for (uint32_t i = 0; i < n; ++i)
            curve[i] = {morton_cell(points[i].position, info.position_bits, info.position_bits), i};
        constexpr unsigned kDigit = 12;
        constexpr uint64_t mask = (uint64_t(1) << kDigit) - 1;
        std::vector<uint32_t> count(size_t(1) << kDigit);
        for (unsigned low = 0; low < 3u * info.position_bits; low += kDigit) {
            std::fill(count.begin(), count.end(), 0);
            for (const auto& e : curve) ++count[(e.first >> low) & mask];
            uint32_t sum = 0;
            for (uint32_t& c : count) sum += std::exchange(c, sum);
            for (const auto& e : curve) scratch[count[(e.first >> low) & mask]++] = e;
            curve.swap(scratch);
        }
        for (uint32_t j = 0; j < n; ++j) {
            numbers.stream_of[j] = curve[j].second;
            numbers.inside[curve[j].second] = j;
        }
    }
    std::vector<std::array<uint32_t, 3>> positions;
    std::vector<std::array<uint32_t, 2>> texcoords;
    positions.reserve(total);
    texcoords.reserve(total);
    for (uint32_t j = 0; j < n; ++j) {
        positions.push_back(points[numbers.stream_of[j]].position);
        texcoords.push_back(points[numbers.stream_of[j]].texcoord);
    }
    const PointGrid grid(std::span(positions.data(), n), numbers.stream_of);
    const LazyKdTree tree(points);  // built for the first search the grid gives up
    CarriedNeighbours lists(total, n);
    RangeDecoder rc(coded);
    Contexts ctx;
    Traversal tr;
    tr.triangles.reserve(triangle_count);
    // In place for the points and as many carried vertices (a claimed carried count is only a
    // claim: the others' edges go to the table, which grows with the triangles actually taken).
    tr.edges.reset(std::min<size_t>(total, 2 * n + 4096));
    std::vector<QuantizedPoint> fresh_vertices;
    std::vector<Candidate> best;
    std::vector<std::pair<uint64_t, uint32_t>> near;
    auto fresh = [&](const Prediction& r, uint32_t& v) {
        QuantizedPoint q;
        if (!decode_fresh(rc, ctx, r, info, object, q)) {
            why = "carried vertex " + std::to_string(n + fresh_vertices.size()) +
                  " lies outside the frame or the texture-coordinate range, or its displacement has no length";
            return false;
        }
        v = uint32_t(n + fresh_vertices.size());
        positions.push_back(q.position);
        texcoords.push_back(q.texcoord);
        fresh_vertices.push_back(q);
        return true;
    };
    while (tr.triangles.size() < triangle_count) {
        const size_t known = n + fresh_vertices.size();
        const bool may_be_fresh = fresh_vertices.size() < carried_count;
        if (tr.gates.empty()) {
            std::array<uint32_t, 3> corner{};
            for (int k = 0; k < 3; ++k) {
                if (fresh_vertices.size() < carried_count && rc.bit(ctx.fresh[0])) {
                    if (!fresh(seed_prediction(info, positions, texcoords, k, k > 0 ? corner[k - 1] : 0), corner[k]))
                        return Error::MalformedPayload;
                    continue;
                }
                const uint32_t read = rc.direct(w);
                const size_t now_known = n + fresh_vertices.size();
                corner[k] = read < now_known ? numbers.to_inside(read) : read;
                if (read >= now_known || (k > 0 && corner[k] == corner[0]) || (k > 1 && corner[k] == corner[1])) {
                    why = "seed triangle " + std::to_string(tr.triangles.size()) + " names vertex " +
                          std::to_string(read) + " of " + std::to_string(now_known) + " known, or one twice";
                    return Error::MalformedPayload;
                }
            }
            take_triangle(tr, lists, corner[0], corner[1], corner[2]);
            continue;
        }
        const Gate g = tr.gates.pop_front();
        if (tr.edges.contains(g.b, g.a)) continue;
        if (rc.bit(ctx.none)) continue;
        const std::array<int64_t, 3> r = prediction(positions, g);
        uint32_t x = 0;
        lists.local(g.a, g.b, r, positions, near);
        if (may_be_fresh && rc.bit(ctx.fresh[fresh_context(near.size())])) {
            if (!fresh(gate_prediction(r, texcoords, g), x)) return Error::MalformedPayload;
            take_triangle(tr, lists, g.b, g.a, x);
            continue;
        }
        int rank = 0;
        for (int k = 1; k <= kRanks && rank == 0; ++k)
            if (rc.bit(ctx.rank[k - 1])) rank = k;
        if (rank > 0) {
            // The nearest point lies at most as far from r as the gate's third corner o when o is a
            // point (never a or b): a bound that spares the search most cells.
            const uint64_t bound = rank == 1 && g.o < n ? dist2(positions[g.o], r) : UINT64_MAX;
            candidates(tree, grid, numbers, r, g.a, g.b, bound, size_t(rank), near, best);
            if (best.size() < size_t(rank)) {
                why = "a rank past the gate's candidates";
                return Error::MalformedPayload;
            }
            x = best[size_t(rank) - 1].v;
        } else {
            const uint32_t read = rc.direct(w);
            x = read < known ? numbers.to_inside(read) : read;
            if (read >= known || x == g.a || x == g.b) {
                why = "triangle " + std::to_string(tr.triangles.size()) + " names vertex " + std::to_string(read) +
                      " of " + std::to_string(known) + " known beside " + std::to_string(numbers.to_stream(g.b)) +
                      " and " + std::to_string(numbers.to_stream(g.a));
                return Error::MalformedPayload;
            }
        }
        take_triangle(tr, lists, g.b, g.a, x);
    }
    if (fresh_vertices.size() != carried_count) {
        why = std::to_string(carried_count - fresh_vertices.size()) + " of its " + std::to_string(carried_count) +
              " carried vertices are used by no triangle";
        return Error::MalformedPayload;
    }
    for (Triangle& t : tr.triangles)
        for (uint32_t& v : t) v = numbers.to_stream(v);
    out = std::move(tr.triangles);
    carried = std::move(fresh_vertices);
    return Error::Ok;
}

Error encode_connectivity(const std::vector<std::array<uint32_t, 3>>& positions, const std::vector<Triangle>& input,
                          std::vector<uint8_t>& coded, std::vector<Triangle>& sent) {
    std::vector<QuantizedPoint> points(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) points[i].position = positions[i];
    StreamInfo info;
    ObjectInfo object;
    std::vector<uint32_t> carried_order;
    return encode_exact_mesh(points, points.size(), input, info, object, coded, sent, carried_order);
}

Error decode_connectivity(std::span<const uint8_t> coded, uint32_t triangle_count,
                          const std::vector<std::array<uint32_t, 3>>& positions, std::vector<Triangle>& out,
                          std::string& why) {
    const size_t n = positions.size();
    if (n < 3 || triangle_count == 0 || triangle_count > 8 * uint64_t(n)) {
        why = "the triangle count does not fit the object's points";
        return Error::MalformedPayload;
    }
    std::vector<QuantizedPoint> points(n), carried;
    for (size_t i = 0; i < n; ++i) points[i].position = positions[i];
    return decode_exact_mesh(coded, triangle_count, 0, points, StreamInfo{}, ObjectInfo{}, out, carried, why);
}

}  // namespace ellicast

// Choosing ellipsoids among the candidates (Bischoff & Kobbelt 2002, section 3.2): greedy set
// cover on a voxel grid. Each candidate is rasterized once into runs of voxels; the gain of a
// candidate is a popcount of the still-uncovered interior bits under its runs; gains only shrink,
// so a lazy priority queue re-evaluates few of them. Then a second greedy pass covers surface
// samples that are still far from every chosen ellipsoid (thin parts such as ears and fins).
#include "encoder_internal.h"

#include "ellicast/format/bits.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <queue>
#include <thread>

namespace ellicast::detail {

std::vector<Span> rasterize(const VoxelGrid& grid, const Candidate& e, double inflate) {
    std::vector<Span> spans;
    Vec3 r = e.radii + Vec3::Constant(inflate);
    if (!(r.minCoeff() > 0)) return spans;
    Eigen::Matrix3d A = e.axes * r.cwiseInverse().cwiseAbs2().asDiagonal() * e.axes.transpose();
    Vec3 half;
    for (int k = 0; k < 3; ++k) half[k] = (e.axes.row(k).transpose().cwiseProduct(r)).norm();
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
        lo[k] = std::max(0, int(std::ceil((e.center[k] - half[k] - grid.origin[k]) / grid.h)));
        hi[k] = std::min(grid.n[k] - 1, int(std::floor((e.center[k] + half[k] - grid.origin[k]) / grid.h)));
    }
    if (A(0, 0) <= 0) return spans;
    for (int z = lo[2]; z <= hi[2]; ++z) {
        double dz = grid.origin[2] + z * grid.h - e.center.z();
        for (int y = lo[1]; y <= hi[1]; ++y) {
            double dy = grid.origin[1] + y * grid.h - e.center.y();
            double b = A(0, 1) * dy + A(0, 2) * dz;
            double c = A(1, 1) * dy * dy + 2 * A(1, 2) * dy * dz + A(2, 2) * dz * dz - 1;
            double disc = b * b - A(0, 0) * c;
            if (disc < 0) continue;
            double s = std::sqrt(disc);
            double t0 = (-b - s) / A(0, 0), t1 = (-b + s) / A(0, 0);
            int x0 = std::max(0, int(std::ceil((e.center.x() + t0 - grid.origin[0]) / grid.h)));
            int x1 = std::min(grid.n[0] - 1, int(std::floor((e.center.x() + t1 - grid.origin[0]) / grid.h)));
            if (x1 < x0) continue;
            spans.push_back({uint32_t(y + size_t(z) * grid.n[1]), uint16_t(x0), uint16_t(x1 + 1)});
        }
    }
    return spans;
}

VoxelBits::VoxelBits(const VoxelGrid& grid, bool value)
    : words_per_row_((size_t(grid.n[0]) + 63) / 64), bits_(words_per_row_ * grid.n[1] * grid.n[2], 0) {
    if (value)
        for (size_t row = 0; row < size_t(grid.n[1]) * grid.n[2]; ++row)
            for (int x = 0; x < grid.n[0]; ++x) set(x, row, true);
}

void VoxelBits::set(size_t x, size_t row, bool v) {
    uint64_t& w = bits_[row * words_per_row_ + x / 64];
    uint64_t m = uint64_t(1) << (x % 64);
    w = v ? (w | m) : (w & ~m);
}

bool VoxelBits::get(size_t x, size_t row) const { return bits_[row * words_per_row_ + x / 64] >> (x % 64) & 1; }

namespace {

// Mask of bits [a, b) within word number `word` of a row.
uint64_t span_mask(size_t word, size_t a, size_t b) {
    size_t lo = std::max(a, word * 64), hi = std::min(b, word * 64 + 64);
    if (hi <= lo) return 0;
    size_t n = hi - lo;
    uint64_t m = n == 64 ? ~uint64_t(0) : ((uint64_t(1) << n) - 1);
    return m << (lo - word * 64);
}

}  // namespace

// The selection's inner loop (a candidate's gain, counted again whenever it reaches the top of the
// queue): compiled twice, with the POPCNT instruction for the processors that have it (chosen when
// the program loads) and without.
__attribute__((target_clones("popcnt", "default"))) size_t VoxelBits::count(const std::vector<Span>& spans) const {
    size_t total = 0;
    for (const Span& s : spans) {
        const uint64_t* row = &bits_[s.row * words_per_row_];
        for (size_t w = s.x0 / 64; w * 64 < s.x1; ++w) total += size_t(__builtin_popcountll(row[w] & span_mask(w, s.x0, s.x1)));
    }
    return total;
}

void VoxelBits::clear(const std::vector<Span>& spans) {
    for (const Span& s : spans)
        for (size_t w = s.x0 / 64; w * 64 < s.x1; ++w) bits_[s.row * words_per_row_ + w] &= ~span_mask(w, s.x0, s.x1);
}

void VoxelBits::fill(const std::vector<Span>& spans) {
    for (const Span& s : spans)
        for (size_t w = s.x0 / 64; w * 64 < s.x1; ++w) bits_[s.row * words_per_row_ + w] |= span_mask(w, s.x0, s.x1);
}

size_t VoxelBits::count_all() const {
    size_t total = 0;
    for (uint64_t w : bits_) total += ones(w);
    return total;
}

namespace {

// Lazy greedy maximum coverage: `gain(i)` is re-evaluated when i reaches the top of the queue;
// `take(i)` records a choice. Ties go to the lower index. Stops when `more()` is false or the best
// gain is below `min_gain`.
template <class Gain, class Take, class More>
void lazy_greedy(size_t n, const std::vector<size_t>& initial, Gain gain, Take take, More more, size_t min_gain) {
    using Entry = std::pair<size_t, int64_t>;  // (gain, -index)
    std::priority_queue<Entry> queue;
    for (size_t i = 0; i < n; ++i)
        if (initial[i] >= std::max<size_t>(min_gain, 1)) queue.push({initial[i], -int64_t(i)});
    while (!queue.empty() && more()) {
        auto [stale, neg] = queue.top();
        queue.pop();
        size_t i = size_t(-neg);
        size_t g = gain(i);
        if (g < std::max<size_t>(min_gain, 1)) continue;
        if (!queue.empty() && g < queue.top().first) {
            queue.push({g, neg});
            continue;
        }
        take(i);
    }
}

bool inside_inflated(const Candidate& e, const Vec3& p, double inflate) {
    Vec3 local = e.axes.transpose() * (p - e.center);
    Vec3 r = e.radii + Vec3::Constant(inflate);
    return local.cwiseQuotient(r).squaredNorm() <= 1.0;
}

}  // namespace

SelectionResult select_ellipsoids(const VoxelGrid& grid, const VoxelGrid* measure,
                                  const std::vector<Candidate>& candidates, const std::vector<Vec3>& surface_samples,
                                  double near, double coverage, uint32_t max_volume, uint32_t max_count,
                                  const std::function<void(double)>& progress, SelectionCache* cache,
                                  unsigned threads) {
    SelectionResult result;
    const size_t n = candidates.size();
    SelectionCache own;
    SelectionCache& c = cache ? *cache : own;
    const size_t rasterized = std::min(c.spans.size(), n);
    c.spans.resize(n);
    c.fine_spans.resize(n);
    c.fine_done.resize(n, 0);
    const size_t rows = size_t(grid.n[1]) * grid.n[2];
    VoxelBits remaining(grid, false);
    for (size_t row = 0; row < rows; ++row)
        for (int x = 0; x < grid.n[0]; ++x)
            if (grid.inside(row * grid.n[0] + x)) remaining.set(x, row, true);
    const size_t interior = remaining.count_all();
    std::vector<std::vector<Span>>& spans = c.spans;
    // Every call starts from the whole interior: a candidate's first gain is counted once.
    const size_t counted = std::min(c.interior_under.size(), n);
    c.interior_under.resize(n);
    parallel_for(n - counted, threads, [&](size_t k) {
        const size_t i = counted + k;
        if (i >= rasterized) spans[i] = rasterize(grid, candidates[i], 0);
        c.interior_under[i] = remaining.count(spans[i]);
    });
    const std::vector<size_t>& gains = c.interior_under;
    if (progress) progress(0.3);

    std::vector<bool> chosen(n, false);
    // Coverage is counted on the measuring grid when there is one (the chosen candidates only).
    std::optional<VoxelBits> measured;
    size_t measured_interior = interior;
    if (measure) {
        measured.emplace(*measure, false);
        measured_interior = 0;
        for (size_t row = 0; row < size_t(measure->n[1]) * measure->n[2]; ++row)
            for (int x = 0; x < measure->n[0]; ++x)
                if (measure->inside(row * measure->n[0] + x)) measured->set(x, row, true), ++measured_interior;
    }
    size_t covered = 0;
    const size_t target = size_t(std::ceil(coverage * double(measured_interior)));
    // A chosen candidate's runs on the measuring grid are made when it is taken (most candidates
    // never are). With a second thread, a helper makes them ahead for the candidates of the largest
    // first gains, the likeliest to be taken, while the greedy runs on this one (its recounts are
    // serial); whichever thread claims a candidate first makes its runs, the other waits for them.
    // The runs are the same whoever makes them.
    enum : uint8_t { kToMake, kMaking, kMade };
    std::vector<std::atomic<uint8_t>> fine_state(measured ? n : 0);
    for (size_t i = 0; i < fine_state.size(); ++i) fine_state[i].store(c.fine_done[i] ? kMade : kToMake, std::memory_order_relaxed);
    auto make_fine = [&](size_t i) {
        uint8_t expected = kToMake;
        if (fine_state[i].compare_exchange_strong(expected, kMaking, std::memory_order_acq_rel)) {
            try {
                c.fine_spans[i] = rasterize(*measure, candidates[i], 0);
            } catch (...) {
                fine_state[i].store(kToMake, std::memory_order_release);  // to be made by whoever needs it
                throw;
            }
            fine_state[i].store(kMade, std::memory_order_release);
        }
    };
    {  // the greedy, with the helper beside it
        std::atomic<bool> greedy_done{false};
        std::thread helper;
        // The helper stops and is joined when the greedy ends, however it ends (an exception included).
        struct Stop {
            std::atomic<bool>& done;
            std::thread& thread;
            ~Stop() {
                done.store(true, std::memory_order_relaxed);
                if (thread.joinable()) thread.join();
            }
        } stop{greedy_done, helper};
        if (measured && threads > 1) {
            std::vector<uint32_t> likely;
            for (size_t i = 0; i < n; ++i)
                if (gains[i] > 0 && !c.fine_done[i]) likely.push_back(uint32_t(i));
            std::sort(likely.begin(), likely.end(),
                      [&](uint32_t a, uint32_t b) { return gains[a] > gains[b] || (gains[a] == gains[b] && a < b); });
            helper = std::thread([&, likely = std::move(likely)] {
                try {
                    for (uint32_t i : likely) {
                        if (greedy_done.load(std::memory_order_relaxed)) break;
                        make_fine(i);
                    }
                } catch (...) {
                    // Only ahead of the greedy: what it needs it makes itself.
                }
            });
        }
        lazy_greedy(
            n, gains, [&](size_t i) { return remaining.count(spans[i]); },
            [&](size_t i) {
                if (measured) {
                    // Made here unless the helper has claimed it: then wait for it (or make it after all,
                    // should the helper have failed and given it back).
                    while (fine_state[i].load(std::memory_order_acquire) != kMade) {
                        make_fine(i);
                        std::this_thread::yield();
                    }
                    const auto& fine = c.fine_spans[i];
                    covered += measured->count(fine);
                    measured->clear(fine);
                } else {
                    covered += remaining.count(spans[i]);
                }
                remaining.clear(spans[i]);
                result.volume.push_back(uint32_t(i));
                chosen[i] = true;
            },
            [&] { return result.volume.size() < std::min(max_volume, max_count) && covered < target; }, 1);
    }
    for (size_t i = 0; i < fine_state.size(); ++i) c.fine_done[i] = fine_state[i].load(std::memory_order_relaxed) == kMade;
    result.coverage = measured_interior ? double(covered) / double(measured_interior) : 0;
    if (progress) progress(0.6);

    // Surface pass: samples farther than `near` from every chosen ellipsoid.
    const size_t m = surface_samples.size();
    if (m == 0 || result.volume.size() >= max_count) return result;
    std::vector<bool> done(m, false);
    // The samples sorted by voxel, so that each candidate looks only at the samples under its runs.
    std::vector<std::pair<uint64_t, uint32_t>> by_voxel;  // (voxel index, sample)
    by_voxel.reserve(m);
    for (size_t s = 0; s < m; ++s) {
        bool in_grid = true;
        int idx[3];
        for (int k = 0; k < 3; ++k) {
            idx[k] = int(std::lround((surface_samples[s][k] - grid.origin[k]) / grid.h));
            in_grid = in_grid && idx[k] >= 0 && idx[k] < grid.n[k];
        }
        if (in_grid) by_voxel.push_back({grid.index(idx[0], idx[1], idx[2]), uint32_t(s)});
    }
    std::sort(by_voxel.begin(), by_voxel.end());
    // Where each row of voxels starts in by_voxel: a candidate's runs are pieces of rows.
    std::vector<uint32_t> row_start(rows + 1, 0);
    for (const auto& entry : by_voxel) ++row_start[entry.first / uint64_t(grid.n[0]) + 1];
    for (size_t r = 0; r < rows; ++r) row_start[r + 1] += row_start[r];
    std::vector<std::vector<uint32_t>>& near_samples = c.near_samples;
    const size_t found = std::min(near_samples.size(), n);
    near_samples.resize(n);
    parallel_for(n - found, threads, [&](size_t k) {
        const size_t i = found + k;
        near_samples[i].clear();
        for (const Span& sp : rasterize(grid, candidates[i], near + grid.h)) {
            const uint64_t first = uint64_t(sp.row) * grid.n[0] + sp.x0, last = uint64_t(sp.row) * grid.n[0] + sp.x1;
            for (uint32_t j = row_start[sp.row]; j < row_start[sp.row + 1]; ++j) {
                const auto& [voxel, sample] = by_voxel[j];
                if (voxel < first) continue;
                if (voxel >= last) break;
                if (inside_inflated(candidates[i], surface_samples[sample], near)) near_samples[i].push_back(sample);
            }
        }
        std::sort(near_samples[i].begin(), near_samples[i].end());
    });
    for (size_t i = 0; i < n; ++i)
        if (chosen[i])
            for (uint32_t s : near_samples[i]) done[s] = true;
    auto surface_gain = [&](size_t i) {
        if (chosen[i]) return size_t(0);
        size_t g = 0;
        for (uint32_t s : near_samples[i]) g += !done[s];
        return g;
    };
    std::vector<size_t> initial(n);
    for (size_t i = 0; i < n; ++i) initial[i] = surface_gain(i);
    const size_t min_gain = std::max<size_t>(2, m / 2000);
    lazy_greedy(
        n, initial, surface_gain,
        [&](size_t i) {
            for (uint32_t s : near_samples[i]) done[s] = true;
            chosen[i] = true;
            result.surface.push_back(uint32_t(i));
        },
        [&] { return result.volume.size() + result.surface.size() < max_count; }, min_gain);
    if (progress) progress(1.0);
    return result;
}

}  // namespace ellicast::detail

// The encoder pipeline: for each mesh, the inside test, candidate ellipsoids, the greedy choice,
// flat ellipsoids for sheets, quantization with a containment re-check, and the point stream.
#include "ellicast/codec/encoder.h"

#include "encoder_internal.h"
#include "surface_samples.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <future>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <tuple>

namespace ellicast {

using namespace detail;

std::string check_encode_options(const EncodeOptions& o) {
    if (o.max_ellipsoids < 1 || o.max_ellipsoids > 100000)
        return "the ellipsoid count must be between 1 and 100000 (got " + std::to_string(o.max_ellipsoids) + ")";
    if (!(o.coverage > 0) || o.coverage > 1)
        return "the coverage target must be in (0, 1] (got " + std::to_string(o.coverage) + ")";
    if (o.candidates > 200000)
        return "at most 200000 candidate ellipsoids (got " + std::to_string(o.candidates) + ")";
    if (o.grid != 0 && (o.grid < 16 || o.grid > 256))
        return "the voxel grid must have 16 to 256 cells along the longest side (got " + std::to_string(o.grid) + ")";
    if (o.position_bits < 8 || o.position_bits > 16)
        return "position bits must be 8..16 (got " + std::to_string(o.position_bits) + ")";
    if (o.normal_bits < 4 || o.normal_bits > 16)
        return "normal bits must be 4..16 (got " + std::to_string(o.normal_bits) + ")";
    if (o.texcoord_bits < 4 || o.texcoord_bits > 16)
        return "texture coordinate bits must be 4..16 (got " + std::to_string(o.texcoord_bits) + ")";
    if (o.color_bits < 2 || o.color_bits > 16)
        return "colour bits must be 2..16 (got " + std::to_string(o.color_bits) + ")";
    if (o.packet_size < kMinPacketSize || o.packet_size > kMaxPacketSize)
        return "the packet size must be " + std::to_string(kMinPacketSize) + ".." + std::to_string(kMaxPacketSize) +
               " bytes (got " + std::to_string(o.packet_size) + ")";
    if (!(o.sample_spacing >= 0) || o.sample_spacing > 1)
        return "the sample spacing must be in [0, 1] (a fraction of the object's diagonal; got " +
               std::to_string(o.sample_spacing) + ")";
    if (o.max_samples > 10000000)
        return "at most 10000000 surface samples per object (got " + std::to_string(o.max_samples) + ")";
    if (!(o.sample_budget >= -1) || o.sample_budget > 1000)
        return "the sample budget must be in [-1, 1000] (surface samples per vertex; -1: no limit; got " +
               std::to_string(o.sample_budget) + ")";
    if (!(o.base_ratio >= 0) || o.base_ratio > 1000)
        return "the base ratio must be in [0, 1000] (the base's bytes against the exact data's; got " +
               std::to_string(o.base_ratio) + ")";
    if (o.threads < 1 || o.threads > 256) return "threads must be 1..256 (got " + std::to_string(o.threads) + ")";
    if (!(o.repair_ratio >= 0) || o.repair_ratio > 4)
        return "the repair ratio must be in [0, 4] (repair symbols per source packet; got " + std::to_string(o.repair_ratio) + ")";
    if (!(o.point_share >= 0) || o.point_share > 1)
        return "the point share must be in [0, 1] (the share of an object's vertices sent as points; got " +
               std::to_string(o.point_share) + ")";
    if (!(o.normal_tolerance >= 0) || o.normal_tolerance > 90)
        return "the normal tolerance must be in [0, 90] degrees (got " + std::to_string(o.normal_tolerance) + ")";
    return "";
}

namespace {

struct Progress {
    const EncodeOptions& options;
    size_t object = 0, objects = 1;
    void operator()(const std::string& stage, double f) const {
        if (options.progress) options.progress(stage, (double(object) + std::clamp(f, 0.0, 1.0)) / double(objects));
    }
};

Frame frame_of(const Mesh& mesh) {
    std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const auto& p : mesh.positions)
        for (int k = 0; k < 3; ++k) lo[k] = std::min<double>(lo[k], p[k]), hi[k] = std::max<double>(hi[k], p[k]);
    double extent = 0, magnitude = 0;
    for (int k = 0; k < 3; ++k) extent = std::max(extent, hi[k] - lo[k]);
    for (int k = 0; k < 3; ++k) magnitude = std::max({magnitude, std::abs(lo[k]), std::abs(hi[k])});
    extent = std::max(extent, 1e-6 * magnitude);  // a flat or single-point model still gets a cube
    if (!(extent > 1e-30)) extent = magnitude > 0 ? magnitude : 1.0;
    // A small margin so that the extreme vertices do not sit on the frame's edge.
    const double pad = extent * 1e-3;
    Frame f;
    for (int k = 0; k < 3; ++k) f.origin[k] = float(lo[k] - pad);
    f.scale = float(extent + 2 * pad);
    // float rounding must not leave a vertex outside the cube
    for (int k = 0; k < 3; ++k)
        while (double(f.origin[k]) + double(f.scale) < hi[k]) f.scale = std::nextafter(f.scale, INFINITY);
    return f;
}

Ellipsoid to_ellipsoid(const Candidate& c) {
    Eigen::Matrix3d R = c.axes;
    if (R.determinant() < 0) R.col(2) = -R.col(2);
    Eigen::Quaterniond q(R);
    q.normalize();
    Ellipsoid e;
    for (int k = 0; k < 3; ++k) e.center[k] = float(c.center[k]), e.radii[k] = float(c.radii[k]);
    e.rotation = {float(q.w()), float(q.x()), float(q.y()), float(q.z())};
    return e;
}

Candidate to_candidate(const Ellipsoid& e) {
    Candidate c;
    c.center = Vec3(e.center[0], e.center[1], e.center[2]);
    c.radii = Vec3(e.radii[0], e.radii[1], e.radii[2]);
    c.axes = Eigen::Quaterniond(e.rotation[0], e.rotation[1], e.rotation[2], e.rotation[3]).normalized().toRotationMatrix();
    return c;
}

// Vertices welded by exact position: for the boundary test, glTF seams are not holes.
// Each vertex's id is the first vertex at its position (positions compared as std::array<float, 3>
// compares them: 0 and -0 are one position), found by sorting the vertices by position.
std::vector<uint32_t> weld_by_position(const Mesh& mesh) {
    const auto& p = mesh.positions;
    std::vector<uint32_t> by_position(p.size());
    std::iota(by_position.begin(), by_position.end(), 0u);
    std::sort(by_position.begin(), by_position.end(),
              [&](uint32_t a, uint32_t b) { return p[a] < p[b] || (!(p[b] < p[a]) && a < b); });
    std::vector<uint32_t> id(p.size());
    for (size_t k = 0, group = 0; k < by_position.size(); ++k) {
        if (k > 0 && p[by_position[k - 1]] < p[by_position[k]]) group = k;  // a new position: its first vertex leads
        id[by_position[k]] = by_position[group];
    }
    return id;
}

bool is_closed(const Mesh& mesh, const std::vector<uint32_t>& weld) {
    std::vector<uint64_t> edges;
    edges.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = weld[t[e]], b = weld[t[(e + 1) % 3]];
            edges.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if (j - i == 1) return false;
        i = j;
    }
    return !edges.empty();
}

// True when every directed edge (by welded vertex) is matched by as many in the opposite direction:
// the surface has no boundary and a consistent orientation, so its winding number is an integer
// that signed ray crossings give exactly. Degenerate triangles are left out.
bool is_cycle(const Mesh& mesh, const std::vector<uint32_t>& weld) {
    std::vector<uint64_t> forward, backward;
    forward.reserve(mesh.triangles.size() * 3);
    backward.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) {
        uint32_t v[3] = {weld[t[0]], weld[t[1]], weld[t[2]]};
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
        for (int e = 0; e < 3; ++e) {
            forward.push_back(uint64_t(v[e]) << 32 | v[(e + 1) % 3]);
            backward.push_back(uint64_t(v[(e + 1) % 3]) << 32 | v[e]);
        }
    }
    std::sort(forward.begin(), forward.end());
    std::sort(backward.begin(), backward.end());
    return !forward.empty() && forward == backward;
}

// ---------------------------------------------------------------------------------------------
// Ellipsoids of one triangle mesh

// `weld`: weld_by_position(mesh); `closed`: is_closed(mesh, weld).
std::vector<QuantizedEllipsoid> encode_ellipsoids(const Mesh& mesh, const std::vector<uint32_t>& weld, bool closed,
                                                  const Frame& frame, const EncodeOptions& options,
                                                  uint32_t object_seed, double seed_share, ObjectReport& report,
                                                  std::vector<std::string>& warnings, const Progress& progress) {
    std::vector<QuantizedEllipsoid> out;
    TriangleTree tree(mesh.positions, mesh.triangles);
    if (tree.empty()) return out;
    report.closed = closed;

    WindingNumber winding(tree);
    const TriangleTree::Box box = tree.bounds();
    // A stream of many objects (seed_share < 1: 8 / objects past 8) spends less on each: the seeds
    // fall with the square of the share, the grid cells with its cube root (at least 40).
    const double share = seed_share * seed_share;
    int cells = int(options.grid);
    if (cells == 0) {
        // 64 or 96 cells along the longest side, finer for a flat model so that its thinnest side
        // still spans 12 cells, at most 256 cells.
        cells = mesh.triangles.size() < 2000 ? 64 : 96;
        if (share < 1) cells = std::max(40, int(std::lround(cells * std::cbrt(share))));
        double lo = INFINITY, hi = 0;
        for (int k = 0; k < 3; ++k) {
            double e = box.max[k] - box.min[k];
            hi = std::max(hi, e);
            if (e > 0) lo = std::min(lo, e);
        }
        if (hi > 0 && lo < hi) {
            const double ratio = hi / lo;
            int wanted = int(std::ceil(12 * ratio));
            if (wanted > cells && ratio < 1e3) cells = std::min(wanted, 256);
        }
    }
    progress("inside test", 0.0);
    // A surface without boundary gets exact winding numbers from ray crossings (far cheaper).
    const bool cycle = is_cycle(mesh, weld);
    VoxelGrid grid = cycle
                         ? build_closed_winding_grid(tree, box, cells, options.threads)
                         : build_winding_grid(tree, winding, box, cells, options.threads,
                                              [&](double f) { progress("inside test", 0.2 * f); });
    size_t interior = 0;
    for (size_t i = 0; i < grid.size(); ++i) interior += grid.inside(i);
    // A model whose inside spans few voxels (thin limbs, small parts far apart) gets a finer grid,
    // up to twice as fine, so that about 50,000 voxels (fewer for a small share) sample its inside;
    // only where the exact inside test is cheap.
    const double wanted_interior = 50000 * share;
    if (options.grid == 0 && cycle && interior > 0 && double(interior) < 0.6 * wanted_interior) {
        const int finer = std::min({2 * cells, 256, int(std::ceil(cells * std::cbrt(wanted_interior / double(interior))))});
        if (finer > cells) {
            cells = finer;
            grid = build_closed_winding_grid(tree, box, cells, options.threads);
            interior = 0;
            for (size_t i = 0; i < grid.size(); ++i) interior += grid.inside(i);
        }
    }
    for (int k = 0; k < 3; ++k) report.grid[k] = uint32_t(grid.n[k]);
    report.interior_fraction = double(interior) / double(grid.size());

    // Seeds: points spread over the surface by area, each with the normal pointing inside.
    const auto& tris = tree.triangles();
    std::vector<double> cumulative(tris.size());
    double total_area = 0;
    for (size_t i = 0; i < tris.size(); ++i) {
        const auto& t = tris[i];
        total_area += 0.5 * (to_vec(t.v[1]) - to_vec(t.v[0])).cross(to_vec(t.v[2]) - to_vec(t.v[0])).norm();
        cumulative[i] = total_area;
    }
    // Automatic: four seeds per ellipsoid wanted (the greedy choice needs a choice), fewer per object
    // when a stream has many objects, never under 64.
    uint32_t seeds = options.candidates;
    if (seeds == 0)
        seeds = std::max<uint32_t>(64, uint32_t(share * std::min<uint32_t>(4 * options.max_ellipsoids + 200, 4000)));
    Random rng(object_seed);
    struct Seed {
        Vec3 p, n;
    };
    std::vector<Seed> seed_points(seeds);
    for (auto& s : seed_points) {
        double target = rng.uniform() * total_area;
        size_t i = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin());
        i = std::min(i, tris.size() - 1);
        double u = rng.uniform(), v = rng.uniform();
        if (u + v > 1) u = 1 - u, v = 1 - v;
        const auto& t = tris[i];
        Vec3 a = to_vec(t.v[0]), b = to_vec(t.v[1]), c = to_vec(t.v[2]);
        s.p = a + u * (b - a) + v * (c - a);
        s.n = (b - a).cross(c - a);
        double len = s.n.norm();
        s.n = len > 0 ? Vec3(s.n / len) : Vec3::Zero();
    }

    GrowthContext ctx{tree, grid, winding, report.closed, 0.25 * grid.h, {}, {}, {}};
    prepare_growth(ctx);
    const double eps = 0.05 * grid.h;
    std::vector<Candidate> grown(seeds);
    std::vector<char> ok(seeds, 0);
    // Grow in chunks so that progress can be reported from this thread.
    const size_t chunk = 64;
    for (size_t start = 0; start < seeds; start += chunk) {
        size_t end = std::min<size_t>(seeds, start + chunk);
        parallel_for(end - start, options.threads, [&](size_t k) {
            size_t i = start + k;
            const Seed& s = seed_points[i];
            if (s.n.isZero()) return;
            double w_back = winding(to_arr(s.p - eps * s.n)), w_front = winding(to_arr(s.p + eps * s.n));
            Vec3 inward;
            if (w_back > 0.5 && w_back >= w_front) inward = -s.n;
            else if (w_front > 0.5) inward = s.n;
            else return;  // no inside on either side: a sheet, handled below
            ok[i] = grow_ellipsoid(ctx, s.p, inward, grown[i]) ? 1 : 0;
        });
        progress("candidates", 0.2 + 0.5 * double(end) / double(seeds));
    }
    std::vector<Candidate> candidates;
    for (size_t i = 0; i < seeds; ++i)
        if (ok[i]) candidates.push_back(grown[i]);
    report.candidates = uint32_t(candidates.size());

    // Surface samples: the distinct vertex positions (at most 20000, a seeded subset beyond).
    std::vector<Vec3> samples;
    std::vector<Vec3> sample_normals;
    std::vector<uint32_t> sample_vertex;  // the vertex each sample is
    {
        std::vector<Vec3> vnormal(mesh.positions.size(), Vec3::Zero());
        for (const auto& t : mesh.triangles) {
            Vec3 a(mesh.positions[t[0]][0], mesh.positions[t[0]][1], mesh.positions[t[0]][2]);
            Vec3 b(mesh.positions[t[1]][0], mesh.positions[t[1]][1], mesh.positions[t[1]][2]);
            Vec3 c(mesh.positions[t[2]][0], mesh.positions[t[2]][1], mesh.positions[t[2]][2]);
            Vec3 fn = (b - a).cross(c - a);
            for (uint32_t v : t) vnormal[weld[v]] += fn;
        }
        std::vector<uint32_t> distinct;
        std::vector<char> used(mesh.positions.size(), 0);
        for (const auto& t : mesh.triangles)
            for (uint32_t v : t) used[weld[v]] = 1;
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            if (weld[i] == i && used[i]) distinct.push_back(uint32_t(i));
        if (distinct.size() > 20000) {
            Random pick(object_seed ^ 0x51ED270Bu);
            for (size_t i = distinct.size(); i > 1; --i) std::swap(distinct[i - 1], distinct[pick.below(uint32_t(i))]);
            distinct.resize(20000);
            std::sort(distinct.begin(), distinct.end());
        }
        for (uint32_t i : distinct) {
            sample_vertex.push_back(i);
            samples.emplace_back(mesh.positions[i][0], mesh.positions[i][1], mesh.positions[i][2]);
            double len = vnormal[i].norm();
            sample_normals.push_back(len > 0 ? Vec3(vnormal[i] / len) : Vec3::Zero());
        }
    }
    const double near = grid.h;
    // An open surface keeps a fifth of the budget for its thin and sheet-like parts.
    const uint32_t max_volume =
        report.closed ? options.max_ellipsoids : std::max<uint32_t>(1, uint32_t(0.8 * options.max_ellipsoids));
    const uint32_t max_inside =
        report.closed ? options.max_ellipsoids : std::max<uint32_t>(1, uint32_t(0.9 * options.max_ellipsoids));
    // Coverage (when the selection stops, and what is reported) is measured on a grid twice as
    // fine as the working one when the surface has no boundary (its exact inside test is cheap), so
    // that ellipsoids hugging flat faces aligned with the voxels are not credited with the whole
    // voxel layer they reach, nor thin parts misjudged by few voxel centres; else on the working grid.
    std::optional<VoxelGrid> fine;
    if (cycle && interior > 0 && grid.size() <= (size_t(2) << 20))  // at most 16M fine voxels
        fine = build_closed_winding_grid(tree, box, 2 * cells, options.threads);
    const VoxelGrid& measure_grid = fine ? *fine : grid;
    const VoxelGrid* measure = fine ? &*fine : nullptr;
    size_t measure_interior = 0;
    for (size_t i = 0; i < measure_grid.size(); ++i) measure_interior += measure_grid.inside(i);
    // Aim a little higher: quantization may shrink a few ellipsoids by a step.
    const double aim = std::min(1.0, options.coverage + 0.01);
    // Every selection below is over these grids and samples, and the candidates only grow.
    SelectionCache selection_cache;
    SelectionResult chosen = select_ellipsoids(grid, measure, candidates, samples, near, aim, max_volume,
                                               max_inside, [&](double f) { progress("selection", 0.7 + 0.1 * f); },
                                               &selection_cache, options.threads);

    // More rounds where the first left interior uncovered (corners, crevices, sharp edges, the thin
    // layer under flat faces): seeds at the surface points nearest to uncovered voxels, each growing
    // one candidate toward its voxel and one flat candidate hugging the surface there (its axes
    // turned by 45 degrees for every other seed, to reach into the corners of a face); then choose
    // again among all candidates (a better set may reach more coverage with the same count). At
    // most three rounds, and none after a round that gained less than 0.25% of the interior.
    double gained = 1;
    for (int round = 0; round < 3 && chosen.coverage < aim && interior > 0 && gained >= 0.0025; ++round) {
        const double before = chosen.coverage;
        VoxelBits covered(grid, false);
        for (uint32_t i : chosen.volume) covered.fill(selection_cache.spans[i]);
        std::vector<size_t> uncovered;
        for (size_t row = 0; row < size_t(grid.n[1]) * grid.n[2]; ++row)
            for (int x = 0; x < grid.n[0]; ++x)
                if (grid.inside(row * grid.n[0] + x) && !covered.get(x, row)) uncovered.push_back(row * grid.n[0] + x);
        const size_t extra = std::min<size_t>(uncovered.size(), seeds / 2);
        Random pick(object_seed ^ (0xA511E9B3u + uint32_t(round)));
        for (size_t i = 0; i < extra; ++i)
            std::swap(uncovered[i], uncovered[i + pick.below(uint32_t(uncovered.size() - i))]);
        // Two candidates per uncovered voxel: one grown toward it, one flat under the surface there.
        std::vector<Candidate> more(2 * extra);
        std::vector<char> more_ok(2 * extra, 0);
        for (size_t start = 0; start < extra; start += chunk) {
            size_t end = std::min(extra, start + chunk);
            parallel_for(end - start, options.threads, [&](size_t k) {
                size_t v = uncovered[start + k];
                size_t x = v % grid.n[0], y = (v / grid.n[0]) % grid.n[1], z = v / (size_t(grid.n[0]) * grid.n[1]);
                Vec3 c(grid.origin[0] + x * grid.h, grid.origin[1] + y * grid.h, grid.origin[2] + z * grid.h);
                ClosestPoint cp = tree.closest_point(to_arr(c));
                if (!cp.found) return;
                Vec3 q = to_vec(cp.point), d = c - q;
                if (d.norm() < 1e-12) return;
                more_ok[start + k] = grow_ellipsoid(ctx, q, d.normalized(), more[start + k]) ? 1 : 0;
                const double thickness = std::max(0.6 * grid.h, 0.75 * d.norm());
                const double turn = (start + k) % 2 ? 0.7853981634 : 0.0;
                more_ok[extra + start + k] = grow_flat(ctx, q, d.normalized(), thickness, turn, more[extra + start + k]);
            });
            progress("candidates", 0.8 + 0.1 * double(end) / double(extra));
        }
        for (size_t i = 0; i < 2 * extra; ++i)
            if (more_ok[i]) candidates.push_back(more[i]);
        report.candidates = uint32_t(candidates.size());
        chosen = select_ellipsoids(grid, measure, candidates, samples, near, aim, max_volume, max_inside,
                                   [&](double f) { progress("selection", 0.9 + 0.05 * f); }, &selection_cache,
                                   options.threads);
        gained = chosen.coverage - before;
    }

    // Quantize each chosen ellipsoid; dequantized it must still be clear of the surface.
    const double radius_step = frame.scale / 8191.0;
    // The placed ellipsoid, whether it had to shrink, or nothing when none fits.
    struct Placed {
        QuantizedEllipsoid q;
        bool shrunk = false;
    };
    auto placed = [&](const Candidate& c, bool check) -> std::optional<Placed> {
        Candidate cur = c;
        for (int attempt = 0; attempt < 40; ++attempt) {
            QuantizedEllipsoid q = quantize_ellipsoid(to_ellipsoid(cur), frame);
            Candidate back = to_candidate(dequantize_ellipsoid(q, frame));
            if (back.radii.minCoeff() <= 0) return std::nullopt;
            if (!check || clear_of_surface(tree, back, nullptr, &ctx.balls)) return Placed{q, attempt > 0};
            if (attempt < 8) cur.radii -= Vec3::Constant(radius_step);
            else cur.radii *= 0.95;
            if (cur.radii.minCoeff() <= radius_step) return std::nullopt;
        }
        return std::nullopt;
    };
    auto keep = [&](const std::optional<Placed>& p) {
        if (!p) return false;
        out.push_back(p->q);
        if (p->shrunk) ++report.shrunk;
        return true;
    };
    // The chosen candidates' placements, found in parallel (each alone; the surface test is most of
    // the serial tail of an encode) and once per candidate however many passes choose it.
    std::vector<std::optional<Placed>> placements(candidates.size());
    std::vector<char> tried(candidates.size(), 0);
    auto place_chosen = [&](const std::vector<uint32_t>& chosen_ids) {
        std::vector<uint32_t> unplaced;
        for (uint32_t i : chosen_ids)
            if (!tried[i]) unplaced.push_back(i), tried[i] = 1;
        parallel_for(unplaced.size(), options.threads,
                     [&](size_t k) { placements[unplaced[k]] = placed(candidates[unplaced[k]], true); });
        for (uint32_t i : chosen_ids) keep(placements[i]);
    };

    // Surface samples far from every chosen ellipsoid (after quantization).
    auto voxel_row = [&](const Vec3& p, size_t& x, size_t& row) {
        int idx[3];
        for (int k = 0; k < 3; ++k) {
            idx[k] = int(std::lround((p[k] - grid.origin[k]) / grid.h));
            if (idx[k] < 0 || idx[k] >= grid.n[k]) return false;
        }
        x = size_t(idx[0]);
        row = size_t(idx[1]) + size_t(idx[2]) * grid.n[1];
        return true;
    };
    auto near_count = [&](const std::vector<Vec3>& points, std::vector<uint32_t>* far) {
        VoxelBits near_base(grid, false);
        for (const auto& q : out) near_base.fill(rasterize(grid, to_candidate(dequantize_ellipsoid(q, frame)), near + grid.h));
        size_t count = 0;
        for (size_t s = 0; s < points.size(); ++s) {
            size_t x, row;
            bool is_near = voxel_row(points[s], x, row) && near_base.get(x, row);
            count += is_near;
            if (!is_near && far) far->push_back(uint32_t(s));
        }
        return count;
    };

    // Sheets are looked for among the vertices and, on faces larger than the grid (a low-poly sheet
    // has its vertices at its corners only), among points inside the faces.
    const bool may_have_sheets = !report.closed || interior == 0;
    std::vector<Vec3> sheet_points, sheet_normals, on_faces, on_faces_normals;
    std::vector<uint32_t> sheet_parts, on_faces_triangles;
    if (may_have_sheets) {
        // The faces of an open part (all of them on a closed model with no inside voxel).
        const MeshParts parts = mesh_parts(mesh, weld);
        std::vector<char> allowed;
        if (interior > 0)
            for (uint32_t part : parts.of_triangle) allowed.push_back(parts.open[part]);
        face_samples(tree, allowed, grid.h, 500000, on_faces, on_faces_normals, on_faces_triangles);
        sheet_points = samples;
        sheet_normals = sample_normals;
        sheet_points.insert(sheet_points.end(), on_faces.begin(), on_faces.end());
        sheet_normals.insert(sheet_normals.end(), on_faces_normals.begin(), on_faces_normals.end());
        for (uint32_t v : sample_vertex) sheet_parts.push_back(parts.of_vertex[v]);
        for (uint32_t t : on_faces_triangles) sheet_parts.push_back(parts.of_triangle[t]);
    }

    // Quantize and place the chosen ellipsoids, add flat ones for sheets, and measure. When the
    // finer measure falls short of the target the working grid said was reached, choose again
    // aiming higher by the difference (at most twice).
    double select_aim = aim;
    for (int pass = 0;; ++pass) {
        out.clear();
        report.shrunk = report.flat_ellipsoids = 0;
        place_chosen(chosen.volume);
        size_t before_surface = out.size();
        place_chosen(chosen.surface);
        report.surface_ellipsoids = uint32_t(out.size() - before_surface);

        // Flat ellipsoids go where the surface stays far from the base: on an open surface (a sheet, a
        // single-sided panel), or on a closed one with no inside voxel at all (thinner than the grid).
        // A closed surface with an inside never gets them: its ellipsoids must stay inside it.
        std::vector<uint32_t> sheet_samples;
        if (may_have_sheets) {
            near_count(samples, &sheet_samples);
            std::vector<uint32_t> far_on_faces;
            near_count(on_faces, &far_on_faces);
            for (uint32_t i : far_on_faces) sheet_samples.push_back(uint32_t(samples.size() + i));
        }
        if (!sheet_samples.empty() && out.size() < options.max_ellipsoids)
            for (const Candidate& flat : sheet_ellipsoids(sheet_points, sheet_normals, sheet_parts, sheet_samples, grid.h,
                                                          options.max_ellipsoids - out.size()))
                if (keep(placed(flat, false))) ++report.flat_ellipsoids;
        report.surface_covered = samples.empty() ? 0 : double(near_count(samples, nullptr)) / double(samples.size());

        VoxelBits uni(measure_grid, false);
        std::vector<std::vector<Span>> runs(out.size());
        parallel_for(out.size(), options.threads,
                     [&](size_t k) { runs[k] = rasterize(measure_grid, to_candidate(dequantize_ellipsoid(out[k], frame)), 0); });
        for (const auto& r : runs) uni.fill(r);
        size_t in_cov = 0, out_cov = 0;
        for (size_t row = 0; row < size_t(measure_grid.n[1]) * measure_grid.n[2]; ++row)
            for (int x = 0; x < measure_grid.n[0]; ++x)
                if (uni.get(x, row)) (measure_grid.inside(row * measure_grid.n[0] + x) ? in_cov : out_cov)++;
        report.coverage = measure_interior ? double(in_cov) / double(measure_interior) : 0;
        report.outside = measure_interior ? double(out_cov) / double(measure_interior) : 0;
        report.ellipsoids = uint32_t(out.size());
        const bool short_of_aim = chosen.coverage + 1e-9 < select_aim;  // stopped by the count or no gain
        if (pass >= 2 || !fine || report.coverage >= options.coverage + 0.002 || short_of_aim || select_aim >= 1) break;
        select_aim = std::min(1.0, select_aim + (options.coverage + 0.005 - report.coverage));
        chosen = select_ellipsoids(grid, measure, candidates, samples, near, select_aim, max_volume, max_inside,
                                   [&](double f) { progress("selection", 0.95 + 0.04 * f); }, &selection_cache,
                                   options.threads);
    }
    if (interior == 0 && report.flat_ellipsoids == 0 && out.empty())
        warnings.push_back(mesh.name + ": no interior volume and no sheet found; no ellipsoids");
    // The target is for closed models; an object whose bytes cap its base (base_ratio) falls short on
    // purpose, which its report says (ellipsoid_budget), not a warning.
    const bool capped_by_bytes = report.ellipsoid_budget > 0 && out.size() >= report.ellipsoid_budget;
    if (report.closed && interior > 0 && report.coverage + 1e-9 < options.coverage && !capped_by_bytes) {
        char text[256];
        std::snprintf(text, sizeof text, "%s: the ellipsoids cover %.1f%% of the interior, below the target %.1f%% (%zu "
                      "ellipsoids; %s)", mesh.name.c_str(), 100 * report.coverage, 100 * options.coverage, out.size(),
                      out.size() >= options.max_ellipsoids
                          ? "raise --ellipsoids"
                          : "no candidate adds volume: sharp edges and corners cannot be filled by inscribed ellipsoids");
        warnings.push_back(text);
    }
    progress("selection", 0.95);
    return out;
}

// ---------------------------------------------------------------------------------------------
// Points of one mesh

// Vertex i of a mesh with its attributes, as a point.
SurfacePoint vertex_point(const Mesh& mesh, size_t i) {
    SurfacePoint p;
    p.position = mesh.positions[i];
    if (mesh.has_normals()) p.normal = mesh.normals[i];
    if (mesh.has_texcoords()) p.texcoord = mesh.texcoords[i];
    if (mesh.has_colors()) p.color = mesh.colors[i];
    return p;
}

// A vertex's further texture-coordinate sets (format 1.14), quantized in their ranges; unused sets 0.
using SetRecords = std::array<std::array<uint16_t, 2>, kMaxTexcoordSets>;

SetRecords vertex_sets(const Mesh& mesh, size_t i, const std::vector<TexcoordRange>& ranges) {
    SetRecords r{};
    for (size_t s = 0; s < ranges.size(); ++s) r[s] = quantize_texcoord(mesh.texcoord_sets[s][i], ranges[s]);
    return r;
}

// The points of a mesh: its vertices quantized, welded where position and every attribute (the
// further texture-coordinate sets too: spec 30.2) are equal, in the spread order. `sets` receives the
// further sets' records of each point (one entry per point when `ranges` is not empty).
std::vector<QuantizedPoint> encode_points(const Mesh& mesh, const StreamInfo& info, const ObjectInfo& object,
                                          uint32_t seed, std::vector<uint32_t>* vertex_points = nullptr,
                                          const std::vector<TexcoordRange>& ranges = {},
                                          std::vector<SetRecords>* sets = nullptr) {
    struct Keyed {
        QuantizedPoint q;
        SetRecords sets;
        uint32_t vertex;  // the vertex of the mesh this record was made from
    };
    std::vector<Keyed> all;
    all.reserve(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        all.push_back({quantize_point(vertex_point(mesh, i), info, object), vertex_sets(mesh, i, ranges), uint32_t(i)});
    auto key = [](const Keyed& k) { return std::tie(k.q.position, k.q.normal, k.q.texcoord, k.q.color, k.sets); };
    std::sort(all.begin(), all.end(), [&](const Keyed& a, const Keyed& b) { return key(a) < key(b); });
    // The record each vertex became: a run of equal records in sorted order, numbered here, kept once.
    std::vector<uint32_t> record_of(vertex_points ? mesh.positions.size() : 0);
    size_t records = 0;
    for (size_t i = 0; i < all.size(); ++i) {
        if (i > 0 && key(all[i]) != key(all[i - 1])) ++records;
        if (vertex_points) record_of[all[i].vertex] = uint32_t(records);
    }
    all.erase(std::unique(all.begin(), all.end(), [&](const Keyed& a, const Keyed& b) { return key(a) == key(b); }),
              all.end());
    // Distinct positions; a seam's attribute sets follow each other.
    std::vector<std::array<uint32_t, 3>> positions;
    std::vector<size_t> first;
    for (size_t i = 0; i < all.size(); ++i)
        if (i == 0 || all[i].q.position != all[i - 1].q.position) {
            positions.push_back(all[i].q.position);
            first.push_back(i);
        }
    first.push_back(all.size());
    std::vector<uint32_t> order = spread_order(positions, info.position_bits, seed);
    std::vector<Keyed> sorted;
    sorted.reserve(all.size());
    std::vector<uint32_t> point_of(vertex_points ? all.size() : 0);  // per record: its point
    for (uint32_t p : order)
        for (size_t i = first[p]; i < first[p + 1]; ++i) {
            if (vertex_points) point_of[i] = uint32_t(sorted.size());
            sorted.push_back(all[i]);
        }
    if (vertex_points) {
        // The point each vertex became: its quantized position and attributes.
        vertex_points->resize(mesh.positions.size());
        for (size_t i = 0; i < mesh.positions.size(); ++i) (*vertex_points)[i] = point_of[record_of[i]];
    }
    std::vector<QuantizedPoint> out;
    out.reserve(sorted.size());
    for (const Keyed& k : sorted) out.push_back(k.q);
    if (sets) {
        sets->clear();
        if (!ranges.empty())
            for (const Keyed& k : sorted) sets->push_back(k.sets);
    }
    return out;
}

// The exact layer of one object (spec 19): its original triangles over its points, coded. A
// triangle whose corners became fewer than three points is left out (counted in `dropped`).
// The exact layer's triangles over the points: each input triangle through vertex_points, those
// whose corners fall on fewer than three points left out.
std::vector<Triangle> exact_triangles_of(const Mesh& input, const std::vector<uint32_t>& vertex_points) {
    std::vector<Triangle> triangles;
    triangles.reserve(input.triangles.size());
    for (const auto& t : input.triangles) {
        const Triangle p = {vertex_points[t[0]], vertex_points[t[1]], vertex_points[t[2]]};
        if (p[0] != p[1] && p[1] != p[2] && p[0] != p[2]) triangles.push_back(p);
    }
    return triangles;
}

// `carried`: the vertices the layer carries (format 1.11), named by vertex_points as
// content.points.size() + their index; in content.carried as the coded mesh introduces them.
void encode_exact_layer(const Mesh& input, const std::vector<uint32_t>& vertex_points,
                        const std::vector<QuantizedPoint>& carried, const StreamInfo& info, const ObjectInfo& object,
                        ObjectContent& content, uint32_t& dropped) {
    const std::vector<Triangle> triangles = exact_triangles_of(input, vertex_points);
    dropped = uint32_t(input.triangles.size() - triangles.size());
    if (triangles.empty()) return;
    std::vector<QuantizedPoint> vertices = content.points;
    vertices.insert(vertices.end(), carried.begin(), carried.end());
    std::vector<Triangle> sent;
    std::vector<uint32_t> order;
    if (encode_exact_mesh(vertices, content.points.size(), triangles, info, object, content.connectivity, sent, order) !=
        Error::Ok) {
        content.connectivity.clear();
        return;
    }
    content.carried.clear();
    for (uint32_t v : order) content.carried.push_back(vertices[v]);
    content.triangle_count = uint32_t(sent.size());
}

// Format 1.11 (spec 27.4): of the points a triangle uses, in the spread order, the first
// ceil(share * V) stay points; the exact layer carries the others (returned, in that order; the
// vertices that became them are renumbered content.points.size() + their index). Surface samples,
// which no triangle uses, stay points, and so do points whose normal is sent (`normals`, the
// entries of an object with surface normals, follow the points that stay).
std::vector<QuantizedPoint> carry_vertices(const Mesh& input, std::vector<uint32_t>& vertex_points,
                                           std::vector<QuantizedPoint>& points, std::vector<NormalEntry>& normals,
                                           double share) {
    std::vector<char> used(points.size(), 0);
    for (const Triangle& t : exact_triangles_of(input, vertex_points))
        for (uint32_t v : t) used[v] = 1;
    size_t vertices = 0;
    for (char u : used) vertices += u;
    const size_t keep = size_t(std::ceil(share * double(vertices) - 1e-9));
    if (keep >= vertices) return {};
    std::vector<QuantizedPoint> kept, carried;
    std::vector<NormalEntry> kept_normals;
    std::vector<uint32_t> index(points.size());
    size_t used_seen = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        const bool sent_normal = !normals.empty() && normals[i].sent;
        if (used[i] && used_seen++ >= keep && !sent_normal) {
            index[i] = uint32_t(carried.size()) | 0x80000000u;
            carried.push_back(points[i]);
        } else {
            index[i] = uint32_t(kept.size());
            kept.push_back(points[i]);
            if (!normals.empty()) kept_normals.push_back(normals[i]);
        }
    }
    if (!normals.empty()) normals = std::move(kept_normals);
    for (uint32_t& v : vertex_points)
        v = (index[v] & 0x80000000u) ? uint32_t(kept.size()) + (index[v] & 0x7FFFFFFFu) : index[v];
    points = std::move(kept);
    return carried;
}

// Surface normals (format 1.8, spec 24.5): per point, whether its normal can be left to the surface
// of the exact layer: the surface normal (spec 24.3) is defined, far enough from cancelling out that
// rounding cannot turn it (|S| at least a tenth of the angles' sum), and within `tolerance_degrees`
// of the point's normal as it would be sent. A point no triangle uses (a surface sample) keeps its
// normal: it is shown only before the exact layer is complete, and there the receiver's estimate
// over flat triangles would lose the smooth shading of a low-poly model's interpolated normals.
std::vector<NormalEntry> surface_normal_entries(const std::vector<QuantizedPoint>& points,
                                                const std::vector<Triangle>& triangles, const StreamInfo& info,
                                                double tolerance_degrees) {
    std::vector<std::array<uint32_t, 3>> positions;
    positions.reserve(points.size());
    for (const auto& q : points) positions.push_back(q.position);
    const SurfaceNormals surface = surface_normals(positions, triangles);
    const double cos_tolerance = std::cos(tolerance_degrees * M_PI / 180.0);
    // Points at a crease (another point at their position with a normal more than 30 degrees away:
    // a hard edge's split vertex) keep their normals: before the exact layer is complete, the
    // receiver's reconstruction turns its faces across creases by them (codec/src/normal_repair.cpp).
    std::vector<char> crease(points.size(), 0);
    {
        std::vector<uint32_t> order(points.size());
        for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return positions[a] < positions[b]; });
        const double cos_crease = std::cos(30.0 * M_PI / 180.0);
        for (size_t first = 0; first < order.size();) {
            size_t end = first + 1;
            while (end < order.size() && positions[order[end]] == positions[order[first]]) ++end;
            for (size_t a = first; a < end && end - first > 1; ++a) {
                const auto na = decode_octahedral(points[order[a]].normal, info.normal_bits);
                // Against the group's first 16 only: all of a hostile mesh's points at one position stay linear.
                for (size_t b = first; b < std::min(end, first + 16); ++b) {
                    const auto nb = decode_octahedral(points[order[b]].normal, info.normal_bits);
                    if (double(na[0]) * nb[0] + double(na[1]) * nb[1] + double(na[2]) * nb[2] < cos_crease) {
                        crease[order[a]] = 1;
                        break;
                    }
                }
            }
            first = end;
        }
    }
    std::vector<NormalEntry> entries(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const auto sent = decode_octahedral(points[i].normal, info.normal_bits);
        const auto& s = surface.normal[i];
        const double dot = double(sent[0]) * s[0] + double(sent[1]) * s[1] + double(sent[2]) * s[2];
        const bool leave = !crease[i] && surface.condition[i] >= 0.1f && dot >= cos_tolerance;
        entries[i].sent = !leave;
        if (!leave) entries[i].normal = points[i].normal;
    }
    return entries;
}

// Spacings for the surface samples of one object, from its bounding box.
// A sheet (an object given flat ellipsoids) gets half the spacing: its base is a thin shell whose two
// sides share its points, and woody, a flat figure, needs 1.5% rather than 3% to come back within
// 0.1% RMS (bench/run.sh quality).
SurfaceSampleOptions sample_options(const Mesh& mesh, const Frame& frame, const EncodeOptions& options,
                                    bool sheet) {
    std::array<float, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const auto& p : mesh.positions)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    double diagonal = 0;
    for (int k = 0; k < 3; ++k) diagonal += (double(hi[k]) - lo[k]) * (double(hi[k]) - lo[k]);
    diagonal = std::sqrt(diagonal);
    if (!(diagonal > 0)) diagonal = frame.scale;
    SurfaceSampleOptions s;
    s.spacing = options.sample_spacing * diagonal * (sheet ? 0.5 : 1.0);
    s.crease_spacing = s.spacing / 2;
    s.max_samples = std::max<size_t>(options.max_samples, mesh.positions.size());
    if (options.sample_budget >= 0)
        s.max_samples = std::min(s.max_samples, size_t(options.sample_budget * double(mesh.positions.size())));
    return s;
}

// The ellipsoids an object's exact data warrants (EncodeOptions::base_ratio): the base's bytes at
// most base_ratio times those of its vertices as point records and about a byte a triangle of
// connectivity, at least 8 ellipsoids, at most max_ellipsoids.
uint32_t ellipsoid_budget(const Mesh& mesh, const StreamInfo& info, const ObjectInfo& object, const EncodeOptions& options) {
    if (options.base_ratio <= 0) return options.max_ellipsoids;
    const double exact = double(mesh.positions.size()) * double(point_record_bits(info, object)) / 8.0 +
                         double(mesh.triangles.size());
    const double per_ellipsoid = double(info.packet_size) / double(std::max<size_t>(1, ellipsoids_per_packet(info.packet_size)));
    const double wanted = std::max(8.0, std::ceil(options.base_ratio * exact / per_ellipsoid));
    return uint32_t(std::min(wanted, double(options.max_ellipsoids)));  // max_ellipsoids may be under 8
}

// The encoder trusts nothing of a Mesh it is handed: sizes, indices and coordinates are checked.
// Fills `oriented` with `mesh` repaired by orient_outward() and returns how many triangles it
// turned (0: `oriented` is left empty and `mesh` is right as it is), with a warning saying what.
uint32_t orient_for_encoding(const Mesh& mesh, const std::vector<uint32_t>& weld, Mesh& oriented,
                             std::vector<std::string>& warnings) {
    if (mesh.is_point_set || mesh.triangles.empty()) return 0;
    OrientationReport r;
    auto triangles = orient_outward(mesh, weld, r);
    if (r.turned_faces == 0) return 0;
    oriented = mesh;
    oriented.triangles = std::move(triangles);
    std::string text = (mesh.name.empty() ? std::string("object") : mesh.name) + ": ";
    if (r.reversed_parts > 0)
        text += std::to_string(r.reversed_parts) + " of " + std::to_string(r.parts) +
                (r.parts == 1 ? " part faces" : " parts face") + " inward";
    if (r.mended_parts > 0)
        text += std::string(r.reversed_parts > 0 ? "; " : "") + std::to_string(r.mended_parts) + " of " +
                std::to_string(r.parts) + (r.parts == 1 ? " part has" : " parts have") +
                " triangles facing against their neighbours";
    text += " (" + std::to_string(r.turned_faces) + " of " + std::to_string(mesh.triangles.size()) +
            " triangles); encoded as if turned to face outward";
    if (r.non_orientable_parts > 0)
        text += "; " + std::to_string(r.non_orientable_parts) + " non-orientable part(s) left as found";
    warnings.push_back(text);
    return uint32_t(r.turned_faces);
}

void check_mesh(const Mesh& mesh, size_t m) {
    const std::string name = "mesh " + std::to_string(m) + (mesh.name.empty() ? "" : " (" + mesh.name + ")");
    const size_t n = mesh.positions.size();
    if (n == 0) throw std::invalid_argument(name + " has no vertices");
    if (n > (size_t(1) << 31)) throw std::invalid_argument(name + " has too many vertices");
    for (size_t i = 0; i < n; ++i)
        for (float c : mesh.positions[i])
            if (!std::isfinite(c))
                throw std::invalid_argument(name + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
        for (uint32_t v : mesh.triangles[t])
            if (v >= n)
                throw std::invalid_argument(name + ": triangle " + std::to_string(t) + " refers to vertex " +
                                            std::to_string(v) + " of " + std::to_string(n));
    auto sized = [&](size_t size, const char* what) {
        if (size != 0 && size != n)
            throw std::invalid_argument(name + ": " + what + " has " + std::to_string(size) + " values for " +
                                        std::to_string(n) + " vertices");
    };
    sized(mesh.normals.size(), "the normal array");
    sized(mesh.texcoords.size(), "the texture coordinate array");
    sized(mesh.colors.size(), "the colour array");
    if (mesh.texcoord_sets.size() > kMaxTexcoordSets)
        throw std::invalid_argument(name + ": " + std::to_string(mesh.texcoord_sets.size() + 1) +
                                    " texture-coordinate sets, at most " + std::to_string(kMaxTexcoordSets + 1) +
                                    " travel (TEXCOORD_0 to TEXCOORD_7)");
    if (!mesh.texcoord_sets.empty() && !mesh.has_texcoords())
        throw std::invalid_argument(name + ": TEXCOORD_1 and above without TEXCOORD_0");
    for (size_t k = 0; k < mesh.texcoord_sets.size(); ++k) {
        const std::string what = "the TEXCOORD_" + std::to_string(k + 1) + " array";
        if (mesh.texcoord_sets[k].size() != n)
            throw std::invalid_argument(name + ": " + what + " has " + std::to_string(mesh.texcoord_sets[k].size()) +
                                        " values for " + std::to_string(n) + " vertices");
    }
}

}  // namespace

namespace {

// An object's points and exact layer (everything of it but the ellipsoids), which depend on its
// ellipsoids only through `sheet` (flat ellipsoids were found: samples twice as dense): what
// encode_meshes keeps of them. May run beside the ellipsoids' encode, on its own copies.
struct PointsStage {
    ObjectContent content;  // all but the ellipsoids
    ObjectInfo object;
    ObjectReport report;    // the points' fields only (see take_points_report)
    std::vector<std::string> warnings;
    bool sheet = false;     // as made
};

void take_points_report(const ObjectReport& from, ObjectReport& to) {
    to.samples = from.samples;
    to.plain_point_bytes = from.plain_point_bytes;
    to.map_level = from.map_level;
    to.map_bytes = from.map_bytes;
    to.mapped_point_bytes = from.mapped_point_bytes;
    to.exact_triangles = from.exact_triangles;
    to.carried = from.carried;
    to.connectivity_bytes = from.connectivity_bytes;
    to.surface_normals = from.surface_normals;
    to.normals_sent = from.normals_sent;
    to.texcoord_sets = from.texcoord_sets;
}

PointsStage encode_object_points(const Mesh& mesh, const Mesh& input, size_t m, const StreamInfo& info,
                                 const ObjectInfo& object_in, const EncodeOptions& options, uint32_t object_seed,
                                 bool sheet, const Progress* progress) {
    PointsStage stage;
    stage.object = object_in;
    stage.sheet = sheet;
    ObjectContent& content = stage.content;
    ObjectInfo& object = stage.object;
    ObjectReport& report = stage.report;
    std::vector<std::string>& warnings = stage.warnings;
    std::vector<uint32_t> vertex_points;  // per vertex of the input (samples come after them)
    // Format 1.14 (spec 30.3): a range per further texture-coordinate set, at the first set's bits.
    std::vector<TexcoordRange> set_ranges;
    for (const auto& values : mesh.texcoord_sets) set_ranges.push_back(texcoord_range(values, options.texcoord_bits));
    std::vector<SetRecords> point_sets;
    if (!mesh.is_point_set && !mesh.triangles.empty() && options.sample_spacing > 0) {
        size_t added = 0;
        const Mesh sampled = with_surface_samples(mesh, sample_options(mesh, object.frame, options, sheet), added);
        report.samples = uint32_t(added);
        content.points = encode_points(sampled, info, object, object_seed, &vertex_points, set_ranges, &point_sets);
    } else {
        content.points = encode_points(mesh, info, object, object_seed, &vertex_points, set_ranges, &point_sets);
    }
    // Format 1.8 (spec 24): normals left to the exact layer's surface where they agree with it;
    // the records then carry none, and NORMALS packets say which are sent.
    if (options.normal_tolerance > 0 && options.exact_layer && object.has(kAttrNormal) && !mesh.is_point_set &&
        !input.triangles.empty()) {
        content.normals = surface_normal_entries(content.points, exact_triangles_of(input, vertex_points), info,
                                                 options.normal_tolerance);
        // Only where it pays: NORMALS packets (a bit a point, the normals sent, their framing)
        // smaller than the normals in the records. A box, whose every point is at a crease, keeps
        // format 1.7's records.
        size_t sent = 0;
        for (const NormalEntry& e : content.normals) sent += e.sent;
        const double record_bits = 2.0 * info.normal_bits * double(content.points.size());
        const double normals_bits = double(content.points.size()) + 2.0 * info.normal_bits * double(sent);
        const double packets = std::ceil(normals_bits / (8.0 * double(info.packet_size - kPacketOverhead - kNormalsHeaderSize)));
        if (sent < content.normals.size() &&
            normals_bits + 8.0 * double(kPacketOverhead + kNormalsHeaderSize) * packets < record_bits) {
            object.attributes &= uint8_t(~kAttrNormal);
            object.surface_normals = true;
        } else {
            content.normals.clear();
        }
    }
    // Format 1.11 (spec 27): vertices carried by the exact layer, in an object without per-point
    // data and without normals in its records (those would travel with each carried vertex); with
    // surface normals (format 1.8), the vertices whose normal the surface gives back.
    std::vector<QuantizedPoint> carried;
    // Nor in an object with further texture-coordinate sets (format 1.14, spec 30.3): TEXCOORDS
    // records are per point.
    if (options.point_share < 1 && options.exact_layer && !mesh.is_point_set && !mesh.per_point_data &&
        set_ranges.empty() && !input.triangles.empty() && !object.has(kAttrNormal))
        carried = carry_vertices(input, vertex_points, content.points, content.normals, options.point_share);
    // Format 1.7 (spec 23): points sent over a map of occupied cells, where that takes fewer bytes.
    // The map deals them to packets along a space-filling curve: the order changes, and every
    // per-vertex index with it.
    object.point_count = uint32_t(content.points.size());
    if (options.point_map) {
        const PointMapChoice choice = choose_point_map(content.points, info, object);
        report.plain_point_bytes = choice.plain_bytes;
        if (choice.level > 0) {
            const std::vector<uint32_t> order =
                mapped_order(content.points, info.position_bits, choice.level, choice.batch);
            std::vector<QuantizedPoint> sorted(order.size());
            std::vector<uint32_t> new_index(order.size());
            for (uint32_t i = 0; i < order.size(); ++i) {
                sorted[i] = content.points[order[i]];
                new_index[order[i]] = i;
            }
            content.points = std::move(sorted);
            if (!content.normals.empty()) {
                std::vector<NormalEntry> normals(order.size());
                for (uint32_t i = 0; i < order.size(); ++i) normals[i] = content.normals[order[i]];
                content.normals = std::move(normals);
            }
            if (!point_sets.empty()) {
                std::vector<SetRecords> sets(order.size());
                for (uint32_t i = 0; i < order.size(); ++i) sets[i] = point_sets[order[i]];
                point_sets = std::move(sets);
            }
            for (uint32_t& v : vertex_points)
                if (v < new_index.size()) v = new_index[v];  // a carried vertex keeps its number
            object.map_level = choice.level;
            object.map_batch = choice.batch;
            report.map_level = choice.level;
            report.map_bytes = choice.map_bytes;
            report.mapped_point_bytes = choice.point_bytes;
        }
    }
    // The original triangles as the input has them (not as turned for encoding): the exact layer.
    if (options.exact_layer && !mesh.is_point_set && !input.triangles.empty()) {
        if (progress) (*progress)("exact layer", 0.99);
        uint32_t dropped = 0;
        object.point_count = uint32_t(content.points.size());
        encode_exact_layer(input, vertex_points, carried, info, object, content, dropped);
        report.exact_triangles = content.triangle_count;
        report.carried = uint32_t(content.carried.size());
        if (content.connectivity.empty() && !carried.empty())
            throw std::logic_error("the exact layer that was to carry " + std::to_string(carried.size()) +
                                   " vertices could not be coded");
        object.exact_layer = !content.connectivity.empty();
        report.connectivity_bytes = uint32_t(content.connectivity.size());
        if (dropped > 0)
            warnings.push_back("mesh " + std::to_string(m) + (input.name.empty() ? "" : " (" + input.name + ")") + ": " + std::to_string(dropped) +
                                      " triangle(s) whose corners are one point after quantization are left out "
                                      "of the exact layer");
    }
    if (object.surface_normals && !object.exact_layer) {
        // No exact layer after all (every triangle degenerate): the normals go in the records.
        object.surface_normals = false;
        object.attributes |= kAttrNormal;
        content.normals.clear();
    }
    if (object.surface_normals) {
        report.surface_normals = true;
        for (const NormalEntry& e : content.normals) report.normals_sent += e.sent;
    }
    // Format 1.14 (spec 30): the further sets, a record per point in the points' final order.
    for (size_t s = 0; s < set_ranges.size(); ++s) {
        TexcoordSet set;
        set.range = set_ranges[s];
        set.records.reserve(point_sets.size());
        for (const SetRecords& r : point_sets) set.records.push_back(r[s]);
        content.texcoord_sets.push_back(std::move(set));
    }
    report.texcoord_sets = uint32_t(content.texcoord_sets.size());
    return stage;
}

}  // namespace

EncodeResult encode_meshes(const std::vector<Mesh>& meshes, const EncodeOptions& options) {
    if (std::string why = check_encode_options(options); !why.empty()) throw std::invalid_argument(why);
    if (meshes.empty()) throw std::invalid_argument("no meshes to encode");
    if (meshes.size() > kMaxObjects)
        throw std::invalid_argument("at most " + std::to_string(kMaxObjects) + " objects per stream (got " +
                                    std::to_string(meshes.size()) + ")");
    EncodeResult result;
    StreamInfo& info = result.info;
    info.packet_size = options.packet_size;
    info.position_bits = options.position_bits;
    info.normal_bits = options.normal_bits;
    info.texcoord_bits = options.texcoord_bits;
    info.color_bits = options.color_bits;
    info.coverage_target = float(options.coverage);
    info.seed = options.seed;
    Progress progress{options, 0, meshes.size()};
    uint16_t grid_hint = 0;
    // Many objects share the work: past 8 surfaces, each gets a smaller share of the seeds.
    size_t surfaces = 0;
    for (const Mesh& mesh : meshes) surfaces += !mesh.is_point_set && !mesh.triangles.empty();
    const double seed_share = surfaces > 8 ? 8.0 / double(surfaces) : 1.0;
    for (size_t m = 0; m < meshes.size(); ++m) {
        const Mesh& input = meshes[m];
        progress.object = m;
        check_mesh(input, m);
        // The inside test and the crease detection need outward-facing triangles: parts that face
        // inward or disagree with themselves are encoded as their repair (orientation.cpp).
        // Vertices welded once: turning triangles leaves the positions as they are.
        const bool surface = !input.is_point_set && !input.triangles.empty();
        const std::vector<uint32_t> weld = surface ? weld_by_position(input) : std::vector<uint32_t>{};
        Mesh oriented;
        const uint32_t turned = orient_for_encoding(input, weld, oriented, result.warnings);
        const Mesh& mesh = turned > 0 ? oriented : input;
        const bool closed = surface && is_closed(mesh, weld);
        ObjectInfo object;
        object.frame = frame_of(mesh);
        object.kind = mesh.is_point_set ? ObjectKind::PointSet : ObjectKind::Surface;
        if (mesh.has_normals()) object.attributes |= kAttrNormal;
        if (mesh.has_texcoords()) {
            object.attributes |= kAttrTexcoord;
            std::array<float, 2> lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
            for (const auto& t : mesh.texcoords)
                for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], t[k]), hi[k] = std::max(hi[k], t[k]);
            for (int k = 0; k < 2; ++k) {
                object.texcoord_origin[k] = lo[k];
                object.texcoord_scale[k] = hi[k] > lo[k] ? hi[k] - lo[k] : 1.0f;
                while (double(lo[k]) + double(object.texcoord_scale[k]) < hi[k])
                    object.texcoord_scale[k] = std::nextafter(object.texcoord_scale[k], INFINITY);
            }
        }
        if (mesh.has_colors()) object.attributes |= kAttrColor | (mesh.colors_have_alpha ? kAttrColorAlpha : 0);

        ObjectReport report;
        report.name = mesh.name;
        report.point_set = mesh.is_point_set;
        report.vertices = uint32_t(mesh.positions.size());
        report.turned_faces = turned;
        ObjectContent content;
        const uint32_t object_seed = options.seed * 2654435761u + uint32_t(m) * 40503u + 1u;
        // The points stage depends on the ellipsoids only through `sheet` (flat ellipsoids found,
        // which only an open surface or one without inside has): with worker threads, it starts
        // beside them on a guess (flat ones on an open surface, none on a closed one), and runs
        // again after them when the guess was wrong.
        std::future<PointsStage> early;
        if (surface && options.threads > 1)
            early = std::async(std::launch::async, encode_object_points, std::cref(mesh), std::cref(input), m,
                               std::cref(info), std::cref(object), std::cref(options), object_seed,
                               options.sample_spacing > 0 && !closed, nullptr);
        if (surface) {
            EncodeOptions object_options = options;
            object_options.max_ellipsoids = ellipsoid_budget(mesh, info, object, options);
            if (object_options.max_ellipsoids < options.max_ellipsoids) report.ellipsoid_budget = object_options.max_ellipsoids;
            content.ellipsoids = encode_ellipsoids(mesh, weld, closed, object.frame, object_options, object_seed,
                                                   seed_share, report, result.warnings, progress);
            grid_hint = std::max<uint16_t>(grid_hint, uint16_t(std::max({report.grid[0], report.grid[1], report.grid[2]})));
        }
        progress("points", 0.97);
        const bool sheet = report.flat_ellipsoids > 0 && options.sample_spacing > 0;
        PointsStage stage;
        bool made = false;
        if (early.valid()) {
            // Kept when the guess was right; a guess's error is not this stream's (made again, an
            // error of the right guess comes back).
            try {
                stage = early.get();
                made = stage.sheet == sheet;
            } catch (const std::exception&) {
            }
        }
        if (!made) stage = encode_object_points(mesh, input, m, info, object, options, object_seed, sheet, &progress);
        stage.content.ellipsoids = std::move(content.ellipsoids);
        content = std::move(stage.content);
        object = stage.object;
        take_points_report(stage.report, report);
        for (auto& w : stage.warnings) result.warnings.push_back(std::move(w));
        object.ellipsoid_count = uint32_t(content.ellipsoids.size());
        object.point_count = uint32_t(content.points.size());
        report.points = object.point_count;
        info.objects.push_back(object);
        result.contents.push_back(std::move(content));
        result.reports.push_back(report);
        progress("points", 1.0);
    }
    info.grid_hint = grid_hint;
    // The content id: a checksum of everything quantized, so a receiver can tell new content.
    uint32_t crc = 0;
    for (size_t m = 0; m < result.contents.size(); ++m) {
        for (const auto& q : result.contents[m].ellipsoids) {
            uint8_t bytes[kEllipsoidBytes];
            pack_ellipsoid(q, bytes);
            crc = crc32c(bytes, kEllipsoidBytes, crc);
        }
        // Format 1.11: the carried vertices are content too.
        std::vector<QuantizedPoint> all = result.contents[m].points;
        all.insert(all.end(), result.contents[m].carried.begin(), result.contents[m].carried.end());
        for (const auto& q : all) {
            uint32_t v[11] = {q.position[0], q.position[1], q.position[2], q.normal[0], q.normal[1], q.texcoord[0],
                              q.texcoord[1], q.color[0], q.color[1], q.color[2], q.color[3]};
            crc = crc32c(reinterpret_cast<const uint8_t*>(v), sizeof v, crc);
        }
        // Which normals are sent (format 1.8): another tolerance is other content.
        for (const NormalEntry& e : result.contents[m].normals) {
            const uint8_t sent = e.sent;
            crc = crc32c(&sent, 1, crc);
        }
        // Further texture-coordinate sets (format 1.14): their ranges and records.
        for (const TexcoordSet& set : result.contents[m].texcoord_sets) {
            const float range[4] = {set.range.origin[0], set.range.origin[1], set.range.scale[0], set.range.scale[1]};
            crc = crc32c(reinterpret_cast<const uint8_t*>(range), sizeof range, crc);
            crc = crc32c(reinterpret_cast<const uint8_t*>(set.records.data()), set.records.size() * sizeof(set.records[0]), crc);
        }
    }
    info.content_id = crc;
    if (check_stream_info(info) != Error::Ok) throw std::logic_error("encoder produced an invalid stream info");
    return result;
}

}  // namespace ellicast

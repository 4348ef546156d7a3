// Encoder speed, size and coverage: the bunny, a ~50k-vertex closed procedural model with 400
// ellipsoids, and every sample model. Prints time per stage and the figures of issue 3.
//   build/bench/bench_encode [--samples DIR] [--only NAME]
#include "ellicast/codec/encoder.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"
#include "shapes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <sys/resource.h>

using namespace ellicast;
using Clock = std::chrono::steady_clock;

namespace {

// A closed, bumpy, genus-1 model: a torus with ridges, `u` x `v` vertices.
Mesh bumpy_torus(int u, int v) {
    Mesh m;
    m.name = "bumpy torus";
    for (int i = 0; i < u; ++i)
        for (int j = 0; j < v; ++j) {
            double a = 2 * M_PI * i / u, b = 2 * M_PI * j / v;
            double r = 0.35 + 0.06 * std::sin(5 * a) * std::cos(3 * b) + 0.03 * std::sin(11 * b);
            double R = 1.0 + 0.15 * std::cos(3 * a);
            m.positions.push_back({float((R + r * std::cos(b)) * std::cos(a)), float((R + r * std::cos(b)) * std::sin(a)),
                                   float(r * std::sin(b) + 0.2 * std::sin(2 * a))});
        }
    for (int i = 0; i < u; ++i)
        for (int j = 0; j < v; ++j) {
            uint32_t p = i * v + j, q = ((i + 1) % u) * v + j, r = ((i + 1) % u) * v + (j + 1) % v,
                     s = i * v + (j + 1) % v;
            m.triangles.push_back({p, q, r});
            m.triangles.push_back({p, r, s});
        }
    return m;
}

// A small closed sphere of `n` rings around `c`.
Mesh small_sphere(int n, std::array<float, 3> c, float r) {
    Mesh m = samples::uv_ellipsoid(n, {c[0], c[1], c[2]}, {r, r, r});
    m.name = "sphere";
    return m;
}

struct Run {
    double seconds = 0;
    std::map<std::string, double> stages;
    EncodeResult result;
    size_t base_bytes = 0, detail_bytes = 0;
};

Run encode(const std::vector<Mesh>& meshes, EncodeOptions options) {
    Run run;
    std::string stage;
    auto t0 = Clock::now(), last = t0;
    options.progress = [&](const std::string& s, double) {
        auto now = Clock::now();
        if (!stage.empty()) run.stages[stage] += std::chrono::duration<double>(now - last).count();
        stage = s;
        last = now;
    };
    run.result = encode_meshes(meshes, options);
    auto end = Clock::now();
    if (!stage.empty()) run.stages[stage] += std::chrono::duration<double>(end - last).count();
    run.seconds = std::chrono::duration<double>(end - t0).count();
    StreamPackets packets;
    if (packetize_stream(run.result.info, run.result.contents, 1, packets) == Error::Ok) {
        for (auto& p : packets.ellipsoids) run.base_bytes += p.size();
        for (auto& p : packets.points) run.detail_bytes += p.size();
        for (auto& p : packets.maps) run.detail_bytes += p.size();  // format 1.7: the map, counted with the points it places
        for (auto& p : packets.normals) run.detail_bytes += p.size();  // format 1.8: NORMALS
    }
    return run;
}

void report(const std::string& name, const Run& run) {
    size_t e = 0, p = 0;
    for (const auto& o : run.result.info.objects) e += o.ellipsoid_count, p += o.point_count;
    std::printf("%-28s %7.2f s  ellipsoids %5zu  points %7zu  B/ellipsoid %.2f  B/point %.2f\n", name.c_str(),
                run.seconds, e, p, e ? double(run.base_bytes) / e : 0.0, p ? double(run.detail_bytes) / p : 0.0);
    std::printf("    stages:");
    for (const auto& [s, t] : run.stages) std::printf("  %s %.2f s", s.c_str(), t);
    std::printf("\n");
    for (const auto& r : run.result.reports) {
        if (r.point_set) continue;
        std::printf("    %-24s %s  coverage %5.1f%%  outside %5.2f%%  ellipsoids %u (thin %u, flat %u, shrunk %u)  "
                    "grid %ux%ux%u  candidates %u  interior %.3f  surface near %.3f\n",
                    r.name.c_str(), r.closed ? "closed" : "open  ", 100 * r.coverage, 100 * r.outside, r.ellipsoids,
                    r.surface_ellipsoids, r.flat_ellipsoids, r.shrunk, r.grid[0], r.grid[1], r.grid[2], r.candidates,
                    r.interior_fraction, r.surface_covered);
    }
}

}  // namespace

int main(int argc, char** argv) {
    // ../shared/samples next to the checkout (this file is <checkout>/bench/bench_encode.cpp).
    std::string samples = (std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "shared" /
                           "samples").string();
    std::string only;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--samples")) samples = argv[i + 1];
        else if (!std::strcmp(argv[i], "--only")) only = argv[i + 1];
    }
    EncodeOptions options;  // defaults: 400 ellipsoids, 95% coverage, 14-bit positions
    if (only.empty() || only == "torus") {
        Mesh torus = bumpy_torus(400, 125);  // 50,000 vertices, closed
        report("bumpy torus 50k (400 ell.)", encode({torus}, options));
    }
    if (only.empty() || only == "spheres") {
        std::vector<Mesh> scene;  // a scene of many small objects: the per-object work is shared out
        for (int i = 0; i < 64; ++i) scene.push_back(small_sphere(8, {float(i % 8), float(i / 8), 0}, 0.4f));
        Run run = encode(scene, options);
        std::printf("%-28s %7.2f s  objects %zu\n", "64 small spheres", run.seconds, scene.size());
        std::printf("    stages:");
        for (const auto& [s, t] : run.stages) std::printf("  %s %.2f s", s.c_str(), t);
        std::printf("\n");
        double low = 1, high_out = 0;
        size_t ellipsoids = 0;
        for (const ObjectReport& r : run.result.reports) {
            low = std::min(low, r.coverage);
            high_out = std::max(high_out, r.outside);
            ellipsoids += r.ellipsoids;
        }
        const ObjectReport& r = run.result.reports[0];
        std::printf("    per sphere: lowest coverage %5.1f%%  highest outside %5.2f%%  ellipsoids %zu in all  grid %ux%ux%u  "
                    "candidates %u\n", 100 * low, 100 * high_out, ellipsoids, r.grid[0], r.grid[1], r.grid[2], r.candidates);
    }
    std::vector<std::string> files;  // every model under the samples, in a fixed order
    if (std::filesystem::is_directory(samples))
        for (const auto& entry : std::filesystem::recursive_directory_iterator(samples)) {
            std::string ext = entry.path().extension().string();
            if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl" || ext == ".gltf" || ext == ".glb")
                files.push_back(std::filesystem::relative(entry.path(), samples).string());
        }
    std::sort(files.begin(), files.end());
    if (files.empty()) std::printf("no sample models under %s\n", samples.c_str());
    for (const std::string& f : files) {
        if (!only.empty() && f.find(only) == std::string::npos) continue;
        std::string path = samples + "/" + f;
        try {
            LoadResult loaded = load_meshes(path);
            report(f, encode(loaded.meshes, options));
        } catch (const std::exception& e) {
            std::printf("%-28s error: %s\n", f.c_str(), e.what());
        }
    }
    struct rusage usage {};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("peak memory (max RSS) %.1f MB\n", usage.ru_maxrss / 1024.0);
    return 0;
}

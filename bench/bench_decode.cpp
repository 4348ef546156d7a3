// Decoder benchmarks.
//
//   bench_decode                         speed on synthetic input: base mesh from 400 ellipsoids,
//                                        50k points inserted with flips and collapses; a stream far
//                                        sparser than its base (8 points); peak memory
//   bench_decode STREAM.ellc ORIGINAL    quality on a real stream against its original model:
//                                        ellipsoids only, every packet, half of the point packets
//                                        lost at random (several seeds); RMS/max/far area both ways
//
// Times are wall clock and CPU time of the decoding thread (the CPU time is what to compare on a
// shared, loaded machine).
#include "ellicast/codec/decoder.h"
#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <sys/resource.h>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <algorithm>
#include <random>

using namespace ellicast;

namespace {

double wall_now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
double cpu_now() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}
double peak_mb() {
    rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss / 1024.0;
}

std::vector<SurfacePoint> fibonacci_sphere(size_t n, double radius) {
    std::vector<SurfacePoint> points(n);
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (size_t i = 0; i < n; ++i) {
        double y = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - y * y), t = golden * i;
        double d[3] = {std::cos(t) * r, y, std::sin(t) * r};
        for (int k = 0; k < 3; ++k) points[i].position[k] = float(radius * d[k]), points[i].normal[k] = float(d[k]);
    }
    return points;
}

// 400 ellipsoids filling a unit sphere roughly, as an encoder would: spheroids under the surface.
std::vector<Ellipsoid> blob_ellipsoids(size_t n) {
    std::vector<Ellipsoid> out;
    auto centres = fibonacci_sphere(n, 0.75);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> jitter(0.9f, 1.1f);
    for (const auto& c : centres) {
        Ellipsoid e;
        e.center = c.position;
        e.radii = {0.3f * jitter(rng), 0.3f * jitter(rng), 0.24f * jitter(rng)};
        // Rotate the short axis towards the normal: quaternion from z to n.
        double nz[3] = {c.normal[0], c.normal[1], c.normal[2]};
        double w = 1 + nz[2], x = -nz[1], y = nz[0], z = 0;
        double l = std::sqrt(w * w + x * x + y * y + z * z);
        if (l < 1e-9) e.rotation = {0, 1, 0, 0};
        else e.rotation = {float(w / l), float(x / l), float(y / l), float(z / l)};
        out.push_back(e);
    }
    return out;
}

int speed() {
    ObjectInfo info;
    info.frame.origin = {-1.25f, -1.25f, -1.25f};
    info.frame.scale = 2.5f;
    info.attributes = kAttrNormal;
    auto ellipsoids = blob_ellipsoids(400);
    info.ellipsoid_count = uint32_t(ellipsoids.size());

    // Base mesh: rasterization + marching cubes, best of 5.
    double best_wall = 1e9, best_cpu = 1e9;
    size_t base_faces = 0;
    for (int rep = 0; rep < 5; ++rep) {
        double w0 = wall_now(), c0 = cpu_now();
        EllipsoidGrid grid;
        std::string error;
        if (!rasterize_ellipsoids(ellipsoids, info.frame, kDefaultGridResolution, grid, error)) {
            std::fprintf(stderr, "%s\n", error.c_str());
            return 1;
        }
        DecoderTriMesh base = marching_cubes(grid);
        best_wall = std::min(best_wall, wall_now() - w0);
        best_cpu = std::min(best_cpu, cpu_now() - c0);
        base_faces = base.n_faces();
    }
    std::printf("base mesh from %zu ellipsoids (grid %d): %.4f s wall, %.4f s CPU (best of 5), %zu faces\n",
                ellipsoids.size(), kDefaultGridResolution, best_wall, best_cpu, base_faces);
    std::printf("  peak memory so far (max RSS): %.1f MB\n", peak_mb());

    for (size_t n : {size_t(50000), size_t(100000)}) {
        auto points = fibonacci_sphere(n, 1.0);
        // Spread order, like the encoder's stream: a fixed pseudo-random permutation.
        std::mt19937 rng(7);
        std::shuffle(points.begin(), points.end(), rng);
        info.point_count = uint32_t(n);
        // The stages one by one, as decode_object runs them, timed separately.
        EllipsoidGrid grid;
        std::string error;
        rasterize_ellipsoids(ellipsoids, info.frame, kDefaultGridResolution, grid, error);
        Reconstruction r;
        start_reconstruction(r, marching_cubes(grid), info.frame, grid.cell, n, ReconstructionOptions{});
        double w0 = wall_now(), c0 = cpu_now();
        for (size_t i = 0; i < n; ++i) {
            OpenMesh::VertexHandle v;
            if (insert_point(r, uint32_t(i), points[i].position, v) == Insertion::SeamDuplicate) continue;
            flip_edges_around(r, v);
            collapse_mc_vertices_near(r, v);
        }
        double insert_wall = wall_now() - w0, insert_cpu = cpu_now() - c0;
        size_t during = r.collapses, left = r.mc_vertices;
        w0 = wall_now(), c0 = cpu_now();
        collapse_all_mc_vertices(r, true);
        double clean_wall = wall_now() - w0, clean_cpu = cpu_now() - c0;
        w0 = wall_now(), c0 = cpu_now();
        r.normals = &points;
        const size_t reinserted = agree_with_received_normals(r);
        double agree_wall = wall_now() - w0, agree_cpu = cpu_now() - c0;
        w0 = wall_now(), c0 = cpu_now();
        Mesh out = extract_mesh(r, info, points);
        double out_wall = wall_now() - w0, out_cpu = cpu_now() - c0;
        std::printf("%zu points inserted with flips and collapses: %.3f s wall, %.3f s CPU (%.0f points/s CPU); "
                    "%zu face splits, %zu edge splits, %zu MC vertices moved, %zu flips, %zu collapses "
                    "(%zu MC vertices left)\n",
                    n, insert_wall, insert_cpu, n / insert_cpu, r.face_splits, r.edge_splits, r.vertex_moves, r.flips,
                    during, left);
        std::printf("  final collapse of the remaining MC vertices: %.3f s wall, %.3f s CPU (%zu collapses, %zu left); "
                    "output mesh %.3f s wall, %.3f s CPU; %zu faces\n",
                    clean_wall, clean_cpu, r.collapses - during, r.mc_vertices, out_wall, out_cpu, out.triangles.size());
        std::printf("  agreement with the received normals: %.3f s wall, %.3f s CPU (%zu vertices inserted again)\n",
                    agree_wall, agree_cpu, reinserted);
        std::printf("  peak memory so far (max RSS): %.1f MB\n", peak_mb());
    }
    {
        // A stream far sparser than its base (what an older encoder, or --sample-spacing 0, sends for
        // a cube): a ball's base and the cube's 8 corners. The final forced collapse removes every
        // marching-cubes vertex; it should cost about as much as the base.
        ObjectInfo cube = info;
        cube.point_count = 8;
        std::vector<SurfacePoint> corners(8);
        for (int i = 0; i < 8; ++i)
            corners[i].position = {i & 1 ? 0.55f : -0.55f, i & 2 ? 0.55f : -0.55f, i & 4 ? 0.55f : -0.55f};
        Ellipsoid ball;
        ball.center = {0, 0, 0};
        ball.radii = {0.9f, 0.9f, 0.9f};
        double w0 = wall_now(), c0 = cpu_now();
        EllipsoidGrid grid;
        std::string error;
        rasterize_ellipsoids({ball}, cube.frame, kDefaultGridResolution, grid, error);
        DecoderTriMesh base = marching_cubes(grid);
        const double base_cpu = cpu_now() - c0, base_wall = wall_now() - w0;
        const size_t base_vertices = base.n_vertices();
        Reconstruction r;
        start_reconstruction(r, std::move(base), cube.frame, grid.cell, 8, ReconstructionOptions{});
        for (size_t i = 0; i < corners.size(); ++i) {
            OpenMesh::VertexHandle v;
            if (insert_point(r, uint32_t(i), corners[i].position, v) == Insertion::SeamDuplicate) continue;
            flip_edges_around(r, v);
            collapse_mc_vertices_near(r, v);
        }
        w0 = wall_now(), c0 = cpu_now();
        collapse_all_mc_vertices(r, true);
        const double clean_cpu = cpu_now() - c0, clean_wall = wall_now() - w0;
        Mesh out = extract_mesh(r, cube, corners);
        std::printf("sparse stream (8 cube corners on a ball's base of %zu vertices): base %.3f s wall, %.3f s CPU; "
                    "final collapse %.3f s wall, %.3f s CPU (%zu collapses, %zu flips, %zu MC vertices left); %zu "
                    "faces out\n",
                    base_vertices, base_wall, base_cpu, clean_wall, clean_cpu, r.collapses, r.flips, r.mc_vertices,
                    out.triangles.size());
    }
    std::printf("peak memory (max RSS): %.1f MB\n", peak_mb());
    return 0;
}

struct Row {
    std::string name;
    size_t ellipsoids = 0, points = 0, faces = 0, mc_left = 0;
    double seconds = 0;
    SurfaceDistance d;
};

bool decode_packets(const std::vector<const ContainerPacket*>& packets, Mesh& mesh, ObjectDecodeReport& report,
                    double& seconds) {
    ReceivedStream stream;
    for (const auto* p : packets) stream.add_parsed(p->view, p->offset);
    std::vector<Mesh> meshes;
    StreamDecodeReport sr;
    std::string error;
    double w0 = wall_now();
    DecodeOptions options;
    options.exact = false;  // what is measured is the reconstruction, not the exact layer (spec 19)
    if (!decode_stream(stream, options, meshes, sr, error)) {
        std::fprintf(stderr, "decode: %s\n", error.c_str());
        return false;
    }
    seconds = wall_now() - w0;
    if (meshes.empty()) return false;
    mesh = meshes[0];
    report = sr.objects[0];
    return true;
}

int quality(const std::string& stream_path, const std::string& original_path, int trials) {
    std::vector<uint8_t> bytes;
    std::string message;
    if (read_file(stream_path, bytes, message) != Error::Ok) {
        std::fprintf(stderr, "%s\n", message.c_str());
        return 1;
    }
    ContainerContents contents = read_container(bytes);
    std::vector<Mesh> original;
    try {
        original = load_meshes(original_path).meshes;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    // The base (stream info, ellipsoids, format 1.7's point map, the scene) and the point packets;
    // repair packets and the exact layer (formats 1.2, 1.3) are left out: the rows with lost points
    // measure what the points alone give, as the paper does (before, the repair packets counted as
    // base and brought back every point).
    std::vector<const ContainerPacket*> info, ellipsoids, points, extra;
    for (const auto& p : contents.packets) {
        const uint8_t type = p.view.header.type;
        if (is_points_type(type)) points.push_back(&p);
        else if (type == uint8_t(PacketType::Ellipsoids)) ellipsoids.push_back(&p);
        else if (type == uint8_t(PacketType::PointsRepair) || is_exact_layer_type(type) || is_exact_layer_repair_type(type))
            extra.push_back(&p);
        else info.push_back(&p);
    }
    std::vector<Row> rows;
    auto run = [&](const std::string& name, std::vector<const ContainerPacket*> packets) {
        Row row;
        row.name = name;
        Mesh mesh;
        ObjectDecodeReport report;
        if (!decode_packets(packets, mesh, report, row.seconds)) return;
        row.ellipsoids = report.ellipsoids;
        row.points = report.points;
        row.faces = mesh.triangles.size();
        row.mc_left = report.mc_vertices_left;
        std::string error;
        SurfaceDistanceOptions options;
        options.threshold_percent = 0.5;
        if (!surface_distance(original, {mesh}, options, row.d, error)) {
            std::fprintf(stderr, "%s: %s\n", name.c_str(), error.c_str());
            return;
        }
        rows.push_back(row);
    };
    auto base = info;
    base.insert(base.end(), ellipsoids.begin(), ellipsoids.end());
    run("ellipsoids only", base);
    auto all = base;
    all.insert(all.end(), points.begin(), points.end());
    run("all packets", all);  // every point; the exact layer is not what is measured (decode_packets)
    for (int t = 0; t < trials; ++t) {
        std::mt19937 rng(100 + t);
        auto half = points;
        std::shuffle(half.begin(), half.end(), rng);
        half.resize(points.size() / 2);
        auto packets = base;
        packets.insert(packets.end(), half.begin(), half.end());
        std::shuffle(packets.begin(), packets.end(), rng);
        run("half point packets lost (seed " + std::to_string(100 + t) + ")", packets);
    }
    std::printf("%s vs %s (diagonal %.6g; far = > 0.5%% of it)\n", original_path.c_str(), stream_path.c_str(),
                rows.empty() ? 0.0 : rows[0].d.diagonal);
    std::printf("| received | ellipsoids | points | faces | MC left | orig->rec RMS | orig->rec max | orig far area | "
                "rec->orig RMS | rec->orig max | decode s |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& r : rows) {
        std::printf("| %s | %zu | %zu | %zu | %zu | %.4f%% | %.3f%% | %.3f%% | %.4f%% | %.3f%% | %.3f |\n", r.name.c_str(),
                    r.ellipsoids, r.points, r.faces, r.mc_left, r.d.percent(r.d.a_to_b.rms), r.d.percent(r.d.a_to_b.max),
                    100 * r.d.a_to_b.far_fraction, r.d.percent(r.d.b_to_a.rms), r.d.percent(r.d.b_to_a.max), r.seconds);
    }
    std::printf("peak memory (max RSS): %.1f MB\n", peak_mb());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 1) return speed();
    if (argc >= 3) return quality(argv[1], argv[2], argc >= 4 ? std::atoi(argv[3]) : 3);
    std::fprintf(stderr, "usage: bench_decode [STREAM.ellc ORIGINAL [TRIALS]]\n");
    return 2;
}

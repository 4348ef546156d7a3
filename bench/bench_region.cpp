// Refinement where the viewer looks (issue 33; the paper's closing claim): a receiver that inserts
// only the points inside a region of interest, holding the others, against one that inserts every
// point it holds. For shares of the points received (the first N in stream order, spread over the
// surface as the packets are), both decode the object; the table gives the insertion time and the
// surface error inside the region (reference surface cropped to the region -> decoded surface, RMS
// in % of the reference's diagonal) and outside it. The region receiver inserts the points within a
// margin of 2% of the diagonal around the region, so that the triangles at its border are refined
// from both sides (without it, the error inside rose 1.9x at every point on the bunny).
//
//   bench_region STREAM.ellc REFERENCE [X0,Y0,Z0,X1,Y1,Z1]
//                 the region defaults to the quarter of the bounding box at the largest x and y
//   bench_region subdivide IN OUT.ply LEVELS
//                 Loop subdivision (OpenMesh), to make a dense model from a sample
#include "ellicast/codec/decoder.h"
#include "ellicast/codec/region.h"
#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/converters/mesh_output.h"
#include "ellicast/format.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

using namespace ellicast;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int subdivide(const std::string& in, const std::string& out, int levels) {
    Mesh m = load_meshes(in).meshes.at(0);
    using TriMesh = OpenMesh::TriMesh_ArrayKernelT<>;
    TriMesh tm;
    std::vector<TriMesh::VertexHandle> v;
    for (const auto& p : m.positions) v.push_back(tm.add_vertex(TriMesh::Point(p[0], p[1], p[2])));
    for (const auto& t : m.triangles) tm.add_face(v[t[0]], v[t[1]], v[t[2]]);
    // Vertices no face could take (the scan's non-manifold spots) have no neighbours to average.
    tm.request_vertex_status();
    tm.request_edge_status();
    tm.request_face_status();
    tm.delete_isolated_vertices();
    tm.garbage_collection();
    OpenMesh::Subdivider::Uniform::LoopT<TriMesh> loop;
    loop.attach(tm);
    loop(levels);
    loop.detach();
    Mesh dense;
    dense.name = m.name;
    // A vertex the subdivision could not place (not finite) is left out with its faces.
    std::vector<uint32_t> index(tm.n_vertices(), UINT32_MAX);
    for (auto vh : tm.vertices()) {
        const auto& p = tm.point(vh);
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
        index[size_t(vh.idx())] = uint32_t(dense.positions.size());
        dense.positions.push_back({p[0], p[1], p[2]});
    }
    size_t dropped = 0;
    for (auto fh : tm.faces()) {
        std::array<uint32_t, 3> t{};
        int k = 0;
        for (auto vh : tm.fv_range(fh)) t[k++ % 3] = index[size_t(vh.idx())];
        if (t[0] == UINT32_MAX || t[1] == UINT32_MAX || t[2] == UINT32_MAX) {
            ++dropped;
            continue;
        }
        dense.triangles.push_back(t);
    }
    if (dropped) std::printf("%zu triangles dropped around vertices the subdivision left undefined\n", dropped);
    std::string error;
    if (!write_meshes(out, {dense}, error)) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }
    std::printf("%s: %zu vertices, %zu triangles (%d Loop subdivision levels of %s)\n", out.c_str(),
                dense.positions.size(), dense.triangles.size(), levels, in.c_str());
    return 0;
}

// The triangles of `m` whose centroid is inside (or outside) the region.
Mesh crop(const Mesh& m, const Region& r, bool inside) {
    Mesh out;
    out.positions = m.positions;
    for (const auto& t : m.triangles) {
        std::array<double, 3> c{};
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) c[k] += m.positions[t[j]][k] / 3.0;
        if (r.contains(c) == inside) out.triangles.push_back(t);
    }
    return out;
}

double rms_percent(const Mesh& reference_part, const Mesh& decoded, double diagonal) {
    SurfaceDistanceOptions o;
    o.samples = 100000;
    SurfaceDistance d;
    std::string error;
    if (!surface_distance({reference_part}, {decoded}, o, d, error)) return -1;
    return 100.0 * d.a_to_b.rms / diagonal;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 5 && std::string(argv[1]) == "subdivide") return subdivide(argv[2], argv[3], std::atoi(argv[4]));
    if (argc < 3) {
        std::fprintf(stderr, "usage: bench_region STREAM.ellc REFERENCE [X0,Y0,Z0,X1,Y1,Z1]\n"
                             "       bench_region subdivide IN OUT.ply LEVELS\n");
        return 2;
    }
    std::vector<uint8_t> bytes;
    std::string message;
    if (read_file(argv[1], bytes, message) != Error::Ok) {
        std::fprintf(stderr, "%s\n", message.c_str());
        return 1;
    }
    ContainerContents contents = read_container(bytes);
    ReceivedStream stream;
    for (const auto& p : contents.packets) stream.add_parsed(p.view, p.offset);
    if (!stream.info() || stream.objects().empty() || !stream.objects()[0].info) {
        std::fprintf(stderr, "%s: no stream info\n", argv[1]);
        return 1;
    }
    const Mesh reference = load_meshes(argv[2]).meshes.at(0);
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const auto& p : reference.positions)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
    const double diagonal = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]));
    Region region = Region::box({(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, lo[2]}, hi);
    if (argc > 3) {
        std::vector<double> v;
        std::stringstream items(argv[3]);
        std::string item;
        while (std::getline(items, item, ',')) v.push_back(std::stod(item));
        if (v.size() != 6) {
            std::fprintf(stderr, "the region is X0,Y0,Z0,X1,Y1,Z1\n");
            return 2;
        }
        region = Region::box({v[0], v[1], v[2]}, {v[3], v[4], v[5]});
    }
    const Mesh inside = crop(reference, region, true), outside = crop(reference, region, false);
    const double margin = 0.02 * diagonal;
    const Region widened = Region::box({region.min[0] - margin, region.min[1] - margin, region.min[2] - margin},
                                       {region.max[0] + margin, region.max[1] + margin, region.max[2] + margin});
    const ObjectInfo& info = *stream.objects()[0].info;
    const std::vector<Ellipsoid> ellipsoids = stream.ellipsoids(0);
    const std::vector<SurfacePoint> all = stream.points(0);
    std::printf("%s: %zu points; region %s holds %zu of %zu reference triangles\n", argv[1], all.size(),
                region.describe().c_str(), inside.triangles.size(), reference.triangles.size());
    std::printf("| points received | inserted: all / region | insertion s: all / region | speed-up | RMS inside: all / region | RMS outside: all / region |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|\n");
    for (double share : {0.25, 0.5, 1.0}) {
        const size_t n = size_t(share * double(all.size()));
        std::vector<SurfacePoint> received(all.begin(), all.begin() + long(n)), in_region;
        for (const auto& p : received)
            if (widened.contains({p.position[0], p.position[1], p.position[2]})) in_region.push_back(p);
        DecodeOptions options;
        options.faces_per_point = 0;  // the whole base: the same surface outside the region in both
        Mesh full, partial;
        ObjectDecodeReport r1, r2;
        std::string error;
        auto t0 = Clock::now();
        decode_object(info, ellipsoids, received, stream.info()->grid_hint, options, 0, full, r1, error);
        const double t_full = r1.timings.insertion > 0 ? r1.timings.insertion : since(t0);
        t0 = Clock::now();
        decode_object(info, ellipsoids, in_region, stream.info()->grid_hint, options, 0, partial, r2, error);
        const double t_region = r2.timings.insertion > 0 ? r2.timings.insertion : since(t0);
        std::printf("| %zu (%.0f%%) | %zu / %zu | %.3f / %.3f | %.1fx | %.4f%% / %.4f%% | %.4f%% / %.4f%% |\n", n,
                    100 * share, received.size(), in_region.size(), t_full, t_region, t_full / std::max(t_region, 1e-9),
                    rms_percent(inside, full, diagonal), rms_percent(inside, partial, diagonal),
                    rms_percent(outside, full, diagonal), rms_percent(outside, partial, diagonal));
        std::fflush(stdout);
    }
    return 0;
}

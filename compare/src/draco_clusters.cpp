// Baseline 3: the mesh cut into spatial clusters that each compress (Draco) into one packet and
// decode alone. A receiver shows the union of the clusters it holds; a lost packet is a hole.
#include "ellicast/compare/schemes.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ellicast::compare {

namespace {

constexpr size_t kClusterHeader = 4;  // u16 cluster index, u16 cluster count

struct Builder {
    const Mesh& mesh;
    DracoSettings settings;
    size_t capacity;  // bytes available for one cluster's Draco file
    std::vector<std::array<float, 3>> centroid;
    std::vector<std::vector<uint32_t>> clusters;
    std::vector<std::vector<uint8_t>> files;

    // Cuts `tris` into `parts` clusters (more where a cluster's file does not fit).
    void build(std::vector<uint32_t> tris, size_t parts) {
        if (tris.empty()) return;
        if (parts <= 1) {
            std::vector<uint8_t> file = draco_encode(submesh(mesh, tris), settings);
            if (file.size() <= capacity) {
                clusters.push_back(std::move(tris));
                files.push_back(std::move(file));
                return;
            }
            if (tris.size() == 1)
                throw CompareError("a single triangle does not fit one packet: the packet size is too small");
            parts = 2;
        }
        // Split along the longest axis of the centroids' box, in proportion to the parts on each side.
        std::array<float, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
        for (uint32_t t : tris)
            for (int c = 0; c < 3; ++c) {
                lo[c] = std::min(lo[c], centroid[t][c]);
                hi[c] = std::max(hi[c], centroid[t][c]);
            }
        int axis = 0;
        for (int c = 1; c < 3; ++c)
            if (hi[c] - lo[c] > hi[axis] - lo[axis]) axis = c;
        const size_t left_parts = parts / 2;
        const size_t cut = std::clamp<size_t>(tris.size() * left_parts / parts, 1, tris.size() - 1);
        std::nth_element(tris.begin(), tris.begin() + cut, tris.end(), [&](uint32_t a, uint32_t b) {
            return centroid[a][axis] < centroid[b][axis] || (centroid[a][axis] == centroid[b][axis] && a < b);
        });
        std::vector<uint32_t> left(tris.begin(), tris.begin() + cut), right(tris.begin() + cut, tris.end());
        std::sort(left.begin(), left.end());
        std::sort(right.begin(), right.end());
        build(std::move(left), left_parts);
        build(std::move(right), parts - left_parts);
    }
};

}  // namespace

DracoClusters::DracoClusters(const Mesh& mesh, const DracoSettings& settings, size_t packet_size) {
    const size_t capacity = payload_capacity(packet_size) - kClusterHeader;
    if (mesh.triangles.empty()) throw CompareError("Draco clusters: the mesh has no triangles");
    // One position grid for every cluster: that of the whole mesh, so shared borders match exactly.
    DracoSettings shared = settings;
    if (!shared.position_origin) {
        auto [origin, range] = position_cube(mesh);
        shared.position_origin = origin;
        shared.position_range = range;
    }
    Builder builder{mesh, shared, capacity, {}, {}, {}};
    builder.centroid.resize(mesh.triangles.size());
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c)
            builder.centroid[t][c] = (mesh.positions[mesh.triangles[t][0]][c] + mesh.positions[mesh.triangles[t][1]][c] +
                                      mesh.positions[mesh.triangles[t][2]][c]) /
                                     3.f;
    // First guess of the cluster count from the whole file's bytes per triangle, plus a margin for
    // what small files cost more (headers, vertices repeated along cluster borders).
    const size_t whole = draco_encode(mesh, shared).size();
    const size_t guess = std::max<size_t>(1, static_cast<size_t>(std::ceil(1.35 * double(whole) / double(capacity))));
    std::vector<uint32_t> all(mesh.triangles.size());
    for (size_t t = 0; t < all.size(); ++t) all[t] = uint32_t(t);
    builder.build(std::move(all), guess);
    if (builder.files.size() > 0xFFFF) throw CompareError("Draco clusters: more than 65535 clusters");

    clusters_ = std::move(builder.clusters);
    double fill = 0;
    for (size_t i = 0; i < builder.files.size(); ++i) {
        std::vector<uint8_t> payload(kClusterHeader + builder.files[i].size());
        payload[0] = uint8_t(i);
        payload[1] = uint8_t(i >> 8);
        payload[2] = uint8_t(builder.files.size());
        payload[3] = uint8_t(builder.files.size() >> 8);
        std::copy(builder.files[i].begin(), builder.files[i].end(), payload.begin() + kClusterHeader);
        fill += double(payload.size()) / double(capacity + kClusterHeader);
        packets_.push_back(baseline_packet(kDracoClusterType, static_cast<uint32_t>(i), payload));
    }
    mean_fill_ = fill / double(packets_.size());
}

std::string DracoClusters::describe() const {
    std::ostringstream s;
    s << cluster_count() << " spatial clusters, each its own Draco file in one packet (mean fill "
      << std::lround(mean_fill_ * 100) << "%), sent round robin; a lost packet is a hole";
    return s.str();
}

bool DracoClusters::reconstruct(const std::vector<uint32_t>& held, Mesh& out) const {
    out = Mesh{};
    std::vector<Mesh> parts;
    for (uint32_t index : held) {
        if (index >= packets_.size()) continue;
        auto payload = baseline_payload(packets_[index], kDracoClusterType);
        if (payload.size() <= kClusterHeader) continue;
        Mesh part;
        std::string error;
        if (!draco_decode(payload.subspan(kClusterHeader), part, error)) continue;
        parts.push_back(std::move(part));
    }
    if (parts.empty()) return false;
    out = concatenate(parts);
    return !out.triangles.empty();
}

}  // namespace ellicast::compare

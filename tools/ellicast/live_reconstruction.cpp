// The live receiver's progressive reconstruction.
#include "live_reconstruction.h"

namespace ellicast::cli {

bool LiveReconstruction::start(const ReceivedStream& stream, std::string& error) {
    if (!stream.info()) {
        error = "no stream info has arrived";
        return false;
    }
    stream_info_ = *stream.info();
    const auto& received = stream.objects();
    objects_.clear();
    objects_.resize(received.size());
    for (size_t i = 0; i < received.size(); ++i) {
        Object& o = objects_[i];
        if (!received[i].info) continue;
        o.present = true;
        o.info = *received[i].info;
        o.inserted.assign(o.info.point_count, false);
        if (o.info.kind != ObjectKind::Surface) continue;
        std::vector<Ellipsoid> ellipsoids = stream.ellipsoids(i);
        if (ellipsoids.empty()) continue;
        int resolution = grid_resolution_ > 0 ? grid_resolution_
                                              : (stream_info_.grid_hint > 0 ? stream_info_.grid_hint
                                                                            : kDefaultGridResolution);
        EllipsoidGrid grid;
        if (!rasterize_ellipsoids(ellipsoids, o.info.frame, resolution, grid, error)) {
            error = "object " + std::to_string(i) + ": " + error;
            return false;
        }
        if (grid.empty()) continue;
        DecoderTriMesh base = marching_cubes(grid);
        if (base.n_faces() == 0) continue;
        start_reconstruction(o.reconstruction, std::move(base), o.info.frame, grid.cell, o.info.point_count,
                             ReconstructionOptions{});
        o.surface = true;
    }
    started_ = true;
    ++changes_;
    take_exact_layers(stream);
    return true;
}

bool LiveReconstruction::exact_ready(const ReceivedStream& stream, size_t i) const {
    const auto& received = stream.objects();
    if (i >= objects_.size() || i >= received.size()) return false;
    const Object& o = objects_[i];
    const ReceivedObject& r = received[i];
    return o.present && !o.exact && !o.exact_failed && r.info && r.info->exact_layer &&
           r.points.size() >= r.info->point_count && r.connectivity && r.connectivity->complete;
}

void LiveReconstruction::take_exact_layers(const ReceivedStream& stream) {
    for (size_t i = 0; i < objects_.size(); ++i) {
        if (!exact_ready(stream, i)) continue;
        Object& o = objects_[i];
        std::string why;
        bool unusable = false;
        // Every point and the whole connectivity are there: a failure now is for good.
        if (!exact_mesh(stream, i, o.exact_mesh, why, unusable)) {
            o.exact_failed = true;
            continue;
        }
        o.exact = true;
        ++changes_;
    }
}

LiveReconstruction::State LiveReconstruction::state(size_t i) const {
    if (i >= objects_.size() || !objects_[i].present) return State::Waiting;
    const Object& o = objects_[i];
    if (o.exact) return State::Exact;
    if (!o.surface) return o.points.empty() ? State::Waiting : State::PointSet;
    return o.points.empty() ? State::Base : State::Points;
}

namespace {
size_t received_points(const ReceivedStream& stream) {
    size_t n = 0;
    for (const auto& o : stream.objects()) n += o.points.size();
    return n;
}
}  // namespace

void LiveReconstruction::set_region(InsertIf insert_if) {
    insert_if_ = std::move(insert_if);
    scan_complete_ = false;
    held_ = 0;
}

size_t LiveReconstruction::work(const ReceivedStream& stream, std::chrono::microseconds budget) {
    if (!started_) return 0;
    // An object whose exact layer is whole needs none of its remaining points inserted.
    take_exact_layers(stream);
    const auto deadline = std::chrono::steady_clock::now() + budget;
    size_t done = 0, held = 0;
    const size_t received_now = insert_if_ ? received_points(stream) : 0;
    const auto& received = stream.objects();
    for (size_t i = 0; i < objects_.size() && i < received.size(); ++i) {
        Object& o = objects_[i];
        if (!o.present || o.exact || o.points.size() >= received[i].points.size()) continue;
        for (const auto& [index, quantized] : received[i].points) {
            if (index >= o.inserted.size() || o.inserted[index]) continue;
            SurfacePoint p = dequantize_point(quantized, stream_info_, o.info);
            if (insert_if_ && !insert_if_(i, p.position)) {
                ++held;
                continue;
            }
            o.inserted[index] = true;
            uint32_t slot = static_cast<uint32_t>(o.points.size());
            o.points.push_back(p);
            ++done;
            ++inserted_total_;
            if (o.surface) {
                OpenMesh::VertexHandle v;
                Insertion kind = insert_point(o.reconstruction, slot, p.position, v);
                if (kind != Insertion::SeamDuplicate && kind != Insertion::NoMesh) {
                    flip_edges_around(o.reconstruction, v);
                    collapse_mc_vertices_near(o.reconstruction, v);
                }
            }
            if ((done & 15) == 0 && std::chrono::steady_clock::now() >= deadline) {
                changes_ += done > 0;
                if (insert_if_) scan_complete_ = false;
                return done;
            }
        }
    }
    changes_ += done > 0;
    if (insert_if_) {
        held_ = held;
        scan_complete_ = true;
        scanned_received_ = received_now;
    }
    take_exact_layers(stream);
    return done;
}

bool LiveReconstruction::caught_up(const ReceivedStream& stream) const {
    if (!started_) return false;
    for (size_t i = 0; i < objects_.size(); ++i)
        if (exact_ready(stream, i)) return false;
    if (insert_if_) return scan_complete_ && scanned_received_ == received_points(stream);
    const auto& received = stream.objects();
    for (size_t i = 0; i < objects_.size() && i < received.size(); ++i)
        if (objects_[i].present && !objects_[i].exact && objects_[i].points.size() < received[i].points.size())
            return false;
    return true;
}

std::vector<Mesh> LiveReconstruction::objects() const {
    std::vector<Mesh> out(objects_.size());
    for (size_t i = 0; i < objects_.size(); ++i) {
        const Object& o = objects_[i];
        if (!o.present) continue;
        Mesh& mesh = out[i];
        if (o.exact) {
            mesh = o.exact_mesh;
        } else if (o.surface) {
            mesh = extract_mesh(o.reconstruction, o.info, o.points);
        } else {
            mesh.is_point_set = true;
            mesh.colors_have_alpha = o.info.has(kAttrColorAlpha);
            for (const auto& p : o.points) {
                mesh.positions.push_back(p.position);
                if (o.info.has(kAttrNormal)) mesh.normals.push_back(p.normal);
                if (o.info.has(kAttrTexcoord)) mesh.texcoords.push_back(p.texcoord);
                if (o.info.has(kAttrColor)) mesh.colors.push_back(p.color);
            }
        }
        mesh.name = "object" + std::to_string(i);
    }
    return out;
}

}  // namespace ellicast::cli

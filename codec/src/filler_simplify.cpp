#include "filler_simplify.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <array>
#include <cstring>
#include <unordered_set>

namespace ellicast::detail {

namespace {

struct FillerTraits : public OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    HalfedgeAttributes(OpenMesh::Attributes::Status);
    FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using FillerMesh = OpenMesh::TriMesh_ArrayKernelT<FillerTraits>;

struct PositionHash {
    size_t operator()(const std::array<float, 3>& p) const {
        size_t h = 1469598103934665603ull;
        for (float c : p) {
            uint32_t bits;
            static_assert(sizeof bits == sizeof c);
            std::memcpy(&bits, &c, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
        }
        return h;
    }
};

}  // namespace

size_t simplify_filler(Mesh& mesh, const std::vector<SurfacePoint>& received, size_t max_faces) {
    if (mesh.triangles.size() <= max_faces || mesh.is_point_set) return 0;
    // A received point's vertex has its position bit for bit (extract_mesh copies it).
    std::unordered_set<std::array<float, 3>, PositionHash> kept;
    kept.reserve(received.size());
    for (const SurfacePoint& p : received) kept.insert(p.position);

    FillerMesh m;
    std::vector<FillerMesh::VertexHandle> handle(mesh.positions.size());
    OpenMesh::VPropHandleT<uint32_t> source;
    m.add_property(source);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const auto& p = mesh.positions[i];
        handle[i] = m.add_vertex(FillerMesh::Point(p[0], p[1], p[2]));
        m.property(source, handle[i]) = uint32_t(i);
        if (kept.count(p)) m.status(handle[i]).set_locked(true);
    }
    for (const auto& t : mesh.triangles) {
        const auto f = m.add_face(handle[t[0]], handle[t[1]], handle[t[2]]);
        if (!f.is_valid()) return 0;  // not a manifold OpenMesh takes: leave the mesh as it is
    }
    m.update_face_normals();

    // The heap-driven decimater: deterministic (the multiple-choice one draws from rand()).
    using Decimater = OpenMesh::Decimater::DecimaterT<FillerMesh>;
    Decimater decimater(m);
    OpenMesh::Decimater::ModQuadricT<FillerMesh>::Handle quadric;
    OpenMesh::Decimater::ModNormalFlippingT<FillerMesh>::Handle flipping;
    decimater.add(quadric);
    decimater.add(flipping);
    decimater.module(quadric).unset_max_err();
    decimater.module(flipping).set_max_normal_deviation(60.0);  // no face turned further than this
    if (!decimater.initialize()) return 0;
    decimater.decimate_to_faces(0, max_faces);
    m.garbage_collection();

    Mesh out;
    out.name = mesh.name;
    out.colors_have_alpha = mesh.colors_have_alpha;
    out.texcoord_sets.assign(mesh.texcoord_sets.size(), {});
    std::vector<uint32_t> index(mesh.positions.size(), UINT32_MAX);
    for (auto v : m.vertices()) {
        const uint32_t s = m.property(source, v);
        index[s] = uint32_t(out.positions.size());
        out.positions.push_back(mesh.positions[s]);
        if (mesh.has_normals()) out.normals.push_back(mesh.normals[s]);
        if (mesh.has_texcoords()) out.texcoords.push_back(mesh.texcoords[s]);
        for (size_t k = 0; k < mesh.texcoord_sets.size(); ++k) out.texcoord_sets[k].push_back(mesh.texcoord_sets[k][s]);
        if (mesh.has_colors()) out.colors.push_back(mesh.colors[s]);
    }
    for (auto f : m.faces()) {
        std::array<uint32_t, 3> t{};
        int c = 0;
        for (auto v : m.fv_range(f)) t[c++] = index[m.property(source, v)];
        out.triangles.push_back(t);
    }
    const size_t removed = mesh.triangles.size() - out.triangles.size();
    mesh = std::move(out);
    return removed;
}

}  // namespace ellicast::detail

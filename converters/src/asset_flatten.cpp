// An Asset as world-space meshes: every object under every node that shows it, transformed by the
// node's world transform (for formats without a scene graph: PLY, OBJ).
#include "ellicast/converters/asset.h"

#include <Eigen/Dense>

#include <optional>

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"  // false positive in string concatenation (GCC bug 105651)
#endif

namespace ellicast {

namespace {

Mesh transformed(const Mesh& in, const Eigen::Matrix4d& world) {
    Mesh out = in;
    const Eigen::Matrix3d linear = world.topLeftCorner<3, 3>();
    const Eigen::Vector3d offset = world.topRightCorner<3, 1>();
    Eigen::Matrix3d normal_matrix = linear.inverse().transpose();
    if (!normal_matrix.allFinite()) normal_matrix = Eigen::Matrix3d::Identity();
    for (auto& p : out.positions) {
        Eigen::Vector3d v = linear * Eigen::Vector3d(p[0], p[1], p[2]) + offset;
        p = {float(v.x()), float(v.y()), float(v.z())};
    }
    for (auto& n : out.normals) {
        Eigen::Vector3d v = normal_matrix * Eigen::Vector3d(n[0], n[1], n[2]);
        if (v.norm() > 0) v.normalize();
        n = {float(v.x()), float(v.y()), float(v.z())};
    }
    if (linear.determinant() < 0)  // a mirroring transform turns faces inside out: keep them outward
        for (auto& t : out.triangles) std::swap(t[1], t[2]);
    return out;
}

}  // namespace

Eigen::Matrix4d node_matrix(const SceneNode& n) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (n.has_matrix) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m(r, c) = n.matrix[size_t(c * 4 + r)];
        return m;
    }
    Eigen::Quaterniond q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (q.norm() > 0) m.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix();
    m.topLeftCorner<3, 3>() *= Eigen::Vector3d(n.scale[0], n.scale[1], n.scale[2]).asDiagonal();
    m.topRightCorner<3, 1>() = Eigen::Vector3d(n.translation[0], n.translation[1], n.translation[2]);
    return m;
}

// World transforms, following parents; a node in or under a cycle (or a parent outside the table)
// gets none and shows nothing.
static std::vector<std::optional<Eigen::Matrix4d>> node_world_matrices(const std::vector<SceneNode>& nodes) {
    std::vector<std::optional<Eigen::Matrix4d>> world(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) {
        Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
        size_t at = i;
        bool ok = false;
        for (size_t steps = 0; steps <= nodes.size(); ++steps) {
            m = node_matrix(nodes[at]) * m;
            if (nodes[at].parent == kNone) {
                ok = true;
                break;
            }
            if (nodes[at].parent >= nodes.size()) break;
            at = nodes[at].parent;
        }
        if (ok && m.allFinite()) world[i] = m;
    }
    return world;
}

std::vector<Mesh> flatten_asset(const Asset& asset) {
    std::vector<Mesh> out;
    const auto& nodes = asset.scene.nodes;
    auto present = [&](size_t o) { return o < asset.objects.size() && !asset.objects[o].positions.empty(); };
    if (nodes.empty()) {
        for (size_t o = 0; o < asset.objects.size(); ++o)
            if (present(o)) out.push_back(asset.objects[o]);
        return out;
    }
    const std::vector<std::optional<Eigen::Matrix4d>> world = node_world_matrices(nodes);
    for (size_t i = 0; i < nodes.size(); ++i) {
        if (!world[i] || nodes[i].mesh == kNone || nodes[i].mesh >= asset.scene.meshes.size()) continue;
        const SceneMesh& mesh = asset.scene.meshes[nodes[i].mesh];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            if (!present(mesh.primitives[p].object)) continue;
            Mesh m = transformed(asset.objects[mesh.primitives[p].object], *world[i]);
            m.name = (nodes[i].name.empty() ? "node" + std::to_string(i) : nodes[i].name) +
                     (mesh.primitives.size() > 1 ? "#" + std::to_string(p) : "");
            out.push_back(std::move(m));
        }
    }
    return out;
}

}  // namespace ellicast

namespace ellicast {

std::vector<std::vector<std::array<double, 16>>> object_world_transforms(const Asset& asset) {
    std::vector<std::vector<std::array<double, 16>>> out(asset.objects.size());
    auto as_array = [](const Eigen::Matrix4d& m) {
        std::array<double, 16> a;
        Eigen::Map<Eigen::Matrix4d>(a.data()) = m;
        return a;
    };
    const auto& nodes = asset.scene.nodes;
    if (nodes.empty()) {
        for (auto& o : out) o.push_back(as_array(Eigen::Matrix4d::Identity()));
        return out;
    }
    const auto world = node_world_matrices(nodes);
    for (size_t i = 0; i < nodes.size(); ++i) {
        if (!world[i] || nodes[i].mesh == kNone || nodes[i].mesh >= asset.scene.meshes.size()) continue;
        for (const auto& primitive : asset.scene.meshes[nodes[i].mesh].primitives)
            if (primitive.object < out.size()) out[primitive.object].push_back(as_array(*world[i]));
    }
    return out;
}

}  // namespace ellicast

// glTF 2.0 output of a flat list of meshes, built in glTF's own terms: meshes, nodes, scene. The
// scene writer (asset_output.cpp) writes scene graphs, materials, textures and Draco.
#include "ellicast/converters/mesh_output.h"

#include "gltf_write.h"

namespace ellicast {

namespace {

// Buffer views, accessors, primitives and saving are shared with the scene writer (gltf_write.h).
using namespace gltf_write;

// A glTF mesh with one primitive; returns its index.
int add_mesh(tinygltf::Model& model, const Mesh& mesh, const std::string& name) {
    tinygltf::Mesh m;
    m.name = name;
    m.primitives.push_back(add_primitive(model, mesh));
    model.meshes.push_back(std::move(m));
    return int(model.meshes.size()) - 1;
}

// A node instancing mesh `mesh`; returns its index.
int add_node(tinygltf::Model& model, int mesh, const std::string& name) {
    tinygltf::Node node;
    node.mesh = mesh;
    node.name = name;
    model.nodes.push_back(std::move(node));
    return int(model.nodes.size()) - 1;
}

// The default scene holding `nodes` as roots.
void add_scene(tinygltf::Model& model, const std::vector<int>& nodes) {
    tinygltf::Scene scene;
    scene.nodes = nodes;
    model.scenes.push_back(std::move(scene));
    model.defaultScene = int(model.scenes.size()) - 1;
}

}  // namespace

bool write_gltf(const std::string& path, const std::vector<Mesh>& meshes, bool binary, std::string& error) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "ellicast 1.0";
    std::vector<int> roots;
    for (size_t i = 0; i < meshes.size(); ++i) {
        const Mesh& mesh = meshes[i];
        if (mesh.positions.empty()) continue;  // an accessor may not be empty
        if (!valid_indices(mesh)) {
            error = path + ": mesh " + std::to_string(i) + " has a triangle index beyond its vertices";
            return false;
        }
        const std::string name = mesh.name.empty() ? "object" + std::to_string(i) : mesh.name;
        roots.push_back(add_node(model, add_mesh(model, mesh, name), name));
    }
    if (!roots.empty()) add_scene(model, roots);  // tinygltf writes an empty scene as null
    return save_model(path, model, binary, error);
}

}  // namespace ellicast

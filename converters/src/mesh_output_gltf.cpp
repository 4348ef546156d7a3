// glTF 2.0 output, built in glTF's own terms: buffer, buffer views, accessors, primitives, meshes,
// nodes, scene. Issue 5 extends this file (scene graph, materials, textures, Draco): keep one
// function per glTF concept.
#include "ellicast/converters/mesh_output.h"

#include "ellicast/format.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>

namespace ellicast {

namespace {

constexpr int kArrayBuffer = TINYGLTF_TARGET_ARRAY_BUFFER;
constexpr int kElementArrayBuffer = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;

// Appends `bytes` to buffer 0 (4-byte aligned) as a new buffer view; returns its index.
int add_buffer_view(tinygltf::Model& model, const void* data, size_t bytes, int target) {
    if (model.buffers.empty()) model.buffers.emplace_back();
    auto& buffer = model.buffers[0].data;
    while (buffer.size() % 4 != 0) buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size()) - 1;
}

// An accessor over a whole buffer view; min/max given for POSITION (the spec requires them).
int add_accessor(tinygltf::Model& model, int view, int component_type, int type, size_t count,
                 const std::vector<double>& min = {}, const std::vector<double>& max = {}) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    accessor.minValues = min;
    accessor.maxValues = max;
    model.accessors.push_back(accessor);
    return int(model.accessors.size()) - 1;
}

// A float VECn vertex attribute accessor.
template <size_t N>
int add_float_attribute(tinygltf::Model& model, const std::vector<std::array<float, N>>& values, int type,
                        bool with_bounds) {
    std::vector<double> mn, mx;
    if (with_bounds) {
        mn.assign(N, std::numeric_limits<double>::max());
        mx.assign(N, -std::numeric_limits<double>::max());
        for (const auto& v : values)
            for (size_t k = 0; k < N; ++k) mn[k] = std::min(mn[k], double(v[k])), mx[k] = std::max(mx[k], double(v[k]));
    }
    int view = add_buffer_view(model, values.data(), values.size() * sizeof(values[0]), kArrayBuffer);
    return add_accessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, type, values.size(), mn, mx);
}

// Normals as the spec wants them: unit length (a zero normal becomes +Z).
std::vector<std::array<float, 3>> unit_normals(const std::vector<std::array<float, 3>>& normals) {
    std::vector<std::array<float, 3>> out(normals.size());
    for (size_t i = 0; i < normals.size(); ++i) {
        const auto& n = normals[i];
        double l = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
        if (!(l > 1e-12) || !std::isfinite(l)) out[i] = {0, 0, 1};
        else out[i] = {float(n[0] / l), float(n[1] / l), float(n[2] / l)};
    }
    return out;
}

// The primitive of one mesh: attributes, indices, mode.
tinygltf::Primitive add_primitive(tinygltf::Model& model, const Mesh& mesh) {
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = add_float_attribute(model, mesh.positions, TINYGLTF_TYPE_VEC3, true);
    if (mesh.has_normals())
        primitive.attributes["NORMAL"] = add_float_attribute(model, unit_normals(mesh.normals), TINYGLTF_TYPE_VEC3, false);
    if (mesh.has_texcoords())
        primitive.attributes["TEXCOORD_0"] = add_float_attribute(model, mesh.texcoords, TINYGLTF_TYPE_VEC2, false);
    if (mesh.has_colors()) {
        if (mesh.colors_have_alpha) {
            std::vector<std::array<float, 4>> c(mesh.colors.size());
            for (size_t i = 0; i < c.size(); ++i)
                for (int k = 0; k < 4; ++k) c[i][k] = std::clamp(mesh.colors[i][k], 0.0f, 1.0f);
            primitive.attributes["COLOR_0"] = add_float_attribute(model, c, TINYGLTF_TYPE_VEC4, false);
        } else {
            std::vector<std::array<float, 3>> c(mesh.colors.size());
            for (size_t i = 0; i < c.size(); ++i)
                for (int k = 0; k < 3; ++k) c[i][k] = std::clamp(mesh.colors[i][k], 0.0f, 1.0f);
            primitive.attributes["COLOR_0"] = add_float_attribute(model, c, TINYGLTF_TYPE_VEC3, false);
        }
    }
    if (mesh.is_point_set || mesh.triangles.empty()) {
        primitive.mode = TINYGLTF_MODE_POINTS;
        return primitive;
    }
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    const size_t count = mesh.triangles.size() * 3;
    int view;
    int component;
    if (mesh.positions.size() <= 0xFFFF) {
        std::vector<uint16_t> idx;
        idx.reserve(count);
        for (const auto& t : mesh.triangles)
            for (uint32_t i : t) idx.push_back(uint16_t(i));
        view = add_buffer_view(model, idx.data(), idx.size() * 2, kElementArrayBuffer);
        component = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    } else {
        view = add_buffer_view(model, mesh.triangles.data(), count * 4, kElementArrayBuffer);
        component = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    }
    primitive.indices = add_accessor(model, view, component, TINYGLTF_TYPE_SCALAR, count);
    return primitive;
}

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

bool valid_indices(const Mesh& mesh) {
    for (const auto& t : mesh.triangles)
        for (uint32_t i : t)
            if (i >= mesh.positions.size()) return false;
    return true;
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
    if (!model.buffers.empty()) {
        if (binary) {
            model.buffers[0].uri.clear();  // buffer 0 with no uri goes to the GLB BIN chunk
        } else {
            model.buffers[0].uri = std::filesystem::path(path).stem().string() + ".bin";
        }
    }
    tinygltf::TinyGLTF writer;
    if (binary) {
        std::ostringstream stream;
        if (!writer.WriteGltfSceneToStream(&model, stream, false, true)) {
            error = path + ": tinygltf could not serialize the model";
            return false;
        }
        const std::string bytes = stream.str();
        std::string message;
        if (write_file(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()),
                       message) != Error::Ok) {
            error = "cannot write " + path + ": " + message;
            return false;
        }
        return true;
    }
    // .gltf: the buffer goes to <stem>.bin beside it (tinygltf writes it), the JSON via a temporary.
    std::string tmp = path + ".tmp";
    if (!writer.WriteGltfSceneToFile(&model, tmp, false, false, true, false)) {
        std::filesystem::remove(tmp);
        error = "cannot write " + path + " (or its .bin)";
        return false;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp);
        error = "cannot write " + path + ": " + ec.message();
        return false;
    }
    return true;
}

}  // namespace ellicast

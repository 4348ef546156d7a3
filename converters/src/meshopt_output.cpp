// EXT_meshopt_compression output: buffer views compressed with meshoptimizer's vertex and index
// codecs (version 0 vertex data, version 1 triangle indices, as the extension defines them), their
// plain layout kept in a fallback buffer without bytes.
#include "meshopt_output.h"

#include <meshoptimizer.h>

#include <map>
#include <vector>

namespace ellicast::meshopt_output {

namespace {

enum class Mode { None, Attributes, Triangles, Indices };

struct Plan {
    Mode mode = Mode::None;
    size_t stride = 0, count = 0;
};

size_t element_size(const tinygltf::Accessor& a) {
    const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    const int bytes = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    return components > 0 && bytes > 0 ? size_t(components) * size_t(bytes) : 0;
}

void align(std::vector<unsigned char>& data) {
    while (data.size() % 4) data.push_back(0);
}

}  // namespace

Report compress(tinygltf::Model& model, gltf_write::JsonPatches& patches) {
    Report report;
    if (model.buffers.size() != 1) return report;  // the writer's one buffer, nothing else
    report.views = model.bufferViews.size();
    // How each view is used: by which accessors, and whether as triangle indices.
    std::map<int, std::vector<int>> users;
    for (size_t a = 0; a < model.accessors.size(); ++a)
        if (model.accessors[a].bufferView >= 0 && model.accessors[a].sparse.isSparse == false)
            users[model.accessors[a].bufferView].push_back(int(a));
    std::map<int, int> index_mode;  // accessor -> primitive mode, for index accessors
    std::map<int, bool> vertex_data;  // accessors of attributes, morph targets and animation keys
    for (const auto& mesh : model.meshes)
        for (const auto& prim : mesh.primitives) {
            if (prim.indices >= 0) index_mode[prim.indices] = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            for (const auto& [name, a] : prim.attributes) vertex_data[a] = true;
            for (const auto& target : prim.targets)
                for (const auto& [name, a] : target) vertex_data[a] = true;
        }
    for (const auto& animation : model.animations)
        for (const auto& sampler : animation.samplers) vertex_data[sampler.input] = vertex_data[sampler.output] = true;

    std::vector<Plan> plans(model.bufferViews.size());
    for (const auto& [view, list] : users) {
        if (list.size() != 1 || view < 0 || size_t(view) >= model.bufferViews.size()) continue;
        const tinygltf::Accessor& a = model.accessors[size_t(list[0])];
        const tinygltf::BufferView& v = model.bufferViews[size_t(view)];
        const size_t element = element_size(a);
        const size_t stride = v.byteStride > 0 ? v.byteStride : element;
        if (a.byteOffset != 0 || element == 0 || stride < element || a.count == 0 || v.byteLength != a.count * stride)
            continue;
        Plan& p = plans[size_t(view)];
        if (auto im = index_mode.find(list[0]); im != index_mode.end()) {
            if (stride != 2 && stride != 4) continue;  // 8-bit indices stay plain
            p.mode = im->second == TINYGLTF_MODE_TRIANGLES && a.count % 3 == 0 ? Mode::Triangles : Mode::Indices;
        } else if (vertex_data.count(list[0])) {
            if (stride % 4 != 0 || stride > 256) continue;
            p.mode = Mode::Attributes;
        } else {
            continue;
        }
        p.stride = stride;
        p.count = a.count;
    }

    const std::vector<unsigned char>& old = model.buffers[0].data;
    std::vector<unsigned char> data;  // buffer 0: compressed views and the plain ones (images)
    size_t fallback = 0;
    meshopt_encodeIndexVersion(1);
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        tinygltf::BufferView& v = model.bufferViews[i];
        if (v.buffer != 0 || v.byteOffset + v.byteLength > old.size()) continue;
        const unsigned char* raw = old.data() + v.byteOffset;
        const Plan& p = plans[i];
        std::vector<unsigned char> coded;
        if (p.mode == Mode::Attributes) {
            coded.resize(meshopt_encodeVertexBufferBound(p.count, p.stride));
            coded.resize(meshopt_encodeVertexBuffer(coded.data(), coded.size(), raw, p.count, p.stride));
        } else if (p.mode != Mode::None) {
            std::vector<unsigned int> indices(p.count);
            unsigned int largest = 0;
            for (size_t k = 0; k < p.count; ++k) {
                unsigned int x = 0;
                for (size_t b = 0; b < p.stride; ++b) x |= unsigned(raw[k * p.stride + b]) << (8 * b);
                indices[k] = x;
                largest = std::max(largest, x);
            }
            if (p.mode == Mode::Triangles) {
                coded.resize(meshopt_encodeIndexBufferBound(p.count, size_t(largest) + 1));
                coded.resize(meshopt_encodeIndexBuffer(coded.data(), coded.size(), indices.data(), p.count));
            } else {
                coded.resize(meshopt_encodeIndexSequenceBound(p.count, size_t(largest) + 1));
                coded.resize(meshopt_encodeIndexSequence(coded.data(), coded.size(), indices.data(), p.count));
            }
        }
        align(data);
        if (p.mode == Mode::None || coded.empty() || coded.size() >= v.byteLength) {
            // Plain: images, views shared by accessors, 8-bit indices, data the codec does not shrink.
            const size_t at = data.size();
            data.insert(data.end(), raw, raw + v.byteLength);
            v.byteOffset = at;
            continue;
        }
        const size_t at = data.size();
        data.insert(data.end(), coded.begin(), coded.end());
        // tinygltf does not write a buffer view's extensions: they are set after serialization.
        const char* mode = p.mode == Mode::Attributes ? "ATTRIBUTES" : p.mode == Mode::Triangles ? "TRIANGLES" : "INDICES";
        patches.emplace_back("/bufferViews/" + std::to_string(i) + "/extensions",
                             "{\"" + std::string(kExtension) + "\":{\"buffer\":0,\"byteOffset\":" + std::to_string(at) +
                                 ",\"byteLength\":" + std::to_string(coded.size()) +
                                 ",\"byteStride\":" + std::to_string(p.stride) + ",\"count\":" + std::to_string(p.count) +
                                 ",\"mode\":\"" + mode + "\"}}");
        v.buffer = 1;
        fallback = (fallback + 3) / 4 * 4;
        v.byteOffset = fallback;
        fallback += v.byteLength;
        ++report.compressed;
        report.plain_bytes += v.byteLength;
        report.coded_bytes += coded.size();
    }
    if (report.compressed == 0) {
        // Nothing compressed: the views were only moved (aligned) within buffer 0.
        model.buffers[0].data = std::move(data);
        return report;
    }
    align(data);
    model.buffers[0].data = std::move(data);
    // The fallback: its length and the extension's flag; no bytes, no uri (tinygltf would write an
    // empty data: URI for a buffer without data, so the whole entry is set after serialization).
    tinygltf::Buffer fallback_buffer;
    model.buffers.push_back(fallback_buffer);
    patches.emplace_back("/buffers/1", "{\"byteLength\":" + std::to_string(fallback) +
                                           ",\"extensions\":{\"" + kExtension + "\":{\"fallback\":true}}}");
    model.extensionsUsed.push_back(kExtension);
    model.extensionsRequired.push_back(kExtension);
    return report;
}

Mesh in_fetch_order(const Mesh& mesh, VertexWeights* weights) {
    if (mesh.is_point_set || mesh.triangles.empty()) return mesh;
    const size_t n = mesh.positions.size();
    std::vector<unsigned int> indices;
    indices.reserve(mesh.triangles.size() * 3);
    for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
    meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), n);
    std::vector<unsigned int> remap(n);
    const size_t kept = meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indices.size(), n);
    Mesh out = mesh;
    auto reorder = [&](const auto& in, auto& dst) {
        if (in.size() != n) return;
        dst.assign(kept, {});
        for (size_t v = 0; v < n; ++v)
            if (remap[v] != ~0u) dst[remap[v]] = in[v];
    };
    reorder(mesh.positions, out.positions);
    reorder(mesh.normals, out.normals);
    reorder(mesh.texcoords, out.texcoords);
    reorder(mesh.colors, out.colors);
    for (size_t s = 0; s < mesh.texcoord_sets.size(); ++s) reorder(mesh.texcoord_sets[s], out.texcoord_sets[s]);
    if (weights && weights->joints.size() == n && weights->weights.size() == n) {
        const VertexWeights in = *weights;
        reorder(in.joints, weights->joints);
        reorder(in.weights, weights->weights);
    }
    for (size_t t = 0; t < out.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) out.triangles[t][size_t(c)] = remap[indices[3 * t + size_t(c)]];
    return out;
}

}  // namespace ellicast::meshopt_output

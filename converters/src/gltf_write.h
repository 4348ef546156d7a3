// Internal to converters: glTF writing pieces shared by mesh_output_gltf.cpp (a flat list of
// meshes) and asset_output.cpp (a scene), in glTF's own terms: buffer views, accessors, primitives,
// and saving the model as .glb or .gltf + .bin.
#pragma once

#include "ellicast/codec/mesh.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace ellicast::gltf_write {

// Appends `bytes` to buffer 0 (4-byte aligned) as a new buffer view; returns its index. A target of
// 0 leaves the view without target (image data, Draco data).
int add_buffer_view(tinygltf::Model& model, const void* data, size_t bytes, int target);

// An accessor over a whole buffer view (view -1: no buffer view, as Draco-compressed data needs);
// min/max for POSITION (the spec requires them).
int add_accessor(tinygltf::Model& model, int view, int component_type, int type, size_t count,
                 const std::vector<double>& min = {}, const std::vector<double>& max = {}, bool normalized = false);

// A float VECn vertex attribute accessor, with its bounds when asked.
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
    int view = add_buffer_view(model, values.data(), values.size() * sizeof(values[0]), TINYGLTF_TARGET_ARRAY_BUFFER);
    return add_accessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, type, values.size(), mn, mx);
}

// A morph target's displacements (VEC3 floats): sparse where that is smaller, as glTF allows and as
// exporters write them (a target that moves a few vertices of many): no buffer view (zeros) and the
// non-zero displacements with their indices; a target that moves nothing is zeros alone. Dense
// otherwise. With bounds when asked (POSITION: glTF requires them, over every vertex).
int add_displacements(tinygltf::Model& model, const std::vector<std::array<float, 3>>& values, bool with_bounds);

// Normals as the spec wants them: unit length (a zero or non-finite normal becomes +Z).
std::vector<std::array<float, 3>> unit_normals(const std::vector<std::array<float, 3>>& normals);

// Colours clamped to [0, 1], as many channels as the mesh has (3 or 4).
std::vector<float> clamped_colors(const Mesh& mesh);

// The indices accessor of a triangle mesh (unsigned short when the vertices allow, else unsigned int).
int add_indices(tinygltf::Model& model, const Mesh& mesh);

// The primitive of one mesh with float attributes: POSITION (with bounds), NORMAL, TEXCOORD_0,
// COLOR_0, indices; POINTS for a point set, TRIANGLES otherwise.
tinygltf::Primitive add_primitive(tinygltf::Model& model, const Mesh& mesh);

// True when every triangle index is below the vertex count.
bool valid_indices(const Mesh& mesh);

// JSON values set in the document tinygltf serializes: a JSON pointer ("/nodes/3/extras") and the
// value as JSON text. For what tinygltf's values cannot hold (a null inside extras, format 1.12).
using JsonPatches = std::vector<std::pair<std::string, std::string>>;

// The GLB bytes of `model` (buffer 0 as the BIN chunk), in memory, with `patches` set. False with
// `error` otherwise.
bool glb_bytes(tinygltf::Model& model, std::vector<uint8_t>& out, std::string& error, const JsonPatches& patches = {});

// Writes `model` to `path`: binary (.glb, buffer 0 as the BIN chunk) or JSON with buffer 0 in a
// .bin of the same stem beside it, with `patches` set. Writes through a temporary name. False with
// `error` otherwise.
bool save_model(const std::string& path, tinygltf::Model& model, bool binary, std::string& error,
                const JsonPatches& patches = {});

}  // namespace ellicast::gltf_write

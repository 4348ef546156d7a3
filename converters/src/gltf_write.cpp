// glTF writing pieces shared by the mesh and scene writers: buffer views, accessors, primitives,
// saving as .glb or .gltf + .bin.
#include "gltf_write.h"

#include "ellicast/format.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include <cstring>

namespace ellicast::gltf_write {

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

int add_accessor(tinygltf::Model& model, int view, int component_type, int type, size_t count,
                 const std::vector<double>& min, const std::vector<double>& max, bool normalized) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    accessor.minValues = min;
    accessor.maxValues = max;
    accessor.normalized = normalized;
    model.accessors.push_back(accessor);
    return int(model.accessors.size()) - 1;
}

int add_displacements(tinygltf::Model& model, const std::vector<std::array<float, 3>>& values, bool with_bounds) {
    std::vector<uint32_t> moved;
    for (size_t i = 0; i < values.size(); ++i)
        if (values[i][0] != 0 || values[i][1] != 0 || values[i][2] != 0) moved.push_back(uint32_t(i));
    const size_t index_size = values.size() <= 0x100 ? 1 : values.size() <= 0x10000 ? 2 : 4;
    const size_t dense = values.size() * sizeof(values[0]);
    // Each buffer view is padded to 4 bytes: counted, so that sparse is chosen only where it is smaller.
    const size_t sparse = (moved.size() * index_size + 3) / 4 * 4 + moved.size() * sizeof(values[0]);
    if (sparse >= dense) return add_float_attribute(model, values, TINYGLTF_TYPE_VEC3, with_bounds);
    std::vector<double> mn, mx;
    if (with_bounds) {
        mn.assign(3, 0.0);  // the zeros count too
        mx.assign(3, 0.0);
        for (uint32_t i : moved)
            for (size_t k = 0; k < 3; ++k)
                mn[k] = std::min(mn[k], double(values[i][k])), mx[k] = std::max(mx[k], double(values[i][k]));
    }
    const int accessor = add_accessor(model, -1, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, values.size(), mn, mx);
    if (moved.empty()) return accessor;  // all zeros: no buffer view, no sparse (glTF: initialized with zeros)
    std::vector<uint8_t> indices(moved.size() * index_size);
    for (size_t j = 0; j < moved.size(); ++j)
        for (size_t b = 0; b < index_size; ++b) indices[j * index_size + b] = uint8_t(moved[j] >> (8 * b));
    std::vector<std::array<float, 3>> moved_values;
    moved_values.reserve(moved.size());
    for (uint32_t i : moved) moved_values.push_back(values[i]);
    auto& a = model.accessors[size_t(accessor)];
    a.sparse.isSparse = true;
    a.sparse.count = int(moved.size());
    a.sparse.indices.bufferView = add_buffer_view(model, indices.data(), indices.size(), 0);
    a.sparse.indices.byteOffset = 0;
    a.sparse.indices.componentType = index_size == 1   ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE
                                     : index_size == 2 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT
                                                       : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.sparse.values.bufferView = add_buffer_view(model, moved_values.data(), moved_values.size() * sizeof(moved_values[0]), 0);
    a.sparse.values.byteOffset = 0;
    return accessor;
}

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

std::vector<float> clamped_colors(const Mesh& mesh) {
    const int channels = mesh.colors_have_alpha ? 4 : 3;
    std::vector<float> out;
    out.reserve(mesh.colors.size() * channels);
    for (const auto& c : mesh.colors)
        for (int k = 0; k < channels; ++k) out.push_back(std::isfinite(c[k]) ? std::clamp(c[k], 0.0f, 1.0f) : 0.0f);
    return out;
}

int add_indices(tinygltf::Model& model, const Mesh& mesh) {
    const size_t count = mesh.triangles.size() * 3;
    int view;
    int component;
    if (mesh.positions.size() <= 0xFFFF) {
        std::vector<uint16_t> idx;
        idx.reserve(count);
        for (const auto& t : mesh.triangles)
            for (uint32_t i : t) idx.push_back(uint16_t(i));
        view = add_buffer_view(model, idx.data(), idx.size() * 2, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        component = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    } else {
        view = add_buffer_view(model, mesh.triangles.data(), count * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        component = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    }
    return add_accessor(model, view, component, TINYGLTF_TYPE_SCALAR, count);
}

tinygltf::Primitive add_primitive(tinygltf::Model& model, const Mesh& mesh) {
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = add_float_attribute(model, mesh.positions, TINYGLTF_TYPE_VEC3, true);
    if (mesh.has_normals())
        primitive.attributes["NORMAL"] = add_float_attribute(model, unit_normals(mesh.normals), TINYGLTF_TYPE_VEC3, false);
    if (mesh.has_texcoords()) {
        primitive.attributes["TEXCOORD_0"] = add_float_attribute(model, mesh.texcoords, TINYGLTF_TYPE_VEC2, false);
        for (size_t s = 0; s < mesh.texcoord_sets.size(); ++s)  // format 1.14: TEXCOORD_1, ...
            if (mesh.texcoord_sets[s].size() == mesh.positions.size())
                primitive.attributes["TEXCOORD_" + std::to_string(s + 1)] =
                    add_float_attribute(model, mesh.texcoord_sets[s], TINYGLTF_TYPE_VEC2, false);
            else
                break;
    }
    if (mesh.has_colors()) {
        std::vector<float> c = clamped_colors(mesh);
        int view = add_buffer_view(model, c.data(), c.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
        primitive.attributes["COLOR_0"] =
            add_accessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT,
                         mesh.colors_have_alpha ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, mesh.colors.size());
    }
    if (mesh.is_point_set || mesh.triangles.empty()) {
        primitive.mode = TINYGLTF_MODE_POINTS;
        return primitive;
    }
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.indices = add_indices(model, mesh);
    return primitive;
}

bool valid_indices(const Mesh& mesh) {
    for (const auto& t : mesh.triangles)
        for (uint32_t i : t)
            if (i >= mesh.positions.size()) return false;
    return true;
}

namespace {

// tinygltf writes a perspective camera's zfar even when it is 0 (infinite), which glTF forbids
// (zfar > 0 when present): such a camera is written without it (spec 26.4). Only a model with such a
// camera has its JSON rewritten, so every other file is written exactly as tinygltf makes it.
bool has_infinite_camera(const tinygltf::Model& model) {
    return std::any_of(model.cameras.begin(), model.cameras.end(),
                       [](const tinygltf::Camera& c) { return c.type == "perspective" && c.perspective.zfar == 0; });
}
void drop_infinite_zfar(nlohmann::json& doc) {
    if (!doc.contains("cameras") || !doc["cameras"].is_array()) return;
    for (auto& camera : doc["cameras"])
        if (camera.contains("perspective") && camera["perspective"].contains("zfar") &&
            camera["perspective"]["zfar"] == 0)
            camera["perspective"].erase("zfar");
}

// The document with each patch's value set at its pointer (a patch whose text is not JSON, or whose
// pointer names no place, is left out: the writer made both).
void apply_patches(nlohmann::json& doc, const JsonPatches& patches) {
    for (const auto& [pointer, text] : patches) {
        nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
        if (value.is_discarded()) continue;
        try {
            doc[nlohmann::json::json_pointer(pointer)] = std::move(value);
        } catch (const nlohmann::json::exception&) {
        }
    }
}

uint32_t read_u32le(const std::string& s, size_t at) {
    return uint32_t(uint8_t(s[at])) | uint32_t(uint8_t(s[at + 1])) << 8 | uint32_t(uint8_t(s[at + 2])) << 16 |
           uint32_t(uint8_t(s[at + 3])) << 24;
}
void put_u32le(std::vector<uint8_t>& out, uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
}

// The GLB `bytes` with its JSON chunk passed through drop_infinite_zfar and the patches; false when it
// is not the GLB tinygltf writes (a 12-byte header, then a JSON chunk).
bool fix_glb(const std::string& bytes, std::vector<uint8_t>& out, const JsonPatches& patches) {
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || bytes.compare(16, 4, "JSON") != 0) return false;
    const size_t json_length = read_u32le(bytes, 12);
    if (20 + json_length > bytes.size()) return false;
    nlohmann::json doc = nlohmann::json::parse(bytes.substr(20, json_length), nullptr, false);
    if (doc.is_discarded()) return false;
    drop_infinite_zfar(doc);
    apply_patches(doc, patches);
    std::string json = doc.dump();
    while (json.size() % 4) json += ' ';
    const size_t rest = bytes.size() - 20 - json_length;  // the BIN chunk, if any
    std::vector<uint8_t> glb(bytes.begin(), bytes.begin() + 8);  // magic, version
    put_u32le(glb, uint32_t(12 + 8 + json.size() + rest));
    put_u32le(glb, uint32_t(json.size()));
    glb.resize(20 + json.size() + rest);
    std::memcpy(glb.data() + 16, bytes.data() + 16, 4);  // "JSON"
    std::memcpy(glb.data() + 20, json.data(), json.size());
    if (rest) std::memcpy(glb.data() + 20 + json.size(), bytes.data() + 20 + json_length, rest);
    out = std::move(glb);
    return true;
}

}  // namespace

bool glb_bytes(tinygltf::Model& model, std::vector<uint8_t>& out, std::string& error, const JsonPatches& patches) {
    if (!model.buffers.empty()) model.buffers[0].uri.clear();  // buffer 0 with no uri goes to the GLB BIN chunk
    tinygltf::TinyGLTF writer;
    std::ostringstream stream;
    if (!writer.WriteGltfSceneToStream(&model, stream, false, true)) {
        error = "tinygltf could not serialize the model";
        return false;
    }
    const std::string bytes = stream.str();
    if (has_infinite_camera(model) || !patches.empty()) {
        if (!fix_glb(bytes, out, patches)) {
            error = "tinygltf wrote a GLB whose JSON chunk does not parse";
            return false;
        }
        return true;
    }
    out.assign(bytes.begin(), bytes.end());
    return true;
}

bool save_model(const std::string& path, tinygltf::Model& model, bool binary, std::string& error,
                const JsonPatches& patches) {
    if (!model.buffers.empty()) {
        if (binary) {
            model.buffers[0].uri.clear();  // buffer 0 with no uri goes to the GLB BIN chunk
        } else {
            model.buffers[0].uri = std::filesystem::path(path).stem().string() + ".bin";
        }
    }
    tinygltf::TinyGLTF writer;
    if (binary) {
        std::vector<uint8_t> bytes;
        if (!glb_bytes(model, bytes, error, patches)) {
            error = path + ": " + error;
            return false;
        }
        std::string message;
        if (write_file(path, bytes, message) != Error::Ok) {
            error = "cannot write " + path + ": " + message;
            return false;
        }
        return true;
    }
    // .gltf: the buffer goes to <stem>.bin beside it and the JSON to `path`, both through
    // write_file (private temporaries, no symlink followed). tinygltf serializes the JSON with the
    // buffer embedded; the embedded copy is replaced by the .bin's name.
    std::vector<uint8_t> bin;
    if (!model.buffers.empty()) bin = model.buffers[0].data;
    std::ostringstream stream;
    if (!writer.WriteGltfSceneToStream(&model, stream, true, false)) {
        error = path + ": tinygltf could not serialize the model";
        return false;
    }
    nlohmann::json doc = nlohmann::json::parse(stream.str(), nullptr, false);
    if (doc.is_discarded()) {
        error = path + ": tinygltf wrote JSON that does not parse";
        return false;
    }
    drop_infinite_zfar(doc);
    apply_patches(doc, patches);
    std::string message;
    if (!model.buffers.empty()) {
        const std::string bin_name = std::filesystem::path(path).stem().string() + ".bin";
        doc["buffers"][0]["uri"] = bin_name;
        const std::string bin_path = (std::filesystem::path(path).parent_path() / bin_name).string();
        if (write_file(bin_path, bin, message) != Error::Ok) {
            error = "cannot write " + message;
            return false;
        }
    }
    const std::string text = doc.dump(2) + "\n";
    if (write_file(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()), message) !=
        Error::Ok) {
        error = "cannot write " + message;
        return false;
    }
    return true;
}

}  // namespace ellicast::gltf_write

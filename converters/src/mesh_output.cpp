// Mesh output: file type dispatch, PLY and OBJ writers (glTF is in mesh_output_gltf.cpp).
#include "ellicast/converters/mesh_output.h"

#include "ellicast/format.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace ellicast {

namespace {

bool save(const std::string& path, const std::string& bytes, std::string& error) {
    std::string message;
    auto data = reinterpret_cast<const uint8_t*>(bytes.data());
    if (write_file(path, std::span<const uint8_t>(data, bytes.size()), message) != Error::Ok) {
        error = "cannot write " + path + ": " + message;
        return false;
    }
    return true;
}

template <typename T>
void put(std::string& out, T value) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));  // little-endian hosts only (x86-64, aarch64)
    out.append(b, sizeof(T));
}

// ellicast::Mesh colours are linear (glTF's COLOR_0); PLY and OBJ colours are sRGB, as the readers
// in openmesh_input.cpp assume when they convert them to linear.
float linear_to_srgb(float c) {
    if (!(c > 0)) return 0;
    if (c >= 1) return 1;
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1 / 2.4f) - 0.055f;
}

uint8_t to_byte(float c) { return uint8_t(std::lround(linear_to_srgb(c) * 255.0f)); }

bool all_have(const std::vector<Mesh>& meshes, bool (Mesh::*has)() const) {
    bool any = false;
    for (const auto& m : meshes) {
        if (m.positions.empty()) continue;
        if (!(m.*has)()) return false;
        any = true;
    }
    return any;
}

void append_float(std::string& s, float v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", double(v));
    s += b;
}

}  // namespace

bool mesh_file_type_from_path(const std::string& path, MeshFileType& type) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".glb") type = MeshFileType::Glb;
    else if (ext == ".gltf") type = MeshFileType::Gltf;
    else if (ext == ".ply") type = MeshFileType::Ply;
    else if (ext == ".obj") type = MeshFileType::Obj;
    else return false;
    return true;
}

bool write_meshes(const std::string& path, const std::vector<Mesh>& meshes, std::string& error) {
    MeshFileType type;
    if (!mesh_file_type_from_path(path, type)) {
        error = path + ": unknown output type (expected .glb, .gltf, .ply or .obj)";
        return false;
    }
    switch (type) {
        case MeshFileType::Glb: return write_gltf(path, meshes, true, error);
        case MeshFileType::Gltf: return write_gltf(path, meshes, false, error);
        case MeshFileType::Ply: return write_ply(path, meshes, error);
        case MeshFileType::Obj: return write_obj(path, meshes, error);
    }
    return false;
}

bool write_ply(const std::string& path, const std::vector<Mesh>& meshes, std::string& error) {
    const bool normals = all_have(meshes, &Mesh::has_normals);
    const bool texcoords = all_have(meshes, &Mesh::has_texcoords);
    const bool colors = all_have(meshes, &Mesh::has_colors);
    bool alpha = colors;
    size_t nv = 0, nf = 0;
    for (const auto& m : meshes) {
        nv += m.positions.size();
        nf += m.triangles.size();
        if (!m.positions.empty()) alpha = alpha && m.colors_have_alpha;
    }
    if (nv > 0xFFFFFFFFu) {
        error = path + ": too many vertices for 32-bit PLY indices";
        return false;
    }
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by ellicast\n";
    out += "element vertex " + std::to_string(nv) + "\nproperty float x\nproperty float y\nproperty float z\n";
    if (normals) out += "property float nx\nproperty float ny\nproperty float nz\n";
    if (texcoords) out += "property float s\nproperty float t\n";
    if (colors) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    if (alpha) out += "property uchar alpha\n";
    out += "element face " + std::to_string(nf) + "\nproperty list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + nv * 40 + nf * 13);
    for (const auto& m : meshes) {
        for (size_t i = 0; i < m.positions.size(); ++i) {
            for (float c : m.positions[i]) put(out, c);
            if (normals)
                for (float c : m.normals[i]) put(out, c);
            if (texcoords)
                for (float c : m.texcoords[i]) put(out, c);
            if (colors)
                for (int k = 0; k < (alpha ? 4 : 3); ++k)
                    put(out, k == 3 ? uint8_t(std::lround(std::clamp(m.colors[i][3], 0.0f, 1.0f) * 255.0f))
                                    : to_byte(m.colors[i][k]));
        }
    }
    uint32_t base = 0;
    for (const auto& m : meshes) {
        for (const auto& t : m.triangles) {
            put(out, uint8_t(3));
            for (uint32_t i : t) put(out, int32_t(base + i));
        }
        base += uint32_t(m.positions.size());
    }
    return save(path, out, error);
}

bool write_obj(const std::string& path, const std::vector<Mesh>& meshes, std::string& error) {
    std::string out = "# written by ellicast\n";
    size_t base = 1;
    for (size_t mi = 0; mi < meshes.size(); ++mi) {
        const Mesh& m = meshes[mi];
        if (m.positions.empty()) continue;
        out += "o " + (m.name.empty() ? "object" + std::to_string(mi) : m.name) + "\n";
        for (size_t i = 0; i < m.positions.size(); ++i) {
            out += "v";
            for (float c : m.positions[i]) out += ' ', append_float(out, c);
            if (m.has_colors())
                for (int k = 0; k < 3; ++k) out += ' ', append_float(out, linear_to_srgb(m.colors[i][k]));
            out += '\n';
        }
        for (const auto& t : m.texcoords) {
            out += "vt ";
            append_float(out, t[0]);
            out += ' ';
            append_float(out, t[1]);
            out += '\n';
        }
        for (const auto& n : m.normals) {
            out += "vn";
            for (float c : n) out += ' ', append_float(out, c);
            out += '\n';
        }
        if (m.is_point_set || m.triangles.empty()) {
            for (size_t i = 0; i < m.positions.size(); ++i) out += "p " + std::to_string(base + i) + "\n";
        }
        for (const auto& t : m.triangles) {
            out += "f";
            for (uint32_t i : t) {
                std::string idx = std::to_string(base + i);
                out += ' ' + idx;
                if (m.has_texcoords() || m.has_normals()) {
                    out += '/';
                    if (m.has_texcoords()) out += idx;
                    if (m.has_normals()) out += '/' + idx;
                }
            }
            out += '\n';
        }
        base += m.positions.size();
    }
    return save(path, out, error);
}

}  // namespace ellicast

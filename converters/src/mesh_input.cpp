// Choosing a reader for a model file, and the checks every reader's output goes through.
#include "ellicast/converters/mesh_input.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace ellicast {

namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

bool starts_with_gltf_magic(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    return in.gcount() == 4 && magic[0] == 'g' && magic[1] == 'l' && magic[2] == 'T' && magic[3] == 'F';
}

}  // namespace

std::string quoted_input(const std::string& text, size_t limit) {
    size_t n = std::min(text.size(), limit);
    while (n < text.size() && n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
    std::string out;
    out.reserve(n + 32);
    out += '"';
    out.append(text, 0, n);
    if (n < text.size()) {
        out += "...\" (";
        out += std::to_string(text.size());
        out += " bytes)";
    } else {
        out += '"';
    }
    return out;
}

LoadResult load_meshes(const std::string& path, const InputOptions& options) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": no such file");
    if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a directory, not a model file");
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw InputError(path + ": cannot be opened for reading");
    probe.seekg(0, std::ios::end);
    if (probe.tellg() <= 0) throw InputError(path + ": the file is empty");
    probe.close();

    std::string ext = lower_extension(path);
    if (ext == ".gltf" || ext == ".glb" || starts_with_gltf_magic(path)) return load_gltf(path, options);
    if (ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl") return load_openmesh(path);
    throw InputError(path + ": unsupported file type '" + ext +
                     "' (ellicast reads .gltf, .glb, .obj, .ply, .off and .stl)");
}

void check_and_repair_mesh(Mesh& mesh, const std::string& source, std::vector<std::string>& warnings) {
    const size_t n = mesh.positions.size();
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            if (!std::isfinite(mesh.positions[i][k]))
                throw InputError(source + ": vertex " + std::to_string(i) + " has a non-finite coordinate (" +
                                 std::to_string(mesh.positions[i][k]) + ")");

    auto drop_mismatched = [&](auto& attr, const char* name) {
        if (!attr.empty() && attr.size() != n) {
            warnings.push_back(source + ": " + name + " has " + std::to_string(attr.size()) + " values for " +
                               std::to_string(n) + " vertices; dropped");
            attr.clear();
        }
    };
    drop_mismatched(mesh.normals, "normal attribute");
    drop_mismatched(mesh.texcoords, "TEXCOORD_0");
    drop_mismatched(mesh.colors, "COLOR_0");
    // Further sets (format 1.14): only after a TEXCOORD_0, complete, in order.
    if (!mesh.has_texcoords() && !mesh.texcoord_sets.empty()) {
        warnings.push_back(source + ": TEXCOORD_1 and above without TEXCOORD_0; dropped");
        mesh.texcoord_sets.clear();
    }
    for (size_t s = 0; s < mesh.texcoord_sets.size(); ++s)
        if (mesh.texcoord_sets[s].size() != n) {
            warnings.push_back(source + ": TEXCOORD_" + std::to_string(s + 1) + " has " +
                               std::to_string(mesh.texcoord_sets[s].size()) + " values for " + std::to_string(n) +
                               " vertices; it and the sets after it dropped");
            mesh.texcoord_sets.resize(s);
            break;
        }

    size_t bad_normals = 0, bad_uv = 0, bad_colors = 0;
    for (auto& v : mesh.normals) {
        double len = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
        if (!std::isfinite(len) || len < 1e-12) {
            v = {0, 0, 1};
            ++bad_normals;
        } else if (std::abs(len - 1) > 1e-6) {
            for (auto& c : v) c = float(c / len);
        }
    }
    for (auto& v : mesh.texcoords)
        for (auto& c : v)
            if (!std::isfinite(c)) {
                c = 0;
                ++bad_uv;
            }
    for (auto& set : mesh.texcoord_sets)
        for (auto& v : set)
            for (auto& c : v)
                if (!std::isfinite(c)) {
                    c = 0;
                    ++bad_uv;
                }
    for (auto& v : mesh.colors)
        for (auto& c : v)
            if (!std::isfinite(c) || c < 0 || c > 1) {
                c = std::isfinite(c) ? std::clamp(c, 0.0f, 1.0f) : 0.0f;
                ++bad_colors;
            }
    if (bad_normals)
        warnings.push_back(source + ": " + std::to_string(bad_normals) + " zero or non-finite normals replaced");
    if (bad_uv) warnings.push_back(source + ": " + std::to_string(bad_uv) + " non-finite texture coordinates set to 0");
    if (bad_colors) warnings.push_back(source + ": " + std::to_string(bad_colors) + " colour values clamped to [0,1]");

    if (mesh.is_point_set) {
        mesh.triangles.clear();
        return;
    }

    // Each triangle's vertices sorted, with its index: the same three positions in any order and
    // orientation is a duplicate face, the first in the input kept. Found by sorting these keys (a
    // std::set of every triangle took 30 to 50 ms of a 100k-triangle load).
    struct Key {
        std::array<uint32_t, 3> v;
        uint32_t triangle;
        bool operator<(const Key& o) const { return v < o.v || (v == o.v && triangle < o.triangle); }
    };
    std::vector<Key> keys;
    keys.reserve(mesh.triangles.size());
    size_t degenerate = 0, duplicate = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        for (uint32_t v : tri)
            if (v >= n)
                throw InputError(source + ": triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                 " of " + std::to_string(n));
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
            ++degenerate;
            continue;
        }
        const auto &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
        double u[3], w[3];
        for (int k = 0; k < 3; ++k) {
            u[k] = double(b[k]) - a[k];
            w[k] = double(c[k]) - a[k];
        }
        double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2], cz = u[0] * w[1] - u[1] * w[0];
        if (cx * cx + cy * cy + cz * cz == 0) {
            ++degenerate;
            continue;
        }
        Key key{tri, uint32_t(t)};
        std::sort(key.v.begin(), key.v.end());
        keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end());
    std::vector<char> keep(mesh.triangles.size(), 0);
    for (size_t i = 0; i < keys.size(); ++i) {
        if (i > 0 && keys[i].v == keys[i - 1].v) {
            ++duplicate;
            continue;
        }
        keep[keys[i].triangle] = 1;
    }
    std::vector<std::array<uint32_t, 3>> kept;
    kept.reserve(keys.size() - duplicate);
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
        if (keep[t]) kept.push_back(mesh.triangles[t]);
    if (degenerate)
        warnings.push_back(source + ": " + std::to_string(degenerate) + " degenerate (zero-area) triangles dropped");
    if (duplicate) warnings.push_back(source + ": " + std::to_string(duplicate) + " duplicate triangles dropped");
    mesh.triangles = std::move(kept);

    // Non-manifold edges (three or more faces) are harmless to the encoder; say so once. Each edge
    // (lower vertex, higher vertex) once per face, sorted: an edge of three or more faces is a run of
    // three or more.
    std::vector<uint64_t> edges;
    edges.reserve(3 * mesh.triangles.size());
    for (const auto& tri : mesh.triangles)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = tri[e], b = tri[(e + 1) % 3];
            edges.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    size_t nonmanifold = 0;
    for (size_t i = 0, j; i < edges.size(); i = j) {
        for (j = i + 1; j < edges.size() && edges[j] == edges[i];) ++j;
        if (j - i > 2) ++nonmanifold;
    }
    if (nonmanifold)
        warnings.push_back(source + ": " + std::to_string(nonmanifold) +
                           " non-manifold edges (3 or more faces) kept as they are; the encoder does not need a "
                           "manifold surface");
}

}  // namespace ellicast

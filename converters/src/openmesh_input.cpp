// OBJ, PLY, OFF and STL through OpenMesh's readers, into the same Mesh a glTF primitive gives:
// per-corner texture coordinates (OBJ "vt") split vertices at seams, colours become linear RGBA.
#include "ellicast/converters/mesh_input.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace ellicast {

namespace {

struct InputTraits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3f Point;
    typedef OpenMesh::Vec3f Normal;
    typedef OpenMesh::Vec4f Color;
    typedef OpenMesh::Vec2f TexCoord2D;
    VertexAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Color | OpenMesh::Attributes::TexCoord2D);
    HalfedgeAttributes(OpenMesh::Attributes::TexCoord2D | OpenMesh::Attributes::PrevHalfedge);
    FaceAttributes(OpenMesh::Attributes::None);
};
using InputMesh = OpenMesh::TriMesh_ArrayKernelT<InputTraits>;

float srgb_to_linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// OpenMesh reports trouble (complex edges, unreadable lines) on omerr: collect it instead.
class CapturedErrors {
public:
    CapturedErrors() {
        omerr().disconnect(std::cerr);
        omerr().connect(captured_);
        omlog().disable();
    }
    ~CapturedErrors() {
        omerr().flush();
        omerr().disconnect(captured_);
        omerr().connect(std::cerr);
        omlog().enable();
    }
    std::vector<std::string> lines() {
        omerr().flush();
        std::vector<std::string> out;
        std::istringstream in(captured_.str());
        for (std::string line; std::getline(in, line);)
            if (!line.empty()) out.push_back(line);
        return out;
    }

private:
    std::ostringstream captured_;
};

// OpenMesh's OBJ reader silently skips a "v" line it cannot parse (nan, inf, garbage), which would
// shift every later index. Check the vertex lines first and name the first bad one.
void check_obj_vertex_lines(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    for (size_t number = 1; std::getline(in, line); ++number) {
        if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
        const char* p = line.c_str() + 2;
        for (int k = 0; k < 3; ++k) {
            char* end = nullptr;
            double value = std::strtod(p, &end);
            if (end == p || !std::isfinite(value))
                throw InputError(path + ": line " + std::to_string(number) + ": vertex coordinate " +
                                 std::to_string(k + 1) + " is not a finite number (\"" + line + "\")");
            p = end;
        }
    }
}

}  // namespace

LoadResult load_openmesh(const std::string& path) {
    InputMesh om;
    OpenMesh::IO::Options opt;
    opt += OpenMesh::IO::Options::VertexNormal;
    opt += OpenMesh::IO::Options::VertexColor;
    opt += OpenMesh::IO::Options::VertexTexCoord;
    opt += OpenMesh::IO::Options::FaceTexCoord;
    std::string ext = std::filesystem::path(path).extension().string();
    for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".obj") check_obj_vertex_lines(path);
    std::vector<std::string> reader_messages;
    bool ok;
    {
        CapturedErrors capture;
        ok = OpenMesh::IO::read_mesh(om, path, opt);
        reader_messages = capture.lines();
    }
    if (!ok) {
        std::string why = reader_messages.empty() ? "the reader rejected it" : reader_messages.front();
        throw InputError(path + ": not a readable mesh file: " + why);
    }

    LoadResult result;
    size_t complex = 0;
    for (const auto& line : reader_messages)
        if (line.find("complex") != std::string::npos) ++complex;
    if (complex)
        result.warnings.push_back(path + ": " + std::to_string(complex) +
                                  " faces touched non-manifold edges or vertices; the reader duplicated their "
                                  "vertices to keep them");
    else if (!reader_messages.empty())
        result.warnings.push_back(path + ": reader: " + reader_messages.front());

    Mesh mesh;
    mesh.name = std::filesystem::path(path).stem().string();
    const bool normals = opt.check(OpenMesh::IO::Options::VertexNormal);
    const bool colors = opt.check(OpenMesh::IO::Options::VertexColor);
    const bool corner_uv = opt.check(OpenMesh::IO::Options::FaceTexCoord);
    const bool vertex_uv = !corner_uv && opt.check(OpenMesh::IO::Options::VertexTexCoord);
    mesh.colors_have_alpha = colors && opt.check(OpenMesh::IO::Options::ColorAlpha);

    // With per-corner texture coordinates a vertex is split once per distinct (vertex, uv).
    std::map<std::pair<int, std::array<float, 2>>, uint32_t> split;
    std::vector<uint32_t> plain(om.n_vertices(), UINT32_MAX);
    std::vector<bool> used(om.n_vertices(), false);
    auto emit = [&](InputMesh::VertexHandle vh, const std::array<float, 2>* uv) -> uint32_t {
        used[vh.idx()] = true;
        uint32_t* slot;
        if (uv) {
            auto [it, inserted] = split.try_emplace({vh.idx(), *uv}, uint32_t(mesh.positions.size()));
            if (!inserted) return it->second;
            slot = &it->second;
        } else {
            if (plain[vh.idx()] != UINT32_MAX) return plain[vh.idx()];
            plain[vh.idx()] = uint32_t(mesh.positions.size());
            slot = &plain[vh.idx()];
        }
        auto p = om.point(vh);
        mesh.positions.push_back({p[0], p[1], p[2]});
        if (normals) {
            auto n = om.normal(vh);
            mesh.normals.push_back({n[0], n[1], n[2]});
        }
        if (colors) {
            auto c = om.color(vh);
            mesh.colors.push_back({srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2]),
                                   mesh.colors_have_alpha ? c[3] : 1.0f});
        }
        if (uv) mesh.texcoords.push_back(*uv);
        else if (vertex_uv) {
            auto t = om.texcoord2D(vh);
            mesh.texcoords.push_back({t[0], t[1]});
        }
        return *slot;
    };

    mesh.triangles.reserve(om.n_faces());
    for (auto fh : om.faces()) {
        std::array<uint32_t, 3> tri{};
        int k = 0;
        for (auto heh : om.fh_range(fh)) {
            if (k == 3) break;
            auto vh = om.to_vertex_handle(heh);
            if (corner_uv) {
                auto t = om.texcoord2D(heh);
                std::array<float, 2> uv{t[0], t[1]};
                tri[k++] = emit(vh, &uv);
            } else {
                tri[k++] = emit(vh, nullptr);
            }
        }
        if (k == 3) mesh.triangles.push_back(tri);
    }
    // Vertices no face uses are original vertices too (the bunny has about a thousand): keep them.
    const std::array<float, 2> no_uv{0, 0};
    for (auto vh : om.vertices())
        if (!used[vh.idx()]) emit(vh, corner_uv ? &no_uv : nullptr);
    if (mesh.triangles.empty()) {
        if (om.n_vertices() == 0) throw InputError(path + ": the file holds no vertices");
        throw InputError(path + ": no faces could be read (" + std::to_string(om.n_vertices()) +
                         " vertices): the file has none, or the reader stopped at a value it could not parse "
                         "(such as nan); ellicast encodes triangle meshes from this format");
    }
    check_and_repair_mesh(mesh, path, result.warnings);
    if (mesh.triangles.empty()) throw InputError(path + ": every face is degenerate; nothing to encode");
    result.meshes.push_back(std::move(mesh));
    return result;
}

}  // namespace ellicast

// Mesh output: glTF/GLB checked by the Khronos glTF-Validator, PLY and OBJ read back by our reader.
#include "decoder_shapes.h"
#include "support.h"

#include "ellicast/codec/decoder.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/converters/mesh_output.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

// A decoded sphere carrying normals, texture coordinates and RGBA colours.
Mesh attributed_sphere() {
    auto points = seamed_uv_sphere(10, 20, 1.0);
    for (auto& p : points) p.color = {p.texcoord[0], p.texcoord[1], 0.5f, 0.75f};
    auto info = object_info({-1.25f, -1.25f, -1.25f}, 2.5f, 1, points.size(),
                            kAttrNormal | kAttrTexcoord | kAttrColor | kAttrColorAlpha);
    Mesh mesh;
    ObjectDecodeReport report;
    std::string error;
    REQUIRE(decode_object(info, {sphere_ellipsoid({0, 0, 0}, 1)}, points, 0, DecodeOptions{}, 0, mesh, report, error));
    mesh.name = "sphere";
    return mesh;
}

// A flat grid of n x n vertices (more than 65535 of them needs 32-bit indices).
Mesh grid_mesh(int n) {
    Mesh m;
    m.name = "grid";
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            m.positions.push_back({float(i), float(j), 0});
            m.normals.push_back({0, 0, 2});  // not unit: the writer must normalize
        }
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            m.triangles.push_back({a, b, d});
            m.triangles.push_back({a, d, c});
        }
    return m;
}

Mesh point_cloud() {
    Mesh m;
    m.name = "points";
    m.is_point_set = true;
    for (const auto& p : fibonacci_sphere(100, 2.0)) {
        m.positions.push_back(p.position);
        m.colors.push_back({1.5f, 0.2f, -0.1f, 1});  // out of range: the writer clamps
    }
    return m;
}

}  // namespace

TEST_CASE("written GLB and glTF files pass the Khronos glTF-Validator with no error") {
    auto dir = scratch_dir("mesh_output_validator");
    std::vector<Mesh> meshes = {attributed_sphere(), grid_mesh(260), point_cloud(), Mesh{}};
    for (const char* name : {"all.glb", "all.gltf"}) {
        std::string error;
        REQUIRE_MESSAGE(write_meshes((dir / name).string(), meshes, error), error);
        int errors = -1;
        std::string report;
        if (!validate_gltf(dir / name, errors, report)) return;
        CHECK_MESSAGE(errors == 0, name << ": " << report);
    }
    CHECK(fs::exists(dir / "all.bin"));
    // An empty model is still a valid glTF.
    std::string error;
    REQUIRE(write_meshes((dir / "empty.glb").string(), {}, error));
    int errors = -1;
    std::string report;
    if (validate_gltf(dir / "empty.glb", errors, report)) CHECK_MESSAGE(errors == 0, report);
}

TEST_CASE("GLB, glTF, PLY and OBJ output read back with the same geometry and attributes") {
    auto dir = scratch_dir("mesh_output_roundtrip");
    Mesh sphere = attributed_sphere();
    for (const char* name : {"s.glb", "s.gltf", "s.ply", "s.obj"}) {
        CAPTURE(name);
        std::string error;
        REQUIRE_MESSAGE(write_meshes((dir / name).string(), {sphere}, error), error);
        LoadResult loaded = load_meshes((dir / name).string());
        REQUIRE(loaded.meshes.size() == 1);
        const Mesh& m = loaded.meshes[0];
        CHECK(m.triangles.size() == sphere.triangles.size());
        CHECK(m.has_normals());
        CHECK(m.has_texcoords());
        // Every vertex read back is one we wrote, within float printing precision.
        std::map<std::array<float, 3>, int> written;
        for (const auto& p : sphere.positions) written[p] = 1;
        size_t unknown = 0;
        for (const auto& p : m.positions) {
            auto it = written.lower_bound({p[0] - 1e-6f, p[1] - 1e-6f, p[2] - 1e-6f});
            bool found = false;
            for (; it != written.end() && it->first[0] <= p[0] + 1e-6f && !found; ++it)
                found = std::abs(it->first[1] - p[1]) < 1e-6f && std::abs(it->first[2] - p[2]) < 1e-6f;
            unknown += found ? 0 : 1;
        }
        CHECK(unknown == 0);
    }
}

TEST_CASE("an unknown output extension or an unwritable path is refused with the path in the message") {
    auto dir = scratch_dir("mesh_output_errors");
    std::string error;
    CHECK_FALSE(write_meshes((dir / "out.stl").string(), {grid_mesh(3)}, error));
    CHECK(error.find("out.stl") != std::string::npos);
    error.clear();
    CHECK_FALSE(write_meshes((dir / "missing" / "out.ply").string(), {grid_mesh(3)}, error));
    CHECK(error.find("out.ply") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "missing" / "out.ply"));
}

TEST_CASE("a bad triangle index is refused instead of writing an invalid glTF") {
    auto dir = scratch_dir("mesh_output_bad_index");
    Mesh m = grid_mesh(3);
    m.triangles.push_back({0, 1, 99});
    std::string error;
    CHECK_FALSE(write_meshes((dir / "bad.glb").string(), {m}, error));
    CHECK(error.find("index") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "bad.glb"));
}

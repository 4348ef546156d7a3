// EXT_meshopt_compression input: assets compressed by glTF-Transform's `meshopt` command (meshopt
// codecs, octahedral normals, KHR_mesh_quantization) load as their uncompressed twins, within the
// quantization glTF-Transform applied; broken compressed data gives an error naming the buffer view.
#include "ellicast/converters/asset.h"
#include "ellicast/converters/mesh_input.h"
#include "support.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

std::string sample(const std::string& rel) { return (shared_samples() / rel).string(); }

// `input` through `gltf-transform meshopt` into `out`; false (with a message) when it is absent.
bool compress_with_meshopt(const std::string& input, const fs::path& out) {
    if (!have_node_package("@gltf-transform/cli")) return false;
    int status = 0;
    std::string command = "'";
    command += (node_modules() / ".bin" / "gltf-transform").string();
    command += "' meshopt '" + input;
    command += "' '" + out.string() + "'";
    const std::string log = run_command(command, status);
    INFO(log);
    REQUIRE(status == 0);
    return true;
}

double diagonal(const Mesh& m) {
    std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const auto& p : m.positions)
        for (int k = 0; k < 3; ++k) lo[k] = std::min<double>(lo[k], p[k]), hi[k] = std::max<double>(hi[k], p[k]);
    return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// Largest distance from a position of `a` to the nearest position of `b` (a grid of cells of
// size `cell` keeps it linear).
double farthest(const Mesh& a, const Mesh& b, double cell) {
    std::map<std::array<long, 3>, std::vector<uint32_t>> grid;
    auto key = [&](const std::array<float, 3>& p) {
        return std::array<long, 3>{long(std::floor(p[0] / cell)), long(std::floor(p[1] / cell)), long(std::floor(p[2] / cell))};
    };
    for (uint32_t i = 0; i < b.positions.size(); ++i) grid[key(b.positions[i])].push_back(i);
    double worst = 0;
    for (const auto& p : a.positions) {
        const auto k = key(p);
        double best = INFINITY;
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy)
                for (long dz = -1; dz <= 1; ++dz) {
                    auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
                    if (it == grid.end()) continue;
                    for (uint32_t j : it->second) {
                        const auto& q = b.positions[j];
                        best = std::min(best, std::hypot(double(p[0]) - q[0], double(p[1]) - q[1], double(p[2]) - q[2]));
                    }
                }
        worst = std::max(worst, best);
    }
    return worst;
}

}  // namespace

TEST_CASE("a glTF compressed with EXT_meshopt_compression loads as its uncompressed twin within quantization") {
    const fs::path dir = scratch_dir("meshopt_input");
    for (const auto& [source, compressed] : std::vector<std::pair<std::string, std::string>>{
             {"gltf/Duck/Duck.gltf", "duck.glb"}, {"gltf/Box-glb/Box.glb", "box.gltf"}}) {
        if (!have_sample(source)) continue;
        CAPTURE(source);
        if (!compress_with_meshopt(sample(source), dir / compressed)) return;
        const LoadResult plain = load_meshes(sample(source));
        const LoadResult packed = load_meshes((dir / compressed).string());
        REQUIRE(plain.meshes.size() == packed.meshes.size());
        for (size_t i = 0; i < plain.meshes.size(); ++i) {
            const Mesh &a = plain.meshes[i], &b = packed.meshes[i];
            CHECK(a.triangles.size() == b.triangles.size());
            CHECK(a.has_normals() == b.has_normals());
            CHECK(a.has_texcoords() == b.has_texcoords());
            // glTF-Transform quantizes positions to 14 bits of the bounding box: half a step is
            // diagonal / 2^14 / 2 per axis at most.
            const double step = diagonal(a) / 16383.0;
            CHECK(farthest(a, b, 4 * step) <= step);
            CHECK(farthest(b, a, 4 * step) <= step);
            if (a.has_normals()) {
                // Every normal has a twin at the same position (a seam has several) within a few
                // degrees: glTF-Transform keeps 8-bit octahedral normals.
                size_t checked = 0, off = 0;
                for (size_t v = 0; v < b.positions.size(); v += 7, ++checked) {
                    const auto& p = b.positions[v];
                    double best = -1;
                    for (size_t u = 0; u < a.positions.size(); ++u) {
                        const auto& q = a.positions[u];
                        if (std::hypot(double(p[0]) - q[0], double(p[1]) - q[1], double(p[2]) - q[2]) > step) continue;
                        const auto &n = b.normals[v], &m = a.normals[u];
                        best = std::max(best, double(n[0] * m[0] + n[1] * m[1] + n[2] * m[2]));
                    }
                    off += best < 0.99;
                }
                CHECK(off == 0);
                CHECK(checked > 0);
            }
        }
    }
}

TEST_CASE("broken EXT_meshopt_compression data gives an error naming the buffer view, never a crash") {
    const fs::path dir = scratch_dir("meshopt_input_broken");
    if (!have_sample("gltf/Box-glb/Box.glb")) return;
    if (!compress_with_meshopt(sample("gltf/Box-glb/Box.glb"), dir / "box.gltf")) return;
    const nlohmann::json original = nlohmann::json::parse(std::ifstream(dir / "box.gltf"));
    size_t view = 0;
    while (!original["bufferViews"][view].contains("extensions")) ++view;
    const std::string at = "bufferViews[" + std::to_string(view) + "]";
    struct Case {
        const char* what;
        std::function<void(nlohmann::json&)> edit;
        std::string says;
    };
    const std::vector<Case> cases = {
        {"count past the view", [&](auto& d) { d["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["count"] = 1u << 30; }, "more than its byteLength"},
        {"stride not a multiple of 4", [&](auto& d) {
             auto& e = d["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
             e["byteStride"] = 3;
             e["count"] = 4;
             e["mode"] = "ATTRIBUTES";
         }, "byteStride 3"},
        {"unknown mode", [&](auto& d) { d["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["mode"] = "WAVELETS"; }, "unknown mode"},
        {"source past the buffer", [&](auto& d) { d["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 100000; }, "run past"},
        {"cut short", [&](auto& d) { d["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 2; }, "does not decode"},
        {"a buffer outside the folder", [&](auto& d) { d["buffers"][0]["uri"] = "..%2F..%2Fetc%2Fpasswd"; }, "a file above the asset's folder"},
    };
    for (const auto& c : cases) {
        INFO(std::string(c.what));
        nlohmann::json doc = original;
        c.edit(doc);
        std::ofstream(dir / "broken.gltf") << doc.dump();
        try {
            load_meshes((dir / "broken.gltf").string());
            FAIL("loaded");
        } catch (const InputError& e) {
            const std::string message = e.what();
            INFO(message);
            CHECK(message.find(c.says) != std::string::npos);
            CHECK(message.find("broken.gltf") != std::string::npos);
        }
    }
}

TEST_CASE("--meshopt writes EXT_meshopt_compression that the validator, glTF-Transform and our reader take, the geometry "
          "of --quantize, and a meshopt input comes back meshopt") {
    const fs::path dir = scratch_dir("meshopt_output");
    std::vector<std::string> inputs = {(source_dir() / "samples" / "multiuv" / "MultiUVBox.gltf").string(),
                                       (source_dir() / "samples" / "khronos" / "RiggedSimple" / "RiggedSimple.gltf").string()};
    if (have_sample("gltf/Duck/Duck.gltf")) inputs.push_back(sample("gltf/Duck/Duck.gltf"));
    for (const std::string& input : inputs) {
        CAPTURE(input);
        const std::string stem = fs::path(input).stem().string();
        auto convert = [&](const std::string& in, const fs::path& out, const std::string& flags) {
            int status = 0;
            const std::string log = run_command("'" + ellicast_exe().string() + "' convert " + flags + " '" + in + "' '" +
                                                    out.string() + "' 2>&1",
                                                status);
            REQUIRE_MESSAGE(status == 0, log);
            return log;
        };
        const fs::path packed = dir / (stem + "-meshopt.glb"), quantized = dir / (stem + "-quantized.glb");
        convert(input, packed, "-q --meshopt");
        convert(input, quantized, "-q --quantize");
        check_gltf_clean(packed, {"NODE_SKINNED_MESH_NON_ROOT"});
        const nlohmann::json doc = gltf_document(packed);
        CHECK(doc["extensionsRequired"].dump().find("EXT_meshopt_compression") != std::string::npos);
        REQUIRE(doc["buffers"].size() == 2);
        CHECK_FALSE(doc["buffers"][1].contains("uri"));
        CHECK(doc["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"] == true);
        size_t compressed = 0;
        for (const auto& view : doc["bufferViews"]) compressed += view.contains("extensions");
        CHECK(compressed >= 3);  // positions, indices and more at least
        // Smaller than the quantized file, but on a box of 24 vertices (the extension's JSON outweighs
        // what the codecs save there).
        if (stem != "MultiUVBox") CHECK(fs::file_size(packed) < fs::file_size(quantized));
        // Read back: the same meshes as the quantized file (vertices reordered, the same set).
        const Asset a = load_asset(packed.string()), b = load_asset(quantized.string());
        REQUIRE(a.objects.size() == b.objects.size());
        for (size_t o = 0; o < a.objects.size(); ++o) {
            CHECK(a.objects[o].triangles.size() == b.objects[o].triangles.size());
            CHECK(a.objects[o].texcoord_sets.size() == b.objects[o].texcoord_sets.size());
            CHECK(farthest(a.objects[o], b.objects[o], diagonal(b.objects[o]) / 64) <= 1e-6 * diagonal(b.objects[o]));
            CHECK(farthest(b.objects[o], a.objects[o], diagonal(b.objects[o]) / 64) <= 1e-6 * diagonal(b.objects[o]));
        }
        // A meshopt input comes back meshopt.
        const std::string log = convert(packed.string(), dir / (stem + "-again.glb"), "");
        CHECK_MESSAGE(log.find("output written meshopt-compressed (EXT_meshopt_compression") != std::string::npos, log);
        if (have_node_package("@gltf-transform/cli")) {
            int status = 0;
            const std::string report = run_command(
                "'" + (node_modules() / ".bin" / "gltf-transform").string() + "' inspect --format csv '" + packed.string() + "' 2>&1",
                status);
            CHECK_MESSAGE(status == 0, report);
            CHECK(report.find("EXT_meshopt_compression") != std::string::npos);
        }
    }
    // Refused with Draco, and for a PLY.
    int status = 0;
    const std::string box = (source_dir() / "samples" / "multiuv" / "MultiUVBox.gltf").string();
    std::string log = run_command("'" + ellicast_exe().string() + "' convert --meshopt --draco '" + box + "' '" +
                                      (dir / "x.glb").string() + "' 2>&1", status);
    CHECK(status == 2);
    CHECK_MESSAGE(log.find("--draco and --meshopt cannot be combined") != std::string::npos, log);
    log = run_command("'" + ellicast_exe().string() + "' convert --meshopt '" + box + "' '" + (dir / "x.ply").string() +
                          "' 2>&1", status);
    CHECK(status == 2);
    CHECK_MESSAGE(log.find("need a .glb or .gltf output") != std::string::npos, log);
}

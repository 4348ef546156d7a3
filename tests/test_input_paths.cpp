// A glTF's buffers and images must be in its folder: URIs that climb out of it (plainly, percent-
// encoded, absolute, or through a symlink) are refused unless the user allows it.
#include "ellicast/converters/asset.h"
#include "ellicast/converters/mesh_input.h"
#include "support.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <fstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

TEST_CASE("glTF buffer and image URIs that leave the asset's folder are refused, unless allowed") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const fs::path dir = scratch_dir("input_paths");
    const fs::path inner = dir / "a" / "b";
    fs::create_directories(inner);
    const fs::path duck = shared_samples() / "gltf" / "Duck";
    fs::copy_file(duck / "Duck0.bin", inner / "Duck0.bin");
    fs::copy_file(duck / "DuckCM.png", dir / "a" / "DuckCM.png");
    fs::copy_file(duck / "Duck0.bin", dir / "outside.bin");
    fs::create_symlink(dir / "outside.bin", inner / "link.bin");
    const nlohmann::json original = nlohmann::json::parse(std::ifstream(duck / "Duck.gltf"));
    struct Case {
        const char* name;
        const char* list;
        const char* uri;
        const char* says;
    };
    for (const Case& c : {Case{"up", "images", "../DuckCM.png", "a file above the asset's folder"},
                          Case{"percent", "buffers", "..%2F..%2Foutside.bin", "a file above the asset's folder"},
                          Case{"absolute", "buffers", "/etc/passwd", "an absolute path"},
                          Case{"link", "buffers", "link.bin", "a link to a file outside the asset's folder"}}) {
        CAPTURE(c.name);
        nlohmann::json doc = original;
        doc[c.list][0]["uri"] = c.uri;
        const fs::path file = inner / (std::string(c.name) + ".gltf");
        std::ofstream(file) << doc.dump();
        for (int reader = 0; reader < 2; ++reader) {
            try {
                if (reader == 0) load_asset(file.string());
                else load_meshes(file.string());
                FAIL("read " << file);
            } catch (const InputError& e) {
                const std::string message = e.what();
                CHECK(message.find(c.says) != std::string::npos);
                CHECK(message.find(std::string(c.list) + "[0]") != std::string::npos);
            }
        }
    }
    // Inside the folder, "./" is fine; a user who trusts the asset may allow the rest.
    nlohmann::json doc = original;
    doc["buffers"][0]["uri"] = "./Duck0.bin";
    doc["images"][0]["uri"] = "../DuckCM.png";
    std::ofstream(inner / "allowed.gltf") << doc.dump();
    CHECK_THROWS_AS(load_asset((inner / "allowed.gltf").string()), InputError);
    const Asset allowed = load_asset((inner / "allowed.gltf").string(), InputOptions{true});
    REQUIRE(allowed.scene.textures.size() == 1);
    CHECK(!allowed.scene.textures[0].image.empty());
    doc["images"][0]["uri"] = "../b/../../a/DuckCM.png";  // climbs out before coming back: refused
    std::ofstream(inner / "zigzag.gltf") << doc.dump();
    CHECK_THROWS_AS(load_asset((inner / "zigzag.gltf").string()), InputError);
}

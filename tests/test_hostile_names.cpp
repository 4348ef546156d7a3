// Names in a stream are UTF-8 (spec 15.1), but a sender may put any bytes there, with valid
// checksums: a decoder shows an ill-formed name with U+FFFD in place (never a crash in a JSON
// writer), warns, and `validate` says the stream does not conform.
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/format.h"
#include "encode_options.h"
#include "shapes.h"
#include "support.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <fstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

TEST_CASE("UTF-8 well-formedness and U+FFFD replacement follow Unicode's rules") {
    CHECK(is_valid_utf8(""));
    CHECK(is_valid_utf8("plain ascii"));
    CHECK(is_valid_utf8("caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"));
    CHECK_FALSE(is_valid_utf8("\xFF"));
    CHECK_FALSE(is_valid_utf8("\xC3"));              // cut short
    CHECK_FALSE(is_valid_utf8("\xC0\xAF"));          // overlong '/'
    CHECK_FALSE(is_valid_utf8("\xED\xA0\x80"));      // a surrogate
    CHECK_FALSE(is_valid_utf8("\xF4\x90\x80\x80"));  // above U+10FFFF
    CHECK(replace_invalid_utf8("ok") == "ok");
    CHECK(replace_invalid_utf8("a\xFF" "b") == "a\xEF\xBF\xBD" "b");
    CHECK(replace_invalid_utf8("\xE2\x82") == "\xEF\xBF\xBD");          // one maximal subpart
    CHECK(replace_invalid_utf8("\xED\xA0\x80") == "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");
    CHECK(replace_invalid_utf8("\xC3\xA9\xC3") == "\xC3\xA9\xEF\xBF\xBD");
    CHECK(is_valid_utf8(replace_invalid_utf8("\x80\xBF\xFE\xFF\xF0\x9F\x98")));
}

TEST_CASE("a stream whose node, mesh and material names are not UTF-8 decodes, writes valid glTF, and does not conform") {
    Asset asset;
    asset.objects = {samples::uv_ellipsoid(12, {0, 0, 0}, {1, 0.7, 0.5})};
    SceneNode node;
    node.name = "bad\xFF\xFEname";
    node.mesh = 0;
    asset.scene.nodes = {node};
    asset.scene.meshes = {SceneMesh{0, "\xC3", {{0, 0}}, {}}};
    Material material;
    material.name = "surrogate \xED\xA0\x80";
    asset.scene.materials = {material};
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(asset, fast_options(), 7, true, encoded, error), error);

    const fs::path dir = scratch_dir("hostile_names");
    {
        std::ofstream out(dir / "names.ellc", std::ios::binary);
        const auto bytes = write_container(encoded.packets);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    ReceivedStream stream;
    for (size_t i = 0; i < encoded.packets.size(); ++i) REQUIRE(stream.add_packet(encoded.packets[i], i) == Error::Ok);
    Asset decoded;
    StreamDecodeReport report;
    DecodeOptions options;
    options.grid_resolution = 32;
    REQUIRE_MESSAGE(decode_asset(stream, options, decoded, report, error), error);
    REQUIRE(decoded.scene.nodes.size() == 1);
    CHECK(decoded.scene.nodes[0].name == "bad\xEF\xBF\xBD\xEF\xBF\xBDname");
    CHECK(decoded.scene.meshes[0].name == "\xEF\xBF\xBD");
    CHECK(is_valid_utf8(decoded.scene.materials[0].name));
    size_t name_warnings = 0;
    for (const auto& w : decoded.warnings) name_warnings += w.find("is not valid UTF-8") != std::string::npos;
    CHECK(name_warnings == 3);

    for (const char* file : {"names.gltf", "names.glb"}) {
        std::vector<std::string> warnings;
        REQUIRE_MESSAGE(write_asset((dir / file).string(), decoded, AssetWriteOptions{}, warnings, error), error);
        int errors = -1;
        std::string text;
        if (validate_gltf(dir / file, errors, text)) CHECK_MESSAGE(errors == 0, text);
    }
    const auto json = nlohmann::json::parse(std::ifstream(dir / "names.gltf"));
    CHECK(json["nodes"][0]["name"] == "bad\xEF\xBF\xBD\xEF\xBF\xBDname");

    // The command-line decoder writes it too, and validate names what is wrong.
    int status = 0;
    std::string command = "'";
    command += ellicast_exe().string();
    command += "' decode -q '" + (dir / "names.ellc").string();
    command += "' -o '" + (dir / "cli.glb").string() + "' --grid 32";
    std::string log = run_command(command, status);
    CHECK_MESSAGE(status == 0, log);
    command = "'";
    command += ellicast_exe().string();
    command += "' validate '" + (dir / "names.ellc").string() + "'";
    log = run_command(command, status);
    CHECK(status == 1);
    CHECK_MESSAGE(log.find("the name of node(s) 0 is not valid UTF-8") != std::string::npos, log);
    CHECK_MESSAGE(log.find("the name of material(s) 0 is not valid UTF-8") != std::string::npos, log);
}

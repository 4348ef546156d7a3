// Skinned assets (format 1.5, spec 21): the Fox read from glTF with its skin and the weights of every
// vertex, sent as SKIN and JOINT_WEIGHTS packets, shown skinned once its skin and weights have
// arrived, and written back as a skinned glTF the Khronos validator accepts.
#include "scene_compare.h"
#include "support.h"

#include "ellicast/converters/asset_stream.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <cstring>
#include <fstream>
#include <map>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

const char* const kFox = "gltf/Fox/Fox.gltf";
// The Fox's skinned node is a child of its root node, as in the source asset, which the validator
// warns about (a skinned mesh ignores its parents' transforms) in the source as in the output.
const std::vector<std::string> kFoxWarnings = {"NODE_SKINNED_MESH_NON_ROOT"};

Asset decode_without(const EncodedAsset& encoded, const std::function<bool(size_t)>& lost) {
    return received_without(encoded.packets, lost, 24);
}

bool any_warning(const Asset& a, const std::string& text) {
    return std::any_of(a.warnings.begin(), a.warnings.end(), [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

// The influences of one vertex as joint -> weight, the zero weights left out.
std::map<uint16_t, float> influences(const VertexWeights& w, size_t v) {
    std::map<uint16_t, float> out;
    for (size_t k = 0; k < 4; ++k)
        if (w.weights[v][k] > 0) out[w.joints[v][k]] += w.weights[v][k];
    return out;
}

}  // namespace

TEST_CASE("the Fox moves after a broadcast: its skin and every vertex's weights come back, and the file validates") {
    if (!have_sample(kFox)) return;
    const Asset in = load_asset(sample(kFox));
    REQUIRE(in.scene.skins.size() == 1);
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    CHECK(encoded.weight_packets > 0);
    const size_t skin_packets =
        size_t(std::count_if(encoded.packets.begin(), encoded.packets.end(), [](const auto& p) { return is_packet_type(p, PacketType::Skin); }));
    CHECK(skin_packets == 2);  // 24 joints of 66 bytes: 17 and 7 in 1200-byte packets

    const Asset all = decode_without(encoded, [](size_t) { return false; });
    check_same_scene(in, all);
    REQUIRE(all.scene.skins.size() == 1);
    const SceneSkin& a = in.scene.skins[0];
    const SceneSkin& b = all.scene.skins[0];
    CHECK(b.name == a.name);
    CHECK(b.skeleton == a.skeleton);
    REQUIRE(b.joints.size() == a.joints.size());
    for (size_t j = 0; j < a.joints.size(); ++j) {
        CAPTURE(j);
        CHECK(b.joints[j].node == a.joints[j].node);  // nodes keep their indices: every one arrived
        CHECK(b.joints[j].inverse_bind == a.joints[j].inverse_bind);
    }
    for (size_t n = 0; n < in.scene.nodes.size(); ++n) CHECK(all.scene.nodes[n].skin == in.scene.nodes[n].skin);
    // The Fox comes back exact: each vertex is an original one, with that vertex's influences, to
    // a 255th (the records' quantum), the weights summing to 1.
    REQUIRE(all.weights.size() == 1);
    const VertexWeights& w = all.weights[0];
    const Mesh& out = all.objects[0];
    REQUIRE(w.joints.size() == out.positions.size());
    const Mesh& original = in.objects[0];
    size_t compared = 0, differing = 0;
    for (size_t v = 0; v < out.positions.size(); ++v) {
        float sum = 0;
        for (float x : w.weights[v]) sum += x;
        CHECK(sum == doctest::Approx(1.0).epsilon(1e-5));
        // Its original vertex: the nearest input vertex (quantization moves it by far less than an edge).
        size_t nearest = 0;
        double best = 1e300;
        for (size_t u = 0; u < original.positions.size(); ++u) {
            double d = 0;
            for (int k = 0; k < 3; ++k) d += double(out.positions[v][k] - original.positions[u][k]) * (out.positions[v][k] - original.positions[u][k]);
            if (d < best) best = d, nearest = u;
        }
        const auto got = influences(w, v), want = influences(in.weights[0], nearest);
        ++compared;
        bool same = true;
        for (const auto& [joint, weight] : want) {
            auto it = got.find(joint);
            const float have = it == got.end() ? 0.0f : it->second;
            same &= std::abs(have - weight) <= 1.0f / 255.0f + 1e-6f;
        }
        for (const auto& [joint, weight] : got) same &= want.count(joint) > 0;
        differing += !same;
    }
    CHECK(compared == out.positions.size());
    // Vertices that share a quantized position with another carrying other weights could differ; the
    // Fox has none.
    CHECK(differing == 0);

    const fs::path dir = scratch_dir("skin_fox");
    std::vector<std::string> warnings;
    REQUIRE_MESSAGE(write_asset((dir / "fox.glb").string(), all, AssetWriteOptions{}, warnings, error), error);
    CHECK(warnings.empty());
    check_gltf_clean(dir / "fox.glb", kFoxWarnings);
    // Quantized or Draco output writes the skinned mesh plain (its weights follow its vertices).
    for (bool draco : {false, true}) {
        AssetWriteOptions packed;
        packed.draco = draco;
        packed.quantize = !draco;
        warnings.clear();
        const fs::path file = dir / (draco ? "fox_draco.glb" : "fox_quantized.glb");
        REQUIRE_MESSAGE(write_asset(file.string(), all, packed, warnings, error), error);
        check_gltf_clean(file, kFoxWarnings);
    }
}

TEST_CASE("the Fox stays in its bind pose, and says why, until its skin and weights have arrived") {
    if (!have_sample(kFox)) return;
    const Asset in = load_asset(sample(kFox));
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    const fs::path dir = scratch_dir("skin_fox_lossy");

    // One SKIN packet lost: the skin is not complete, the mesh is shown unskinned.
    size_t first_skin = 0;
    while (first_skin < encoded.packets.size() && !is_packet_type(encoded.packets[first_skin], PacketType::Skin)) ++first_skin;
    REQUIRE(first_skin < encoded.packets.size());
    const Asset no_skin = decode_without(encoded, [&](size_t i) { return i == first_skin; });
    CHECK(no_skin.scene.skins.empty());
    CHECK(std::none_of(no_skin.scene.nodes.begin(), no_skin.scene.nodes.end(), [](const SceneNode& n) { return n.skin != kNone; }));
    CHECK(any_warning(no_skin, "without its skin"));
    CHECK(any_warning(no_skin, "of its 24 joints"));
    std::vector<std::string> warnings;
    REQUIRE_MESSAGE(write_asset((dir / "no_skin.glb").string(), no_skin, AssetWriteOptions{}, warnings, error), error);
    check_gltf_clean(dir / "no_skin.glb");

    // Every JOINT_WEIGHTS packet lost: no weights, no skin.
    const Asset no_weights =
        decode_without(encoded, [&](size_t i) { return is_packet_type(encoded.packets[i], PacketType::JointWeights); });
    CHECK(no_weights.scene.skins.empty());
    CHECK(any_warning(no_weights, "no weights of object 0 have arrived"));

    // Half of the JOINT_WEIGHTS packets and half of the points lost: the Fox is skinned already, each
    // vertex with the weights of the nearest point whose record arrived; the file is valid.
    size_t k = 0;
    const Asset half = decode_without(encoded, [&](size_t i) {
        const bool detail = is_packet_type(encoded.packets[i], PacketType::JointWeights) || is_packet_type(encoded.packets[i], PacketType::Points) || is_packet_type(encoded.packets[i], PacketType::MappedPoints);
        return detail && (k++ % 2 == 1);
    });
    REQUIRE(half.scene.skins.size() == 1);
    REQUIRE(half.weights.size() == 1);
    CHECK(half.weights[0].joints.size() == half.objects[0].positions.size());
    warnings.clear();
    REQUIRE_MESSAGE(write_asset((dir / "half.glb").string(), half, AssetWriteOptions{}, warnings, error), error);
    check_gltf_clean(dir / "half.glb", kFoxWarnings);
}

TEST_CASE("a mesh shown by a skinned node and by a node without a skin is written unskinned, with a warning") {
    // A mesh shown by a skinned node and by a node without a skin: one glTF mesh cannot be both, so
    // the writer writes it unskinned and says so.
    if (!have_sample(kFox)) return;
    Asset in = load_asset(sample(kFox));
    size_t skinned = 0;
    while (skinned < in.scene.nodes.size() && in.scene.nodes[skinned].skin == kNone) ++skinned;
    REQUIRE(skinned < in.scene.nodes.size());
    SceneNode twin = in.scene.nodes[skinned];
    twin.index = uint16_t(in.scene.nodes.size());
    twin.parent = kNone;
    twin.skin = kNone;
    twin.name = "twin";
    in.scene.nodes.push_back(twin);
    const fs::path dir = scratch_dir("skin_twin");
    std::vector<std::string> warnings;
    std::string error;
    REQUIRE_MESSAGE(write_asset((dir / "twin.glb").string(), in, AssetWriteOptions{}, warnings, error), error);
    CHECK(std::any_of(warnings.begin(), warnings.end(), [](const std::string& w) {
        return w.find("shown both by skinned nodes and by nodes without a skin") != std::string::npos;
    }));
    check_gltf_clean(dir / "twin.glb");
}

TEST_CASE("a receiver waiting for the Fox is not done before its last SKIN and JOINT_WEIGHTS packets (or animation keys)") {
    if (!have_sample(kFox)) return;
    const Asset in = load_asset(sample(kFox));
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(in, coarse_options(), 1, true, encoded, error), error);
    // Every packet but one of a kind, then that one: complete only with it.
    for (PacketType held_back : {PacketType::Skin, PacketType::JointWeights, PacketType::Animation})
        check_complete_only_with_last(encoded.packets, held_back);
}

TEST_CASE("a vertex with more than four influences (JOINTS_1 / WEIGHTS_1) keeps its four largest, with a warning counting them") {
    if (!have_sample(kFox)) return;
    const Asset plain = load_asset(sample(kFox));
    REQUIRE(plain.weights.size() == 1);
    const size_t n = plain.weights[0].joints.size();
    size_t full = 0;  // vertices whose four JOINTS_0 slots all have a weight
    for (size_t v = 0; v < n; ++v) full += influences(plain.weights[0], v).size() == 4;
    REQUIRE(full > 0);

    // The Fox with a second set giving every vertex joint 5 at weight 1 (as large as any weight).
    const fs::path dir = scratch_dir("fox_joints_1");
    for (const char* file : {"Fox.bin", "Texture.png"})
        if (!fs::exists(dir / file)) fs::copy_file(shared_samples() / "gltf/Fox" / file, dir / file);
    auto j = nlohmann::json::parse(read_bytes(shared_samples() / kFox));
    std::vector<uint8_t> data;
    for (size_t v = 0; v < n; ++v)
        for (uint16_t x : {uint16_t(5), uint16_t(0), uint16_t(0), uint16_t(0)}) data.push_back(uint8_t(x)), data.push_back(0);
    const size_t weights_at = data.size();
    for (size_t v = 0; v < n; ++v)
        for (float x : {1.0f, 0.0f, 0.0f, 0.0f}) {
            uint8_t b[4];
            std::memcpy(b, &x, 4);
            data.insert(data.end(), b, b + 4);
        }
    const size_t buffer = j["buffers"].size(), views = j["bufferViews"].size(), accessors = j["accessors"].size();
    j["buffers"].push_back({{"byteLength", data.size()}, {"uri", "data:application/octet-stream;base64," + base64(data)}});
    j["bufferViews"].push_back({{"buffer", buffer}, {"byteOffset", 0}, {"byteLength", weights_at}});
    j["bufferViews"].push_back({{"buffer", buffer}, {"byteOffset", weights_at}, {"byteLength", data.size() - weights_at}});
    j["accessors"].push_back({{"bufferView", views}, {"componentType", 5123}, {"count", n}, {"type", "VEC4"}});
    j["accessors"].push_back({{"bufferView", views + 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC4"}});
    auto& attributes = j["meshes"][0]["primitives"][0]["attributes"];
    attributes["JOINTS_1"] = accessors;
    attributes["WEIGHTS_1"] = accessors + 1;
    std::ofstream(dir / "Fox8.gltf", std::ios::binary) << j.dump();

    const Asset eight = load_asset((dir / "Fox8.gltf").string());
    REQUIRE(eight.weights.size() == 1);
    REQUIRE(eight.weights[0].joints.size() == n);
    // Every vertex now has joint 5 at the largest weight; those that had four influences lost their
    // smallest, and the warning counts them (not JOINTS_1 as an attribute left out).
    size_t with_five = 0;
    for (size_t v = 0; v < n; ++v) {
        const auto got = influences(eight.weights[0], v);
        with_five += got.count(5) && got.at(5) >= 1.0f;
        CHECK(got.size() <= 4);
    }
    CHECK(with_five == n);
    CHECK(any_warning(eight, std::to_string(full) + " of " + std::to_string(n) +
                                 " vertices have more than four joint influences"));
    CHECK(std::count_if(eight.warnings.begin(), eight.warnings.end(), [](const std::string& w) {
              return w.find("more than four joint influences") != std::string::npos;
          }) == 1);  // once for the asset
    CHECK_FALSE(any_warning(eight, "JOINTS_1 not sent"));
    CHECK_FALSE(any_warning(eight, "vertex attribute(s)"));
}

TEST_CASE("--draco compresses a skinned mesh with its joints and weights, --meshopt keeps its positions float and its weights exact, and tracks with the same key times share one input") {
    std::vector<std::string> inputs = {(source_dir() / "samples" / "khronos" / "RiggedSimple" / "RiggedSimple.gltf").string(),
                                       (source_dir() / "samples" / "khronos" / "RiggedFigure" / "RiggedFigure.gltf").string()};
    if (have_sample("gltf/Fox/Fox.gltf")) inputs.push_back((shared_samples() / "gltf/Fox/Fox.gltf").string());
    const fs::path dir = scratch_dir("skin_draco");
    for (const std::string& input : inputs) {
        CAPTURE(input);
        const std::string stem = fs::path(input).stem().string();
        const fs::path draco = dir / (stem + "-draco.glb"), plain = dir / (stem + "-plain.glb"),
                       quantized = dir / (stem + "-quantized.glb");
        for (const auto& [out, flags] : {std::pair{draco, std::string("--draco")}, std::pair{plain, std::string("--plain")},
                                         std::pair{quantized, std::string("--meshopt")}}) {
            int status = 0;
            const std::string log = run_command(shell_quoted(ellicast_exe().string()) + " convert -q " + flags + " " +
                                                    shell_quoted(input) + " " + shell_quoted(out.string()) + " 2>&1",
                                                status);
            REQUIRE_MESSAGE(status == 0, log);
        }
        check_gltf_clean(draco, {"NODE_SKINNED_MESH_NON_ROOT"});
        const nlohmann::json doc = gltf_document(draco);
        size_t skinned = 0;
        for (const auto& mesh : doc["meshes"])
            for (const auto& prim : mesh["primitives"]) {
                if (!prim["attributes"].contains("JOINTS_0")) continue;
                ++skinned;
                const auto& ext = prim["extensions"]["KHR_draco_mesh_compression"]["attributes"];
                CHECK(ext.contains("JOINTS_0"));
                CHECK(ext.contains("WEIGHTS_0"));
                // A stream's weights are multiples of 1/255: normalized bytes, exactly.
                CHECK(doc["accessors"][prim["attributes"]["WEIGHTS_0"].get<size_t>()]["componentType"] == 5121);
            }
        CHECK(skinned > 0);
        // Read back, every object has the weights of the plain file, vertex by vertex (matched by position).
        const Asset a = load_asset(draco.string()), b = load_asset(plain.string());
        REQUIRE(a.objects.size() == b.objects.size());
        REQUIRE(a.weights.size() == b.weights.size());
        for (size_t o = 0; o < a.objects.size(); ++o) {
            if (b.weights[o].empty()) continue;
            REQUIRE(a.weights[o].joints.size() == a.objects[o].positions.size());
            std::map<std::array<float, 3>, std::map<uint16_t, float>> want;
            for (size_t v = 0; v < b.objects[o].positions.size(); ++v) want[b.objects[o].positions[v]] = influences(b.weights[o], v);
            size_t matched = 0;
            for (size_t v = 0; v < a.objects[o].positions.size(); ++v) {
                // Draco quantizes positions: the nearest plain vertex.
                const auto& p = a.objects[o].positions[v];
                double best = INFINITY;
                const std::map<uint16_t, float>* w = nullptr;
                for (const auto& [q, inf] : want) {
                    const double d = std::hypot(double(p[0]) - q[0], double(p[1]) - q[1], double(p[2]) - q[2]);
                    if (d < best) best = d, w = &inf;
                }
                const auto got = influences(a.weights[o], v);
                bool same = w && got.size() == w->size();
                for (const auto& [joint, weight] : got) same = same && w->count(joint) && std::abs(w->at(joint) - weight) < 1e-6f;
                matched += same;
            }
            CHECK(matched >= a.objects[o].positions.size() * 95 / 100);  // vertices Draco moved onto a neighbour aside
        }
        // --meshopt (and --quantize under it): a skinned mesh keeps float positions (no dequantizing node
        // under a skeleton), its weights as exact normalized bytes, the same influences per vertex.
        check_gltf_clean(quantized, {"NODE_SKINNED_MESH_NON_ROOT"});
        const nlohmann::json qdoc = gltf_document(quantized);
        for (const auto& mesh : qdoc["meshes"])
            for (const auto& prim : mesh["primitives"]) {
                if (!prim["attributes"].contains("JOINTS_0")) continue;
                CHECK(qdoc["accessors"][prim["attributes"]["POSITION"].get<size_t>()]["componentType"] == 5126);
                CHECK(qdoc["accessors"][prim["attributes"]["WEIGHTS_0"].get<size_t>()]["componentType"] == 5121);
            }
        const Asset q = load_asset(quantized.string());
        for (size_t o = 0; o < q.objects.size() && o < b.objects.size(); ++o) {
            if (b.weights[o].empty()) continue;
            std::map<std::array<float, 3>, std::map<uint16_t, float>> want;
            for (size_t v = 0; v < b.objects[o].positions.size(); ++v) want[b.objects[o].positions[v]] = influences(b.weights[o], v);
            size_t same = 0;
            for (size_t v = 0; v < q.objects[o].positions.size(); ++v) {
                const auto it = want.find(q.objects[o].positions[v]);
                if (it == want.end()) continue;
                const auto got = influences(q.weights[o], v);
                bool equal = got.size() == it->second.size();
                for (const auto& [joint, weight] : got)
                    equal = equal && it->second.count(joint) && std::abs(it->second.at(joint) - weight) < 1e-6f;
                same += equal;
            }
            CHECK(same == q.objects[o].positions.size());
        }
        // Rotation keys (LINEAR or STEP) as normalized int16 there, within 1.6e-5 a component of the plain file's.
        for (const auto& animation : qdoc.value("animations", nlohmann::json::array()))
            for (const auto& channel : animation["channels"]) {
                if (channel["target"]["path"] != "rotation") continue;
                const auto& sampler = animation["samplers"][channel["sampler"].get<size_t>()];
                if (sampler.value("interpolation", "LINEAR") == "CUBICSPLINE") continue;
                const auto& output = qdoc["accessors"][sampler["output"].get<size_t>()];
                CHECK(output["componentType"] == 5122);
                CHECK(output["normalized"] == true);
            }
        REQUIRE(q.scene.animations.size() == b.scene.animations.size());
        for (size_t a = 0; a < b.scene.animations.size(); ++a) {
            REQUIRE(q.scene.animations[a].tracks.size() == b.scene.animations[a].tracks.size());
            for (size_t t = 0; t < b.scene.animations[a].tracks.size(); ++t) {
                const auto &x = q.scene.animations[a].tracks[t].values, &y = b.scene.animations[a].tracks[t].values;
                REQUIRE(x.size() == y.size());
                float worst = 0;
                for (size_t k = 0; k < x.size(); ++k) worst = std::max(worst, std::abs(x[k] - y[k]));
                CHECK(worst <= 2e-5f);
            }
        }
        // One input accessor per list of key times.
        std::set<size_t> inputs_used;
        std::set<std::vector<float>> times;
        for (const auto& animation : doc.value("animations", nlohmann::json::array()))
            for (const auto& sampler : animation["samplers"]) inputs_used.insert(sampler["input"].get<size_t>());
        for (const auto& animation : b.scene.animations)
            for (const auto& track : animation.tracks) times.insert(track.times);
        CHECK(inputs_used.size() == times.size());
    }
}

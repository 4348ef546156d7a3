// A catalogue converted as a user converts it (`ellicast convert IN OUT.glb`): every glTF sample here
// (the shared samples, the Khronos samples in samples/khronos, the lightmapped box in samples/multiuv) comes back with the same scene, feature
// by feature — nodes and their names, cameras and lights on their nodes, materials with their
// extensions and texture slots, attributes, morph targets, animation channels, skins, extras,
// extensions used and required — or with a warning that names what it lost: no silent loss. And the
// output is valid glTF with no validator warning the input does not have.
#include "support.h"

#include <fstream>
#include <set>
#include <sstream>

using namespace ellicast::test;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// One feature of a scene, and the word a warning about its loss must contain.
struct Feature {
    std::string what;  // unique description
    std::string word;  // e.g. "TEXCOORD_1", "KHR_materials_sheen", "camera", a node's name
    bool operator<(const Feature& o) const { return what < o.what; }
};

std::string name_or(const json& element, const std::string& fallback) {
    return element.contains("name") && element["name"].is_string() ? element["name"].get<std::string>() : fallback;
}

// The features of the default scene of `doc` (nodes reachable from it; the other tables whole).
std::set<Feature> features(const json& doc) {
    std::set<Feature> out;
    auto add = [&](const std::string& what, const std::string& word) { out.insert({what, word}); };
    const json nodes = doc.value("nodes", json::array());
    const json scenes = doc.value("scenes", json::array());
    std::vector<int> stack;
    if (!scenes.empty()) {
        const size_t s = doc.value("scene", 0);
        for (const auto& n : scenes.at(s < scenes.size() ? s : 0).value("nodes", json::array())) stack.push_back(n.get<int>());
    } else {
        for (size_t i = 0; i < nodes.size(); ++i) stack.push_back(int(i));
    }
    std::set<int> reached;
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        if (i < 0 || size_t(i) >= nodes.size() || !reached.insert(i).second) continue;
        const json& n = nodes[size_t(i)];
        for (const auto& c : n.value("children", json::array())) stack.push_back(c.get<int>());
        const std::string name = name_or(n, "");
        if (!name.empty()) add("node " + name, name);
        if (n.contains("camera")) add("a camera on node " + name, "camera");
        if (n.contains("extensions") && n["extensions"].contains("KHR_lights_punctual")) add("a light on node " + name, "light");
        if (n.contains("extras")) add("extras of node " + name + ": " + n["extras"].dump(), "extras");
    }
    for (const auto& c : doc.value("cameras", json::array())) add("camera " + c.value("type", "") + " " + name_or(c, ""), "camera");
    if (doc.contains("extensions") && doc["extensions"].contains("KHR_lights_punctual"))
        for (const auto& l : doc["extensions"]["KHR_lights_punctual"].value("lights", json::array()))
            add("light " + l.value("type", "") + " " + name_or(l, ""), "light");
    static const char* slots[] = {"baseColorTexture", "metallicRoughnessTexture", "normalTexture", "occlusionTexture", "emissiveTexture"};
    for (const auto& m : doc.value("materials", json::array())) {
        const std::string name = name_or(m, "?");
        add("material " + name, name);
        const json extensions = m.value("extensions", json::object());  // items() of a temporary would dangle
        for (const auto& [ext, value] : extensions.items()) add("material " + name + " " + ext, ext);
        const json pbr = m.value("pbrMetallicRoughness", json::object());
        for (const char* slot : slots) {
            const json info = pbr.contains(slot) ? pbr[slot] : m.value(slot, json());
            if (info.is_null()) continue;
            add("material " + name + " " + slot + " on TEXCOORD_" + std::to_string(info.value("texCoord", 0)), slot);
            const json info_extensions = info.value("extensions", json::object());
            for (const auto& [ext, value] : info_extensions.items()) add("material " + name + " " + slot + " " + ext, ext);
        }
        if (m.contains("extras")) add("extras of material " + name, "extras");
    }
    for (const auto& m : doc.value("meshes", json::array())) {
        const std::string name = name_or(m, "?");
        for (const auto& p : m.value("primitives", json::array())) {
            const json attributes = p.value("attributes", json::object());
            for (const auto& [attribute, accessor] : attributes.items()) add("mesh " + name + " " + attribute, attribute);
            if (p.contains("targets")) add("mesh " + name + " " + std::to_string(p["targets"].size()) + " morph targets", "target");
        }
        if (m.contains("extras")) add("extras of mesh " + name + ": " + m["extras"].dump(), "extras");
    }
    for (const auto& a : doc.value("animations", json::array()))
        for (const auto& c : a.value("channels", json::array())) {
            const json target = c.value("target", json::object());
            const int node = target.value("node", -1);
            const std::string on = node >= 0 && size_t(node) < nodes.size() ? name_or(nodes[size_t(node)], std::to_string(node)) : "-";
            add("animation " + name_or(a, "") + " " + target.value("path", "") + " of " + on, "animation");
        }
    for (const auto& s : doc.value("skins", json::array()))
        add("skin " + name_or(s, "") + " of " + std::to_string(s.value("joints", json::array()).size()) + " joints", "skin");
    // How the geometry is stored (Draco, quantized, meshopt) is not a feature of the scene (as in bench/corpus.py).
    auto storage = [](const std::string& e) {
        return e == "KHR_draco_mesh_compression" || e == "KHR_mesh_quantization" || e == "EXT_meshopt_compression";
    };
    for (const auto& e : doc.value("extensionsUsed", json::array()))
        if (!storage(e.get<std::string>())) add("uses " + e.get<std::string>(), e.get<std::string>());
    for (const auto& e : doc.value("extensionsRequired", json::array()))
        if (!storage(e.get<std::string>())) add("requires " + e.get<std::string>(), e.get<std::string>());
    if (doc.contains("asset") && doc["asset"].contains("extras")) add("extras of the asset", "extras");
    return out;
}

// Every .gltf and .glb under `folder`, sorted.
std::vector<fs::path> gltf_files(const fs::path& folder) {
    std::vector<fs::path> out;
    if (!fs::exists(folder)) return out;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) out.push_back(entry.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST_CASE("every glTF sample converts with its scene feature by feature, or a warning naming each loss") {
    std::vector<fs::path> assets = gltf_files(source_dir() / "samples" / "khronos");
    for (const fs::path& p : gltf_files(source_dir() / "samples" / "multiuv")) assets.push_back(p);  // TEXCOORD_1
    if (have_sample("gltf")) {
        const std::vector<fs::path> shared = gltf_files(shared_samples() / "gltf");
        assets.insert(assets.end(), shared.begin(), shared.end());
    }
    REQUIRE(assets.size() >= 7);
    const fs::path dir = scratch_dir("catalogue_features");
    size_t compared = 0, kept = 0;
    for (const fs::path& input : assets) {
        CAPTURE(input.string());
        const fs::path output = dir / (input.stem().string() + ".glb");
        int status = 0;
        const std::string log = run_command(shell_quoted(ellicast_exe().string()) + " convert -q " + shell_quoted(input.string()) +
                                                " " + shell_quoted(output.string()),
                                            status);
        REQUIRE_MESSAGE(status == 0, log);
        std::vector<std::string> warnings;
        std::istringstream lines(log);
        for (std::string line; std::getline(lines, line);)
            if (line.rfind("ellicast: warning: ", 0) == 0) warnings.push_back(line);
        const std::set<Feature> in = features(gltf_document(input)), out = features(gltf_document(output));
        for (const Feature& f : in) {
            if (out.count(f)) {
                ++kept;
                continue;
            }
            const bool named = std::any_of(warnings.begin(), warnings.end(),
                                           [&](const std::string& w) { return w.find(f.word) != std::string::npos; });
            CHECK_MESSAGE(named, "lost without a warning naming " << f.word << ": " << f.what << "\n" << log);
        }
        // What the input's own validator warnings are, the output may keep (a faithful copy keeps a
        // source's quirks); nothing else.
        int errors = 0;
        std::string report;
        std::vector<std::string> allowed;
        if (validate_gltf(input, errors, report)) allowed = json::parse(report).value("warnings", std::vector<std::string>{});
        check_gltf_clean(output, allowed);
        ++compared;
    }
    MESSAGE(compared << " assets compared, " << kept << " features kept");
    CHECK(compared == assets.size());
}

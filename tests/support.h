// Helpers shared by the tests: where the sample assets are, and skipping when they are absent.
#pragma once

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <sys/wait.h>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <vector>
#include <string>

namespace ellicast::test {

// ../shared/samples next to the checkout; a user's checkout may not have it. The environment variable
// ELLICAST_SHARED_SAMPLES overrides it at run time: CI runs the suite once more with it naming a folder
// that does not exist, as a clean clone without ../shared would.
inline std::filesystem::path shared_samples() {
    if (const char* dir = std::getenv("ELLICAST_SHARED_SAMPLES"); dir && *dir) return dir;
    return ELLICAST_SHARED_SAMPLES;
}
inline std::filesystem::path source_dir() { return ELLICAST_SOURCE_DIR; }
inline std::filesystem::path binary_dir() { return ELLICAST_BINARY_DIR; }
inline std::filesystem::path ellicast_exe() { return binary_dir() / "ellicast"; }

// True when the shared sample exists; otherwise prints why the test is skipped.
inline bool have_sample(const std::string& relative) {
    if (std::filesystem::exists(shared_samples() / relative)) return true;
    MESSAGE("skipped: " << (shared_samples() / relative).string()
                        << " is absent (the tests read real assets from ../shared/samples)");
    return false;
}

// `text` in single quotes for a shell command (built with +=: GCC 12 warns falsely, -Wrestrict, on
// "'" + std::string).
inline std::string shell_quoted(const std::string& text) {
    std::string quoted = "'";
    quoted += text;
    quoted += "'";
    return quoted;
}

// A fresh empty scratch directory for one test.
inline std::filesystem::path scratch_dir(const std::string& name) {
    auto dir = binary_dir() / "test-scratch" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A copy of the .gltf `source` in `dir` with `edit` made to its JSON, named `prefix` + its name, with
// the files beside it (buffers, images) copied too; its path.
inline std::filesystem::path edited_gltf(const std::filesystem::path& source, const std::filesystem::path& dir,
                                         const std::function<void(nlohmann::json&)>& edit, const std::string& prefix = "Edited_") {
    namespace fs = std::filesystem;
    for (const auto& entry : fs::directory_iterator(source.parent_path()))
        if (entry.path() != source) fs::copy_file(entry.path(), dir / entry.path().filename(), fs::copy_options::overwrite_existing);
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(source));
    edit(doc);
    const fs::path out = dir / (prefix + source.filename().string());
    std::ofstream(out) << doc.dump(1);
    return out;
}

// The npm packages the glTF checks use (scripts/setup.sh installs them into .cache/node).
inline std::filesystem::path node_modules() { return source_dir() / ".cache" / "node" / "node_modules"; }

// True when node and the npm package `package` are installed; otherwise prints why the test is skipped.
inline bool have_node_package(const std::string& package) {
    if (!std::filesystem::exists(node_modules() / package)) {
        MESSAGE("skipped: " << (node_modules() / package).string() << " is absent (run scripts/setup.sh)");
        return false;
    }
    if (std::system("command -v node > /dev/null 2>&1") != 0) {
        MESSAGE("skipped: node is not installed (run scripts/setup.sh)");
        return false;
    }
    return true;
}

// Runs a shell command and returns its standard output and error; `status` receives its exit status.
inline std::string run_command(const std::string& command, int& status) {
    std::string out;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) {
        status = -1;
        return out;
    }
    char buffer[4096];
    while (size_t n = fread(buffer, 1, sizeof buffer, pipe)) out.append(buffer, n);
    int rc = pclose(pipe);
    status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    return out;
}

// Runs the Khronos glTF-Validator (tests/gltf_validate.js) on `file`; false (with a message) when
// it is not installed. `errors` receives the number of errors, `report` the validator's summary.
inline bool validate_gltf(const std::filesystem::path& file, int& errors, std::string& report) {
    if (!have_node_package("gltf-validator")) return false;
    int status = 0;
    report = run_command("NODE_PATH='" + node_modules().string() + "' node '" +
                             (source_dir() / "tests" / "gltf_validate.js").string() + "' '" + file.string() + "'",
                         status);
    auto json = nlohmann::json::parse(report, nullptr, false);
    REQUIRE_MESSAGE(!json.is_discarded(), report);
    errors = json.value("numErrors", -1);
    return true;
}

// Checks that the validator finds neither an error nor a warning in `file` (skipped with a message
// when it is not installed), but for warnings whose code `allowed` names (ones the source asset has
// itself, such as NODE_SKINNED_MESH_NON_ROOT for a skinned node under a parent).
inline void check_gltf_clean(const std::filesystem::path& file, const std::vector<std::string>& allowed = {}) {
    int errors = -1;
    std::string report;
    if (!validate_gltf(file, errors, report)) return;
    CHECK_MESSAGE(errors == 0, report);
    size_t other = 0;
    for (const auto& code : nlohmann::json::parse(report).value("warnings", std::vector<std::string>{}))
        other += std::find(allowed.begin(), allowed.end(), code) == allowed.end();
    CHECK_MESSAGE(other == 0, report);
    CHECK_MESSAGE(nlohmann::json::parse(report).value("numWarnings", -1) >= 0, report);
}

// The bytes of a file (empty when it cannot be read).
inline std::vector<uint8_t> read_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// The JSON of a .gltf file, or of a .glb file's JSON chunk.
inline nlohmann::json gltf_document(const std::filesystem::path& path) {
    const std::vector<uint8_t> b = read_bytes(path);
    if (b.size() < 4 || !std::equal(b.begin(), b.begin() + 4, "glTF")) return nlohmann::json::parse(b.begin(), b.end());
    REQUIRE(b.size() >= 20);
    const uint32_t length = uint32_t(b[12]) | uint32_t(b[13]) << 8 | uint32_t(b[14]) << 16 | uint32_t(b[15]) << 24;
    REQUIRE(20 + size_t(length) <= b.size());
    return nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + length);
}

// `bytes` in base64 (RFC 4648, with padding): for data: URIs of test assets.
inline std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t n = uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                           (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        out += digits[n >> 18 & 63];
        out += digits[n >> 12 & 63];
        out += i + 1 < bytes.size() ? digits[n >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? digits[n & 63] : '=';
    }
    return out;
}

}  // namespace ellicast::test

// The conformance vectors of spec/vectors/: every .ellc decodes with the library to exactly the
// committed expected decode beside it (so any change of decoding behaviour breaks this test), every
// vector is described in spec/vectors/README.md, and `ellicast validate` accepts the valid and unusual
// sets and refuses every faulty vector.
#include "support.h"

#include "../spec/vectors/expected_decode.h"

#include <ellicast/format.h>

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace fs = std::filesystem;
using namespace ellicast;

namespace {

fs::path vectors_dir() { return test::source_dir() / "spec" / "vectors"; }

std::vector<fs::path> vectors_in(const std::string& set) {
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(vectors_dir() / set))
        if (entry.path().extension() == ".ellc") out.push_back(entry.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<uint8_t> read_bytes(const fs::path& path) {
    std::vector<uint8_t> bytes;
    std::string message;
    REQUIRE_MESSAGE(read_file(path.string(), bytes, message) == Error::Ok, message);
    return bytes;
}

nlohmann::json read_json(const fs::path& path) {
    std::ifstream in(path);
    REQUIRE_MESSAGE(in.good(), "missing expected decode " << path.string());
    return nlohmann::json::parse(in);
}

void check_set(const std::string& set, size_t at_least) {
    const auto files = vectors_in(set);
    CHECK(files.size() >= at_least);
    for (const auto& file : files) {
        auto expected = read_json(fs::path(file).replace_extension(".json"));
        auto actual = conformance::expected_decode(read_bytes(file));
        expected.erase("vector");
        std::vector<std::string> diffs;
        conformance::compare_json(expected, actual, set + "/" + file.stem().string(), diffs);
        INFO(file.string());
        for (const auto& d : diffs) MESSAGE(d);
        CHECK(diffs.empty());
    }
}

int run(const std::string& command) {
    int status = std::system((command + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("every valid conformance vector decodes to its committed expected decode") { check_set("valid", 5); }

TEST_CASE("every unusual conformance vector decodes to its committed expected decode") { check_set("unusual", 20); }

TEST_CASE("every faulty conformance vector is rejected exactly as its committed expected decode says") {
    check_set("faulty", 20);
}

TEST_CASE("the faulty vectors name the reason they must be rejected with") {
    // Pin the named reason of the vectors whose defect is a single rejection or damaged region.
    const std::vector<std::pair<std::string, std::string>> reasons = {
        {"bad_magic", "bad magic"},
        {"bad_crc", "bad checksum"},
        {"truncated_packet", "truncated"},
        {"wrong_major", "unsupported major version"},
        {"type_zero", "invalid type"},
        {"oversized_length", "oversized"},
        {"garbage_between_packets", "bad magic"},
        {"unknown_critical_type", "unknown critical type"},
        {"payload_length_inconsistent", "malformed payload"},
        {"index_out_of_range", "index out of range"},
        {"stream_info_bad_bits", "malformed payload"},
        {"stream_info_object_id", "malformed payload"},
        {"mixed_stream_ids", "stream mismatch"},
        {"contradicting_stream_info", "stream mismatch"},
        {"unknown_object", "unknown object"},
        {"truncated_container", "too short"},
        {"bad_signature", "bad container signature"},
        {"container_version_2", "unsupported container version"},
    };
    for (const auto& [name, reason] : reasons) {
        INFO(name);
        auto j = read_json(vectors_dir() / "faulty" / (name + ".json"));
        std::vector<std::string> found;
        if (!j["container_error"].is_null()) found.push_back(j["container_error"]);
        for (const auto& d : j["damaged"]) found.push_back(d["reason"]);
        for (const auto& r : j["rejections"]) found.push_back(r["reason"]);
        REQUIRE(found.size() >= 1);
        CHECK(std::all_of(found.begin(), found.end(), [&](const std::string& f) { return f == reason; }));
    }
}

TEST_CASE("an independent decoder written from the spec alone (spec/vectors/check_vectors.py) agrees with every vector") {
    if (std::system("python3 --version > /dev/null 2>&1") != 0) {
        MESSAGE("skipped: python3 is absent");
        return;
    }
    const std::string script = (vectors_dir() / "check_vectors.py").string();
    CHECK(run("python3 '" + script + "'") == 0);
}

TEST_CASE("a reordered and duplicated stream decodes to the same objects as the stream in order") {
    auto in_order = conformance::expected_decode(read_bytes(vectors_dir() / "valid" / "two_objects.ellc"));
    auto shuffled = conformance::expected_decode(read_bytes(vectors_dir() / "unusual" / "duplicated_reordered.ellc"));
    CHECK(in_order["objects"] == shuffled["objects"]);
    CHECK(in_order["stream_info"] == shuffled["stream_info"]);
    CHECK(shuffled["counters"]["duplicates"].get<int>() > 0);
}

TEST_CASE("every conformance vector is listed in spec/vectors/README.md") {
    std::ifstream in(vectors_dir() / "README.md");
    REQUIRE(in.good());
    std::stringstream text;
    text << in.rdbuf();
    for (const std::string set : {"valid", "unusual", "faulty"})
        for (const auto& file : vectors_in(set)) {
            std::string name = "`";
            name += file.stem().string();
            name += '`';
            INFO(set << "/" << file.filename().string());
            CHECK(text.str().find(name) != std::string::npos);
        }
}

#ifndef ELLICAST_FORMAT_TESTS_ONLY  // the format-only test executable has no ellicast binary
TEST_CASE("ellicast validate accepts every valid and unusual vector and refuses every faulty one") {
    const std::string exe = test::ellicast_exe().string();
    for (const std::string set : {"valid", "unusual"})
        for (const auto& file : vectors_in(set)) {
            INFO(file.string());
            CHECK(run("'" + exe + "' validate '" + file.string() + "'") == 0);
        }
    for (const auto& file : vectors_in("faulty")) {
        INFO(file.string());
        CHECK(run("'" + exe + "' validate '" + file.string() + "'") == 1);
    }
}
#endif

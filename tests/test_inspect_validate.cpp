// `ellicast inspect` and `ellicast validate` through the real binary: what they print for conforming,
// damaged and incomplete recordings, their exit codes, and their usage errors.
#include "support.h"

#include "ellicast/format.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

struct Result {
    int code = -1;
    std::string out, err;
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

Result run_ellicast(const std::string& args) {
    static int counter = 0;
    auto dir = ellicast::test::binary_dir() / "test-scratch" / "inspect_validate_runs";
    fs::create_directories(dir);
    // CTest runs test cases as parallel processes: name the files after the process and the call.
    const std::string tag = std::to_string(getpid()) + "-" + std::to_string(counter++);
    const auto out = dir / ("out-" + tag + ".txt");
    const auto err = dir / ("err-" + tag + ".txt");
    std::string cmd = "'";  // built with += : GCC 12 warns falsely (-Wrestrict) on "'" + std::string
    cmd += ellicast::test::ellicast_exe().string();
    cmd += "' " + args + " > '";
    cmd += out.string();
    cmd += "' 2> '";
    cmd += err.string();
    cmd += "'";
    int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(out);
    r.err = slurp(err);
    return r;
}

std::string vector_path(const std::string& name) {
    std::string quoted = "'";
    quoted += (ellicast::test::source_dir() / "spec" / "vectors" / (name + ".ellc")).string();
    quoted += "'";
    return quoted;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("validate exits 0 for a conforming recording and says what it holds") {
    Result r = run_ellicast("validate " + vector_path("valid/two_objects"));
    CHECK(r.code == 0);
    CHECK(contains(r.out, "conforms to ellicast format 1.0"));
    CHECK(contains(r.out, "2 objects, 16 ellipsoids, 100 points"));
    Result quiet = run_ellicast("validate -q " + vector_path("valid/two_objects"));
    CHECK(quiet.code == 0);
    CHECK(quiet.out.empty());
}

TEST_CASE("validate lists every violation with its byte offset and exits 1") {
    Result r = run_ellicast("validate " + vector_path("faulty/bad_crc"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "offset 368: 195 damaged bytes hold no valid packet (bad CRC-32C)"));
    CHECK(contains(r.out, "object 0: 19 of 40 points received; missing 0..20"));
    CHECK(contains(r.out, "does not conform: 2 violations"));

    r = run_ellicast("validate " + vector_path("faulty/incomplete"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "2 of 12 ellipsoids received; missing 0..9"));
    CHECK(contains(r.out, "21 of 40 points received; missing 21..39"));

    r = run_ellicast("validate " + vector_path("faulty/packet_over_declared_size"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "offset 112: ELLIPSOIDS packet of 192 bytes is larger than the declared packet size 128"));

    r = run_ellicast("validate " + vector_path("faulty/mixed_stream_ids"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "packets of 2 stream ids"));
    CHECK(contains(r.out, "offset 368: STREAM_INFO packet rejected"));

    r = run_ellicast("validate " + vector_path("faulty/no_stream_info"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "no valid STREAM_INFO"));
    CHECK(contains(r.out, "offset 12: ELLIPSOIDS packet of object 0 never got its STREAM_INFO entry"));

    r = run_ellicast("validate " + vector_path("faulty/bad_signature"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "offset 0: not a readable ellicast container"));
}

TEST_CASE("validate of several files fails if any one does") {
    Result r = run_ellicast("validate " + vector_path("valid/minimal") + " " + vector_path("faulty/truncated_packet"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "minimal.ellc: conforms"));
    CHECK(contains(r.out, "truncated_packet.ellc: offset 563: 90 damaged bytes"));
}

TEST_CASE("inspect summarizes stream info, packet types, objects and damage") {
    Result r = run_ellicast("inspect " + vector_path("faulty/bad_crc"));
    CHECK(r.code == 0);
    CHECK(contains(r.out, "container: version 1, 12-byte header, 4 intact packets, 1 damaged region"));
    CHECK(contains(r.out, "stream id: 0x0E11CA57"));
    CHECK(contains(r.out, "versions: 1.0 (4)"));
    CHECK(contains(r.out, "packet size 200"));
    CHECK(contains(r.out, "bits: position 14, normal 10, texcoord 12, colour 8"));
    CHECK(contains(r.out, "coverage target 0.95, seed 7, grid hint 64"));
    CHECK(contains(r.out, "ELLIPSOIDS"));
    CHECK(contains(r.out, "ellipsoids 12/12, points 19/40"));
    CHECK(contains(r.out, "missing points 0..20"));
    CHECK(contains(r.out, "offset 368, 195 bytes: bad CRC-32C"));
    CHECK(contains(r.out, "conforms: no"));

    r = run_ellicast("inspect --packets " + vector_path("unusual/minor_1_1"));
    CHECK(r.code == 0);
    CHECK(contains(r.out, "UNKNOWN(0xF0)"));
    CHECK(contains(r.out, "skipped"));
    CHECK(contains(r.out, "versions: 1.1 (4)"));
    CHECK(contains(r.out, "conforms: yes"));
}

TEST_CASE("inspect says of each object its exact layer's kind, triangles and carried vertices, and its normal entries") {
    Result r = run_ellicast("inspect " + vector_path("valid/exact_mesh"));
    REQUIRE(r.code == 0);
    CHECK_MESSAGE(contains(r.out, "exact layer: EXACT_MESH (format 1.11), 128 triangles, 33 vertices carried beside the "
                                  "points; 325/325 bytes, complete"),
                  r.out);
    r = run_ellicast("inspect " + vector_path("valid/exact_mesh_surface_normals"));
    REQUIRE(r.code == 0);
    CHECK_MESSAGE(contains(r.out, "surface normals (format 1.8): entries 36/36, complete"), r.out);
    r = run_ellicast("inspect --json " + vector_path("valid/exact_mesh_surface_normals"));
    REQUIRE(r.code == 0);
    CHECK(contains(r.out, "\"carried_vertices\": 20"));
    CHECK(contains(r.out, "\"packets\": \"EXACT_MESH\""));
}

TEST_CASE("inspect names a freshly encoded stream's repair packets as repair not needed, not as duplicates") {
    const auto dir = ellicast::test::scratch_dir("inspect_repair");
    const std::string stream = (dir / "trefoil.ellc").string();
    Result r = run_ellicast("encode -q '" + (ellicast::test::source_dir() / "samples" / "trefoil.obj").string() + "' -o '" +
                            stream + "' --repair 1");
    REQUIRE_MESSAGE(r.code == 0, r.err);
    r = run_ellicast("inspect '" + stream + "'");
    REQUIRE(r.code == 0);
    CHECK_MESSAGE(contains(r.out, " 0 duplicates, "), r.out);
    CHECK_MESSAGE(!contains(r.out, " 0 repair not needed"), r.out);
    CHECK(contains(r.out, "repair not needed (what they protect arrived whole)"));
    r = run_ellicast("inspect --json '" + stream + "'");
    REQUIRE(r.code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["counters"]["duplicates"] == 0);
    CHECK(j["counters"]["repair_not_needed"].get<int>() > 0);
    // What the receiver holds, against its byte budget (spec 11.2): the whole trefoil, well inside it.
    const auto held = j["memory"]["held"].get<uint64_t>(), taken = j["memory"]["bytes_taken"].get<uint64_t>();
    CHECK(held > 0);
    CHECK(taken == std::filesystem::file_size(stream) - 12);  // every packet, not the container header
    CHECK(j["memory"]["budget"].get<uint64_t>() == (64u << 20) + 8 * taken);
    CHECK(held < 4 * taken);
    // A repeat of a point packet is still a duplicate.
    r = run_ellicast("schedule '" + stream + "' -o '" + (dir / "cycle.ellc").string() + "'");
    REQUIRE_MESSAGE(r.code == 0, r.err);
    r = run_ellicast("inspect --json '" + (dir / "cycle.ellc").string() + "'");
    REQUIRE(r.code == 0);
    CHECK(nlohmann::json::parse(r.out)["counters"]["duplicates"].get<int>() > 0);
}

TEST_CASE("validate --received tells a lossy recording (conforming but incomplete) from a broken one (offsets)") {
    const auto dir = ellicast::test::scratch_dir("validate_received");
    const std::string stream = (dir / "trefoil.ellc").string(), lossy = (dir / "lossy.ellc").string();
    Result r = run_ellicast("encode -q '" + (ellicast::test::source_dir() / "samples" / "trefoil.obj").string() + "' -o '" +
                            stream + "'");
    REQUIRE_MESSAGE(r.code == 0, r.err);
    r = run_ellicast("simulate '" + stream + "' -o '" + lossy + "' --loss 0.5 --seed 3");
    REQUIRE_MESSAGE(r.code == 0, r.err);
    // Plain validate: a lossy recording does not conform, but it says every violation is missing data.
    r = run_ellicast("validate '" + lossy + "'");
    CHECK(r.code == 1);
    CHECK(contains(r.out, "points received; missing"));
    CHECK(contains(r.out, "every one of them missing data"));
    // --received: conforming but incomplete, what is missing listed.
    r = run_ellicast("validate --received '" + lossy + "'");
    CHECK_MESSAGE(r.code == 0, r.out);
    CHECK(contains(r.out, "conforming but incomplete"));
    CHECK(contains(r.out, "missing: object 0:"));
    r = run_ellicast("validate --received -q '" + lossy + "'");
    CHECK(r.code == 0);
    CHECK(r.out.empty());
    // A damaged byte in what arrived still fails, with its offset; the missing parts are counted, not listed.
    std::vector<uint8_t> bytes = ellicast::test::read_bytes(lossy);
    REQUIRE(bytes.size() > 3000);
    bytes[3000] ^= 0xFF;
    const std::string damaged = (dir / "damaged.ellc").string();
    std::string message;
    REQUIRE(ellicast::write_file(damaged, bytes, message) == ellicast::Error::Ok);
    r = run_ellicast("validate --received '" + damaged + "'");
    CHECK(r.code == 1);
    CHECK(contains(r.out, "damaged bytes hold no valid packet"));
    CHECK(contains(r.out, "offset "));
    CHECK(contains(r.out, "in what arrived"));
    CHECK(!contains(r.out, "points received; missing"));
    // A complete stream passes either way.
    CHECK(run_ellicast("validate --received -q '" + stream + "'").code == 0);
}

TEST_CASE("inspect --json gives the same summary as machine-readable JSON") {
    Result r = run_ellicast("inspect --json " + vector_path("unusual/split_stream_info"));
    REQUIRE(r.code == 0);
    auto j = nlohmann::json::parse(r.out);
    CHECK(j["stream_info"]["parts"] == 3);
    CHECK(j["stream_info"]["object_count"] == 60);
    CHECK(j["objects"].size() == 60);
    CHECK(j["objects"][59]["complete"] == true);
    CHECK(j["conforms"] == true);
    CHECK(j["damaged"].empty());
    CHECK(j["stream_id"] == 0x0E11CA57);

    r = run_ellicast("inspect --json " + vector_path("faulty/index_out_of_range"));
    REQUIRE(r.code == 0);
    j = nlohmann::json::parse(r.out);
    REQUIRE(j["rejected"].size() == 1);
    CHECK(j["rejected"][0]["offset"] == 368);
    CHECK(j["rejected"][0]["reason"] == "index beyond the declared count");
    CHECK(j["objects"][0]["missing_points"] == "0..20");
    CHECK(j["conforms"] == false);
}

TEST_CASE("inspect and validate refuse bad usage and unreadable files with a clear message") {
    Result r = run_ellicast("inspect");
    CHECK(r.code == 2);
    CHECK(contains(r.err, "file"));
    r = run_ellicast("validate");
    CHECK(r.code == 2);
    r = run_ellicast("inspect --frobnicate " + vector_path("valid/minimal"));
    CHECK(r.code == 2);
    r = run_ellicast("inspect /nonexistent/stream.ellc");
    CHECK(r.code == 3);
    CHECK(contains(r.err, "ellicast: error: /nonexistent/stream.ellc: cannot open"));
    r = run_ellicast("validate /nonexistent/stream.ellc");
    CHECK(r.code == 3);
    CHECK(contains(r.err, "/nonexistent/stream.ellc"));
    r = run_ellicast("inspect " + vector_path("faulty/truncated_container"));
    CHECK(r.code == 1);
    CHECK(contains(r.out, "container: unreadable"));
}

TEST_CASE("validate refuses a recording whose texture is not a file of its image_type (spec 15.3, 15.4)") {
    // The JPEG scene vector conforms; the same packets with every fragment's image_type changed to
    // PNG (checksums redone, so the receiver accepts them all) do not.
    Result r = run_ellicast("validate " + vector_path("valid/scene_jpeg"));
    CHECK(r.code == 0);
    const fs::path source = ellicast::test::source_dir() / "spec" / "vectors" / "valid" / "scene_jpeg.ellc";
    std::ifstream in(source, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const ellicast::ContainerContents contents = ellicast::read_container(bytes);
    REQUIRE(contents.header_error == ellicast::Error::Ok);
    std::vector<std::vector<uint8_t>> packets;
    int relabelled = 0;
    for (const auto& p : contents.packets) {
        if (ellicast::PacketType(p.view.header.type) != ellicast::PacketType::TextureFragment) {
            packets.emplace_back(bytes.begin() + std::ptrdiff_t(p.offset),
                                 bytes.begin() + std::ptrdiff_t(p.offset + p.view.size));
            continue;
        }
        ellicast::TextureFragment f;
        REQUIRE(ellicast::decode_texture_fragment_payload(p.view.payload, f) == ellicast::Error::Ok);
        REQUIRE(f.info.image_type == ellicast::ImageType::Jpeg);
        f.info.image_type = ellicast::ImageType::Png;
        packets.push_back(ellicast::write_packet(p.view.header, ellicast::encode_texture_fragment_payload(f)));
        ++relabelled;
    }
    REQUIRE(relabelled > 0);
    const auto dir = ellicast::test::binary_dir() / "test-scratch" / "inspect_validate_image_type";
    fs::create_directories(dir);
    const fs::path file = dir / "jpeg_called_png.ellc";
    {
        const std::vector<uint8_t> out = ellicast::write_container(packets);
        std::ofstream o(file, std::ios::binary);
        o.write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
    }
    r = run_ellicast("validate '" + file.string() + "'");
    CHECK(r.code == 1);
    CHECK(contains(r.out, "texture 0: image_type says PNG but the image is a JPEG file"));
    CHECK(contains(r.out, "texture 1: image_type says PNG but the image is a JPEG file"));
    CHECK(contains(r.out, "does not conform: 2 violations"));
}

// Nothing a user gave is overwritten or lost: outputs never land on an input or on a file an input
// names, temporaries are private (unpredictable names, created exclusively, no symlink followed),
// and a symlink planted at an output's path is replaced, its target left alone.
#include "ellicast/format.h"
#include "support.h"

#include <doctest/doctest.h>

#include <fstream>

using namespace ellicast;
using namespace ellicast::test;
namespace fs = std::filesystem;

namespace {

std::string text_of(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

int run(const std::string& args, std::string* log = nullptr) {
    int status = 0;
    std::string command = "'";
    command += ellicast_exe().string();
    command += "' ";
    command += args;
    const std::string out = run_command(command, status);
    if (log) *log = out;
    return status;
}

}  // namespace

TEST_CASE("outputs never overwrite an input, its buffers or images, and a planted symlink or temporary is not followed") {
    if (!have_sample("gltf/Duck/Duck.gltf")) return;
    const fs::path dir = scratch_dir("output_safety");
    for (const char* f : {"Duck.gltf", "Duck0.bin", "DuckCM.png"}) fs::copy_file(shared_samples() / "gltf/Duck" / f, dir / f);
    const std::string buffer = text_of(dir / "Duck0.bin");
    std::string d = "'";
    d += dir.string();
    d += '/';
    std::string log;

    // encode model.gltf -o model's own buffer: refused, the buffer intact.
    CHECK(run("encode -q " + d + "Duck.gltf' -o " + d + "Duck0.bin'", &log) == 2);
    CHECK_MESSAGE(log.find("a file of the input") != std::string::npos, log);
    CHECK(text_of(dir / "Duck0.bin") == buffer);

    REQUIRE(run("encode -q " + d + "Duck.gltf' -o " + d + "duck.ellc'") == 0);
    const std::string stream = text_of(dir / "duck.ellc");
    // decode X.bin -o X.gltf would write the .gltf's buffer onto the input: refused.
    fs::copy_file(dir / "duck.ellc", dir / "x.bin");
    CHECK(run("decode -q " + d + "x.bin' -o " + d + "x.gltf'") == 2);
    CHECK(text_of(dir / "x.bin") == stream);
    // Inputs named like the old temporaries are kept: decode X.gltf.tmp -o X.gltf, X.glb.partial -o X.glb.
    fs::copy_file(dir / "duck.ellc", dir / "y.gltf.tmp");
    fs::copy_file(dir / "duck.ellc", dir / "z.glb.partial");
    CHECK(run("decode -q " + d + "y.gltf.tmp' -o " + d + "y.gltf' --grid 32") == 0);
    CHECK(run("decode -q " + d + "z.glb.partial' -o " + d + "z.glb' --grid 32") == 0);
    CHECK(text_of(dir / "y.gltf.tmp") == stream);
    CHECK(text_of(dir / "z.glb.partial") == stream);
    CHECK(fs::file_size(dir / "z.glb") > 0);

    // A symlink planted at the output, or at the old predictable temporary name, is not followed.
    std::ofstream(dir / "victim") << "keep";
    std::ofstream(dir / "victim2") << "keep";
    fs::create_symlink(dir / "victim", dir / "out.glb");
    fs::create_symlink(dir / "victim2", dir / "out2.glb.partial");
    CHECK(run("decode -q " + d + "duck.ellc' -o " + d + "out.glb' --grid 32") == 0);
    CHECK(run("decode -q " + d + "duck.ellc' -o " + d + "out2.glb' --grid 32") == 0);
    CHECK(text_of(dir / "victim") == "keep");
    CHECK(text_of(dir / "victim2") == "keep");
    CHECK_FALSE(fs::is_symlink(dir / "out.glb"));
    CHECK(fs::file_size(dir / "out.glb") > 1000);

    // write_file leaves no temporary behind, and two writes never share one.
    std::string message;
    const std::vector<uint8_t> bytes = {1, 2, 3};
    REQUIRE(write_file((dir / "plain.bin").string(), bytes, message) == Error::Ok);
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        const bool ours = name == "z.glb.partial" || name == "out2.glb.partial";
        CHECK_MESSAGE((ours || name.find(".partial") == std::string::npos), name);
    }
    CHECK(write_file((dir / "no-such-folder" / "x.bin").string(), bytes, message) == Error::IoError);
    CHECK(message.find("no-such-folder") != std::string::npos);
}

TEST_CASE("convert DIR OUTDIR converts a catalogue one process an asset: a broken asset fails alone, the table says so") {
    const fs::path dir = scratch_dir("catalogue");
    const fs::path in = dir / "assets", out = dir / "converted";
    fs::create_directories(in / "nested");
    for (const char* name : {"Cameras", "SimpleMorph"})
        fs::copy(source_dir() / "samples" / "khronos" / name, in / (name == std::string("Cameras") ? "" : "nested") / name,
                 fs::copy_options::recursive);
    std::ofstream(in / "broken.glb", std::ios::binary) << "glTF\x02\x00\x00\x00 not really";
    std::ofstream(in / "notes.txt") << "not an asset";
    // A validator that accepts everything but the morph asset.
    const fs::path validator = dir / "validator.sh";
    std::ofstream(validator) << "#!/bin/sh\ncase \"$1\" in *Morph*) echo '{\"numErrors\": 2, \"numWarnings\": 1}';; "
                                "*) echo '{\"numErrors\": 0, \"numWarnings\": 3}';; esac\n";
    fs::permissions(validator, fs::perms::owner_all);
    std::string log;
    const int status = run("convert " + shell_quoted(in.string()) + " " + shell_quoted(out.string()) +
                               " -q -j 2 --validator " + shell_quoted(validator.string()),
                           &log);
    INFO(log);
    CHECK(status == 1);  // one failure and one validator rejection
    CHECK(fs::exists(out / "Cameras" / "Cameras.gltf"));
    CHECK(fs::exists(out / "nested" / "SimpleMorph" / "SimpleMorph.gltf"));
    CHECK(fs::exists(out / "broken.glb.log"));
    CHECK_FALSE(fs::exists(out / "broken.glb"));
    const std::string table = text_of(out / "catalogue.md");
    CHECK(table.find("| Cameras/Cameras.gltf | ok |") != std::string::npos);
    CHECK(table.find("0 errors, 3 warnings") != std::string::npos);
    CHECK(table.find("2 errors, 1 warnings") != std::string::npos);
    CHECK(table.find("| broken.glb | failed: ") != std::string::npos);
    CHECK(table.find("notes.txt") == std::string::npos);
    CHECK(log.find("3 assets: 2 converted, 1 failed, 1 rejected by the validator") != std::string::npos);
    // The output folder inside the input folder is left out of the next run's assets.
    const fs::path inside = in / "converted";
    CHECK(run("convert " + shell_quoted(in.string()) + " " + shell_quoted(inside.string()) + " -q", &log) == 1);
    CHECK(run("convert " + shell_quoted(in.string()) + " " + shell_quoted(inside.string()) + " -q", &log) == 1);
    CHECK(log.find("3 assets:") != std::string::npos);
    // Never into the input folder itself or a folder that holds it; --jobs only for folders.
    CHECK(run("convert " + shell_quoted(in.string()) + " " + shell_quoted(in.string()), &log) == 2);
    CHECK(log.find("outputs could replace inputs") != std::string::npos);
    CHECK(run("convert " + shell_quoted((in / "nested").string()) + " " + shell_quoted(in.string()), &log) == 2);
    CHECK(run("convert " + shell_quoted((in / "Cameras" / "Cameras.gltf").string()) + " " +
                  shell_quoted((dir / "c.glb").string()) + " -j 2",
              &log) == 2);
}

// `ellicast convert IN OUT [--draco|--quantize]`: encode and decode in one go with every packet, to
// check an asset end to end (a glTF comes out with its scene, materials and textures). With a folder,
// every glTF under it (convert_catalogue.cpp).
#include "commands.h"
#include "convert_catalogue.h"
#include "progress.h"

#include "ellicast/converters/asset_stream.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/converters/mesh_output.h"
#include "ellicast/format.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace ellicast::cli {

namespace {

struct ConvertArgs {
    std::string input, output;
    uint32_t ellipsoids = 400;
    double coverage = 0.95;
    int position_bits = 14;
    int packet_size = int(kDefaultPacketSize);
    uint32_t seed = 1;
    unsigned threads = 2;
    int grid = 0;
    bool quiet = false;
    bool verbose = false;  // every warning on its own line
    bool allow_external_paths = false;
    AssetWriteOptions write;
    bool plain = false;     // glTF output without Draco or quantization even when the input had them
    int jobs = 1;           // with a folder: conversions at once
    std::string validator;  // with a folder: a command run on each output
};

// A folder: each asset through this command in a process of its own, with the same options.
int run_convert_folder(const ConvertArgs& a) {
    CatalogueArgs c;
    c.input = a.input;
    c.output = a.output;
    c.jobs = a.jobs;
    c.validator = a.validator;
    c.quiet = a.quiet;
    c.forwarded = {"-e", std::to_string(a.ellipsoids), "-c", std::to_string(a.coverage), "--position-bits",
                   std::to_string(a.position_bits), "--packet-size", std::to_string(a.packet_size), "--seed",
                   std::to_string(a.seed), "--threads", std::to_string(a.threads), "--grid", std::to_string(a.grid)};
    if (a.write.draco) c.forwarded.push_back("--draco");
    if (a.write.quantize) c.forwarded.push_back("--quantize");
    if (a.write.meshopt) c.forwarded.push_back("--meshopt");
    if (a.plain) c.forwarded.push_back("--plain");
    if (a.allow_external_paths) c.forwarded.push_back("--allow-external-paths");
    return run_convert_catalogue(c);
}

int run_convert(const ConvertArgs& a) {
    if (std::filesystem::is_directory(a.input)) return run_convert_folder(a);
    if (a.jobs != 1 || !a.validator.empty()) return fail(kExitUsage, "--jobs and --validator are for a folder of assets");
    const auto start = std::chrono::steady_clock::now();
    MeshFileType type;
    if (!mesh_file_type_from_path(a.output, type))
        return fail(kExitUsage, a.output + ": unknown output type (expected .glb, .gltf, .ply or .obj)");
    if (std::string bad = check_asset_write_options(a.write); !bad.empty()) return fail(kExitUsage, bad);
    if ((a.write.draco || a.write.quantize || a.write.meshopt) && type != MeshFileType::Glb && type != MeshFileType::Gltf)
        return fail(kExitUsage, "--draco, --quantize and --meshopt need a .glb or .gltf output");
    if (a.plain && (a.write.draco || a.write.quantize || a.write.meshopt))
        return fail(kExitUsage, "--plain excludes --draco, --quantize and --meshopt");
    if (output_clobbers_input(a.output, {a.input})) return kExitUsage;
    if (type == MeshFileType::Gltf &&
        output_clobbers_input(std::filesystem::path(a.output).replace_extension(".bin").string(), {a.input}))
        return kExitUsage;

    if (a.grid != 0 && (a.grid < kMinGridResolution || a.grid > kMaxGridResolution))
        return fail(kExitUsage, "--grid must be 0 or " + std::to_string(kMinGridResolution) + ".." +
                                    std::to_string(kMaxGridResolution));
    EncodeOptions encode;
    encode.max_ellipsoids = a.ellipsoids;
    encode.coverage = a.coverage;
    encode.position_bits = uint8_t(std::clamp(a.position_bits, 0, 255));
    encode.packet_size = uint16_t(std::clamp(a.packet_size, 0, 65535));
    encode.seed = a.seed;
    encode.threads = a.threads;
    if (std::string why = check_encode_options(encode); !why.empty()) return fail(kExitUsage, why);

    Asset asset;
    try {
        asset = load_asset(a.input, InputOptions{a.allow_external_paths});
    } catch (const InputError& e) {
        return fail(kExitFailure, e.what());
    }
    print_warnings(asset.warnings, a.verbose);
    // A glTF output is written as its input was stored, unless told otherwise: Draco stays Draco,
    // meshopt stays meshopt, a quantized input comes back quantized, so that an output is not several
    // times its input for the same meshes.
    AssetWriteOptions write = a.write;
    std::string written_like;
    if (!a.plain && !write.draco && !write.quantize && !write.meshopt &&
        (type == MeshFileType::Glb || type == MeshFileType::Gltf)) {
        if (asset.source_draco) {
            write.draco = true;
            written_like = "Draco (KHR_draco_mesh_compression), as the input";
        } else if (asset.source_meshopt) {
            write.meshopt = true;
            written_like = "meshopt-compressed (EXT_meshopt_compression over KHR_mesh_quantization), as the input";
        } else if (asset.source_quantized) {
            write.quantize = true;
            written_like = "quantized (KHR_mesh_quantization), as the input";
        }
    }

    auto bar = std::make_shared<ProgressBar>(!a.quiet);
    encode.progress = [bar](const std::string& stage, double f) { bar->update(stage, f); };
    EncodedAsset encoded;
    std::string error;
    bool ok = encode_asset(asset, encode, 1, is_gltf_file(a.input), encoded, error);
    bar->finish();
    if (!ok) return fail(kExitFailure, a.input + ": " + error);
    print_warnings(encoded.encoded.warnings, a.verbose);

    // Every packet arrives, in transmission order.
    ReceivedStream stream;
    for (size_t i = 0; i < encoded.packets.size(); ++i)
        if (Error e = stream.add_packet(encoded.packets[i], i); e != Error::Ok)
            return fail(kExitFailure, "packet " + std::to_string(i) + " of our own stream was refused: " + error_name(e));

    DecodeOptions decode;
    decode.grid_resolution = a.grid;
    decode.threads = a.threads;
    decode.progress = [bar](const std::string& stage, double f) { bar->update(stage, f); };
    Asset decoded;
    StreamDecodeReport report;
    ok = decode_asset(stream, decode, decoded, report, error);
    bar->finish();
    if (!ok) return fail(kExitFailure, a.input + ": " + error);
    std::vector<std::string> warnings = decoded.warnings;
    write.warn_unused_required = false;  // the encoder named every extension it does not send
    if (!write_asset(a.output, decoded, write, warnings, error)) return fail(kExitFailure, error);
    print_warnings(warnings, a.verbose);

    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s -> %s\n", a.input.c_str(), a.output.c_str());
    if (!written_like.empty()) std::printf("output written %s (--plain for plain glTF)\n", written_like.c_str());
    // Every packet of the stream counts: the repair packets, the exact layer and the skin weights too.
    size_t all_bytes = 0;
    for (const auto& p : encoded.packets) all_bytes += p.size();
    std::printf("stream: %zu packets (%zu stream info, %zu ellipsoids, %zu scene, %zu points, %zu skin weights, "
                "%zu morph targets, %zu exact layer, %zu repair%s), %zu bytes\n",
                encoded.packets.size(), encoded.stream_info_packets, encoded.ellipsoid_packets, encoded.scene_packets,
                encoded.point_packets, encoded.weight_packets, encoded.morph_packets, encoded.connectivity_packets,
                encoded.repair_packets,
                encoded.texcoord_packets
                    ? (", " + std::to_string(encoded.texcoord_packets) + " further texture coordinates").c_str()
                    : "",
                all_bytes);
    size_t morphed = 0;
    for (const auto& m : decoded.scene.meshes) morphed += !m.weights.empty();
    const std::string with_targets = morphed ? " (" + std::to_string(morphed) + " with morph targets)" : "";
    std::printf("scene: %zu nodes, %zu meshes%s, %zu objects, %zu materials, %zu textures, %zu animations, %zu skins\n",
                decoded.scene.nodes.size(), decoded.scene.meshes.size(), with_targets.c_str(), decoded.objects.size(),
                decoded.scene.materials.size(), decoded.scene.textures.size(), decoded.scene.animations.size(),
                decoded.scene.skins.size());
    for (size_t i = 0; i < report.objects.size(); ++i) {
        const auto& o = report.objects[i];
        std::printf("  object %zu: %zu ellipsoids, %zu points -> %zu vertices, %zu faces%s\n", i, o.ellipsoids,
                    o.points, o.vertices_out, o.faces_out,
                    o.exact ? " (exact: the original triangles)" : o.has_surface ? "" : " (point set)");
    }
    const uint64_t in_bytes = model_files_size(a.input), out_bytes = model_files_size(a.output);
    size_t stream_bytes = 0;
    for (const auto& p : encoded.packets) stream_bytes += p.size();
    auto times = [&](double n) {
        char text[32];
        std::snprintf(text, sizeof text, in_bytes > 0 ? "%.2fx the input" : "input size unknown",
                      in_bytes > 0 ? n / double(in_bytes) : 0.0);
        return std::string(text);
    };
    std::printf("size: input %llu bytes, stream %zu bytes (%s), output %llu bytes (%s)\n",
                static_cast<unsigned long long>(in_bytes), stream_bytes, times(double(stream_bytes)).c_str(),
                static_cast<unsigned long long>(out_bytes), times(double(out_bytes)).c_str());
    std::printf("time %.2f s\n", seconds);
    return kExitOk;
}

const RegisterCommand kRegisterConvert({45, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<ConvertArgs>();
    CLI::App* cmd = app.add_subcommand(
        "convert", "Encode and decode a model in one go with every packet (checks an asset end to end)");
    cmd->add_option("input", args->input,
                    "model to convert (glTF, OBJ, PLY, OFF, STL), or a folder: every .gltf/.glb under it")
        ->required();
    cmd->add_option("output", args->output,
                    "model to write: .glb, .gltf (+ .bin), .ply or .obj; for a folder, the folder to write into (the "
                    "same relative paths, a log beside each output, and catalogue.md)")
        ->required();
    cmd->add_option("-j,--jobs", args->jobs, "with a folder: assets converted at once, each in its own process (1..64)")
        ->capture_default_str();
    cmd->add_option("--validator", args->validator,
                    "with a folder: a command run on each output (its path appended), which prints a JSON line with "
                    "numErrors and numWarnings or exits non-zero on an invalid file; e.g. 'node tests/gltf_validate.js' "
                    "with NODE_PATH naming gltf-validator's node_modules");
    cmd->add_option("-e,--ellipsoids", args->ellipsoids, "most ellipsoids per object (1..100000)")->capture_default_str();
    cmd->add_option("-c,--coverage", args->coverage, "fraction of the interior volume to cover, (0, 1]")
        ->capture_default_str();
    cmd->add_option("--position-bits", args->position_bits, "bits per position coordinate (8..16)")->capture_default_str();
    cmd->add_option("--packet-size", args->packet_size, "largest packet in bytes (128..65000)")->capture_default_str();
    cmd->add_option("--seed", args->seed, "random seed (same seed, same result)")->capture_default_str();
    cmd->add_option("--threads", args->threads, "worker threads of the encoder and the decoder (the result does not depend on it)")
        ->capture_default_str();
    cmd->add_option("--grid", args->grid, "decoder grid resolution (0: the stream's hint)")->capture_default_str();
    cmd->add_flag("--draco", args->write.draco, "glTF output: compress triangle meshes with KHR_draco_mesh_compression");
    cmd->add_flag("--quantize", args->write.quantize, "glTF output: quantize attributes with KHR_mesh_quantization");
    cmd->add_flag("--meshopt", args->write.meshopt,
                  "glTF output: quantize, then compress vertex, index and animation data with EXT_meshopt_compression");
    cmd->add_flag("--plain", args->plain,
                  "glTF output: plain accessors even when the input was Draco-compressed, meshopt-compressed or "
                  "quantized (by default the output is written as the input was)");
    cmd->add_flag("-q,--quiet", args->quiet, "no progress bar");
    cmd->add_flag("--verbose", args->verbose, "every warning on a line of its own (by default three or more of a kind are one line)");
    cmd->add_flag("--allow-external-paths", args->allow_external_paths,
                  "read glTF buffers and images outside the model's folder (refused by default)");
    cmd->callback([args, &exit_code] { exit_code = run_convert(*args); });
}});

}  // namespace

}  // namespace ellicast::cli

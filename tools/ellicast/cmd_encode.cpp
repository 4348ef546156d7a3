// `ellicast encode INPUT -o OUT.ellc`: a model (glTF, OBJ, PLY, OFF, STL) to a recorded stream; a
// glTF's scene (nodes, materials, textures) travels with it.
#include "commands.h"
#include "progress.h"

#include "ellicast/codec/encoder.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/format.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

namespace ellicast::cli {

namespace {

struct EncodeArgs {
    std::string input, output;
    uint32_t ellipsoids = 400;
    double coverage = 0.95;
    uint32_t candidates = 0;
    uint32_t grid = 0;
    int position_bits = 14, normal_bits = 10, texcoord_bits = 12, color_bits = 8;
    int packet_size = int(kDefaultPacketSize);
    uint32_t seed = 1;
    double sample_spacing = EncodeOptions{}.sample_spacing;
    uint32_t max_samples = EncodeOptions{}.max_samples;
    double sample_budget = EncodeOptions{}.sample_budget;
    double base_ratio = EncodeOptions{}.base_ratio;
    uint32_t stream_id = 1;
    bool stream_id_given = false;  // --stream-id on the command line (else a signed stream takes its content id)
    unsigned threads = 2;
    bool quiet = false;
    bool verbose = false;  // every warning on its own line
    bool allow_external_paths = false;
    std::string sign;  // secret key file: sign the stream (spec 16)
    double repair = EncodeOptions{}.repair_ratio;
    bool no_point_map = false;
    double normal_tolerance = EncodeOptions{}.normal_tolerance;
    double point_share = EncodeOptions{}.point_share;
};

// The content id the stream's STREAM_INFO carries (spec 5.4).
std::optional<uint32_t> content_id_of(const std::vector<std::vector<uint8_t>>& packets) {
    for (const auto& bytes : packets) {
        PacketView view;
        if (parse_packet(bytes, view) != Error::Ok) continue;
        if (const auto content = stream_info_content_id(view.header.type, view.payload)) return content;
    }
    return std::nullopt;
}

int run_encode(const EncodeArgs& a) {
    auto start = std::chrono::steady_clock::now();
    if (output_clobbers_input(a.output, {a.input})) return kExitUsage;
    std::error_code ec;
    if (std::filesystem::path(a.output).has_parent_path() &&
        !std::filesystem::is_directory(std::filesystem::path(a.output).parent_path(), ec))
        return fail(kExitUsage, "the output directory of " + a.output + " does not exist");

    EncodeOptions options;
    options.max_ellipsoids = a.ellipsoids;
    options.coverage = a.coverage;
    options.candidates = a.candidates;
    options.grid = a.grid;
    auto bits = [](int v) { return uint8_t(v < 0 || v > 255 ? 0 : v); };
    options.position_bits = bits(a.position_bits);
    options.normal_bits = bits(a.normal_bits);
    options.texcoord_bits = bits(a.texcoord_bits);
    options.color_bits = bits(a.color_bits);
    options.packet_size = uint16_t(a.packet_size < 0 || a.packet_size > 65535 ? 0 : a.packet_size);
    options.seed = a.seed;
    options.sample_spacing = a.sample_spacing;
    options.max_samples = a.max_samples;
    options.sample_budget = a.sample_budget;
    options.base_ratio = a.base_ratio;
    options.threads = a.threads;
    options.repair_ratio = a.repair;
    options.point_map = !a.no_point_map;
    options.normal_tolerance = a.normal_tolerance;
    options.point_share = a.point_share;
    if (std::string why = check_encode_options(options); !why.empty()) return fail(kExitUsage, why);

    // A glTF keeps its scene: each distinct primitive once in its mesh's frame, plus the SCENE,
    // MATERIAL and TEXTURE_FRAGMENT packets. Other formats are one object per mesh, no scene.
    Asset asset;
    try {
        asset = load_asset(a.input, InputOptions{a.allow_external_paths});
    } catch (const InputError& e) {
        return fail(kExitFailure, e.what());
    }
    print_warnings(asset.warnings, a.verbose);
    const bool with_scene = is_gltf_file(a.input);

    auto bar = std::make_shared<ProgressBar>(!a.quiet);
    options.progress = [bar](const std::string& stage, double f) { bar->update(stage, f); };
    EncodedAsset out;
    std::string error;
    bool ok = encode_asset(asset, options, a.stream_id, with_scene, out, error);
    bar->finish();
    if (!ok) return fail(kExitFailure, a.input + ": " + error);
    const EncodeResult& encoded = out.encoded;
    print_warnings(encoded.warnings, a.verbose);

    size_t manifest_parts = 0;
    if (!a.sign.empty()) {
        // Each content signed under its own stream id unless one was chosen (spec 25.3): two contents
        // signed under one could otherwise be spliced by a receiver that accepts older, unbound parts.
        if (!a.stream_id_given) {
            const std::optional<uint32_t> content = content_id_of(out.packets);
            if (content) {
                for (auto& p : out.packets) set_packet_stream_id(p, *content);
                std::printf("stream id 0x%08X (%u): the content id, a signed stream's own (--stream-id chooses "
                            "another)\n",
                            unsigned(*content), unsigned(*content));
            }
        }
        if (int code = sign_packets_with_key(a.sign, out.packets, manifest_parts); code != kExitOk) return code;
    }
    std::vector<uint8_t> file = write_container(out.packets);
    std::string message;
    if (write_file(a.output, file, message) != Error::Ok) return fail(kExitFailure, message);

    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    size_t ellipsoids = 0, points = 0;
    for (const auto& o : encoded.info.objects) ellipsoids += o.ellipsoid_count, points += o.point_count;
    std::printf("%s -> %s\n", a.input.c_str(), a.output.c_str());
    for (size_t i = 0; i < encoded.reports.size(); ++i) {
        const ObjectReport& r = encoded.reports[i];
        if (r.point_set) {
            std::printf("  object %zu %-24s point set: %u points\n", i, r.name.c_str(), r.points);
            continue;
        }
        std::string samples;
        if (r.samples) samples.append(" + ").append(std::to_string(r.samples)).append(" surface samples");
        const std::string budget = r.ellipsoid_budget > 0 ? " (at most " + std::to_string(r.ellipsoid_budget) +
                                                                " for its bytes: --base-ratio)"
                                                          : "";
        std::printf("  object %zu %-24s %u ellipsoids%s (%u for thin parts, %u flat) of %u candidates, %u points (%u vertices%s); "
                    "%s, coverage %.1f%%, outside %.2f%%, surface near base %.1f%%\n",
                    i, r.name.c_str(), r.ellipsoids, budget.c_str(), r.surface_ellipsoids, r.flat_ellipsoids, r.candidates, r.points,
                    r.vertices, samples.c_str(),
                    r.closed ? "closed" : "open", 100 * r.coverage, 100 * r.outside, 100 * r.surface_covered);
    }
    std::printf("objects %zu, ellipsoids %zu, points %zu\n", encoded.info.objects.size(), ellipsoids, points);
    if (with_scene) {
        size_t morphed = 0;
        for (const auto& m : asset.scene.meshes) morphed += !m.weights.empty();
        const std::string with_targets = morphed ? " (" + std::to_string(morphed) + " with morph targets)" : "";
        std::printf("scene: %zu nodes, %zu meshes%s, %zu materials, %zu textures, %zu animations, %zu skins\n",
                    asset.scene.nodes.size(), asset.scene.meshes.size(), with_targets.c_str(), asset.scene.materials.size(),
                    asset.scene.textures.size(), asset.scene.animations.size(), asset.scene.skins.size());
        if (out.weight_packets || out.morph_packets)
            std::printf("per-point scene data: skin weights %zu (%zu packets), morph targets %zu (%zu packets)\n",
                        out.weight_bytes, out.weight_packets, out.morph_bytes, out.morph_packets);
    }
    std::printf("bytes: stream info %zu (%zu packets), base %zu (%zu packets), point map %zu (%zu packets), scene %zu "
                "(%zu packets), detail %zu (%zu packets), repair %zu (%zu packets), file %zu\n",
                out.stream_info_bytes, out.stream_info_packets, out.ellipsoid_bytes, out.ellipsoid_packets, out.map_bytes,
                out.map_packets, out.scene_bytes, out.scene_packets, out.point_bytes, out.point_packets, out.repair_bytes,
                out.repair_packets, file.size());
    if (manifest_parts) {
        size_t manifest_bytes = 0;  // sign_stream puts the MANIFEST parts first
        for (size_t i = 0; i < manifest_parts; ++i) manifest_bytes += out.packets[i].size();
        std::printf("signed: %zu MANIFEST part(s), %zu bytes\n", manifest_parts, manifest_bytes);
    }
    std::printf("bytes per ellipsoid %.2f, bytes per point %.2f (packet overhead and point map included)\n",
                ellipsoids ? double(out.ellipsoid_bytes) / double(ellipsoids) : 0.0,
                points ? double(out.point_bytes + out.map_bytes) / double(points) : 0.0);
    for (size_t i = 0; i < encoded.reports.size(); ++i) {
        const ObjectReport& r = encoded.reports[i];
        if (r.map_level > 0)
            std::printf("object %zu: points mapped at level %u (format 1.7): %.2f bytes a point (map %.2f) against "
                        "%.2f as POINTS\n",
                        i, unsigned(r.map_level), double(r.map_bytes + r.mapped_point_bytes) / double(r.points),
                        double(r.map_bytes) / double(r.points), double(r.plain_point_bytes) / double(r.points));
        if (r.carried > 0)
            std::printf("object %zu: %u of its vertices carried by the exact layer (format 1.11), %u sent as points; "
                        "exact layer %u bytes\n",
                        i, r.carried, r.points, r.connectivity_bytes);
        if (r.texcoord_sets > 0)
            std::printf("object %zu: TEXCOORD_1%s (format 1.14) sent for its %u points\n", i,
                        r.texcoord_sets > 1 ? (" to TEXCOORD_" + std::to_string(r.texcoord_sets)).c_str() : "", r.points);
        if (r.surface_normals)
            std::printf("object %zu: surface normals (format 1.8): %u of %u normals sent, the others within %g degrees "
                        "of the surface's\n",
                        i, r.normals_sent, r.points, a.normal_tolerance);
    }
    if (out.normal_packets)
        std::printf("normals: %zu bytes (%zu NORMALS packets), %.2f bytes a point\n", out.normal_bytes, out.normal_packets,
                    points ? double(out.normal_bytes) / double(points) : 0.0);
    if (out.texcoord_packets)
        std::printf("further texture coordinates: %zu bytes (%zu TEXCOORDS packets)\n", out.texcoord_bytes,
                    out.texcoord_packets);
    std::printf("time %.2f s\n", seconds);
    return kExitOk;
}

const RegisterCommand kRegisterEncode({10, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<EncodeArgs>();
    CLI::App* cmd = app.add_subcommand("encode", "Encode a model (glTF, OBJ, PLY, OFF, STL) into a stream file (.ellc)");
    cmd->add_option("input", args->input, "model to encode")->required();
    cmd->add_option("-o,--output", args->output, "stream file to write (.ellc)")->required();
    cmd->add_option("-e,--ellipsoids", args->ellipsoids, "most ellipsoids per object (1..100000)")->capture_default_str();
    cmd->add_option("-c,--coverage", args->coverage, "fraction of the interior volume to cover, (0, 1]")
        ->capture_default_str();
    cmd->add_option("--candidates", args->candidates, "candidate ellipsoids grown per object (0: automatic)")
        ->capture_default_str();
    cmd->add_option("--grid", args->grid, "voxel grid cells along the longest side (16..256, 0: automatic)")
        ->capture_default_str();
    cmd->add_option("--position-bits", args->position_bits, "bits per position coordinate (8..16)")->capture_default_str();
    cmd->add_option("--normal-bits", args->normal_bits, "bits per octahedral normal component (4..16)")
        ->capture_default_str();
    cmd->add_option("--texcoord-bits", args->texcoord_bits, "bits per texture coordinate (4..16)")->capture_default_str();
    cmd->add_option("--color-bits", args->color_bits, "bits per colour channel (2..16)")->capture_default_str();
    cmd->add_option("--packet-size", args->packet_size, "largest packet in bytes (128..65000)")->capture_default_str();
    cmd->add_option("--seed", args->seed, "random seed (same seed, same stream)")->capture_default_str();
    cmd->add_option("--sample-spacing", args->sample_spacing,
                    "add surface samples so that no edge inside a face is longer than this fraction of the "
                    "object's diagonal (half of it along creases); 0: original vertices only, [0, 1]")
        ->capture_default_str();
    cmd->add_option("--max-samples", args->max_samples,
                    "most surface samples per object (or its vertex count if larger); the spacing grows to fit")
        ->capture_default_str();
    cmd->add_option("--sample-budget", args->sample_budget,
                    "most surface samples per original vertex of an object: samples serve a receiver only until the "
                    "exact layer is whole, and lengthen every cycle (-1: no limit but --max-samples), [-1, 1000]")
        ->capture_default_str();
    cmd->add_option("--base-ratio", args->base_ratio,
                    "an object's ellipsoids take at most this multiple of the bytes of its points and triangles "
                    "(at least 8 ellipsoids; 0: --ellipsoids alone), [0, 1000]")
        ->capture_default_str();
    CLI::Option* stream_id = cmd->add_option("--stream-id", args->stream_id,
                                             "stream id written in every packet (default 1; with --sign, the "
                                             "content id, so that each signed content has its own)");
    cmd->add_option("--threads", args->threads, "worker threads (1..256; with more than one, an object's points are made beside its ellipsoids in one more; the result does not depend on it)")
        ->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "no progress bar");
    cmd->add_flag("--verbose", args->verbose, "every warning on a line of its own (by default three or more of a kind are one line)");
    cmd->add_option("--repair", args->repair,
                    "POINTS_REPAIR packets per POINTS packet, per block (format 1.2): a carousel sends them in turn "
                    "with the POINTS packets so that a receiver under loss gets every point sooner; 0: none, [0, 4]")
        ->capture_default_str();
    cmd->add_flag("--no-point-map", args->no_point_map,
                  "send every point as a full POINTS record (format 1.0), readable by decoders before format 1.7, "
                  "instead of MAPPED_POINTS over a POINT_MAP where that takes fewer bytes");
    cmd->add_option("--normal-tolerance", args->normal_tolerance,
                    "degrees (0..90): an object with normals and an exact layer sends only the normals further than "
                    "this from its surface's, in NORMALS packets (format 1.8); 0 sends every normal in the point "
                    "records, readable with normals by decoders before format 1.8")
        ->capture_default_str();
    cmd->add_option("--point-share", args->point_share,
                    "share of an object's vertices sent as points (0..1); the exact layer carries the others, coded "
                    "against its triangles (format 1.11): a smaller stream and the exact model sooner, fewer points "
                    "for the picture before it. Objects with skins, morph targets or normals in their records keep "
                    "every vertex a point (with surface normals, the vertices whose normal is sent); 1: every vertex "
                    "a point, readable exact by decoders before format 1.11")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--sign", args->sign, "sign the stream with this secret key (NAME.key from `ellicast keygen`)");
    cmd->add_flag("--allow-external-paths", args->allow_external_paths,
                  "read glTF buffers and images outside the model's folder (refused by default)");
    cmd->callback([args, stream_id, &exit_code] {
        args->stream_id_given = stream_id->count() > 0;
        exit_code = run_encode(*args);
    });
}});

}  // namespace

}  // namespace ellicast::cli

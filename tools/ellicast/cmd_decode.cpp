// `ellicast decode IN.ellc -o OUT.glb|.gltf|.ply|.obj [--snapshots N] [--grid R] [--draco|--quantize]`:
// rebuild the models from whatever packets a recorded stream holds, in their scene when it has one.
#include "commands.h"
#include "region_option.h"
#include "progress.h"

#include "ellicast/codec/decoder.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/converters/mesh_output.h"
#include "ellicast/format.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace ellicast::cli {
namespace {

struct DecodeArgs {
    std::string input;
    std::string output;
    size_t snapshots = 0;
    int grid = 0;
    double faces_per_point = DecodeOptions{}.faces_per_point;
    bool quiet = false;
    bool verbose = false;  // every warning on its own line
    bool no_exact = false;    // --no-exact: always the reconstruction
    std::string key;          // --key: decode only what this sender signed
    AssetWriteOptions write;  // --draco, --quantize
    std::string region;       // --region: refine only there (region_option.h)
    unsigned threads = DecodeOptions{}.threads;
};

std::string snapshot_path(const std::string& output, size_t object, size_t points) {
    namespace fs = std::filesystem;
    fs::path out(output);
    char name[64];
    std::snprintf(name, sizeof name, ".snap-o%zu-p%07zu", object, points);
    return (out.parent_path() / (out.stem().string() + name + out.extension().string())).string();
}

// One line on what arrived of the scene: table sizes as the packets announce them ("?" when no
// packet of that kind arrived), materials shown (a material waiting for a texture is not; the
// warnings name it and the texture), textures complete.
void print_scene_summary(const ReceivedStream& stream, const Asset& asset) {
    size_t material_total = 0, texture_total = 0, textures_complete = 0;
    for (const auto& [index, m] : stream.materials()) material_total = std::max<size_t>(material_total, m.material_count);
    for (const auto& [index, t] : stream.textures()) {
        texture_total = std::max<size_t>(texture_total, t.info.texture_count);
        if (t.complete) ++textures_complete;
    }
    auto total = [](size_t n, bool known) { return known ? std::to_string(n) : std::string("?"); };
    const size_t shown = asset.scene.materials.size();
    // With a scene, every material that arrived is shown unless it waits for a texture; without
    // one nothing can be placed (received_asset says so).
    const size_t waiting = stream.has_scene() ? stream.materials().size() - std::min(shown, stream.materials().size()) : 0;
    std::printf("scene: %zu of %s nodes, %zu of %s meshes, %zu of %s materials shown", stream.scene_nodes().size(),
                total(stream.scene_node_count(), stream.has_scene()).c_str(), stream.scene_meshes().size(),
                total(stream.scene_mesh_count(), stream.has_scene()).c_str(), shown,
                total(material_total, !stream.materials().empty()).c_str());
    if (waiting) std::printf(" (%zu waiting for a texture)", waiting);
    std::printf(", %zu of %s textures complete", textures_complete, total(texture_total, !stream.textures().empty()).c_str());
    if (stream.animation_count())
        std::printf(", %zu of %u animations shown", asset.scene.animations.size(), unsigned(*stream.animation_count()));
    if (stream.skin_count())
        std::printf(", %zu of %u skins shown", asset.scene.skins.size(), unsigned(*stream.skin_count()));
    size_t with_targets = 0, shown_targets = 0;
    for (const auto& [i, m] : stream.scene_meshes()) with_targets += !m.weights.empty();
    for (const auto& m : asset.scene.meshes) shown_targets += !m.weights.empty();
    if (with_targets) std::printf(", %zu of %zu meshes with their morph targets", shown_targets, with_targets);
    std::printf("\n");
}

int run_decode(const DecodeArgs& args) {
    MeshFileType type;
    if (!mesh_file_type_from_path(args.output, type))
        return fail(kExitUsage, args.output + ": unknown output type (expected .glb, .gltf, .ply or .obj)");
    if (output_clobbers_input(args.output, {args.input})) return kExitUsage;
    if (std::string bad = check_asset_write_options(args.write); !bad.empty()) return fail(kExitUsage, bad);
    if ((args.write.draco || args.write.quantize || args.write.meshopt) && type != MeshFileType::Glb &&
        type != MeshFileType::Gltf)
        return fail(kExitUsage, "--draco, --quantize and --meshopt need a .glb or .gltf output");
    Region region;
    if (!args.region.empty()) {
        std::string error;
        if (!parse_region(args.region, region, error)) return fail(kExitUsage, error);
    }
    if (type == MeshFileType::Gltf) {
        auto bin = std::filesystem::path(args.output).replace_extension(".bin").string();
        if (output_clobbers_input(bin, {args.input})) return kExitUsage;
    }

    auto t0 = std::chrono::steady_clock::now();
    RecordingPackets recording;
    if (int code = read_recording(args.input, args.key, recording); code != kExitOk) return code;
    const ContainerContents& contents = recording.contents;
    ReceivedStream stream;
    for (const auto& packet : contents.packets) stream.add_parsed(packet.view, packet.offset);
    double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    ProgressBar bar(!args.quiet);
    DecodeOptions options;
    options.grid_resolution = args.grid;
    options.faces_per_point = args.faces_per_point;
    options.exact = !args.no_exact;
    options.threads = args.threads;
    options.snapshot_every = args.snapshots;
    options.progress = [&](const std::string& stage, double fraction) { bar.update(stage, fraction); };
    if (!args.region.empty()) options.insert_if = region_filter(region, stream);
    std::string snapshot_error;
    size_t snapshots_written = 0;
    if (args.snapshots > 0) {
        options.snapshot = [&](size_t object, size_t points, const Mesh& mesh) {
            if (!snapshot_error.empty()) return;
            Mesh named = mesh;
            named.name = "object" + std::to_string(object);
            std::string path = snapshot_path(args.output, object, points);
            if (output_clobbers_input(path, {args.input})) {
                snapshot_error = "a snapshot would overwrite the input";
                return;
            }
            if (!write_meshes(path, {named}, snapshot_error)) return;
            ++snapshots_written;
        };
    }
    Asset asset;
    StreamDecodeReport report;
    std::string error;
    bool ok = decode_asset(stream, options, asset, report, error);
    bar.finish();
    if (!ok) {
        std::string damage;
        if (!contents.damaged.empty())
            damage = " (" + std::to_string(contents.damaged.size()) + " damaged region(s) of the file were skipped, the first at byte " +
                     std::to_string(contents.damaged[0].offset) + ": " + error_name(contents.damaged[0].first_error) + ")";
        return fail(kExitInvalid, args.input + ": " + error + damage);
    }
    if (!snapshot_error.empty()) return fail(kExitFailure, snapshot_error);
    if (std::none_of(asset.objects.begin(), asset.objects.end(), [](const Mesh& m) { return !m.positions.empty(); }))
        return fail(kExitInvalid, args.input + ": nothing can be built: no object received any ellipsoid or point");

    auto tw = std::chrono::steady_clock::now();
    std::vector<std::string> warnings = asset.warnings;
    if (!write_asset(args.output, asset, args.write, warnings, error)) return fail(kExitFailure, error);
    print_warnings(warnings, args.verbose);
    double write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count();

    const auto& c = stream.counters();
    uint64_t damaged_bytes = 0;
    for (const auto& d : contents.damaged) damaged_bytes += d.length;
    std::printf("decoded %s -> %s\n", args.input.c_str(), args.output.c_str());
    std::printf("packets: %llu used, %llu duplicate, %llu skipped (unknown skippable type), %llu rejected, "
                "%llu waiting for stream info; %zu damaged region(s), %llu byte(s)\n",
                (unsigned long long)c.accepted, (unsigned long long)c.duplicates, (unsigned long long)c.skipped,
                (unsigned long long)c.rejected, (unsigned long long)c.pending, contents.damaged.size(),
                (unsigned long long)damaged_bytes);
    if (stream.has_scene() || !stream.materials().empty() || !stream.textures().empty())
        print_scene_summary(stream, asset);
    const auto& objects = stream.objects();
    for (size_t i = 0; i < report.objects.size(); ++i) {
        const auto& o = report.objects[i];
        if (!objects[i].info) {
            std::printf("object %zu: no stream info entry arrived; skipped\n", i);
            continue;
        }
        const auto& info = *objects[i].info;
        std::printf("object %zu: %zu/%u ellipsoids, %zu/%u points -> %zu vertices, %zu faces", i, o.ellipsoids,
                    info.ellipsoid_count, o.points, info.point_count, o.vertices_out, o.faces_out);
        if (o.exact)
            std::printf(" (exact: the original triangles)");
        else if (o.has_surface)
            std::printf(" (base %zu vertices, %zu faces; %zu marching-cubes vertices left; %zu flips, %zu collapses%s)",
                        o.base_vertices, o.base_faces, o.mc_vertices_left, o.flips, o.collapses,
                        o.simplified_faces > 0
                            ? ("; " + std::to_string(o.simplified_faces) + " base triangles simplified away").c_str()
                            : "");
        else
            std::printf(" (point set)");
        if (!o.exact && o.has_connectivity)
            std::printf("; exact layer: %llu of %llu bytes", (unsigned long long)o.connectivity_bytes,
                        (unsigned long long)o.connectivity_size);
        std::printf("\n");
        for (const auto& note : o.notes) std::fprintf(stderr, "ellicast: warning: object %zu: %s\n", i, note.c_str());
        // Format 1.7 (spec 23.4): points whose map fragment did not arrive are held, not shown.
        if (!objects[i].unplaced.empty())
            std::fprintf(stderr,
                         "ellicast: warning: object %zu: %zu points arrived but are not shown: the POINT_MAP fragments "
                         "that place them did not arrive (its map holds %llu of %u ranks)\n",
                         i, objects[i].unplaced.size(), (unsigned long long)objects[i].map_ranks, info.point_count);
    }
    const auto& t = report.timings;
    std::printf("time: read %.3f s, rasterize %.3f s, marching cubes %.3f s, insertion %.3f s, cleanup %.3f s, "
                "output mesh %.3f s, write %.3f s\n",
                read_seconds, t.rasterize, t.marching_cubes, t.insertion, t.cleanup, t.output, write_seconds);
    if (snapshots_written > 0)
        std::printf("snapshots: %zu written as %s\n", snapshots_written, snapshot_path(args.output, 0, 0).c_str());
    return kExitOk;
}

const RegisterCommand kRegisterDecode{{40, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<DecodeArgs>();
    auto* cmd = app.add_subcommand("decode", "Rebuild the models of a recorded stream (.ellc) from the packets it holds");
    cmd->add_option("input", args->input, "recorded stream (.ellc)")->required();
    cmd->add_option("-o,--output", args->output, "output model: .glb, .gltf (+ .bin), .ply or .obj")->required();
    cmd->add_option("--snapshots", args->snapshots,
                    "also write the reconstruction of each object as its base and after every N points "
                    "(OUT.snap-o<object>-p<points>.<ext>)")
        ->check(CLI::Range(size_t(1), size_t(1) << 40));
    cmd->add_option("--grid", args->grid,
                    "grid resolution for the base (cells along the object's frame; default: the stream's hint, "
                    "else " + std::to_string(kDefaultGridResolution) + ")")
        ->check(CLI::Range(kMinGridResolution, kMaxGridResolution));
    cmd->add_option("--faces-per-point", args->faces_per_point,
                    "an incomplete object is written with at most this many triangles per point of its stream "
                    "(at least 5000), the base simplified around the points received; 0: the whole base")
        ->check(CLI::Range(0.0, 1000.0))
        ->capture_default_str();
    cmd->add_flag("--draco", args->write.draco, "glTF output: compress triangle meshes with KHR_draco_mesh_compression");
    cmd->add_flag("--quantize", args->write.quantize, "glTF output: quantize attributes with KHR_mesh_quantization");
    cmd->add_flag("--meshopt", args->write.meshopt,
                  "glTF output: quantize, then compress vertex, index and animation data with EXT_meshopt_compression");
    cmd->add_option("--key", args->key,
                    "public key (NAME.pub or 64 hex digits): decode only the packets a MANIFEST signed with it lists");
    cmd->add_option("--region", args->region,
                    "refine only inside a region, holding the other points: box:X0,Y0,Z0,X1,Y1,Z1 or "
                    "view:EX,EY,EZ,TX,TY,TZ,FOV[,ASPECT] (a camera's position, target and field of view in degrees; "
                    "world coordinates). An object whose exact layer is whole is still written exact");
    cmd->add_flag("--no-exact", args->no_exact,
                  "reconstruct every object, also one whose exact layer (original triangles) arrived whole");
    cmd->add_option("--threads", args->threads,
                    "objects reconstructed side by side (1..256; the result does not depend on it)")
        ->check(CLI::Range(1u, 256u))
        ->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "no progress bar");
    cmd->add_flag("--verbose", args->verbose, "every warning on a line of its own (by default three or more of a kind are one line)");
    cmd->callback([args, &exit_code] { exit_code = run_decode(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

// `ellicast diff A B`: surface distance between two models (Metro / MeshLab Hausdorff style).
#include "commands.h"

#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/mesh_input.h"

#include <cstdio>
#include <iostream>
#include <memory>

namespace ellicast::cli {
namespace {

struct DiffArgs {
    std::string a, b;
    size_t samples = 0;
    double threshold = 0.5;
    uint64_t seed = 1;
};

void describe(const char* label, const std::string& path, const std::vector<Mesh>& meshes) {
    size_t v = 0, f = 0;
    for (const auto& m : meshes) v += m.positions.size(), f += m.triangles.size();
    std::printf("%s: %s (%zu vertices, %zu triangles, bounding-box diagonal %.6g)\n", label, path.c_str(), v, f,
                bounding_box_diagonal(meshes));
}

void row(const char* label, const DirectedDistance& d, const SurfaceDistance& s) {
    std::printf("%-8s %12.6g (%7.4f%%) %12.6g (%7.4f%%) %12.6g (%7.4f%%) %9.4f%%  %zu\n", label, d.max, s.percent(d.max),
                d.mean, s.percent(d.mean), d.rms, s.percent(d.rms), 100.0 * d.far_fraction, d.samples);
}

int run_diff(const DiffArgs& args) {
    std::vector<Mesh> a, b;
    std::string error;
    if (!load_model(args.a, a, error)) return fail(kExitFailure, error);
    if (!load_model(args.b, b, error)) return fail(kExitFailure, error);
    SurfaceDistanceOptions options;
    options.samples = args.samples;
    options.threshold_percent = args.threshold;
    options.seed = args.seed;
    SurfaceDistance d;
    if (!surface_distance(a, b, options, d, error)) return fail(kExitInvalid, error);
    describe("A", args.a, a);
    describe("B", args.b, b);
    std::printf("distances in model units and in %% of A's bounding-box diagonal (%.6g); far = farther than %.4g%% "
                "(%.6g)\n",
                d.diagonal, args.threshold, d.threshold);
    std::printf("%-8s %24s %24s %24s %10s  %s\n", "", "max (Hausdorff)", "mean", "RMS", "far area", "samples");
    row("A -> B", d.a_to_b, d);
    row("B -> A", d.b_to_a, d);
    std::printf("Hausdorff distance (symmetric): %.6g (%.4f%%)\n", d.hausdorff(), d.percent(d.hausdorff()));
    return kExitOk;
}

const RegisterCommand kRegisterDiff{{50, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<DiffArgs>();
    auto* cmd = app.add_subcommand("diff", "Surface distance between two models, both directions (any format ellicast reads)");
    cmd->add_option("a", args->a, "first model (the reference: percentages are of its bounding-box diagonal)")->required();
    cmd->add_option("b", args->b, "second model")->required();
    cmd->add_option("--samples", args->samples, "samples per direction (default: 10 per triangle, 100k..2M)")
        ->check(CLI::Range(size_t(1), size_t(100'000'000)));
    cmd->add_option("--threshold", args->threshold, "'far' threshold in % of A's diagonal (default 0.5)")
        ->check(CLI::Range(0.0, 100.0));
    cmd->add_option("--seed", args->seed, "seed of the sample positions (default 1)");
    cmd->callback([args, &exit_code] { exit_code = run_diff(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

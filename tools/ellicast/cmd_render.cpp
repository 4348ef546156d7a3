// `ellicast render MODEL... -o OUT.png`: pictures of models (side by side, framed alike), for looking at
// reconstructions and snapshots rather than reading numbers.
#include "commands.h"

#include "ellicast/converters/render.h"

#include <cstdio>
#include <filesystem>

namespace ellicast::cli {
namespace {

struct RenderArgs {
    std::vector<std::string> inputs;
    std::string output;
    std::string frame_from;
    std::vector<std::string> labels;  // one a panel, written across its top
    RenderOptions options;
};

int run_render(const RenderArgs& args) {
    if (std::filesystem::path(args.output).extension() != ".png")
        return fail(kExitUsage, args.output + ": the output must be a .png file");
    std::vector<std::string> all_inputs = args.inputs;
    if (!args.frame_from.empty()) all_inputs.push_back(args.frame_from);
    if (output_clobbers_input(args.output, all_inputs)) return kExitUsage;
    if (!args.labels.empty() && args.labels.size() != args.inputs.size())
        return fail(kExitUsage, "--labels: " + std::to_string(args.labels.size()) + " labels for " +
                                    std::to_string(args.inputs.size()) + " models (one a panel)");
    std::vector<std::vector<Mesh>> models(all_inputs.size());
    std::string error;
    for (size_t i = 0; i < all_inputs.size(); ++i)
        if (!load_model(all_inputs[i], models[i], error)) return fail(kExitFailure, error);
    // Every panel is framed by the same box: the --frame-from model's, else the first model's.
    std::array<double, 3> lo, hi;
    bounding_box(args.frame_from.empty() ? models.front() : models.back(), lo, hi);
    std::vector<Image> panels;
    for (size_t i = 0; i < args.inputs.size(); ++i) {
        panels.push_back(render_meshes(models[i], lo, hi, args.options));
        if (!args.labels.empty()) draw_label(panels.back(), args.labels[i], std::max(1, args.options.width / 160));
    }
    try {
        write_png(args.output, side_by_side(panels));
    } catch (const std::exception& e) {
        return fail(kExitFailure, e.what());
    }
    std::fprintf(stderr, "wrote %s (%zu panel%s)\n", args.output.c_str(), panels.size(), panels.size() == 1 ? "" : "s");
    return kExitOk;
}

const RegisterCommand kRegisterRender{{90, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand("render", "Draw models as a PNG picture, side by side and framed alike");
    cmd->add_option("models", args->inputs, "models to draw, one panel each (any format ellicast reads)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", args->output, "picture to write (.png)")->required();
    cmd->add_option("--width", args->options.width, "pixels per panel")->check(CLI::Range(16, 4096));
    cmd->add_option("--height", args->options.height, "pixels per panel")->check(CLI::Range(16, 4096));
    cmd->add_option("--azimuth", args->options.azimuth, "view direction around the vertical axis, degrees")
        ->check(CLI::Range(-360.0, 360.0));
    cmd->add_option("--elevation", args->options.elevation, "view direction above the horizon, degrees")
        ->check(CLI::Range(-90.0, 90.0));
    cmd->add_flag("--wireframe", args->options.wireframe, "draw the triangle edges");
    cmd->add_option("--labels", args->labels, "a caption for each panel, comma-separated (as many as models)")
        ->delimiter(',');
    cmd->add_flag("!--no-colors", args->options.use_colors, "ignore vertex colours");
    cmd->add_option("--frame-from", args->frame_from, "frame every panel by this model's bounding box")
        ->check(CLI::ExistingFile);
    cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

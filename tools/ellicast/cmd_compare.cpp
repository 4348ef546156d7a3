// `ellicast compare MODEL -o RESULTS_DIR`: ellicast against Draco baselines under identical losses,
// with a CSV of every trial, plots and a Markdown report.
#include "commands.h"
#include "progress.h"

#include "ellicast/compare/channel_trace.h"
#include "ellicast/compare/ellicast_scheme.h"
#include "ellicast/compare/experiment.h"
#include "ellicast/compare/hybrid_scheme.h"
#include "ellicast/compare/metric.h"
#include "ellicast/compare/report.h"
#include "ellicast/compare/schemes.h"
#include "ellicast/converters/mesh_input.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

namespace ellicast::cli {

namespace {

struct CompareArgs {
    std::string model, output;
    std::vector<double> loss{0, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7};
    std::vector<double> burst{0, 8, 32};
    size_t trials = 200;
    size_t curve_trials = 3;
    size_t steps = 16;
    double horizon = 4, long_horizon = 8, long_from = 0.4;
    int mds_block_data = compare::DracoMds::kDefaultBlockData;
    int draco_speed = 0;  // Draco's encoding and decoding speed: 0 gives the smallest file (draco_encoder -cl 10)
    uint64_t seed = 1;
    int packet_size = 1200;
    uint32_t ellipsoids = 400;
    double base_share = 0.15;
    double point_share = 1.0;  // format 1.11: the share of the vertices sent as points
    std::string fec_redundancy = "auto";
    size_t samples = 20000;
    double hole_threshold = 0.5;
    unsigned threads = 2;
    bool quiet = false;
    bool allow_external_paths = false;
};

std::string list(const std::vector<double>& v) {
    std::ostringstream s;
    for (size_t i = 0; i < v.size(); ++i) s << (i ? "," : "") << v[i];
    return s.str();
}

std::string text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// The command line that reproduces a run (every option that matters, spelled out).
std::string reproduce_command(const CompareArgs& a) {
    std::ostringstream s;
    s << "ellicast compare " << a.model << " --loss " << list(a.loss) << " --burst " << list(a.burst) << " --trials "
      << a.trials << " --curve-trials " << a.curve_trials << " --seed " << a.seed << " --steps-per-cycle " << a.steps
      << " --horizon " << a.horizon << " --long-horizon " << a.long_horizon << " --long-from " << a.long_from
      << " --packet-size " << a.packet_size << " --ellipsoids " << a.ellipsoids << " --point-share " << a.point_share
      << " --base-share " << a.base_share
      << " --rs-redundancy " << a.fec_redundancy << " --mds-block-data " << a.mds_block_data << " --draco-speed "
      << a.draco_speed << " --samples " << a.samples << " --hole-threshold "
      << a.hole_threshold << " -o " << a.output;
    return s.str();
}

// All meshes of the model as one (the baselines compress one mesh; ellicast gets the same one).
Mesh merge_meshes(const std::vector<Mesh>& meshes) {
    std::vector<Mesh> surfaces;
    for (const auto& m : meshes)
        if (!m.is_point_set && !m.triangles.empty()) surfaces.push_back(m);
    if (surfaces.size() == 1) return surfaces[0];
    return compare::concatenate(surfaces);
}

int run_compare(const CompareArgs& a) {
    using namespace ellicast::compare;
    const auto start = std::chrono::steady_clock::now();
    if (a.packet_size < int(kMinPacketSize) || a.packet_size > 65000)
        return fail(kExitUsage, "--packet-size " + std::to_string(a.packet_size) + " is outside [128, 65000]");
    if (a.trials < 1 || a.trials > 100000) return fail(kExitUsage, "--trials must be in [1, 100000]");
    if (a.curve_trials > a.trials)
        return fail(kExitUsage, "--curve-trials " + std::to_string(a.curve_trials) + " exceeds --trials " + std::to_string(a.trials));
    if (a.steps < 1 || a.steps > 1024) return fail(kExitUsage, "--steps-per-cycle must be in [1, 1024]");
    for (double h : {a.horizon, a.long_horizon})
        if (!(h >= 1 && h <= 100)) return fail(kExitUsage, "--horizon and --long-horizon must be in [1, 100] cycles, not " + text(h));
    if (!(a.long_from >= 0 && a.long_from <= 1)) return fail(kExitUsage, "--long-from must be in [0, 1]");
    if (a.mds_block_data < 1 || a.mds_block_data > 254) return fail(kExitUsage, "--mds-block-data must be in [1, 254]");
    if (a.draco_speed < 0 || a.draco_speed > 10) return fail(kExitUsage, "--draco-speed must be in [0, 10]");
    for (double p : a.loss)
        if (!(p >= 0 && p < 1)) return fail(kExitUsage, "--loss " + text(p) + " is outside [0, 1)");
    for (double b : a.burst)
        if (!(b >= 0 && b <= 1e6)) return fail(kExitUsage, "--burst " + text(b) + " is outside [0, 1e6]");
    if (!(a.base_share > 0 && a.base_share < 1)) return fail(kExitUsage, "--base-share must be in (0, 1)");
    if (!(a.point_share >= 0 && a.point_share <= 1)) return fail(kExitUsage, "--point-share must be in [0, 1]");
    if (a.samples < 1000 || a.samples > 5000000) return fail(kExitUsage, "--samples must be in [1000, 5000000]");
    if (!(a.hole_threshold > 0 && a.hole_threshold < 100)) return fail(kExitUsage, "--hole-threshold must be in (0, 100)");
    double fec_redundancy = -1;
    if (a.fec_redundancy != "auto") {
        try {
            size_t used = 0;
            fec_redundancy = std::stod(a.fec_redundancy, &used);
            if (used != a.fec_redundancy.size() || !(fec_redundancy >= 0 && fec_redundancy <= 10)) throw 0;
        } catch (...) {
            return fail(kExitUsage, "--rs-redundancy must be 'auto' or a number in [0, 10], not '" + a.fec_redundancy + "'");
        }
    }
    std::error_code ec;
    if (std::filesystem::exists(a.output, ec) && !std::filesystem::is_directory(a.output, ec))
        return fail(kExitUsage, a.output + " exists and is not a directory");
    if (std::filesystem::equivalent(a.output, a.model, ec)) return fail(kExitUsage, "the output is the model itself");

    std::vector<Mesh> meshes;
    std::string error;
    if (!load_model(a.model, meshes, error, InputOptions{a.allow_external_paths})) return fail(kExitFailure, error);
    Mesh mesh = merge_meshes(meshes);
    if (mesh.triangles.empty()) return fail(kExitFailure, a.model + ": no triangle mesh to compare");

    auto bar = std::make_shared<ProgressBar>(!a.quiet);
    std::unique_ptr<EllicastScheme> ellicast, ellicast_repeat;
    std::unique_ptr<DracoWhole> whole;
    std::unique_ptr<DracoRsRepeat> fec;
    std::unique_ptr<DracoMds> mds;
    std::unique_ptr<DracoClusters> clusters;
    std::unique_ptr<EllipsoidsDracoMds> hybrid;  // ellicast's base + draco-mds
    try {
        EllicastSettings es;
        es.encode.max_ellipsoids = a.ellipsoids;
        es.encode.point_share = a.point_share;
        es.encode.packet_size = uint16_t(a.packet_size);
        es.encode.seed = 1;
        es.encode.threads = a.threads;
        es.encode.progress = [bar](const std::string& stage, double f) { bar->update("encode: " + stage, f); };
        es.base_share = a.base_share;
        ellicast = std::make_unique<EllicastScheme>(mesh, es);
        // The same stream without repair packets, as a carousel of format 1.1 sends it.
        es.repair_ratio = 0;
        es.name = "ellicast-repeat";
        es.encode.progress = nullptr;
        ellicast_repeat = std::make_unique<EllicastScheme>(mesh, es);
        bar->update("Draco baselines", 0);
        DracoSettings ds;  // glTF-Transform's quantization; the speed a broadcaster encoding offline would pick
        ds.encoding_speed = ds.decoding_speed = a.draco_speed;
        if (fec_redundancy < 0) fec_redundancy = ellicast->repetition_overhead();
        whole = std::make_unique<DracoWhole>(mesh, ds, size_t(a.packet_size));
        bar->update("Draco baselines", 0.3);
        fec = std::make_unique<DracoRsRepeat>(mesh, ds, size_t(a.packet_size), fec_redundancy);
        bar->update("Draco baselines", 0.4);
        mds = std::make_unique<DracoMds>(mesh, ds, size_t(a.packet_size), a.mds_block_data);
        hybrid = std::make_unique<EllipsoidsDracoMds>(*ellicast, *mds);
        bar->update("Draco baselines", 0.6);
        clusters = std::make_unique<DracoClusters>(mesh, ds, size_t(a.packet_size));
        bar->update("Draco baselines", 1);
    } catch (const std::exception& e) {
        bar->finish();
        return fail(kExitFailure, a.model + ": " + e.what());
    }

    ExperimentOptions options;
    options.loss_rates = a.loss;
    options.bursts = a.burst;
    options.trials = a.trials;
    options.seed = a.seed;
    options.curve_trials = a.curve_trials;
    options.steps_per_cycle = a.steps;
    options.horizon = a.horizon;
    options.long_horizon = a.long_horizon;
    options.long_from = a.long_from;
    options.cycle_bytes = uint64_t(std::llround(ellicast->cycle_bytes()));
    options.slot_bytes = uint64_t(a.packet_size);
    options.threads = a.threads;  // trials in parallel; each decode and metric on one thread
    options.progress = [bar](double f) { bar->update("trials", f); };
    SurfaceDistanceOptions metric;
    metric.samples = a.samples;
    metric.threshold_percent = a.hole_threshold;
    metric.threads = 1;

    std::vector<const Scheme*> schemes{ellicast.get(), ellicast_repeat.get(), whole.get(),   fec.get(),
                                       mds.get(),      hybrid.get(),          clusters.get()};
    ExperimentResult result;
    std::vector<std::string> plots;
    try {
        result = run_experiment(schemes, surface_metric(mesh, metric), channel_trace(size_t(a.packet_size)), options);
        bar->finish();
        std::filesystem::create_directories(a.output);
        write_trials_csv(result, (std::filesystem::path(a.output) / "trials.csv").string());
        write_summary_csv(result, (std::filesystem::path(a.output) / "summary.csv").string());
        write_overview_csv(result, (std::filesystem::path(a.output) / "overview.csv").string());
        plots = write_plots(result, a.output);
        ReportSetup setup;
        setup.command = reproduce_command(a);
        setup.model = a.model;
        setup.vertices = mesh.positions.size();
        setup.triangles = mesh.triangles.size();
        std::vector<std::string> attrs;
        if (mesh.has_normals()) attrs.push_back("normals");
        if (mesh.has_texcoords()) attrs.push_back("TEXCOORD_0");
        if (mesh.has_colors()) attrs.push_back("COLOR_0");
        for (size_t i = 0; i < attrs.size(); ++i) setup.attributes += (i ? ", " : "") + attrs[i];
        if (attrs.empty()) setup.attributes = "positions only";
        setup.diagonal = bounding_box_diagonal({mesh});
        setup.packet_size = size_t(a.packet_size);
        std::ostringstream channel;
        channel << "Loss models: ";
        for (size_t i = 0; i < a.burst.size(); ++i) channel << (i ? "; " : "") << describe_loss_model(a.burst[i]);
        channel << ". Loss rates " << list(a.loss) << ".";
        setup.channel = channel.str();
        std::ostringstream m;
        m << "the project's surface distance (`ellicast diff`): " << a.samples
          << " area-uniform samples per direction, closest point on the other surface; RMS from the original to the "
             "reconstruction (rms_back in the CSV: the other way), symmetric Hausdorff, and holes = share of the "
             "original's surface farther than "
          << a.hole_threshold << "% of the diagonal from the reconstruction; all in % of the original's bounding-box diagonal.";
        setup.metric = m.str();
        setup.notes.push_back("Draco settings: Edgebreaker, glTF-Transform's quantization (14-bit positions, 10-bit "
                              "normals, 12-bit texture coordinates, 8-bit colours), encoding and decoding speed " +
                              std::to_string(a.draco_speed) + "/" + std::to_string(a.draco_speed) +
                              (a.draco_speed == 0 ? " (the smallest file, as draco_encoder -cl 10; --draco-speed)"
                                                  : " (--draco-speed; 0 gives the smallest file)") +
                              ", the same attributes as ellicast.");
        std::ostringstream fecnote;
        fecnote << "draco-rs-repeat redundancy " << fec->redundancy() << " parity per data packet"
                << (a.fec_redundancy == "auto" ? ": ellicast's repetition overhead (the bytes it spends repeating its base)" : "")
                << "; like every scheme it repeats its packets to fill the cycle.";
        setup.notes.push_back(fecnote.str());
        setup.notes.push_back("draco-mds: blocks of at most " + std::to_string(a.mds_block_data) +
                              " data symbols, each filled with parity to the 255 symbols of GF(2^8), so that a receiver "
                              "gets a new symbol in every slot for " + std::to_string(mds->packets().size()) +
                              " slots; the strongest carousel of the Draco file short of a rateless code.");
        setup.notes.push_back("ellicast: " + std::to_string(a.ellipsoids) + " ellipsoids at most, encoder seed 1, carousel base share " +
                              text(a.base_share) + ", decoder at its default grid.");
        write_report(result, setup, plots, a.output);
    } catch (const std::exception& e) {
        bar->finish();
        return fail(kExitFailure, e.what());
    }

    // A summary on stdout.
    std::printf("compare %s: cycle of %llu bytes, packets of at most %d bytes, %zu trials per setting\n",
                a.model.c_str(), (unsigned long long)options.cycle_bytes, a.packet_size, a.trials);
    std::printf("%-16s %9s %12s %14s  %s\n", "scheme", "packets", "bytes once", "bytes/cycle", "with every packet");
    for (const auto& s : result.schemes)
        std::printf("%-16s %9zu %12llu %14llu  RMS %.4f%%, holes %.2f%%\n", s.name.c_str(), s.packets,
                    (unsigned long long)s.packet_bytes, (unsigned long long)s.cycle_bytes, s.complete.rms, s.complete.holes);
    for (double burst : result.options.bursts) {
        std::printf("%s: cycles to a first picture (median / p90) and to full quality (median)\n",
                    burst <= 1 ? "independent loss" : ("burst " + text(burst)).c_str());
        std::printf("%6s", "loss");
        for (const auto& s : result.schemes) std::printf(" | %-24s", s.name.c_str());
        std::printf("\n");
        for (double loss : result.options.loss_rates) {
            std::printf("%5.0f%%", 100 * loss);
            for (size_t s = 0; s < result.schemes.size(); ++s) {
                const EventSummary f = summarize_events(result, s, loss, burst, false);
                const EventSummary q = summarize_events(result, s, loss, burst, true);
                auto c = [](double t) { return std::isnan(t) ? std::string("never") : text(std::round(t * 100) / 100); };
                std::printf(" | %-24s", (c(f.median) + " / " + c(f.p90) + " -> " + c(q.median)).c_str());
            }
            std::printf("\n");
        }
        std::printf("after one cycle, %s: shown share / median RMS %% / median holes %%\n",
                    burst <= 1 ? "independent loss" : ("burst " + std::to_string(burst)).c_str());
        std::printf("%6s", "loss");
        for (const auto& s : result.schemes) std::printf(" | %-24s", s.name.c_str());
        std::printf("\n");
        for (double loss : result.options.loss_rates) {
            std::printf("%5.0f%%", 100 * loss);
            for (size_t s = 0; s < result.schemes.size(); ++s) {
                Cell c = summarize(result, s, loss, burst, 1.0);
                char buf[64];
                std::snprintf(buf, sizeof buf, "%3.0f%% / %.3f / %.1f", 100 * c.shown_share, c.rms_median, c.holes_median);
                std::printf(" | %-24s", buf);
            }
            std::printf("\n");
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %s/report.md, trials.csv, summary.csv and %zu plots (SVG + PNG) in %.1f s\n", a.output.c_str(),
                plots.size(), seconds);
    return kExitOk;
}

RegisterCommand reg{{80, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<CompareArgs>();
    auto* cmd = app.add_subcommand("compare", "Compare ellicast with Draco baselines under identical packet loss");
    cmd->add_option("model", args->model, "Model to send (glTF, OBJ, PLY, OFF, STL)")->required();
    cmd->add_option("-o,--output", args->output, "Directory for report.md, CSVs and plots")->required();
    cmd->add_option("--loss", args->loss, "Loss rates, comma-separated")->delimiter(',')->capture_default_str();
    cmd->add_option("--burst", args->burst,
                    "Mean burst lengths in packets, comma-separated (0: independent loss; > 1: Gilbert-Elliott)")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--trials", args->trials, "Trials per setting")->capture_default_str();
    cmd->add_option("--seed", args->seed, "Seed of the loss traces and tune-in times")->capture_default_str();
    cmd->add_option("--curve-trials", args->curve_trials,
                    "Of the trials, how many also measure the error on the time grid (the costly part)")
        ->capture_default_str();
    cmd->add_option("--steps-per-cycle", args->steps, "Points of the time grid per cycle")->capture_default_str();
    cmd->add_option("--horizon", args->horizon, "Cycles after tune-in simulated below --long-from loss")->capture_default_str();
    cmd->add_option("--long-horizon", args->long_horizon, "Cycles after tune-in simulated from --long-from loss on")
        ->capture_default_str();
    cmd->add_option("--long-from", args->long_from, "Loss rate from which the long horizon applies")->capture_default_str();
    cmd->add_option("--mds-block-data", args->mds_block_data,
                    "draco-mds: data symbols per block at most (each block has 255 symbols)")
        ->capture_default_str();
    cmd->add_option("--draco-speed", args->draco_speed,
                    "Draco baselines: encoding and decoding speed, 0 (smallest file, what a broadcaster encoding "
                    "offline picks) .. 10 (fastest)")
        ->capture_default_str();
    cmd->add_option("--packet-size", args->packet_size, "Packet size in bytes, the same for every scheme")->capture_default_str();
    cmd->add_option("--ellipsoids", args->ellipsoids, "ellicast: ellipsoids at most")->capture_default_str();
    cmd->add_option("--base-share", args->base_share, "ellicast carousel: share of the cycle spent on the base")
        ->capture_default_str();
    cmd->add_option("--point-share", args->point_share,
                    "ellicast: share of the vertices sent as points, the exact layer carrying the others (format 1.11; "
                    "1: every vertex a point)")
        ->capture_default_str();
    cmd->add_option("--rs-redundancy", args->fec_redundancy,
                    "draco-rs-repeat: parity packets per data packet, or 'auto' (ellicast's repetition overhead)")
        ->capture_default_str();
    cmd->add_option("--samples", args->samples, "Metric: surface samples per direction")->capture_default_str();
    cmd->add_option("--hole-threshold", args->hole_threshold,
                    "Metric: distance (% of the diagonal) beyond which the original's surface counts as missing")
        ->capture_default_str();
    cmd->add_option("--threads", args->threads, "Threads for the encoder and the trials")->capture_default_str();
    cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
    cmd->add_flag("--allow-external-paths", args->allow_external_paths,
                  "read glTF buffers and images outside the model's folder (refused by default)");
    cmd->callback([args, &exit_code]() { exit_code = run_compare(*args); });
}}};

}  // namespace

}  // namespace ellicast::cli

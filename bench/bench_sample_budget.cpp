// What surface samples buy a receiver, and what they cost it: one model encoded with several sample
// budgets (EncodeOptions::sample_budget, samples per original vertex), each sent by the carousel at
// the same byte rate through the same loss traces (the comparison's experiment, compare/), and the
// error a viewer sees after tune-in.
//
//   bench_sample_budget MODEL [--budgets -1,0,0.25,1] [--loss 0.5] [--trials 12] [--horizon 4]
//
// Time is counted in cycles of the first budget's carousel (by default -1, the samples without a
// budget: the longest stream), so every row is on one clock. A sample only serves a receiver whose
// exact layer is not whole yet; it also makes every cycle longer, which delays the exact layer of
// every receiver. The table shows both: the error at fixed times, and when the exact model comes.
#include "ellicast/compare/channel_trace.h"
#include "ellicast/compare/ellicast_scheme.h"
#include "ellicast/compare/experiment.h"
#include "ellicast/compare/metric.h"
#include "ellicast/compare/schemes.h"
#include "ellicast/converters/mesh_input.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

using namespace ellicast;
using namespace ellicast::compare;

namespace {

std::vector<double> parse_list(const std::string& text) {
    std::vector<double> out;
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ',')) out.push_back(std::stod(item));
    return out;
}

int usage() {
    std::fprintf(stderr,
                 "usage: bench_sample_budget MODEL [--budgets -1,0,0.25,1] [--loss 0.5] [--trials 12] [--horizon 4]\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    const std::string model = argv[1];
    std::vector<double> budgets{-1, 0, 0.25, 1};
    double loss = 0.5, horizon = 4;
    size_t trials = 12;
    try {
        for (int i = 2; i < argc; ++i) {
            const std::string a = argv[i];
            if (i + 1 >= argc) return usage();
            const std::string v = argv[++i];
            if (a == "--budgets") budgets = parse_list(v);
            else if (a == "--loss") loss = std::stod(v);
            else if (a == "--trials") trials = std::stoul(v);
            else if (a == "--horizon") horizon = std::stod(v);
            else return usage();
        }
    } catch (const std::exception&) {
        return usage();
    }
    if (budgets.empty() || !(loss >= 0 && loss < 1) || trials < 1 || trials > 1000 || !(horizon >= 1 && horizon <= 100))
        return usage();

    std::vector<Mesh> surfaces;
    try {
        for (auto& m : load_meshes(model).meshes)
            if (!m.is_point_set && !m.triangles.empty()) surfaces.push_back(std::move(m));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", model.c_str(), e.what());
        return 1;
    }
    if (surfaces.empty()) {
        std::fprintf(stderr, "%s: no triangle mesh\n", model.c_str());
        return 1;
    }
    const Mesh mesh = surfaces.size() == 1 ? surfaces[0] : concatenate(surfaces);

    std::vector<std::unique_ptr<EllicastScheme>> schemes;
    std::vector<const Scheme*> list;
    for (double b : budgets) {
        EllicastSettings es;
        es.encode.sample_budget = b;
        es.encode.seed = 1;
        std::ostringstream name;
        name << "budget " << b;
        es.name = name.str();
        std::fprintf(stderr, "bench_sample_budget: encoding with %s\n", es.name.c_str());
        try {
            schemes.push_back(std::make_unique<EllicastScheme>(mesh, es));
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", model.c_str(), e.what());
            return 1;
        }
        list.push_back(schemes.back().get());
    }

    ExperimentOptions options;
    options.loss_rates = {loss};
    options.bursts = {0};
    options.trials = trials;
    options.curve_trials = trials;
    options.steps_per_cycle = 16;
    options.horizon = horizon;
    options.long_horizon = horizon;
    options.cycle_bytes = uint64_t(std::llround(schemes[0]->cycle_bytes()));
    options.slot_bytes = 1200;
    options.threads = 2;
    size_t last = 0;
    options.progress = [&last](double f) {
        const size_t percent = size_t(f * 100);
        if (percent >= last + 10) std::fprintf(stderr, "bench_sample_budget: trials %zu%%\n", last = percent);
    };
    SurfaceDistanceOptions metric;
    metric.samples = 20000;
    metric.threshold_percent = 0.5;
    metric.threads = 1;
    const ExperimentResult result = run_experiment(list, surface_metric(mesh, metric), channel_trace(1200), options);

    std::printf("%s, %zu vertices, %zu triangles; loss %.0f%% (independent), %zu trials; time in cycles of the "
                "first row's carousel (%llu bytes)\n",
                model.c_str(), mesh.positions.size(), mesh.triangles.size(), 100 * loss, trials,
                (unsigned long long)options.cycle_bytes);
    const std::vector<double> times{0.125, 0.25, 0.5, 1, 2, horizon};
    std::printf("| budget | points | bytes once | cycle bytes | first picture (median) | exact model (median / p90) |");
    for (double t : times) std::printf(" RMS at %g |", t);
    std::printf("\n|---|---:|---:|---:|---:|---:|");
    for (size_t i = 0; i < times.size(); ++i) std::printf("---:|");
    std::printf("\n");
    auto when = [](double v) {
        char buf[32];
        if (std::isnan(v)) return std::string("never");
        std::snprintf(buf, sizeof buf, "%.2f", v);
        return std::string(buf);
    };
    for (size_t s = 0; s < schemes.size(); ++s) {
        const auto first = summarize_events(result, s, loss, 0, false);
        const auto full = summarize_events(result, s, loss, 0, true);
        std::printf("| %g | %zu | %llu | %.0f | %s | %s / %s |", budgets[s], schemes[s]->points(),
                    (unsigned long long)result.schemes[s].packet_bytes, schemes[s]->cycle_bytes(),
                    when(first.median).c_str(), when(full.median).c_str(), when(full.p90).c_str());
        for (double t : times) {
            const Cell c = summarize(result, s, loss, 0, t);
            std::printf(" %.4f%% |", c.error_median);
        }
        std::printf("\n");
    }
    return 0;
}

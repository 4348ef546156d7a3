// The robustness comparison: Draco baselines, the erasure code, the experiment and its report.
#include "support.h"

#include "ellicast/compare/channel_trace.h"
#include "ellicast/compare/ellicast_scheme.h"
#include "ellicast/compare/erasure_code.h"
#include "ellicast/compare/experiment.h"
#include "ellicast/compare/metric.h"
#include "ellicast/compare/report.h"
#include "ellicast/compare/schemes.h"
#include "ellicast/converters/mesh_input.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>

using namespace ellicast;
using namespace ellicast::compare;

namespace {

Mesh load_sample(const std::string& relative) {
    auto result = load_meshes((test::shared_samples() / relative).string());
    REQUIRE(result.meshes.size() == 1);
    return result.meshes[0];
}

std::vector<uint32_t> all_but(size_t count, std::vector<uint32_t> missing) {
    std::vector<uint32_t> held;
    for (uint32_t i = 0; i < count; ++i)
        if (std::find(missing.begin(), missing.end(), i) == missing.end()) held.push_back(i);
    return held;
}

}  // namespace

TEST_CASE("the erasure code recovers the data exactly from any m losses of a block and fails with m + 1") {
    const int k = 12, m = 4;
    ErasureCode code(k, m);
    std::mt19937 rng(7);
    std::vector<std::vector<uint8_t>> data(k, std::vector<uint8_t>(97));
    for (auto& d : data)
        for (auto& b : d) b = uint8_t(rng());
    auto parity = code.encode(data);
    REQUIRE(parity.size() == size_t(m));
    std::vector<std::vector<uint8_t>> shards = data;
    shards.insert(shards.end(), parity.begin(), parity.end());

    for (int trial = 0; trial < 200; ++trial) {
        std::vector<int> order(k + m);
        std::iota(order.begin(), order.end(), 0);
        std::shuffle(order.begin(), order.end(), rng);
        const int lose = trial % (m + 2);  // 0..m+1 losses
        auto received = shards;
        for (int i = 0; i < lose; ++i) received[order[i]].clear();
        std::vector<std::vector<uint8_t>> back;
        if (lose <= m) {
            REQUIRE(code.decode(received, back));
            CHECK(back == data);
        } else {
            CHECK_FALSE(code.decode(received, back));
            CHECK(back.empty());
        }
    }
}

TEST_CASE("an erasure code with more than 255 shards or no data shard is refused with a message") {
    CHECK_THROWS_AS(ErasureCode(200, 56), CompareError);
    CHECK_THROWS_AS(ErasureCode(0, 3), CompareError);
    CHECK_NOTHROW(ErasureCode(200, 55));
}

TEST_CASE("Draco whole decodes only once every packet is held, in any order") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoWhole whole(spot, DracoSettings{}, 1200);
    const size_t n = whole.packets().size();
    REQUIRE(n >= 3);
    for (const auto& p : whole.packets()) CHECK(p.size() <= 1200);
    Mesh out;
    REQUIRE(whole.reconstruct(all_but(n, {}), out));
    CHECK(out.triangles.size() == spot.triangles.size());
    CHECK(out.has_texcoords());  // the same attributes as the input
    for (uint32_t missing = 0; missing < n; ++missing) CHECK_FALSE(whole.reconstruct(all_but(n, {missing}), out));
    CHECK_FALSE(whole.reconstruct({}, out));
}

TEST_CASE("Draco + erasure code decodes from any k of its packets and not from fewer") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoFec fec(spot, DracoSettings{}, 1200, 0.5);
    REQUIRE(fec.blocks().size() == 1);
    const size_t k = fec.data_shards(), m = fec.parity_shards();
    CHECK(m == (k + 1) / 2);
    CHECK(fec.packets().size() == k + m);
    DracoWhole whole(spot, DracoSettings{}, 1200);
    CHECK(fec.draco_bytes() == whole.draco_bytes());  // the same Draco bytes, protected
    std::mt19937 rng(3);
    Mesh out;
    for (int trial = 0; trial < 10; ++trial) {
        std::vector<uint32_t> order(k + m);
        std::iota(order.begin(), order.end(), 0u);
        std::shuffle(order.begin(), order.end(), rng);
        std::vector<uint32_t> held(order.begin(), order.begin() + k);
        std::sort(held.begin(), held.end());
        REQUIRE(fec.reconstruct(held, out));
        CHECK(out.triangles.size() == spot.triangles.size());
        held.pop_back();
        CHECK_FALSE(fec.reconstruct(held, out));
    }
}

TEST_CASE("Draco clusters each fit one packet, decode alone, and together give back every triangle") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoClusters clusters(spot, DracoSettings{}, 1200);
    const size_t n = clusters.cluster_count();
    REQUIRE(n > 4);
    size_t triangles = 0;
    for (uint32_t i = 0; i < n; ++i) {
        CHECK(clusters.packets()[i].size() <= 1200);
        Mesh alone;
        REQUIRE(clusters.reconstruct({i}, alone));
        CHECK(alone.triangles.size() == clusters.cluster_triangles()[i].size());
        triangles += alone.triangles.size();
    }
    CHECK(triangles == spot.triangles.size());
    CHECK(clusters.mean_fill() > 0.5);
    // A lost packet is a hole: the others still decode.
    Mesh most;
    REQUIRE(clusters.reconstruct(all_but(n, {0}), most));
    CHECK(most.triangles.size() == spot.triangles.size() - clusters.cluster_triangles()[0].size());
}

TEST_CASE("a damaged baseline packet is rejected by its checksum") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoClusters clusters(spot, DracoSettings{}, 600);
    auto packet = clusters.packets()[0];
    CHECK_FALSE(baseline_payload(packet, kDracoClusterType).empty());
    packet[packet.size() / 2] ^= 0x10;
    CHECK(baseline_payload(packet, kDracoClusterType).empty());
}

namespace {

// A stand-in metric for the experiment's own tests: the share of the original's triangles missing.
MeasureFn triangle_share_metric(size_t original_triangles) {
    return [original_triangles](const Mesh& m) {
        Distance d;
        d.holes = 100.0 * (1.0 - std::min(1.0, double(m.triangles.size()) / double(original_triangles)));
        d.rms = d.holes / 100.0;
        d.hausdorff = d.rms;
        return d;
    };
}

std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("the experiment gives the same CSV for the same seed, whatever the thread count") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoWhole whole(spot, DracoSettings{}, 600);
    DracoClusters clusters(spot, DracoSettings{}, 600);
    std::vector<const Scheme*> schemes{&whole, &clusters};
    ExperimentOptions options;
    options.loss_rates = {0, 0.3};
    options.time_loss_rates = {0.3};
    options.times = {0.5, 1, 2};
    options.trials = 3;
    options.cycle_bytes = 2 * clusters.period_bytes();
    options.slot_bytes = 600;
    options.seed = 11;
    auto dir = test::scratch_dir("compare_determinism");
    auto a = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(600), options);
    options.threads = 2;
    auto b = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(600), options);
    write_trials_csv(a, (dir / "a.csv").string());
    write_trials_csv(b, (dir / "b.csv").string());
    CHECK(read_text(dir / "a.csv") == read_text(dir / "b.csv"));
    options.seed = 12;
    auto c = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(600), options);
    write_trials_csv(c, (dir / "c.csv").string());
    CHECK(read_text(dir / "a.csv") != read_text(dir / "c.csv"));

    // Every scheme sends the same bytes per cycle (up to the packet that straddles the cycle's end).
    for (const auto& s : a.schemes) {
        CHECK(s.cycle_bytes >= options.cycle_bytes);
        CHECK(s.cycle_bytes < options.cycle_bytes + 600);
    }
    // Every scheme of a trial loses the very same slots; without loss every scheme shows everything.
    for (const auto& r : a.trials) {
        for (const auto& s : a.trials)
            if (s.trial == r.trial && s.loss == r.loss && s.time == r.time) {
                CHECK(s.trace_loss == r.trace_loss);
                CHECK(s.tune_in == r.tune_in);
            }
        if (r.loss == 0 && r.time >= 1) {
            CHECK(r.shown);
            CHECK(r.distance.holes == doctest::Approx(0));
        }
    }
    // At 30% loss the clusters scheme shows something with holes; Draco whole rarely completes in one cycle.
    Cell lossy = summarize(a, 1, 0.3, 0, 1.0);
    CHECK(lossy.trials == 3);
    CHECK(lossy.shown_share == 1.0);
    CHECK(lossy.holes_median > 0);
}

TEST_CASE("the report writes the CSVs, SVG and PNG plots and a Markdown report that starts with the command") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoWhole whole(spot, DracoSettings{}, 1200);
    DracoFec fec(spot, DracoSettings{}, 1200, 0.2);
    std::vector<const Scheme*> schemes{&whole, &fec};
    ExperimentOptions options;
    options.loss_rates = {0, 0.1};
    options.time_loss_rates = {0.1};
    options.times = {1, 2};
    options.trials = 2;
    options.cycle_bytes = fec.period_bytes() + 2400;
    auto result = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(1200), options);
    auto dir = test::scratch_dir("compare_report");
    write_trials_csv(result, (dir / "trials.csv").string());
    write_summary_csv(result, (dir / "summary.csv").string());
    auto plots = write_plots(result, dir.string());
    ReportSetup setup;
    setup.command = "ellicast compare spot.obj --trials 2 -o out";
    setup.model = "spot.obj";
    write_report(result, setup, plots, dir.string());
    REQUIRE(plots.size() == 2);
    for (const auto& p : plots) {
        CHECK(std::filesystem::file_size(dir / (p + ".svg")) > 1000);
        CHECK(std::filesystem::file_size(dir / (p + ".png")) > 1000);
    }
    const std::string md = read_text(dir / "report.md");
    CHECK(md.find("ellicast compare spot.obj --trials 2 -o out") < 200);
    CHECK(md.find("| draco-fec |") != std::string::npos);
    // 1 header + 2 schemes x (2 losses at one cycle + 1 extra time at 10%) lines... counted exactly:
    const std::string csv = read_text(dir / "trials.csv");
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 2 * 2 * (1 + 2));
}

TEST_CASE("the experiment's metric counts the surface of lost clusters as holes") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoClusters clusters(spot, DracoSettings{}, 1200);
    SurfaceDistanceOptions options;
    options.samples = 20000;
    options.threads = 1;
    MeasureFn measure = surface_metric(spot, options);
    std::vector<uint32_t> every(clusters.cluster_count());
    std::iota(every.begin(), every.end(), 0u);
    Mesh whole;
    REQUIRE(clusters.reconstruct(every, whole));
    Distance full = measure(whole);
    CHECK(full.holes == doctest::Approx(0));
    CHECK(full.rms < 0.01);  // 14-bit quantization only

    // Every other cluster lost: the holes are the lost clusters' share of the area.
    auto area = [&](uint32_t t) {
        const auto& a = spot.positions[spot.triangles[t][0]];
        const auto& b = spot.positions[spot.triangles[t][1]];
        const auto& c = spot.positions[spot.triangles[t][2]];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
        return 0.5 * std::sqrt(x * x + y * y + z * z);
    };
    double total = 0, lost = 0;
    std::vector<uint32_t> held;
    for (uint32_t i = 0; i < clusters.cluster_count(); ++i) {
        double a = 0;
        for (uint32_t t : clusters.cluster_triangles()[i]) a += area(t);
        total += a;
        if (i % 2) lost += a;
        else held.push_back(i);
    }
    Mesh half;
    REQUIRE(clusters.reconstruct(held, half));
    Distance d = measure(half);
    // Near a hole's rim the surface is within the threshold of the kept clusters: a bit less than all.
    CHECK(d.holes < 100 * lost / total);
    CHECK(d.holes > 0.6 * 100 * lost / total);
    CHECK(d.rms > full.rms);
}

TEST_CASE("ellicast as a scheme: its carousel's cycle, a surface from the base alone, the model from every packet") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    EllicastSettings settings;
    settings.encode.threads = 1;
    EllicastScheme ellicast(spot, settings);
    REQUIRE(ellicast.base_packets() >= 2);
    REQUIRE(ellicast.point_packets() > 0);
    CHECK(ellicast.period() > ellicast.packets().size());  // the base is repeated within a cycle
    CHECK(ellicast.repetition_overhead() > 0);
    Mesh out;
    CHECK_FALSE(ellicast.reconstruct({}, out));
    // The base alone (stream info and ellipsoids, no point) already gives a surface.
    std::vector<uint32_t> base;
    for (uint32_t i = 0; i < ellicast.base_packets(); ++i) base.push_back(i);
    REQUIRE(ellicast.reconstruct(base, out));
    CHECK(out.triangles.size() > 0);
    CHECK(ellicast.data_fraction(base) == 0);
    // Points without the stream info give nothing to show.
    std::vector<uint32_t> points;
    for (uint32_t i = uint32_t(ellicast.base_packets()); i < ellicast.packets().size(); ++i) points.push_back(i);
    CHECK_FALSE(ellicast.reconstruct(points, out));
    std::vector<uint32_t> every(ellicast.packets().size());
    std::iota(every.begin(), every.end(), 0u);
    REQUIRE(ellicast.reconstruct(every, out));
    CHECK(ellicast.data_fraction(every) == doctest::Approx(1));
}

TEST_CASE("every scheme gets the same bytes per cycle: ellicast's carousel cycle") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    EllicastSettings settings;
    settings.encode.threads = 1;
    EllicastScheme ellicast(spot, settings);
    DracoWhole whole(spot, DracoSettings{}, 1200);
    DracoFec fec(spot, DracoSettings{}, 1200, ellicast.repetition_overhead());
    DracoClusters clusters(spot, DracoSettings{}, 1200);
    ExperimentOptions options;
    options.loss_rates = {0.2};
    options.times = {1};
    options.trials = 1;
    options.cycle_bytes = ellicast.period_bytes();
    SurfaceDistanceOptions metric;
    metric.samples = 2000;
    metric.threads = 1;
    auto result = run_experiment({&ellicast, &whole, &fec, &clusters}, surface_metric(spot, metric), channel_trace(1200), options);
    REQUIRE(result.schemes.size() == 4);
    CHECK(result.schemes[0].cycle_bytes == options.cycle_bytes);
    for (const auto& s : result.schemes) {
        CHECK(s.cycle_bytes >= options.cycle_bytes);
        CHECK(s.cycle_bytes < options.cycle_bytes + 1200);
    }
    // The erasure code spends ellicast's repetition overhead on parity.
    CHECK(double(fec.parity_shards()) >= ellicast.repetition_overhead() * double(fec.data_shards()));
    CHECK(double(fec.parity_shards()) < ellicast.repetition_overhead() * double(fec.data_shards()) + 1);
}

TEST_CASE("ellicast compare writes a report, CSVs and plots, and refuses absurd options") {
    if (!test::have_sample("meshes/spot.obj")) return;
    auto dir = test::scratch_dir("compare_cli");
    const std::string model = (test::shared_samples() / "meshes/spot.obj").string();
    const std::string exe = test::ellicast_exe().string();
    std::string cmd = exe + " compare " + model + " --trials 1 --loss 0,0.5 --times 1 --time-loss 0.5 --samples 2000 --threads 1 -q -o " +
                      (dir / "out").string() + " > " + (dir / "stdout.txt").string() + " 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    for (const char* f : {"report.md", "trials.csv", "summary.csv", "loss_one_cycle.svg", "loss_one_cycle.png",
                          "time_loss50.svg", "time_loss50.png"})
        CHECK_MESSAGE(std::filesystem::exists(dir / "out" / f), f);
    const std::string md = read_text(dir / "out" / "report.md");
    CHECK(md.find("ellicast compare " + model) != std::string::npos);
    CHECK(md.find("| ellicast |") != std::string::npos);
    CHECK(md.find("| draco-clusters |") != std::string::npos);
    CHECK(read_text(dir / "stdout.txt").find("draco-fec") != std::string::npos);

    auto code = [&](const std::string& args) {
        int rc = std::system((exe + " compare " + args + " > /dev/null 2>&1").c_str());
        return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    };
    CHECK(code(model + " --loss 1.5 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --trials 0 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --packet-size 20 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --fec-redundancy lots -o " + (dir / "bad").string()) == 2);
    CHECK(code((dir / "missing.obj").string() + " -o " + (dir / "bad").string()) == 3);
    CHECK_FALSE(std::filesystem::exists(dir / "bad"));
}

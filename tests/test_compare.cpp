// The robustness comparison: Draco baselines, the erasure code, the experiment and its report.
#include "support.h"

#include "ellicast/compare/channel_trace.h"
#include "ellicast/compare/ellicast_scheme.h"
#include "ellicast/compare/hybrid_scheme.h"
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

TEST_CASE("Draco + a repeated erasure code decodes from any k of its packets and not from fewer") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoRsRepeat fec(spot, DracoSettings{}, 1200, 0.5);
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
        CHECK(fec.decodable(held));
        held.pop_back();
        CHECK_FALSE(fec.reconstruct(held, out));
        CHECK_FALSE(fec.decodable(held));
    }
}

TEST_CASE("Draco MDS: every block is 255 symbols, decodes from any k of each block and not from k - 1") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoWhole whole(spot, DracoSettings{}, 1200);
    for (int max_data : {DracoMds::kDefaultBlockData, 4}) {
        CAPTURE(max_data);
        DracoMds mds(spot, DracoSettings{}, 1200, max_data);
        CHECK(mds.draco_bytes() == whole.draco_bytes());
        const auto& blocks = mds.blocks();
        REQUIRE(!blocks.empty());
        if (max_data == 4) CHECK(blocks.size() == (mds.data_shards() + 3) / 4);
        else CHECK(blocks.size() == 1);
        for (const auto& b : blocks) {
            CHECK(b.data + b.parity == 255);
            CHECK(b.data <= max_data);
        }
        CHECK(mds.packets().size() == 255 * blocks.size());
        for (const auto& p : mds.packets()) CHECK(p.size() <= 1200);
        // The schedule: no symbol of a block comes twice before all 255 have come once.
        std::vector<std::vector<int>> seen(blocks.size(), std::vector<int>(255, 0));
        for (uint64_t n = 0; n < mds.period(); ++n) {
            auto [b, s] = mds.shard_of(mds.packet_at(n));
            REQUIRE(b >= 0);
            CHECK(++seen[size_t(b)][size_t(s)] == 1);
        }
        // Any k of each block decode; k - 1 of one block do not.
        std::mt19937 rng(5 + max_data);
        Mesh out;
        for (int trial = 0; trial < 6; ++trial) {
            std::vector<std::vector<uint32_t>> by_block(blocks.size());
            for (uint32_t i = 0; i < mds.packets().size(); ++i) by_block[size_t(mds.shard_of(i).first)].push_back(i);
            std::vector<uint32_t> held;
            for (size_t b = 0; b < blocks.size(); ++b) {
                std::shuffle(by_block[b].begin(), by_block[b].end(), rng);
                held.insert(held.end(), by_block[b].begin(), by_block[b].begin() + blocks[b].data);
            }
            std::sort(held.begin(), held.end());
            REQUIRE(mds.reconstruct(held, out));
            CHECK(out.triangles.size() == spot.triangles.size());
            CHECK(mds.can_show(held));
            CHECK(mds.complete(held));
            const size_t drop = size_t(rng()) % blocks.size();
            held.erase(std::find(held.begin(), held.end(), by_block[drop][0]));
            CHECK_FALSE(mds.reconstruct(held, out));
            CHECK_FALSE(mds.can_show(held));
            CHECK(mds.outcome_key(held) != mds.outcome_key(all_but(mds.packets().size(), {})));
        }
    }
    CHECK_THROWS_AS(DracoMds(spot, DracoSettings{}, 1200, 255), CompareError);
    CHECK_THROWS_AS(DracoMds(spot, DracoSettings{}, 1200, 0), CompareError);
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
    options.bursts = {0};
    options.steps_per_cycle = 4;
    options.horizon = 2;
    options.long_horizon = 3;
    options.trials = 6;
    options.curve_trials = 3;
    options.cycle_bytes = 2 * clusters.period_bytes();
    options.slot_bytes = 600;
    options.seed = 11;
    auto dir = test::scratch_dir("compare_determinism");
    auto a = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(600), options);
    options.threads = 2;
    auto b = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(600), options);
    write_trials_csv(a, (dir / "a.csv").string());
    write_trials_csv(b, (dir / "b.csv").string());
    write_summary_csv(a, (dir / "a_summary.csv").string());
    write_summary_csv(b, (dir / "b_summary.csv").string());
    CHECK(read_text(dir / "a.csv") == read_text(dir / "b.csv"));
    CHECK(read_text(dir / "a_summary.csv") == read_text(dir / "b_summary.csv"));
    options.seed = 12;
    auto c = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(600), options);
    write_trials_csv(c, (dir / "c.csv").string());
    CHECK(read_text(dir / "a.csv") != read_text(dir / "c.csv"));
    // Every trial has its events for every scheme; the curve trials have every grid time, and Draco
    // whole (two outcomes: decodable or not) is on the grid in every trial.
    CHECK(a.events.size() == 2 * 2 * 6);
    CHECK(a.trials.size() == 2 * (6 + 3) * 8);
    CHECK(summarize(a, 0, 0.3, 0, 1.0).trials == 6);
    CHECK(summarize(a, 1, 0.3, 0, 1.0).trials == 3);

    // Every scheme sends the same bytes per cycle (up to the packet that straddles the cycle's end).
    for (const auto& s : a.schemes) {
        CHECK(s.cycle_bytes >= options.cycle_bytes);
        CHECK(s.cycle_bytes < options.cycle_bytes + 600);
    }
    // Every scheme of a trial loses the very same slots; without loss every scheme shows everything.
    for (const auto& e : a.events)
        for (const auto& f : a.events)
            if (f.trial == e.trial && f.loss == e.loss) {
                CHECK(f.trace_loss == e.trace_loss);
                CHECK(f.tune_in == e.tune_in);
            }
    for (const auto& r : a.trials) {
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
    DracoRsRepeat fec(spot, DracoSettings{}, 1200, 0.2);
    std::vector<const Scheme*> schemes{&whole, &fec};
    ExperimentOptions options;
    options.loss_rates = {0, 0.1};
    options.bursts = {0};
    options.horizon = 2;
    options.trials = 2;
    options.curve_trials = 2;
    options.cycle_bytes = fec.period_bytes() + 2400;
    auto result = run_experiment(schemes, triangle_share_metric(spot.triangles.size()), channel_trace(1200), options);
    auto dir = test::scratch_dir("compare_report");
    write_trials_csv(result, (dir / "trials.csv").string());
    write_summary_csv(result, (dir / "summary.csv").string());
    write_overview_csv(result, (dir / "overview.csv").string());
    auto plots = write_plots(result, dir.string());
    ReportSetup setup;
    setup.command = "ellicast compare spot.obj --trials 2 -o out";
    setup.model = "spot.obj";
    write_report(result, setup, plots, dir.string());
    CHECK(plots == std::vector<std::string>{"loss_one_cycle", "error_time", "first_picture", "lead_map"});
    for (const auto& p : plots) {
        CHECK(std::filesystem::file_size(dir / (p + ".svg")) > 1000);
        CHECK(std::filesystem::file_size(dir / (p + ".png")) > 1000);
    }
    const std::string md = read_text(dir / "report.md");
    CHECK(md.find("ellicast compare spot.obj --trials 2 -o out") < 200);
    CHECK(md.find("| draco-rs-repeat |") != std::string::npos);
    CHECK(md.find("### Which scheme leads") != std::string::npos);
    for (const auto& p : plots) CHECK(md.find("(" + p + ".png)") != std::string::npos);
    // 1 header + 2 schemes x 2 losses x 2 trials; the curves: 2 schemes x 2 losses x 32 grid times.
    const std::string csv = read_text(dir / "trials.csv");
    CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 2 * 2 * 2);
    const std::string summary = read_text(dir / "summary.csv");
    CHECK(std::count(summary.begin(), summary.end(), '\n') == 1 + 2 * 2 * 32);
    const std::string overview = read_text(dir / "overview.csv");
    CHECK(std::count(overview.begin(), overview.end(), '\n') == 1 + 2 * 2);
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

TEST_CASE("ellicast with repair packets: any k packets of a block give all its points, without, every packet is needed") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    EllicastSettings settings;
    settings.encode.threads = 1;
    EllicastScheme repaired(spot, settings);
    settings.repair_ratio = 0;
    settings.name = "ellicast-repeat";
    EllicastScheme repeated(spot, settings);
    CHECK(repaired.name() == "ellicast");
    CHECK(repeated.name() == "ellicast-repeat");
    // Packets by type: the base, POINTS and their repairs, and the exact layer (format 1.3) and its repairs.
    auto count = [](const EllicastScheme& s, PacketType type) {
        return size_t(std::count_if(s.packets().begin(), s.packets().end(),
                                    [&](const auto& p) { return p[6] == uint8_t(type); }));
    };
    const size_t points = count(repaired, PacketType::Points) + count(repaired, PacketType::MappedPoints), pieces = count(repaired, PacketType::Connectivity);
    REQUIRE(points > 0);
    REQUIRE(pieces > 0);
    CHECK(count(repaired, PacketType::PointsRepair) == points);  // one repair per POINTS packet
    CHECK(count(repaired, PacketType::ConnectivityRepair) == pieces);
    CHECK(count(repeated, PacketType::PointsRepair) == 0);
    CHECK(count(repeated, PacketType::ConnectivityRepair) == 0);
    CHECK(count(repeated, PacketType::Connectivity) == pieces);
    // The period is two cycles with repair, one without; a cycle costs the same bytes but for the
    // exact layer's repair packets, which go once a cycle.
    size_t layer_repair_bytes = 0;
    for (const auto& p : repaired.packets())
        if (p[6] == uint8_t(PacketType::ConnectivityRepair)) layer_repair_bytes += p.size();
    CHECK(repaired.period_bytes() > 1.9 * repaired.cycle_bytes());
    CHECK(repeated.period_bytes() == doctest::Approx(repeated.cycle_bytes()));
    // (2%: the STREAM_INFO parts repeated inside chunks follow the count of data packets, which weigh
    // more next to format 1.7's smaller point packets.)
    CHECK(repaired.cycle_bytes() == doctest::Approx(repeated.cycle_bytes() + double(layer_repair_bytes)).epsilon(0.02));
    // The base, the POINTS_REPAIR packets and the exact layer's repairs alone: every point, and exact.
    std::vector<uint32_t> held;
    for (uint32_t i = 0; i < repaired.packets().size(); ++i) {
        const uint8_t type = repaired.packets()[i][6];
        if (!is_points_type(type) && type != uint8_t(PacketType::Connectivity)) held.push_back(i);
    }
    CHECK(repaired.complete(held));
    CHECK(repaired.data_fraction(held) == doctest::Approx(1));
    Mesh out;
    REQUIRE(repaired.reconstruct(held, out));
    // One POINTS_REPAIR fewer: not complete, and no point is held (none of the POINTS packets arrived).
    for (size_t k = held.size(); k-- > 0;)
        if (repaired.packets()[held[k]][6] == uint8_t(PacketType::PointsRepair)) {
            held.erase(held.begin() + long(k));
            break;
        }
    CHECK_FALSE(repaired.complete(held));
    CHECK(repaired.data_fraction(held) == 0);
    // Without repair, every POINTS packet is needed.
    std::vector<uint32_t> all_but_one(repeated.packets().size() - 1);
    std::iota(all_but_one.begin(), all_but_one.end(), 0u);
    CHECK_FALSE(repeated.complete(all_but_one));
}

TEST_CASE("every scheme gets the same bytes per cycle: ellicast's carousel cycle") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    EllicastSettings settings;
    settings.encode.threads = 1;
    EllicastScheme ellicast(spot, settings);
    DracoWhole whole(spot, DracoSettings{}, 1200);
    DracoRsRepeat fec(spot, DracoSettings{}, 1200, ellicast.repetition_overhead());
    DracoMds mds(spot, DracoSettings{}, 1200);
    DracoClusters clusters(spot, DracoSettings{}, 1200);
    ExperimentOptions options;
    options.loss_rates = {0.2};
    options.bursts = {0};
    options.horizon = 1;
    options.steps_per_cycle = 2;
    options.trials = 1;
    options.curve_trials = 1;
    options.cycle_bytes = uint64_t(std::llround(ellicast.cycle_bytes()));
    SurfaceDistanceOptions metric;
    metric.samples = 2000;
    metric.threads = 1;
    auto result = run_experiment({&ellicast, &whole, &fec, &mds, &clusters}, surface_metric(spot, metric),
                                 channel_trace(1200), options);
    REQUIRE(result.schemes.size() == 5);
    // ellicast's cycles differ by a few bytes over its two-cycle period (a repair packet is as long as a
    // full POINTS packet); every scheme gets within one packet of its mean cycle.
    for (const auto& s : result.schemes) {
        CHECK(s.cycle_bytes + 1200 > options.cycle_bytes);
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
    std::string cmd = exe + " compare " + model +
                      " --trials 3 --curve-trials 1 --loss 0,0.5 --burst 0 --horizon 1 --long-horizon 2 --steps-per-cycle 4"
                      " --samples 2000 --threads 1 -q -o " +
                      (dir / "out").string() + " > " + (dir / "stdout.txt").string() + " 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    for (const char* f : {"report.md", "trials.csv", "summary.csv", "overview.csv", "loss_one_cycle.svg",
                          "loss_one_cycle.png", "error_time.svg", "error_time.png", "first_picture.png", "lead_map.png"})
        CHECK_MESSAGE(std::filesystem::exists(dir / "out" / f), f);
    const std::string md = read_text(dir / "out" / "report.md");
    CHECK(md.find("ellicast compare " + model) != std::string::npos);
    CHECK(md.find("| ellicast |") != std::string::npos);
    CHECK(md.find("| draco-clusters |") != std::string::npos);
    for (const char* scheme : {"draco-rs-repeat", "draco-mds"}) CHECK(read_text(dir / "stdout.txt").find(scheme) != std::string::npos);

    auto code = [&](const std::string& args) {
        int rc = std::system((exe + " compare " + args + " > /dev/null 2>&1").c_str());
        return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    };
    CHECK(code(model + " --loss 1.5 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --trials 0 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --packet-size 20 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --rs-redundancy lots -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --trials 2 --curve-trials 3 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --mds-block-data 255 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --horizon 0 -o " + (dir / "bad").string()) == 2);
    CHECK(code(model + " --steps-per-cycle 0 -o " + (dir / "bad").string()) == 2);
    CHECK(code((dir / "missing.obj").string() + " -o " + (dir / "bad").string()) == 3);
    CHECK_FALSE(std::filesystem::exists(dir / "bad"));
}

TEST_CASE("without loss, draco-mds shows the exact model after k slots whenever the receiver tunes in") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoMds mds(spot, DracoSettings{}, 1200);
    DracoMds blocks(spot, DracoSettings{}, 1200, 4);  // several blocks of at most 4 data symbols, interleaved
    DracoWhole whole(spot, DracoSettings{}, 1200);
    ExperimentOptions options;
    options.loss_rates = {0};
    options.bursts = {0};
    options.trials = 40;
    options.curve_trials = 0;
    options.horizon = 2;
    options.cycle_bytes = 40 * 1200;
    auto result = run_experiment({&mds, &blocks, &whole}, triangle_share_metric(spot.triangles.size()),
                                 channel_trace(1200), options);
    // A time t means t * cycle + one slot of air time after tune-in (the packet on the air then is missed).
    auto slots = [&](double t) { return t * double(options.cycle_bytes) / 1200.0; };
    const double k = double(mds.data_shards());
    size_t blocks_max = 0;
    for (const auto& b : blocks.blocks()) blocks_max = std::max<size_t>(blocks_max, size_t(b.data));
    REQUIRE(result.events.size() == 3 * 40);
    for (const auto& e : result.events) {
        REQUIRE_FALSE(std::isnan(e.first_picture));
        CHECK(e.first_picture == e.full_quality);
        if (e.scheme == 0) {
            CHECK(slots(e.first_picture) >= k - 1);
            CHECK(slots(e.first_picture) < k);
        } else if (e.scheme == 1) {
            // Equal blocks decode after k slots; unequal ones after at most the largest block's share.
            CHECK(slots(e.first_picture) >= k - 1);
            CHECK(slots(e.first_picture) < double(blocks_max * blocks.blocks().size()));
        } else {
            // Draco whole needs its n packets in sequence: n slots after the first one starts.
            CHECK(slots(e.first_picture) < double(whole.packets().size()) + 1);
        }
    }
    const EventSummary f = summarize_events(result, 0, 0, 0, false);
    CHECK(f.trials == 40);
    CHECK(f.never_share == 0);
    CHECK(f.median <= f.p90);
    CHECK(f.p90 <= f.p99);
}

TEST_CASE("at heavy loss the events summary says 'never' for what did not happen within the horizon") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    DracoWhole whole(spot, DracoSettings{}, 1200);
    ExperimentOptions options;
    options.loss_rates = {0.9};
    options.bursts = {0};
    options.trials = 20;
    options.curve_trials = 2;
    options.long_horizon = 1;
    options.steps_per_cycle = 4;
    options.cycle_bytes = whole.period_bytes();
    auto result = run_experiment({&whole}, triangle_share_metric(spot.triangles.size()), channel_trace(1200), options);
    const EventSummary f = summarize_events(result, 0, 0.9, 0, false);
    CHECK(f.never_share == 1.0);  // 15 packets each through a 10% channel in one period: practically never
    CHECK(std::isnan(f.median));
    const Cell c = summarize(result, 0, 0.9, 0, 1.0);
    CHECK(c.trials == 20);  // two outcomes only: measured on the grid in every trial
    CHECK(c.error_median == 100);  // nothing shown counts as the whole diagonal
    CHECK(std::isnan(time_to_error(result, 0, 0.9, 0, 0.5)));
}

TEST_CASE("ellicast's can_show agrees with its decoder on random sets of packets") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    EllicastSettings settings;
    settings.encode.threads = 1;
    EllicastScheme ellicast(spot, settings);
    std::mt19937 rng(17);
    const size_t n = ellicast.packets().size();
    size_t shown = 0;
    for (int trial = 0; trial < 30; ++trial) {
        std::vector<uint32_t> held;
        const double keep = 0.05 + 0.03 * trial;
        for (uint32_t i = 0; i < n; ++i)
            if (std::uniform_real_distribution<double>(0, 1)(rng) < keep) held.push_back(i);
        Mesh out;
        const bool decoded = ellicast.reconstruct(held, out);
        CHECK(ellicast.can_show(held) == decoded);
        shown += decoded ? 1 : 0;
    }
    CHECK(shown > 5);
    CHECK(shown < 30);
}

TEST_CASE("ellipsoids+draco-mds: ellicast's base at its carousel share, Draco symbols elsewhere, the base's surface until Draco decodes") {
    if (!test::have_sample("meshes/spot.obj")) return;
    Mesh spot = load_sample("meshes/spot.obj");
    EllicastSettings settings;
    settings.encode.threads = 1;
    EllicastScheme ellicast(spot, settings);
    DracoMds mds(spot, DracoSettings{}, 1200);
    EllipsoidsDracoMds hybrid(ellicast, mds);
    const size_t nb = hybrid.packets().size() - mds.packets().size();
    REQUIRE(nb >= 2);
    // One period: every ELLIPSOIDS packet equally often, each after a STREAM_INFO part, every Draco
    // symbol as often as in draco-mds's own period.
    std::vector<size_t> sent(hybrid.packets().size(), 0);
    size_t base_sent = 0, ellipsoids_sent = 0;
    uint32_t previous_base = UINT32_MAX;
    for (uint64_t n = 0; n < hybrid.period(); ++n) {
        const uint32_t p = hybrid.packet_at(n);
        ++sent.at(p);
        if (p >= nb) continue;
        ++base_sent;
        if (hybrid.packets()[p][6] == uint8_t(PacketType::Ellipsoids)) {
            ++ellipsoids_sent;
            if (previous_base != UINT32_MAX) CHECK(hybrid.packets()[previous_base][6] == uint8_t(PacketType::StreamInfo));
        }
        previous_base = p;
    }
    CHECK(base_sent == hybrid.base_slots());
    size_t per_ellipsoids = 0;
    for (size_t i = 0; i < nb; ++i)
        if (hybrid.packets()[i][6] == uint8_t(PacketType::Ellipsoids)) {
            if (per_ellipsoids == 0) per_ellipsoids = sent[i];
            CHECK(sent[i] == per_ellipsoids);
        }
    CHECK(per_ellipsoids > 0);
    CHECK(2 * ellipsoids_sent == base_sent);
    for (size_t i = nb; i < sent.size(); ++i) CHECK(sent[i] == 1);
    const double share = double(hybrid.base_slots()) / double(hybrid.period());
    CHECK(std::abs(share - ellicast.base_share()) < double(2 * nb) / double(hybrid.period()) + 0.02);
    // The base alone shows the ellipsoids' surface; the Draco symbols alone, the exact model.
    std::vector<uint32_t> base(nb), draco;
    std::iota(base.begin(), base.end(), 0u);
    for (uint32_t i = uint32_t(nb); i < hybrid.packets().size(); ++i) draco.push_back(i);
    Mesh out;
    CHECK_FALSE(hybrid.can_show({}));
    REQUIRE(hybrid.can_show(base));
    REQUIRE(hybrid.reconstruct(base, out));
    CHECK(out.triangles.size() > 0);
    CHECK_FALSE(hybrid.complete(base));
    REQUIRE(hybrid.complete(draco));
    REQUIRE(hybrid.reconstruct(draco, out));
    CHECK(out.triangles.size() == spot.triangles.size());
    // Once Draco decodes, the base held no longer matters.
    std::vector<uint32_t> both = base;
    both.insert(both.end(), draco.begin(), draco.end());
    CHECK(hybrid.outcome_key(both) == hybrid.outcome_key(draco));
    CHECK(hybrid.outcome_key(base) != hybrid.outcome_key(draco));
}

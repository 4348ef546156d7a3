// The robustness comparison: Draco baselines, the erasure code, the experiment and its report.
#include "support.h"

#include "ellicast/compare/erasure_code.h"
#include "ellicast/compare/schemes.h"
#include "ellicast/converters/mesh_input.h"

#include <algorithm>
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

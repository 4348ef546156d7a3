// Streams a sender can make without breaking a checksum, which once crashed the decoder.
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/format.h"
#include "support.h"

#include <doctest/doctest.h>

using namespace ellicast;
using namespace ellicast::test;

namespace {

ReceivedStream every_packet(const EncodedAsset& encoded) {
    ReceivedStream stream;
    for (size_t i = 0; i < encoded.packets.size(); ++i) REQUIRE(stream.add_packet(encoded.packets[i], i) == Error::Ok);
    return stream;
}

}  // namespace

TEST_CASE("the milk truck decodes on the coarsest grids, where cutting tunnels adds edges while rims are walked") {
    // Filling a tunnel's rim adds edges whose halfedges lay past the marks taken before: a heap
    // write past the end (SIGSEGV at --grid 4, "free(): invalid next size" at --grid 8).
    if (!have_sample("gltf/CesiumMilkTruck/CesiumMilkTruck.gltf")) return;
    const Asset truck = load_asset((shared_samples() / "gltf/CesiumMilkTruck/CesiumMilkTruck.gltf").string());
    EncodeOptions encode;
    encode.max_ellipsoids = 40;
    encode.max_samples = 5000;
    EncodedAsset encoded;
    std::string error;
    REQUIRE_MESSAGE(encode_asset(truck, encode, 1, true, encoded, error), error);
    const ReceivedStream stream = every_packet(encoded);
    for (int grid : {4, 5, 8}) {
        CAPTURE(grid);
        DecodeOptions options;
        options.grid_resolution = grid;
        Asset decoded;
        StreamDecodeReport report;
        REQUIRE_MESSAGE(decode_asset(stream, options, decoded, report, error), error);
        size_t faces = 0;
        for (const auto& o : decoded.objects) faces += o.triangles.size();
        CHECK(faces > 0);
        for (const auto& o : decoded.objects)
            for (const auto& t : o.triangles)
                for (uint32_t v : t) REQUIRE(v < o.positions.size());
    }
}

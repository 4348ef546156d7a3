// Fuzzes what a receiver does with the packets it holds: the decoder (rasterizing, marching cubes,
// point insertion, flips, collapses, normal repair) and the glTF writer, on streams whose payloads the
// fuzzer mutates with valid checksums.
//
// Input: as fuzz_packet (one mode byte, then packets back to back; mode bit 0 reseals each packet's
// CRC-32C so that mutated fields reach the decoders); mode bit 2 writes .gltf + .bin instead of .glb.
//
// Speed (the decoder's work follows its mesh, and under ASan + UBSan + coverage a base of a few
// hundred vertices costs ~10 ms): the decoder's grid budget (spec 13's work bound, DecodeOptions) is
// 64 + 4 nodes per received element instead of 2^18 + 2048, so that the resolution is lowered, down
// to the minimum of 4 cells per frame edge, for nearly every input: every stage still runs, on
// coarse meshes. The receiver's element cap (20000 declared) still takes every conformance vector.
// Run with -max_len=1024 (a few dozen elements; scripts/check-sanitizers.sh adds seeds that fit)
// and -entropic_scale_per_exec_time=1 (inputs that still take long, such as large ellipsoids whose
// grid reaches far past the frame, are mutated less often): about 1,000 inputs/s on one core, not ~25.
#include "fuzz_common.h"

#include <ellicast/codec/decoder.h>
#include <ellicast/converters/asset.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <unistd.h>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace ellicast;
    if (size < 1) return 0;
    const uint8_t mode = data[0];
    ReceivedStream::Limits limits = fuzz::small_limits();
    limits.max_elements = 20000;  // declared ellipsoids + points: every vector fits (at most 14,888)
    ReceivedStream stream(limits);
    uint64_t ordinal = 0;
    // Bit 1 (the datagram length check) is fuzz_packet's business; bit 2 here chooses .gltf.
    fuzz::for_each_datagram(mode & 1, data + 1, size - 1,
                            [&](const std::vector<uint8_t>& datagram) { stream.add_packet(datagram, ordinal++); });
    if (!stream.info()) return 0;
    DecodeOptions options;
    options.base_grid_nodes = 64;  // the grid budget (see the top): small, so that meshes stay coarse
    options.grid_nodes_per_element = 4;
    options.threads = 1;
    std::vector<Mesh> meshes;
    StreamDecodeReport report;
    std::string error;
    decode_stream(stream, options, meshes, report, error);
    for (const Mesh& m : meshes)
        for (const auto& t : m.triangles)
            for (uint32_t v : t)
                if (v >= m.positions.size()) std::abort();  // a face pointing past its vertices
    Asset asset = received_asset(stream, std::move(meshes));
    static const std::string dir = [] {
        const char* shm = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
        return std::string(shm) + "/ellicast_fuzz_decode_" + std::to_string(getpid());
    }();
    const std::string path = dir + ((mode & 4) ? ".gltf" : ".glb");
    std::vector<std::string> warnings;
    if (write_asset(path, asset, AssetWriteOptions{}, warnings, error)) {
        std::remove(path.c_str());
        std::remove((dir + ".bin").c_str());
    }
    return 0;
}

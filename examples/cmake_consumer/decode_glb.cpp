// decode_glb IN.ellc OUT.glb: what `ellicast decode` does, with the installed static C++ libraries
// (ellicast::converters, which brings the codec and the format): read a recording, take its packets
// as a receiver would, rebuild every object and write the scene as GLB.
#include <ellicast/converters/asset.h>
#include <ellicast/converters/asset_stream.h>
#include <ellicast/format.h>

#include <cstdio>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: decode_glb IN.ellc OUT.glb\n");
        return 2;
    }
    std::vector<uint8_t> bytes;
    std::string error;
    if (ellicast::read_file(argv[1], bytes, error) != ellicast::Error::Ok) {
        std::fprintf(stderr, "decode_glb: %s\n", error.c_str());
        return 1;
    }
    const ellicast::ContainerContents contents = ellicast::read_container(bytes);
    ellicast::ReceivedStream stream;
    for (const auto& packet : contents.packets) stream.add_parsed(packet.view, packet.offset);
    ellicast::Asset asset;
    ellicast::StreamDecodeReport report;
    if (!ellicast::decode_asset(stream, {}, asset, report, error)) {
        std::fprintf(stderr, "decode_glb: %s: %s\n", argv[1], error.c_str());
        return 1;
    }
    std::vector<std::string> warnings;
    if (!ellicast::write_asset(argv[2], asset, {}, warnings, error)) {
        std::fprintf(stderr, "decode_glb: %s\n", error.c_str());
        return 1;
    }
    for (const auto& w : warnings) std::fprintf(stderr, "decode_glb: warning: %s\n", w.c_str());
    size_t exact = 0;
    for (const auto& o : report.objects) exact += o.exact;
    std::printf("%s -> %s: %zu objects, %zu exact\n", argv[1], argv[2], report.objects.size(), exact);
    return 0;
}

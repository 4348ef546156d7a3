// count_packets FILE.ellc: the packets of a recorded stream by type, and its damaged regions, with
// nothing but the installed format library (ellicast::format, C++20).
#include <ellicast/format.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: count_packets FILE.ellc\n");
        return 2;
    }
    std::vector<uint8_t> bytes;
    std::string message;
    if (ellicast::read_file(argv[1], bytes, message) != ellicast::Error::Ok) {
        std::fprintf(stderr, "count_packets: %s\n", message.c_str());
        return 1;
    }
    const ellicast::ContainerContents contents = ellicast::read_container(bytes);
    if (contents.header_error != ellicast::Error::Ok) {
        std::fprintf(stderr, "count_packets: %s: %s\n", argv[1], ellicast::error_name(contents.header_error));
        return 1;
    }
    std::map<std::string, size_t> by_type;
    for (const auto& packet : contents.packets) ++by_type[ellicast::packet_type_name(packet.view.header.type)];
    for (const auto& [type, count] : by_type) std::printf("%-20s %zu\n", type.c_str(), count);
    std::printf("%zu packets, %zu damaged regions\n", contents.packets.size(), contents.damaged.size());
    return 0;
}

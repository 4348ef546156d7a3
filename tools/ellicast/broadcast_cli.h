// Shared pieces of the broadcast commands (schedule, simulate, serve, receive): reading a stream
// file into packets, the carousel and channel options, and printing the carousel's figures.
#pragma once

#include <ellicast/broadcast/carousel.h>
#include <ellicast/broadcast/channel.h>

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ellicast::cli {

// Reads every intact packet of a container file. False (with a message naming the file and the
// problem) when the file cannot be read, is not a container, or holds no packet. Damaged regions
// are reported in `warnings` and skipped.
bool load_stream_packets(const std::string& path, std::vector<std::vector<uint8_t>>& packets, std::string& error,
                         std::vector<std::string>& warnings);

struct CarouselCli;

// Loads a stream file (warnings for damaged regions on stderr) and builds its carousel. Returns
// kExitOk, or the exit code after printing the error.
int load_carousel(const std::string& path, const CarouselCli& options, std::vector<std::vector<uint8_t>>& packets,
                  broadcast::Carousel& carousel);

struct CarouselCli {
    size_t chunk = 0;
    double base_share = 0.15;
    size_t min_base_repetitions = broadcast::CarouselOptions{}.min_base_repetitions;
    size_t stream_info_every = broadcast::CarouselOptions{}.stream_info_every;
    double repair_ratio = broadcast::CarouselOptions{}.repair_ratio;
    void add(CLI::App* app);
    broadcast::CarouselOptions options() const;
};

struct ChannelCli {
    double loss = 0;
    double burst = 0;                 // mean burst length (Gilbert model) when > 0
    std::vector<double> gilbert_elliott;  // good_to_bad, bad_to_good, loss_good, loss_bad
    double reorder = 0;
    uint32_t reorder_window = 8;
    double duplicate = 0;
    double bit_errors = 0;
    uint64_t seed = 1;
    std::string trace_in;
    std::string trace_out;
    void add(CLI::App* app, bool with_trace_files);
    // True when any loss, reordering, duplication or bit error was asked for.
    bool active() const;
    // The model from the options; `error` for inconsistent options.
    bool model(broadcast::ChannelModel& out, std::string& error) const;
    // The trace of `slots` slots: read from --trace-in, or drawn from the model. Written to
    // --trace-out when given.
    bool trace(uint64_t slots, size_t packet_bytes, broadcast::LossTrace& out, std::string& error) const;
};

// "12,345" for 12345.
std::string with_commas(uint64_t value);
// "1.20 s" / "850 ms" for a duration in seconds.
std::string seconds_text(double seconds);

// Prints the carousel's shape and figures (overhead, worst-case base wait...), with times at
// `bits_per_second` when it is positive.
void print_carousel(std::FILE* out, const broadcast::Carousel& carousel, double bits_per_second);

}  // namespace ellicast::cli

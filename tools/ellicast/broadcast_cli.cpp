// Shared pieces of the broadcast commands.
#include "broadcast_cli.h"
#include "commands.h"

#include <ellicast/format.h>

#include <cinttypes>
#include <cstdio>

namespace ellicast::cli {

bool load_stream_packets(const std::string& path, std::vector<std::vector<uint8_t>>& packets, std::string& error,
                         std::vector<std::string>& warnings) {
    std::vector<uint8_t> bytes;
    std::string message;
    if (read_file(path, bytes, message) != Error::Ok) {
        error = "cannot read " + path + ": " + message;
        return false;
    }
    ContainerContents contents = read_container(bytes);
    if (contents.header_error != Error::Ok) {
        error = path + " is not an ellicast stream file (" + error_name(contents.header_error) + ")";
        return false;
    }
    for (const auto& region : contents.damaged)
        warnings.push_back(path + ": skipped " + std::to_string(region.length) + " damaged bytes at offset " +
                           std::to_string(region.offset) + " (" + error_name(region.first_error) + ")");
    packets.clear();
    packets.reserve(contents.packets.size());
    for (const auto& p : contents.packets) {
        const uint8_t* start = bytes.data() + p.offset;
        packets.emplace_back(start, start + p.view.size);
    }
    if (packets.empty()) {
        error = path + " holds no intact packet";
        return false;
    }
    return true;
}

int load_carousel(const std::string& path, const CarouselCli& options, std::vector<std::vector<uint8_t>>& packets,
                  broadcast::Carousel& carousel) {
    std::string error;
    std::vector<std::string> warnings;
    if (!load_stream_packets(path, packets, error, warnings)) return fail(kExitFailure, error);
    for (const auto& w : warnings) std::fprintf(stderr, "ellicast: warning: %s\n", w.c_str());
    if (!broadcast::build_carousel(packets, options.options(), carousel, error)) return fail(kExitInvalid, path + ": " + error);
    return kExitOk;
}

void CarouselCli::add(CLI::App* app) {
    auto* chunk_option = app->add_option("--chunk", chunk, "POINTS packets per chunk between two repetitions of the base")
                             ->check(CLI::PositiveNumber);
    app->add_option("--base-share", base_share,
                    "share of the bandwidth spent on the base, when --chunk is not given (default 0.15)")
        ->check(CLI::Range(0.001, 0.999))
        ->excludes(chunk_option);
    app->add_option("--min-base-repeats", min_base_repetitions,
                    "with --base-share: repeat the base at least this often per cycle (default 4)")
        ->check(CLI::Range(1, 100000))
        ->excludes(chunk_option);
    app->add_option("--stream-info-every", stream_info_every,
                    "inside each chunk, the stream info again after every N POINTS packets (0: only with the base; "
                    "default 8)")
        ->check(CLI::Range(0, 1000000));
    app->add_option("--repair", repair_ratio,
                    "repair packets sent per POINTS packet of a block, of those the stream holds (format 1.2): "
                    "1 gets every point to a receiver at 50% loss in about 2.1 cycles but halves the points it "
                    "holds early; 0.25 keeps 80% of them and still takes 1.1 cycles at 10% loss; 0: repeat the "
                    "POINTS packets (default: all the stream holds)")
        ->check(CLI::Range(0.0, 4.0));
}

broadcast::CarouselOptions CarouselCli::options() const {
    broadcast::CarouselOptions o;
    o.chunk_packets = chunk;
    o.base_share = base_share;
    o.min_base_repetitions = min_base_repetitions;
    o.stream_info_every = stream_info_every;
    o.repair_ratio = repair_ratio;
    return o;
}

void ChannelCli::add(CLI::App* app, bool with_trace_files) {
    app->add_option("--loss", loss, "independent loss probability per packet (with --burst: the mean loss)")
        ->check(CLI::Range(0.0, 1.0));
    app->add_option("--burst", burst, "mean length of loss bursts in packets (Gilbert model with mean loss --loss)")
        ->check(CLI::Range(1.0, 1e6));
    app->add_option("--gilbert-elliott", gilbert_elliott,
                    "explicit Gilbert-Elliott model: P(good->bad),P(bad->good),loss in good,loss in bad")
        ->delimiter(',')
        ->expected(4);
    app->add_option("--reorder", reorder, "probability that a packet is held back (reordering)")
        ->check(CLI::Range(0.0, 1.0));
    app->add_option("--reorder-window", reorder_window, "largest delay of a held-back packet, in packets (default 8)")
        ->check(CLI::Range(1, 1000000));
    app->add_option("--duplicate", duplicate, "probability that a packet arrives twice")->check(CLI::Range(0.0, 1.0));
    app->add_option("--bit-errors", bit_errors, "bit error rate: probability that each bit flips")
        ->check(CLI::Range(0.0, 1.0));
    app->add_option("--seed", seed, "seed of the channel's random draws (same seed, same losses)");
    if (with_trace_files) {
        app->add_option("--trace-in", trace_in, "apply the losses recorded in this trace file instead of drawing them")
            ->check(CLI::ExistingFile);
        app->add_option("--trace-out", trace_out, "write the trace of what the channel did to this file");
    }
}

bool ChannelCli::active() const {
    return loss > 0 || !gilbert_elliott.empty() || reorder > 0 || duplicate > 0 || bit_errors > 0 || !trace_in.empty();
}

bool ChannelCli::model(broadcast::ChannelModel& out, std::string& error) const {
    if (!gilbert_elliott.empty() && (burst > 0 || loss > 0)) {
        error = "--gilbert-elliott gives the whole loss model: do not combine it with --loss or --burst";
        return false;
    }
    if (burst > 0) {
        if (loss >= 1) {
            error = "--burst needs a mean loss --loss below 1";
            return false;
        }
        out = broadcast::ChannelModel::gilbert(loss, burst, seed);
    } else if (!gilbert_elliott.empty()) {
        out = broadcast::ChannelModel{};
        out.bursty = true;
        out.good_to_bad = gilbert_elliott[0];
        out.bad_to_good = gilbert_elliott[1];
        out.loss_good = gilbert_elliott[2];
        out.loss_bad = gilbert_elliott[3];
    } else {
        out = broadcast::ChannelModel{};
        out.loss = loss;
    }
    out.reorder = reorder;
    out.reorder_window = reorder > 0 ? reorder_window : 0;
    out.duplicate = duplicate;
    out.bit_error_rate = bit_errors;
    out.seed = seed;
    error = broadcast::check_channel_model(out);
    if (!error.empty()) error = "channel model: " + error;
    return error.empty();
}

bool ChannelCli::trace(uint64_t slots, size_t packet_bytes, broadcast::LossTrace& out, std::string& error) const {
    if (!trace_in.empty()) {
        broadcast::LossTrace whole;
        if (!broadcast::read_trace(trace_in, whole, error)) return false;
        if (whole.slots() < slots) {
            error = "the trace " + trace_in + " covers " + std::to_string(whole.slots()) + " packets but " +
                    std::to_string(slots) + " are sent";
            return false;
        }
        out = whole.slice(0, slots);
    } else {
        broadcast::ChannelModel m;
        if (!model(m, error)) return false;
        if (!broadcast::generate_trace(m, slots, packet_bytes, out, error)) return false;
    }
    if (!trace_out.empty() && !broadcast::write_trace(trace_out, out, error)) return false;
    return true;
}

std::string with_commas(uint64_t value) {
    std::string digits = std::to_string(value), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string seconds_text(double seconds) {
    char buffer[64];
    if (seconds < 1)
        std::snprintf(buffer, sizeof buffer, "%.1f ms", seconds * 1e3);
    else
        std::snprintf(buffer, sizeof buffer, "%.2f s", seconds);
    return buffer;
}

void print_carousel(std::FILE* out, const broadcast::Carousel& c, double bits_per_second) {
    broadcast::CarouselStats s = broadcast::carousel_stats(c);
    auto at_rate = [&](double bytes) {
        if (bits_per_second <= 0) return std::string();
        return " = " + seconds_text(bytes * 8.0 / bits_per_second);
    };
    std::fprintf(out, "base: %zu packets, %s bytes (STREAM_INFO, ELLIPSOIDS, SCENE, MATERIAL)\n",
                 s.base_packets, with_commas(s.base_bytes).c_str());
    std::fprintf(out, "detail: %zu packets, %s bytes (POINTS, TEXTURE_FRAGMENT), in %zu chunks of at most %zu packets\n", s.data_packets,
                 with_commas(s.data_bytes).c_str(), c.chunk_count, c.chunk_packets);
    if (c.period_cycles > 1) {
        size_t repairs = 0;
        for (const auto& b : c.blocks) repairs += b.symbols.size() - b.sources;
        std::fprintf(out,
                     "repair: %zu blocks, %zu POINTS_REPAIR packets; each block's slots carry its POINTS and repair "
                     "packets in turn, so the schedule repeats after %zu cycles\n",
                     c.blocks.size(), repairs, c.period_cycles);
    }
    std::fprintf(out, "cycle: b d1 b d2 ... b d%zu = %zu packets, %s bytes%s\n", c.chunk_count,
                 s.cycle_packets / c.period_cycles, with_commas(uint64_t(c.bytes_per_cycle())).c_str(),
                 at_rate(c.bytes_per_cycle()).c_str());
    std::fprintf(out, "base share of the bandwidth: %.1f%%\n", s.base_share * 100);
    std::fprintf(out, "repetition overhead: %.1f%% more bytes than sending the stream once (the paper: about 15%%)\n",
                 s.repetition_overhead * 100);
    std::fprintf(out, "worst-case wait for a complete base after tune-in: %s bytes (one chunk + one base + one packet)%s\n",
                 with_commas(s.worst_base_wait_bytes).c_str(), at_rate(double(s.worst_base_wait_bytes)).c_str());
    std::fprintf(out, "mean wait for a complete base (no loss): %s bytes%s\n",
                 with_commas(static_cast<uint64_t>(s.mean_base_wait_bytes)).c_str(),
                 at_rate(s.mean_base_wait_bytes).c_str());
    std::fprintf(out, "worst-case wait for every packet (full quality): %s bytes%s; mean %s bytes%s\n",
                 with_commas(s.worst_full_wait_bytes).c_str(), at_rate(double(s.worst_full_wait_bytes)).c_str(),
                 with_commas(static_cast<uint64_t>(s.mean_full_wait_bytes)).c_str(),
                 at_rate(s.mean_full_wait_bytes).c_str());
}

}  // namespace ellicast::cli

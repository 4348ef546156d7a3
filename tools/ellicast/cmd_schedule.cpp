// `ellicast schedule IN.ellc -o cycle.ellc`: writes the carousel (b d1 b d2 ... b dn, repeated) as a
// stream file, in exactly the order `simulate` and `serve` send it, and prints its figures.
#include "broadcast_cli.h"
#include "commands.h"

#include <ellicast/format.h>

#include <cmath>
#include <iostream>

namespace ellicast::cli {
namespace {

struct ScheduleArgs {
    std::string input;
    std::string output;
    CarouselCli carousel;
    double cycles = 1;
    double rate = 0;
};

int run_schedule(const ScheduleArgs& a) {
    if (output_clobbers_input(a.output, {a.input})) return kExitUsage;
    std::vector<std::vector<uint8_t>> packets;
    broadcast::Carousel carousel;
    if (int code = load_carousel(a.input, a.carousel, packets, carousel); code != kExitOk) return code;
    std::string error;
    // --cycles counts cycles (b d1 .. b dn); with repair packets the schedule repeats only after
    // period_cycles of them.
    const uint64_t slots = static_cast<uint64_t>(
        std::ceil(a.cycles * double(carousel.cycle.size()) / double(carousel.period_cycles)));
    // A schedule file is a recording of what the sender sends: bound it like any output.
    const uint64_t bytes = static_cast<uint64_t>(std::ceil(a.cycles * carousel.bytes_per_cycle()));
    if (bytes > (uint64_t(4) << 30))
        return fail(kExitUsage, "--cycles " + std::to_string(a.cycles) + " would write " + with_commas(bytes) +
                                    " bytes (more than 4 GiB)");
    std::vector<std::vector<uint8_t>> sent;
    sent.reserve(slots);
    for (uint64_t k = 0; k < slots; ++k) sent.push_back(broadcast::carousel_packet(carousel, packets, k));
    std::string message;
    if (write_file(a.output, write_container(sent), message) != Error::Ok)
        return fail(kExitFailure, "cannot write " + a.output + ": " + message);
    std::printf("%s: %zu packets -> %s: %s packets (%g cycles)\n", a.input.c_str(), packets.size(), a.output.c_str(),
                with_commas(slots).c_str(), a.cycles);
    print_carousel(stdout, carousel, a.rate);
    return kExitOk;
}

const RegisterCommand kRegisterSchedule{{60, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<ScheduleArgs>();
    auto* cmd = app.add_subcommand("schedule", "Write the broadcast carousel of a stream (b d1 b d2 ... b dn) to a file");
    cmd->add_option("input", args->input, "stream file (.ellc)")->required()->check(CLI::ExistingFile);
    cmd->add_option("-o,--output", args->output, "the scheduled stream file to write")->required();
    args->carousel.add(cmd);
    cmd->add_option("--cycles", args->cycles, "how many cycles to write (default 1; fractions allowed)")
        ->check(CLI::Range(0.001, 1e6));
    cmd->add_option("--rate", args->rate, "bit rate to express the waits in seconds (optional)")
        ->check(CLI::PositiveNumber);
    cmd->callback([args, &exit_code] { exit_code = run_schedule(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

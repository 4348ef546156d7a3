// The `ellicast` command line: each subcommand lives in its own cmd_*.cpp and registers itself here,
// so adding a command touches no other file.
#pragma once

#include "ellicast/codec/mesh.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace ellicast::cli {

// A subcommand: `setup` adds it to the app; its callback stores the process exit code in `exit_code`.
struct Command {
    int order;  // position in `ellicast --help`
    std::function<void(CLI::App& app, int& exit_code)> setup;
};

std::vector<Command>& command_registry();

struct RegisterCommand {
    explicit RegisterCommand(Command command) { command_registry().push_back(std::move(command)); }
};

// Exit codes shared by every command.
inline constexpr int kExitOk = 0;
inline constexpr int kExitInvalid = 1;   // the input is not valid / the check failed
inline constexpr int kExitUsage = 2;     // bad options or arguments (CLI11's own code too)
inline constexpr int kExitFailure = 3;   // the work could not be done (I/O, unsupported input)

// Prints "ellicast: error: <message>" on stderr and returns `code`.
int fail(int code, const std::string& message);

// Reads any model ellicast reads (load_meshes), printing its warnings on stderr as
// "ellicast: warning: PATH: ...". Returns false with `error` naming the file and the problem.
bool load_model(const std::string& path, std::vector<Mesh>& meshes, std::string& error, const InputOptions& options = {});

// Prints warnings on stderr as "ellicast: warning: ...": three or more of one kind (the same words
// about different parts) as one line naming the first and counting the rest, unless `verbose`.
void print_warnings(const std::vector<std::string>& warnings, bool verbose);

// Refuses to overwrite an input: true (and an error printed) when `output` is the same file as one
// of `inputs`.
bool output_clobbers_input(const std::string& output, const std::vector<std::string>& inputs);

// Signs whole packets of one stream with the secret key in `key_path` (spec 16; cmd_sign.cpp):
// MANIFEST parts first, then the distinct packets, renumbered. Returns an exit code, the error printed.
int sign_packets_with_key(const std::string& key_path, std::vector<std::vector<uint8_t>>& packets, size_t& parts);

// Reads a recorded stream's packets for decoding. With a public key (--key, spec 16.3) only the
// packets a MANIFEST signed with it lists are kept, and a summary goes to stderr; a recording with
// nothing authenticated is an error. Returns an exit code, the error printed.
struct RecordingPackets {
    std::vector<uint8_t> bytes;
    ContainerContents contents;
};
int read_recording(const std::string& path, const std::string& key, RecordingPackets& out);

}  // namespace ellicast::cli

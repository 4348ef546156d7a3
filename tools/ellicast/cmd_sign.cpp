// `ellicast sign IN.ellc --key NAME.key -o OUT.ellc`: signs a recorded stream (spec 16): its distinct
// packets, preceded by the MANIFEST parts that list them, renumbered from 0. A signed input is signed
// again (its old MANIFESTs are dropped).
#include "commands.h"

#include <ellicast/auth.h>
#include <ellicast/format.h>

#include <cstdio>
#include <memory>

namespace ellicast::cli {

int sign_packets_with_key(const std::string& key_path, std::vector<std::vector<uint8_t>>& packets, size_t& parts) {
    auth::KeyPair key;
    std::string error;
    if (!auth::read_secret_key(key_path, key, error)) return fail(kExitUsage, "--sign/--key: " + error);
    if (auth::sign_stream(packets, key, parts, error) != Error::Ok) return fail(kExitFailure, "signing: " + error);
    return kExitOk;
}

namespace {

struct SignArgs {
    std::string input, output, key;
};

int run_sign(const SignArgs& a) {
    if (output_clobbers_input(a.output, {a.input})) return kExitUsage;
    std::vector<uint8_t> bytes;
    std::string message;
    if (read_file(a.input, bytes, message) != Error::Ok) return fail(kExitFailure, message);
    ContainerContents contents = read_container(bytes);
    if (contents.header_error != Error::Ok)
        return fail(kExitInvalid, a.input + ": not an ellicast container (" + error_name(contents.header_error) + ")");
    if (!contents.damaged.empty())
        return fail(kExitInvalid, a.input + ": " + std::to_string(contents.damaged.size()) +
                                      " damaged region(s), the first at byte " + std::to_string(contents.damaged[0].offset) +
                                      ": a signature would vouch for an incomplete stream");
    std::vector<std::vector<uint8_t>> packets;
    for (const auto& p : contents.packets)
        packets.emplace_back(bytes.begin() + std::ptrdiff_t(p.offset), bytes.begin() + std::ptrdiff_t(p.offset + p.view.size));
    const size_t before = packets.size();
    size_t parts = 0;
    if (int code = sign_packets_with_key(a.key, packets, parts); code != kExitOk) return code;
    std::vector<uint8_t> file = write_container(packets);
    if (write_file(a.output, file, message) != Error::Ok) return fail(kExitFailure, message);
    std::printf("%s -> %s: %zu packets signed in %zu MANIFEST part(s), %zu bytes (was %zu packets, %zu bytes)\n",
                a.input.c_str(), a.output.c_str(), packets.size() - parts, parts, file.size(), before, bytes.size());
    return kExitOk;
}

const RegisterCommand kRegisterSign{{14, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<SignArgs>();
    auto* cmd = app.add_subcommand("sign", "Sign a recorded stream (.ellc) with a secret key: MANIFEST packets (spec 16)");
    cmd->add_option("input", args->input, "recorded stream (.ellc)")->required();
    cmd->add_option("-o,--output", args->output, "signed stream to write (.ellc)")->required();
    cmd->add_option("--key", args->key, "secret key file (NAME.key from `ellicast keygen`)")->required();
    cmd->callback([args, &exit_code] { exit_code = run_sign(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

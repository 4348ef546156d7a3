// `ellicast keygen NAME`: an Ed25519 key pair for signed streams (spec 16): NAME.key (the secret,
// mode 0600, for `encode --sign` and `sign`) and NAME.pub (for `receive`, `decode` and `validate`
// with --key). Existing files are never replaced.
#include "commands.h"

#include <ellicast/auth.h>

#include <cstdio>
#include <memory>

namespace ellicast::cli {
namespace {

struct KeygenArgs {
    std::string name;
};

int run_keygen(const KeygenArgs& a) {
    if (!auth::available()) return fail(kExitFailure, "libsodium cannot be initialized: no key made");
    const std::string secret = a.name + ".key", pub = a.name + ".pub";
    const auth::KeyPair key = auth::generate_key_pair();
    std::string error;
    if (!auth::write_key_pair(secret, pub, key, error)) return fail(kExitFailure, error);
    std::printf("wrote %s (secret: keep it to the sender) and %s (public: give it to receivers)\n", secret.c_str(),
                pub.c_str());
    std::printf("key id %s\n", auth::to_hex(key_id_of(std::span<const uint8_t, 32>(key.public_key))).c_str());
    return kExitOk;
}

const RegisterCommand kRegisterKeygen{{12, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<KeygenArgs>();
    auto* cmd = app.add_subcommand("keygen", "Make an Ed25519 key pair for signed streams: NAME.key (secret) and NAME.pub");
    cmd->add_option("name", args->name, "path and name of the key files, without extension")->required();
    cmd->callback([args, &exit_code] { exit_code = run_keygen(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

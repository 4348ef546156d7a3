// `ellicast validate FILE.ellc`: exit 0 only for a conforming recorded stream (spec/format.md 11.5);
// otherwise every violation is listed with its byte offset and the exit code is 1. With --received,
// a recording of a lossy reception passes when all that is wrong is what did not arrive: it says
// "conforming but incomplete" and lists what is missing per object; anything wrong in what did
// arrive still fails, with its offset.
#include "commands.h"
#include "stream_report.h"

#include "ellicast/format.h"

#include <algorithm>
#include <iostream>
#include <memory>

namespace ellicast::cli {
namespace {

struct ValidateArgs {
    std::vector<std::string> inputs;
    bool quiet = false;
    bool received = false;
    std::string key;
};

int validate_one(const std::string& path, bool quiet, bool received, const auth::PublicKey* key) {
    std::vector<uint8_t> bytes;
    std::string message;
    if (read_file(path, bytes, message) != Error::Ok) return fail(kExitFailure, message);
    StreamReport report = analyze_stream(path, bytes, key);
    auto violations = report.violations;
    std::stable_sort(violations.begin(), violations.end(), [](const Violation& a, const Violation& b) {
        if (a.offset.has_value() != b.offset.has_value()) return a.offset.has_value();
        return a.offset.value_or(0) < b.offset.value_or(0);
    });
    if (violations.empty()) {
        if (!quiet) {
            const auto& info = *report.stream.info();
            uint64_t ellipsoids = 0, points = 0;
            for (const auto& o : report.stream.objects()) ellipsoids += o.ellipsoids.size(), points += o.points.size();
            std::cout << path << ": conforms to ellicast format 1." << int(report.stream.newest_minor()) << " ("
                      << report.packets.size() << " packets, stream " << hex32(report.stream.stream_id()) << ", "
                      << report.stream.objects().size() << " object" << (report.stream.objects().size() == 1 ? "" : "s")
                      << ", " << ellipsoids << " ellipsoids, " << points << " points, packet size " << info.packet_size
                      << ")\n";
            if (report.signing.is_signed)
                std::cout << path << ": signed: " << report.signing.parts << " MANIFEST part(s), key id "
                          << report.signing.key_id
                          << (key ? ", every signature verified" : "; signatures not checked (give --key)") << "\n";
        }
        return kExitOk;
    }
    const size_t missing = size_t(std::count_if(violations.begin(), violations.end(), [](const Violation& v) { return v.missing; }));
    if (received && missing == violations.size()) {
        // A lossy recording of a conforming stream: what arrived conforms, the rest is missing.
        if (!quiet) {
            std::cout << path << ": conforming but incomplete (a received recording: every packet in it conforms; "
                      << missing << " part" << (missing == 1 ? "" : "s") << " of the stream did not arrive):\n";
            for (const Violation& v : violations) std::cout << path << ":   missing: " << v.message << "\n";
        }
        return kExitOk;
    }
    for (const Violation& v : violations) {
        if (received && v.missing) continue;
        std::cout << path << ": ";
        if (v.offset) std::cout << "offset " << *v.offset << ": ";
        std::cout << v.message << (v.missing ? " (missing)" : "") << "\n";
    }
    if (received) {
        std::cout << path << ": does not conform: " << violations.size() - missing << " violation"
                  << (violations.size() - missing == 1 ? "" : "s") << " in what arrived (and " << missing
                  << " part" << (missing == 1 ? "" : "s") << " missing, not listed)\n";
    } else {
        std::cout << path << ": does not conform: " << violations.size() << " violation"
                  << (violations.size() == 1 ? "" : "s");
        if (missing == violations.size())
            std::cout << ", every one of them missing data: a recording of a lossy reception? (validate --received "
                         "accepts one whose every packet conforms)";
        else if (missing > 0)
            std::cout << " (" << missing << " of them missing data)";
        std::cout << "\n";
    }
    return kExitInvalid;
}

int run_validate(const ValidateArgs& args) {
    auth::PublicKey key;
    if (!args.key.empty()) {
        std::string error;
        if (!auth::read_public_key(args.key, key, error)) return fail(kExitUsage, "--key: " + error);
    }
    int code = kExitOk;
    for (const auto& input : args.inputs) {
        int c = validate_one(input, args.quiet, args.received, args.key.empty() ? nullptr : &key);
        code = std::max(code, c);
    }
    return code;
}

const RegisterCommand kRegisterValidate{{60, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<ValidateArgs>();
    auto* cmd = app.add_subcommand("validate",
                                   "Check that recorded streams (.ellc) conform to the format: exit 0 only if every "
                                   "file does; every violation is listed with its byte offset");
    cmd->add_option("files", args->inputs, "recorded streams (.ellc)")->required();
    cmd->add_flag("-q,--quiet", args->quiet, "print nothing for a conforming file");
    cmd->add_flag("--received", args->received,
                  "a recording of a reception: pass when all that is wrong is what did not arrive (\"conforming but "
                  "incomplete\", listing what is missing); anything wrong in what arrived still fails");
    cmd->add_option("--key", args->key,
                    "public key (NAME.pub or 64 hex digits): the stream must be signed with it, every signature checked");
    cmd->callback([args, &exit_code] { exit_code = run_validate(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

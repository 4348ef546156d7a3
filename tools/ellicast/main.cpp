// ellicast: encode, inspect, validate and decode ellicast streams.
#include "commands.h"

#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <algorithm>
#include <new>
#include <filesystem>
#include <iostream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace ellicast::cli {

std::vector<Command>& command_registry() {
    static std::vector<Command> commands;
    return commands;
}

int fail(int code, const std::string& message) {
    std::cerr << "ellicast: error: " << message << "\n";
    return code;
}

bool load_model(const std::string& path, std::vector<Mesh>& meshes, std::string& error, const InputOptions& options) {
    try {
        LoadResult result = load_meshes(path, options);
        for (const auto& w : result.warnings) std::cerr << "ellicast: warning: " << path << ": " << w << "\n";
        meshes = std::move(result.meshes);
        return true;
    } catch (const InputError& e) {
        error = e.what();
    } catch (const std::exception& e) {
        error = path + ": " + e.what();
    }
    return false;
}

bool output_clobbers_input(const std::string& output, const std::vector<std::string>& inputs) {
    std::error_code ec;
    if (!std::filesystem::exists(output, ec)) return false;
    for (const auto& input : inputs) {
        // A model's own buffers and images are inputs too (encode model.gltf -o model.bin).
        for (const auto& file : model_files(input)) {
            if (std::filesystem::equivalent(output, file, ec)) {
                fail(kExitUsage, std::string("refusing to overwrite ") + (file == input ? "the input " : "a file of the input, ") +
                                     file + ", with the output");
                return true;
            }
        }
    }
    return false;
}

}  // namespace ellicast::cli

int main(int argc, char** argv) {
    using namespace ellicast::cli;
#if defined(__GLIBC__)
    // Each stage of a command allocates large arrays and frees them for the next. glibc maps a block
    // of 128 KB and more on its own and gives it back when freed (its threshold rises only after
    // such a free), and trims the heap's top past 128 KB: the next stage's memory then comes as fresh
    // zeroed pages, a page fault each. Freed memory stays in the heap for reuse instead (blocks up to
    // 32 MB, glibc's largest threshold; the heap's free top up to 256 MB): the 500k-vertex torus's
    // exact decode takes a third fewer page faults and 6-8% less wall time, its peak memory the same.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
    const std::string format_version = std::to_string(ellicast::kFormatMajor) + "." + std::to_string(ellicast::kSpecMinor);
    CLI::App app{"ellicast: 3D models over lossy one-way channels (format " + format_version + ")", "ellicast"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "ellicast 1.0.0, format " + format_version);
    int exit_code = kExitOk;
    auto commands = command_registry();
    std::sort(commands.begin(), commands.end(), [](const Command& a, const Command& b) { return a.order < b.order; });
    for (auto& command : commands) command.setup(app, exit_code);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int code = app.exit(e);
        return code == 0 ? 0 : kExitUsage;
    } catch (const std::bad_alloc&) {
        // Every reader bounds what it allocates by the input's size; this is the last line, for
        // what slipped through (or a machine without the memory for a legitimate input).
        return fail(kExitFailure, "out of memory (the input asks for more than this machine can give)");
    } catch (const std::exception& e) {
        return fail(kExitFailure, std::string("internal error: ") + e.what());
    }
    return exit_code;
}

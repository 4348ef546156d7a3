// `ellicast convert DIR OUTDIR`: every glTF asset under DIR through `ellicast convert`, each in a process
// of its own (a crash or a failure in one asset stops nothing else), several at once, with one summary
// table of sizes, ratios, warnings and, when a validator is named, its verdict.
#include "convert_catalogue.h"

#include "broadcast_cli.h"
#include "commands.h"
#include "progress.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

extern char** environ;

namespace ellicast::cli {

namespace fs = std::filesystem;

namespace {

struct CatalogueJob {
    fs::path input, output, log;
    std::string relative;
    int exit_code = -1;  // the child's, or 128 + signal
    uint64_t input_bytes = 0, stream_bytes = 0, output_bytes = 0;
    size_t warnings = 0;
    std::string error;      // the first error line
    std::string validator;  // the validator's verdict, "" when none ran
    bool validator_failed = false;
    double seconds = 0;
    std::chrono::steady_clock::time_point started;
};

std::string ascii_lower(std::string s) {
    for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool path_inside(const fs::path& path, const fs::path& dir) {
    auto p = path.begin(), d = dir.begin();
    for (; d != dir.end(); ++d, ++p)
        if (p == path.end() || *p != *d) return false;
    return true;
}

// Every .gltf and .glb under `dir` (not under `skip`), sorted, symbolic links to folders not followed.
std::vector<fs::path> find_catalogue_assets(const fs::path& dir, const fs::path& skip, std::string& error) {
    std::vector<fs::path> out;
    std::error_code ec;
    fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
    if (ec) {
        error = dir.string() + ": cannot list: " + ec.message();
        return out;
    }
    for (; it != end; it.increment(ec)) {
        if (ec) {
            error = it->path().string() + ": " + ec.message();
            return {};
        }
        const fs::path& p = it->path();
        if (it->is_directory(ec) && path_inside(fs::weakly_canonical(p, ec), skip)) {
            it.disable_recursion_pending();
            continue;
        }
        const std::string ext = ascii_lower(p.extension().string());
        if ((ext == ".gltf" || ext == ".glb") && it->is_regular_file(ec)) out.push_back(p);
    }
    std::sort(out.begin(), out.end());
    return out;
}

// The numbers `ellicast convert` prints, and its warnings and first error, from its log.
void read_convert_log(CatalogueJob& job) {
    std::ifstream in(job.log);
    std::string line;
    static const std::regex size_line(R"(^size: input (\d+) bytes, stream (\d+) bytes .*output (\d+) bytes)");
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, size_line)) {
            job.input_bytes = std::stoull(m[1]);
            job.stream_bytes = std::stoull(m[2]);
            job.output_bytes = std::stoull(m[3]);
        } else if (line.rfind("ellicast: warning: ", 0) == 0) {
            ++job.warnings;
        } else if (job.error.empty() && line.rfind("ellicast: error: ", 0) == 0) {
            job.error = line.substr(17);
        }
    }
}

std::string shell_arg(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Runs `command OUTPUT`; a validator prints a JSON line with "numErrors" and "numWarnings" (as
// tests/gltf_validate.js does), or exits non-zero on an invalid file.
void run_output_validator(const std::string& command, CatalogueJob& job) {
    const std::string line = command + " " + shell_arg(job.output.string()) + " 2>&1";
    FILE* pipe = popen(line.c_str(), "r");
    if (!pipe) {
        job.validator = "could not run";
        job.validator_failed = true;
        return;
    }
    std::string text;
    char buffer[4096];
    while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) {
        if (text.size() < (1u << 20)) text.append(buffer, n);
    }
    const int status = pclose(pipe);
    std::smatch errors, warnings;
    static const std::regex num_errors(R"("numErrors"\s*:\s*(-?\d+))"), num_warnings(R"("numWarnings"\s*:\s*(\d+))");
    if (std::regex_search(text, errors, num_errors)) {
        const long e = std::stol(errors[1]);
        std::string w = std::regex_search(text, warnings, num_warnings) ? std::string(warnings[1]) : "?";
        job.validator = e < 0 ? "validator failed" : std::to_string(e) + " errors, " + w + " warnings";
        job.validator_failed = e != 0;
    } else {
        job.validator = status == 0 ? "valid (exit 0)" : "invalid (exit " + std::to_string(WEXITSTATUS(status)) + ")";
        job.validator_failed = status != 0;
    }
}

std::string size_ratio(uint64_t n, uint64_t of) {
    if (of == 0) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.2fx", double(n) / double(of));
    return text;
}

std::string job_status(const CatalogueJob& job) {
    if (job.exit_code == 0) return "ok";
    if (job.exit_code > 128) return "crashed (signal " + std::to_string(job.exit_code - 128) + ")";
    std::string why = job.error.empty() ? "exit " + std::to_string(job.exit_code) : job.error;
    for (char& c : why)
        if (c == '|' || c == '\n') c = ' ';
    return "failed: " + why;
}

}  // namespace

int run_convert_catalogue(const CatalogueArgs& a) {
    const auto start = std::chrono::steady_clock::now();
    std::error_code ec;
    const fs::path dir = fs::weakly_canonical(a.input, ec);
    if (ec || !fs::is_directory(dir)) return fail(kExitUsage, a.input + ": not a folder");
    if (fs::exists(a.output) && !fs::is_directory(a.output))
        return fail(kExitUsage, a.output + ": exists and is not a folder (a catalogue is converted into a folder)");
    const fs::path out_dir = fs::weakly_canonical(a.output, ec);
    if (ec) return fail(kExitUsage, a.output + ": " + ec.message());
    if (path_inside(dir, out_dir))
        return fail(kExitUsage, a.output + ": the output folder is " + a.input +
                                    " or holds it; outputs could replace inputs (choose a folder beside it)");
    if (a.jobs < 1 || a.jobs > 64) return fail(kExitUsage, "--jobs must be 1..64");
    std::string error;
    const std::vector<fs::path> assets = find_catalogue_assets(dir, out_dir, error);
    if (!error.empty()) return fail(kExitFailure, error);
    if (assets.empty()) return fail(kExitFailure, a.input + ": no .gltf or .glb file under it");
    fs::create_directories(out_dir, ec);
    if (ec) return fail(kExitFailure, a.output + ": cannot create: " + ec.message());

    std::vector<CatalogueJob> jobs;
    for (const fs::path& p : assets) {
        CatalogueJob job;
        job.input = p;
        job.relative = fs::relative(p, dir).string();
        job.output = out_dir / fs::relative(p, dir);
        job.log = job.output;
        job.log += ".log";
        jobs.push_back(std::move(job));
    }
    const std::string self = fs::read_symlink("/proc/self/exe", ec).string();
    if (ec) return fail(kExitFailure, "cannot find the ellicast executable (/proc/self/exe): " + ec.message());

    ProgressBar bar(!a.quiet);
    std::map<pid_t, size_t> running;  // child -> its job
    size_t next = 0, done = 0;
    auto launch = [&](CatalogueJob& job) -> bool {
        fs::create_directories(job.output.parent_path(), ec);
        std::vector<std::string> args = {self, "convert", job.input.string(), job.output.string(), "-q"};
        args.insert(args.end(), a.forwarded.begin(), a.forwarded.end());
        std::vector<char*> argv;
        for (auto& s : args) argv.push_back(s.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 1, job.log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_adddup2(&actions, 1, 2);
        posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
        pid_t pid = 0;
        const int e = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        if (e != 0) {
            job.exit_code = kExitFailure;
            job.error = std::string("could not start: ") + std::strerror(e);
            return false;
        }
        running[pid] = size_t(&job - jobs.data());
        job.started = std::chrono::steady_clock::now();
        return true;
    };
    bar.update("catalogue", 0.0);
    while (done < jobs.size()) {
        while (running.size() < size_t(a.jobs) && next < jobs.size())
            if (!launch(jobs[next++])) ++done;
        if (running.empty()) continue;
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR) continue;
            return fail(kExitFailure, std::string("waiting for a conversion: ") + std::strerror(errno));
        }
        auto it = running.find(pid);
        if (it == running.end()) continue;
        CatalogueJob& job = jobs[it->second];
        job.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
        job.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - job.started).count();
        running.erase(it);
        read_convert_log(job);
        if (job.exit_code == 0 && !a.validator.empty()) run_output_validator(a.validator, job);
        ++done;
        bar.update("catalogue", double(done) / double(jobs.size()));
    }
    bar.finish();

    // The table: on stdout, and as OUTDIR/catalogue.md.
    std::ostringstream table;
    size_t ok = 0, failed = 0, invalid = 0, warned = 0;
    uint64_t in_total = 0, stream_total = 0, out_total = 0;
    table << "| asset | result | input bytes | stream | output | warnings |" << (a.validator.empty() ? "" : " validator |")
          << " seconds |\n|---|---|---:|---:|---:|---:|" << (a.validator.empty() ? "" : "---|") << "---:|\n";
    for (const CatalogueJob& job : jobs) {
        const bool good = job.exit_code == 0;
        ok += good;
        failed += !good;
        invalid += job.validator_failed;
        warned += job.warnings > 0;
        if (good) {
            in_total += job.input_bytes;
            stream_total += job.stream_bytes;
            out_total += job.output_bytes;
        }
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.1f", job.seconds);
        table << "| " << job.relative << " | " << job_status(job) << " | " << (good ? with_commas(job.input_bytes) : "-")
              << " | " << (good ? with_commas(job.stream_bytes) + " (" + size_ratio(job.stream_bytes, job.input_bytes) + ")" : "-")
              << " | " << (good ? with_commas(job.output_bytes) + " (" + size_ratio(job.output_bytes, job.input_bytes) + ")" : "-")
              << " | " << job.warnings << " |" << (a.validator.empty() ? "" : " " + (job.validator.empty() ? "-" : job.validator) + " |")
              << " " << seconds << " |\n";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ostringstream summary;
    summary << jobs.size() << " assets: " << ok << " converted, " << failed << " failed";
    if (!a.validator.empty()) summary << ", " << invalid << " rejected by the validator";
    summary << ", " << warned << " with warnings (each asset's log: OUTPUT.log); converted: input " << with_commas(in_total)
            << " bytes, streams " << with_commas(stream_total) << " (" << size_ratio(stream_total, in_total) << "), outputs "
            << with_commas(out_total) << " (" << size_ratio(out_total, in_total) << "); " << a.jobs << " at a time, ";
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.1f s", seconds);
    summary << wall;
    std::printf("%s\n%s\n", table.str().c_str(), summary.str().c_str());
    const fs::path md = out_dir / "catalogue.md";
    std::ofstream(md) << "# " << a.input << " through ellicast convert\n\n" << table.str() << "\n" << summary.str() << "\n";
    std::printf("table written to %s\n", md.string().c_str());
    return failed || invalid ? kExitInvalid : kExitOk;
}

}  // namespace ellicast::cli

// Synthetic streams for the broadcast tests: real packets made by the format library from
// random geometry, so that carousel, channel and UDP tests do not depend on the encoder.
#pragma once

#include "support.h"

#include <doctest/doctest.h>
#include <ellicast/format.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <fstream>
#include <functional>
#include <iterator>

#include <fcntl.h>
#include <vector>

namespace ellicast::test {

// A one-object surface stream with `ellipsoids` ellipsoids and `points` points (with normals),
// cut into packets of `packet_size` bytes: STREAM_INFO, ELLIPSOIDS..., POINTS...
inline std::vector<std::vector<uint8_t>> synthetic_stream(uint32_t ellipsoids, uint32_t points,
                                                          uint32_t stream_id = 0x5EED, uint16_t packet_size = 1200,
                                                          uint32_t seed = 7) {
    StreamInfo info;
    info.packet_size = packet_size;
    ObjectInfo object;
    object.frame.origin = {-1, -1, -1};
    object.frame.scale = 2;
    object.ellipsoid_count = ellipsoids;
    object.point_count = points;
    object.attributes = kAttrNormal;
    info.objects.push_back(object);
    // A ball: ellipsoids inside a sphere of radius 0.5, points on it with outward normals.
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    ObjectContent content;
    for (uint32_t i = 0; i < ellipsoids; ++i) {
        Ellipsoid e;
        e.center = {0.2f * u(rng), 0.2f * u(rng), 0.2f * u(rng)};
        e.radii = {0.25f + 0.03f * u(rng), 0.25f + 0.03f * u(rng), 0.25f + 0.03f * u(rng)};
        content.ellipsoids.push_back(quantize_ellipsoid(e, object.frame));
    }
    for (uint32_t i = 0; i < points; ++i) {
        float x, y, z, l;
        do {
            x = u(rng), y = u(rng), z = u(rng);
            l = std::sqrt(x * x + y * y + z * z);
        } while (l < 0.1f || l > 1.0f);
        SurfacePoint p;
        p.position = {0.5f * x / l, 0.5f * y / l, 0.5f * z / l};
        p.normal = {x / l, y / l, z / l};
        content.points.push_back(quantize_point(p, info, object));
    }
    StreamPackets sp;
    Error e = packetize_stream(info, {content}, stream_id, sp);
    REQUIRE(e == Error::Ok);
    std::vector<std::vector<uint8_t>> all;
    for (auto* part : {&sp.stream_info, &sp.ellipsoids, &sp.maps, &sp.points, &sp.normals})
        for (auto& p : *part) all.push_back(p);
    return all;
}

}  // namespace ellicast::test

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

extern char** environ;

namespace ellicast::test {

// A packet with its checksum recomputed after an edit: what a sender (or a forger) writes.
inline std::vector<uint8_t> resealed(std::vector<uint8_t> p) {
    const size_t body = p.size() - kChecksumSize;
    const uint32_t crc = crc32c(p.data(), body);
    for (int i = 0; i < 4; ++i) p[body + i] = uint8_t(crc >> (8 * i));
    return p;
}

// A packet with its payload changed by `edit` and its checksum recomputed: what a sender could send.
inline std::vector<uint8_t> edited(std::vector<uint8_t> packet, const std::function<void(uint8_t*)>& edit) {
    edit(packet.data() + kHeaderSize);
    return resealed(std::move(packet));
}

// Writes `packets` as a stream file.
inline void write_stream_file(const std::filesystem::path& path, const std::vector<std::vector<uint8_t>>& packets) {
    std::string message;
    REQUIRE(write_file(path.string(), write_container(packets), message) == Error::Ok);
}

// Every intact packet of a stream file, as bytes.
inline std::vector<std::vector<uint8_t>> read_stream_file(const std::filesystem::path& path) {
    std::vector<uint8_t> bytes;
    std::string message;
    REQUIRE(read_file(path.string(), bytes, message) == Error::Ok);
    ContainerContents contents = read_container(bytes);
    REQUIRE(contents.header_error == Error::Ok);
    CHECK(contents.damaged.empty());
    std::vector<std::vector<uint8_t>> out;
    for (const auto& p : contents.packets)
        out.emplace_back(bytes.begin() + p.offset, bytes.begin() + p.offset + p.view.size);
    return out;
}

// A child process running `ellicast` with `args`, stdout and stderr to `log`. Killed if still
// running when destroyed.
class Child {
public:
    Child(const std::vector<std::string>& args, const std::filesystem::path& log) {
        std::vector<std::string> all = {ellicast_exe().string()};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_adddup2(&actions, 1, 2);
        REQUIRE(posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), environ) == 0);
        posix_spawn_file_actions_destroy(&actions);
    }
    ~Child() {
        if (pid_ > 0) {
            kill(pid_, SIGKILL);
            waitpid(pid_, nullptr, 0);
        }
    }
    // Waits up to `timeout` for the process to end; its exit code, or -1 on timeout.
    int wait(std::chrono::milliseconds timeout) {
        auto deadline = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < deadline) {
            int status = 0;
            pid_t r = waitpid(pid_, &status, WNOHANG);
            if (r == pid_) {
                pid_ = -1;
                return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return -1;
    }

private:
    pid_t pid_ = -1;
};

// Runs `ellicast` with `args` to the end (bounded by `timeout`); its exit code.
inline int run_ellicast(const std::vector<std::string>& args, const std::filesystem::path& log,
                        std::chrono::milliseconds timeout = std::chrono::seconds(60)) {
    Child child(args, log);
    return child.wait(timeout);
}

inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace ellicast::test

// `ellicast receive --from ADDRESS:PORT -o OUT.glb`: joins a broadcast at any moment, keeps the
// ellicast packets of one stream (counting and dropping everything else), shows the base mesh as
// soon as the base is complete and inserts points as they arrive, shows progress on stderr, writes
// snapshots, and stops when the stream is complete or at the deadline. The final model is decoded
// from everything received, exactly as `ellicast decode` would from the same packets.
#include "broadcast_cli.h"
#include "commands.h"
#include "live_reconstruction.h"
#include "live_view.h"
#include "region_option.h"
#include "progress.h"

#include "ellicast/codec/decoder.h"
#include "ellicast/converters/asset.h"
#include "ellicast/converters/mesh_output.h"

#include <ellicast/broadcast/reception.h>
#include <ellicast/broadcast/udp.h>
#include <ellicast/format.h>

#include <atomic>
#include <optional>
#include <chrono>
#include <cstdint>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace ellicast::cli {
namespace {

std::atomic<bool> g_receive_stop{false};
void on_receive_interrupt(int) { g_receive_stop.store(true); }

struct ReceiveArgs {
    std::string from;
    std::string output;
    std::string snapshots;
    std::string until = "complete";
    std::string interface;
    int64_t stream_id = -1;
    int grid = 0;
    uint64_t max_elements = ReceivedStream::Limits{}.max_elements;
    size_t max_pending_mb = ReceivedStream::Limits{}.max_pending_bytes >> 20;
    bool quiet = false;
    std::string key;  // accept only the stream this public key signs (spec 16.3)
    bool view = false;  // serve the live view (live_view.h)
    std::string view_bind = "127.0.0.1";
    uint16_t view_port = 8765;
    std::string three, reference;
    double view_linger = -1;  // seconds to keep the page after the end (-1: until interrupted)
};

// A moment at which to write a snapshot: when the base is complete, at a share of the points, or
// at a time after tune-in.
struct Snapshot {
    enum Kind { Base, Points, Seconds } kind;
    double value = 0;
    std::string label;
    bool done = false;
};

bool parse_snapshots(const std::string& text, std::vector<Snapshot>& out, std::string& error) {
    std::stringstream items(text);
    std::string item;
    while (std::getline(items, item, ',')) {
        if (item.empty()) continue;
        Snapshot s{Snapshot::Base, 0, "", false};
        try {
            if (item == "base") {
                s.kind = Snapshot::Base;
                s.label = "base";
            } else if (item.back() == '%') {
                s.kind = Snapshot::Points;
                size_t used = 0;
                s.value = std::stod(item.substr(0, item.size() - 1), &used);
                if (used != item.size() - 1 || !(s.value > 0 && s.value <= 100)) throw std::invalid_argument("range");
                s.label = item.substr(0, item.size() - 1) + "pct";
            } else if (item.back() == 's') {
                s.kind = Snapshot::Seconds;
                size_t used = 0;
                s.value = std::stod(item.substr(0, item.size() - 1), &used);
                if (used != item.size() - 1 || !(s.value > 0 && s.value < 1e7)) throw std::invalid_argument("range");
                s.label = item;
            } else {
                throw std::invalid_argument("kind");
            }
        } catch (const std::exception&) {
            error = "--snapshots: \"" + item + "\" is not \"base\", a share of the points like \"50%\", or a time like \"2.5s\"";
            return false;
        }
        out.push_back(s);
        if (out.size() > 1000) {
            error = "--snapshots: at most 1000 snapshots";
            return false;
        }
    }
    return true;
}

std::string snapshot_path(const std::string& output, const std::string& label) {
    std::filesystem::path p(output);
    return (p.parent_path() / (p.stem().string() + "-" + label + p.extension().string())).string();
}

// Writes what has been received so far: the packets that brought new content, as a stream file.
bool write_received(const std::string& path, const std::vector<std::vector<uint8_t>>& kept, std::string& error) {
    std::string message;
    if (write_file(path, write_container(kept), message) != Error::Ok) {
        error = "cannot write " + path + ": " + message;
        return false;
    }
    return true;
}

// Writes the objects (index = object id, empty = not arrived): glTF with the stream's scene,
// materials and textures (format 1.1) when the output is glTF, plain meshes otherwise.
bool write_model(const std::string& path, const ReceivedStream& stream, std::vector<Mesh> objects, bool gltf,
                 std::vector<std::string>& warnings, std::string& error) {
    if (gltf) {
        Asset asset = received_asset(stream, std::move(objects));
        warnings.insert(warnings.end(), asset.warnings.begin(), asset.warnings.end());
        return write_asset(path, asset, AssetWriteOptions{}, warnings, error);
    }
    std::vector<Mesh> meshes;
    for (auto& m : objects)
        if (!m.positions.empty()) meshes.push_back(std::move(m));
    if (meshes.empty()) {
        error = "nothing to write to " + path + " yet";
        return false;
    }
    return write_meshes(path, meshes, error);
}

// After the reception: the page stays for `linger` seconds, or until Ctrl-C when negative.
void keep_serving(LiveView& view, double linger) {
    g_receive_stop.store(false);
    std::signal(SIGINT, on_receive_interrupt);
    std::signal(SIGTERM, on_receive_interrupt);
    if (linger < 0) std::fprintf(stderr, "view: the page stays at %s until Ctrl-C\n", view.url().c_str());
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(linger < 0 ? 1e9 : linger);
    while (!g_receive_stop.load() && std::chrono::steady_clock::now() < until) view.poll(std::chrono::milliseconds(100));
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

int run_receive(const ReceiveArgs& a) {
    double deadline_seconds = -1;
    if (a.until != "complete") {
        try {
            size_t used = 0;
            deadline_seconds = std::stod(a.until, &used);
            if (used != a.until.size() || !(deadline_seconds > 0)) throw std::invalid_argument("x");
        } catch (const std::exception&) {
            return fail(kExitUsage, "--until: \"" + a.until + "\" is neither \"complete\" nor a number of seconds");
        }
    }
    std::vector<Snapshot> snapshots;
    std::string error;
    if (!parse_snapshots(a.snapshots, snapshots, error)) return fail(kExitUsage, error);
    const bool stream_output = std::filesystem::path(a.output).extension() == ".ellc";
    MeshFileType mesh_type;
    if (!stream_output && !mesh_file_type_from_path(a.output, mesh_type))
        return fail(kExitUsage, "-o: \"" + a.output + "\": expected a model (.glb, .gltf, .ply, .obj) or a stream file (.ellc)");
    const bool gltf_output = !stream_output && (mesh_type == MeshFileType::Glb || mesh_type == MeshFileType::Gltf);
    broadcast::Endpoint from;
    if (!broadcast::parse_endpoint(a.from, from, error)) return fail(kExitUsage, "--from: " + error);
    broadcast::ReceiverOptions receiver_options;
    receiver_options.interface = a.interface;
    broadcast::UdpReceiver receiver;
    if (!receiver.open(from, receiver_options, error)) return fail(kExitFailure, error);

    broadcast::Reception::Options reception_options;
    reception_options.limits.max_elements = a.max_elements;
    reception_options.limits.max_pending_bytes = a.max_pending_mb << 20;
    if (a.stream_id >= 0) reception_options.stream_id = static_cast<uint32_t>(a.stream_id);
    if (!a.key.empty()) {
        auth::PublicKey key;
        if (!auth::read_public_key(a.key, key, error)) return fail(kExitUsage, "--key: " + error);
        reception_options.key = key;
    }
    broadcast::Reception reception(reception_options);
    // The stream shown and written: the candidate with the most packets (broadcast/reception.h);
    // it may change while packets arrive.
    auto stream = [&]() -> const ReceivedStream& { return reception.stream(); };
    // Packets that brought new content, with the candidates that took them (only for .ellc output).
    std::vector<std::pair<uint64_t, std::vector<uint8_t>>> kept;
    auto kept_of_chosen = [&]() {
        std::vector<std::vector<uint8_t>> packets;
        for (const auto& [by, bytes] : kept)
            if (reception.chosen() < 64 && (by >> reception.chosen() & 1)) packets.push_back(bytes);
        return packets;
    };
    // The candidate the live reconstruction is built on, by serial (a place may be given to another
    // candidate when the reception makes room).
    uint64_t live_candidate = UINT64_MAX;
    auto chosen_serial = [&]() {
        return reception.chosen() < reception.candidate_count() ? reception.candidate_serial(reception.chosen()) : UINT64_MAX;
    };
    std::vector<uint8_t> buffer(kMaxPacketSize + 1);
    LiveReconstruction live(a.grid);
    // The page shows the live reconstruction: with --view it is built whatever the output.
    const bool live_wanted = !stream_output || a.view;
    std::optional<LiveView> view;
    uint64_t region_applied = 0;
    if (a.view) {
        LiveViewOptions view_options;
        view_options.bind = a.view_bind;
        view_options.port = a.view_port;
        view_options.three_dir = a.three;
        view_options.reference = a.reference;
        view_options.title = "reception on " + a.from;
        view.emplace();
        if (!view->start(view_options, error)) return fail(kExitFailure, "--view: " + error);
        std::fprintf(stderr, "view: %s\n", view->url().c_str());
        if (view->reachable_from_other_hosts())
            std::fprintf(stderr, "ellicast: warning: --view-bind %s: the page can be opened from other hosts\n",
                         a.view_bind.c_str());
        std::fflush(stderr);
    }

    std::signal(SIGINT, on_receive_interrupt);
    std::signal(SIGTERM, on_receive_interrupt);
    const bool tty = isatty(fileno(stderr)) != 0;
    const auto start = std::chrono::steady_clock::now();
    // Done: the stream shown is complete and, when more than one stream was heard without a key to
    // tell them apart, every other one too (a small forged stream that completes first must not end
    // the reception while the real one is still arriving; --until, --stream-id or --key end the wait).
    bool told_waiting = false;
    auto done = [&]() {
        if (!reception.complete()) return false;
        if (reception.candidate_count() <= 1 || reception.authenticator() || reception.every_candidate_complete())
            return true;
        if (!told_waiting && !a.quiet) {
            std::fprintf(stderr,
                         "%sellicast: warning: the stream shown is complete, but %zu streams were heard on this address: "
                         "waiting for every one to complete (--until, --stream-id or --key end this)\n",
                         tty ? "\n" : "", reception.candidate_count());
            told_waiting = true;
        }
        return false;
    };
    auto seconds_since = [&](std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(t - start).count();
    };
    double first_packet_at = -1, base_at = -1, shown_at = -1, complete_at = -1;
    auto last_progress = start;
    auto print_progress = [&](bool final_line) {
        if (a.quiet) return;
        const auto& c = reception.counters();
        uint64_t declared = reception.points_declared();
        std::fprintf(stderr,
                     "%s%.1f s: %s packets received, %s rejected (%s damaged, %s not ellicast, %s other stream, %s "
                     "oversized%s), est. loss %.1f%%, base %s, points %s/%s received, %s inserted%s",
                     tty && !final_line ? "\r" : "", seconds_since(std::chrono::steady_clock::now()),
                     with_commas(c.accepted + c.duplicates).c_str(), with_commas(c.rejected()).c_str(),
                     with_commas(c.damaged).c_str(), with_commas(c.not_ellicast).c_str(),
                     with_commas(c.other_stream).c_str(), with_commas(c.oversized).c_str(),
                     reception.authenticator()
                         ? (", " + with_commas(c.unauthenticated) + " not authenticated, " +
                            with_commas(c.awaiting_manifest) + " waiting for their MANIFEST")
                               .c_str()
                         : "",
                     100.0 * reception.loss().loss(), reception.base_complete() ? "complete" : "incomplete",
                     with_commas(reception.points_received()).c_str(), declared ? with_commas(declared).c_str() : "?",
                     with_commas(live.inserted()).c_str(), tty && !final_line ? "  " : "\n");
        std::fflush(stderr);
    };
    auto take_snapshot = [&](Snapshot& s) {
        s.done = true;
        std::string path = snapshot_path(a.output, s.label);
        std::string e;
        std::vector<std::string> warnings;
        bool ok = stream_output ? write_received(path, kept_of_chosen(), e)
                                : write_model(path, stream(), live.objects(), gltf_output, warnings, e);
        if (ok)
            std::fprintf(stderr, "%swrote snapshot %s (%s points %s)\n", tty && !a.quiet ? "\n" : "", path.c_str(),
                         with_commas(stream_output ? reception.points_received() : live.inserted()).c_str(),
                         stream_output ? "received" : "inserted");
        else
            std::cerr << "ellicast: warning: snapshot: " << e << "\n";
    };

    while (!g_receive_stop.load()) {
        auto now = std::chrono::steady_clock::now();
        double elapsed = seconds_since(now);
        if (deadline_seconds > 0 && elapsed >= deadline_seconds) break;
        // Wait for datagrams only when there is no reconstruction work to do; then read every
        // datagram that is waiting before working again.
        const bool busy = live.started() && !live.caught_up(stream());
        double wait = busy ? 0.0 : (view ? 0.05 : 0.2);
        if (deadline_seconds > 0) wait = std::min(wait, deadline_seconds - elapsed);
        for (int n = 0; n < 1024; ++n) {
            broadcast::Datagram datagram;
            auto timeout = std::chrono::milliseconds(n == 0 ? static_cast<int64_t>(wait * 1000) : 0);
            int got = receiver.receive(buffer, timeout, datagram, error);
            if (got < 0) return fail(kExitFailure, error);
            if (got == 0) break;
            std::span<const uint8_t> bytes(buffer.data(), datagram.size);
            const uint64_t verified_before =
                reception.authenticator() ? reception.authenticator()->counters().manifests_verified : 0;
            const Error taken = reception.take(bytes, datagram.truncated);
            // A candidate dropped to make room: the packets it took are no longer its place's.
            if (const uint64_t evicted = reception.last_evicted(); evicted != 0 && stream_output)
                for (auto& [by, packet] : kept)
                    if (by != ~uint64_t(0)) by &= ~evicted;
            if (taken != Error::Ok) continue;
            if (first_packet_at < 0) first_packet_at = seconds_since(std::chrono::steady_clock::now());
            if (stream_output && reception.last_accepted_by() != 0)
                kept.emplace_back(reception.last_accepted_by(), std::vector<uint8_t>(bytes.begin(), bytes.end()));
            // A signed stream's recording keeps each MANIFEST part that verified, so that it can be
            // checked again (decode --key, validate --key), and the packets it released.
            if (stream_output && reception.authenticator()) {
                if (reception.authenticator()->counters().manifests_verified > verified_before)
                    kept.emplace_back(~uint64_t(0), std::vector<uint8_t>(bytes.begin(), bytes.end()));
                for (auto& released : reception.take_released_accepted()) kept.push_back(std::move(released));
            }
            if (done()) break;
        }
        if (base_at < 0 && reception.base_complete()) {
            base_at = seconds_since(std::chrono::steady_clock::now());
            if (live_wanted) {
                if (view) view->publish_preview(reception, seconds_since(std::chrono::steady_clock::now()));
                if (!live.start(stream(), error)) return fail(kExitFailure, "building the base mesh: " + error);
                live_candidate = chosen_serial();
                shown_at = seconds_since(std::chrono::steady_clock::now());
                if (!a.quiet)
                    std::fprintf(stderr, "%sbase mesh ready after %s (base complete after %s)\n", tty ? "\n" : "",
                                 seconds_text(shown_at).c_str(), seconds_text(base_at).c_str());
            }
            // The base snapshot shows the base alone, before any point is inserted.
            for (auto& s : snapshots)
                if (!s.done && s.kind == Snapshot::Base) take_snapshot(s);
        }
        if (done()) {
            complete_at = seconds_since(std::chrono::steady_clock::now());
            break;
        }
        if (live_wanted && live.started() && chosen_serial() != live_candidate && reception.base_complete()) {
            // Another candidate has overtaken the one shown: show that one from its base.
            if (!live.start(stream(), error)) return fail(kExitFailure, "building the base mesh: " + error);
            live_candidate = chosen_serial();
            if (!a.quiet)
                std::fprintf(stderr, "%sswitched to stream id 0x%X (the candidate with the most packets)\n", tty ? "\n" : "",
                             stream().stream_id());
        }
        if (view && live.started() && view->region_version() != region_applied) {
            region_applied = view->region_version();
            live.set_region(view->region() ? region_filter(*view->region(), stream()) : LiveReconstruction::InsertIf{});
        }
        if (live_wanted && live.started() && !live.caught_up(stream())) live.work(stream(), std::chrono::milliseconds(view && view->serving() ? 5 : 20));
        now = std::chrono::steady_clock::now();
        if (view) {
            view->update(reception, live, seconds_since(now), {});
            view->poll(std::chrono::milliseconds(0));
        }
        const uint64_t shown_points = stream_output ? reception.points_received() : live.inserted();
        const double share = reception.points_declared() ? 100.0 * double(shown_points) / double(reception.points_declared()) : 0.0;
        for (auto& s : snapshots) {
            if (s.done || base_at < 0) continue;
            if (s.kind == Snapshot::Base || (s.kind == Snapshot::Points && share >= s.value) ||
                (s.kind == Snapshot::Seconds && seconds_since(now) >= s.value))
                take_snapshot(s);
        }
        if (now - last_progress > std::chrono::milliseconds(tty ? 250 : 5000)) {
            print_progress(false);
            last_progress = now;
        }
    }
    if (view) {
        // The page's last picture: everything inserted (the final decode below writes the output).
        while (live.started() && !live.caught_up(stream()) && !g_receive_stop.load())
            live.work(stream(), std::chrono::milliseconds(100));
        view->update(reception, live, seconds_since(std::chrono::steady_clock::now()), {}, true);
        view->poll(std::chrono::milliseconds(0));
    }
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (tty && !a.quiet) std::fprintf(stderr, "\n");
    print_progress(true);
    if (const auth::Authenticator* authenticator = reception.authenticator()) {
        const auto& ac = authenticator->counters();
        if (std::string problem = authenticator->problem(); !problem.empty())
            std::fprintf(stderr, "ellicast: warning: %s\n", problem.c_str());
        else
            std::fprintf(stderr,
                         "signed stream: %s MANIFEST part(s) verified, %s packet(s) authenticated, %s rejected as not "
                         "authenticated, %s MANIFEST(s) failed verification, %s left unchecked (verification "
                         "budget spent: a flood of MANIFESTs)\n",
                         with_commas(ac.manifests_verified).c_str(), with_commas(ac.passed).c_str(),
                         with_commas(ac.not_authenticated).c_str(), with_commas(ac.manifests_failed).c_str(),
                         with_commas(ac.manifests_unchecked).c_str());
    }
    if (reception.authenticator() && reception.authenticator()->counters().passed == 0)
        return fail(kExitInvalid, "nothing authenticated with the key given: " + reception.authenticator()->problem() +
                                      " (" + with_commas(reception.counters().datagrams) + " datagrams)");
    if (first_packet_at < 0)
        return fail(kExitFailure, "no packet of an ellicast stream arrived on " + a.from + " (" +
                                      with_commas(reception.counters().datagrams) + " datagrams dropped" +
                                      (reception.authenticator() ? ", none authenticated with the key given" : "") + ")");
    std::fprintf(stderr, "first packet after %s; base %s; everything %s\n", seconds_text(first_packet_at).c_str(),
                 base_at >= 0 ? ("complete after " + seconds_text(base_at)).c_str() : "incomplete",
                 complete_at >= 0 ? ("complete after " + seconds_text(complete_at)).c_str()
                                  : (g_receive_stop.load() ? "not complete (interrupted)" : "not complete at the deadline"));
    if (reception.candidate_count() > 1) {
        std::string heard;
        for (size_t i = 0; i < reception.candidate_count(); ++i) {
            char line[96];
            std::snprintf(line, sizeof line, "%sstream id 0x%X with %llu packets accepted", i ? ", " : "",
                          reception.candidate(i).stream_id(),
                          (unsigned long long)reception.candidate(i).counters().accepted);
            heard += line;
        }
        char kept_id[32];
        std::snprintf(kept_id, sizeof kept_id, "0x%X", stream().stream_id());
        std::fprintf(stderr,
                     "ellicast: warning: %zu candidate streams were heard (%s; a stream id can appear twice when its "
                     "stream info was contradicted); kept stream id %s, the one with the most packets. Another sender "
                     "may be on this address: --stream-id picks a stream\n",
                     reception.candidate_count(), heard.c_str(), kept_id);
    }
    if (stream_output) {
        for (auto& s : snapshots)
            if (!s.done && base_at >= 0) take_snapshot(s);
        const auto packets = kept_of_chosen();
        if (!write_received(a.output, packets, error)) return fail(kExitFailure, error);
        std::fprintf(stderr, "wrote %s: %s packets\n", a.output.c_str(), with_commas(packets.size()).c_str());
        if (view) keep_serving(*view, a.view_linger);
        return kExitOk;
    }
    // The final model: everything received, decoded in stream order (deterministic: the same as
    // `ellicast decode` of the same packets), object by object.
    auto t0 = std::chrono::steady_clock::now();
    ProgressBar bar(!a.quiet);
    DecodeOptions options;
    options.grid_resolution = a.grid;
    options.progress = [&](const std::string& stage, double fraction) { bar.update(stage, fraction); };
    const ReceivedStream& chosen = stream();
    if (!chosen.info()) {
        const std::string why = chosen.stream_info_problem();
        return fail(kExitInvalid, why.empty() ? "no STREAM_INFO packet arrived: nothing can be decoded"
                                              : "no STREAM_INFO packet was accepted (" + why + "): nothing can be decoded");
    }
    std::vector<Mesh> objects(chosen.objects().size());
    size_t vertices = 0, faces = 0, built = 0, exact = 0;
    options.base_grid_nodes = shared_base_grid_nodes(chosen, options);
    // --until bounds the whole command: the last decode inserts no point past the deadline, and an
    // exact layer is not decoded once it has passed.
    std::optional<std::chrono::steady_clock::time_point> deadline;
    if (deadline_seconds > 0)
        deadline = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(deadline_seconds));
    options.deadline = deadline;
    auto past_deadline = [&] { return deadline && std::chrono::steady_clock::now() >= *deadline; };
    for (size_t i = 0; i < objects.size(); ++i) {
        const auto& object = chosen.objects()[i];
        if (!object.info) {
            std::fprintf(stderr, "ellicast: warning: object %zu: its stream info entry never arrived\n", i);
            continue;
        }
        ObjectDecodeReport report;
        // The exact layer (spec 19.4): every point and the whole connectivity give the original triangles.
        std::string why;
        bool unusable = false;
        const bool late = object.connectivity && past_deadline();
        if (late) {
            std::fprintf(stderr, "object %zu: its exact layer is not decoded: the deadline (--until) has passed\n", i);
        } else if (object.connectivity && exact_mesh(chosen, i, objects[i], why, unusable)) {
            std::fprintf(stderr, "object %zu: exact (the original %s triangles)\n", i,
                         with_commas(objects[i].triangles.size()).c_str());
            objects[i].name = "object" + std::to_string(i);
            vertices += objects[i].positions.size();
            faces += objects[i].triangles.size();
            ++built;
            ++exact;
            continue;
        }
        if (unusable) std::fprintf(stderr, "ellicast: warning: object %zu: its exact layer is unusable (%s)\n", i, why.c_str());
        else if (object.connectivity && !late)
            std::fprintf(stderr, "object %zu: not exact yet (%s): reconstructed\n", i, why.c_str());
        if (!decode_object(*object.info, chosen.ellipsoids(i), chosen.points(i), chosen.info()->grid_hint, options, i,
                           objects[i], report, error)) {
            // One object that cannot be built does not cost the others theirs.
            std::fprintf(stderr, "ellicast: warning: object %zu: not decoded: %s\n", i, error.c_str());
            objects[i] = Mesh{};
            continue;
        }
        for (const auto& note : report.notes)
            std::fprintf(stderr, "ellicast: warning: object %zu: %s\n", i, note.c_str());
        objects[i].name = "object" + std::to_string(i);
        vertices += objects[i].positions.size();
        faces += objects[i].triangles.size();
        if (!objects[i].positions.empty()) ++built;
    }
    bar.finish();
    if (built == 0) return fail(kExitInvalid, "nothing can be built: no object received any ellipsoid or point");
    std::vector<std::string> warnings;
    for (auto& s : snapshots) {
        if (s.done || base_at < 0) continue;
        std::string path = snapshot_path(a.output, s.label), e;
        if (write_model(path, chosen, objects, gltf_output, warnings, e))
            std::fprintf(stderr, "wrote snapshot %s (final model)\n", path.c_str());
    }
    if (!write_model(a.output, chosen, std::move(objects), gltf_output, warnings, error))
        return fail(kExitFailure, error);
    for (const auto& w : warnings) std::fprintf(stderr, "ellicast: warning: %s\n", w.c_str());
    std::fprintf(stderr, "decoded in %s; wrote %s: %zu object(s) (%zu exact), %s vertices, %s triangles\n",
                 seconds_text(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()).c_str(),
                 a.output.c_str(), built, exact, with_commas(vertices).c_str(), with_commas(faces).c_str());
    if (view) keep_serving(*view, a.view_linger);
    return kExitOk;
}

const RegisterCommand kRegisterReceive{{63, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<ReceiveArgs>();
    auto* cmd = app.add_subcommand("receive", "Join a UDP broadcast at any moment and rebuild the model it carries");
    cmd->add_option("--from", args->from,
                    "ADDRESS:PORT to listen on: a local address (127.0.0.1:5000, [::]:5000) or a multicast group")
        ->required();
    cmd->add_option("-o,--output", args->output,
                    "the model (.glb, .gltf, .ply, .obj), or what was received as a stream file (.ellc)")
        ->required();
    cmd->add_option("--grid", args->grid, "decoder grid resolution (default: the stream's hint)")
        ->check(CLI::Range(kMinGridResolution, kMaxGridResolution));
    cmd->add_option("--snapshots", args->snapshots,
                    "comma-separated moments to write OUT-<moment> too: base, a share of the points (50%), a time (2.5s)");
    cmd->add_option("--until", args->until, "stop when \"complete\" (default) or after this many seconds");
    cmd->add_option("--interface", args->interface, "network interface to join a multicast group on, e.g. lo");
    cmd->add_option("--stream-id", args->stream_id, "keep only this stream id (default: every stream heard, as candidates; the one with the most packets is written)")
        ->check(CLI::Range(int64_t(0), int64_t(0xFFFFFFFF)));
    cmd->add_option("--max-elements", args->max_elements,
                    "refuse a stream that declares more ellipsoids + points than this (memory cap)")
        ->check(CLI::Range(uint64_t(1), uint64_t(1'000'000'000)));
    cmd->add_option("--max-pending-mb", args->max_pending_mb,
                    "megabytes of packets held while waiting for the stream info (memory cap, default 64)")
        ->check(CLI::Range(size_t(1), size_t(4096)));
    cmd->add_option("--key", args->key,
                    "public key (NAME.pub or 64 hex digits): accept only packets a MANIFEST signed with it lists");
    auto* view_flag = cmd->add_flag("--view", args->view,
                  "watch the reception in a web page (three.js): http://127.0.0.1:8765/ unless --view-bind/--view-port say otherwise");
    cmd->add_option("--view-bind", args->view_bind,
                    "address the page is served on (default 127.0.0.1: this machine only)")
        ->needs(view_flag);
    cmd->add_option("--view-port", args->view_port, "TCP port of the page (default 8765; 0: any free port)")
        ->needs(view_flag);
    cmd->add_option("--three", args->three, "three.js's npm package folder (default: the one scripts/setup.sh installs)")
        ->needs(view_flag);
    cmd->add_option("--reference", args->reference, "the original model: the page shows the surface error against it")
        ->needs(view_flag);
    cmd->add_option("--view-linger", args->view_linger,
                    "seconds to keep serving the page after the output is written (default: until Ctrl-C)")
        ->check(CLI::Range(0.0, 1e7))
        ->needs(view_flag);
    cmd->add_flag("-q,--quiet", args->quiet, "no progress on stderr");
    cmd->callback([args, &exit_code] { exit_code = run_receive(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

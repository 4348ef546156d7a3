// The live view behind `ellicast view` and `ellicast receive --view`: a local web page (three.js)
// showing the model as it arrives. The reception loop calls update() as packets come and the live
// reconstruction works; the view publishes the current model as GLB (at most every
// `min_interval`, and at once when an object turns exact) and a status (packets, loss, points,
// per-object state, surface error against a reference model when one is given) as Server-Sent
// Events, and serves them with the page and three.js from the HTTP server of viewer/.
#pragma once

#include "live_reconstruction.h"

#include "ellicast/codec/mesh.h"
#include "ellicast/codec/region.h"
#include "ellicast/converters/asset.h"

#include <ellicast/broadcast/reception.h>
#include <ellicast/viewer/http_server.h>

#include <chrono>
#include <future>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ellicast::cli {

struct LiveViewOptions {
    std::string bind = "127.0.0.1";
    uint16_t port = 8765;
    std::string three_dir;      // three.js's npm package folder; empty: look in the usual places
    std::string reference;      // a model file to measure the surface error against (optional)
    std::string title;          // what is being shown ("bunny.ellc at 30% loss")
    std::chrono::milliseconds min_interval{150};  // between two published models
};

// What the view knows of the channel beyond the reception (the simulator knows what it lost).
struct ChannelFacts {
    std::optional<uint64_t> slots_sent, slots_lost;
};

class LiveView {
public:
    // Finds three.js, loads the reference model and starts listening. False with `error`.
    bool start(const LiveViewOptions& options, std::string& error);
    std::string url() const { return server_.url(); }
    bool reachable_from_other_hosts() const { return !server_.loopback(); }

    // Publishes what changed: the status at most every 250 ms, the model when the reconstruction
    // changed (at most every min_interval; at once when an object turned exact or `final`).
    void update(const broadcast::Reception& reception, const LiveReconstruction& live, double seconds,
                const ChannelFacts& channel, bool final = false);
    // The first picture, before the live reconstruction builds its base: every surface object's
    // base on a coarse grid (a few tens of milliseconds), published at once; then serves the page
    // until each open page has fetched it (at most 200 ms), so that it shows while the full base
    // is built.
    void publish_preview(const broadcast::Reception& reception, double seconds);
    // Serves the page for at most `timeout`, then finishes writing any response begun (a model: the
    // browser reads it in a few milliseconds on this machine, where written a piece per call between
    // slices of reconstruction it took 130-180 ms), for at most 100 ms more.
    void poll(std::chrono::milliseconds timeout);
    size_t viewers() const { return server_.event_clients(); }
    // A page is fetching something, or a model published last has not been fetched by every open page
    // yet: keep the slices of other work short, so that the request is read soon.
    bool serving() const { return server_.writing() || (model_version_ > 0 && model_fetches_ < server_.event_clients()); }
    // The page's camera when it asks to refine where it looks (GET /camera?eye=X,Y,Z&target=X,Y,Z&fov=DEG&aspect=A;
    // /camera?off ends it), and a number that changes with it.
    const std::optional<Region>& region() const { return region_; }
    uint64_t region_version() const { return region_version_; }
    uint64_t models_published() const { return model_version_; }
    // Seconds spent building the published models (the reconstruction's meshes to GLB).
    double publish_seconds() const { return publish_seconds_; }

private:
    void publish_model(const broadcast::Reception& reception, const LiveReconstruction& live, double seconds);
    void publish_asset(const Asset& asset, double seconds);
    std::string status_json(const broadcast::Reception& reception, const LiveReconstruction& live, double seconds,
                            const ChannelFacts& channel, bool final) const;

    LiveViewOptions options_;
    viewer::HttpServer server_;
    std::string three_dir_;
    std::vector<Mesh> reference_;  // world space, empty without a reference
    std::vector<Mesh> shown_;      // the model published last, world space (kept with a reference)
    std::string glb_;              // the current model
    uint64_t model_version_ = 0;
    uint64_t model_fetches_ = 0;  // /model.glb answered for the current version
    bool preview_published_ = false;
    uint64_t published_changes_ = UINT64_MAX;
    size_t published_exact_ = 0;
    uint64_t triangles_ = 0;
    std::string status_;  // the last status sent
    std::optional<double> error_percent_;
    double error_at_ = -1e9;           // when the error was last measured
    uint64_t error_model_version_ = 0;  // the model it was measured on
    std::vector<std::pair<double, double>> history_;  // (seconds, error % or share of points %)
    std::chrono::steady_clock::time_point last_model_{}, last_status_{};
    double last_build_seconds_ = 0;
    std::optional<Region> region_;
    uint64_t region_version_ = 0;
    // The surface error being measured on its own thread (declared last: it reads reference_,
    // and a future from std::async waits for its thread when destroyed).
    std::future<std::optional<double>> error_job_;
    double publish_seconds_ = 0;
};

// three.js's npm package folder: `given` when not empty (an error when it holds no
// build/three.module.js), else $ELLICAST_THREE_DIR, else the copy scripts/setup.sh installs
// beside the sources. False with `error` naming where it looked and how to get it.
bool find_three_dir(const std::string& given, std::string& out, std::string& error);

}  // namespace ellicast::cli

// The live view (see live_view.h).
#include "live_view.h"

#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/asset.h"
#include "region_option.h"

#include <ellicast/viewer/web_assets.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <sstream>

#include <unistd.h>

namespace ellicast::cli {
namespace {

const char* state_name(LiveReconstruction::State s) {
    switch (s) {
        case LiveReconstruction::State::Waiting: return "waiting";
        case LiveReconstruction::State::Base: return "base";
        case LiveReconstruction::State::Points: return "points";
        case LiveReconstruction::State::Exact: return "exact";
        case LiveReconstruction::State::PointSet: return "point set";
    }
    return "waiting";
}

viewer::HttpResponse web_asset_response(const std::string& name) {
    const viewer::WebAsset* asset = viewer::find_web_asset(name);
    if (!asset) return viewer::http_error(404, "not found: " + name);
    viewer::HttpResponse r;
    r.content_type = viewer::content_type_for(name);
    r.body.assign(reinterpret_cast<const char*>(asset->data), asset->size);
    r.no_store = true;
    return r;
}

// "eye=1,2,3&target=0,0,0&fov=40&aspect=1.5" -> a view region (parse_region's "view:..." form);
// false with `error`.
bool parse_camera_query(const std::string& query, Region& out, std::string& error) {
    std::string eye, target, fov, aspect = "1";
    std::stringstream items(query);
    std::string item;
    while (std::getline(items, item, '&')) {
        const auto eq = item.find('=');
        const std::string key = item.substr(0, eq), value = eq == std::string::npos ? "" : item.substr(eq + 1);
        if (key == "eye") eye = value;
        else if (key == "target") target = value;
        else if (key == "fov") fov = value;
        else if (key == "aspect") aspect = value;
    }
    if (eye.empty() || target.empty() || fov.empty()) {
        error = "camera: eye, target and fov are required";
        return false;
    }
    return parse_region("view:" + eye + "," + target + "," + fov + "," + aspect, out, error);
}

std::filesystem::path executable_dir() {
    std::error_code ec;
    auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::filesystem::path() : exe.parent_path();
}

}  // namespace

bool find_three_dir(const std::string& given, std::string& out, std::string& error) {
    auto holds_three = [](const std::filesystem::path& dir) {
        std::error_code ec;
        return std::filesystem::is_regular_file(dir / "build" / "three.module.js", ec) &&
               std::filesystem::is_directory(dir / "examples" / "jsm", ec);
    };
    if (!given.empty()) {
        if (!holds_three(given)) {
            error = "--three \"" + given + "\": not three.js's npm package (no build/three.module.js and examples/jsm in it)";
            return false;
        }
        out = given;
        return true;
    }
    std::vector<std::filesystem::path> places;
    if (const char* env = std::getenv("ELLICAST_THREE_DIR"); env && *env) places.emplace_back(env);
    if (auto dir = executable_dir(); !dir.empty()) {
        places.push_back(dir / ".." / ".cache" / "node" / "node_modules" / "three");  // build/ in a source tree
        places.push_back(dir / ".." / "share" / "ellicast" / "three");               // an installed tool
    }
#ifdef ELLICAST_SOURCE_DIR
    places.push_back(std::filesystem::path(ELLICAST_SOURCE_DIR) / ".cache" / "node" / "node_modules" / "three");
#endif
    std::string looked;
    for (const auto& p : places) {
        if (holds_three(p)) {
            out = std::filesystem::weakly_canonical(p).string();
            return true;
        }
        looked += (looked.empty() ? "" : ", ") + p.lexically_normal().string();
    }
    error = "three.js not found (looked in " + looked +
            "): run scripts/setup.sh, which installs it with npm into .cache/node, or `npm install three` and give "
            "--three DIR/node_modules/three";
    return false;
}

bool LiveView::start(const LiveViewOptions& options, std::string& error) {
    options_ = options;
    if (!find_three_dir(options.three_dir, three_dir_, error)) return false;
    if (!options.reference.empty()) {
        try {
            Asset reference = load_asset(options.reference);
            reference_ = flatten_asset(reference);
        } catch (const std::exception& e) {
            error = "--reference: " + std::string(e.what());
            return false;
        }
        size_t triangles = 0;
        for (const auto& m : reference_) triangles += m.triangles.size();
        if (triangles == 0) {
            error = "--reference \"" + options.reference + "\": it has no triangles to measure against";
            return false;
        }
    }
    server_.route("/", [](const std::string&, const std::string&) { return web_asset_response("index.html"); });
    for (const char* name : {"viewer.js", "viewer.css"})
        server_.route(std::string("/") + name,
                      [name](const std::string&, const std::string&) { return web_asset_response(name); });
    server_.route("/favicon.ico", [](const std::string&, const std::string&) {
        viewer::HttpResponse r = web_asset_response("favicon.svg");
        r.content_type = "image/svg+xml";
        return r;
    });
    server_.route_prefix("/three/", [this](const std::string& rest, const std::string&) {
        return viewer::file_response(three_dir_, rest);
    });
    server_.route("/model.glb", [this](const std::string&, const std::string&) {
        if (glb_.empty()) return viewer::http_error(404, "no model yet: the base has not arrived");
        ++model_fetches_;
        viewer::HttpResponse r;
        r.content_type = "model/gltf-binary";
        r.body = glb_;
        r.no_store = true;
        return r;
    });
    server_.route("/camera", [this](const std::string&, const std::string& query) {
        if (query == "off") {
            region_.reset();
            ++region_version_;
            return viewer::HttpResponse{200, "text/plain; charset=utf-8", "refining everything\n", true};
        }
        Region region;
        std::string problem;
        if (!parse_camera_query(query, region, problem)) return viewer::http_error(400, problem);
        region_ = region;
        ++region_version_;
        return viewer::HttpResponse{200, "text/plain; charset=utf-8", "refining " + region.describe() + "\n", true};
    });
    server_.route("/status.json", [this](const std::string&, const std::string&) {
        viewer::HttpResponse r;
        r.content_type = "application/json";
        r.body = status_.empty() ? "{}" : status_;
        r.no_store = true;
        return r;
    });
    server_.event_stream("/events", [this] {
        std::vector<std::pair<std::string, std::string>> greeting;
        if (!status_.empty()) greeting.emplace_back("status", status_);
        if (model_version_ > 0)
            greeting.emplace_back("model", "{\"version\":" + std::to_string(model_version_) + "}");
        return greeting;
    });
    return server_.listen(options.bind, options.port, error);
}

void LiveView::poll(std::chrono::milliseconds timeout) {
    server_.poll(timeout);
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
    while (server_.writing() && std::chrono::steady_clock::now() < until) server_.poll(std::chrono::milliseconds(1));
}

void LiveView::publish_model(const broadcast::Reception& reception, const LiveReconstruction& live, double seconds) {
    publish_asset(received_asset(reception.stream(), live.objects()), seconds);
}

void LiveView::publish_preview(const broadcast::Reception& reception, double seconds) {
    const ReceivedStream& stream = reception.stream();
    if (!stream.info()) return;
    std::vector<Mesh> objects(stream.objects().size());
    DecodeOptions options;
    options.faces_per_point = 0;
    for (size_t i = 0; i < objects.size(); ++i) {
        const auto& info = stream.objects()[i].info;
        if (!info || info->kind != ObjectKind::Surface) continue;
        const int hint = stream.info()->grid_hint > 0 ? stream.info()->grid_hint : kDefaultGridResolution;
        options.grid_resolution = std::clamp(hint / 2, kMinGridResolution, 48);
        ObjectDecodeReport report;
        std::string error;
        if (!decode_object(*info, stream.ellipsoids(i), {}, stream.info()->grid_hint, options, i, objects[i], report, error))
            objects[i] = Mesh{};
    }
    publish_asset(received_asset(stream, std::move(objects)), seconds);
    preview_published_ = true;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
    while (model_fetches_ < server_.event_clients() && std::chrono::steady_clock::now() < until)
        server_.poll(std::chrono::milliseconds(10));
}

void LiveView::publish_asset(const Asset& asset, double seconds) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<uint8_t> bytes;
    std::vector<std::string> warnings;
    std::string error;
    // Quantized (KHR_mesh_quantization, which three.js reads): about half the bytes for the page
    // to fetch and parse with every picture.
    AssetWriteOptions write;
    write.quantize = true;
    if (!write_asset_glb(asset, write, bytes, warnings, error)) {
        server_.send_event("problem", nlohmann::json("the model cannot be written as GLB: " + error).dump());
        return;
    }
    glb_.assign(bytes.begin(), bytes.end());
    model_fetches_ = 0;
    triangles_ = 0;
    std::vector<Mesh> flat = flatten_asset(asset);
    for (const auto& m : flat) triangles_ += m.triangles.size();
    if (!reference_.empty()) shown_ = std::move(flat);
    ++model_version_;
    last_build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    publish_seconds_ += last_build_seconds_;
    server_.send_event("model", nlohmann::ordered_json{{"version", model_version_},
                                                       {"bytes", glb_.size()},
                                                       {"triangles", triangles_},
                                                       {"seconds", seconds}}
                                    .dump());
}

void LiveView::update(const broadcast::Reception& reception, const LiveReconstruction& live, double seconds,
                      const ChannelFacts& channel, bool final) {
    const auto now = std::chrono::steady_clock::now();
    size_t exact = 0;
    for (size_t i = 0; i < live.object_count(); ++i) exact += live.state(i) == LiveReconstruction::State::Exact;
    const bool turned_exact = exact != published_exact_;
    // Building the GLB takes time on a large model: publish no more often than thrice that.
    const auto interval = std::max<std::chrono::steady_clock::duration>(
        options_.min_interval, std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(3 * last_build_seconds_)));
    bool published = false;
    if (live.started() && live.changes() != published_changes_ && (final || turned_exact || now - last_model_ >= interval)) {
        publish_model(reception, live, seconds);
        published_changes_ = live.changes();
        published_exact_ = exact;
        last_model_ = now;
        published = true;
    }
    if (!final && !published && now - last_status_ < std::chrono::milliseconds(250)) return;
    last_status_ = now;
    // The surface error on the model shown, at most once a second, on a thread of its own (it
    // samples both surfaces and builds their search trees: 0.1 to 0.3 s on the bunny) so that the
    // page's requests and the reconstruction do not wait for it. The last status waits for it.
    auto measure = [reference = &reference_](std::vector<Mesh> shown) -> std::optional<double> {
        SurfaceDistanceOptions o;
        o.samples = 10000;
        o.threads = 1;
        SurfaceDistance d;
        std::string error;
        if (!surface_distance(*reference, shown, o, d, error)) return std::nullopt;
        return d.percent(std::max(d.a_to_b.rms, d.b_to_a.rms));
    };
    if (error_job_.valid() && (final || error_job_.wait_for(std::chrono::seconds(0)) == std::future_status::ready))
        if (auto measured = error_job_.get()) error_percent_ = measured;
    const bool due = !reference_.empty() && !shown_.empty() && error_model_version_ != model_version_ &&
                     (final || turned_exact || seconds - error_at_ >= 1.0);
    if (due && final) {
        if (auto measured = measure(shown_)) error_percent_ = measured;
        error_model_version_ = model_version_;
    } else if (due && !error_job_.valid()) {
        error_job_ = std::async(std::launch::async, measure, shown_);
        error_at_ = seconds;
        error_model_version_ = model_version_;
    }
    const double declared = static_cast<double>(reception.points_declared());
    const double share = declared > 0 ? 100.0 * static_cast<double>(live.inserted()) / declared : 0.0;
    if (reference_.empty()) history_.emplace_back(seconds, share);
    else if (error_percent_) history_.emplace_back(seconds, *error_percent_);
    if (history_.size() > 600) {  // keep every second sample: the line keeps its shape
        std::vector<std::pair<double, double>> kept;
        for (size_t i = 0; i < history_.size(); i += 2) kept.push_back(history_[i]);
        history_ = std::move(kept);
    }
    status_ = status_json(reception, live, seconds, channel, final);
    server_.send_event("status", status_);
}

std::string LiveView::status_json(const broadcast::Reception& reception, const LiveReconstruction& live,
                                  double seconds, const ChannelFacts& channel, bool final) const {
    using Json = nlohmann::ordered_json;
    const auto c = reception.counters();
    const ReceivedStream& stream = reception.stream();
    Json packets = {{"datagrams", c.datagrams}, {"accepted", c.accepted},   {"duplicates", c.duplicates},
                    {"rejected", c.rejected()}, {"damaged", c.damaged},     {"loss_estimate", reception.loss().loss()}};
    if (channel.slots_sent) packets["sent"] = *channel.slots_sent;
    if (channel.slots_lost) packets["lost"] = *channel.slots_lost;
    Json objects = Json::array();
    size_t exact = 0;
    for (size_t i = 0; i < std::max(live.object_count(), stream.objects().size()); ++i) {
        const auto state = live.state(i);
        exact += state == LiveReconstruction::State::Exact;
        const ReceivedObject* r = i < stream.objects().size() ? &stream.objects()[i] : nullptr;
        // Before the live reconstruction has its base, an object the coarse first picture shows.
        const bool coarse = !live.started() && preview_published_ && r && r->info && r->info->kind == ObjectKind::Surface;
        objects.push_back({{"id", i},
                           {"state", coarse ? "coarse base" : state_name(state)},
                           {"points", r ? r->points.size() : 0},
                           {"declared", r && r->info ? r->info->point_count : 0},
                           {"inserted", live.inserted(i)}});
    }
    Json j = {{"title", options_.title},
              {"seconds", seconds},
              {"packets", std::move(packets)},
              {"ellipsoids", {{"received", reception.ellipsoids_received()}, {"declared", reception.ellipsoids_declared()}}},
              {"points", {{"received", reception.points_received()},
                          {"declared", reception.points_declared()},
                          {"inserted", live.inserted()}}},
              {"base", reception.base_complete()},
              {"complete", reception.complete()},
              {"objects", std::move(objects)},
              {"exact_objects", exact},
              {"held", live.held()},
              {"region", region_ ? Json(region_->describe()) : Json(nullptr)},
              {"model", {{"version", model_version_}, {"triangles", triangles_}, {"bytes", glb_.size()}}},
              {"error", {{"reference", options_.reference},
                         {"rms_percent", error_percent_ ? Json(*error_percent_) : Json(nullptr)}}},
              {"history", {{"kind", reference_.empty() ? "points" : "error"}, {"samples", history_}}}};
    if (final) j["final"] = true;
    return j.dump();
}

}  // namespace ellicast::cli

// The live view (see live_view.h).
#include "live_view.h"

#include "ellicast/codec/surface_distance.h"
#include "ellicast/converters/asset.h"

#include <ellicast/viewer/web_assets.h>

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

// A JSON string literal.
std::string view_json_string(const std::string& text) {
    std::string out = "\"";
    for (unsigned char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c < 0x20) {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
            out += escaped;
        } else {
            out += static_cast<char>(c);
        }
    }
    return out + "\"";
}

std::string view_json_number(double value) {
    if (!std::isfinite(value)) return "null";
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

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

// "eye=1,2,3&target=0,0,0&fov=40&aspect=1.5" -> a view region; false with `error`.
bool parse_camera_query(const std::string& query, Region& out, std::string& error) {
    std::array<double, 3> eye{}, target{};
    double fov = 0, aspect = 1;
    int have = 0;
    std::stringstream items(query);
    std::string item;
    auto numbers = [](const std::string& text, double* values, int count) {
        std::stringstream parts(text);
        std::string part;
        int n = 0;
        while (std::getline(parts, part, ',')) {
            if (n == count || part.empty()) return false;
            char* end = nullptr;
            values[n++] = std::strtod(part.c_str(), &end);
            if (*end != 0) return false;
        }
        return n == count;
    };
    while (std::getline(items, item, '&')) {
        const auto eq = item.find('=');
        const std::string key = item.substr(0, eq), value = eq == std::string::npos ? "" : item.substr(eq + 1);
        bool ok = true;
        if (key == "eye") ok = numbers(value, eye.data(), 3), have |= 1;
        else if (key == "target") ok = numbers(value, target.data(), 3), have |= 2;
        else if (key == "fov") ok = numbers(value, &fov, 1), have |= 4;
        else if (key == "aspect") ok = numbers(value, &aspect, 1);
        if (!ok) {
            error = "camera: \"" + item + "\" is not a list of numbers of the right length";
            return false;
        }
    }
    if (have != 7) {
        error = "camera: eye, target and fov are required";
        return false;
    }
    out = Region::view(eye, target, fov, aspect);
    error = out.problem();
    return error.empty();
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
        server_.send_event("problem", view_json_string("the model cannot be written as GLB: " + error));
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
    server_.send_event("model", "{\"version\":" + std::to_string(model_version_) + ",\"bytes\":" +
                                    std::to_string(glb_.size()) + ",\"triangles\":" + std::to_string(triangles_) +
                                    ",\"seconds\":" + view_json_number(seconds) + "}");
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
    status_ = status_json(reception, live, seconds, channel);
    if (final) status_.insert(status_.size() - 1, ",\"final\":true");
    server_.send_event("status", status_);
}

std::string LiveView::status_json(const broadcast::Reception& reception, const LiveReconstruction& live,
                                  double seconds, const ChannelFacts& channel) const {
    const auto c = reception.counters();
    const ReceivedStream& stream = reception.stream();
    std::string j = "{";
    j += "\"title\":" + view_json_string(options_.title);
    j += ",\"seconds\":" + view_json_number(seconds);
    j += ",\"packets\":{\"datagrams\":" + std::to_string(c.datagrams) + ",\"accepted\":" + std::to_string(c.accepted) +
         ",\"duplicates\":" + std::to_string(c.duplicates) + ",\"rejected\":" + std::to_string(c.rejected()) +
         ",\"damaged\":" + std::to_string(c.damaged) + ",\"loss_estimate\":" + view_json_number(reception.loss().loss());
    if (channel.slots_sent) j += ",\"sent\":" + std::to_string(*channel.slots_sent);
    if (channel.slots_lost) j += ",\"lost\":" + std::to_string(*channel.slots_lost);
    j += "}";
    j += ",\"ellipsoids\":{\"received\":" + std::to_string(reception.ellipsoids_received()) +
         ",\"declared\":" + std::to_string(reception.ellipsoids_declared()) + "}";
    j += ",\"points\":{\"received\":" + std::to_string(reception.points_received()) +
         ",\"declared\":" + std::to_string(reception.points_declared()) + ",\"inserted\":" + std::to_string(live.inserted()) +
         "}";
    j += std::string(",\"base\":") + (reception.base_complete() ? "true" : "false");
    j += std::string(",\"complete\":") + (reception.complete() ? "true" : "false");
    j += ",\"objects\":[";
    const size_t objects = std::max(live.object_count(), stream.objects().size());
    size_t exact = 0;
    for (size_t i = 0; i < objects; ++i) {
        const auto state = live.state(i);
        exact += state == LiveReconstruction::State::Exact;
        // Before the live reconstruction has its base, an object the coarse first picture shows.
        const bool coarse = !live.started() && preview_published_ && i < stream.objects().size() &&
                            stream.objects()[i].info && stream.objects()[i].info->kind == ObjectKind::Surface;
        const ReceivedObject* r = i < stream.objects().size() ? &stream.objects()[i] : nullptr;
        j += (i ? "," : "") + std::string("{\"id\":") + std::to_string(i) + ",\"state\":" +
             view_json_string(coarse ? "coarse base" : state_name(state)) + ",\"points\":" + std::to_string(r ? r->points.size() : 0) +
             ",\"declared\":" + std::to_string(r && r->info ? r->info->point_count : 0) +
             ",\"inserted\":" + std::to_string(live.inserted(i)) + "}";
    }
    j += "],\"exact_objects\":" + std::to_string(exact);
    j += ",\"held\":" + std::to_string(live.held()) +
         ",\"region\":" + (region_ ? view_json_string(region_->describe()) : std::string("null"));
    j += ",\"model\":{\"version\":" + std::to_string(model_version_) + ",\"triangles\":" + std::to_string(triangles_) +
         ",\"bytes\":" + std::to_string(glb_.size()) + "}";
    j += ",\"error\":{\"reference\":" + view_json_string(options_.reference) + ",\"rms_percent\":" +
         (error_percent_ ? view_json_number(*error_percent_) : std::string("null")) + "}";
    j += ",\"history\":{\"kind\":" + view_json_string(reference_.empty() ? "points" : "error") + ",\"samples\":[";
    for (size_t i = 0; i < history_.size(); ++i)
        j += (i ? "," : "") + std::string("[") + view_json_number(history_[i].first) + "," +
             view_json_number(history_[i].second) + "]";
    j += "]}}";
    return j;
}

}  // namespace ellicast::cli

// The C API (ellicast.h) over the C++ libraries: a receiver is a broadcast::Reception (candidates,
// keys, loss estimate) whose chosen stream is decoded by decode_asset into a snapshot; encoding is
// load_asset + encode_asset + write_container, as `ellicast encode` does. Every entry point catches
// every exception and turns it into a status and a message: nothing propagates across the C boundary.
#include "ellicast.h"

#include "ellicast/broadcast/reception.h"
#include "ellicast/codec/decoder.h"
#include "ellicast/converters/asset.h"
#include "ellicast/converters/asset_stream.h"
#include "ellicast/converters/mesh_input.h"
#include "ellicast/format.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <random>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

namespace {

using namespace ellicast;

thread_local std::string t_last_error;

ellicast_status fail(ellicast_status status, std::string message) {
    t_last_error = std::move(message);
    return status;
}

ellicast_status ok() {
    t_last_error.clear();
    return ELLICAST_OK;
}

// Runs `body` (returning a status) with every exception turned into a status and a message.
template <class Body>
ellicast_status guarded(const char* call, Body&& body) {
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return fail(ELLICAST_ERROR_MEMORY, std::string(call) + ": out of memory");
    } catch (const InputError& e) {
        return fail(ELLICAST_ERROR_INPUT, e.what());
    } catch (const std::exception& e) {
        return fail(ELLICAST_ERROR_INTERNAL, std::string(call) + ": " + e.what());
    } catch (...) {
        return fail(ELLICAST_ERROR_INTERNAL, std::string(call) + ": unknown exception");
    }
}

ellicast_status null_argument(const char* call, const char* name) {
    return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": " + name + " is NULL");
}

// Copies `bytes` into a buffer the caller frees with ellicast_buffer_free (malloc'd, so that a C
// caller could also free() it).
ellicast_status fill_buffer(const std::vector<uint8_t>& bytes, ellicast_buffer* out, const char* call) {
    out->data = nullptr;
    out->size = 0;
    if (bytes.empty()) return ok();
    auto* data = static_cast<uint8_t*>(std::malloc(bytes.size()));
    if (!data) return fail(ELLICAST_ERROR_MEMORY, std::string(call) + ": out of memory for " + std::to_string(bytes.size()) + " bytes");
    std::memcpy(data, bytes.data(), bytes.size());
    out->data = data;
    out->size = bytes.size();
    return ok();
}

// The per-object state the progress call reports (spec 19.1: an object with an exact layer is
// whole once every point and its connectivity arrived).
bool object_exact(const ReceivedObject& o) {
    return o.info && o.info->exact_layer && o.points.size() >= o.info->point_count && o.connectivity &&
           o.connectivity->complete;
}

}  // namespace

struct ellicast_receiver {
    broadcast::Reception reception;
    DecodeOptions decode;
    explicit ellicast_receiver(broadcast::Reception::Options options) : reception(std::move(options)) {}
};

struct ellicast_snapshot {
    Asset asset;
    std::vector<Mesh> meshes;  // flatten_asset(asset), in world space
};

static_assert(sizeof(std::array<float, 3>) == 3 * sizeof(float), "mesh arrays are handed out as float*");
static_assert(sizeof(std::array<float, 2>) == 2 * sizeof(float), "mesh arrays are handed out as float*");
static_assert(sizeof(std::array<uint32_t, 3>) == 3 * sizeof(uint32_t), "mesh arrays are handed out as uint32_t*");

extern "C" {

const char* ellicast_version(void) { return "1.0.0"; }

void ellicast_format_version(int* major, int* minor) {
    if (major) *major = kFormatMajor;
    if (minor) *minor = kSpecMinor;
}

const char* ellicast_status_name(ellicast_status status) {
    switch (status) {
        case ELLICAST_OK: return "ELLICAST_OK";
        case ELLICAST_ERROR_ARGUMENT: return "ELLICAST_ERROR_ARGUMENT";
        case ELLICAST_ERROR_IO: return "ELLICAST_ERROR_IO";
        case ELLICAST_ERROR_INPUT: return "ELLICAST_ERROR_INPUT";
        case ELLICAST_ERROR_REJECTED: return "ELLICAST_ERROR_REJECTED";
        case ELLICAST_ERROR_NOT_READY: return "ELLICAST_ERROR_NOT_READY";
        case ELLICAST_ERROR_MEMORY: return "ELLICAST_ERROR_MEMORY";
        case ELLICAST_ERROR_INTERNAL: return "ELLICAST_ERROR_INTERNAL";
    }
    return "ELLICAST_ERROR_UNKNOWN";
}

const char* ellicast_last_error(void) { return t_last_error.c_str(); }

void ellicast_buffer_free(ellicast_buffer* buffer) {
    if (!buffer) return;
    std::free(buffer->data);
    buffer->data = nullptr;
    buffer->size = 0;
}

// ---------------------------------------------------------------------------------------------
// Receiving

void ellicast_receiver_options_init(ellicast_receiver_options* options) {
    if (!options) return;
    std::memset(options, 0, sizeof *options);
    options->struct_size = sizeof *options;
    options->exact = 1;
}

ellicast_status ellicast_receiver_create(const ellicast_receiver_options* options, ellicast_receiver** out) {
    static const char* call = "ellicast_receiver_create";
    if (!out) return null_argument(call, "out");
    *out = nullptr;
    ellicast_receiver_options o;
    ellicast_receiver_options_init(&o);
    if (options) {
        if (options->struct_size < sizeof o)
            return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": options.struct_size is " +
                                                     std::to_string(options->struct_size) + ", expected " +
                                                     std::to_string(sizeof o) + " (call ellicast_receiver_options_init)");
        o = *options;
    }
    if (o.grid_resolution != 0 && (o.grid_resolution < kMinGridResolution || o.grid_resolution > kMaxGridResolution))
        return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": grid_resolution " + std::to_string(o.grid_resolution) +
                                                 " is outside 0 (automatic) or " + std::to_string(kMinGridResolution) + ".." +
                                                 std::to_string(kMaxGridResolution));
    return guarded(call, [&]() -> ellicast_status {
        broadcast::Reception::Options reception;
        if (o.has_stream_id) reception.stream_id = o.stream_id;
        if (o.max_pending_bytes) reception.limits.max_pending_bytes = size_t(o.max_pending_bytes);
        if (o.public_key_path) {
            auth::PublicKey key;
            std::string error;
            if (!auth::read_public_key(o.public_key_path, key, error))
                return fail(ELLICAST_ERROR_INPUT, std::string(call) + ": public_key_path: " + error);
            reception.key = key;
        }
        auto* r = new ellicast_receiver(std::move(reception));
        r->decode.grid_resolution = o.grid_resolution;
        r->decode.exact = o.exact != 0;
        *out = r;
        return ok();
    });
}

void ellicast_receiver_destroy(ellicast_receiver* receiver) { delete receiver; }

ellicast_status ellicast_receiver_take_datagram(ellicast_receiver* receiver, const void* data, size_t size) {
    static const char* call = "ellicast_receiver_take_datagram";
    if (!receiver) return null_argument(call, "receiver");
    if (!data && size) return null_argument(call, "data");
    return guarded(call, [&]() -> ellicast_status {
        const Error e = receiver->reception.take({static_cast<const uint8_t*>(data), size});
        if (e != Error::Ok)
            return fail(ELLICAST_ERROR_REJECTED, std::string("datagram of ") + std::to_string(size) + " bytes dropped: " + error_name(e));
        return ok();
    });
}

ellicast_status ellicast_receiver_take_recording(ellicast_receiver* receiver, const void* data, size_t size) {
    static const char* call = "ellicast_receiver_take_recording";
    if (!receiver) return null_argument(call, "receiver");
    if (!data && size) return null_argument(call, "data");
    return guarded(call, [&]() -> ellicast_status {
        const ContainerContents contents = read_container({static_cast<const uint8_t*>(data), size});
        if (contents.header_error != Error::Ok)
            return fail(ELLICAST_ERROR_INPUT, std::string("not an ellicast recording (") + error_name(contents.header_error) +
                                                  " in its 12-byte header)");
        const auto* bytes = static_cast<const uint8_t*>(data);
        for (const ContainerPacket& p : contents.packets) receiver->reception.take({bytes + p.offset, p.view.size});
        return ok();
    });
}

ellicast_status ellicast_receiver_take_file(ellicast_receiver* receiver, const char* path) {
    static const char* call = "ellicast_receiver_take_file";
    if (!receiver) return null_argument(call, "receiver");
    if (!path) return null_argument(call, "path");
    return guarded(call, [&]() -> ellicast_status {
        std::vector<uint8_t> bytes;
        std::string message;
        if (read_file(path, bytes, message) != Error::Ok) return fail(ELLICAST_ERROR_IO, message);
        const ellicast_status s = ellicast_receiver_take_recording(receiver, bytes.data(), bytes.size());
        if (s != ELLICAST_OK) t_last_error = std::string(path) + ": " + t_last_error;
        return s;
    });
}

ellicast_status ellicast_receiver_progress(const ellicast_receiver* receiver, ellicast_progress* out) {
    static const char* call = "ellicast_receiver_progress";
    if (!receiver) return null_argument(call, "receiver");
    if (!out) return null_argument(call, "out");
    return guarded(call, [&]() -> ellicast_status {
        const broadcast::Reception& r = receiver->reception;
        const broadcast::ReceptionCounters c = r.counters();
        ellicast_progress p{};
        p.datagrams = c.datagrams;
        p.accepted = c.accepted;
        p.duplicates = c.duplicates;
        p.rejected = c.rejected();
        p.loss = r.loss().loss();
        const ReceivedStream& stream = r.stream();
        p.objects = stream.info() ? uint32_t(stream.objects().size()) : 0;
        p.points_received = r.points_received();
        p.points_declared = r.points_declared();
        p.ellipsoids_received = r.ellipsoids_received();
        p.ellipsoids_declared = r.ellipsoids_declared();
        for (const ReceivedObject& o : stream.objects()) p.exact_objects += object_exact(o);
        p.base_complete = r.base_complete();
        p.complete = r.complete();
        *out = p;
        return ok();
    });
}

ellicast_status ellicast_receiver_object_progress(const ellicast_receiver* receiver, uint32_t index,
                                                  ellicast_object_progress* out) {
    static const char* call = "ellicast_receiver_object_progress";
    if (!receiver) return null_argument(call, "receiver");
    if (!out) return null_argument(call, "out");
    return guarded(call, [&]() -> ellicast_status {
        const ReceivedStream& stream = receiver->reception.stream();
        const size_t count = stream.info() ? stream.objects().size() : 0;
        if (index >= count)
            return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": object " + std::to_string(index) + " does not exist (the stream declares " +
                                                     std::to_string(count) + ")");
        const ReceivedObject& o = stream.objects()[index];
        ellicast_object_progress p{};
        p.arrived = o.info.has_value();
        if (o.info) {
            p.point_set = o.info->kind == ObjectKind::PointSet;
            p.points_declared = o.info->point_count;
            p.ellipsoids_declared = o.info->ellipsoid_count;
            p.has_exact_layer = o.info->exact_layer;
        }
        p.points_received = o.points.size();
        p.ellipsoids_received = o.ellipsoids.size();
        p.exact = object_exact(o);
        *out = p;
        return ok();
    });
}

// ---------------------------------------------------------------------------------------------
// Snapshots

ellicast_status ellicast_receiver_snapshot(ellicast_receiver* receiver, ellicast_snapshot** out) {
    static const char* call = "ellicast_receiver_snapshot";
    if (!receiver) return null_argument(call, "receiver");
    if (!out) return null_argument(call, "out");
    *out = nullptr;
    return guarded(call, [&]() -> ellicast_status {
        const ReceivedStream& stream = receiver->reception.stream();
        if (!stream.info()) {
            const std::string why = stream.stream_info_problem();
            return fail(ELLICAST_ERROR_NOT_READY, "nothing can be built yet: no STREAM_INFO has arrived" + (why.empty() ? "" : " (" + why + ")"));
        }
        auto snapshot = std::make_unique<ellicast_snapshot>();
        StreamDecodeReport report;
        std::string error;
        if (!decode_asset(stream, receiver->decode, snapshot->asset, report, error))
            return fail(ELLICAST_ERROR_NOT_READY, "nothing can be built yet: " + error);
        if (std::none_of(snapshot->asset.objects.begin(), snapshot->asset.objects.end(),
                         [](const Mesh& m) { return !m.positions.empty(); }))
            return fail(ELLICAST_ERROR_NOT_READY, "nothing can be built yet: no object has received an ellipsoid or a point");
        snapshot->meshes = flatten_asset(snapshot->asset);
        *out = snapshot.release();
        return ok();
    });
}

void ellicast_snapshot_destroy(ellicast_snapshot* snapshot) { delete snapshot; }

ellicast_status ellicast_snapshot_glb(const ellicast_snapshot* snapshot, ellicast_buffer* out) {
    static const char* call = "ellicast_snapshot_glb";
    if (!snapshot) return null_argument(call, "snapshot");
    if (!out) return null_argument(call, "out");
    out->data = nullptr;
    out->size = 0;
    return guarded(call, [&]() -> ellicast_status {
        std::vector<uint8_t> bytes;
        std::vector<std::string> warnings;
        std::string error;
        if (!write_asset_glb(snapshot->asset, AssetWriteOptions{}, bytes, warnings, error))
            return fail(ELLICAST_ERROR_INTERNAL, std::string(call) + ": " + error);
        return fill_buffer(bytes, out, call);
    });
}

size_t ellicast_snapshot_mesh_count(const ellicast_snapshot* snapshot) { return snapshot ? snapshot->meshes.size() : 0; }

ellicast_status ellicast_snapshot_mesh(const ellicast_snapshot* snapshot, size_t index, ellicast_mesh* out) {
    static const char* call = "ellicast_snapshot_mesh";
    if (!snapshot) return null_argument(call, "snapshot");
    if (!out) return null_argument(call, "out");
    if (index >= snapshot->meshes.size())
        return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": mesh " + std::to_string(index) + " does not exist (the snapshot has " +
                                                 std::to_string(snapshot->meshes.size()) + ")");
    const Mesh& m = snapshot->meshes[index];
    ellicast_mesh v{};
    v.name = m.name.c_str();
    v.vertex_count = m.positions.size();
    v.positions = m.positions.empty() ? nullptr : m.positions.front().data();
    v.normals = m.normals.size() == m.positions.size() && !m.normals.empty() ? m.normals.front().data() : nullptr;
    v.texcoords = m.texcoords.size() == m.positions.size() && !m.texcoords.empty() ? m.texcoords.front().data() : nullptr;
    if (m.colors.size() == m.positions.size() && !m.colors.empty()) {
        v.colors = m.colors.front().data();
        v.color_has_alpha = m.colors_have_alpha;
    }
    v.triangle_count = m.triangles.size();
    v.indices = m.triangles.empty() ? nullptr : m.triangles.front().data();
    *out = v;
    return ok();
}

ellicast_status ellicast_receiver_snapshot_glb(ellicast_receiver* receiver, ellicast_buffer* out) {
    if (!out) return null_argument("ellicast_receiver_snapshot_glb", "out");
    out->data = nullptr;
    out->size = 0;
    ellicast_snapshot* snapshot = nullptr;
    if (ellicast_status s = ellicast_receiver_snapshot(receiver, &snapshot); s != ELLICAST_OK) return s;
    const ellicast_status s = ellicast_snapshot_glb(snapshot, out);
    ellicast_snapshot_destroy(snapshot);
    return s;
}

// ---------------------------------------------------------------------------------------------
// Sending

void ellicast_encode_options_init(ellicast_encode_options* options) {
    if (!options) return;
    std::memset(options, 0, sizeof *options);
    const EncodeOptions d;
    options->struct_size = sizeof *options;
    options->stream_id = 1;
    options->packet_size = d.packet_size;
    options->position_bits = d.position_bits;
    options->max_ellipsoids = d.max_ellipsoids;
    options->repair_ratio = d.repair_ratio;
    options->sample_spacing = d.sample_spacing;
    options->point_map = d.point_map;
    options->normal_tolerance = d.normal_tolerance;
    options->threads = d.threads;
    options->sample_budget = d.sample_budget;
    options->base_ratio = d.base_ratio;
}

}  // extern "C"

namespace {

// The caller's options (NULL: the defaults) into `out`; a struct older than this library's is refused.
ellicast_status resolve_encode_options(const ellicast_encode_options* options, ellicast_encode_options& out,
                                       const char* call) {
    ellicast_encode_options_init(&out);
    if (!options) return ELLICAST_OK;
    // The struct of version 1.0 ended with progress_user; a caller built against it keeps the
    // defaults of the fields added since.
    constexpr size_t kFirstSize = offsetof(ellicast_encode_options, sample_budget);
    if (options->struct_size < kFirstSize || options->struct_size > 1 << 16)
        return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": options.struct_size is " + std::to_string(options->struct_size) +
                                                 ", expected " + std::to_string(sizeof out) + " (call ellicast_encode_options_init)");
    std::memcpy(&out, options, std::min(sizeof out, options->struct_size));
    out.struct_size = sizeof out;
    return ELLICAST_OK;
}

ellicast_status encode_path(const std::string& path, const std::string& shown_as, const ellicast_encode_options& o,
                            ellicast_buffer* stream_out, const char* call) {
    EncodeOptions e;
    e.packet_size = uint16_t(o.packet_size > 65535 ? 0 : o.packet_size);
    e.position_bits = uint8_t(o.position_bits < 0 || o.position_bits > 255 ? 0 : o.position_bits);
    e.max_ellipsoids = o.max_ellipsoids;
    e.repair_ratio = o.repair_ratio;
    e.sample_spacing = o.sample_spacing;
    e.sample_budget = o.sample_budget;
    e.base_ratio = o.base_ratio;
    e.point_map = o.point_map != 0;
    e.normal_tolerance = o.normal_tolerance;
    e.threads = o.threads;
    if (std::string why = check_encode_options(e); !why.empty()) return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": " + why);
    if (o.progress) {
        auto progress = o.progress;
        void* user = o.progress_user;
        e.progress = [progress, user](const std::string& stage, double fraction) { progress(stage.c_str(), fraction, user); };
    }
    Asset asset;
    try {
        asset = load_asset(path, InputOptions{o.allow_external_paths != 0});
    } catch (const InputError& error) {
        std::string message = error.what();
        if (shown_as != path) {  // name the caller's buffer, not our temporary file
            for (size_t at = message.find(path); at != std::string::npos; at = message.find(path, at + shown_as.size()))
                message.replace(at, path.size(), shown_as);
        }
        return fail(ELLICAST_ERROR_INPUT, message);
    }
    EncodedAsset encoded;
    std::string error;
    if (!encode_asset(asset, e, o.stream_id, is_gltf_file(path), encoded, error))
        return fail(ELLICAST_ERROR_INPUT, shown_as + ": " + error);
    return fill_buffer(write_container(encoded.packets), stream_out, call);
}

// A private temporary folder holding one file, removed when it goes out of scope.
class TemporaryFile {
public:
    explicit TemporaryFile(const std::string& extension) {
        std::string pattern = (std::filesystem::temp_directory_path() / "ellicast-XXXXXX").string();
        if (::mkdtemp(pattern.data())) {
            folder_ = pattern;
            path_ = folder_ + "/model." + extension;
        }
    }
    ~TemporaryFile() {
        if (folder_.empty()) return;
        std::error_code ec;
        std::filesystem::remove_all(folder_, ec);
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string folder_, path_;
};

}  // namespace

extern "C" {

ellicast_status ellicast_encode_file(const char* model_path, const ellicast_encode_options* options, ellicast_buffer* stream_out) {
    static const char* call = "ellicast_encode_file";
    if (!model_path) return null_argument(call, "model_path");
    if (!stream_out) return null_argument(call, "stream_out");
    stream_out->data = nullptr;
    stream_out->size = 0;
    ellicast_encode_options o;
    if (ellicast_status bad = resolve_encode_options(options, o, call); bad != ELLICAST_OK) return bad;
    return guarded(call, [&]() { return encode_path(model_path, model_path, o, stream_out, call); });
}

ellicast_status ellicast_encode_memory(const void* data, size_t size, const char* type, const ellicast_encode_options* options,
                                       ellicast_buffer* stream_out) {
    static const char* call = "ellicast_encode_memory";
    if (!data && size) return null_argument(call, "data");
    if (!type) return null_argument(call, "type");
    if (!stream_out) return null_argument(call, "stream_out");
    stream_out->data = nullptr;
    stream_out->size = 0;
    std::string extension = type;
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    static const char* known[] = {"glb", "gltf", "obj", "ply", "off", "stl"};
    if (std::none_of(std::begin(known), std::end(known), [&](const char* k) { return extension == k; }))
        return fail(ELLICAST_ERROR_ARGUMENT, std::string(call) + ": type " + quoted_input(type, 20) +
                                                 " is not one of glb, gltf, obj, ply, off, stl");
    ellicast_encode_options o;
    if (ellicast_status bad = resolve_encode_options(options, o, call); bad != ELLICAST_OK) return bad;
    o.allow_external_paths = 0;  // a buffer has no folder: a glTF must embed its buffers and images
    return guarded(call, [&]() -> ellicast_status {
        TemporaryFile file(extension);
        if (file.path().empty()) return fail(ELLICAST_ERROR_IO, std::string(call) + ": cannot create a temporary folder");
        std::string message;
        if (write_file(file.path(), {static_cast<const uint8_t*>(data), size}, message) != Error::Ok)
            return fail(ELLICAST_ERROR_IO, std::string(call) + ": " + message);
        return encode_path(file.path(), "(" + extension + " in memory)", o, stream_out, call);
    });
}

ellicast_status ellicast_recording_next_packet(const void* data, size_t size, size_t* offset, const uint8_t** packet,
                                               size_t* packet_size) {
    static const char* call = "ellicast_recording_next_packet";
    if (!data && size) return null_argument(call, "data");
    if (!offset) return null_argument(call, "offset");
    if (!packet) return null_argument(call, "packet");
    if (!packet_size) return null_argument(call, "packet_size");
    *packet = nullptr;
    *packet_size = 0;
    const std::span<const uint8_t> bytes(static_cast<const uint8_t*>(data), size);
    const ContainerContents header = read_container(bytes.first(std::min(size, kContainerHeaderSize)));
    if (header.header_error != Error::Ok)
        return fail(ELLICAST_ERROR_INPUT, std::string("not an ellicast recording (") + error_name(header.header_error) + " in its 12-byte header)");
    size_t pos = std::max(*offset, kContainerHeaderSize);
    while (pos < size) {
        PacketView view;
        if (parse_packet_prefix(bytes.subspan(pos), view) == Error::Ok) {
            *packet = bytes.data() + pos;
            *packet_size = view.size;
            *offset = pos + view.size;
            return ok();
        }
        // Damage: the next intact packet starts at a later byte equal to the packet magic's first.
        const void* hit = pos + 1 < size ? std::memchr(bytes.data() + pos + 1, kPacketMagic[0], size - pos - 1) : nullptr;
        pos = hit ? size_t(static_cast<const uint8_t*>(hit) - bytes.data()) : size;
    }
    *offset = size;
    return ok();
}

}  // extern "C"

// `ellicast inspect FILE.ellc [--json] [--packets]`: a readable summary of a recorded stream: container
// header, stream id, versions, stream info, counts per packet type, per object what arrived of what was
// declared, damaged regions and rejected packets with their offsets.
#include "commands.h"
#include "stream_report.h"

#include "ellicast/format.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <utility>

namespace ellicast::cli {
namespace {

struct InspectArgs {
    std::string input;
    bool json = false;
    bool packets = false;
};

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

const char* kind_name(ObjectKind k) { return k == ObjectKind::Surface ? "surface" : "point set"; }

nlohmann::json to_json(const StreamReport& r, bool with_packets) {
    using nlohmann::json;
    json j;
    j["file"] = r.path;
    j["file_size"] = r.file_size;
    j["container"] = {{"error", r.container_error == Error::Ok ? json(nullptr) : json(error_name(r.container_error))},
                      {"version", r.container_version}};
    j["stream_id"] = r.stream.has_stream_id() ? json(r.stream.stream_id()) : json(nullptr);
    j["versions"] = r.versions;
    json ids = json::object();
    for (const auto& [id, n] : r.stream_ids) ids[hex32(id)] = n;
    j["stream_ids"] = ids;
    if (const auto& info = r.stream.info()) {
        j["stream_info"] = {{"parts", r.stream_info_parts},
                            {"content_id", info->content_id},
                            {"packet_size", info->packet_size},
                            {"position_bits", info->position_bits},
                            {"normal_bits", info->normal_bits},
                            {"texcoord_bits", info->texcoord_bits},
                            {"color_bits", info->color_bits},
                            {"ellipsoid_encoding", info->ellipsoid_encoding},
                            {"grid_hint", info->grid_hint},
                            {"coverage_target", info->coverage_target},
                            {"seed", info->seed},
                            {"object_count", r.stream.objects().size()}};
    } else {
        j["stream_info"] = nullptr;
    }
    json types = json::array();
    for (const auto& [type, c] : r.per_type)
        types.push_back({{"type", packet_type_name(type)}, {"code", type}, {"packets", c.packets}, {"bytes", c.bytes}});
    j["packet_types"] = types;
    const auto& c = r.stream.counters();
    // A repair packet whose block was already whole is counted apart from duplicates.
    j["counters"] = {{"packets", r.packets.size()}, {"accepted", c.accepted},
                     {"duplicates", c.duplicates - r.repair_not_needed}, {"repair_not_needed", r.repair_not_needed},
                     {"skipped", c.skipped},        {"rejected", c.rejected}, {"held", c.pending}};
    // The receiver's byte budget (spec 11.2): what its objects hold against it.
    j["memory"] = {{"held", r.stream.held_memory()}, {"budget", r.stream.memory_budget()}, {"bytes_taken", r.stream.bytes_taken()}};
    json objects = json::array();
    for (size_t i = 0; i < r.stream.objects().size(); ++i) {
        const ReceivedObject& o = r.stream.objects()[i];
        json oj = {{"id", i}, {"ellipsoids_received", o.ellipsoids.size()}, {"points_received", o.points.size()}};
        if (o.info) {
            oj["kind"] = kind_name(o.info->kind);
            oj["attributes"] = attribute_names(o.info->attributes);
            oj["frame"] = {{"origin", o.info->frame.origin}, {"scale", o.info->frame.scale}};
            oj["ellipsoid_count"] = o.info->ellipsoid_count;
            oj["point_count"] = o.info->point_count;
            oj["complete"] = o.ellipsoids.size() == o.info->ellipsoid_count && o.points.size() == o.info->point_count;
            oj["missing_ellipsoids"] = missing_ranges(o.ellipsoids, o.info->ellipsoid_count);
            oj["missing_points"] = missing_ranges(o.points, o.info->point_count);
            if (o.info->mapped())  // format 1.7 (spec 23)
                oj["point_map"] = {{"level", o.info->map_level},     {"batch", o.info->map_batch},
                                   {"fragments", o.map_fragments.size()}, {"ranks", o.map_ranks},
                                   {"complete", o.map_complete()},    {"unplaced_points", o.unplaced.size()}};
            if (o.info->exact_layer) {  // format 1.3 (spec 19), carried vertices format 1.11 (spec 27)
                json layer = {{"packets", nullptr}, {"complete", false}};
                if (const auto& c = o.connectivity) {
                    layer = {{"packets", c->mesh ? "EXACT_MESH" : "CONNECTIVITY"},
                             {"triangle_count", c->triangle_count},
                             {"carried_vertices", c->carried_count},
                             {"bytes_received", c->received_bytes},
                             {"coded_size", c->coded_size},
                             {"complete", c->complete},
                             {"recovered", c->recovered}};
                }
                oj["exact_layer"] = layer;
            }
            if (o.info->surface_normals)  // format 1.8 (spec 24)
                oj["normal_entries"] = {{"received", o.normal_entries.size()}, {"complete", o.normals_complete()}};
            if (!o.texcoord_sets.empty()) {  // format 1.14 (spec 30)
                nlohmann::json sets = nlohmann::json::array();
                for (size_t s = 0; s < o.texcoord_sets.size(); ++s)
                    sets.push_back({{"set", s + 1},
                                    {"received", o.texcoord_sets[s].records.size()},
                                    {"complete", o.texcoord_sets[s].records.size() == o.info->point_count}});
                oj["texcoord_sets"] = sets;
            }
        } else {
            oj["info"] = nullptr;
        }
        objects.push_back(oj);
    }
    j["objects"] = objects;
    if (r.stream.has_scene() || !r.stream.materials().empty() || !r.stream.textures().empty()) {
        size_t complete = 0;
        for (const auto& [i, t] : r.stream.textures()) complete += t.complete;
        j["scene"] = {{"nodes", r.stream.scene_nodes().size()},   {"node_count", r.stream.scene_node_count()},
                      {"meshes", r.stream.scene_meshes().size()}, {"mesh_count", r.stream.scene_mesh_count()},
                      {"materials", r.stream.materials().size()}, {"textures", r.stream.textures().size()},
                      {"textures_complete", complete}};
        if (const auto count = r.stream.animation_count()) {
            size_t whole = 0;
            for (const auto& [i, a] : r.stream.animations()) whole += a.complete();
            j["scene"]["animations"] = r.stream.animations().size();
            j["scene"]["animation_count"] = *count;
            j["scene"]["animations_complete"] = whole;
        }
        if (const auto count = r.stream.skin_count()) {
            size_t whole = 0;
            for (const auto& [i, s] : r.stream.skins()) whole += s.complete();
            j["scene"]["skins"] = r.stream.skins().size();
            j["scene"]["skin_count"] = *count;
            j["scene"]["skins_complete"] = whole;
        }
        if (const auto count = r.stream.morph_animation_count()) {
            size_t whole = 0;
            for (const auto& [i, a] : r.stream.morph_animations()) whole += a.complete();
            j["scene"]["morph_animations"] = r.stream.morph_animations().size();
            j["scene"]["morph_animation_count"] = *count;
            j["scene"]["morph_animations_complete"] = whole;
        }
        size_t morph_meshes = 0;
        for (const auto& [i, m] : r.stream.scene_meshes()) morph_meshes += !m.weights.empty();
        if (morph_meshes) j["scene"]["meshes_with_targets"] = morph_meshes;
        if (const auto count = r.stream.camera_count()) {  // format 1.10
            j["scene"]["cameras"] = r.stream.cameras().size();
            j["scene"]["camera_count"] = *count;
        }
        if (const auto count = r.stream.light_count()) {
            j["scene"]["lights"] = r.stream.lights().size();
            j["scene"]["light_count"] = *count;
        }
        if (const auto count = r.stream.extras_count()) {  // format 1.12
            size_t whole = 0;
            for (const auto& [key, e] : r.stream.extras()) whole += e.complete;
            j["scene"]["extras"] = whole;
            j["scene"]["extras_count"] = *count;
        }
        if (const auto count = r.stream.required_extension_count()) {  // format 1.13
            json names = json::array();
            for (const auto& [index, name] : r.stream.required_extensions()) names.push_back(name);
            j["scene"]["required_extensions"] = names;
            j["scene"]["required_extension_count"] = *count;
        }
    }
    json damaged = json::array();
    for (const auto& d : r.damaged)
        damaged.push_back({{"offset", d.offset}, {"length", d.length}, {"reason", error_name(d.first_error)}});
    j["damaged"] = damaged;
    json rejected = json::array();
    for (const auto& x : r.stream.rejections())
        rejected.push_back({{"offset", x.where}, {"reason", error_name(x.error)}, {"detail", x.detail}});
    j["rejected"] = rejected;
    j["conforms"] = r.conforms();
    if (with_packets) {
        json packets = json::array();
        for (const auto& p : r.packets)
            packets.push_back({{"offset", p.offset},
                               {"size", p.size},
                               {"type", packet_type_name(p.header.type)},
                               {"version", std::to_string(p.header.version_major) + "." + std::to_string(p.header.version_minor)},
                               {"flags", p.header.flags},
                               {"stream_id", p.header.stream_id},
                               {"sequence", p.header.sequence},
                               {"object_id", p.header.object_id},
                               {"result", p.result}});
        j["packets"] = packets;
    }
    return j;
}

void print_text(const StreamReport& r, bool with_packets) {
    std::ostringstream out;
    out << r.path << ": " << r.file_size << " bytes\n";
    if (r.container_error != Error::Ok) {
        out << "container: unreadable: " << error_name(r.container_error) << "\n";
        std::cout << out.str();
        return;
    }
    out << "container: version " << int(r.container_version) << ", " << kContainerHeaderSize << "-byte header, "
        << r.packets.size() << " intact packet" << (r.packets.size() == 1 ? "" : "s") << ", " << r.damaged.size()
        << " damaged region" << (r.damaged.size() == 1 ? "" : "s") << "\n";
    out << "stream id: " << (r.stream.has_stream_id() ? hex32(r.stream.stream_id()) : std::string("none"));
    if (r.stream_ids.size() > 1) out << " (" << r.stream_ids.size() << " stream ids in the file)";
    out << "\nversions:";
    for (const auto& [v, n] : r.versions) out << " " << v << " (" << n << ")";
    out << "\n";
    if (const auto& info = r.stream.info()) {
        out << "stream info: " << r.stream_info_parts << " STREAM_INFO packet" << (r.stream_info_parts == 1 ? "" : "s")
            << ", content id " << hex32(info->content_id) << ", packet size " << info->packet_size << "\n"
            << "  bits: position " << int(info->position_bits) << ", normal " << int(info->normal_bits) << ", texcoord "
            << int(info->texcoord_bits) << ", colour " << int(info->color_bits) << "; ellipsoid encoding "
            << int(info->ellipsoid_encoding) << "\n"
            << "  encoder: coverage target " << fmt("%.3g", info->coverage_target) << ", seed " << info->seed
            << ", grid hint " << info->grid_hint << "\n";
    } else {
        out << "stream info: none received\n";
    }
    out << "packet types:\n";
    for (const auto& [type, c] : r.per_type) {
        char line[128];
        std::snprintf(line, sizeof line, "  %-18s %8llu packets %12llu bytes\n", packet_type_name(type).c_str(),
                      static_cast<unsigned long long>(c.packets), static_cast<unsigned long long>(c.bytes));
        out << line;
    }
    const auto& c = r.stream.counters();
    out << "packets: " << c.accepted << " accepted, " << c.duplicates - r.repair_not_needed << " duplicates, "
        << r.repair_not_needed << " repair not needed (what they protect arrived whole), " << c.skipped << " skipped, "
        << c.rejected << " rejected, " << c.pending << " held without stream info\n";
    out << "receiver memory: objects hold " << r.stream.held_memory() << " bytes, budget " << r.stream.memory_budget()
        << " (64 MiB plus 8 times the " << r.stream.bytes_taken() << " bytes of intact packets, spec 11.2)\n";
    const auto& objects = r.stream.objects();
    out << "objects: " << objects.size() << "\n";
    for (size_t i = 0; i < objects.size(); ++i) {
        const ReceivedObject& o = objects[i];
        out << "  " << i << ": ";
        if (!o.info) {
            out << "no STREAM_INFO entry; " << o.ellipsoids.size() << " ellipsoids, " << o.points.size() << " points\n";
            continue;
        }
        const ObjectInfo& oi = *o.info;
        const bool complete = o.ellipsoids.size() == oi.ellipsoid_count && o.points.size() == oi.point_count;
        out << kind_name(oi.kind) << ", attributes " << attribute_names(oi.attributes) << ", frame ("
            << fmt("%g", oi.frame.origin[0]) << ", " << fmt("%g", oi.frame.origin[1]) << ", " << fmt("%g", oi.frame.origin[2])
            << ") scale " << fmt("%g", oi.frame.scale) << "; ellipsoids " << o.ellipsoids.size() << "/" << oi.ellipsoid_count
            << ", points " << o.points.size() << "/" << oi.point_count << (complete ? ", complete" : "") << "\n";
        if (oi.mapped())
            out << "     point map (format 1.7): level " << int(oi.map_level) << ", batch " << oi.map_batch << ", "
                << o.map_fragments.size() << " fragments holding " << o.map_ranks << "/" << oi.point_count << " ranks"
                << (o.unplaced.empty() ? "" : "; " + std::to_string(o.unplaced.size()) + " points held but not placed")
                << "\n";
        if (oi.exact_layer) {
            out << "     exact layer: ";
            if (const auto& c = o.connectivity)
                out << (c->mesh ? "EXACT_MESH (format 1.11), " : "CONNECTIVITY (format 1.3), ") << c->triangle_count
                    << " triangles, " << c->carried_count << " vertices carried beside the points; "
                    << c->received_bytes << "/" << c->coded_size << " bytes"
                    << (c->complete ? (c->recovered ? ", complete (through repair)" : ", complete") : "") << "\n";
            else
                out << "announced, nothing received\n";
        }
        if (oi.surface_normals)
            out << "     surface normals (format 1.8): entries " << o.normal_entries.size() << "/" << oi.point_count
                << (o.normals_complete() ? ", complete" : "") << "\n";
        for (size_t s = 0; s < o.texcoord_sets.size(); ++s)  // format 1.14 (spec 30)
            out << "     TEXCOORD_" << s + 1 << " (format 1.14): records " << o.texcoord_sets[s].records.size() << "/"
                << oi.point_count << (o.texcoord_sets[s].records.size() == oi.point_count ? ", complete" : "") << "\n";
        if (!complete) {
            std::string me = missing_ranges(o.ellipsoids, oi.ellipsoid_count), mp = missing_ranges(o.points, oi.point_count);
            if (!me.empty()) out << "     missing ellipsoids " << me << "\n";
            if (!mp.empty()) out << "     missing points " << mp << "\n";
        }
    }
    if (r.stream.has_scene() || !r.stream.materials().empty() || !r.stream.textures().empty()) {
        size_t complete = 0;
        for (const auto& [i, t] : r.stream.textures()) complete += t.complete;
        out << "scene (format 1.1): nodes " << r.stream.scene_nodes().size() << "/" << r.stream.scene_node_count()
            << ", meshes " << r.stream.scene_meshes().size() << "/" << r.stream.scene_mesh_count() << ", materials "
            << r.stream.materials().size() << ", textures " << complete << " complete of " << r.stream.textures().size()
            << " started";
        if (const auto count = r.stream.animation_count()) {
            size_t whole = 0;
            for (const auto& [i, a] : r.stream.animations()) whole += a.complete();
            out << ", animations (format 1.4) " << whole << " complete of " << *count;
        }
        if (const auto count = r.stream.skin_count()) {
            size_t whole = 0;
            for (const auto& [i, s] : r.stream.skins()) whole += s.complete();
            out << ", skins (format 1.5) " << whole << " complete of " << *count;
        }
        size_t morph_meshes = 0;
        for (const auto& [i, m] : r.stream.scene_meshes()) morph_meshes += !m.weights.empty();
        if (morph_meshes) out << ", meshes with morph targets (format 1.6) " << morph_meshes;
        if (const auto count = r.stream.morph_animation_count()) {
            size_t whole = 0;
            for (const auto& [i, a] : r.stream.morph_animations()) whole += a.complete();
            out << ", morph animations (format 1.6) " << whole << " complete of " << *count;
        }
        if (const auto count = r.stream.camera_count())
            out << ", cameras (format 1.10) " << r.stream.cameras().size() << "/" << *count;
        if (const auto count = r.stream.light_count())
            out << ", lights (format 1.10) " << r.stream.lights().size() << "/" << *count;
        if (const auto count = r.stream.extras_count()) {
            size_t whole = 0;
            for (const auto& [key, e] : r.stream.extras()) whole += e.complete;
            out << ", extras (format 1.12) " << whole << " complete of " << *count;
        }
        if (const auto count = r.stream.required_extension_count()) {
            out << ", required extensions (format 1.13) " << r.stream.required_extensions().size() << "/" << unsigned(*count);
            const char* sep = ": ";
            for (const auto& [index, name] : r.stream.required_extensions()) out << std::exchange(sep, ", ") << name;
        }
        out << "\n";
    }
    out << "damaged regions: " << r.damaged.size() << "\n";
    for (const auto& d : r.damaged)
        out << "  offset " << d.offset << ", " << d.length << " bytes: " << error_name(d.first_error) << "\n";
    out << "rejected packets: " << r.stream.rejections().size() << "\n";
    for (const auto& x : r.stream.rejections())
        out << "  offset " << x.where << ": " << error_name(x.error) << (x.detail.empty() ? "" : " (" + x.detail + ")") << "\n";
    if (with_packets) {
        out << "packets:\n";
        for (const auto& p : r.packets) {
            char line[200];
            std::snprintf(line, sizeof line, "  %10llu %6zu  %-18s %u.%u obj %5u seq %10u  %s\n",
                          static_cast<unsigned long long>(p.offset), p.size, packet_type_name(p.header.type).c_str(),
                          p.header.version_major, p.header.version_minor, p.header.object_id, p.header.sequence,
                          p.result.c_str());
            out << line;
        }
    }
    out << "conforms: " << (r.conforms() ? "yes" : "no (see `ellicast validate`)") << "\n";
    std::cout << out.str();
}

int run_inspect(const InspectArgs& args) {
    std::vector<uint8_t> bytes;
    std::string message;
    if (read_file(args.input, bytes, message) != Error::Ok) return fail(kExitFailure, message);
    StreamReport report = analyze_stream(args.input, bytes);
    if (args.json) std::cout << to_json(report, args.packets).dump(2) << "\n";
    else print_text(report, args.packets);
    // Inspecting works on damaged files too; only a file that is not a container at all fails.
    return report.container_error == Error::Ok ? kExitOk : kExitInvalid;
}

const RegisterCommand kRegisterInspect{{50, [](CLI::App& app, int& exit_code) {
    auto args = std::make_shared<InspectArgs>();
    auto* cmd = app.add_subcommand("inspect", "Summarize a recorded stream (.ellc): stream info, packets per type, "
                                              "objects, damaged regions");
    cmd->add_option("file", args->input, "recorded stream (.ellc)")->required();
    cmd->add_flag("--json", args->json, "machine-readable output");
    cmd->add_flag("--packets", args->packets, "also list every packet");
    cmd->callback([args, &exit_code] { exit_code = run_inspect(*args); });
}}};

}  // namespace
}  // namespace ellicast::cli

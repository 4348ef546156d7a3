// Reads a recorded stream like a decoder and lists every way it departs from a conforming file
// (spec/format.md section 11.5).
#include "stream_report.h"

#include "ellicast/converters/image_file.h"

#include <cstdio>
#include <map>
#include <set>

namespace ellicast::cli {

std::string hex32(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%08X", v);
    return buf;
}

std::string attribute_names(uint8_t a) {
    std::string out;
    auto add = [&](const char* name) {
        if (!out.empty()) out += ",";
        out += name;
    };
    if (a & kAttrNormal) add("normal");
    if (a & kAttrTexcoord) add("texcoord");
    if (a & kAttrColor) add(a & kAttrColorAlpha ? "rgba" : "rgb");
    if (out.empty()) out = "-";
    return out;
}

bool VersionOrder::operator()(const std::string& a, const std::string& b) const {
    const auto parts = [](const std::string& v) {
        const size_t dot = v.find('.');
        return std::make_pair(std::atoi(v.substr(0, dot).c_str()), dot == std::string::npos ? 0 : std::atoi(v.c_str() + dot + 1));
    };
    return parts(a) < parts(b);
}

StreamReport analyze_stream(const std::string& path, const std::vector<uint8_t>& bytes, const auth::PublicKey* key) {
    StreamReport r;
    r.path = path;
    r.file_size = bytes.size();
    ContainerContents contents = read_container(bytes);
    r.container_error = contents.header_error;
    if (contents.header_error != Error::Ok) {
        r.violations.push_back({0, contents.header_error == Error::TooShort
                                       ? std::string("not a readable ellicast container: shorter than the 12-byte container header")
                                       : std::string("not a readable ellicast container: ") + error_name(contents.header_error)});
        return r;
    }
    r.container_version = bytes[8];
    r.damaged = contents.damaged;

    for (const ContainerPacket& p : contents.packets) {
        const ReceiveCounters before = r.stream.counters();
        const size_t rejections_before = r.stream.rejections().size();
        Error e = r.stream.add_parsed(p.view, p.offset);
        const ReceiveCounters& after = r.stream.counters();
        const PacketHeader& h = p.view.header;
        ReportPacket rp{p.offset, h, p.view.size, ""};
        if (e != Error::Ok) rp.result = error_name(e);
        else if (after.accepted > before.accepted) rp.result = "accepted";
        else if (after.duplicates > before.duplicates && (h.type == uint8_t(PacketType::PointsRepair) ||
                                                          is_exact_layer_repair_type(h.type))) {
            rp.result = "repair, not needed";  // its block was already whole
            ++r.repair_not_needed;
        } else if (after.duplicates > before.duplicates) rp.result = "duplicate";
        else if (after.skipped > before.skipped) rp.result = "skipped";
        else rp.result = "held";
        r.packets.push_back(rp);

        auto& count = r.per_type[h.type];
        ++count.packets;
        count.bytes += p.view.size;
        r.versions[std::to_string(h.version_major) + "." + std::to_string(h.version_minor)]++;
        r.stream_ids[h.stream_id]++;
        if (h.type == uint8_t(PacketType::StreamInfo) && e == Error::Ok) ++r.stream_info_parts;
        if (e != Error::Ok) {
            std::string detail;
            if (r.stream.rejections().size() > rejections_before) detail = r.stream.rejections().back().detail;
            r.violations.push_back({p.offset, packet_type_name(h.type) + " packet rejected: " + error_name(e) +
                                                  (detail.empty() ? "" : " (" + detail + ")")});
        }
        // The format 1.0 types, MAPPED_POINTS and POINT_MAP are critical; every other type this
        // format assigns is sent skippable (spec 3.1, 9.1): a decoder that does not know it may skip it.
        const bool critical = h.type <= uint8_t(PacketType::Points) || h.type == uint8_t(PacketType::MappedPoints) ||
                              h.type == uint8_t(PacketType::PointMap);
        if (critical && h.skippable())
            r.violations.push_back({p.offset, packet_type_name(h.type) + " packet marked skippable (flags bit 0 must be 0 for a format 1.0 type, MAPPED_POINTS and POINT_MAP)"});
        else if (!critical && is_known_packet_type(h.type) && !h.skippable())
            r.violations.push_back({p.offset, packet_type_name(h.type) +
                                                  " packet marked critical (flags bit 0 must be 1 for this type: a "
                                                  "decoder that does not know it would reject it, spec 3.1, 9.1)"});
    }
    // Packets held for their stream info and rejected when it arrived (their result when read was
    // "held"): each is a violation at its own offset too.
    {
        std::set<uint64_t> reported;
        for (const ReportPacket& p : r.packets)
            if (p.result != "accepted" && p.result != "duplicate" && p.result != "repair, not needed" &&
                p.result != "skipped" && p.result != "held")
                reported.insert(p.offset);
        for (const Rejection& rejection : r.stream.rejections())
            if (!reported.count(rejection.where))
                r.violations.push_back({rejection.where, "packet held for its stream info, then rejected: " +
                                                             std::string(error_name(rejection.error)) + " (" +
                                                             rejection.detail + ")"});
    }
    r.signing = auth::check_signed_recording(contents.packets, bytes, key);
    for (const auto& problem : r.signing.problems) r.violations.push_back({problem.offset, problem.message});
    if (key && !r.signing.is_signed)
        r.violations.push_back({std::nullopt, "not signed: no MANIFEST packet, but a key was given"});
    for (const DamagedRegion& d : r.damaged)
        r.violations.push_back({d.offset, std::to_string(d.length) + " damaged byte" + (d.length == 1 ? "" : "s") +
                                              " hold no valid packet (" + error_name(d.first_error) + ")"});

    if (r.stream_ids.size() > 1) {
        std::string ids;
        for (const auto& [id, n] : r.stream_ids) ids += (ids.empty() ? "" : ", ") + hex32(id) + " (" + std::to_string(n) + ")";
        r.violations.push_back({std::nullopt, "packets of " + std::to_string(r.stream_ids.size()) + " stream ids: " + ids});
    }

    const auto& info = r.stream.info();
    if (!info) {
        r.violations.push_back({std::nullopt, contents.packets.empty() ? "no packets at all: no STREAM_INFO"
                                                                       : "no valid STREAM_INFO: nothing can be decoded",
                                true});
    } else {
        for (const ReportPacket& p : r.packets)
            if (p.size > info->packet_size)
                r.violations.push_back({p.offset, packet_type_name(p.header.type) + " packet of " + std::to_string(p.size) +
                                                      " bytes is larger than the declared packet size " +
                                                      std::to_string(info->packet_size)});
    }
    // Packets still held: their object's stream info never arrived.
    for (const ReportPacket& p : r.packets) {
        if (p.result != "held") continue;
        const auto& objects = r.stream.objects();
        if (p.header.object_id < objects.size() && objects[p.header.object_id].info) continue;
        r.violations.push_back({p.offset, packet_type_name(p.header.type) + " packet of object " +
                                              std::to_string(p.header.object_id) +
                                              (info && p.header.object_id >= objects.size()
                                                   ? " names an object beyond the object table"
                                                   : " never got its STREAM_INFO entry"),
                                !(info && p.header.object_id >= objects.size())});
    }
    const auto& objects = r.stream.objects();
    for (size_t i = 0; i < objects.size(); ++i) {
        const ReceivedObject& o = objects[i];
        const std::string name = "object " + std::to_string(i);
        if (!o.info) {
            r.violations.push_back({std::nullopt, name + ": no STREAM_INFO entry arrived", true});
            continue;
        }
        std::string missing = missing_ranges(o.ellipsoids, o.info->ellipsoid_count);
        if (!missing.empty())
            r.violations.push_back({std::nullopt, name + ": " + std::to_string(o.ellipsoids.size()) + " of " +
                                                      std::to_string(o.info->ellipsoid_count) +
                                                      " ellipsoids received; missing " + missing, true});
        missing = missing_ranges(o.points, o.info->point_count);
        if (!missing.empty())
            r.violations.push_back({std::nullopt, name + ": " + std::to_string(o.points.size()) + " of " +
                                                      std::to_string(o.info->point_count) + " points received; missing " +
                                                      missing, true});
        // Format 1.7 (spec 23.6): a mapped object's map holds every rank.
        if (o.info->mapped() && !o.map_complete())
            r.violations.push_back({std::nullopt, name + ": its point map holds " + std::to_string(o.map_ranks) + " of " +
                                                      std::to_string(o.info->point_count) + " ranks (" +
                                                      std::to_string(o.unplaced.size()) +
                                                      " points held but not placed)", true});
        // Format 1.3, the exact layer (spec 19.4): announced, complete, and decodable with every point.
        if (o.connectivity && !o.info->exact_layer)
            r.violations.push_back({std::nullopt, name + (o.connectivity->mesh ? ": EXACT_MESH" : ": CONNECTIVITY") +
                                                      " packets arrived but its entry does not announce an exact layer"});
        if (o.info->exact_layer && !(o.connectivity && o.connectivity->complete)) {
            r.violations.push_back({std::nullopt, name + ": its exact layer did not all arrive (" +
                                                      std::to_string(o.connectivity ? o.connectivity->received_bytes : 0) +
                                                      " of " +
                                                      (o.connectivity ? std::to_string(o.connectivity->coded_size)
                                                                      : std::string("?")) +
                                                      " bytes)", true});
        } else if (o.connectivity && o.connectivity->complete && missing.empty()) {
            std::vector<Triangle> triangles;
            std::vector<QuantizedPoint> carried;
            std::string why;
            if (exact_layer(r.stream, i, triangles, carried, why) != Error::Ok) {
                r.violations.push_back({std::nullopt, name + ": its exact layer is unusable: " + why});
            } else if (o.info->surface_normals) {
                // Format 1.8 (spec 24.4): no point of the exact layer left to an undefined surface normal;
                // format 1.11 (spec 27.3): no carried vertex either.
                std::vector<std::array<uint32_t, 3>> positions(o.info->point_count);
                for (const auto& [index, q] : o.points) positions[index] = q.position;
                for (const QuantizedPoint& q : carried) positions.push_back(q.position);
                const std::vector<char> defined = surface_normal_defined(positions, triangles);
                size_t undefined_carried = 0;
                for (size_t k = o.info->point_count; k < positions.size(); ++k) undefined_carried += !defined[k];
                if (undefined_carried > 0)
                    r.violations.push_back({std::nullopt, name + ": " + std::to_string(undefined_carried) +
                                                              " carried vertices have no surface normal (no triangle "
                                                              "with an area uses them)"});
                std::vector<char> used(positions.size(), 0);
                for (const Triangle& t : triangles)
                    for (uint32_t v : t) used[v] = 1;
                std::vector<uint32_t> bad;
                for (const auto& [index, entry] : o.normal_entries)
                    if (!entry.sent && used[index] && !defined[index]) bad.push_back(index);
                if (!bad.empty())
                    r.violations.push_back({std::nullopt, name + ": " + std::to_string(bad.size()) +
                                                              " point(s) of its exact layer left to the surface have no "
                                                              "surface normal (no triangle with an area uses them), "
                                                              "first point " + std::to_string(bad[0])});
            }
        }
        // Format 1.8 (spec 24.4): an object with surface normals has the normal entry of every point.
        if (o.info->surface_normals && !o.normals_complete()) {
            r.violations.push_back({std::nullopt, name + ": the NORMALS entries of " +
                                                      std::to_string(o.normal_entries.size()) + " of " +
                                                      std::to_string(o.info->point_count) + " points arrived; missing " +
                                                      missing_ranges(o.normal_entries, o.info->point_count), true});
        }
        // Format 1.14 (spec 30.2): an object with TEXCOORDS packets has every set's record of every point.
        for (size_t s = 0; s < o.texcoord_sets.size(); ++s) {
            const auto& records = o.texcoord_sets[s].records;
            if (records.size() == o.info->point_count) continue;
            r.violations.push_back({std::nullopt, name + ": the TEXCOORD_" + std::to_string(s + 1) + " records of " +
                                                      std::to_string(records.size()) + " of " +
                                                      std::to_string(o.info->point_count) + " points arrived; missing " +
                                                      missing_ranges(records, o.info->point_count), true});
        }
    }
    // Format 1.2 repair packets: each symbol must be its row of the code over the points (spec 17.4).
    RepairPacketChecker repair_checker(r.stream);
    for (const ContainerPacket& p : contents.packets) {
        if (p.view.header.type != uint8_t(PacketType::PointsRepair)) continue;
        std::string why;
        const Error e = repair_checker.check(p.view, why);
        if (e == Error::StreamMismatch) r.violations.push_back({p.offset, "POINTS_REPAIR packet: " + why});
    }
    // Format 1.3: each CONNECTIVITY_REPAIR symbol must be its row of the code over the connectivity (spec 19.5).
    ConnectivityRepairChecker connectivity_repair_checker(r.stream);
    for (const ContainerPacket& p : contents.packets) {
        if (!is_exact_layer_repair_type(p.view.header.type)) continue;
        std::string why;
        if (connectivity_repair_checker.check(p.view, why) == Error::StreamMismatch)
            r.violations.push_back({p.offset, packet_type_name(p.view.header.type) + " packet: " + why});
    }
    // Format 1.1 scene tables: complete when present.
    if (r.stream.has_scene()) {
        std::string missing = missing_ranges(r.stream.scene_nodes(), r.stream.scene_node_count());
        if (!missing.empty()) r.violations.push_back({std::nullopt, "scene: nodes missing: " + missing, true});
        missing = missing_ranges(r.stream.scene_meshes(), r.stream.scene_mesh_count());
        if (!missing.empty()) r.violations.push_back({std::nullopt, "scene: meshes missing: " + missing, true});
        // Parent links that never reach a root (spec 15.1: no packet can be rejected for a cycle).
        const auto& nodes = r.stream.scene_nodes();
        std::string cyclic;
        for (const auto& [index, node] : nodes) {
            uint16_t at = index;
            size_t steps = 0;
            for (auto it = nodes.find(at); it != nodes.end() && it->second.parent != kNone && steps <= nodes.size();
                 it = nodes.find(at), ++steps)
                at = it->second.parent;
            if (steps > nodes.size()) cyclic += (cyclic.empty() ? "" : ", ") + std::to_string(index);
        }
        if (!cyclic.empty())
            r.violations.push_back({std::nullopt, "scene: the parent chain of node(s) " + cyclic + " runs into a cycle and never reaches a root"});
    }
    // Spec 15.1: names are UTF-8 (a decoder shows an ill-formed one with U+FFFD in place).
    auto check_names = [&](const auto& table, const char* what) {
        std::string bad;
        for (const auto& [index, item] : table)
            if (!is_valid_utf8(item.name)) bad += (bad.empty() ? "" : ", ") + std::to_string(index);
        if (!bad.empty())
            r.violations.push_back({std::nullopt, std::string("scene: the name of ") + what + " " + bad + " is not valid UTF-8"});
    };
    check_names(r.stream.scene_nodes(), "node(s)");
    check_names(r.stream.scene_meshes(), "mesh(es)");
    check_names(r.stream.materials(), "material(s)");
    if (!r.stream.materials().empty()) {
        std::string missing = missing_ranges(r.stream.materials(), r.stream.materials().begin()->second.material_count);
        if (!missing.empty()) r.violations.push_back({std::nullopt, "materials missing: " + missing, true});
    }
    // A track of an animation or a morph animation that has not arrived whole or is not usable (spec
    // 20.2, 22.2): reported; its description when any key of it arrived.
    const auto checked_track = [&](const ReceivedStream::ReceivedAnimation& a, uint16_t t,
                                   const std::string& track) -> const AnimationTrackInfo* {
        const auto it = a.tracks.find(t);
        if (it == a.tracks.end()) {
            r.violations.push_back({std::nullopt, track + ": no key received", true});
            return nullptr;
        }
        if (!it->second.complete)
            r.violations.push_back({std::nullopt, track + ": " + std::to_string(it->second.keys_held) + " of " +
                                                      std::to_string(it->second.info.key_count) + " keys received", true});
        else if (!it->second.usable)
            r.violations.push_back({std::nullopt, track + ": its times do not strictly increase across packets"});
        return &it->second.info;
    };
    // Spec 20.2: every animation complete, every track usable, its node recorded, one track per target.
    if (const auto count = r.stream.animation_count()) {
        std::string missing = missing_ranges(r.stream.animations(), *count);
        if (!missing.empty()) r.violations.push_back({std::nullopt, "animations missing: " + missing, true});
        for (const auto& [index, a] : r.stream.animations()) {
            const std::string name = "animation " + std::to_string(index);
            if (!is_valid_utf8(a.name)) r.violations.push_back({std::nullopt, name + ": its name is not valid UTF-8"});
            std::set<std::pair<uint16_t, int>> targets;
            for (uint16_t t = 0; t < a.track_count; ++t) {
                const std::string track = name + " track " + std::to_string(t);
                const AnimationTrackInfo* held = checked_track(a, t, track);
                if (!held) continue;
                const auto& info = *held;
                if (info.node >= r.stream.scene_node_count() || !r.stream.scene_nodes().count(info.node))
                    r.violations.push_back({std::nullopt, track + ": its node " + std::to_string(info.node) +
                                                              " has no node record"});
                if (!targets.insert({info.node, int(info.path)}).second)
                    r.violations.push_back({std::nullopt, track + ": another track of the animation moves the same "
                                                              "property of node " + std::to_string(info.node)});
            }
        }
    }
    // Spec 21.3: skins complete, their nodes recorded, nodes naming skins in the table, every point of a
    // skinned node's objects with a record, every record's joints inside the skins that use them.
    {
        const auto& skins = r.stream.skins();
        if (const auto count = r.stream.skin_count()) {
            std::string missing = missing_ranges(skins, *count);
            if (!missing.empty()) r.violations.push_back({std::nullopt, "skins missing: " + missing, true});
        }
        auto recorded = [&](uint16_t node) {
            return node < r.stream.scene_node_count() && r.stream.scene_nodes().count(node) > 0;
        };
        for (const auto& [index, skin] : skins) {
            const std::string name = "skin " + std::to_string(index);
            if (!is_valid_utf8(skin.name)) r.violations.push_back({std::nullopt, name + ": its name is not valid UTF-8"});
            if (!skin.complete())
                r.violations.push_back({std::nullopt, name + ": " + std::to_string(skin.joints.size()) + " of " +
                                                          std::to_string(skin.joint_count) + " joints received", true});
            for (const auto& [j, joint] : skin.joints)
                if (!recorded(joint.node))
                    r.violations.push_back({std::nullopt, name + " joint " + std::to_string(j) + ": its node " +
                                                              std::to_string(joint.node) + " has no node record"});
            if (skin.skeleton != kNone && !recorded(skin.skeleton))
                r.violations.push_back({std::nullopt, name + ": its skeleton node " + std::to_string(skin.skeleton) +
                                                          " has no node record"});
        }
        for (const auto& [index, node] : r.stream.scene_nodes()) {
            if (node.skin == kNone) continue;
            const std::string name = "node " + std::to_string(index);
            const auto count = r.stream.skin_count();
            if (!count || node.skin >= *count)
                r.violations.push_back({std::nullopt, name + ": it names skin " + std::to_string(node.skin) +
                                                          ", past the skin table"});
            if (node.mesh == kNone) r.violations.push_back({std::nullopt, name + ": it names a skin but has no mesh"});
        }
        // Objects of skinned nodes' meshes (a missing mesh record is reported as such above).
        for (const auto& [o, joints] : skinned_objects(r.stream)) {
            if (o >= r.stream.objects().size() || !r.stream.objects()[o].info) continue;
            const ReceivedObject& object = r.stream.objects()[o];
            const std::string name = "object " + std::to_string(o);
            if (object.weights.size() < object.info->point_count) {
                std::string gaps;
                uint32_t at = 0, shown = 0;
                auto gap = [&](uint32_t from, uint32_t to) {
                    if (from >= to || shown++ >= 8) return;
                    gaps += (gaps.empty() ? "" : ", ") + std::to_string(from) + (to - from > 1 ? ".." + std::to_string(to - 1) : "");
                };
                for (const auto& [i, record] : object.weights) gap(at, i), at = i + 1;
                gap(at, object.info->point_count);
                r.violations.push_back({std::nullopt, name + ": a skinned node shows it, and " +
                                                          std::to_string(object.info->point_count - object.weights.size()) +
                                                          " of its points have no joint weights (" + gaps +
                                                          (shown > 8 ? ", ..." : "") + ")", true});
            }
            for (const auto& [i, record] : object.weights) {
                bool past = false;
                for (size_t k = 0; k < record->count; ++k) past |= record->joints[k] >= joints;
                if (past) {
                    r.violations.push_back({std::nullopt, name + " point " + std::to_string(i) +
                                                              ": its weights name a joint past the " + std::to_string(joints) +
                                                              " joints of a skin that uses it"});
                    break;
                }
            }
        }
    }
    // Spec 28.3: every announced extras text complete, and each naming an element of the stream.
    if (const auto count = r.stream.extras_count()) {
        if (r.stream.extras().size() < *count)
            r.violations.push_back({std::nullopt, std::to_string(*count - r.stream.extras().size()) + " of " +
                                                      std::to_string(*count) + " extras texts missing", true});
        const auto table_size = [&](ExtrasTarget kind) -> std::optional<size_t> {
            const auto opt = [](const auto& c) { return c ? std::optional<size_t>(*c) : std::nullopt; };
            switch (kind) {
            case ExtrasTarget::Asset:
            case ExtrasTarget::Scene: return 1;
            case ExtrasTarget::Node: return r.stream.has_scene() ? std::optional<size_t>(r.stream.scene_node_count()) : std::nullopt;
            case ExtrasTarget::Mesh: return r.stream.has_scene() ? std::optional<size_t>(r.stream.scene_mesh_count()) : std::nullopt;
            case ExtrasTarget::Material:
                return r.stream.materials().empty() ? std::nullopt
                                                    : std::optional<size_t>(r.stream.materials().begin()->second.material_count);
            case ExtrasTarget::Texture:
                return r.stream.textures().empty() ? std::nullopt
                                                   : std::optional<size_t>(r.stream.textures().begin()->second.info.texture_count);
            case ExtrasTarget::Animation: return opt(r.stream.animation_count());
            case ExtrasTarget::Skin: return opt(r.stream.skin_count());
            case ExtrasTarget::Camera: return opt(r.stream.camera_count());
            case ExtrasTarget::Light: return opt(r.stream.light_count());
            case ExtrasTarget::MorphAnimation: return opt(r.stream.morph_animation_count());
            }
            return std::nullopt;
        };
        for (const auto& [key, e] : r.stream.extras()) {
            const std::string name = "extras of " + extras_target_label(key.first, key.second);
            if (!e.complete)
                r.violations.push_back({std::nullopt, name + ": " + std::to_string(e.received_bytes) + " of " +
                                                          std::to_string(e.text_size) + " bytes received", true});
            const auto size = table_size(key.first);
            if (!size || key.second >= *size)
                r.violations.push_back({std::nullopt, name + ": no such " + extras_target_name(key.first) + " in the stream"});
            if (key.first == ExtrasTarget::MorphAnimation) {
                const auto a = r.stream.morph_animations().find(key.second);
                if (a != r.stream.morph_animations().end() && a->second.joins != kNone)
                    r.violations.push_back({std::nullopt, name + ": that morph animation joins animation " +
                                                              std::to_string(a->second.joins) + " (its extras go there)"});
            }
        }
    }
    // Spec 29.2: a name held at every index below the name count.
    if (const auto count = r.stream.required_extension_count()) {
        std::string missing = missing_ranges(r.stream.required_extensions(), *count);
        if (!missing.empty())
            r.violations.push_back({std::nullopt, "required extension names missing: " + missing, true});
    }
    // Spec 26.4: cameras and lights complete, their names valid UTF-8, every node naming one inside its table.
    {
        const auto check = [&](const auto& table, std::optional<uint16_t> count, const char* what, auto field) {
            if (count) {
                std::string missing = missing_ranges(table, *count);
                if (!missing.empty()) r.violations.push_back({std::nullopt, std::string(what) + "s missing: " + missing, true});
            }
            for (const auto& [index, record] : table)
                if (!is_valid_utf8(record.name))
                    r.violations.push_back({std::nullopt, std::string(what) + " " + std::to_string(index) +
                                                              ": its name is not valid UTF-8"});
            for (const auto& [index, node] : r.stream.scene_nodes()) {
                const uint16_t named = node.*field;
                if (named != kNone && (!count || named >= *count))
                    r.violations.push_back({std::nullopt, "node " + std::to_string(index) + ": it names " + what + " " +
                                                              std::to_string(named) + ", past the " + what + " table"});
            }
        };
        check(r.stream.cameras(), r.stream.camera_count(), "camera", &SceneNode::camera);
        check(r.stream.lights(), r.stream.light_count(), "light", &SceneNode::light);
    }
    // Spec 22.4: morph animations complete, their tracks usable over recorded nodes whose meshes carry
    // as many targets, one track per node in each written animation, joined animations in the table;
    // every point of the objects of meshes with targets with displacements of that count, and every
    // object with displacements shown by a mesh with its count.
    {
        const auto& morphs = r.stream.morph_animations();
        if (const auto count = r.stream.morph_animation_count()) {
            std::string missing = missing_ranges(morphs, *count);
            if (!missing.empty()) r.violations.push_back({std::nullopt, "morph animations missing: " + missing, true});
        }
        std::map<uint16_t, std::set<uint16_t>> written_nodes;  // by written animation: ANIMATION j, or 0x10000 + m
        for (const auto& [index, a] : morphs) {
            const std::string name = "morph animation " + std::to_string(index);
            if (!is_valid_utf8(a.name)) r.violations.push_back({std::nullopt, name + ": its name is not valid UTF-8"});
            if (a.joins != kNone && (!r.stream.animation_count() || a.joins >= *r.stream.animation_count()))
                r.violations.push_back({std::nullopt, name + ": it joins animation " + std::to_string(a.joins) +
                                                          ", past the animation table"});
            auto& nodes = written_nodes[a.joins != kNone ? a.joins : uint16_t(0)];
            std::set<uint16_t> own;
            auto& seen = a.joins != kNone ? nodes : own;
            for (uint16_t t = 0; t < a.track_count; ++t) {
                const std::string track = name + " track " + std::to_string(t);
                const AnimationTrackInfo* held = checked_track(a, t, track);
                if (!held) continue;
                const auto& info = *held;
                const auto node = r.stream.scene_nodes().find(info.node);
                if (info.node >= r.stream.scene_node_count() || node == r.stream.scene_nodes().end()) {
                    r.violations.push_back({std::nullopt, track + ": its node " + std::to_string(info.node) +
                                                              " has no node record"});
                } else {
                    const auto mesh = r.stream.scene_meshes().find(node->second.mesh);
                    if (node->second.mesh == kNone || (mesh != r.stream.scene_meshes().end() &&
                                                       mesh->second.weights.size() != info.targets))
                        r.violations.push_back({std::nullopt, track + ": node " + std::to_string(info.node) +
                                                                  " has no mesh with " + std::to_string(info.targets) +
                                                                  " morph targets"});
                }
                if (!seen.insert(info.node).second)
                    r.violations.push_back({std::nullopt, track + ": another morph track of the same written animation "
                                                              "moves the weights of node " + std::to_string(info.node)});
            }
        }
        std::map<uint16_t, std::set<size_t>> counts;  // object -> target counts of the meshes showing it
        for (const auto& [index, mesh] : r.stream.scene_meshes())
            for (const auto& p : mesh.primitives) counts[p.object].insert(mesh.weights.size());
        for (size_t o = 0; o < r.stream.objects().size(); ++o) {
            const ReceivedObject& object = r.stream.objects()[o];
            if (!object.info) continue;
            const std::string name = "object " + std::to_string(o);
            const auto shown = counts.find(uint16_t(o));
            std::set<size_t> targets;
            if (shown != counts.end()) targets = shown->second;
            targets.erase(0);
            if (!object.morph.empty() && !targets.count(object.morph_targets))
                r.violations.push_back({std::nullopt, name + ": it has " + std::to_string(object.morph_targets) +
                                                          " morph targets, but no mesh with that count shows it"});
            if (targets.empty()) continue;
            if (targets.size() > 1)
                r.violations.push_back({std::nullopt, name + ": meshes with different morph target counts show it"});
            if (object.morph.size() < object.info->point_count)
                r.violations.push_back({std::nullopt, name + ": a mesh with morph targets shows it, and " +
                                                          std::to_string(object.info->point_count - object.morph.size()) +
                                                          " of its points have no displacements", true});
        }
    }
    if (!r.stream.textures().empty()) {
        std::string missing = missing_ranges(r.stream.textures(), r.stream.textures().begin()->second.info.texture_count);
        if (!missing.empty()) r.violations.push_back({std::nullopt, "textures missing: " + missing, true});
        for (const auto& [index, t] : r.stream.textures()) {
            const std::string name = "texture " + std::to_string(index);
            if (!t.complete) {
                r.violations.push_back({std::nullopt, name + ": " + std::to_string(t.received_bytes) + " of " +
                                                          std::to_string(t.info.image_size) + " image bytes received", true});
                continue;
            }
            // Spec 15.3/15.4: a complete texture must be a file of its image_type, with the header a
            // viewer needs (a file cut off in its image data is still one, as the source had it).
            const auto declared = t.info.image_type == ImageType::Png ? image_file::Format::Png : image_file::Format::Jpeg;
            const image_file::Check c = image_file::check(t.image);
            if (c.format != declared)
                r.violations.push_back({std::nullopt, name + ": image_type says " + image_file::name(declared) +
                                                          " but the image is " +
                                                          (c.format == image_file::Format::Unknown
                                                               ? std::string("neither a PNG nor a JPEG file")
                                                               : std::string("a ") + image_file::name(c.format) + " file")});
            else if (!c.readable)
                r.violations.push_back({std::nullopt, name + ": the " + image_file::name(c.format) +
                                                          " file cannot be shown: " + c.problem});
        }
    }
    // Spec 18.4 (format 1.3): every flagged material has its patch, every patch's material its flag,
    // and every texture a patch refers to is in the table and complete.
    for (const auto& [index, m] : r.stream.materials())
        if (m.has_extensions && !r.stream.material_extensions().count(index))
            r.violations.push_back({std::nullopt, "material " + std::to_string(index) +
                                                      ": its has_extensions bit is set but its MATERIAL_EXTENSIONS "
                                                      "packet did not arrive"});
    for (const auto& [index, patch] : r.stream.material_extensions()) {
        const std::string name = "material " + std::to_string(index);
        if (auto m = r.stream.materials().find(index); m != r.stream.materials().end() && !m->second.has_extensions)
            r.violations.push_back({std::nullopt, name + ": a MATERIAL_EXTENSIONS packet arrived but the material's "
                                                         "has_extensions bit is not set"});
        std::vector<PatchTextureReference> refs;
        check_material_patch(patch.patch, &refs);
        for (const auto& ref : refs) {
            const auto t = r.stream.textures().find(ref.texture);
            const bool past = !r.stream.textures().empty() &&
                              ref.texture >= r.stream.textures().begin()->second.info.texture_count;
            if (past)
                r.violations.push_back({std::nullopt, name + ": " + ref.path + " refers to texture " +
                                                          std::to_string(ref.texture) + ", past the texture table"});
            else if (t == r.stream.textures().end() || !t->second.complete)
                r.violations.push_back({std::nullopt, name + ": " + ref.path + " refers to texture " +
                                                          std::to_string(ref.texture) + ", which is not complete"});
        }
    }
    return r;
}

}  // namespace ellicast::cli

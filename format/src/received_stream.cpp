// Collects the packets of one stream as they arrive: any order, duplicates, damage, late stream info.
#include "ellicast/format.h"

#include "fragments.h"

#include <algorithm>

namespace ellicast {

namespace {

bool same_stream_fields(const StreamInfo& a, const StreamInfo& b) {
    return a.packet_size == b.packet_size && a.position_bits == b.position_bits && a.normal_bits == b.normal_bits &&
           a.texcoord_bits == b.texcoord_bits && a.color_bits == b.color_bits &&
           a.ellipsoid_encoding == b.ellipsoid_encoding && a.content_id == b.content_id && a.grid_hint == b.grid_hint &&
           a.coverage_target == b.coverage_target && a.seed == b.seed;
}

}  // namespace

ReceivedStream::ReceivedStream() : ReceivedStream(Limits{}) {}
ReceivedStream::ReceivedStream(Limits limits) : limits_(limits) {}

SharedMemoryBudget ReceivedStream::budget_in_force() const {
    if (shared_budget_) return *shared_budget_;
    return {held_memory_, bytes_taken_, limits_.memory_base, limits_.memory_per_byte};
}

void ReceivedStream::share_memory_budget(std::shared_ptr<SharedMemoryBudget> budget) {
    if (shared_budget_) shared_budget_->held -= held_memory_;
    shared_budget_ = std::move(budget);
    if (shared_budget_) shared_budget_->held += held_memory_;
}

Error ReceivedStream::reject(uint64_t where, Error e, std::string detail) {
    ++counters_.rejected;
    if (rejections_.size() < limits_.max_rejections_kept) rejections_.push_back({where, e, std::move(detail)});
    return e;
}

std::string ReceivedStream::stream_info_problem() const {
    if (info_ || !first_stream_info_rejection_) return {};
    const Rejection& r = *first_stream_info_rejection_;
    return std::to_string(stream_info_rejected_) + " STREAM_INFO packet" + (stream_info_rejected_ == 1 ? " was" : "s were") +
           " rejected; the first (at " + std::to_string(r.where) + ") as " + error_name(r.error) + ": " + r.detail;
}

Error ReceivedStream::add_packet(std::span<const uint8_t> bytes, uint64_t where) {
    PacketView view;
    Error e = parse_packet(bytes, view);
    if (e != Error::Ok) return reject(where, e, std::to_string(bytes.size()) + "-byte datagram");
    return add_parsed(view, where);
}

Error ReceivedStream::add_parsed(const PacketView& packet, uint64_t where) {
    const PacketHeader& h = packet.header;
    bytes_taken_ += packet.size;  // intact: the byte budget follows it (spec 11.2)
    if (stream_id_ && *stream_id_ != h.stream_id)
        return reject(where, Error::StreamMismatch, "stream id " + std::to_string(h.stream_id) + ", expected " +
                                                        std::to_string(*stream_id_));
    if (!is_known_packet_type(h.type)) {
        if (!h.skippable())
            return reject(where, Error::UnknownCriticalType, "type " + packet_type_name(h.type));
        stream_id_ = h.stream_id;
        ++counters_.skipped;
        newest_minor_ = std::max(newest_minor_, h.version_minor);
        return Error::Ok;
    }
    auto object_packet = [&](bool well_formed, const char* why) {
        if (!well_formed)
            return reject(where, Error::MalformedPayload,
                          packet_type_name(h.type) + " of object " + std::to_string(h.object_id) + ": " + why);
        return take_object_packet(packet, where);
    };
    Error e;
    switch (static_cast<PacketType>(h.type)) {
    case PacketType::StreamInfo:
        e = take_stream_info(packet, where);
        if (e != Error::Ok && !rejections_.empty() && rejections_.back().where == where) {
            ++stream_info_rejected_;
            if (!first_stream_info_rejection_) first_stream_info_rejection_ = rejections_.back();
        }
        break;
    case PacketType::Scene: e = take_scene(packet, where); break;
    case PacketType::Material: e = take_material(packet, where); break;
    case PacketType::MaterialExtensions: e = take_material_extensions(packet, where); break;
    case PacketType::TextureFragment: e = take_texture_fragment(packet, where); break;
    case PacketType::Animation: e = take_animation(packet, where); break;
    case PacketType::Skin: e = take_skin(packet, where); break;
    case PacketType::MorphAnimation: e = take_morph_animation(packet, where); break;
    case PacketType::Camera: e = take_camera(packet, where); break;
    case PacketType::Light: e = take_light(packet, where); break;
    case PacketType::Extras: e = take_extras(packet, where); break;
    case PacketType::RequiredExtension: e = take_required_extension(packet, where); break;
    case PacketType::Manifest: {
        // A decoder checks its layout and takes nothing from it: verifying signatures is the
        // job of the filter in front of it (spec 16.3), which needs the sender's key.
        ManifestPart part;
        if (decode_manifest_payload(packet.payload, part) != Error::Ok)
            return reject(where, Error::MalformedPayload, "MANIFEST of " + std::to_string(packet.payload.size()) +
                                                              " bytes: its length, part or digest range is inconsistent");
        ++counters_.skipped;
        e = Error::Ok;
        break;
    }
    // Step 11 of the object types whose payload is checked without stream info (spec 17.3, 21.2,
    // 22.1, 23.3, 24.2): malformed now, or on to the object's steps.
    case PacketType::PointsRepair: {
        RepairPacket repair;
        e = object_packet(decode_repair_payload(packet.payload, repair) == Error::Ok,
                          "its block (point_count, batch, source_count, row) is inconsistent or the payload too short");
        break;
    }
    case PacketType::JointWeights: {
        JointWeightsRun run;
        e = object_packet(decode_joint_weights_payload(packet.payload, run) == Error::Ok,
                          "its count, joint size or an influence record (count, zero weight, weights not summing "
                          "to 255, a joint named twice, records not ending with the payload) is malformed");
        break;
    }
    case PacketType::PointMap: {
        PointMapFragment fragment;
        e = object_packet(decode_point_map_header(packet.payload, fragment) == Error::Ok,
                          "shorter than 12 bytes, or point_total 0, rice above 15 or root_count 0");
        break;
    }
    case PacketType::MorphDeltas: {
        MorphDeltasRun run;
        e = object_packet(decode_morph_deltas_payload(packet.payload, run) == Error::Ok,
                          "its count, target count, attributes, a scale (not finite, not above 0, or 2^113 or "
                          "more), a record's mask (a bit past its slots) or its length is malformed");
        break;
    }
    case PacketType::Normals:
        e = object_packet(check_normals_header(packet.payload) == Error::Ok,
                          "shorter than 8 bytes, or count 0, sent_count above count, or a run past index 2^32 - 1");
        break;
    case PacketType::Texcoords: {
        TexcoordsRun run;
        e = object_packet(decode_texcoords_payload(packet.payload, run) == Error::Ok,
                          "shorter than 28 bytes, or count 0, set_count 0 or above 7, set 0 or above set_count, bits "
                          "outside 4..16, a run past index 2^32 - 1, a range not finite, negative or with an infinite "
                          "end, or a length that does not match its count and bits");
        break;
    }
    default: e = take_object_packet(packet, where); break;
    }
    if (e == Error::Ok) {
        stream_id_ = h.stream_id;
        newest_minor_ = std::max(newest_minor_, h.version_minor);
    }
    return e;
}

Error ReceivedStream::take_stream_info(const PacketView& packet, uint64_t where) {
    if (packet.header.object_id != kStreamObjectId)
        return reject(where, Error::MalformedPayload, "STREAM_INFO with object id " +
                                                          std::to_string(packet.header.object_id) + ", expected 65535");
    StreamInfoPart part;
    if (decode_stream_info_payload(packet.payload, part, packet.header.version_minor) != Error::Ok)
        return reject(where, Error::MalformedPayload, "STREAM_INFO payload inconsistent or out of range");
    if (info_) {
        if (!same_stream_fields(*info_, part.info) || part.object_count != object_count_)
            return reject(where, Error::StreamMismatch, "STREAM_INFO contradicts the stream info received before");
    } else {
        uint64_t declared = 0;
        for (const auto& o : part.info.objects) declared += uint64_t(o.ellipsoid_count) + o.point_count;
        if (declared > limits_.max_elements)
            return reject(where, Error::MalformedPayload, "declares more elements than this receiver accepts");
        StreamInfo stream = part.info;
        stream.objects.clear();
        info_ = std::move(stream);
        object_count_ = part.object_count;
        objects_.assign(object_count_, ReceivedObject{});
        // Packets held for objects the table turns out not to have will never be released (one
        // pass: a hold of many packets is not erased one at a time).
        std::vector<Pending> keep;
        keep.reserve(pending_.size());
        for (Pending& p : pending_) {
            if (p.header.object_id < object_count_) {
                keep.push_back(std::move(p));
                continue;
            }
            pending_bytes_ -= p.payload.size() + kHeldPacketCost;
            --counters_.pending;
            reject(p.where, Error::UnknownObject,
                   packet_type_name(p.header.type) + " of object " + std::to_string(p.header.object_id) +
                       ", the stream has " + std::to_string(object_count_) + " objects");
        }
        pending_ = std::move(keep);
    }
    bool news = false;
    uint64_t declared = carried_elements_;  // format 1.11: carried vertices count too (spec 27.1)
    for (const auto& object : objects_)
        if (object.info) declared += uint64_t(object.info->ellipsoid_count) + object.info->point_count;
    for (size_t i = 0; i < part.info.objects.size(); ++i) {
        const ObjectInfo& entry = part.info.objects[i];
        ReceivedObject& object = objects_[part.first_object + i];
        if (object.info) {
            if (!(*object.info == entry))
                return reject(where, Error::StreamMismatch,
                              "object " + std::to_string(part.first_object + i) + " entry contradicts an earlier one");
            continue;
        }
        declared += uint64_t(entry.ellipsoid_count) + entry.point_count;
        if (declared > limits_.max_elements)
            return reject(where, Error::MalformedPayload, "declares more elements than this receiver accepts");
    }
    for (size_t i = 0; i < part.info.objects.size(); ++i) {
        ReceivedObject& object = objects_[part.first_object + i];
        if (object.info) continue;
        object.info = part.info.objects[i];
        object.points.set_layout(*object.info);
        object.unplaced.set_layout(*object.info);
        news = true;
    }
    if (news) release_pending();
    if (news || part.info.objects.empty()) ++counters_.accepted;
    else ++counters_.duplicates;
    return Error::Ok;
}

Error ReceivedStream::take_object_packet(const PacketView& packet, uint64_t where) {
    const uint16_t id = packet.header.object_id;
    const std::string name = packet_type_name(packet.header.type) + " of object " + std::to_string(id);
    if (info_ && id >= object_count_)
        return reject(where, Error::UnknownObject, name + ", the stream has " + std::to_string(object_count_) + " objects");
    if (!info_ || !objects_[id].info) {
        if (pending_bytes_ + packet.payload.size() + kHeldPacketCost > limits_.max_pending_bytes ||
            pending_.size() >= limits_.max_pending_packets)
            return reject(where, Error::NoStreamInfo, name + " arrived before its stream info and the hold is full");
        pending_.push_back({packet.header, {packet.payload.begin(), packet.payload.end()}, where});
        pending_bytes_ += packet.payload.size() + kHeldPacketCost;
        ++counters_.pending;
        return Error::Ok;
    }
    ReceivedObject& object = objects_[id];
    // The byte budget (spec 11.2): checked before the packet, so what it adds (at most what one
    // packet's records cost) may take the objects past it once.
    const SharedMemoryBudget b = budget_in_force();
    if (b.held > b.budget())
        return reject(where, Error::MalformedPayload,
                      name + (shared_budget_ ? ": the candidate streams hold " : ": the objects hold ") +
                          std::to_string(b.held) + " bytes, over this receiver's budget of " + std::to_string(b.budget()) +
                          " (" + std::to_string(b.base) + " plus " + std::to_string(b.per_byte) + " times the " +
                          std::to_string(b.bytes) + " bytes of intact packets taken)");
    const uint64_t before = object.memory();
    const Error e = take_object_content(object, packet, name, where);
    const uint64_t after = object.memory();
    held_memory_ = held_memory_ - before + after;
    if (shared_budget_) shared_budget_->held = shared_budget_->held - before + after;
    return e;
}

Error ReceivedStream::take_object_content(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                          uint64_t where) {
    const ObjectInfo& oi = *object.info;
    if (packet.header.type == static_cast<uint8_t>(PacketType::PointsRepair)) return take_repair(object, packet, name, where);
    if (is_exact_layer_type(packet.header.type)) return take_connectivity(object, packet, name, where);
    if (is_exact_layer_repair_type(packet.header.type)) return take_connectivity_repair(object, packet, name, where);
    if (packet.header.type == static_cast<uint8_t>(PacketType::JointWeights))
        return take_joint_weights(object, packet, name, where);
    if (packet.header.type == static_cast<uint8_t>(PacketType::MorphDeltas))
        return take_morph_deltas(object, packet, name, where);
    if (packet.header.type == static_cast<uint8_t>(PacketType::PointMap)) return take_point_map(object, packet, name, where);
    if (packet.header.type == static_cast<uint8_t>(PacketType::Normals)) return take_normals(object, packet, name, where);
    if (packet.header.type == static_cast<uint8_t>(PacketType::Texcoords))
        return take_texcoords(object, packet, name, where);
    bool news = false;
    if (packet.header.type == static_cast<uint8_t>(PacketType::Ellipsoids)) {
        EllipsoidBatch batch;
        if (decode_ellipsoids_payload(packet.payload, batch) != Error::Ok)
            return reject(where, Error::MalformedPayload, name + ": payload length does not match its count");
        if (uint64_t(batch.first_index) + batch.ellipsoids.size() > oi.ellipsoid_count)
            return reject(where, Error::IndexOutOfRange,
                          name + ": ellipsoids " + std::to_string(batch.first_index) + "+" +
                              std::to_string(batch.ellipsoids.size()) + " of " + std::to_string(oi.ellipsoid_count));
        for (size_t i = 0; i < batch.ellipsoids.size(); ++i)
            news |= object.ellipsoids.insert(batch.first_index + static_cast<uint32_t>(i), &batch.ellipsoids[i]);
    } else {
        // POINTS for an object without a map, MAPPED_POINTS for one with a map (spec 23.4).
        const bool mapped_type = packet.header.type == static_cast<uint8_t>(PacketType::MappedPoints);
        if (mapped_type != oi.mapped())
            return reject(where, Error::MalformedPayload,
                          name + (mapped_type ? ": the object has no map (map_level 0), its points travel as POINTS"
                                              : ": the object is mapped (map_level " + std::to_string(oi.map_level) +
                                                    "), its points travel as MAPPED_POINTS"));
        PointBatch batch;
        if (decode_points_payload(packet.payload, *info_, oi, batch) != Error::Ok)
            return reject(where, Error::MalformedPayload, name + ": payload length does not match its count");
        if (uint64_t(batch.first_index) + batch.points.size() > oi.point_count)
            return reject(where, Error::IndexOutOfRange,
                          name + ": points " + std::to_string(batch.first_index) + "+" +
                              std::to_string(batch.points.size()) + " of " + std::to_string(oi.point_count));
        std::vector<uint32_t> fresh;
        for (size_t i = 0; i < batch.points.size(); ++i)
            if (take_point_record(object, batch.first_index + static_cast<uint32_t>(i), batch.points[i]))
                fresh.push_back(batch.first_index + static_cast<uint32_t>(i));
        news = !fresh.empty();
        if (news) ++counters_.accepted;
        else ++counters_.duplicates;
        if (news && !object.repair_blocks.empty()) note_new_points(object, fresh);
        return Error::Ok;
    }
    if (news) ++counters_.accepted;
    else ++counters_.duplicates;
    return Error::Ok;
}

// Format 1.11 (spec 27.1), for a well-formed exact-layer packet: the first of an object fixes the kind
// of its layer (EXACT_MESH or CONNECTIVITY) and, for EXACT_MESH, counts its carried vertices toward the
// element limit (refused: nothing kept); a later one of the other kind is a mismatch.
Error ReceivedStream::take_layer_kind(const ReceivedObject& object, bool mesh, uint32_t carried_count,
                                      const std::string& name, uint64_t where) {
    if (object.connectivity) {
        if (object.connectivity->mesh == mesh) return Error::Ok;
        return reject(where, Error::StreamMismatch,
                      name + ": the object's exact layer travels in " +
                          (object.connectivity->mesh ? "EXACT_MESH packets" : "CONNECTIVITY packets") +
                          " (spec 27.1: one kind per object)");
    }
    if (!mesh) return Error::Ok;
    uint64_t declared = carried_elements_ + carried_count;
    for (const auto& o : objects_)
        if (o.info) declared += uint64_t(o.info->ellipsoid_count) + o.info->point_count;
    if (declared > limits_.max_elements)
        return reject(where, Error::MalformedPayload,
                      name + ": its " + std::to_string(carried_count) +
                          " carried vertices would take the stream past this receiver's limit of " +
                          std::to_string(limits_.max_elements) + " elements (spec 27.1)");
    carried_elements_ += carried_count;
    return Error::Ok;
}

namespace {

// The object's connectivity, described by the first packet of it taken (spec 19.1, 19.5, 27.1).
ReceivedConnectivity& connectivity_of(ReceivedObject& object, bool mesh, uint32_t triangle_count,
                                      uint32_t carried_count, uint32_t coded_size, uint32_t coded_crc) {
    if (!object.connectivity) {
        object.connectivity.emplace();
        object.connectivity->mesh = mesh;
        object.connectivity->carried_count = carried_count;
        object.connectivity->triangle_count = triangle_count;
        object.connectivity->coded_size = coded_size;
        object.connectivity->coded_crc = coded_crc;
    }
    return *object.connectivity;
}

}  // namespace

// Format 1.3 (spec 19.1): a piece of an object's coded connectivity, kept like a texture's bytes.
Error ReceivedStream::take_connectivity(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                        uint64_t where) {
    const ObjectInfo& oi = *object.info;
    const bool mesh = packet.header.type == static_cast<uint8_t>(PacketType::ExactMesh);
    ConnectivityPiece piece;
    if (decode_connectivity_payload(packet.payload, piece, mesh) != Error::Ok ||
        !exact_layer_fits(*info_, oi, piece.triangle_count, piece.carried_count, piece.coded_size, mesh))
        return reject(where, Error::MalformedPayload,
                      name + (mesh ? ": its triangle count, carried count, coded size or piece does not fit the object "
                                     "(spec 27.1)"
                                   : ": its triangle count, coded size or piece does not fit the object (spec 19.1)"));
    if (Error e = take_layer_kind(object, mesh, piece.carried_count, name, where); e != Error::Ok) return e;
    ReceivedConnectivity& c =
        connectivity_of(object, mesh, piece.triangle_count, piece.carried_count, piece.coded_size, piece.coded_crc);
    if (c.triangle_count != piece.triangle_count || c.carried_count != piece.carried_count ||
        c.coded_size != piece.coded_size || c.coded_crc != piece.coded_crc)
        return reject(where, Error::StreamMismatch,
                      name + (mesh ? ": its triangle count, carried count, coded size or CRC contradicts earlier pieces"
                                   : ": its triangle count, coded size or CRC contradicts earlier pieces"));
    if (c.complete) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    const uint32_t begin = piece.offset, end = uint32_t(piece.offset + piece.data.size());
    std::vector<std::pair<uint32_t, uint32_t>> gaps;
    uint32_t cursor = begin;
    auto it = c.pieces.upper_bound(begin);
    if (it != c.pieces.begin()) --it;
    for (; it != c.pieces.end() && it->first < end; ++it) {
        const uint32_t it_end = uint32_t(it->first + it->second.size());
        if (it_end <= cursor) continue;
        if (it->first > cursor) gaps.emplace_back(cursor, it->first);
        cursor = std::max(cursor, it_end);
    }
    if (cursor < end) gaps.emplace_back(cursor, end);
    if (gaps.empty()) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    // Memory as for textures (spec 15.3): the bytes kept plus kHeldPacketCost per run, under the same cap.
    uint64_t memory = gaps.size() * kHeldPacketCost;
    for (auto [a, b] : gaps) memory += b - a;
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      name + ": the stream's textures and connectivity exceed this receiver's " +
                          std::to_string(limits_.max_texture_bytes) + "-byte memory limit for them");
    texture_bytes_ += memory;
    for (auto [a, b] : gaps) {
        c.pieces.emplace(a, std::vector<uint8_t>(piece.data.begin() + (a - begin), piece.data.begin() + (b - begin)));
        c.received_bytes += b - a;
    }
    if (Error e = complete_connectivity(c, name, where); e != Error::Ok) return e;
    ++counters_.accepted;
    return Error::Ok;
}

namespace {

// Whether bytes [begin, end) of a connectivity have all arrived, and if so (with `out`) what they are.
bool covered(const ReceivedConnectivity& c, uint32_t begin, uint32_t end, std::vector<uint8_t>* out) {
    auto it = c.pieces.upper_bound(begin);
    if (it == c.pieces.begin()) return false;
    --it;
    uint32_t cursor = begin;
    for (; it != c.pieces.end() && cursor < end; ++it) {
        const uint32_t piece_end = uint32_t(it->first + it->second.size());
        if (it->first > cursor) return false;
        if (piece_end <= cursor) continue;
        const uint32_t to = std::min(end, piece_end);
        if (out) out->insert(out->end(), it->second.begin() + (cursor - it->first), it->second.begin() + (to - it->first));
        cursor = to;
    }
    return cursor >= end;
}

}  // namespace

Error ReceivedStream::complete_connectivity(ReceivedConnectivity& c, const std::string& name, uint64_t where) {
    if (c.complete) return Error::Ok;
    if (c.received_bytes < c.coded_size && !c.rows.empty()) {
        // Spec 19.5: held source symbols and repair rows together reach k: solve for the rest.
        const size_t size = c.symbol_size;
        const size_t k = (size_t(c.coded_size) + size - 1) / size;
        std::vector<std::vector<uint8_t>> sources(k);
        size_t held = 0;
        for (size_t j = 0; j < k; ++j) {
            const uint32_t from = uint32_t(j * size), to = uint32_t(std::min<size_t>(c.coded_size, (j + 1) * size));
            std::vector<uint8_t> bytes;
            if (!covered(c, from, to, &bytes)) continue;
            bytes.resize(size, 0);
            sources[j] = std::move(bytes);
            ++held;
        }
        if (held + c.rows.size() >= k) {
            const size_t missing = k - held;
            std::vector<uint8_t> rows(c.rows.begin(), c.rows.begin() + long(missing));
            std::vector<std::vector<uint8_t>> symbols(c.symbols.begin(), c.symbols.begin() + long(missing));
            if (recover_source_symbols(sources, rows, symbols)) {
                std::vector<uint8_t> coded;
                coded.reserve(k * size);
                for (const auto& s : sources) coded.insert(coded.end(), s.begin(), s.end());
                coded.resize(c.coded_size);
                c.pieces.clear();
                c.pieces.emplace(0, std::move(coded));
                c.received_bytes = c.coded_size;
                c.recovered = missing > 0;
            }
        }
    }
    if (c.received_bytes < c.coded_size) return Error::Ok;
    std::vector<uint8_t> coded;
    coded.reserve(c.coded_size);
    for (const auto& [offset, bytes] : c.pieces) coded.insert(coded.end(), bytes.begin(), bytes.end());
    c.pieces.clear();
    c.received_bytes = 0;
    c.rows.clear();
    c.symbols.clear();
    if (crc32c(coded.data(), coded.size()) != c.coded_crc) {
        c.recovered = false;
        return reject(where, Error::StreamMismatch, name + ": the connectivity is complete but its CRC does not match");
    }
    c.coded = std::move(coded);
    c.received_bytes = c.coded_size;
    c.complete = true;
    return Error::Ok;
}

// Format 1.3 (spec 19.5): a repair symbol over an object's coded connectivity.
Error ReceivedStream::take_connectivity_repair(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                               uint64_t where) {
    const ObjectInfo& oi = *object.info;
    const bool mesh = packet.header.type == static_cast<uint8_t>(PacketType::ExactMeshRepair);
    ConnectivityRepair r;
    if (decode_connectivity_repair_payload(packet.payload, r, mesh) != Error::Ok ||
        !exact_layer_fits(*info_, oi, r.triangle_count, r.carried_count, r.coded_size, mesh))
        return reject(where, Error::MalformedPayload,
                      name + (mesh ? ": its triangle count, carried count, coded size, symbol size or row does not fit "
                                     "(spec 27.1)"
                                   : ": its triangle count, coded size, symbol size or row does not fit (spec 19.5)"));
    if (Error e = take_layer_kind(object, mesh, r.carried_count, name, where); e != Error::Ok) return e;
    ReceivedConnectivity& c =
        connectivity_of(object, mesh, r.triangle_count, r.carried_count, r.coded_size, r.coded_crc);
    if (c.triangle_count != r.triangle_count || c.carried_count != r.carried_count || c.coded_size != r.coded_size ||
        c.coded_crc != r.coded_crc || (c.symbol_size != 0 && c.symbol_size != r.symbol_size))
        return reject(where, Error::StreamMismatch,
                      name + ": its triangle count, coded size, CRC or symbol size contradicts earlier packets");
    c.symbol_size = r.symbol_size;
    const size_t k = (size_t(c.coded_size) + r.symbol_size - 1) / r.symbol_size;
    if (c.complete || c.rows.size() >= k || std::find(c.rows.begin(), c.rows.end(), r.row) != c.rows.end()) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    const uint64_t memory = r.symbol.size() + kHeldPacketCost;
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      name + ": the stream's textures and connectivity exceed this receiver's " +
                          std::to_string(limits_.max_texture_bytes) + "-byte memory limit for them");
    texture_bytes_ += memory;
    c.rows.push_back(r.row);
    c.symbols.push_back(std::move(r.symbol));
    if (Error e = complete_connectivity(c, name, where); e != Error::Ok) return e;
    ++counters_.accepted;
    return Error::Ok;
}

Error ReceivedStream::take_repair(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                  uint64_t where) {
    const ObjectInfo& oi = *object.info;
    RepairPacket repair;
    decode_repair_payload(packet.payload, repair);  // checked before it was taken or held
    RepairBlock& block = repair.block;
    const size_t length = repair_symbol_bytes(block, *info_, oi);
    if (repair.symbol.size() != length)
        return reject(where, Error::MalformedPayload,
                      name + ": a symbol of " + std::to_string(repair.symbol.size()) + " bytes where batch " +
                          std::to_string(block.batch) + " makes " + std::to_string(length));
    if (!block.clip(oi.point_count))
        return reject(where, Error::IndexOutOfRange,
                      name + ": " + std::to_string(block.sources) + " batches of " + std::to_string(block.batch) +
                          " points from point " + std::to_string(block.first_index) + ", the last past the object's " +
                          std::to_string(oi.point_count) + " points");
    auto it = object.repair_blocks.find(block.first_index);
    if (it != object.repair_blocks.end()) {
        if (!it->second.block.same_block(block))
            return reject(where, Error::StreamMismatch, name + ": its block contradicts one received before");
    } else {
        // Blocks of an object do not overlap (spec 17.3).
        auto next = object.repair_blocks.lower_bound(block.first_index);
        if (next != object.repair_blocks.end() && next->first < uint64_t{block.first_index} + block.point_count)
            return reject(where, Error::StreamMismatch, name + ": its block overlaps another block");
        if (next != object.repair_blocks.begin()) {
            auto prev = std::prev(next);
            if (uint64_t{prev->first} + prev->second.block.point_count > block.first_index)
                return reject(where, Error::StreamMismatch, name + ": its block overlaps another block");
        }
        ReceivedRepairBlock fresh;
        fresh.block = block;
        fresh.held_in_batch.assign(block.source_count(), 0);
        // Records held count, placed or not (spec 23.6).
        for (uint32_t i = 0; i < block.source_count(); ++i) {
            const uint64_t from = uint64_t{block.first_index} + uint64_t{i} * block.batch, to = from + block.batch_points(i);
            fresh.held_in_batch[i] = uint32_t(object.points.count(from, to) + object.unplaced.count(from, to));
            if (fresh.held_in_batch[i] == block.batch_points(i)) ++fresh.batches_held;
        }
        fresh.complete = fresh.batches_held == block.source_count();
        it = object.repair_blocks.emplace(block.first_index, std::move(fresh)).first;
    }
    ReceivedRepairBlock& held = it->second;
    if (held.complete || std::find(held.rows_accepted.begin(), held.rows_accepted.end(), repair.row) != held.rows_accepted.end()) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    held.rows_accepted.push_back(repair.row);
    held.symbols.push_back(std::move(repair.symbol));
    ++counters_.accepted;
    try_recover(object, held);
    return Error::Ok;
}

ReceivedMapFragment::ReceivedMapFragment(uint32_t point_total, const std::vector<MapCell>& cells, unsigned map_level)
    : point_total_(point_total), wide_(3 * map_level > 32) {
    codes_.reserve(cells.size() * (wide_ ? 2 : 1));
    starts_.reserve(cells.size());
    uint32_t start = 0;
    for (const MapCell& c : cells) {
        codes_.push_back(uint32_t(c.code));
        if (wide_) codes_.push_back(uint32_t(c.code >> 32));
        starts_.push_back(start);
        start += c.count;
    }
}

size_t ReceivedMapFragment::cell_of(uint32_t rank) const {
    return size_t(std::upper_bound(starts_.begin(), starts_.end(), rank) - starts_.begin()) - 1;
}

std::vector<MapCell> ReceivedMapFragment::cells() const {
    std::vector<MapCell> out(size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = {code(i), count(i)};
    return out;
}

bool ReceivedMapFragment::same_cells(const std::vector<MapCell>& cells) const {
    if (cells.size() != size()) return false;
    for (size_t i = 0; i < cells.size(); ++i)
        if (cells[i].code != code(i) || cells[i].count != count(i)) return false;
    return true;
}

namespace {

// Places a mapped record (spec 23.2, 23.4): its offset becomes a position once a fragment holds its
// rank. False while none does.
bool place_point(const ReceivedObject& object, uint32_t index, unsigned position_bits, QuantizedPoint& q) {
    const ObjectInfo& oi = *object.info;
    const uint32_t rank = mapped_rank(index, oi.point_count, oi.map_batch);
    auto it = object.map_fragments.upper_bound(rank);
    if (it == object.map_fragments.begin()) return false;
    --it;
    const ReceivedMapFragment& f = it->second;
    if (rank - it->first >= f.point_total()) return false;
    const std::array<uint32_t, 3> corner = cell_corner(f.code(f.cell_of(rank - it->first)), position_bits, oi.map_level);
    for (int a = 0; a < 3; ++a) q.position[a] += corner[a];
    return true;
}

}  // namespace

uint64_t ReceivedObject::memory() const {
    return ellipsoids.memory() + points.memory() + unplaced.memory() + weights.memory() + morph.memory() +
           normal_entries.memory() + map_memory + texcoord_memory();
}

bool ReceivedStream::take_point_record(ReceivedObject& object, uint32_t index, const QuantizedPoint& record) {
    if (!object.info->mapped()) return object.points.insert(index, record);
    if (object.points.contains(index) || object.unplaced.contains(index)) return false;
    QuantizedPoint q = record;
    if (place_point(object, index, info_->position_bits, q))
        object.points.insert(index, q);
    else
        object.unplaced.insert(index, record);
    return true;
}

// Format 1.7 (spec 23.3): a fragment of an object's map.
Error ReceivedStream::take_point_map(ReceivedObject& object, const PacketView& packet, const std::string& name,
                                     uint64_t where) {
    const ObjectInfo& oi = *object.info;
    PointMapFragment f;
    std::string why;
    if (decode_point_map_payload(packet.payload, info_->position_bits, oi.map_level, f, &why) != Error::Ok)
        return reject(where, Error::MalformedPayload, name + ": " + why);
    const uint64_t end = uint64_t(f.first_rank) + f.point_total;
    if (end > oi.point_count)
        return reject(where, Error::IndexOutOfRange,
                      name + ": ranks " + std::to_string(f.first_rank) + "+" + std::to_string(f.point_total) + " of " +
                          std::to_string(oi.point_count));
    auto same = object.map_fragments.find(f.first_rank);
    if (same != object.map_fragments.end() && same->second.point_total() == f.point_total && same->second.same_cells(f.cells)) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    // The fragments kept lie in order of ranks and cells together, so its neighbours decide.
    auto next = object.map_fragments.lower_bound(f.first_rank);
    if (next != object.map_fragments.end() &&
        (next->first < end || next->second.code(0) <= f.cells.back().code))
        return reject(where, Error::StreamMismatch, name + ": its ranks or cells overlap or cross a fragment received before");
    if (next != object.map_fragments.begin()) {
        auto prev = std::prev(next);
        const ReceivedMapFragment& p = prev->second;
        if (uint64_t(prev->first) + p.point_total() > f.first_rank || p.code(p.size() - 1) >= f.cells.front().code)
            return reject(where, Error::StreamMismatch, name + ": its ranks or cells overlap or cross a fragment received before");
    }
    ReceivedMapFragment kept(f.point_total, f.cells, oi.map_level);
    object.map_memory += kept.memory() + kHeldPacketCost;
    object.map_fragments.emplace(f.first_rank, std::move(kept));
    object.map_ranks += f.point_total;
    ++counters_.accepted;
    // Place the records it covers: over whichever is smaller, the records waiting or its ranks.
    auto place = [&](uint32_t index) {
        std::optional<QuantizedPoint> q = object.unplaced.find(index);
        if (!q) return;
        if (place_point(object, index, info_->position_bits, *q)) {
            object.points.insert(index, *q);
            object.unplaced.erase(index);
        }
    };
    if (object.unplaced.size() <= f.point_total) {
        std::vector<uint32_t> waiting;
        for (const auto& [index, q] : object.unplaced) waiting.push_back(index);
        for (uint32_t index : waiting) place(index);
    } else {
        for (uint64_t rank = f.first_rank; rank < end; ++rank)
            place(mapped_index(uint32_t(rank), oi.point_count, oi.map_batch));
    }
    return Error::Ok;
}

void ReceivedStream::note_new_points(ReceivedObject& object, const std::vector<uint32_t>& indices) {
    std::vector<ReceivedRepairBlock*> touched;
    for (uint32_t index : indices) {
        auto it = object.repair_blocks.upper_bound(index);
        if (it == object.repair_blocks.begin()) continue;
        --it;
        ReceivedRepairBlock& b = it->second;
        if (index >= uint64_t{b.block.first_index} + b.block.point_count || b.complete) continue;
        const uint32_t i = (index - b.block.first_index) / b.block.batch;
        if (++b.held_in_batch[i] == b.block.batch_points(i) && ++b.batches_held == b.block.source_count()) {
            b.complete = true;
            b.symbols.clear();
        }
        if (!b.symbols.empty() && (touched.empty() || touched.back() != &b)) touched.push_back(&b);
    }
    for (ReceivedRepairBlock* b : touched) try_recover(object, *b);
}

void ReceivedStream::try_recover(ReceivedObject& object, ReceivedRepairBlock& held) {
    const RepairBlock& block = held.block;
    const uint32_t k = block.source_count();
    if (held.complete || held.symbols.size() < k - held.batches_held) return;
    const ObjectInfo& oi = *object.info;
    std::vector<std::vector<uint8_t>> sources(k);
    std::vector<QuantizedPoint> batch_points;
    for (uint32_t i = 0; i < k; ++i) {
        if (held.held_in_batch[i] != block.batch_points(i)) continue;
        batch_points.clear();
        const uint32_t first = block.first_index + i * block.batch;
        for (uint32_t index = first; index < first + block.batch_points(i); ++index) {
            std::optional<QuantizedPoint> p = object.points.find(index);
            batch_points.push_back(p ? *p : object.unplaced.find(index).value());
        }
        sources[i] = repair_source_symbol(block, batch_points, *info_, oi);
    }
    std::vector<uint32_t> unknown;
    for (uint32_t i = 0; i < k; ++i)
        if (sources[i].empty()) unknown.push_back(i);
    if (!recover_source_symbols(sources, held.rows_accepted, held.symbols)) return;
    const size_t bits = point_record_bits(*info_, oi);
    for (uint32_t i : unknown) {
        const uint32_t first = block.first_index + i * block.batch, count = block.batch_points(i);
        std::vector<uint8_t> payload(8, 0);
        payload[0] = uint8_t(first), payload[1] = uint8_t(first >> 8), payload[2] = uint8_t(first >> 16),
        payload[3] = uint8_t(first >> 24), payload[4] = uint8_t(count), payload[5] = uint8_t(count >> 8);
        payload.insert(payload.end(), sources[i].begin(), sources[i].begin() + std::ptrdiff_t((size_t{count} * bits + 7) / 8));
        PointBatch batch;
        if (decode_points_payload(payload, *info_, oi, batch) != Error::Ok) continue;  // cannot happen: lengths match
        for (size_t n = 0; n < batch.points.size(); ++n)
            if (take_point_record(object, first + static_cast<uint32_t>(n), batch.points[n])) {
                ++held.points_recovered;
                ++object.points_recovered;
            }
        held.held_in_batch[i] = count;
    }
    held.batches_held = k;
    held.complete = held.recovered = true;
    held.symbols.clear();
    held.symbols.shrink_to_fit();
}

void ReceivedStream::release_pending() {
    // One pass over the hold for all objects whose entry arrived (linear: 100k held packets once
    // took 8.4 s, erased one at a time and once per object).
    std::vector<Pending> held, keep;
    keep.reserve(pending_.size());
    for (Pending& p : pending_) {
        const bool ready = p.header.object_id < objects_.size() && objects_[p.header.object_id].info.has_value();
        (ready ? held : keep).push_back(std::move(p));
    }
    pending_ = std::move(keep);
    for (const Pending& p : held) {
        pending_bytes_ -= p.payload.size() + kHeldPacketCost;
        --counters_.pending;
        PacketView view;
        view.header = p.header;
        view.payload = p.payload;
        view.size = p.header.packet_size();
        take_object_packet(view, p.where);
    }
}

Error ReceivedStream::take_scene(const PacketView& packet, uint64_t where) {
    SceneBatch batch;
    if (decode_scene_payload(packet.payload, batch, packet.header.version_minor) != Error::Ok)
        return reject(where, Error::MalformedPayload, "SCENE payload inconsistent or out of range");
    if (has_scene() && (batch.node_count != scene_node_count_ || batch.mesh_count != scene_mesh_count_))
        return reject(where, Error::StreamMismatch, "SCENE table sizes contradict earlier SCENE packets");
    for (const auto& n : batch.nodes) {
        auto it = scene_nodes_.find(n.index);
        if (it != scene_nodes_.end() && !(it->second == n))
            return reject(where, Error::StreamMismatch, "node " + std::to_string(n.index) + " contradicts an earlier one");
    }
    for (const auto& m : batch.meshes) {
        auto it = scene_meshes_.find(m.index);
        if (it != scene_meshes_.end() && !(it->second == m))
            return reject(where, Error::StreamMismatch, "mesh " + std::to_string(m.index) + " contradicts an earlier one");
    }
    scene_node_count_ = batch.node_count;
    scene_mesh_count_ = batch.mesh_count;
    bool news = false;
    for (auto& n : batch.nodes) news |= scene_nodes_.emplace(n.index, std::move(n)).second;
    for (auto& m : batch.meshes) news |= scene_meshes_.emplace(m.index, std::move(m)).second;
    if (news) ++counters_.accepted;
    else ++counters_.duplicates;
    return Error::Ok;
}

Error ReceivedStream::take_material(const PacketView& packet, uint64_t where) {
    Material m;
    if (decode_material_payload(packet.payload, m) != Error::Ok)
        return reject(where, Error::MalformedPayload, "MATERIAL payload inconsistent or out of range");
    if (auto count = material_count(); count && *count != m.material_count)
        return reject(where, Error::StreamMismatch,
                      "MATERIAL table size contradicts earlier MATERIAL or MATERIAL_EXTENSIONS packets");
    auto it = materials_.find(m.index);
    if (it != materials_.end()) {
        if (!(it->second == m))
            return reject(where, Error::StreamMismatch, "material " + std::to_string(m.index) + " contradicts an earlier one");
        ++counters_.duplicates;
        return Error::Ok;
    }
    materials_.emplace(m.index, std::move(m));
    ++counters_.accepted;
    return Error::Ok;
}

std::optional<uint16_t> ReceivedStream::material_count() const {
    if (!materials_.empty()) return materials_.begin()->second.material_count;
    if (!material_extensions_.empty()) return material_extensions_.begin()->second.material_count;
    return std::nullopt;
}

// Format 1.3 (spec 18.2): a material's JSON patch. Checked in the order the spec gives: the payload,
// the table size, the patch held for the same material, then the memory cap it shares with textures.
Error ReceivedStream::take_material_extensions(const PacketView& packet, uint64_t where) {
    MaterialExtensions m;
    if (decode_material_extensions_payload(packet.payload, m) != Error::Ok)
        return reject(where, Error::MalformedPayload,
                      "MATERIAL_EXTENSIONS of " + std::to_string(packet.payload.size()) +
                          " bytes: its index, table size or JSON patch breaks spec 18.2");
    if (auto count = material_count(); count && *count != m.material_count)
        return reject(where, Error::StreamMismatch,
                      "MATERIAL_EXTENSIONS table size contradicts earlier MATERIAL or MATERIAL_EXTENSIONS packets");
    if (auto it = material_extensions_.find(m.index); it != material_extensions_.end()) {
        if (it->second.patch != m.patch)
            return reject(where, Error::StreamMismatch,
                          "the extensions of material " + std::to_string(m.index) + " contradict earlier ones");
        ++counters_.duplicates;
        return Error::Ok;
    }
    const uint64_t memory = m.patch.size() + kHeldPacketCost;
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      "the extensions of material " + std::to_string(m.index) +
                          " exceed this receiver's " + std::to_string(limits_.max_texture_bytes) +
                          "-byte texture memory limit");
    texture_bytes_ += memory;
    material_extensions_.emplace(m.index, std::move(m));
    ++counters_.accepted;
    return Error::Ok;
}

Error ReceivedStream::take_texture_fragment(const PacketView& packet, uint64_t where) {
    TextureFragment f;
    if (decode_texture_fragment_payload(packet.payload, f) != Error::Ok)
        return reject(where, Error::MalformedPayload, "TEXTURE_FRAGMENT payload inconsistent or out of range");
    if (!textures_.empty() && textures_.begin()->second.info.texture_count != f.info.texture_count)
        return reject(where, Error::StreamMismatch, "TEXTURE_FRAGMENT table size contradicts earlier fragments");
    auto it = textures_.find(f.info.index);
    if (it == textures_.end()) {
        ReceivedTexture t;
        t.info = f.info;
        it = textures_.emplace(f.info.index, std::move(t)).first;
    } else if (!(it->second.info == f.info)) {
        return reject(where, Error::StreamMismatch,
                      "texture " + std::to_string(f.info.index) + " fragment contradicts earlier fragments");
    }
    ReceivedTexture& t = it->second;
    if (t.complete) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    const uint32_t begin = f.offset, end = static_cast<uint32_t>(f.offset + f.data.size());
    const auto gaps = detail::missing_runs(t.pieces, begin, end);
    uint64_t fresh = 0;
    for (auto [a, b] : gaps) fresh += b - a;
    if (fresh == 0) {
        ++counters_.duplicates;
        return Error::Ok;
    }
    // Memory, not just bytes: each run kept costs its bytes plus its bookkeeping, so that 1-byte
    // fragments (about 110 bytes of memory per byte counted before) meet the same cap.
    const uint64_t memory = fresh + gaps.size() * kHeldPacketCost;
    if (texture_bytes_ + memory > limits_.max_texture_bytes)
        return reject(where, Error::MalformedPayload,
                      "texture " + std::to_string(f.info.index) + ": the stream's textures exceed this receiver's " +
                          std::to_string(limits_.max_texture_bytes) + "-byte texture memory limit");
    for (auto [a, b] : gaps)
        t.pieces.emplace(a, std::vector<uint8_t>(f.data.begin() + (a - begin), f.data.begin() + (b - begin)));
    t.received_bytes += fresh;
    t.memory += memory;
    texture_bytes_ += memory;
    if (t.received_bytes == t.info.image_size) {
        std::vector<uint8_t> image = detail::join_runs(t.pieces);
        texture_bytes_ -= t.memory;
        t.memory = 0;
        t.pieces.clear();
        t.received_bytes = 0;
        if (crc32c(image.data(), image.size()) != t.info.image_crc) {
            // Fragments that each passed their packet CRC but do not make the announced image: start over.
            return reject(where, Error::StreamMismatch,
                          "texture " + std::to_string(t.info.index) + " is complete but its image CRC does not match");
        }
        t.image = std::move(image);
        t.received_bytes = t.info.image_size;
        t.complete = true;
    }
    ++counters_.accepted;  // after the image check: a completing fragment that fails it is rejected only
    return Error::Ok;
}

std::vector<Ellipsoid> ReceivedStream::ellipsoids(size_t index) const {
    std::vector<Ellipsoid> out;
    if (index >= objects_.size() || !objects_[index].info) return out;
    out.reserve(objects_[index].ellipsoids.size());
    for (const auto& [i, q] : objects_[index].ellipsoids) out.push_back(dequantize_ellipsoid(*q, objects_[index].info->frame));
    return out;
}

std::vector<SurfacePoint> ReceivedStream::points(size_t index) const {
    std::vector<SurfacePoint> out;
    if (index >= objects_.size() || !objects_[index].info || !info_) return out;
    out.reserve(objects_[index].points.size());
    const ReceivedObject& object = objects_[index];
    for (const auto& [i, q] : object.points) {
        out.push_back(dequantize_point(q, *info_, *object.info));
        // Surface normals (spec 24.4): a sent normal; (0, 0, 0), for "left to the surface", otherwise.
        if (!object.info->surface_normals) continue;
        auto entry = object.normal_entries.find(i);
        if (entry && entry->sent)
            out.back().normal = decode_octahedral(entry->normal, info_->normal_bits);
    }
    return out;
}

}  // namespace ellicast

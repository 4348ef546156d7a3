// An Asset through a stream: encode_asset puts the objects and the scene into packets in
// transmission order; decode_asset rebuilds objects and scene from what arrived.
#include "ellicast/converters/asset_stream.h"

#include "morph_targets.h"
#include "skin_weights.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ellicast {

bool encode_asset(const Asset& asset, const EncodeOptions& options, uint32_t stream_id, bool with_scene,
                  EncodedAsset& out, std::string& error) {
    out = EncodedAsset{};
    if (asset.objects.size() > kMaxObjects) {
        error = std::to_string(asset.objects.size()) + " objects, more than a stream holds (" +
                std::to_string(kMaxObjects) + ")";
        return false;
    }
    try {
        std::vector<Mesh> objects = asset.objects;  // skinned and morphing objects keep every vertex a point
        for (size_t i = 0; i < objects.size(); ++i)
            objects[i].per_point_data = (i < asset.weights.size() && !asset.weights[i].empty()) ||
                                        (i < asset.morphs.size() && !asset.morphs[i].empty());
        out.encoded = encode_meshes(objects, options);
    } catch (const std::exception& e) {
        error = e.what();
        return false;
    }
    StreamPackets stream;
    if (Error e = packetize_stream(out.encoded.info, out.encoded.contents, stream_id, stream); e != Error::Ok) {
        error = std::string("could not cut the stream into packets: ") + error_name(e);
        return false;
    }
    ScenePackets scene;
    if (with_scene) {
        if (Error e = packetize_scene(asset.scene, out.encoded.info.packet_size, stream_id, 0, scene); e != Error::Ok) {
            error = std::string("could not cut the scene into packets (a table over 65534 entries, a record larger "
                                "than a packet, a reference outside its table, or an animation track it cannot carry): ") +
                    error_name(e);
            return false;
        }
        for (uint16_t m : scene.extensions_too_large)
            out.encoded.warnings.push_back("material " + std::to_string(m) + ": its extensions (" +
                                           std::to_string(asset.scene.materials[m].extensions.size()) +
                                           " bytes of JSON) do not fit a " + std::to_string(out.encoded.info.packet_size) +
                                           "-byte packet; the material is sent without them");
    }
    auto take = [&](std::vector<std::vector<uint8_t>>& packets, size_t& count, size_t& bytes) {
        for (auto& p : packets) {
            ++count;
            bytes += p.size();
            out.packets.push_back(std::move(p));
        }
    };
    take(stream.stream_info, out.stream_info_packets, out.stream_info_bytes);
    take(stream.ellipsoids, out.ellipsoid_packets, out.ellipsoid_bytes);
    take(stream.maps, out.map_packets, out.map_bytes);
    take(scene.scene, out.scene_packets, out.scene_bytes);
    take(scene.materials, out.scene_packets, out.scene_bytes);
    take(scene.textures, out.scene_packets, out.scene_bytes);
    take(scene.animations, out.scene_packets, out.scene_bytes);
    take(scene.skins, out.scene_packets, out.scene_bytes);
    take(scene.cameras_lights, out.scene_packets, out.scene_bytes);  // format 1.10, with the base
    take(scene.extras, out.scene_packets, out.scene_bytes);          // format 1.12, with the base
    take(scene.required_extensions, out.scene_packets, out.scene_bytes);  // format 1.13, with the base
    take(stream.points, out.point_packets, out.point_bytes);
    take(stream.normals, out.normal_packets, out.normal_bytes);
    take(stream.texcoords, out.texcoord_packets, out.texcoord_bytes);  // format 1.14
    // Format 1.5: the skin weights of every point of each weighted object (spec 21.2), after the points.
    std::vector<std::vector<uint8_t>> weights;
    for (size_t i = 0; i < out.encoded.contents.size() && with_scene; ++i) {
        if (i >= asset.weights.size() || asset.weights[i].empty()) continue;
        const ObjectInfo& object = out.encoded.info.objects[i];
        const std::vector<Influences> records = skin_weights::point_records(
            asset.objects[i], asset.weights[i], out.encoded.contents[i].points, out.encoded.info, object);
        if (records.empty()) continue;
        if (Error e = packetize_joint_weights(out.encoded.info, uint16_t(i), records, stream_id, 0, weights);
            e != Error::Ok) {
            error = std::string("could not cut the skin weights into packets: ") + error_name(e);
            return false;
        }
    }
    take(weights, out.weight_packets, out.weight_bytes);
    // Format 1.6: the morph target displacements of every point of each object with targets (spec 22.1).
    std::vector<std::vector<uint8_t>> morphs;
    for (size_t i = 0; i < out.encoded.contents.size() && with_scene; ++i) {
        if (i >= asset.morphs.size() || asset.morphs[i].empty()) continue;
        const ObjectInfo& object = out.encoded.info.objects[i];
        const VertexMorph& morph = asset.morphs[i];
        const std::vector<float> values = morph_targets::point_values(asset.objects[i], morph,
                                                                      out.encoded.contents[i].points, out.encoded.info, object);
        if (values.empty()) continue;
        if (Error e = packetize_morph_deltas(out.encoded.info, uint16_t(i), morph.targets, morph.attributes, values,
                                             stream_id, 0, morphs);
            e != Error::Ok) {
            error = std::string("could not cut the morph targets of object ") + std::to_string(i) +
                    " into packets (a point's displacements larger than a packet?): " + error_name(e);
            return false;
        }
    }
    take(morphs, out.morph_packets, out.morph_bytes);
    // Format 1.3: each object's exact layer (spec 19), after its points.
    std::vector<std::vector<uint8_t>> connectivity;
    for (size_t i = 0; i < out.encoded.contents.size(); ++i) {
        const ObjectContent& c = out.encoded.contents[i];
        if (c.connectivity.empty()) continue;
        if (Error e = packetize_connectivity(out.encoded.info, uint16_t(i), c.triangle_count, c.connectivity, stream_id,
                                             0, connectivity, uint32_t(c.carried.size()));
            e != Error::Ok) {
            error = std::string("could not cut the exact layer into packets: ") + error_name(e);
            return false;
        }
    }
    // Its repair symbols (spec 19.5): ceil(ratio * k) rows where the repair ratio is above 0 and k <= 127.
    if (options.repair_ratio > 0) {
        for (size_t i = 0; i < out.encoded.contents.size(); ++i) {
            const ObjectContent& c = out.encoded.contents[i];
            const size_t symbol = out.encoded.info.packet_size - kPacketOverhead -
                                  (c.carried.empty() ? kConnectivityHeaderSize : kExactMeshHeaderSize);
            const size_t k = (c.connectivity.size() + symbol - 1) / symbol;
            if (c.connectivity.empty() || k > 127) continue;
            const size_t count = size_t(std::ceil(options.repair_ratio * double(k) - 1e-9));
            if (Error e = packetize_connectivity_repairs(out.encoded.info, uint16_t(i), c.triangle_count, c.connectivity,
                                                         std::min(count, 255 - k), stream_id, 0, connectivity,
                                                         uint32_t(c.carried.size()));
                e != Error::Ok) {
                error = std::string("could not make the exact layer's repair packets: ") + error_name(e);
                return false;
            }
        }
    }
    take(connectivity, out.connectivity_packets, out.connectivity_bytes);
    if (options.repair_ratio > 0) {
        // Blocks of at most floor(255 / (1 + ratio)) POINTS packets, each with ceil(ratio * k) repair
        // symbols (spec 17.5).
        const StreamInfo& info = out.encoded.info;
        const size_t max_sources = std::max<size_t>(1, size_t(255.0 / (1.0 + options.repair_ratio)));
        std::vector<std::vector<uint8_t>> repairs;
        for (size_t i = 0; i < info.objects.size(); ++i) {
            const ObjectInfo& object = info.objects[i];
            const size_t batch = point_batch_size(info, object);
            if (object.point_count == 0 || batch == 0) continue;
            for (const RepairBlock& block : plan_repair_blocks(object.point_count, uint16_t(batch), max_sources)) {
                const size_t count = size_t(std::ceil(options.repair_ratio * block.source_count() - 1e-9));
                if (Error e = packetize_repairs(info, uint16_t(i), out.encoded.contents[i].points, {block}, count,
                                                stream_id, 0, repairs);
                    e != Error::Ok) {
                    error = std::string("could not make the repair packets: ") + error_name(e);
                    return false;
                }
            }
        }
        take(repairs, out.repair_packets, out.repair_bytes);
    }
    for (size_t i = 0; i < out.packets.size(); ++i) restamp_packet(out.packets[i], uint32_t(i));
    return true;
}

bool decode_asset(const ReceivedStream& stream, const DecodeOptions& options, Asset& out,
                  StreamDecodeReport& report, std::string& error) {
    std::vector<Mesh> meshes;
    std::vector<size_t> mesh_objects;
    if (!decode_stream(stream, options, meshes, report, error, &mesh_objects)) return false;
    std::vector<Mesh> objects(stream.objects().size());
    for (size_t i = 0; i < meshes.size(); ++i) objects[mesh_objects[i]] = std::move(meshes[i]);
    out = received_asset(stream, std::move(objects));
    return true;
}

}  // namespace ellicast

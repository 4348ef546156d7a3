// The conformance vectors of spec/vectors/: every .ellc decodes with the library to exactly the
// committed expected decode beside it (so any change of decoding behaviour breaks this test), every
// vector is described in spec/vectors/README.md, and `ellicast validate` accepts the valid and unusual
// sets and refuses every faulty vector.
#include "support.h"

#include "../spec/vectors/expected_decode.h"
#include "../samples/jpeg_images.h"

#include <ellicast/format.h>
#ifndef ELLICAST_FORMAT_TESTS_ONLY
#include <ellicast/converters/asset.h>
#endif

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <sys/wait.h>
#include <vector>

namespace fs = std::filesystem;
using namespace ellicast;

namespace {

fs::path vectors_dir() { return test::source_dir() / "spec" / "vectors"; }

std::vector<fs::path> vectors_in(const std::string& set) {
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(vectors_dir() / set))
        if (entry.path().extension() == ".ellc") out.push_back(entry.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<uint8_t> read_bytes(const fs::path& path) {
    std::vector<uint8_t> bytes;
    std::string message;
    REQUIRE_MESSAGE(read_file(path.string(), bytes, message) == Error::Ok, message);
    return bytes;
}

nlohmann::json read_json(const fs::path& path) {
    std::ifstream in(path);
    REQUIRE_MESSAGE(in.good(), "missing expected decode " << path.string());
    return nlohmann::json::parse(in);
}

void check_set(const std::string& set, size_t at_least) {
    const auto files = vectors_in(set);
    CHECK(files.size() >= at_least);
    for (const auto& file : files) {
        auto expected = read_json(fs::path(file).replace_extension(".json"));
        auto actual = conformance::expected_decode(read_bytes(file));
        expected.erase("vector");
        std::vector<std::string> diffs;
        conformance::compare_json(expected, actual, set + "/" + file.stem().string(), diffs);
        INFO(file.string());
        for (const auto& d : diffs) MESSAGE(d);
        CHECK(diffs.empty());
    }
}

// The library's receiver after every packet of a vector.
ReceivedStream receive(const std::vector<uint8_t>& bytes) {
    ReceivedStream stream;
    for (const ContainerPacket& p : read_container(bytes).packets) stream.add_parsed(p.view, p.offset);
    return stream;
}

int run(const std::string& command) {
    int status = std::system((command + " >/dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("every valid conformance vector decodes to its committed expected decode") { check_set("valid", 6); }

TEST_CASE("every unusual conformance vector decodes to its committed expected decode") { check_set("unusual", 24); }

TEST_CASE("every faulty conformance vector is rejected exactly as its committed expected decode says") {
    check_set("faulty", 32);
}

TEST_CASE("the faulty vectors name the reason they must be rejected with") {
    // Pin the named reason of the vectors whose defect is a single rejection or damaged region.
    const std::vector<std::pair<std::string, std::string>> reasons = {
        {"bad_magic", "bad magic"},
        {"bad_crc", "bad checksum"},
        {"truncated_packet", "truncated"},
        {"wrong_major", "unsupported major version"},
        {"type_zero", "invalid type"},
        {"oversized_length", "oversized"},
        {"garbage_between_packets", "bad magic"},
        {"unknown_critical_type", "unknown critical type"},
        {"payload_length_inconsistent", "malformed payload"},
        {"index_out_of_range", "index out of range"},
        {"count_zero_past_end", "index out of range"},
        {"stream_info_bad_bits", "malformed payload"},
        {"stream_info_object_id", "malformed payload"},
        {"mixed_stream_ids", "stream mismatch"},
        {"contradicting_stream_info", "stream mismatch"},
        {"unknown_object", "unknown object"},
        {"truncated_container", "too short"},
        {"bad_signature", "bad container signature"},
        {"container_version_2", "unsupported container version"},
        {"scene_fragment_past_end", "malformed payload"},
        {"scene_fragment_size_mismatch", "stream mismatch"},
        {"scene_fragment_crc_mismatch", "stream mismatch"},
        {"scene_image_crc_wrong", "stream mismatch"},
        {"scene_parent_out_of_range", "malformed payload"},
        {"scene_node_own_parent", "malformed payload"},
        {"scene_alpha_mode_3", "malformed payload"},
        {"scene_truncated", "malformed payload"},
        {"scene_contradicting_node", "stream mismatch"},
        {"stream_info_frame_end_infinite", "malformed payload"},
        {"stream_info_texcoord_end_infinite", "malformed payload"},
        {"signed_manifest_empty", "malformed payload"},
        {"signed_manifest_short", "malformed payload"},
        {"signed_manifest_count_mismatch", "malformed payload"},
        {"signed_manifest_part_count_zero", "malformed payload"},
        {"signed_manifest_part_past_count", "malformed payload"},
        {"signed_manifest_range_past_count", "malformed payload"},
        {"repair_payload_short", "malformed payload"},
        {"repair_batch_zero", "malformed payload"},
        {"repair_source_count_zero", "malformed payload"},
        {"repair_row_below_source_count", "malformed payload"},
        {"repair_row_255", "malformed payload"},
        {"repair_index_overflow", "malformed payload"},
        {"repair_symbol_length", "malformed payload"},
        {"repair_index_out_of_range", "index out of range"},
        {"repair_block_contradicts", "stream mismatch"},
        {"repair_block_overlap", "stream mismatch"},
        {"scene_extensions_short", "malformed payload"},
        {"scene_extensions_index_out_of_range", "malformed payload"},
        {"scene_extensions_not_utf8", "malformed payload"},
        {"scene_extensions_byte_order_mark", "malformed payload"},
        {"scene_extensions_second_value", "malformed payload"},
        {"scene_extensions_trailing_garbage", "malformed payload"},
        {"scene_extensions_trailing_comma", "malformed payload"},
        {"scene_extensions_nan", "malformed payload"},
        {"scene_extensions_comment", "malformed payload"},
        {"scene_extensions_top_level_array", "malformed payload"},
        {"scene_extensions_control_character", "malformed payload"},
        {"scene_extensions_lone_high_surrogate", "malformed payload"},
        {"scene_extensions_lone_low_surrogate", "malformed payload"},
        {"scene_extensions_number_infinite", "malformed payload"},
        {"scene_extensions_duplicate_name", "malformed payload"},
        {"scene_extensions_depth_33", "malformed payload"},
        {"scene_extensions_outside_shape", "malformed payload"},
        {"scene_extensions_extension_not_object", "malformed payload"},
        {"scene_extensions_index_leading_zero", "malformed payload"},
        {"scene_extensions_index_65535", "malformed payload"},
        {"scene_extensions_index_fraction", "malformed payload"},
        {"scene_extensions_index_exponent", "malformed payload"},
        {"scene_extensions_texcoord_1", "malformed payload"},
        {"scene_extensions_transform_texcoord_1", "malformed payload"},
        {"scene_extensions_count_contradicts", "stream mismatch"},
        {"scene_extensions_contradicting_patch", "stream mismatch"},
        {"scene_extensions_flag_contradicts", "stream mismatch"},
        {"exact_no_data", "malformed payload"},
        {"exact_piece_past_end", "malformed payload"},
        {"exact_triangle_count_zero", "malformed payload"},
        {"exact_too_many_triangles", "malformed payload"},
        {"exact_coded_size_too_large", "malformed payload"},
        {"exact_point_set", "malformed payload"},
        {"exact_unknown_object", "unknown object"},
        {"exact_triangle_count_contradicts", "stream mismatch"},
        {"exact_coded_size_contradicts", "stream mismatch"},
        {"exact_crc_contradicts", "stream mismatch"},
        {"exact_crc_wrong", "stream mismatch"},
        {"exact_flag_contradicts", "stream mismatch"},
        {"exact_repair_payload_short", "malformed payload"},
        {"exact_repair_symbol_size_zero", "malformed payload"},
        {"exact_repair_symbol_length", "malformed payload"},
        {"exact_repair_too_many_symbols", "malformed payload"},
        {"exact_repair_row_below_k", "malformed payload"},
        {"exact_repair_triangle_count_zero", "malformed payload"},
        {"exact_repair_too_many_triangles", "malformed payload"},
        {"exact_repair_coded_size_too_large", "malformed payload"},
        {"exact_repair_coded_size_zero", "malformed payload"},
        {"exact_repair_point_set", "malformed payload"},
        {"exact_repair_unknown_object", "unknown object"},
        {"exact_repair_triangle_count_contradicts", "stream mismatch"},
        {"exact_repair_coded_size_contradicts", "stream mismatch"},
        {"exact_repair_crc_contradicts", "stream mismatch"},
        {"exact_repair_symbol_size_contradicts", "stream mismatch"},
        {"exact_repair_crc_wrong", "stream mismatch"},
        {"animation_payload_short", "malformed payload"},
        {"animation_length_mismatch", "malformed payload"},
        {"animation_index_past_table", "malformed payload"},
        {"animation_track_past_count", "malformed payload"},
        {"animation_path_3", "malformed payload"},
        {"animation_interpolation_3", "malformed payload"},
        {"animation_key_count_zero", "malformed payload"},
        {"animation_cubicspline_one_key", "malformed payload"},
        {"animation_count_zero", "malformed payload"},
        {"animation_keys_past_count", "malformed payload"},
        {"animation_first_key_overflow", "malformed payload"},
        {"animation_time_infinite", "malformed payload"},
        {"animation_value_nan", "malformed payload"},
        {"animation_time_negative", "malformed payload"},
        {"animation_times_not_increasing", "malformed payload"},
        {"animation_count_contradicts", "stream mismatch"},
        {"animation_track_count_contradicts", "stream mismatch"},
        {"animation_name_contradicts", "stream mismatch"},
        {"animation_node_contradicts", "stream mismatch"},
        {"animation_path_contradicts", "stream mismatch"},
        {"animation_interpolation_contradicts", "stream mismatch"},
        {"animation_key_count_contradicts", "stream mismatch"},
        {"animation_time_contradicts", "stream mismatch"},
        {"animation_value_contradicts", "stream mismatch"},
        {"skin_count_contradicts", "stream mismatch"},
        {"skin_count_zero", "malformed payload"},
        {"skin_first_joint_overflow", "malformed payload"},
        {"skin_index_past_table", "malformed payload"},
        {"skin_joint_contradicts_partly_new", "stream mismatch"},
        {"skin_joint_count_contradicts", "stream mismatch"},
        {"skin_joint_count_zero", "malformed payload"},
        {"skin_joint_node_contradicts", "stream mismatch"},
        {"skin_joints_past_count", "malformed payload"},
        {"skin_length_mismatch", "malformed payload"},
        {"skin_matrix_contradicts", "stream mismatch"},
        {"skin_matrix_infinite", "malformed payload"},
        {"skin_matrix_nan", "malformed payload"},
        {"skin_name_contradicts", "stream mismatch"},
        {"skin_node_skin_contradicts", "stream mismatch"},
        {"skin_node_skin_dropped", "stream mismatch"},
        {"skin_payload_short", "malformed payload"},
        {"skin_skeleton_contradicts", "stream mismatch"},
        {"skin_table_empty", "malformed payload"},
        {"weights_contradicts_partly_new", "stream mismatch"},
        {"weights_count_zero", "malformed payload"},
        {"weights_held_out_of_range", "index out of range"},
        {"weights_index_out_of_range", "index out of range"},
        {"weights_index_overflow", "malformed payload"},
        {"weights_joint_contradicts", "stream mismatch"},
        {"weights_joint_size_3", "malformed payload"},
        {"weights_joint_twice", "malformed payload"},
        {"weights_malformed_before_stream_info", "malformed payload"},
        {"weights_n_5", "malformed payload"},
        {"weights_n_contradicts", "stream mismatch"},
        {"weights_n_zero", "malformed payload"},
        {"weights_order_contradicts", "stream mismatch"},
        {"weights_payload_short", "malformed payload"},
        {"weights_record_past_payload", "malformed payload"},
        {"weights_sum_254", "malformed payload"},
        {"weights_sum_wraps", "malformed payload"},
        {"weights_trailing_byte", "malformed payload"},
        {"weights_unknown_object", "unknown object"},
        {"weights_weight_contradicts", "stream mismatch"},
        {"weights_weight_zero", "malformed payload"},
        {"morph_animation_count_contradicts", "stream mismatch"},
        {"morph_animation_count_zero", "malformed payload"},
        {"morph_animation_cubicspline_one_key", "malformed payload"},
        {"morph_animation_first_key_overflow", "malformed payload"},
        {"morph_animation_index_past_table", "malformed payload"},
        {"morph_animation_interpolation_3", "malformed payload"},
        {"morph_animation_interpolation_contradicts", "stream mismatch"},
        {"morph_animation_joins_contradicts", "stream mismatch"},
        {"morph_animation_key_count_contradicts", "stream mismatch"},
        {"morph_animation_key_count_zero", "malformed payload"},
        {"morph_animation_keys_past_count", "malformed payload"},
        {"morph_animation_length_mismatch", "malformed payload"},
        {"morph_animation_name_contradicts", "stream mismatch"},
        {"morph_animation_node_contradicts", "stream mismatch"},
        {"morph_animation_payload_short", "malformed payload"},
        {"morph_animation_target_count_contradicts", "stream mismatch"},
        {"morph_animation_target_count_zero", "malformed payload"},
        {"morph_animation_time_infinite", "malformed payload"},
        {"morph_animation_time_negative", "malformed payload"},
        {"morph_animation_times_not_increasing", "malformed payload"},
        {"morph_animation_track_count_contradicts", "stream mismatch"},
        {"morph_animation_track_past_count", "malformed payload"},
        {"morph_animation_weight_contradicts", "stream mismatch"},
        {"morph_animation_weight_nan", "malformed payload"},
        {"morph_deltas_attributes_bit_6", "malformed payload"},
        {"morph_deltas_attributes_contradicts", "stream mismatch"},
        {"morph_deltas_attributes_zero", "malformed payload"},
        {"morph_deltas_contradicts_partly_new", "stream mismatch"},
        {"morph_deltas_count_zero", "malformed payload"},
        {"morph_deltas_held_out_of_range", "index out of range"},
        {"morph_deltas_index_out_of_range", "index out of range"},
        {"morph_deltas_index_overflow", "malformed payload"},
        {"morph_deltas_malformed_before_stream_info", "malformed payload"},
        {"morph_deltas_mask_bit_past_slots", "malformed payload"},
        {"morph_deltas_mask_bit_past_slots_second_byte", "malformed payload"},
        {"morph_deltas_payload_short", "malformed payload"},
        {"morph_deltas_record_cut", "malformed payload"},
        {"morph_deltas_record_missing", "malformed payload"},
        {"morph_deltas_record_past_payload", "malformed payload"},
        {"morph_deltas_scale_contradicts", "stream mismatch"},
        {"morph_deltas_scale_infinite", "malformed payload"},
        {"morph_deltas_scale_too_large", "malformed payload"},
        {"morph_deltas_scale_nan", "malformed payload"},
        {"morph_deltas_scale_negative", "malformed payload"},
        {"morph_deltas_scale_negative_zero", "malformed payload"},
        {"morph_deltas_scale_zero", "malformed payload"},
        {"morph_deltas_scales_short", "malformed payload"},
        {"morph_deltas_target_count_contradicts", "stream mismatch"},
        {"morph_deltas_target_count_zero", "malformed payload"},
        {"morph_deltas_trailing_bytes", "malformed payload"},
        {"morph_deltas_unknown_object", "unknown object"},
        {"morph_deltas_value_contradicts", "stream mismatch"},
        {"morph_mesh_target_count_contradicts", "stream mismatch"},
        {"morph_mesh_targets_dropped", "stream mismatch"},
        {"morph_mesh_targets_in_1_5_packet", "stream mismatch"},
        {"morph_mesh_weight_contradicts", "stream mismatch"},
        {"morph_mesh_weight_infinite", "malformed payload"},
        {"morph_mesh_weights_short", "malformed payload"},
        {"map_payload_short", "malformed payload"},
        {"map_point_total_zero", "malformed payload"},
        {"map_rice_16", "malformed payload"},
        {"map_root_count_zero", "malformed payload"},
        {"map_malformed_before_stream_info", "malformed payload"},
        {"map_unknown_object", "unknown object"},
        {"map_unmapped_object", "malformed payload"},
        {"map_root_level_past_level", "malformed payload"},
        {"map_roots_not_increasing", "malformed payload"},
        {"map_mask_zero", "malformed payload"},
        {"map_bits_end_early", "malformed payload"},
        {"map_counts_not_summing", "malformed payload"},
        {"map_trailing_byte", "malformed payload"},
        {"map_ranks_past_point_count", "index out of range"},
        {"map_held_out_of_range", "index out of range"},
        {"map_fragment_contradicts", "stream mismatch"},
        {"map_fragment_overlaps", "stream mismatch"},
        {"map_fragment_cells_misordered", "stream mismatch"},
        {"map_points_length_mismatch", "malformed payload"},
        {"map_points_index_overflow", "malformed payload"},
        {"map_points_index_out_of_range", "index out of range"},
        {"map_points_for_unmapped_object", "malformed payload"},
        {"map_points_for_mapped_object", "malformed payload"},
        {"map_entry_level_at_position_bits", "malformed payload"},
        {"map_entry_batch_zero", "malformed payload"},
        {"map_entry_batch_without_level", "malformed payload"},
        {"map_entry_level_contradicts", "stream mismatch"},
        {"map_entry_batch_contradicts", "stream mismatch"},
        {"map_entry_in_1_6_packet", "stream mismatch"},
        {"map_repair_symbol_length", "malformed payload"},
    };
    for (const auto& [name, reason] : reasons) {
        INFO(name);
        auto j = read_json(vectors_dir() / "faulty" / (name + ".json"));
        std::vector<std::string> found;
        if (!j["container_error"].is_null()) found.push_back(j["container_error"]);
        for (const auto& d : j["damaged"]) found.push_back(d["reason"]);
        for (const auto& r : j["rejections"]) found.push_back(r["reason"]);
        REQUIRE(found.size() >= 1);
        CHECK(std::all_of(found.begin(), found.end(), [&](const std::string& f) { return f == reason; }));
    }
}

TEST_CASE("an independent decoder written from the spec alone (spec/vectors/check_vectors.py) agrees with every vector") {
    if (std::system("python3 --version > /dev/null 2>&1") != 0) {
        MESSAGE("skipped: python3 is absent");
        return;
    }
    const std::string script = (vectors_dir() / "check_vectors.py").string();
    CHECK(run("python3 '" + script + "'") == 0);
}

TEST_CASE("a reordered and duplicated stream decodes to the same objects as the stream in order") {
    auto in_order = conformance::expected_decode(read_bytes(vectors_dir() / "valid" / "two_objects.ellc"));
    auto shuffled = conformance::expected_decode(read_bytes(vectors_dir() / "unusual" / "duplicated_reordered.ellc"));
    CHECK(in_order["objects"] == shuffled["objects"]);
    CHECK(in_order["stream_info"] == shuffled["stream_info"]);
    CHECK(shuffled["counters"]["duplicates"].get<int>() > 0);
}

TEST_CASE("valid/scene decodes to the car it was made from: hierarchy, instancing, materials, byte-exact PNG textures") {
    const ReceivedStream s = receive(read_bytes(vectors_dir() / "valid" / "scene.ellc"));
    REQUIRE(s.scene_node_count() == 5);
    REQUIRE(s.scene_nodes().size() == 5);
    REQUIRE(s.scene_meshes().size() == 2);
    const auto& nodes = s.scene_nodes();
    CHECK(nodes.at(0).parent == kNone);
    CHECK(nodes.at(0).name == "Car");
    CHECK(nodes.at(1).has_matrix);
    CHECK(nodes.at(1).matrix[13] == 0.5f);  // column-major: the translation is in the last column
    CHECK(nodes.at(2).parent == 1);
    CHECK(nodes.at(2).mesh == 1);  // one wheel mesh, instanced by two nodes
    CHECK(nodes.at(3).mesh == 1);
    CHECK(nodes.at(4).name == "Lampe \xC3\xBC");
    CHECK(s.scene_meshes().at(1).primitives == std::vector<ScenePrimitive>{{1, 1}});
    REQUIRE(s.materials().size() == 2);
    const Material& paint = s.materials().at(0);
    CHECK(paint.alpha_mode == AlphaMode::Mask);
    CHECK(paint.alpha_cutoff == 0.3f);
    CHECK(paint.double_sided);
    CHECK(paint.base_color_texture.texture == 0);
    CHECK(s.materials().at(1).normal_texture.scale == 0.5f);
    REQUIRE(s.textures().size() == 2);
    for (const auto& [index, t] : s.textures()) {
        INFO("texture " << index);
        REQUIRE(t.complete);
        CHECK(t.image.size() == t.info.image_size);
        CHECK(crc32c(t.image.data(), t.image.size()) == t.info.image_crc);
        const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
        CHECK(std::equal(png.begin(), png.end(), t.image.begin()));
    }
    // The SCENE packets split over the smallest packets, repeated and reordered: the same scene.
    const ReceivedStream split = receive(read_bytes(vectors_dir() / "unusual" / "scene_split_repeated.ellc"));
    CHECK(split.scene_nodes() == s.scene_nodes());
    CHECK(split.scene_meshes() == s.scene_meshes());
    CHECK(split.materials() == s.materials());
    CHECK(split.textures().at(0).image == s.textures().at(0).image);
}

TEST_CASE("valid/scene_jpeg carries two real JPEG files (baseline, progressive) byte for byte as image_type 2, "
          "in the scene of valid/scene") {
    const ReceivedStream png = receive(read_bytes(vectors_dir() / "valid" / "scene.ellc"));
    const ReceivedStream s = receive(read_bytes(vectors_dir() / "valid" / "scene_jpeg.ellc"));
    CHECK(s.scene_nodes() == png.scene_nodes());
    CHECK(s.scene_meshes() == png.scene_meshes());
    CHECK(s.materials() == png.materials());
    REQUIRE(s.textures().size() == 2);
    const std::vector<uint8_t>* files[] = {&samples::kJpegBaseline16, &samples::kJpegProgressive16};
    for (const auto& [index, t] : s.textures()) {
        INFO("texture " << index);
        REQUIRE(t.complete);
        CHECK(t.info.image_type == ImageType::Jpeg);
        CHECK(t.info.image_size == files[index]->size());
        CHECK(t.image == *files[index]);
        CHECK(t.info.mag_filter == png.textures().at(index).info.mag_filter);
        CHECK(t.info.wrap_s == png.textures().at(index).info.wrap_s);
    }
    const auto j = conformance::expected_decode(read_bytes(vectors_dir() / "valid" / "scene_jpeg.ellc"));
    CHECK(j["scene"]["textures"][0]["image_type"] == "JPEG");
    CHECK(j["scene"]["shown"]["materials"] == nlohmann::json::parse("[0, 1]"));
    CHECK(j["counters"]["duplicates"] == 2);
}

TEST_CASE("a texture with fragments missing is not complete and the material using it waits, as spec 15.4 says") {
    auto j = conformance::expected_decode(read_bytes(vectors_dir() / "faulty" / "scene_texture_incomplete.ellc"));
    const auto& scene = j["scene"];
    CHECK(scene["textures"][0]["complete"] == false);
    CHECK(scene["textures"][0]["missing"] == nlohmann::json::parse("[[148, 444]]"));
    CHECK(scene["shown"]["materials"] == nlohmann::json::parse("[1]"));
    CHECK(scene["shown"]["waiting"][0]["material"] == 0);
    CHECK(scene["shown"]["waiting"][0]["received_bytes"] == 216);
    CHECK(j["rejections"].empty());
    // An image whose bytes do not make the announced CRC is discarded: the completing fragment is
    // rejected and counted once.
    auto bad = conformance::expected_decode(read_bytes(vectors_dir() / "faulty" / "scene_image_crc_wrong.ellc"));
    CHECK(bad["scene"]["textures"][0]["complete"] == false);
    CHECK(bad["scene"]["textures"][0]["received_bytes"] == 0);
    CHECK(bad["counters"]["rejected"] == 1);
    CHECK(bad["counters"]["accepted"].get<int>() + bad["counters"]["rejected"].get<int>() ==
          static_cast<int>(bad["packets"].size()));
}

TEST_CASE("a format 1.0 decoder skips the 1.1 scene packets of every scene vector and decodes the same objects") {
    // (and the 1.3, 1.4, 1.5, 1.6, 1.10, 1.12 and 1.13 ones: MATERIAL_EXTENSIONS, ANIMATION, SKIN, JOINT_WEIGHTS,
    // MORPH_ANIMATION, MORPH_DELTAS, CAMERA, LIGHT, EXTRAS, REQUIRED_EXTENSION)
    size_t checked = 0;
    for (const std::string set : {"valid", "unusual", "faulty"})
        for (const auto& file : vectors_in(set)) {
            auto j = conformance::expected_decode(read_bytes(file));
            if (!j.contains("as_1_0")) continue;
            INFO(file.string());
            size_t scene_packets = 0;
            for (const auto& p : j["packets"])
                if (p["type"] == "SCENE" || p["type"] == "MATERIAL" || p["type"] == "TEXTURE_FRAGMENT" ||
                    p["type"] == "MATERIAL_EXTENSIONS" || p["type"] == "ANIMATION" || p["type"] == "SKIN" ||
                    p["type"] == "JOINT_WEIGHTS" || p["type"] == "MORPH_ANIMATION" || p["type"] == "MORPH_DELTAS" ||
                    p["type"] == "CAMERA" || p["type"] == "LIGHT" || p["type"] == "EXTRAS" ||
                    p["type"] == "REQUIRED_EXTENSION")
                    ++scene_packets;
            CHECK(j["as_1_0"]["same_objects"] == true);
            CHECK(j["as_1_0"]["counters"]["skipped"] == scene_packets);
            ++checked;
        }
    CHECK(checked >= 17);
}

TEST_CASE("the animation vectors: every animation of valid/animation comes back whole from the unusual ones, and a "
          "receiver shows what spec 20.2 says") {
    auto decode = [](const std::string& vector) {
        auto scene = conformance::expected_decode(read_bytes(vectors_dir() / (vector + ".ellc")))["scene"];
        // Without a MORPH_ANIMATION packet (format 1.6) no animation shows a morph track: `shown` lists each
        // animation's index and ANIMATION tracks only.
        for (auto& a : scene["shown"]["animations"]) {
            CHECK(a["morph_only"] == false);
            CHECK(a["morph_tracks"].empty());
            a.erase("morph_only");
            a.erase("morph_tracks");
        }
        return scene;
    };
    const auto valid = decode("valid/animation");
    REQUIRE(valid["animation_count"] == 2);
    REQUIRE(valid["animations"].size() == 2);
    for (const auto& a : valid["animations"]) {
        CHECK(a["complete"] == true);
        for (const auto& t : a["tracks"]) {
            CHECK(t["usable"] == true);
            CHECK(t["times"].size() == t["key_count"]);
        }
    }
    CHECK(valid["animations"][0]["tracks"][0]["values"].size() == 16 * 4);  // LINEAR rotation: V = 4
    CHECK(valid["animations"][1]["tracks"][0]["values"].size() == 5 * 9);   // CUBICSPLINE scale: V = 9
    CHECK(valid["shown"]["animations"] == nlohmann::json::parse(R"([{"index":0,"tracks":[0,1]},{"index":1,"tracks":[0]}])"));
    for (const char* same : {"unusual/animation_negative_zero", "unusual/animation_before_scene",
                             "unusual/animation_overlapping_keys", "unusual/animation_reserved"}) {
        INFO(same);
        const auto s = decode(same);
        CHECK(s["animations"] == valid["animations"]);
        CHECK(s["shown"]["animations"] == valid["shown"]["animations"]);
    }
    // What is left out, and why (spec 20.2).
    const std::vector<std::pair<std::string, std::string>> shown = {
        {"faulty/animation_incomplete", R"([{"index":1,"tracks":[0]}])"},
        {"faulty/animation_lost", R"([{"index":0,"tracks":[0,1]}])"},
        {"faulty/animation_track_unusable", R"([{"index":0,"tracks":[1]},{"index":1,"tracks":[0]}])"},
        {"faulty/animation_duplicate_target", R"([{"index":0,"tracks":[0,1,3]},{"index":1,"tracks":[0]}])"},
        {"faulty/animation_duplicate_target_freed", R"([{"index":0,"tracks":[1,2]},{"index":1,"tracks":[0]}])"},
        {"faulty/animation_node_past_table", R"([{"index":0,"tracks":[0,1]},{"index":1,"tracks":[0]}])"},
        {"faulty/animation_node_absent", R"([{"index":0,"tracks":[0,1]}])"},
        {"faulty/animation_no_scene", "[]"},
    };
    for (const auto& [vector, expected] : shown) {
        INFO(vector);
        CHECK(decode(vector)["shown"]["animations"] == nlohmann::json::parse(expected));
    }
    CHECK(decode("faulty/animation_incomplete")["animations"][0]["tracks"][0]["missing"] ==
          nlohmann::json::parse("[[7, 14]]"));
    CHECK(decode("faulty/animation_name_not_utf8")["animations"][1]["name"] == "Lamp \xEF\xBF\xBD pulse \xEF\xBF\xBD");
}

TEST_CASE("the morph vectors: the unusual ones decode to the targets and morph animations of valid/morph, and a "
          "receiver shows what spec 22.4 says") {
    auto decode = [](const std::string& vector) {
        return conformance::expected_decode(read_bytes(vectors_dir() / (vector + ".ellc")));
    };
    const auto valid = decode("valid/morph");
    const auto& scene = valid["scene"];
    REQUIRE(scene["morph_animation_count"] == 2);
    CHECK(scene["meshes"][0]["weights"] == nlohmann::json::parse("[0.25, 0.0]"));
    CHECK(scene["meshes"][1]["weights"].empty());
    CHECK(valid["objects"][0]["morph"]["target_count"] == 2);
    CHECK(valid["objects"][0]["morph"]["attributes"] == 3);
    CHECK(valid["objects"][0]["morph"]["records"].size() == 20);
    CHECK(valid["objects"][0]["morph"]["records"][0]["values"].size() == 2 * 2 * 3);
    CHECK(valid["objects"][0]["morph"]["records"][0]["q"].size() == 2 * 2 * 3);
    // Slot 3 (target 1's normal displacement) is 0 everywhere: the reference encoder's scale 1 (spec 22.1).
    CHECK(valid["objects"][0]["morph"]["scales"].size() == 4);
    CHECK(valid["objects"][0]["morph"]["scales"][3] == 1.0);
    CHECK(!valid["objects"][1].contains("morph"));
    CHECK(scene["morph_animations"][0]["joins"] == 0);
    CHECK(scene["morph_animations"][1]["joins"].is_null());
    for (const auto& a : scene["morph_animations"]) {
        CHECK(a["complete"] == true);
        for (const auto& t : a["tracks"]) CHECK(t["usable"] == true);
    }
    CHECK(scene["shown"]["morphed"] == nlohmann::json::parse("[0]"));
    const auto shown = nlohmann::json::parse(R"([{"index":0,"tracks":[0],"morph_only":false,"morph_tracks":[[0,0],[0,1]]},
                                                 {"index":1,"tracks":[],"morph_only":true,"morph_tracks":[[1,0]]}])");
    CHECK(scene["shown"]["animations"] == shown);
    CHECK(valid["as_1_0"]["same_objects"] == true);
    for (const char* same : {"unusual/morph_newer_minor", "unusual/morph_trailing_bytes_1_5",
                             "unusual/morph_before_stream_info", "unusual/morph_shuffled_duplicates",
                             "unusual/morph_negative_zero", "unusual/morph_reserved", "unusual/morph_overlapping_runs",
                             "unusual/morph_mesh_target_count_0", "unusual/morph_deltas_explicit_zero"}) {
        INFO(same);
        const auto j = decode(same);
        CHECK(j["rejections"].empty());
        CHECK(j["objects"] == valid["objects"]);
        CHECK(j["scene"]["meshes"] == scene["meshes"]);
        CHECK(j["scene"]["morph_animations"] == scene["morph_animations"]);
        CHECK(j["scene"]["shown"] == scene["shown"]);
    }
    // What is shown with its targets and which morph tracks are kept, and why (spec 22.4).
    const std::vector<std::tuple<std::string, std::string, std::string>> cases = {
        {"faulty/morph_deltas_incomplete", "[0]", R"([[0,[0],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
        {"faulty/morph_deltas_lost", "[]", R"([[0,[0],[]]])"},
        {"faulty/morph_points_lost", "[]", R"([[0,[0],[]]])"},
        {"faulty/morph_target_count_differs", "[]", R"([[0,[0],[]]])"},
        {"faulty/morph_animation_incomplete", "[0]", R"([[1,[],[[1,0]]]])"},
        {"faulty/morph_animation_lost", "[0]", "[]"},
        {"faulty/morph_joined_animation_lost", "[0]", R"([[1,[],[[1,0]]]])"},
        {"faulty/morph_joins_past_table", "[0]", R"([[0,[0],[]],[1,[],[[1,0]]]])"},
        {"faulty/morph_track_node_without_mesh", "[0]", R"([[0,[0],[[0,0],[0,1]]]])"},
        {"faulty/morph_track_target_count_differs", "[0]", R"([[0,[0],[[0,0],[0,1]]]])"},
        {"faulty/morph_track_unusable", "[0]", R"([[0,[0],[[0,1]]],[1,[],[[1,0]]]])"},
        {"faulty/morph_duplicate_node", "[0]", R"([[0,[0],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
        {"faulty/morph_duplicate_node_across_joined", "[0]", R"([[0,[0],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
        {"unusual/morph_two_join_one", "[0]", R"([[0,[0],[[0,0],[2,0]]],[1,[],[[1,0]]]])"},
        {"unusual/morph_weights_only", "[0]", R"([[0,[],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
        {"unusual/morph_deltas_8_slots", "[0]", R"([[0,[0],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
        {"unusual/morph_deltas_10_slots", "[0]", R"([[0,[0],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
        {"unusual/morph_deltas_i16_extremes", "[0]", R"([[0,[0],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
        {"unusual/morph_deltas_scale_subnormal", "[0]", R"([[0,[0],[[0,0],[0,1]]],[1,[],[[1,0]]]])"},
    };
    for (const auto& [vector, morphed, animations] : cases) {
        INFO(vector);
        const auto j = decode(vector);
        CHECK(j["scene"]["shown"]["morphed"] == nlohmann::json::parse(morphed));
        nlohmann::json brief = nlohmann::json::array();
        for (const auto& a : j["scene"]["shown"]["animations"])
            brief.push_back({a["index"], a["tracks"], a["morph_tracks"]});
        CHECK(brief == nlohmann::json::parse(animations));
    }
    // The records' integers (spec 22.1): i16 extremes, a subnormal scale, and the dequantized values as one
    // f32 multiplication each, in every vector whose object 0 holds records.
    CHECK(decode("unusual/morph_deltas_i16_extremes")["objects"][0]["morph"]["records"][0]["q"] ==
          nlohmann::json::parse("[0, 3706, 0, -11019, 0, 0, -32768, 32767, -1, 0, 0, 0]"));
    const auto subnormal = decode("unusual/morph_deltas_scale_subnormal")["objects"][0]["morph"];
    CHECK(subnormal["records"][19]["q"][9] == 1);
    CHECK(subnormal["records"][19]["q"][10] == -2);
    CHECK(subnormal["records"][19]["q"][11] == 32767);
    CHECK(decode("unusual/morph_deltas_8_slots")["objects"][0]["morph"]["scales"].size() == 8);
    CHECK(decode("unusual/morph_deltas_10_slots")["objects"][0]["morph"]["scales"].size() == 10);
    for (const std::string set : {"valid", "unusual", "faulty"})
        for (const auto& file : vectors_in(set)) {
            if (file.stem().string().rfind("morph", 0) != 0) continue;
            const auto j = conformance::expected_decode(read_bytes(file));
            for (const auto& o : j["objects"]) {
                if (!o.contains("morph")) continue;
                INFO(file.string());
                const auto& scales = o["morph"]["scales"];
                for (const auto& r : o["morph"]["records"]) {
                    REQUIRE(r["q"].size() == 3 * scales.size());
                    for (size_t i = 0; i < r["q"].size(); ++i) {
                        const float product = float(r["q"][i].get<int>()) * scales[i / 3].get<float>();
                        CHECK(product == r["values"][i].get<float>());
                    }
                }
            }
        }
}

TEST_CASE("the mapped-point vectors: the unusual ones decode to the objects of valid/map, every placed point lies in "
          "the cell its rank falls in, and what is not placed is listed (spec 23)") {
    auto decode = [](const std::string& vector) {
        return conformance::expected_decode(read_bytes(vectors_dir() / (vector + ".ellc")));
    };
    const auto valid = decode("valid/map");
    const auto& o0 = valid["objects"][0];
    REQUIRE(o0["info"]["map_level"] == 5);
    REQUIRE(o0["info"]["map_batch"] == 28);
    CHECK(!valid["objects"][1]["info"].contains("map_level"));  // listed for a mapped object only
    CHECK(!valid["objects"][1].contains("map"));
    CHECK(o0["points_received"] == 240);
    CHECK(o0["map"]["complete"] == true);
    CHECK(o0["map"]["ranks"] == 240);
    CHECK(o0["map"]["unplaced"].empty());
    CHECK(o0["map"]["fragments"].size() >= 3);
    CHECK(valid["rejections"].empty());
    for (const char* same : {"unusual/map_points_before_map", "unusual/map_before_stream_info",
                             "unusual/map_fragments_reencoded", "unusual/map_odd_batches", "valid/map_repair",
                             "unusual/map_repair_before_map"}) {
        INFO(same);
        const auto j = decode(same);
        CHECK(j["rejections"].empty());
        auto objects = j["objects"];
        CHECK(objects[0]["map"] == o0["map"]);
        CHECK(objects[0]["points"] == o0["points"]);
        CHECK(objects[0]["point_digest"] == o0["point_digest"]);
        CHECK(objects[1] == valid["objects"][1]);
    }
    CHECK(decode("unusual/map_fragments_reencoded")["counters"]["duplicates"] == o0["map"]["fragments"].size());
    CHECK(decode("unusual/map_repair_before_map")["objects"][0]["points_recovered"] == 28);
    // A STREAM_INFO that says 1.6 has no map fields, whatever its 48-byte entries hold (spec 23.1).
    const auto old = decode("unusual/map_entry_1_6");
    CHECK(old["rejections"].empty());
    for (const auto& o : old["objects"]) {
        CHECK(!o["info"].contains("map_level"));
        CHECK(!o.contains("map"));
        CHECK(o["points_received"] == o["info"]["point_count"]);
    }
    // A fragment lost: the points of its ranks stay unplaced, and only they (spec 23.4, 23.6).
    const auto missing = decode("faulty/map_fragment_missing")["objects"][0];
    CHECK(missing["map"]["complete"] == false);
    CHECK(missing["map"]["unplaced"].size() + missing["points_received"].get<size_t>() == 240);
    CHECK(missing["map"]["ranks"].get<uint64_t>() == 240 - missing["map"]["unplaced"].size());
    CHECK(decode("faulty/map_fragment_missing")["rejections"].empty());
    const auto repaired = decode("faulty/map_repair_fragment_missing")["objects"][0];
    CHECK(repaired["points_recovered"] == 28);
    CHECK(repaired["map"]["unplaced"] == missing["map"]["unplaced"]);
    // In every vector with a mapped object: each placed point lies in the cell of level map_level that holds its
    // rank (spec 23.2), its offset is what its record carried, and each unplaced record's rank is in no fragment.
    size_t checked = 0;
    for (const std::string set : {"valid", "unusual", "faulty"})
        for (const auto& file : vectors_in(set)) {
            const auto j = conformance::expected_decode(read_bytes(file));
            for (const auto& o : j["objects"]) {
                if (!o.contains("map")) continue;
                INFO(file.string());
                const unsigned P = j["stream_info"]["position_bits"].get<unsigned>();
                const unsigned L = o["info"]["map_level"].get<unsigned>();
                const uint32_t n = o["info"]["point_count"].get<uint32_t>(), batch = o["info"]["map_batch"].get<uint32_t>();
                auto cell_of_rank = [&](uint32_t rank, uint64_t& code) {
                    for (const auto& f : o["map"]["fragments"]) {
                        uint64_t at = f["first_rank"].get<uint64_t>();
                        if (rank < at || rank >= at + f["point_total"].get<uint64_t>()) continue;
                        for (const auto& c : f["cells"]) {
                            at += c[1].get<uint64_t>();
                            if (rank < at) {
                                code = c[0].get<uint64_t>();
                                return true;
                            }
                        }
                    }
                    return false;
                };
                for (const auto& p : o["points"]) {
                    uint64_t code = 0;
                    REQUIRE(cell_of_rank(mapped_rank(p["index"].get<uint32_t>(), n, batch), code));
                    const std::array<uint32_t, 3> q = {p["q"][0].get<uint32_t>(), p["q"][1].get<uint32_t>(),
                                                       p["q"][2].get<uint32_t>()};
                    CHECK(morton_cell(q, P, L) == code);
                    CHECK(cell_corner(code, P, L)[0] == (q[0] >> (P - L)) << (P - L));
                }
                for (const auto& u : o["map"]["unplaced"]) {
                    uint64_t code = 0;
                    CHECK(!cell_of_rank(mapped_rank(u["index"].get<uint32_t>(), n, batch), code));
                    for (int a = 0; a < 3; ++a) CHECK(u["q"][a].get<uint32_t>() < (1u << (P - L)));
                }
                ++checked;
            }
        }
    CHECK(checked >= 35);
}

TEST_CASE("the surface-normals vectors: the unusual ones decode to the objects of valid/normals, sent normals are "
          "what ReceivedStream::points gives, surface normals are unit vectors, and only the non-conforming vectors "
          "leave a point of the exact layer to an undefined surface normal (spec 24)") {
    auto decode = [](const std::string& vector) {
        return conformance::expected_decode(read_bytes(vectors_dir() / (vector + ".ellc")));
    };
    const auto valid = decode("valid/normals");
    CHECK(valid["rejections"].empty());
    CHECK(valid["newest_minor"] == 8);
    for (int k : {0, 1}) {
        INFO("object " << k);
        const auto& o = valid["objects"][k];
        CHECK(o["surface_normals"] == true);
        CHECK((o["info"]["attributes"].get<int>() & kAttrNormal) == 0);  // no normal in the records (spec 24.1)
        CHECK(o["normals"]["complete"] == true);
        CHECK(o["normals"]["entries"].size() == o["info"]["point_count"].get<size_t>());
        REQUIRE(o["normals"]["surface"].is_array());  // exact
        CHECK(o["normals"]["surface"].size() == o["info"]["point_count"].get<size_t>());
        size_t sent = 0;
        for (const auto& e : o["normals"]["entries"]) sent += e["sent"].get<bool>();
        CHECK(sent > 0);
        CHECK(sent < o["normals"]["entries"].size());
        for (const auto& p : o["points"]) CHECK(!p.contains("normal"));
    }
    CHECK(valid["objects"][0]["info"]["map_level"] == 5);
    CHECK(!valid["objects"][2].contains("normals"));
    CHECK(!valid["objects"][2].contains("surface_normals"));
    for (const std::string same : {"unusual/normals_before_stream_info", "unusual/normals_runs_reordered",
                                   "unusual/normals_padding_nonzero", "valid/normals_repair"}) {
        INFO(same);
        const auto j = decode(same);
        CHECK(j["rejections"].empty());
        for (int k : {0, 1}) {
            CHECK(j["objects"][k].at("normals") == valid["objects"][k].at("normals"));
            CHECK(j["objects"][k].at("points") == valid["objects"][k].at("points"));
            CHECK(j["objects"][k].at("connectivity") == valid["objects"][k].at("connectivity"));
        }
        CHECK(j["objects"][2] == valid["objects"][2]);
    }
    CHECK(decode("valid/normals_repair")["objects"][1]["points_recovered"] == 20);
    CHECK(decode("unusual/normals_runs_reordered")["counters"]["duplicates"] == 3);
    // The same entries at 16 bits: the same points are sent.
    const auto wide = decode("unusual/normals_16_bit");
    for (int k : {0, 1})
        for (size_t i = 0; i < wide["objects"][k]["normals"]["entries"].size(); ++i)
            CHECK(wide["objects"][k]["normals"]["entries"][i]["sent"] == valid["objects"][k]["normals"]["entries"][i]["sent"]);
    // A STREAM_INFO that says 1.7: bit 9 is not read (spec 24.1, 9).
    for (const std::string old : {"unusual/normals_flag_in_1_7_stream", "faulty/normals_flag_in_1_7_packet"}) {
        INFO(old);
        const auto j = decode(old);
        for (const auto& o : j["objects"]) {
            CHECK(!o.contains("surface_normals"));
            CHECK(!o.contains("normals"));
            CHECK(o["points_received"] == o["info"]["point_count"]);
        }
        CHECK(j["objects"][0].at("connectivity").contains("triangles"));
    }
    CHECK(decode("faulty/normals_flag_in_1_7_packet")["rejections"].size() == 3);
    // Incomplete entries; an object not exact lists no surface normal (spec 24.4, 19.4).
    const auto incomplete = decode("faulty/normals_incomplete")["objects"][0]["normals"];
    CHECK(incomplete["complete"] == false);
    CHECK(incomplete["entries"].size() < 258);
    CHECK(incomplete["surface"] == valid["objects"][0]["normals"]["surface"]);
    const auto not_exact = decode("faulty/normals_connectivity_lost")["objects"][1]["normals"];
    CHECK(not_exact["complete"] == true);
    CHECK(not_exact["surface"].is_null());
    // In every vector with surface normals: a sent entry's normal is its integers decoded (spec 8.3) and what
    // ReceivedStream::points gives (a point left to the surface, or without an entry, gets (0, 0, 0)); a listed
    // surface normal is a unit vector; and a point that a triangle of the exact layer uses is left to an undefined
    // surface normal only in faulty/normals_surface_undefined (spec 24.4).
    size_t checked = 0, undefined_left = 0;
    for (const std::string set : {"valid", "unusual", "faulty"})
        for (const auto& file : vectors_in(set)) {
            const auto bytes = read_bytes(file);
            const auto j = conformance::expected_decode(bytes);
            const ReceivedStream stream = receive(bytes);
            for (size_t k = 0; k < j["objects"].size(); ++k) {
                const auto& o = j["objects"][k];
                if (!o.contains("normals")) continue;
                INFO(file.string() << " object " << k);
                const unsigned bits = j["stream_info"]["normal_bits"].get<unsigned>();
                std::map<uint32_t, nlohmann::json> entries;
                for (const auto& e : o["normals"]["entries"]) {
                    entries[e["index"].get<uint32_t>()] = e;
                    if (!e["sent"].get<bool>()) continue;
                    const auto n = decode_octahedral({e["q"][0].get<uint32_t>(), e["q"][1].get<uint32_t>()}, int(bits));
                    for (int a = 0; a < 3; ++a) CHECK(e["normal"][a].get<float>() == n[a]);
                }
                const std::vector<SurfacePoint> shown = stream.points(k);
                REQUIRE(shown.size() == o["points"].size());
                for (size_t i = 0; i < shown.size(); ++i) {
                    const uint32_t index = o["points"][i]["index"].get<uint32_t>();
                    auto e = entries.find(index);
                    for (int a = 0; a < 3; ++a)
                        CHECK(shown[i].normal[a] == (e != entries.end() && e->second["sent"].get<bool>()
                                                         ? e->second["normal"][a].get<float>()
                                                         : 0.0f));
                }
                if (o["normals"]["surface"].is_null()) continue;
                std::set<uint32_t> used;
                for (const auto& t : o.at("connectivity").at("triangles"))
                    for (const auto& v : t) used.insert(v.get<uint32_t>());
                for (const auto& sn : o["normals"]["surface"]) {
                    const uint32_t index = sn["index"].get<uint32_t>();
                    if (sn["normal"].is_null()) {
                        auto e = entries.find(index);
                        if (used.count(index) && e != entries.end() && !e->second["sent"].get<bool>()) {
                            CHECK(file.stem().string() == "normals_surface_undefined");
                            ++undefined_left;
                        }
                        continue;
                    }
                    double length = 0;
                    for (const auto& c : sn["normal"]) length += c.get<double>() * c.get<double>();
                    CHECK(std::fabs(std::sqrt(length) - 1) < 1e-5);
                }
                ++checked;
            }
        }
    CHECK(checked >= 60);
    CHECK(undefined_left == 1);
}

#ifndef ELLICAST_FORMAT_TESTS_ONLY
TEST_CASE("the receiver's asset (received_asset) shows exactly the nodes, materials and textures the vectors expect") {
    for (const std::string set : {"valid", "unusual", "faulty"})
        for (const auto& file : vectors_in(set)) {
            const auto bytes = read_bytes(file);
            auto j = conformance::expected_decode(bytes);
            if (j["scene"].is_null() || j["scene"]["node_count"].is_null()) continue;
            INFO(file.string());
            const ReceivedStream s = receive(bytes);
            // No geometry handed over: every object counts as not arrived, so no extra root nodes.
            Asset asset = received_asset(s, std::vector<Mesh>(s.objects().size()));
            const auto& shown = j["scene"]["shown"];
            CHECK(asset.scene.nodes.size() == shown["nodes"].size());
            CHECK(asset.scene.materials.size() == shown["materials"].size());
            CHECK(asset.scene.textures.size() == shown["textures"].size());
        }
}
#endif

TEST_CASE("every conformance vector is listed in spec/vectors/README.md") {
    std::ifstream in(vectors_dir() / "README.md");
    REQUIRE(in.good());
    std::stringstream text;
    text << in.rdbuf();
    for (const std::string set : {"valid", "unusual", "faulty"})
        for (const auto& file : vectors_in(set)) {
            std::string name = "`";
            name += file.stem().string();
            name += '`';
            INFO(set << "/" << file.filename().string());
            CHECK(text.str().find(name) != std::string::npos);
        }
}

#ifndef ELLICAST_FORMAT_TESTS_ONLY  // the format-only test executable has no ellicast binary
TEST_CASE("ellicast validate accepts every valid and unusual vector and refuses every faulty one") {
    const std::string exe = test::ellicast_exe().string();
    // The signed vectors are judged with the key they are meant to be checked with (README).
    const std::string key = auth::to_hex(conformance::vectors_key().public_key);
    auto validate = [&](const std::filesystem::path& file) {
        const bool is_signed = file.stem().string().rfind("signed", 0) == 0;
        return run("'" + exe + "' validate '" + file.string() + "'" + (is_signed ? " --key " + key : ""));
    };
    for (const std::string set : {"valid", "unusual"})
        for (const auto& file : vectors_in(set)) {
            INFO(file.string());
            CHECK(validate(file) == 0);
        }
    for (const auto& file : vectors_in("faulty")) {
        INFO(file.string());
        CHECK(validate(file) == 1);
    }
}
#endif

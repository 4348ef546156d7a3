// ellicast::Mesh <-> Draco, at glTF-Transform's default Draco settings.
#include "ellicast/converters/draco_mesh.h"

#include "skin_weights.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace ellicast {

namespace {

// Adds a per-vertex float attribute with one value per point (identity mapping).
template <size_t N>
int add_attribute(draco::Mesh& dm, draco::GeometryAttribute::Type type, const std::vector<std::array<float, N>>& values) {
    draco::GeometryAttribute ga;
    ga.Init(type, nullptr, static_cast<uint8_t>(N), draco::DT_FLOAT32, false, sizeof(float) * N, 0);
    int id = dm.AddAttribute(ga, true, static_cast<uint32_t>(values.size()));
    draco::PointAttribute* pa = dm.attribute(id);
    for (size_t i = 0; i < values.size(); ++i) pa->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), values[i].data());
    return int(pa->unique_id());
}

// Reads attribute `type` (the `index`-th of that type) of a decoded mesh, per point, as N floats
// (false when absent).
template <size_t N>
bool read_attribute(const draco::Mesh& dm, draco::GeometryAttribute::Type type, std::vector<std::array<float, N>>& out,
                    int index = 0) {
    if (index >= dm.NumNamedAttributes(type)) return false;
    const draco::PointAttribute* pa = dm.GetNamedAttribute(type, index);
    if (pa == nullptr) return false;
    out.assign(dm.num_points(), {});
    std::array<float, 4> tmp{};
    for (uint32_t p = 0; p < dm.num_points(); ++p) {
        tmp = {0, 0, 0, 1};
        // ConvertValue normalizes integer colours to [0,1] when the attribute is normalized.
        if (!pa->ConvertValue<float>(pa->mapped_index(draco::PointIndex(p)), static_cast<int8_t>(N), tmp.data()))
            return false;
        for (size_t c = 0; c < N; ++c) out[p][c] = tmp[c];
    }
    return true;
}

// Adds a per-vertex integer attribute of 4 components (skin joints), 8- or 16-bit.
int add_joints(draco::Mesh& dm, const std::vector<std::array<uint16_t, 4>>& joints, bool eight_bit) {
    draco::GeometryAttribute ga;
    const draco::DataType type = eight_bit ? draco::DT_UINT8 : draco::DT_UINT16;
    const size_t size = eight_bit ? 1 : 2;
    ga.Init(draco::GeometryAttribute::GENERIC, nullptr, 4, type, false, int64_t(4 * size), 0);
    int id = dm.AddAttribute(ga, true, static_cast<uint32_t>(joints.size()));
    draco::PointAttribute* pa = dm.attribute(id);
    for (size_t i = 0; i < joints.size(); ++i) {
        if (eight_bit) {
            const std::array<uint8_t, 4> v = {uint8_t(joints[i][0]), uint8_t(joints[i][1]), uint8_t(joints[i][2]),
                                              uint8_t(joints[i][3])};
            pa->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), v.data());
        } else {
            pa->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), joints[i].data());
        }
    }
    return int(pa->unique_id());
}

}  // namespace

std::pair<std::array<float, 3>, float> position_cube(const Mesh& mesh) {
    std::array<float, 3> lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::max()};
    std::array<float, 3> hi{-lo[0], -lo[1], -lo[2]};
    for (const auto& p : mesh.positions)
        for (int c = 0; c < 3; ++c) {
            lo[c] = std::min(lo[c], p[c]);
            hi[c] = std::max(hi[c], p[c]);
        }
    if (mesh.positions.empty()) return {{0, 0, 0}, 1.f};
    float range = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    if (!(range > 0)) range = 1;
    return {lo, range};
}

std::vector<uint8_t> draco_encode(const Mesh& mesh, const DracoSettings& settings, DracoAttributeIds* ids,
                                  const DracoSkin& skin) {
    if (mesh.triangles.empty() || mesh.positions.empty())
        throw DracoError("Draco: mesh '" + mesh.name + "' has no triangles to compress");
    draco::Mesh dm;
    dm.set_num_points(static_cast<uint32_t>(mesh.positions.size()));
    DracoAttributeIds found;
    found.position = add_attribute(dm, draco::GeometryAttribute::POSITION, mesh.positions);
    if (mesh.has_normals()) found.normal = add_attribute(dm, draco::GeometryAttribute::NORMAL, mesh.normals);
    if (mesh.has_texcoords()) {
        found.texcoord = add_attribute(dm, draco::GeometryAttribute::TEX_COORD, mesh.texcoords);
        for (const auto& set : mesh.texcoord_sets)  // TEXCOORD_1, ...: further TEX_COORD attributes, in order
            found.texcoord_sets.push_back(add_attribute(dm, draco::GeometryAttribute::TEX_COORD, set));
    }
    if (mesh.has_colors()) {
        if (mesh.colors_have_alpha) {
            found.color = add_attribute(dm, draco::GeometryAttribute::COLOR, mesh.colors);
        } else {
            std::vector<std::array<float, 3>> rgb(mesh.colors.size());
            for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = {mesh.colors[i][0], mesh.colors[i][1], mesh.colors[i][2]};
            found.color = add_attribute(dm, draco::GeometryAttribute::COLOR, rgb);
        }
    }
    if (skin.joints && skin.weights) {
        if (skin.joints->size() != mesh.positions.size() || skin.weights->size() != mesh.positions.size())
            throw DracoError("Draco: mesh '" + mesh.name + "' has skin weights for another vertex count");
        uint16_t top = 0;
        for (const auto& j : *skin.joints)
            for (uint16_t x : j) top = std::max(top, x);
        found.joints_8bit = top < 256;
        found.joints = add_joints(dm, *skin.joints, found.joints_8bit);
        // Weights that are multiples of 1/255 (a stream's, spec 21.2) as normalized bytes, exactly;
        // others as floats, which Draco keeps as they are (no quantization is set for GENERIC).
        found.weights_8bit = skin_weights::in_255ths(*skin.weights);
        if (found.weights_8bit) {
            const std::vector<std::array<uint8_t, 4>> bytes = skin_weights::as_bytes(*skin.weights);
            draco::GeometryAttribute ga;
            ga.Init(draco::GeometryAttribute::GENERIC, nullptr, 4, draco::DT_UINT8, true, 4, 0);
            const int id = dm.AddAttribute(ga, true, static_cast<uint32_t>(bytes.size()));
            draco::PointAttribute* pa = dm.attribute(id);
            for (size_t i = 0; i < bytes.size(); ++i) pa->SetAttributeValue(draco::AttributeValueIndex(uint32_t(i)), bytes[i].data());
            found.weights = int(pa->unique_id());
        } else {
            found.weights = add_attribute(dm, draco::GeometryAttribute::GENERIC, *skin.weights);
        }
    }
    dm.SetNumFaces(mesh.triangles.size());
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
        const auto& t = mesh.triangles[f];
        for (uint32_t v : t)
            if (v >= mesh.positions.size())
                throw DracoError("Draco: triangle " + std::to_string(f) + " of '" + mesh.name +
                                   "' refers to vertex " + std::to_string(v) + " beyond the vertex count");
        dm.SetFace(draco::FaceIndex(uint32_t(f)),
                   {draco::PointIndex(t[0]), draco::PointIndex(t[1]), draco::PointIndex(t[2])});
    }

    draco::Encoder encoder;
    encoder.SetEncodingMethod(draco::MESH_EDGEBREAKER_ENCODING);
    encoder.SetSpeedOptions(settings.encoding_speed, settings.decoding_speed);
    if (settings.position_origin) {
        encoder.SetAttributeExplicitQuantization(draco::GeometryAttribute::POSITION, settings.position_bits, 3,
                                                 settings.position_origin->data(), settings.position_range);
    } else {
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, settings.position_bits);
    }
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, settings.normal_bits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, settings.texcoord_bits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::COLOR, settings.color_bits);
    draco::EncoderBuffer buffer;
    draco::Status status = encoder.EncodeMeshToBuffer(dm, &buffer);
    if (!status.ok()) throw DracoError("Draco could not compress '" + mesh.name + "': " + status.error_msg_string());
    if (ids) *ids = found;
    return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

bool draco_decode(std::span<const uint8_t> bytes, Mesh& out, std::string& error) {
    out = Mesh{};
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    draco::Decoder decoder;
    auto result = decoder.DecodeMeshFromBuffer(&buffer);
    if (!result.ok()) {
        error = "not a decodable Draco mesh: " + result.status().error_msg_string();
        return false;
    }
    const std::unique_ptr<draco::Mesh>& dm = result.value();
    if (!read_attribute(*dm, draco::GeometryAttribute::POSITION, out.positions)) {
        error = "Draco mesh without positions";
        return false;
    }
    read_attribute(*dm, draco::GeometryAttribute::NORMAL, out.normals);
    read_attribute(*dm, draco::GeometryAttribute::TEX_COORD, out.texcoords);
    for (int set = 1; set < dm->NumNamedAttributes(draco::GeometryAttribute::TEX_COORD) && set <= 7; ++set)
        if (!read_attribute(*dm, draco::GeometryAttribute::TEX_COORD, out.texcoord_sets.emplace_back(), set))
            out.texcoord_sets.pop_back();
    if (const draco::PointAttribute* c = dm->GetNamedAttribute(draco::GeometryAttribute::COLOR)) {
        out.colors_have_alpha = c->num_components() == 4;
        if (out.colors_have_alpha) {
            read_attribute(*dm, draco::GeometryAttribute::COLOR, out.colors);
        } else {
            std::vector<std::array<float, 3>> rgb;
            read_attribute(*dm, draco::GeometryAttribute::COLOR, rgb);
            out.colors.resize(rgb.size());
            for (size_t i = 0; i < rgb.size(); ++i) out.colors[i] = {rgb[i][0], rgb[i][1], rgb[i][2], 1.f};
        }
    }
    out.triangles.resize(dm->num_faces());
    for (uint32_t f = 0; f < dm->num_faces(); ++f) {
        const auto& face = dm->face(draco::FaceIndex(f));
        out.triangles[f] = {face[0].value(), face[1].value(), face[2].value()};
    }
    return true;
}

}  // namespace ellicast

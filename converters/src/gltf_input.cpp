// glTF 2.0 reading (.gltf, .glb), in the words of the glTF object model: accessors are read into
// floats, primitives become meshes, nodes are traversed from the default scene with their
// transforms. KHR_draco_mesh_compression is decoded by our own tinygltf copy (built with
// TINYGLTF_ENABLE_DRACO); KHR_mesh_quantization needs nothing more than normalized and integer
// accessors read correctly (the dequantizing scale lives in the node transforms).
#include "gltf_read.h"
#include "ellicast/format.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>

#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

// GCC 12 warns falsely (-Wrestrict) inside std::string concatenation of error messages (GCC bug 105651).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace ellicast {

namespace gltf_read {

// Extensions we implement, or that change nothing of the geometry we read.
const std::set<std::string> kGeometryExtensions = {"KHR_draco_mesh_compression", "KHR_mesh_quantization",
                                                   "EXT_meshopt_compression"};
const std::set<std::string> kAppearanceOnlyPrefixes = {"KHR_materials_", "KHR_texture_", "EXT_texture_",
                                                       "KHR_lights_", "EXT_lights_"};

bool appearance_only(const std::string& ext) {
    for (const auto& prefix : kAppearanceOnlyPrefixes)
        if (ext.rfind(prefix, 0) == 0) return true;
    return false;
}

bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// ---------------------------------------------------------------------------------------------
// Accessors

int component_count(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT4: return 16;  // columns of 4 components need no padding (glTF 3.6.2.4)
        default: return 0;
    }
}

int component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

double read_component(const unsigned char* p, int component_type, bool normalized) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return normalized ? v / 4294967295.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        default: return 0;
    }
}

void read_view(const tinygltf::Model& model, int view_index, size_t byte_offset, size_t count, int components,
               int component_type, bool normalized, size_t stride_override, const std::string& what,
               std::vector<double>& out) {
    if (view_index < 0 || size_t(view_index) >= model.bufferViews.size())
        throw InputError(what + " refers to bufferView " + std::to_string(view_index) + ", which does not exist");
    const tinygltf::BufferView& view = model.bufferViews[view_index];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        throw InputError(what + ": bufferView " + std::to_string(view_index) + " refers to a missing buffer");
    const tinygltf::Buffer& buffer = model.buffers[view.buffer];
    const size_t csize = size_t(component_size(component_type));
    const size_t elem = csize * size_t(components);
    const size_t stride = stride_override ? stride_override : (view.byteStride ? view.byteStride : elem);
    if (stride < elem)
        throw InputError(what + ": byteStride " + std::to_string(stride) + " is smaller than an element");
    if (count > 0) {
        size_t need = byte_offset + stride * (count - 1) + elem;
        if (need > view.byteLength || view.byteOffset + view.byteLength > buffer.data.size() ||
            view.byteOffset + view.byteLength < view.byteOffset)
            throw InputError(what + " runs past the end of its buffer (needs " + std::to_string(need) +
                             " bytes of bufferView " + std::to_string(view_index) + ", which has " +
                             std::to_string(view.byteLength) + "; buffer holds " +
                             std::to_string(buffer.data.size()) + ")");
    }
    out.resize(count * components);
    const unsigned char* base = buffer.data.data() + view.byteOffset + byte_offset;
    for (size_t i = 0; i < count; ++i)
        for (int c = 0; c < components; ++c)
            out[i * components + c] = read_component(base + i * stride + c * csize, component_type, normalized);
}

std::vector<double> read_accessor(const tinygltf::Model& model, int index, const std::string& what, int& components) {
    if (index < 0 || size_t(index) >= model.accessors.size())
        throw InputError(what + " refers to accessor " + std::to_string(index) + ", which does not exist");
    const tinygltf::Accessor& acc = model.accessors[index];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    components = component_count(acc.type);
    if (components == 0 || component_size(acc.componentType) == 0)
        throw InputError(name + " has an unsupported type or component type");
    if (acc.count > (size_t(1) << 28)) throw InputError(name + " declares an absurd count " + std::to_string(acc.count));
    std::vector<double> values;
    if (acc.bufferView >= 0) {
        read_view(model, acc.bufferView, acc.byteOffset, acc.count, components, acc.componentType, acc.normalized, 0,
                  name, values);
    } else {
        values.assign(acc.count * components, 0.0);  // no view: zeros, possibly replaced by sparse values
    }
    if (acc.sparse.isSparse) {
        size_t n = size_t(std::max(acc.sparse.count, 0));
        if (n > acc.count) throw InputError(name + ": sparse count exceeds the accessor count");
        std::vector<double> idx, val;
        read_view(model, acc.sparse.indices.bufferView, size_t(std::max(acc.sparse.indices.byteOffset, 0)), n, 1,
                  acc.sparse.indices.componentType, false, 0, name + " sparse indices", idx);
        read_view(model, acc.sparse.values.bufferView, size_t(std::max(acc.sparse.values.byteOffset, 0)), n,
                  components, acc.componentType, acc.normalized, 0, name + " sparse values", val);
        for (size_t i = 0; i < n; ++i) {
            size_t target = size_t(idx[i]);
            if (target >= acc.count) throw InputError(name + ": sparse index beyond the accessor count");
            for (int c = 0; c < components; ++c) values[target * components + c] = val[i * components + c];
        }
    }
    return values;
}

// ---------------------------------------------------------------------------------------------
// Nodes

Eigen::Matrix4d local_transform(const tinygltf::Node& node) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    if (node.matrix.size() == 16) {
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[c * 4 + r];  // column-major
        return m;
    }
    Eigen::Matrix4d t = Eigen::Matrix4d::Identity(), r = Eigen::Matrix4d::Identity(), s = Eigen::Matrix4d::Identity();
    if (node.translation.size() == 3)
        for (int k = 0; k < 3; ++k) t(k, 3) = node.translation[k];
    if (node.rotation.size() == 4) {
        Eigen::Quaterniond q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        if (q.norm() > 0) r.topLeftCorner<3, 3>() = q.normalized().toRotationMatrix();
    }
    if (node.scale.size() == 3)
        for (int k = 0; k < 3; ++k) s(k, k) = node.scale[k];
    return t * r * s;
}

// ---------------------------------------------------------------------------------------------
// Primitives

std::vector<std::array<uint32_t, 3>> primitive_triangles(const std::vector<uint32_t>& idx, int mode) {
    std::vector<std::array<uint32_t, 3>> tris;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        for (size_t i = 0; i + 2 < idx.size(); i += 3) tris.push_back({idx[i], idx[i + 1], idx[i + 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < idx.size(); ++i)
            tris.push_back(i % 2 == 0 ? std::array<uint32_t, 3>{idx[i], idx[i + 1], idx[i + 2]}
                                      : std::array<uint32_t, 3>{idx[i + 1], idx[i], idx[i + 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 1; i + 1 < idx.size(); ++i) tris.push_back({idx[0], idx[i], idx[i + 1]});
    }
    return tris;
}

const char* mode_name(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLES: return "TRIANGLES";
        case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
        default: return "unknown";
    }
}

bool primitive_to_mesh(const tinygltf::Model& model, const tinygltf::Primitive& prim, const Eigen::Matrix4d& world,
                       const std::string& where, Mesh& mesh, std::vector<std::string>& warnings) {
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
        warnings.push_back(where + ": a " + std::string(mode_name(mode)) + " primitive, skipped (ellicast carries "
                           "triangles and points)");
        return false;
    }
    if (mode != TINYGLTF_MODE_POINTS && mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        warnings.push_back(where + ": primitive mode " + std::to_string(mode) + " is not a glTF mode, skipped");
        return false;
    }
    auto pos_it = prim.attributes.find("POSITION");
    if (pos_it == prim.attributes.end()) {
        warnings.push_back(where + ": primitive without POSITION, skipped");
        return false;
    }
    if (prim.extensions.count("KHR_draco_mesh_compression")) {
        // tinygltf rewrites the accessors to the decoded data; when decoding failed it says nothing.
        const auto& acc = model.accessors.at(size_t(pos_it->second));
        if (acc.bufferView < 0)
            throw InputError(where + ": its KHR_draco_mesh_compression data could not be decoded");
    }
    int comps = 0;
    std::vector<double> pos = read_accessor(model, pos_it->second, where + " POSITION", comps);
    if (comps != 3) throw InputError(where + ": POSITION is not a VEC3 accessor");
    const size_t n = pos.size() / 3;

    Eigen::Matrix3d linear = world.topLeftCorner<3, 3>();
    Eigen::Vector3d offset = world.topRightCorner<3, 1>();
    Eigen::Matrix3d normal_matrix = linear.inverse().transpose();
    if (!normal_matrix.allFinite()) normal_matrix = Eigen::Matrix3d::Identity();
    mesh.positions.resize(n);
    for (size_t i = 0; i < n; ++i) {
        Eigen::Vector3d p = linear * Eigen::Vector3d(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]) + offset;
        mesh.positions[i] = {float(p.x()), float(p.y()), float(p.z())};
    }

    if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end()) {
        std::vector<double> nrm = read_accessor(model, it->second, where + " NORMAL", comps);
        if (comps == 3 && nrm.size() == pos.size()) {
            mesh.normals.resize(n);
            for (size_t i = 0; i < n; ++i) {
                Eigen::Vector3d v = normal_matrix * Eigen::Vector3d(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
                double len = v.norm();
                if (len > 0) v /= len;
                mesh.normals[i] = {float(v.x()), float(v.y()), float(v.z())};
            }
        } else {
            warnings.push_back(where + ": NORMAL is not a VEC3 of the vertex count; ignored");
        }
    }
    if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
        std::vector<double> uv = read_accessor(model, it->second, where + " TEXCOORD_0", comps);
        if (comps == 2 && uv.size() == 2 * n) {
            mesh.texcoords.resize(n);
            for (size_t i = 0; i < n; ++i) mesh.texcoords[i] = {float(uv[2 * i]), float(uv[2 * i + 1])};
        } else {
            warnings.push_back(where + ": TEXCOORD_0 is not a VEC2 of the vertex count; ignored");
        }
    }
    // Further sets (format 1.14, spec 30): TEXCOORD_1 .. TEXCOORD_7, in order, while each is there
    // and readable (glTF numbers the sets without gaps), and only with a TEXCOORD_0.
    for (size_t set = 1; set <= kMaxTexcoordSets && mesh.has_texcoords(); ++set) {
        const std::string name = "TEXCOORD_" + std::to_string(set);
        auto it = prim.attributes.find(name);
        if (it == prim.attributes.end()) break;
        std::vector<double> uv = read_accessor(model, it->second, where + " " + name, comps);
        if (comps != 2 || uv.size() != 2 * n) {
            warnings.push_back(where + ": " + name + " is not a VEC2 of the vertex count; it and the sets after it ignored");
            break;
        }
        auto& values = mesh.texcoord_sets.emplace_back(n);
        for (size_t i = 0; i < n; ++i) values[i] = {float(uv[2 * i]), float(uv[2 * i + 1])};
    }
    if (auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
        std::vector<double> col = read_accessor(model, it->second, where + " COLOR_0", comps);
        if ((comps == 3 || comps == 4) && col.size() == size_t(comps) * n) {
            mesh.colors.resize(n);
            mesh.colors_have_alpha = comps == 4;
            for (size_t i = 0; i < n; ++i)
                for (int c = 0; c < 4; ++c) mesh.colors[i][c] = c < comps ? float(col[i * comps + c]) : 1.0f;
        } else {
            warnings.push_back(where + ": COLOR_0 is not a VEC3/VEC4 of the vertex count; ignored");
        }
    }

    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
        std::vector<double> raw = read_accessor(model, prim.indices, where + " indices", comps);
        if (comps != 1) throw InputError(where + ": its indices accessor is not SCALAR");
        idx.resize(raw.size());
        for (size_t i = 0; i < raw.size(); ++i) {
            // Indices are unsigned integers (glTF: unsigned byte, short or int); a signed or float
            // accessor can hold values below 0 or between integers (-16640 was cast to unsigned).
            if (!(raw[i] >= 0) || raw[i] != std::floor(raw[i]))
                throw InputError(where + ": index " + std::to_string(raw[i]) + " at position " + std::to_string(i) +
                                 " is not a vertex number (indices must be unsigned integers)");
            if (raw[i] >= double(n))
                throw InputError(where + ": index " + std::to_string(size_t(raw[i])) + " at position " +
                                 std::to_string(i) + " is beyond the " + std::to_string(n) + " vertices");
            idx[i] = uint32_t(raw[i]);
        }
    } else {
        idx.resize(n);
        for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
    }

    if (mode == TINYGLTF_MODE_POINTS) {
        mesh.is_point_set = true;
        if (prim.indices >= 0) {  // keep only the referenced points, in index order
            Mesh sub;
            sub.is_point_set = true;
            sub.colors_have_alpha = mesh.colors_have_alpha;
            for (uint32_t i : idx) {
                sub.positions.push_back(mesh.positions[i]);
                if (mesh.has_normals()) sub.normals.push_back(mesh.normals[i]);
                if (mesh.has_texcoords()) sub.texcoords.push_back(mesh.texcoords[i]);
                if (mesh.has_colors()) sub.colors.push_back(mesh.colors[i]);
                sub.texcoord_sets.resize(mesh.texcoord_sets.size());
                for (size_t s = 0; s < mesh.texcoord_sets.size(); ++s) sub.texcoord_sets[s].push_back(mesh.texcoord_sets[s][i]);
            }
            sub.name = mesh.name;
            mesh = std::move(sub);
        }
        return true;
    }
    mesh.triangles = primitive_triangles(idx, mode);
    if (linear.determinant() < 0)  // a mirroring transform turns faces inside out: keep them outward
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    return true;
}

std::string json_text(const std::vector<uint8_t>& bytes, bool binary) {
    if (!binary) return {bytes.begin(), bytes.end()};
    if (bytes.size() < 20) return {};
    uint32_t json_length;
    std::memcpy(&json_length, bytes.data() + 12, 4);
    if (uint64_t(json_length) + 20 > bytes.size()) return {};
    return {reinterpret_cast<const char*>(bytes.data()) + 20, json_length};
}

namespace {

// Calls visit(mesh, primitive, the primitive, its KHR_draco_mesh_compression object) for every
// primitive of `doc` that uses the extension.
void for_each_draco_primitive(
    const nlohmann::json& doc,
    const std::function<void(size_t, size_t, const nlohmann::json&, const nlohmann::json&)>& visit) {
    if (!doc.contains("meshes") || !doc["meshes"].is_array()) return;
    for (size_t m = 0; m < doc["meshes"].size(); ++m) {
        const auto& mesh = doc["meshes"][m];
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
            const auto& prim = mesh["primitives"][p];
            if (prim.is_object() && prim.contains("extensions") && prim["extensions"].is_object() &&
                prim["extensions"].contains("KHR_draco_mesh_compression"))
                visit(m, p, prim, prim["extensions"]["KHR_draco_mesh_compression"]);
        }
    }
}

// tinygltf's Draco path indexes buffers and buffer views without checking them (a wrong "buffer"
// number crashed inside Draco). Check them here, on the JSON, before tinygltf sees the file.
void check_buffer_views(const std::string& path, const std::vector<uint8_t>& bytes, bool binary) {
    const std::string text = json_text(bytes, binary);
    uint64_t bin_length = 0;
    bool has_bin = false;
    if (binary) {
        if (text.empty()) return;  // tinygltf reports header errors itself
        uint64_t next = 20 + uint64_t(text.size());
        if (next + 8 <= bytes.size()) {
            uint32_t length, type;
            std::memcpy(&length, bytes.data() + next, 4);
            std::memcpy(&type, bytes.data() + next + 4, 4);
            if (type == 0x004E4942u) has_bin = true, bin_length = std::min<uint64_t>(length, bytes.size() - next - 8);
        }
    }
    if (text.find("KHR_draco_mesh_compression") == std::string::npos) return;  // tinygltf checks the rest
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object()) return;  // tinygltf names the JSON error
    auto count = [&](const char* key) { return doc.contains(key) && doc[key].is_array() ? doc[key].size() : 0; };
    auto number = [](const nlohmann::json& o, const char* key, double fallback) {
        return o.is_object() && o.contains(key) && o[key].is_number() ? o[key].get<double>() : fallback;
    };
    const size_t buffers = count("buffers"), views = count("bufferViews");
    for (size_t v = 0; v < views; ++v) {
        const auto& view = doc["bufferViews"][v];
        double b = number(view, "buffer", -1);
        if (!(b >= 0 && b < double(buffers)) || b != std::floor(b))
            throw InputError(path + ": bufferViews[" + std::to_string(v) + "] refers to a buffer that does not exist");
        const auto& buffer = doc["buffers"][size_t(b)];
        double length = number(buffer, "byteLength", -1);
        if (size_t(b) == 0 && binary && !(buffer.is_object() && buffer.contains("uri")))
            length = has_bin ? std::min(length, double(bin_length)) : -1;
        double end = number(view, "byteOffset", 0) + number(view, "byteLength", -1);
        if (!(number(view, "byteOffset", 0) >= 0) || !(number(view, "byteLength", -1) >= 0) || !(end <= length))
            throw InputError(path + ": bufferViews[" + std::to_string(v) + "] runs past the end of buffer " +
                             std::to_string(size_t(b)));
    }
    for_each_draco_primitive(doc, [&](size_t m, size_t p, const nlohmann::json&, const nlohmann::json& ext) {
        double v = number(ext, "bufferView", -1);
        if (!(v >= 0 && v < double(views)))
            throw InputError(path + ": meshes[" + std::to_string(m) + "] primitive " + std::to_string(p) +
                             ": its KHR_draco_mesh_compression bufferView does not exist");
    });
}

// tinygltf's Draco path also trusts the accessors and the Draco data: an attribute id the Draco
// mesh does not have was dereferenced as a null pointer, an accessor index or component type out of
// range indexed past its arrays, and more than 4 components overran a 4-value array (found by
// fuzz_readers). Check them here, decoding each Draco buffer view once, before tinygltf does.
void check_draco_primitives(const std::string& path, const std::vector<uint8_t>& bytes, bool binary,
                            const InputOptions& options) {
    const std::string text = json_text(bytes, binary);
    if (text.find("KHR_draco_mesh_compression") == std::string::npos) return;
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("meshes") || !doc["meshes"].is_array()) return;
    const nlohmann::json no_array = nlohmann::json::array();
    const auto& accessors = doc.contains("accessors") && doc["accessors"].is_array() ? doc["accessors"] : no_array;
    const auto& views = doc.contains("bufferViews") && doc["bufferViews"].is_array() ? doc["bufferViews"] : no_array;
    std::vector<std::vector<uint8_t>> buffers;
    bool buffers_read = false;
    auto index_of = [](const nlohmann::json& v, size_t size) -> long long {
        if (!v.is_number_integer() && !v.is_number_unsigned()) return -1;
        const long long i = v.get<long long>();
        return i >= 0 && size_t(i) < size ? i : -1;
    };
    auto component_type = [&](long long accessor) -> int {
        const auto& a = accessors[size_t(accessor)];
        return a.is_object() && a.contains("componentType") && a["componentType"].is_number_integer()
                   ? a["componentType"].get<int>()
                   : 0;
    };
    for_each_draco_primitive(doc, [&](size_t m, size_t p, const nlohmann::json& prim, const nlohmann::json& ext) {
        std::string where = path;
        where += ": meshes[" + std::to_string(m) + "] primitive " + std::to_string(p) + ": ";
        if (!ext.is_object() || !ext.contains("attributes") || !ext["attributes"].is_object())
            throw InputError(where + "its KHR_draco_mesh_compression has no attributes object");
        if (prim.contains("indices")) {
            const long long i = index_of(prim["indices"], accessors.size());
            const int type = i < 0 ? 0 : component_type(i);
            if (type != 5121 && type != 5123 && type != 5125)
                throw InputError(where + "its indices are not an accessor of unsigned bytes, shorts or ints");
        }
        const auto& own = prim.contains("attributes") && prim["attributes"].is_object() ? prim["attributes"]
                                                                                        : nlohmann::json::object();
        for (const auto& [name, id] : ext["attributes"].items()) {
            std::string attribute = where;
            attribute += "Draco attribute " + quoted_input(name) + ": ";
            if (!id.is_number_integer() || id.get<long long>() < 0 || id.get<long long>() > 0xFFFFFF)
                throw InputError(attribute + "its id is not a non-negative integer");
            const long long a = own.contains(name) ? index_of(own[name], accessors.size()) : -1;
            if (a < 0) throw InputError(attribute + "the primitive has no accessor for it");
            const int type = component_type(a);
            if (type != 5120 && type != 5121 && type != 5122 && type != 5123 && type != 5125 && type != 5126)
                throw InputError(attribute + "its accessor has no valid componentType");
        }
        // The Draco data itself.
        const long long v = index_of(ext.contains("bufferView") ? ext["bufferView"] : nlohmann::json(), views.size());
        if (v < 0) return;  // check_buffer_views named it
        const auto& view = views[size_t(v)];
        if (!buffers_read) {
            buffers = gltf_buffers(path, bytes, binary, doc, options);
            buffers_read = true;
        }
        const long long b = view.contains("buffer") ? index_of(view["buffer"], buffers.size()) : -1;
        const size_t offset = view.value("byteOffset", size_t(0)), length = view.value("byteLength", size_t(0));
        if (b < 0 || offset > buffers[size_t(b)].size() || length > buffers[size_t(b)].size() - offset)
            throw InputError(where + "its Draco buffer view lies outside its buffer's data");
        draco::DecoderBuffer input;
        input.Init(reinterpret_cast<const char*>(buffers[size_t(b)].data() + offset), length);
        draco::Decoder decoder;
        auto decoded = decoder.DecodeMeshFromBuffer(&input);
        if (!decoded.ok())
            throw InputError(where + "its KHR_draco_mesh_compression data could not be decoded (" +
                             decoded.status().error_msg_string() + ")");
        const auto& draco_mesh = decoded.value();
        for (const auto& [name, id] : ext["attributes"].items()) {
            const draco::PointAttribute* attribute = draco_mesh->GetAttributeByUniqueId(id.get<uint32_t>());
            std::string what = where;
            what += "Draco attribute " + quoted_input(name) + " (id " + std::to_string(id.get<long long>()) + "): ";
            if (attribute == nullptr) throw InputError(what + "its Draco data has no attribute with that id");
            if (attribute->num_components() < 1 || attribute->num_components() > 4)
                throw InputError(what + "it has " + std::to_string(int(attribute->num_components())) +
                                 " components (glTF attributes have 1 to 4)");
        }
    });
}

}  // namespace

std::vector<uint8_t> read_file_bytes(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        if (std::filesystem::is_directory(path, ec)) throw InputError(path + ": is a folder, not a file");
        std::ifstream in(path, std::ios::binary);  // a pipe or device: read as a stream
        if (!in) throw InputError(path + ": cannot be opened for reading");
        return {std::istreambuf_iterator<char>(in), {}};
    }
    std::vector<uint8_t> bytes;
    std::string message;
    if (read_file(path, bytes, message) != Error::Ok) throw InputError(message);
    return bytes;
}

nlohmann::json read_json(const std::string& path) {
    std::vector<uint8_t> bytes;
    try {
        bytes = read_file_bytes(path);
    } catch (const InputError&) {
        return nlohmann::json::value_t::discarded;
    }
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    return nlohmann::json::parse(json_text(bytes, binary), nullptr, false);
}

std::string resource_file(const std::string& model_path, const std::string& uri, const std::string& what,
                          const InputOptions& options) {
    namespace fs = std::filesystem;
    std::string name;
    name.reserve(uri.size());
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) && std::isxdigit(uint8_t(uri[i + 2]))) {
            name.push_back(char(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            name.push_back(uri[i]);
        }
    }
    const fs::path folder = fs::path(model_path).parent_path();
    const fs::path file = folder / fs::path(name);
    if (options.allow_outside_folder) return file.string();
    auto refuse = [&](const char* why) {
        throw InputError(model_path + ": " + what + " names " + quoted_input(uri) + ", " + why +
                         "; refused (a glTF's files must be in its folder; --allow-external-paths takes them anyway)");
    };
    const fs::path rel(name);
    if (name.empty()) refuse("an empty file name");
    if (rel.is_absolute() || rel.has_root_name() || rel.has_root_directory() || name.find('\\') != std::string::npos ||
        name.find('\0') != std::string::npos)
        refuse("an absolute path");
    int depth = 0;
    for (const auto& part : rel) {
        if (part == "..") --depth;
        else if (part != "." && !part.empty()) ++depth;
        if (depth < 0) refuse("a file above the asset's folder");
    }
    // Symlinks: where the file really is must still be inside where the folder really is.
    std::error_code ec;
    const fs::path real_folder = fs::weakly_canonical(folder.empty() ? fs::path(".") : folder, ec);
    const fs::path real_file = fs::weakly_canonical(file, ec);
    if (!ec) {
        auto f = real_file.begin();
        for (auto d = real_folder.begin(); d != real_folder.end(); ++d, ++f)
            if (f == real_file.end() || *f != *d) refuse("a link to a file outside the asset's folder");
    }
    return file.string();
}

namespace {

// Calls visit(what, uri) for every buffer and image of `doc` given by a URI other than data:,
// `what` naming it ("buffers[2]").
template <typename Visit>
void for_each_resource_uri(const nlohmann::json& doc, Visit visit) {
    if (!doc.is_object()) return;
    for (const char* list : {"buffers", "images"}) {
        if (!doc.contains(list) || !doc[list].is_array()) continue;
        for (size_t i = 0; i < doc[list].size(); ++i) {
            const auto& item = doc[list][i];
            if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
            const std::string uri = item["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) continue;
            visit(std::string(list) + "[" + std::to_string(i) + "]", uri);
        }
    }
}

// Every buffer and image URI (other than data:) checked by resource_file before tinygltf follows it.
void check_resource_uris(const std::string& path, const std::vector<uint8_t>& bytes, bool binary,
                         const InputOptions& options) {
    if (options.allow_outside_folder) return;
    const nlohmann::json doc = nlohmann::json::parse(json_text(bytes, binary), nullptr, false);
    if (doc.is_discarded()) return;  // tinygltf names the JSON error
    for_each_resource_uri(doc, [&](const std::string& what, const std::string& uri) {
        resource_file(path, uri, what, options);
    });
}

}  // namespace

void load_model(const std::string& path, tinygltf::Model& model, tinygltf::LoadImageDataFunction image_loader,
                void* image_user_data, std::vector<std::string>& warnings, const InputOptions& options,
                const std::function<bool(const std::string&)>& carried) {
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(image_loader, image_user_data);
    // Extras travel as the asset's JSON (format 1.12, spec 28): kept as text, nulls included (the
    // parsed values drop null members and array elements).
    loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
    std::string err, warn;
    // The file is read once; every check and tinygltf work on these bytes.
    const std::vector<uint8_t> bytes = read_file_bytes(path);
    if (bytes.size() > 0xFFFFFFFFu) throw InputError(path + ": larger than 4 GiB, the most glTF's loader reads");
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    check_buffer_views(path, bytes, binary);
    check_resource_uris(path, bytes, binary, options);
    check_draco_primitives(path, bytes, binary, options);
    const std::vector<uint8_t> decoded = decode_meshopt(path, bytes, binary, options);
    const std::string base_dir = std::filesystem::path(path).parent_path().string();
    const std::vector<uint8_t>& data = decoded.empty() ? bytes : decoded;
    const bool ok = !decoded.empty() || binary
                        ? loader.LoadBinaryFromMemory(&model, &err, &warn, data.data(), unsigned(data.size()), base_dir)
                        : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(data.data()),
                                                     unsigned(data.size()), base_dir);
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        throw InputError(path + ": not a readable glTF 2.0 " + std::string(binary ? "binary (.glb)" : "(.gltf)") +
                         " file: " + (err.empty() ? "unknown error" : err));
    }
    if (!model.asset.version.empty() && model.asset.version.rfind("2.", 0) != 0)
        throw InputError(path + ": glTF version " + model.asset.version + " (ellicast reads glTF 2.x)");
    // The file was meshopt-compressed (decoded above, the extension taken out): say so, as the file does,
    // so that the asset knows how its source was stored.
    if (!decoded.empty() &&
        std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "EXT_meshopt_compression") ==
            model.extensionsUsed.end())
        model.extensionsUsed.push_back("EXT_meshopt_compression");

    for (const auto& ext : model.extensionsRequired) {
        if (kGeometryExtensions.count(ext)) continue;
        if (appearance_only(ext)) {
            if (carried && carried(ext)) continue;
            warnings.push_back(path + ": required extension " + ext +
                               " only changes appearance; ignored (geometry is sent)");
            continue;
        }
        throw InputError(path + ": requires the glTF extension " + ext + ", which ellicast does not support");
    }
}

}  // namespace gltf_read

namespace {

using namespace gltf_read;

struct Traversal {
    const tinygltf::Model& model;
    const std::string& path;
    LoadResult& result;
    size_t visited = 0;
};

void visit_node(Traversal& tr, int index, const Eigen::Matrix4d& parent, int depth) {
    const auto& model = tr.model;
    if (index < 0 || size_t(index) >= model.nodes.size())
        throw InputError(tr.path + ": a scene refers to node " + std::to_string(index) + ", which does not exist");
    if (depth > 256 || ++tr.visited > 1'000'000)
        throw InputError(tr.path + ": the node hierarchy is too deep or cyclic (at node " + std::to_string(index) + ")");
    const tinygltf::Node& node = model.nodes[index];
    Eigen::Matrix4d world = parent * local_transform(node);
    if (node.mesh >= 0) {
        if (size_t(node.mesh) >= model.meshes.size())
            throw InputError(tr.path + ": node " + std::to_string(index) + " refers to mesh " +
                             std::to_string(node.mesh) + ", which does not exist");
        if (node.skin >= 0)
            tr.result.warnings.push_back(tr.path + ": node " + std::to_string(index) +
                                         " is skinned; its mesh is sent in the bind pose");
        const tinygltf::Mesh& gmesh = model.meshes[node.mesh];
        for (size_t p = 0; p < gmesh.primitives.size(); ++p) {
            std::string label = gmesh.name.empty() ? "mesh " + std::to_string(node.mesh) : gmesh.name;
            std::string where = tr.path + ": " + label + " primitive " + std::to_string(p) + " (node " +
                                std::to_string(index) + ")";
            Mesh mesh;
            mesh.name = label + (gmesh.primitives.size() > 1 ? "#" + std::to_string(p) : "");
            if (!primitive_to_mesh(model, gmesh.primitives[p], world, where, mesh, tr.result.warnings)) continue;
            if (!gmesh.primitives[p].targets.empty())
                tr.result.warnings.push_back(where + ": " + std::to_string(gmesh.primitives[p].targets.size()) +
                                             " morph targets ignored (the base shape is read)");
            check_and_repair_mesh(mesh, where, tr.result.warnings);
            if (!mesh.is_point_set && mesh.triangles.empty()) {
                tr.result.warnings.push_back(where + ": no usable triangles, skipped");
                continue;
            }
            if (mesh.positions.empty()) {
                tr.result.warnings.push_back(where + ": no vertices, skipped");
                continue;
            }
            tr.result.meshes.push_back(std::move(mesh));
        }
    }
    for (int child : node.children) visit_node(tr, child, world, depth + 1);
}

}  // namespace

namespace {

// The model file and the files its URIs name that `options` let it read (others are skipped).
std::vector<std::string> referenced_files(const std::string& path, const InputOptions& options) {
    namespace fs = std::filesystem;
    std::vector<std::string> files{path};
    const std::string ext = fs::path(path).extension().string();
    if (ext != ".gltf" && ext != ".GLTF") return files;
    std::set<fs::path> seen;
    gltf_read::for_each_resource_uri(gltf_read::read_json(path), [&](const std::string& what, const std::string& uri) {
        try {
            const fs::path file = gltf_read::resource_file(path, uri, what, options);
            if (seen.insert(file).second) files.push_back(file.string());
        } catch (const InputError&) {
        }
    });
    return files;
}

}  // namespace

std::vector<std::string> model_files(const std::string& path) { return referenced_files(path, InputOptions{true}); }

uint64_t model_files_size(const std::string& path) {
    uint64_t total = 0;
    for (const auto& file : referenced_files(path, InputOptions{})) {  // a model's own files are in its folder
        std::error_code ec;
        if (auto n = std::filesystem::file_size(file, ec); !ec) total += n;
    }
    return total;
}

LoadResult load_gltf(const std::string& path, const InputOptions& options) {
    tinygltf::Model model;
    LoadResult result;
    gltf_read::load_model(path, model, skip_image, nullptr, result.warnings, options);

    Traversal tr{model, path, result};
    if (!model.scenes.empty()) {
        int scene = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size() ? model.defaultScene : 0;
        for (int root : model.scenes[scene].nodes) visit_node(tr, root, Eigen::Matrix4d::Identity(), 0);
    } else {
        // No scene: nothing would be drawn; send every mesh untransformed rather than nothing.
        result.warnings.push_back(path + ": no scene; every mesh is sent without node transforms");
        for (size_t m = 0; m < model.meshes.size(); ++m) {
            tinygltf::Node fake;
            fake.mesh = int(m);
            model.nodes.push_back(fake);
            visit_node(tr, int(model.nodes.size() - 1), Eigen::Matrix4d::Identity(), 0);
        }
    }
    if (result.meshes.empty())
        throw InputError(path + ": the scene holds no triangle or point primitive to send");
    return result;
}

}  // namespace ellicast
